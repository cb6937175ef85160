"""Turns enhanced_orb_compare's CSV files into the equal-budget section of docs/RESULTS.md (between
the compare:begin and compare:end markers) and its plots in docs/results/.

    python3 scripts/report.py compare RESULTS_DIR [docs/RESULTS.md]
"""
import collections
import csv
import os
import sys

from reports.common import auc, table, write_section

GROUPS = ["<40", "40-80", "80-170", ">170", "webcam"]
ORDER = ["default", "motion", "stretch", "paper", "baseline", "cv::ORB", "CLAHE+cv::ORB", "ORB-SLAM"]
RIVALS = ["baseline", "cv::ORB", "CLAHE+cv::ORB"]  # what the default mode must beat


def group(row):
    if row["set"] == "webcam":
        return "webcam"
    m = float(row["mean_target"])
    return "<40" if m < 40 else "40-80" if m < 80 else "80-170" if m < 170 else ">170"


def mean(values):
    return sum(values) / len(values) if values else 0.0


def verdict(values):
    """The default mode's value over the best rival's, marked when it loses."""
    best = max(values.get(m, 0.0) for m in RIVALS)
    ratio = values.get("default", 0.0) / best if best > 0 else float("inf")
    return ("**%.2fx**" if ratio > 1.0 else "%.2fx (loses)") % ratio


INTRO = """## Equal budgets under real bad light: the default mode

`enhanced_orb_compare` (first step of `bash scripts/results.sh`), one build, one run, all methods
on the same images at the same budgets (single-threaded extraction, two pairs at a time):
**default** = this package's default mode; **stretch** = the `stretch` preset (the default mode
with a linear stretch and each level's strongest corners, for light that changes inside the scene);
**motion** = the `motion` preset (the default mode with its candidates chosen by the frame's noise,
for a moving camera: "Real camera motion" below);
**paper** = the `paper` preset (Dai & Wu as published) at the same budget; **baseline** = the paper's original ORB (no enhancement, FAST 20);
**cv::ORB** = `cv::ORB::create(N, 1.2f, 8)`; **CLAHE+cv::ORB** = `cv::createCLAHE(3.0, 8x8)` then
cv::ORB. Matching: brute-force Hamming, mutual nearest neighbours. Data: the exposure brackets
(HDR Photographic Survey, M. D. Fairchild; Debevec & Malik 1997; Merianos & Mitianoudis, IST 2016)
and the fixed webcams (TILDE, Verdie et al., CVPR 2015, from AMOS) of `../shared/data/lighting`,
and the 95 EuRoC V1_01_easy frames (Burri et al., IJRR 2016) of `../shared/data/euroc`.

This section alone:

```bash
devel/lib/enhanced_orb/enhanced_orb_compare --lighting ../shared/data/lighting \\
  --euroc ../shared/data/euroc/V1_01_easy_micro --output /tmp/compare      # about 15 minutes here
python3 scripts/report.py compare /tmp/compare docs/RESULTS.md
```
"""

LOSSES = """Where it loses, and why as far as measured (lighting numbers at 1000 features, per pair):
- **Webcams** (light changing inside the scene: shadows, lamps, seasons): about 129 correct
  matches against cv::ORB's 178. The same detector and selection without any enhancement
  (`--methods default --set enhance=false`) keep about 158, with the blur but no tone curve
  (`--set gamma_mode=never`) 158, and ranking by FAST score alone on the raw image
  (`--set enhance=false --set candidate_ratio=1`) 184, above cv::ORB, but that loses the exposure
  groups (1.34x instead of 2x below mean gray 40; 0.91x above 170). Every tone curve tried loses on
  the webcams: half strength (`--set beta=0.5`: 144, and 1.9x below 40) and, in experiments not
  kept in the code, the package's earlier 4x4 tiled curves (133), a fixed logarithmic curve, the
  same for every frame (124-140), a gamma that brings the edge-weighted median to mid-gray (139),
  a curve whose strength follows the frame's exposure (at most 142, and 0.82-0.86x on the darkened
  and gamma-changed EuRoC copies); ranking by Harris score instead of FAST score lost everywhere
  (webcams 118-125), and so did every local adaptation measured (CLAHE+cv::ORB; a Retinex-style
  division by the frame's blurred log, 124-130; ranking by score over the cell's threshold; a cap on
  each region's share of the budget). The curve is what wins every exposure group, so the default
  keeps it, one setting for every frame, and loses here. The **stretch** preset is the setting for
  such scenes (its own table above): a linear stretch keeps the camera's order and ratios of tones,
  and each level keeps its strongest corners; it wins the webcams and the darkest targets and loses
  where the light changes in tone or over the frame by itself (spotlight, gradient, saturation,
  gamma), the tests the default mode wins. Looking at the corners kept (`enhanced_orb_extract`
  on a reference and a target): on the webcams most correct matches sit on outlines against the
  sky, the frame's strongest raw contrasts, and the curve and the spreading both move budget from
  them into the square below, where people, cars and parasols change from frame to frame; on EuRoC
  the strongest raw contrasts are the checkerboard's, whose corners repeat and whose white
  saturates under `bright`, and there the same two steps win. The nearest single setting measured
  (`--set tau=0.9 --set candidate_ratio=1`: the curve at a tenth of its strength, the strongest
  corners; EuRoC every 10th frame, pairs every 6th) ties cv::ORB on the webcams (1.00x) and falls to
  1.57x below mean gray 40, 0.81-0.82x under a gamma change and 0.86x under `bright`.
- **At 500 and 2000 features** the tables above say where it falls behind; at 2000, with both
  frames of a pair under `night`, its spread selection reaches corners that noise makes unstable,
  while cv::ORB and CLAHE+cv::ORB rank without spreading.
- **Pose AUC** is a weak test on this excerpt: a static scene, an 11 cm baseline, 74 frames with
  ground truth, each one stereo pair. The translation direction decides the error for every
  method (median over all degradations at 1000 features: 10-20 degrees; the rotation's 0.6-1.4),
  and the AUC moves with the noise drawn: with one frame in three (25 pairs, as this comparison
  used before) the default mode was behind cv::ORB and the baseline at 10 and 20 degrees under
  `lowlight` at 1000 features, with every frame it is ahead. At 500 features the baseline's is
  higher. Read it beside the correct-match counts.
- The EuRoC excerpt's camera is static: EuRoC pairs test light and noise, not viewpoint change.
"""


def budget_tables(budgets, keys, correct, methods, lead_header, lead):
    """One table per budget: a row per key (its first cells `lead(budget, key)`), each method's mean
    correct matches from correct[(budget, key, method)], and the default mode's verdict."""
    lines = []
    for b in budgets:
        body = []
        for k in keys:
            values = {m: mean(correct[(b, k, m)]) for m in methods}
            body.append(lead(b, k) + ["%.1f" % values[m] for m in methods] + [verdict(values)])
        lines.append("**Budget %d**\n" % b)
        lines.append(table(lead_header + methods + ["default / best rival"], body) + "\n")
    return lines


def summary_cell(values_by_test, mode):
    """'wins (a-bx)' or 'loses: test (r), ...' for `mode` from {test: {method: value}}."""
    ratios = {}
    for test, values in values_by_test.items():
        best = max(values.get(m, 0.0) for m in RIVALS)
        if best > 0:
            ratios[test] = values.get(mode, 0.0) / best
    if not ratios:
        return "-"
    losing = {t: r for t, r in ratios.items() if r <= 1.0}
    if not losing:
        low, high = min(ratios.values()), max(ratios.values())
        return "wins (%.2fx)" % low if "%.2f" % low == "%.2f" % high else "wins (%.2f-%.2fx)" % (low, high)
    return "**loses**: " + ", ".join("%s %.2fx" % (t, r) for t, r in sorted(losing.items()))


def main(args):
    if not args:
        sys.exit(__doc__)
    src = args[0]
    doc = args[1] if len(args) > 1 else os.path.join(os.path.dirname(__file__), "..", "..", "docs", "RESULTS.md")
    out_dir = os.path.join(os.path.dirname(doc), "results")
    lines = []

    rows = list(csv.DictReader(open(os.path.join(src, "lighting.csv"))))
    budgets = sorted({int(r["budget"]) for r in rows})
    methods = [m for m in ORDER if m in {r["method"] for r in rows}]
    correct = collections.defaultdict(list)
    repeat = collections.defaultdict(list)
    counts = collections.Counter()
    for r in rows:
        k = (int(r["budget"]), group(r), r["method"])
        correct[k].append(int(r["correct"]))
        repeat[k].append(float(r["repeatability"]))
        if r["method"] == methods[0]:
            counts[(int(r["budget"]), group(r))] += 1
    lines.append("### Real lighting change: exposure brackets and webcams\n")
    lines.append("Correct matches per image pair (mutual Hamming nearest neighbours within 3 px, 4 px on the "
                 "webcams), pairs grouped by the target's mean gray; the last column is the default mode over "
                 "the best of baseline, cv::ORB and CLAHE+cv::ORB.\n")
    lines += budget_tables(budgets, GROUPS, correct, methods, ["target mean", "pairs"],
                           lambda b, g: [g, counts[(b, g)]])
    b = 1000 if 1000 in budgets else budgets[0]
    body = [[g] + ["%.3f" % mean(repeat[(b, g, m)]) for m in methods] for g in GROUPS]
    lines.append("Repeatability at %d (share of the smaller set's keypoints seen again):\n" % b)
    lines.append(table(["target mean"] + methods, body) + "\n")
    plot_groups(correct, b, methods, os.path.join(out_dir, "compare_lighting.png"))
    lines.append("![Correct matches per pair by target brightness, budget %d](results/compare_lighting.png)\n" % b)

    rows = list(csv.DictReader(open(os.path.join(src, "euroc_photometric.csv"))))
    correct = collections.defaultdict(list)
    for r in rows:
        correct[(int(r["budget"]), r["degradation"], r["method"])].append(int(r["correct"]))
    degradations = sorted({k[1] for k in correct}, key=lambda d: (d != "lowlight", d))
    lines.append("### EuRoC frames against their degraded copies\n")
    lines.append("Each sampled cam0 frame against itself under a degradation (identity ground truth, 3 px): "
                 "`lowlight` = light x0.2 with shot and read noise (2 e-/DN, 3 e- read), `lowlight_gain` = the "
                 "same amplified x4, `spotlight` / `gradient` = the same sensor under a light field falling to "
                 "0.08, `dark`/`bright` = x0.4 / x1.6, `gamma_*`, `noise_10` = Gaussian noise of 10 DN.\n")
    lines += budget_tables(budgets, degradations, correct, methods, ["degradation"], lambda b, d: [d])

    rows = list(csv.DictReader(open(os.path.join(src, "euroc_pairs.csv"))))
    correct = collections.defaultdict(list)
    errors = collections.defaultdict(list)
    static = collections.Counter()
    for r in rows:
        k = (int(r["budget"]), r["pair"], r["degradation"], r["method"])
        correct[k].append(int(r["correct"]))
        if r["static"] == "1":
            static[(r["pair"], r["degradation"], r["method"])] += 1
        else:
            errors[k].append(max(float(r["rotation_deg"]), float(r["translation_deg"])))
    pairs = sorted({k[1] for k in correct}, key=lambda p: (p == "stereo", len(p), p))
    lines.append("### EuRoC frame pairs, both frames degraded alike\n")
    lines.append("cam0 frames +1/+5/+10 apart and the cam0/cam1 stereo pair at one time. The excerpt's camera "
                 "barely moves (under 2 cm over its 95 frames), so the temporal pairs are judged by the "
                 "ground-truth rotation alone (x2 = K R K^-1 x1 within 3 px); their pose is not defined and is "
                 "not scored. The stereo pair (11 cm baseline) of every frame is judged by the epipolar geometry "
                 "(3 px) and gives the pose test: essential matrix by RANSAC from the matches, error = "
                 "max(rotation, translation direction), AUC at 5/10/20 degrees.\n")
    b = 1000 if 1000 in budgets else budgets[0]
    for p in pairs:
        body = []
        for d in degradations + (["none"] if "none" not in degradations else []):
            if not correct[(b, p, d, methods[0])]:
                continue
            values = {m: mean(correct[(b, p, d, m)]) for m in methods}
            body.append([d] + ["%.1f" % values[m] for m in methods] + [verdict(values)])
        lines.append("**Correct matches, pairs %s, budget %d**\n" % (p, b))
        lines.append(table(["degradation"] + methods + ["default / best rival"], body) + "\n")
    for b in budgets:
        body = []
        for d in sorted({k[2] for k in errors if k[1] == "stereo"}, key=lambda d: (d != "lowlight", d)):
            cells = []
            for m in methods:
                e = errors[(b, "stereo", d, m)]
                cells.append("%.2f / %.2f / %.2f" % (auc(e, 5), auc(e, 10), auc(e, 20)))
            body.append([d] + cells)
        lines.append("**Stereo pose AUC @5/10/20 degrees, budget %d**\n" % b)
        lines.append(table(["degradation"] + methods, body) + "\n")

    summaries = [summarise(src, budgets, methods, m) for m in ("default", "stretch", "motion") if m in methods]
    section_lines = [INTRO] + summaries + [LOSSES] + lines
    write_section(doc, "compare", "\n".join(section_lines))
    print("report compare: wrote %s" % doc)


def summarise(src, budgets, methods, mode):
    """The table of where `mode` (default, or the stretch preset) wins and loses, per test and budget."""
    light = collections.defaultdict(lambda: collections.defaultdict(list))
    for r in csv.DictReader(open(os.path.join(src, "lighting.csv"))):
        light[(int(r["budget"]), group(r))][r["method"]].append(int(r["correct"]))
    photo = collections.defaultdict(lambda: collections.defaultdict(list))
    for r in csv.DictReader(open(os.path.join(src, "euroc_photometric.csv"))):
        photo[(int(r["budget"]), r["degradation"])][r["method"]].append(int(r["correct"]))
    pairs = collections.defaultdict(lambda: collections.defaultdict(list))
    lowlight = collections.defaultdict(lambda: collections.defaultdict(list))
    for r in csv.DictReader(open(os.path.join(src, "euroc_pairs.csv"))):
        pairs[(int(r["budget"]), r["pair"], r["degradation"])][r["method"]].append(int(r["correct"]))
        if r["pair"] == "stereo" and r["degradation"] == "lowlight":
            lowlight[int(r["budget"])][r["method"]].append(max(float(r["rotation_deg"]), float(r["translation_deg"])))

    def means(d):
        return {m: mean(v) for m, v in d.items()}

    rows = []
    tests = [
        ("exposure brackets, by target brightness",
         lambda b: {g: means(light[(b, g)]) for g in GROUPS[:4]}),
        ("fixed webcams", lambda b: {"webcams": means(light[(b, "webcam")])}),
        ("EuRoC frames against degraded copies",
         lambda b: {d: means(v) for (bb, d), v in photo.items() if bb == b}),
        ("EuRoC frame pairs +1/+5/+10, unchanged",
         lambda b: {p: means(v) for (bb, p, d), v in pairs.items() if bb == b and d == "none" and p != "stereo"}),
        ("EuRoC frame pairs +1/+5/+10, degraded alike",
         lambda b: {p + " " + d: means(v) for (bb, p, d), v in pairs.items() if bb == b and d != "none"
                    and p != "stereo"}),
        ("EuRoC stereo pairs, every degradation",
         lambda b: {d: means(v) for (bb, p, d), v in pairs.items() if bb == b and p == "stereo"}),
    ]
    for name, values in tests:
        rows.append([name] + [summary_cell(values(b), mode) for b in budgets])
    darkest = []
    for b in budgets:
        v = means(light[(b, "<40")])
        best = max(v.get(m, 0.0) for m in RIVALS)
        darkest.append("%.2fx the best other" % (v.get(mode, 0.0) / best) if best else "-")
    rows.append(["targets darker than mean gray 40"] + darkest)
    auc_cells = []
    for b in budgets:
        aucs = {m: [auc(lowlight[b][m], t) for t in (5, 10, 20)] for m in methods if lowlight[b][m]}
        if mode not in aucs:
            auc_cells.append("-")
            continue
        rivals = [m for m in aucs if m != mode and m in RIVALS + ["paper"]]
        behind = [t for k, t in enumerate((5, 10, 20)) if any(aucs[m][k] >= aucs[mode][k] for m in rivals)]
        auc_cells.append("best at 5/10/20" if not behind else "**not best** at " + "/".join(map(str, behind)))
    rows.append(["stereo pose AUC under `lowlight`"] + auc_cells)
    title = "the default mode" if mode == "default" else "the `%s` preset" % mode
    return ("**Where %s stands** (correct matches against the best of baseline, cv::ORB and "
            "CLAHE+cv::ORB, computed from the tables below):\n\n" % title +
            table(["test"] + ["budget %d" % b for b in budgets], rows) + "\n")


def plot_groups(correct, budget, methods, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 3.6))
    width = 0.8 / len(methods)
    for i, m in enumerate(methods):
        xs = [g + (i - len(methods) / 2 + 0.5) * width for g in range(len(GROUPS))]
        ax.bar(xs, [mean(correct[(budget, g, m)]) for g in GROUPS], width, label=m)
    ax.set_xticks(range(len(GROUPS)))
    ax.set_xticklabels(["mean < 40", "40-80", "80-170", "> 170", "webcams"])
    ax.set_ylabel("correct matches per pair")
    ax.set_title("Real lighting change, %d features" % budget)
    ax.legend(fontsize=8, ncol=3)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)

