#!/usr/bin/env python3
"""The report generator of docs/RESULTS.md: each section from the files its run wrote
(scripts/results.sh runs them all; each module of scripts/reports/ is one section).

    python3 scripts/report.py paper [DIR]                      the page itself: enhanced_orb_compare --paper's
                                                               CSV, the benchmark and the pipeline in DIR
                                                               (default docs/results)
    python3 scripts/report.py compare DIR [DOC]                enhanced_orb_compare --lighting/--euroc
    python3 scripts/report.py sequence DIR [DIR ...] [DOC]     enhanced_orb_compare --sequence
    python3 scripts/report.py aarch64 [REPORTS_DIR] [DOC]      scripts/aarch64.sh's gtest reports
    python3 scripts/report.py orbslam3 RUNS DATA [DOC]         scripts/orbslam3_eval.sh's runs
    python3 scripts/report.py glance [RESULTS [README]]        README's relative-pose summary, from the
                                                               sequence sections of RESULTS
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from reports import aarch64, compare, glance, orbslam3, paper, sequence  # noqa: E402

SECTIONS = {"paper": paper, "compare": compare, "sequence": sequence, "aarch64": aarch64, "orbslam3": orbslam3,
            "glance": glance}

if __name__ == "__main__":
    if len(sys.argv) < 2 or sys.argv[1] not in SECTIONS:
        sys.exit(__doc__)
    SECTIONS[sys.argv[1]].main(sys.argv[2:])
