"""scripts/reports/common.py's auc_difference_interval, the bracket the sequence tables give a loss:
how far the AUC difference of two methods moves when the pairs are drawn again in blocks.

Run by scripts/test.sh with the Python module's tests: python3 -m pytest test/python.
"""
import math
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

from reports.common import auc, auc_difference_interval  # noqa: E402

GAPS = (1, 3, 5)


def pairs(errors_of_frame, frames=40):
    """{(frame, gap): error} for every start frame and gap."""
    return {(f, g): errors_of_frame(f, g) for f in range(frames) for g in GAPS}


def test_same_errors_give_no_difference():
    a = pairs(lambda f, g: (f * 7 + g) % 13)
    assert auc_difference_interval(a, dict(a), 10.0, block=5) == (0.0, 0.0)


def test_a_method_better_on_every_pair_is_better_in_every_draw():
    a = pairs(lambda f, g: 1.0 + (f % 3))
    b = pairs(lambda f, g: 6.0 + (f % 3))
    low, high = auc_difference_interval(a, b, 10.0, block=5)
    assert 0.0 < low <= high
    assert math.isclose(low, 0.5) and math.isclose(high, 0.5)  # every pair 5 degrees apart: 0.5 of 10


def test_a_difference_that_hangs_on_a_few_frames_holds_zero():
    # a is better on the first frames, worse on the last: drawn again, either can lead.
    a = pairs(lambda f, g: 1.0 if f < 20 else 9.0)
    b = pairs(lambda f, g: 9.0 if f < 20 else 1.0)
    low, high = auc_difference_interval(a, b, 10.0, block=5)
    assert low < 0.0 < high


def test_one_block_over_every_frame_draws_the_pairs_as_they_are():
    a = pairs(lambda f, g: (f + g) % 11)
    b = pairs(lambda f, g: (2 * f + g) % 11)
    point = auc(list(a.values()), 10.0) - auc(list(b.values()), 10.0)
    low, high = auc_difference_interval(a, b, 10.0, block=1000)
    assert math.isclose(low, point) and math.isclose(high, point)


def test_the_draws_are_the_same_for_the_same_seed():
    a = pairs(lambda f, g: (f * 5 + g) % 12)
    b = pairs(lambda f, g: (f * 3 + 2 * g) % 12)
    assert auc_difference_interval(a, b, 10.0, block=3) == auc_difference_interval(a, b, 10.0, block=3)


def test_no_pairs_give_no_interval():
    assert all(math.isnan(v) for v in auc_difference_interval({}, {}, 10.0, block=3))
