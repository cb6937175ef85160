"""What the report sections share: tables, the pose AUC, and writing a section between its markers."""
import math
import pathlib
import random


def table(header, rows, align=None):
    """A markdown table; `align` one letter per column, l or r (default: the first column l, the
    rest, numbers, r)."""
    align = align or "l" + "r" * (len(header) - 1)
    out = ["| " + " | ".join(header) + " |", "| " + " | ".join("---:" if a == "r" else "---" for a in align) + " |"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def auc(errors, threshold):
    """Area under the recall curve up to threshold, normalised (as ev::poseAuc)."""
    errors = sorted(errors)
    n = len(errors)
    if n == 0:
        return 0.0
    area, previous, reached = 0.0, 0.0, 0
    for i, e in enumerate(errors):
        if e >= threshold:
            break
        area += (e - previous) * i / n
        previous, reached = e, i + 1
    area += (threshold - previous) * reached / n
    return area / threshold


def auc_difference_interval(errors_a, errors_b, threshold, block, draws=1000, level=0.95, seed=0):
    """How far the difference auc(a) - auc(b) moves when the pairs are drawn again: `errors_a` and
    `errors_b` map each pair (start frame, gap) to its error, for the same pairs; the start frames
    are drawn again with replacement in blocks of `block` consecutive ones (pairs that share frames
    stay together), as many blocks as cover them once. Returns the (1 - level) / 2 and
    (1 + level) / 2 quantiles of the `draws` differences; (nan, nan) without pairs."""
    frames = sorted({pair[0] for pair in errors_a})
    if not frames:
        return math.nan, math.nan
    by_frame = {f: [] for f in frames}
    for pair in errors_a:
        by_frame[pair[0]].append(pair)
    block = max(1, min(block, len(frames)))
    starts = list(range(len(frames) - block + 1))
    rng = random.Random(seed)
    diffs = []
    for _ in range(draws):
        a, b = [], []
        for _ in range(math.ceil(len(frames) / block)):
            first = rng.choice(starts)
            for f in frames[first:first + block]:
                for pair in by_frame[f]:
                    a.append(errors_a[pair])
                    b.append(errors_b[pair])
        diffs.append(auc(a, threshold) - auc(b, threshold))
    diffs.sort()
    low = diffs[int(math.floor((1.0 - level) / 2.0 * (draws - 1)))]
    high = diffs[int(math.ceil((1.0 + level) / 2.0 * (draws - 1)))]
    return low, high


def markers(name):
    return "<!-- %s:begin -->" % name, "<!-- %s:end -->" % name


def read_section(text, name):
    """The text between <!-- name:begin --> and <!-- name:end --> of `text`; ValueError without them."""
    begin, end = markers(name)
    if begin not in text or end not in text:
        raise ValueError("no section %s" % name)
    return text[text.index(begin) + len(begin):text.index(end)]


def write_section(doc, name, body):
    """Replaces the text between <!-- name:begin --> and <!-- name:end --> of `doc` with `body`
    (the markers kept), or appends the marked section when the markers are missing."""
    path = pathlib.Path(doc)
    text = path.read_text() if path.exists() else ""
    begin, end = markers(name)
    section = begin + "\n" + body.rstrip("\n") + "\n" + end
    if begin in text and end in text:
        text = text[:text.index(begin)] + section + text[text.index(end) + len(end):]
    else:
        text = text.rstrip("\n") + "\n\n" + section + "\n"
    path.write_text(text)
