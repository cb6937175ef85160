#!/usr/bin/env python3
"""Makes docs/annotated.jpg, the README's picture: a scene drawn here (no third-party image),
darkened to 35 % of its brightness, run through enhanced_orb_extract in the default mode, the
paper preset and as the original ORB, at 1000 features, side by side.

  python3 docs/make_figure.py [--tool devel/lib/enhanced_orb/enhanced_orb_extract]
"""
import argparse
import os
import subprocess
import tempfile

import cv2
import numpy as np


def scene(width=752, height=480, seed=11):
    """Overlapping shaded shapes and a little sensor noise: a room-like clutter of corners."""
    rng = np.random.RandomState(seed)
    yy, xx = np.mgrid[0:height, 0:width].astype(np.float32)
    img = 90 + 60 * (xx / width) + 20 * np.sin(yy / 37.0)
    for _ in range(70):
        x0, y0 = rng.randint(0, width), rng.randint(0, height)
        w, h = rng.randint(15, 140), rng.randint(15, 140)
        level = rng.randint(20, 240)
        shade = level + 25 * ((xx - x0) / max(w, 1))
        if rng.rand() < 0.5:
            mask = (xx >= x0) & (xx < x0 + w) & (yy >= y0) & (yy < y0 + h)
        else:
            mask = ((xx - x0) / max(w, 1)) ** 2 + ((yy - y0) / max(h, 1)) ** 2 < 0.25
        img[mask] = shade[mask]
    img += rng.normal(0, 2.0, img.shape)
    return np.clip(img, 0, 255).astype(np.uint8)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--tool", default="devel/lib/enhanced_orb/enhanced_orb_extract")
    parser.add_argument("--output", default=os.path.join(os.path.dirname(__file__), "annotated.jpg"))
    args = parser.parse_args()
    dark = np.clip(np.rint(scene() * 0.35), 0, 255).astype(np.uint8)
    with tempfile.TemporaryDirectory() as tmp:
        src = os.path.join(tmp, "scene.png")
        cv2.imwrite(src, dark)
        panels = []
        for name, flags in (("default", []), ("paper", ["--preset", "paper"]), ("original", ["--preset", "baseline"])):
            out = os.path.join(tmp, name)
            subprocess.run([args.tool, *flags, "--max-features", "1000", "--save-annotated", src, "--output", out],
                           check=True, stdout=subprocess.DEVNULL)
            panel = cv2.imread(os.path.join(out, "scene_annotated.png"))
            label = {"default": "default mode", "paper": "paper preset", "original": "original ORB (FAST 20)"}[name]
            cv2.putText(panel, label, (10, 46), cv2.FONT_HERSHEY_SIMPLEX, 0.7, (0, 0, 0), 4, cv2.LINE_AA)
            cv2.putText(panel, label, (10, 46), cv2.FONT_HERSHEY_SIMPLEX, 0.7, (255, 255, 255), 1, cv2.LINE_AA)
            panels.append(panel)
    gap = np.zeros((panels[0].shape[0], 8, 3), np.uint8)
    figure = np.hstack([panels[0], gap, panels[1], gap, panels[2]])
    figure = cv2.resize(figure, None, fx=0.6, fy=0.6, interpolation=cv2.INTER_AREA)
    cv2.imwrite(args.output, figure, [cv2.IMWRITE_JPEG_QUALITY, 85])
    print("wrote", args.output)


if __name__ == "__main__":
    main()
