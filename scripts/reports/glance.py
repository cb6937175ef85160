"""README's relative-pose summary: for each sequence section of docs/RESULTS.md (indoor and
driving) and each budget, the default mode's pose AUC@10 over the best rival's in unchanged light
and across the changes of light, and the lights where it loses with their intervals. It reads the
tables the sequence report wrote, so that README and RESULTS.md cannot disagree.

    python3 scripts/report.py glance [RESULTS [README]]   (defaults docs/RESULTS.md, README.md)
"""
import pathlib
import re

from reports.common import read_section, table, write_section

# The sections of RESULTS.md, in README's order: (marker, how README names the sequence).
SECTIONS = [("sequence", "EuRoC `MH_01_easy_moving`, indoor, 20 Hz"),
            ("driving_turn_51", "KITTI `turn_51`, a car turning, 10 Hz"),
            ("driving_straight_51", "KITTI `straight_51`, a car driving straight, 10 Hz")]
COLUMN = "default / best rival"

ROOT = pathlib.Path(__file__).resolve().parents[2]


def pose_rows(section):
    """{budget: [(light, ratio, loss)]} from a section's "N features: pose AUC@10" tables: the
    ratio of the default mode's AUC@10 to the best rival's, and where the table says it loses the
    loss's interval as written ("" without one), else None."""
    rows, budget, column = {}, None, None
    for line in section.splitlines():
        heading = re.match(r"### (\d+) features: pose AUC@10", line)
        if heading:
            budget, column = int(heading.group(1)), None
            continue
        if line.startswith("#"):
            budget = None
        if budget is None or not line.startswith("|"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if COLUMN in cells:
            column = cells.index(COLUMN)
        elif column is not None and cells[0].endswith("AUC@10"):
            ratio = re.search(r"([0-9.]+)x", cells[column])
            if ratio is None:
                raise ValueError("no ratio in %r" % line)
            loss = re.search(r"loses(?:; ([^)]*))?", cells[column])
            rows.setdefault(budget, []).append((cells[0].split()[0], float(ratio.group(1)),
                                                None if loss is None else loss.group(1) or ""))
    return rows


def ratio_cell(ratio, loses):
    return "%.2fx" % ratio if loses else "**%.2fx**" % ratio


def summary(results_text):
    """README's table from the text of RESULTS.md."""
    out = []
    for name, label in SECTIONS:
        rows = pose_rows(read_section(results_text, name))
        if not rows:
            raise ValueError("no pose AUC@10 tables in section %s" % name)
        for budget in sorted(rows):
            lights = rows[budget]
            unchanged = [r for r in lights if r[0] == "unchanged"]
            changed = [r for r in lights if r[0] != "unchanged"]
            losses = ["%s (%s)" % (light, loss) if loss else light for light, _, loss in lights if loss is not None]
            low = min(changed, key=lambda r: r[1])
            high = max(changed, key=lambda r: r[1])
            out.append([label, budget,
                        ratio_cell(unchanged[0][1], unchanged[0][2] is not None) if unchanged else "-",
                        "%s to %s" % (ratio_cell(low[1], low[2] is not None), ratio_cell(high[1], high[2] is not None)),
                        "; ".join(losses) if losses else "none"])
    return table(["sequence", "features", "unchanged light", "the changes of light", "loses (interval)"], out,
                 align="lrrrl")


def main(args):
    results = pathlib.Path(args[0]) if args else ROOT / "docs" / "RESULTS.md"
    readme = pathlib.Path(args[1]) if len(args) > 1 else ROOT / "README.md"
    write_section(readme, "glance", summary(results.read_text()))
    print("glance: wrote the summary into", readme)
