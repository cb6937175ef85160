"""scripts/reports/orbslam3.py's monocular start table (scripts/orbslam3_eval.sh, START_EVERY) on a
made-up tree of starts: frames tracked, maps from the first pair, starts without a map.

Run by scripts/test.sh with the Python module's tests: python3 -m pytest test/python.
"""
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))

from reports import orbslam3  # noqa: E402

FRAMES = 10


def write_start(starts, build, condition, first, tracked, seed=1):
    """One start of FRAMES frames from `first` whose trajectory holds its last `tracked` frames (none:
    no trajectory file, as when ORB-SLAM3 never started a map), run with the two-view RANSAC's `seed`
    (orbslam3_eval.sh, START_SEEDS: FIRST for seed 1, FIRST.SEED for another)."""
    stamps = [1403636584763555584 + 50_000_000 * (first + i) for i in range(FRAMES)]
    run = starts / build / condition / (str(first) if seed == 1 else f"{first}.{seed}")
    run.mkdir(parents=True)
    (run / "times.txt").write_text("".join(f"{s}\n" for s in stamps))
    if tracked is not None:
        # ORB-SLAM3's EuRoC trajectory: stamp, position, quaternion; the last pose written twice
        # (as while lost) must count once.
        lines = [f"{s} 0 0 0 0 0 0 1" for s in stamps[FRAMES - tracked:]]
        (run / "f_run.txt").write_text("\n".join(lines + lines[-1:]) + "\n")


def test_start_table_counts_frames_first_pairs_and_starts_without_a_map(tmp_path):
    starts = tmp_path / "starts"
    for first, tracked in ((0, 9), (10, 4), (20, None)):
        write_start(starts, "stock", "dusk", first, tracked)
    for first, tracked in ((0, 9), (10, 9), (20, 6)):
        write_start(starts, "enhanced_orb-default", "dusk", first, tracked)
    rows = orbslam3.start_table(starts, ["stock", "enhanced_orb-default"])
    assert "3 starts, every 10th frame" in rows[0]
    assert rows[3:5] == ["| dusk | ORB-SLAM3's own | 4.33 | 1 of 3 | 1 of 3 |",
                         "| dusk | enhanced_orb default | 8.00 | 2 of 3 | 0 of 3 |"]


def test_start_table_is_empty_without_starts(tmp_path):
    assert orbslam3.start_table(tmp_path / "starts", ["stock"]) == []


def test_start_table_counts_each_seed_of_a_start_as_a_run(tmp_path):
    starts = tmp_path / "starts"
    for first in (0, 10):
        for seed, tracked in ((1, 9), (2, 5), (3, None)):
            write_start(starts, "stock", "lamp", first, tracked, seed)
    rows = orbslam3.start_table(starts, ["stock"])
    assert "2 starts, every 10th frame, each with 3 seeds of the two-view RANSAC (1, 2, 3)" in rows[0]
    assert rows[3] == "| lamp | ORB-SLAM3's own | 4.67 | 2 of 6 | 2 of 6 |"
