"""The table of scripts/orbslam3_eval.sh: ORB-SLAM3 with its own extractor and with enhanced_orb's,
stereo and monocular, per light condition, over the repeated runs.

    python3 scripts/report.py orbslam3 RUNS DATA [docs/RESULTS.md]

RUNS holds RUNS/<build>/<sensor>/<condition>/<repeat>/ with log.txt and f_run.txt, and RUNS/../frames/
<condition>/times.txt the frames each run was given (ORB-SLAM3's
EuRoC trajectory: timestamp [ns], position, quaternion x y z w; the frames of its largest map that
were tracked); DATA is the EuRoC folder the frames came from (its ground truth and cam0's T_BS).
With a third argument the section between <!-- orbslam3:begin --> and <!-- orbslam3:end --> of
that file is replaced (appended when the markers are missing).

Per run: frames tracked = frames in the trajectory (largest map, tracking not lost) over the frames
given; "local map lost" = ORB-SLAM3's "Fail to track local map!" events; maps = maps started ("New
Map created", the first one included: every further one is a reset or a new map after tracking was
lost); ATE = RMSE of the camera positions after aligning them to the ground truth (SE(3) stereo,
Sim(3) monocular, Umeyama), ground truth T_WB(t) T_BS, matched within 5 ms; repeated timestamps
(ORB-SLAM3 writes the last pose again while lost) dropped."""
import pathlib
import re
import statistics
import sys

import numpy as np

from reports.common import write_section

INTRO = """## Inside ORB-SLAM3: stock extractor against enhanced_orb

ORB-SLAM3 v1.0 (upstream commit 4452a3c) built twice by `scripts/orbslam3_eval.sh` from the same
sources, once as it ships and once with `enhanced_orb::OrbSlamExtractor` in place of its
ORBextractor (docs/ORB_SLAM3.md: the lines a user changes), the EuRoC examples with their own
settings (stereo 1200 features, monocular 1000; FAST 20/7; 8 levels of 1.2), both with the same
vocabulary (trained here with ORB-SLAM3's DBoW2 on images that are not the test sequence; users
use the official ORBvoc.txt). Data: `MH_01_easy_moving` (300 stereo frames at 20 Hz) under each
light condition of the sequence evaluation above, written as EuRoC folders by
`enhanced_orb_compare --write-sequence` (the same frames). Every run at real time, as the examples
pace themselves. A monocular map starts from the first pair of frames whose two-view reconstruction
passes ORB-SLAM3's checks (one clear solution, enough parallax), a RANSAC that ORB-SLAM3 seeds with
0, so that every repeat of a run starts the same way: both copies here read that seed from
`ORBSLAM3_EVAL_SEED` instead, and the monocular runs of a cell (twice the stereo runs by default:
three draws were seen to rank two starts either way) are seeds 1, 2, 3 and on, the same for every
extractor (glibc's `srand` takes 0 as 1, so seed 1 is the start as shipped; stereo does not use
it). **frames tracked**: frames in ORB-SLAM3's trajectory file, i.e. in its largest map and not
lost, over the 300 given; **local map lost**: its
"Fail to track local map!" events; **maps**: maps started (each after the first is a reset or a new map after tracking was lost);
**ATE**: RMSE of the camera positions after alignment to the ground truth (T_WB T_BS of cam0).
**enhanced_orb default** is the adapter as a user gets it (no `ENHANCED_ORB_CONFIG`, or
`config/default.yaml`): the default mode, which judges from the frames ORB-SLAM gives each extractor
in order whether the camera moves (the moving selection here from the first frame on: the adapter
counts a stream's first frame as a moving camera's, and the second confirms it), with the tone curve
on every frame of a moving camera (the adapter's `moving_gamma_mode: always`, since a SLAM map
matches frames against points described under earlier light; outside ORB-SLAM the default mode gives
a moving camera's frames no curve, docs/ORB_SLAM3.md says why not here); **enhanced_orb motion**
`config/motion.yaml` (the moving selection without the judgment; the curve on every frame as in the
default). Another preset or parameter file runs as `PRESETS=<name>` with `config/<name>.yaml`.

```bash
bash scripts/orbslam3_eval.sh ~/ORB_SLAM3 ~/ORB_SLAM3/Vocabulary/ORBvoc.txt \\
  ../shared/data/euroc/MH_01_easy_moving /tmp/eo_orbslam3
python3 scripts/report.py orbslam3 /tmp/eo_orbslam3/runs ../shared/data/euroc/MH_01_easy_moving docs/RESULTS.md
```
"""

# The sequence evaluation's light conditions in its order (enhanced_orb_compare --help).
CONDITIONS = ["unchanged", "dim", "dark", "dusk", "lights_out", "flicker", "lamp", "dip"]


def run_name(run):
    """stock, or enhanced_orb-<preset>."""
    return "ORB-SLAM3's own" if run == "stock" else "enhanced_orb %s" % run.split("-", 1)[1]


def read_sensor_T_BS(path):
    text = pathlib.Path(path).read_text()
    block = text[text.index("T_BS"):]
    numbers = re.search(r"data:\s*\[([^\]]*)\]", block).group(1)
    return np.array([float(v) for v in numbers.replace("\n", " ").split(",")]).reshape(4, 4)


def quaternion_matrix(w, x, y, z):
    n = np.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def ground_truth(data):
    """Camera (cam0) positions in the world frame by timestamp [ns]."""
    mav0 = pathlib.Path(data) / "mav0" if (pathlib.Path(data) / "mav0").is_dir() else pathlib.Path(data)
    T_BS = read_sensor_T_BS(mav0 / "cam0" / "sensor.yaml")
    stamps, positions = [], []
    for line in (mav0 / "state_groundtruth_estimate0" / "data.csv").read_text().splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        v = [float(x) for x in line.split(",")[:8]]
        T = np.eye(4)
        T[:3, :3] = quaternion_matrix(v[4], v[5], v[6], v[7])
        T[:3, 3] = v[1:4]
        stamps.append(int(line.split(",")[0]))
        positions.append((T @ T_BS)[:3, 3])
    order = np.argsort(stamps)
    return np.array(stamps, dtype=np.int64)[order], np.array(positions)[order]


def umeyama(source, target, with_scale):
    """s, R, t minimising |target - (s R source + t)|^2 (Umeyama 1991)."""
    mu_s, mu_t = source.mean(axis=0), target.mean(axis=0)
    a, b = source - mu_s, target - mu_t
    cov = b.T @ a / len(source)
    U, D, Vt = np.linalg.svd(cov)
    S = np.eye(3)
    if np.linalg.det(U) * np.linalg.det(Vt) < 0:
        S[2, 2] = -1
    R = U @ S @ Vt
    s = np.trace(np.diag(D) @ S) / (a * a).sum(axis=1).mean() if with_scale else 1.0
    return s, R, mu_t - s * R @ mu_s


def run_result(run_dir, gt_stamps, gt_positions, n_frames, with_scale):
    log = (run_dir / "log.txt").read_text(errors="replace") if (run_dir / "log.txt").exists() else ""
    result = {
        "lost_local_map": log.count("Fail to track local map!"),
        "maps": log.count("New Map created"),
        "tracked": 0.0,
        "ate": None,
        "no_trajectory": "exit " in log or not (run_dir / "f_run.txt").exists(),
    }
    trajectory = run_dir / "f_run.txt"
    if not trajectory.exists():
        return result
    seen, estimated, truth = set(), [], []
    for line in trajectory.read_text().splitlines():
        fields = line.split()
        if len(fields) < 8:
            continue
        stamp = int(round(float(fields[0])))
        if stamp in seen:
            continue
        seen.add(stamp)
        k = int(np.searchsorted(gt_stamps, stamp))
        best = min((j for j in (k - 1, k) if 0 <= j < len(gt_stamps)), key=lambda j: abs(gt_stamps[j] - stamp))
        if abs(gt_stamps[best] - stamp) <= 5_000_000:
            estimated.append([float(x) for x in fields[1:4]])
            truth.append(gt_positions[best])
    result["tracked"] = len(seen) / n_frames
    if len(estimated) >= 10:
        est, gt = np.array(estimated), np.array(truth)
        s, R, t = umeyama(est, gt, with_scale)
        residual = gt - (s * (R @ est.T).T + t)
        result["ate"] = float(np.sqrt((residual ** 2).sum(axis=1).mean()))
    return result


def start_table(starts, builds):
    """The monocular start (orbslam3_eval.sh, START_EVERY): per condition and build, over the starts,
    the frames in the trajectory (a map started from frames k and k + 1 holds every frame from k + 1
    on), the starts whose first pair started the map, and those with no map by their last frame."""
    if not starts.is_dir():
        return []
    found = {p.name for b in builds for p in (starts / b).glob("*") if p.is_dir()}
    conditions = [c for c in CONDITIONS if c in found] + sorted(found - set(CONDITIONS))
    rows, given, firsts, seeds = [], set(), set(), set()
    for condition in conditions:
        for b in builds:
            runs = sorted((starts / b / condition).glob("*/times.txt"))
            if not runs:
                continue
            tracked, first_pair, none = [], 0, 0
            for times in runs:
                n = len(times.read_text().split())
                given.add(n)
                first, _, seed = times.parent.name.partition(".")  # FIRST (seed 1, as shipped) or FIRST.SEED
                firsts.add(int(first))
                seeds.add(int(seed or 1))
                trajectory = times.parent / "f_run.txt"
                stamps = {line.split()[0] for line in trajectory.read_text().splitlines()
                          if len(line.split()) >= 8} if trajectory.exists() else set()
                tracked.append(len(stamps))
                first_pair += len(stamps) == n - 1
                none += not stamps
            rows.append(f"| {condition} | {run_name(b)} | {statistics.mean(tracked):.2f} | "
                        f"{first_pair} of {len(runs)} | {none} of {len(runs)} |")
    if not rows:
        return []
    n = "/".join(str(v) for v in sorted(given))
    firsts = sorted(firsts)
    every = f", every {firsts[1] - firsts[0]}th frame" if len(firsts) > 1 else ""
    if len(seeds) > 1:
        every += f", each with {len(seeds)} seeds of the two-view RANSAC ({', '.join(map(str, sorted(seeds)))})"
    return [f"**Monocular start** (`mono_euroc` given {n} frames from each of {len(firsts)} starts{every}: "
            "how soon its map starts; a map started from the first pair holds every frame but the "
            f"first, {max(given) - 1})\n",
            "| light | extractor | frames tracked (mean) | map from the first pair | no map |",
            "| --- | --- | ---: | ---: | ---: |"] + rows + [""]


def fmt_ate(values):
    values = [v for v in values if v is not None]
    if not values:
        return "-"
    mm = [1000 * v for v in values]
    if len(mm) == 1:
        return f"{mm[0]:.1f}"
    return f"{statistics.median(mm):.1f} ({min(mm):.1f}-{max(mm):.1f})"


def main(args):
    if len(args) not in (2, 3):
        sys.exit(__doc__)
    runs, data, doc = (list(args) + [None])[:3]
    runs = pathlib.Path(runs)
    gt_stamps, gt_positions = ground_truth(data)
    # the builds that ran: full runs, monocular starts (orbslam3_eval.sh with REPEATS=0 runs only these)
    builds = sorted({p.name for d in (runs, runs.parent / "starts") if d.is_dir() for p in d.iterdir() if p.is_dir()},
                    key=lambda b: (b != "stock", b != "enhanced_orb-default", b))
    lines = [INTRO]
    summary = {}  # (sensor, condition, build) -> (mean frames tracked, median ATE in mm or None)
    for sensor in ("stereo", "mono"):
        found = {p.name for b in builds for p in (runs / b / sensor).glob("*") if p.is_dir()}
        conditions = [c for c in CONDITIONS if c in found] + sorted(found - set(CONDITIONS))
        if not conditions:
            continue
        lines.append(f"**{'Stereo' if sensor == 'stereo' else 'Monocular'}** (`{sensor}_euroc`; "
                     f"ATE: median over the runs, range in brackets, {'SE(3)' if sensor == 'stereo' else 'Sim(3)'} "
                     "alignment)\n")
        lines += ["| light | extractor | frames tracked | local map lost | maps | ATE mm |",
                  "| --- | --- | ---: | ---: | ---: | ---: |"]
        for condition in conditions:
            for b in builds:
                results = []
                for repeat in sorted((runs / b / sensor / condition).glob("*")):
                    times = runs.parent / "frames" / condition / "times.txt"  # the frames given
                    n_frames = len(times.read_text().split()) if times.exists() else len(gt_stamps)
                    results.append(run_result(repeat, gt_stamps, gt_positions, n_frames, sensor == "mono"))
                if not results:
                    continue
                tracked = statistics.mean(r["tracked"] for r in results)
                lost = statistics.mean(r["lost_local_map"] for r in results)
                maps = statistics.mean(r["maps"] for r in results)
                without = sum(r["no_trajectory"] for r in results)
                # ORB-SLAM3's examples crash when asked to save the trajectory of a map that never
                # started: counted as nothing tracked.
                note = f" ({without} of {len(results)} ended without a trajectory)" if without else ""
                lines.append(f"| {condition} | {run_name(b)} | {tracked:.3f}{note} | {lost:.1f} | {maps:.1f} | "
                             f"{fmt_ate([r['ate'] for r in results])} |")
                ates = [1000 * r["ate"] for r in results if r["ate"] is not None]
                summary[(sensor, condition, b)] = (tracked, statistics.median(ates) if ates else None)
        repeats = max(len(list((runs / b / sensor / c).glob("*"))) for b in builds for c in conditions)
        seeds = sorted({int(f.read_text()) for b in builds for f in (runs / b / sensor).glob("*/*/seed")})
        drawn = ""
        if sensor == "mono" and len(seeds) > 1:
            drawn = (f", the two-view RANSAC that starts the map seeded {', '.join(map(str, seeds))} in turn "
                     "(ORB-SLAM3 as shipped: 0, which glibc's srand() takes as 1)")
        lines.append(f"\n{repeats} run(s) per cell{drawn}; tracked, local map lost and maps are means over them.\n")
    lines += start_table(runs.parent / "starts", builds)
    if doc:
        plot(summary, builds, pathlib.Path(doc).resolve().parent / "results" / "orbslam3.png")
        lines.append("![ORB-SLAM3 with its own extractor and with enhanced_orb's: frames tracked and ATE per "
                     "light condition](results/orbslam3.png)\n\nAn x marks a cell without a trajectory to score.\n")
    table = "\n".join(lines)
    print(table)
    if doc:
        write_section(doc, "orbslam3", table)


def plot(summary, builds, path):
    """Frames tracked and ATE per light condition, stereo and monocular, one bar per build."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(12, 6.5))
    width = 0.8 / len(builds)
    for row, sensor in enumerate(("stereo", "mono")):
        conditions = [c for c in CONDITIONS if any((sensor, c, b) in summary for b in builds)]
        for col, (index, label) in enumerate(((0, "frames tracked"), (1, "ATE [mm], median of the runs"))):
            ax = axes[row][col]
            for k, b in enumerate(builds):
                values = [summary.get((sensor, c, b), (0.0, None))[index] for c in conditions]
                xs = [i + (k - (len(builds) - 1) / 2) * width for i in range(len(conditions))]
                ax.bar(xs, [v if v is not None else 0.0 for v in values], width, label=run_name(b))
                for x, v in zip(xs, values):
                    if v is None:  # no trajectory to score
                        ax.text(x, 0.0, "x", ha="center", va="bottom", fontsize=8)
            ax.set_xticks(range(len(conditions)))
            ax.set_xticklabels(conditions, rotation=20, fontsize=8)
            ax.set_title(f"{'stereo' if sensor == 'stereo' else 'monocular'}: {label}", fontsize=10)
            if index == 0:
                ax.set_ylim(0, 1.05)
    axes[0][0].legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=90)
    plt.close(fig)
