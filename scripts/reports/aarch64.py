"""Writes the aarch64 section of docs/RESULTS.md (between the aarch64:begin and aarch64:end markers,
appended when they are missing) from the gtest reports of scripts/aarch64.sh.

    python3 scripts/report.py aarch64 REPORTS_DIR docs/RESULTS.md
REPORTS_DIR holds aarch64-test_*.xml (build_aarch64/test_results after bash scripts/aarch64.sh)."""
import pathlib
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

from reports.common import write_section

FUSION = {"0": "as written (each product rounded)", "1": "first product fused", "2": "second product fused"}


def properties(case):
    """RecordProperty values: attributes of the testcase, or its <properties> child."""
    values = dict(case.attrib)
    for prop in case.iter("property"):
        values[prop.get("name")] = prop.get("value")
    return values


def version(command):
    try:
        return subprocess.run(command, capture_output=True, text=True, check=False).stdout.splitlines()[0]
    except (OSError, IndexError):
        return "?"


def main(args):
    reports, doc = (list(args) + ["build_aarch64/test_results", "docs/RESULTS.md"][len(args):])[:2]
    files = sorted(pathlib.Path(reports).glob("aarch64-test_*.xml"))
    if not files:
        sys.exit(f"report aarch64: no aarch64-test_*.xml in {reports}; run bash scripts/aarch64.sh first")
    rows, facts = [], {}
    total_passed = total_failed = 0
    for path in files:
        root = ET.parse(path).getroot()
        passed = failed = 0
        seconds = float(root.get("time", "0") or 0)
        for case in root.iter("testcase"):
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
            elif case.find("skipped") is None and case.get("status") != "notrun":
                passed += 1
            facts.update({k: v for k, v in properties(case).items()
                          if k.startswith("rotation_rounding") or k.startswith("smoothing_")})
        total_passed += passed
        total_failed += failed
        rows.append(f"| {path.stem.replace('aarch64-', '')} | {passed} | {failed} | {seconds:.0f} |")
    out = ["## On aarch64 (ARM)", ""]
    out.append(f"`bash scripts/aarch64.sh` (part of the test command): the ROS-free libraries and their gtests "
               f"cross-built with {version(['aarch64-linux-gnu-g++', '--version'])} against Debian 12's arm64 "
               "OpenCV 4.6 and run under "
               f"{re.sub(r' *Copyright.*', '', version(['qemu-aarch64', '--version']))}. "
               f"{total_passed} passed, {total_failed} failed.")
    out += ["", "| test program | passed | failed | seconds under emulation |", "| --- | ---: | ---: | ---: |"] + rows
    rounding = (FUSION.get(facts.get("rotation_rounding_x", "?"), "?"),
                FUSION.get(facts.get("rotation_rounding_y", "?"), "?"))
    out += ["",
            "What runs there: at the `neon` level (the best on aarch64) the FAST score map (GCC vectors, "
            "saturating NEON subtraction), the suppression rows, the resize's row and column passes and "
            "the 7x7 smoothing before description (fused multiply-adds, in OpenCV's order) are this "
            "project's NEON kernels, each tested against its scalar reference; the smoothing runs on "
            f"them when the check at start finds they reproduce the installed OpenCV "
            f"(here: {facts.get('smoothing_neon', '?')}). The descriptors are the installed cv::ORB's: "
            f"Debian's arm64 OpenCV rounds rBRIEF's rotated test points with x {rounding[0]} and "
            f"y {rounding[1]}, found at start and used by `describe()`; the identity tests compare "
            "keypoints, descriptors, thresholds and enhanced images with the reference on every fifth "
            "shared EuRoC frame in every mode at budgets 0 and 1000, and the descriptors with cv::ORB's "
            "at rounding ties.",
            "",
            "Speed under emulation means nothing (qemu translates each instruction). On a real arm64 "
            "board with Debian or Ubuntu and ROS, the ratio to cv::ORB at 1000 features on one thread, "
            "measured in one run:",
            "",
            "```bash",
            "bash scripts/setup.sh",
            "devel/lib/enhanced_orb/benchmark_extraction --benchmark_filter='BM_Frame/method:[0-3]/budget:1000/threads:1/' \\",
            "  --benchmark_repetitions=7 --benchmark_enable_random_interleaving=true",
            "```",
            "",
            "(method 3 is the default mode, 2 cv::ORB, 0 the baseline, 1 the paper preset; `bash scripts/results.sh` on the board writes the "
            "whole Speed section with the ratios.)"]
    write_section(doc, "aarch64", "\n".join(out))
    print(f"report aarch64: wrote the aarch64 section of {doc}")
