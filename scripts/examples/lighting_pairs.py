#!/usr/bin/env python3
"""Correct matches on a lighting set (identity ground truth), enhanced_orb against cv2.ORB at one
budget: the same-place evaluation of enhanced_orb_compare --lighting, written against the Python
module in a few lines (mutual nearest neighbours by Hamming distance; a match is correct when both
keypoints lie within 3 px of each other).

    source devel/setup.bash
    python3 scripts/examples/lighting_pairs.py ../shared/data/lighting/exposure_memorial [BUDGET]
"""
import csv
import pathlib
import sys

import cv2
import numpy as np

import enhanced_orb


def correct_matches(orb, reference, target, pixels=3.0):
    k1, d1 = orb.detectAndCompute(reference, None)
    k2, d2 = orb.detectAndCompute(target, None)
    if d1 is None or d2 is None:
        return 0
    matches = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).match(d1, d2)
    return sum(np.hypot(*np.subtract(k1[m.queryIdx].pt, k2[m.trainIdx].pt)) <= pixels for m in matches)


def main(folder, budget=1000):
    folder = pathlib.Path(folder)
    # Two images of one place are not a camera's frames: camera_motion still (as for single images).
    methods = {"enhanced_orb": enhanced_orb.ORB_create(nfeatures=budget, camera_motion="still"),
               "cv2.ORB": cv2.ORB_create(nfeatures=budget)}
    totals = dict.fromkeys(methods, 0)
    with open(folder / "pairs.csv") as f:
        for pair in csv.DictReader(f):
            ref = cv2.imread(str(folder / pair["ref"]), cv2.IMREAD_GRAYSCALE)
            target = cv2.imread(str(folder / pair["target"]), cv2.IMREAD_GRAYSCALE)
            counts = {name: correct_matches(orb, ref, target) for name, orb in methods.items()}
            print("%-28s mean %6.1f  " % (pair["target"], float(pair["mean_target"]))
                  + "  ".join("%s %4d" % item for item in counts.items()))
            for name, n in counts.items():
                totals[name] += n
    print("total: " + "  ".join("%s %d" % item for item in totals.items()))


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 1000)
