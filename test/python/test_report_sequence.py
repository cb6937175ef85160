"""scripts/reports/sequence.py's legend of the light conditions: the descriptions enhanced_orb_compare
writes (sequence_light.csv, LightCondition::describe), read as written, the first folder's first.

Run by scripts/test.sh with the Python module's tests: python3 -m pytest test/python.
"""
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

from reports.sequence import light_descriptions  # noqa: E402


def write_light(folder, rows):
    folder.mkdir()
    lines = ["sequence,condition,frames,description"] + ['s,%s,51,"%s"' % row for row in rows]
    (folder / "sequence_light.csv").write_text("\n".join(lines) + "\n")
    return str(folder)


def test_descriptions_with_commas_and_quotes_are_read_whole(tmp_path):
    src = write_light(tmp_path / "a", [("dim", "x0.25, gain 2"), ("lamp", 'a ""lamp"", x1.2 at the centre')])
    assert light_descriptions([src]) == {"dim": "x0.25, gain 2", "lamp": 'a "lamp", x1.2 at the centre'}


def test_the_first_folder_describes_a_condition_both_describe(tmp_path):
    first = write_light(tmp_path / "a", [("dip", "x0.02 over frames 17-42 of 51")])
    second = write_light(tmp_path / "b", [("dip", "other"), ("dark", "x0.06, gain 4")])
    assert light_descriptions([first, second]) == {"dip": "x0.02 over frames 17-42 of 51", "dark": "x0.06, gain 4"}


def test_a_folder_without_descriptions_adds_none(tmp_path):
    (tmp_path / "old").mkdir()
    assert light_descriptions([str(tmp_path / "old")]) == {}
