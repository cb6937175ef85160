"""scripts/reports/sequence.py's description of the light conditions: the dip's frames as
LightCondition::light() (src/evaluation/sequence.cpp) puts them, for the length of each sequence.

Run by scripts/test.sh with the Python module's tests: python3 -m pytest test/python.
"""
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

from reports.sequence import light_text  # noqa: E402


def test_the_dip_spans_frames_100_to_250_of_300():
    assert "(frames 100-250 of 300)" in light_text("dip", 300)


def test_the_dip_scales_with_a_short_sequence_rounding_half_up():
    # 51 frames: 100 * 51 / 300 = 17, 250 * 51 / 300 = 42.5, rounded as std::lround does.
    assert "(frames 17-43 of 51)" in light_text("dip", 51)


def test_a_condition_without_frames_reads_as_written():
    assert light_text("dim", 51) == "x0.25, gain 2"
    assert light_text("unknown", 51) == ""
