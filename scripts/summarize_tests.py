#!/usr/bin/env python3
"""Sums up the JUnit XML files of a catkin test run: one line per failing test, then
'N passed, N failed[, N skipped]'. Exits 1 when a test failed, errored, or no test ran."""
import pathlib
import sys
import xml.etree.ElementTree as ET


def main(results_dir):
    passed, failed, skipped = 0, 0, 0
    files = sorted(pathlib.Path(results_dir).rglob("*.xml"))
    for path in files:
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as err:
            print(f"unreadable result file {path}: {err}")
            failed += 1
            continue
        for case in root.iter("testcase"):
            name = f"{case.get('classname', '')}.{case.get('name', '')}"
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                print(f"FAILED {path.parent.name}/{path.name}: {name}")
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
            else:
                passed += 1
    if not files:
        print(f"no test results under {results_dir}")
    summary = f"{passed} passed, {failed} failed"
    print(summary + (f", {skipped} skipped" if skipped else ""))
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "build/test_results"))
