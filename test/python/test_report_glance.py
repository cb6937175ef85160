"""scripts/reports/glance.py, README's relative-pose summary read from docs/RESULTS.md's sequence
tables: what it reads from a table, and that README's copy is what docs/RESULTS.md gives.

Run by scripts/test.sh with the Python module's tests: python3 -m pytest test/python.
"""
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

from reports import glance  # noqa: E402

HEADER = ("| light | default | baseline | default / best rival |\n"
          "| --- | ---: | ---: | ---: |\n")


def section(name, tables):
    return "<!-- %s:begin -->\n%s<!-- %s:end -->\n" % (name, tables, name)


def results(turn_500_rows, other_rows="| unchanged AUC@10 | 0.60 | 0.50 | **1.20x** |\n"
                                      "| dim AUC@10 | 0.60 | 0.50 | **1.20x** |\n"):
    pose = "### 500 features: pose AUC@10 (10 pairs)\n\n" + HEADER
    return (section("sequence", pose + other_rows)
            + section("driving_turn_51", pose + turn_500_rows)
            + section("driving_straight_51", pose + other_rows))


def test_reads_the_ratio_column_of_pose_tables_only():
    text = ("### 500 features: pose AUC@10 and frames tracked (10 pairs)\n\n"
            "| light | default | default / best rival | motion / best rival |\n| --- | ---: | ---: | ---: |\n"
            "| unchanged AUC@10 | 0.5 | 0.95x (loses; -0.1 to +0.02) | **1.10x** |\n"
            "| unchanged tracked | 1.0 | **1.00x** | **1.00x** |\n"
            "| dark AUC@10 | 0.3 | **1.50x** | **1.40x** |\n\n"
            "### 1000 features: AUC at 5 / 10 / 20 degrees by frame gap\n\n"
            "| light | gap | default |\n| --- | ---: | ---: |\n| unchanged AUC@10 | +1 | 0.9x |\n")
    rows = glance.pose_rows(text)
    assert list(rows) == [500]
    assert [(light, ratio) for light, ratio, _ in rows[500]] == [("unchanged", 0.95), ("dark", 1.5)]


def test_a_loss_is_not_bold_and_carries_its_interval():
    text = results("| unchanged AUC@10 | 0.80 | 0.82 | 0.98x (loses; -0.05 to +0.01) |\n"
                   "| dim AUC@10 | 0.70 | 0.60 | **1.17x** |\n"
                   "| dark AUC@10 | 0.40 | 0.41 | 0.99x (loses; -0.03 to +0.02) |\n")
    turn = [line for line in glance.summary(text).splitlines() if "turn_51" in line]
    assert turn == ["| %s | 500 | 0.98x | 0.99x to **1.17x** | unchanged (-0.05 to +0.01); dark (-0.03 to +0.02) |"
                    % glance.SECTIONS[1][1]]
    others = [line for line in glance.summary(text).splitlines() if "MH_01" in line]
    assert others == ["| %s | 500 | **1.20x** | **1.20x** to **1.20x** | none |" % glance.SECTIONS[0][1]]


def test_a_missing_section_or_table_is_an_error():
    with pytest.raises(ValueError):
        glance.summary(section("sequence", ""))
    with pytest.raises(ValueError):
        glance.summary(results(""))


def test_readme_shows_what_results_gives():
    readme = (ROOT / "README.md").read_text()
    shown = glance.read_section(readme, "glance").strip()
    assert shown == glance.summary((ROOT / "docs" / "RESULTS.md").read_text()).strip(), \
        "README's summary differs from docs/RESULTS.md: python3 scripts/report.py glance"
