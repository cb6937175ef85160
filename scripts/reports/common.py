"""What the report sections share: tables, the pose AUC, and writing a section between its markers."""
import pathlib


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "| " + " | ".join(["---"] + ["---:"] * (len(header) - 1)) + " |"]
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


def write_section(doc, name, body):
    """Replaces the text between <!-- name:begin --> and <!-- name:end --> of `doc` with `body`
    (the markers kept), or appends the marked section when the markers are missing."""
    path = pathlib.Path(doc)
    text = path.read_text() if path.exists() else ""
    begin, end = "<!-- %s:begin -->" % name, "<!-- %s:end -->" % name
    section = begin + "\n" + body.rstrip("\n") + "\n" + end
    if begin in text and end in text:
        text = text[:text.index(begin)] + section + text[text.index(end) + len(end):]
    else:
        text = text.rstrip("\n") + "\n\n" + section + "\n"
    path.write_text(text)
