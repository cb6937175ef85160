"""A cv2 user's program with only the create line changed, run against the installed package alone:
enhanced_orb must import from the install prefix (not the devel space) and find features."""
import sys

import cv2
import enhanced_orb
import enhanced_orb.msg

prefix = sys.argv[2]
if not enhanced_orb.__file__.startswith(prefix):
    sys.exit("enhanced_orb imported from %s, not from the install prefix %s" % (enhanced_orb.__file__, prefix))
image = cv2.imread(sys.argv[1], cv2.IMREAD_GRAYSCALE)
orb = enhanced_orb.ORB_create(nfeatures=500)  # was cv2.ORB_create(nfeatures=500)
keypoints, descriptors = orb.detectAndCompute(image, None)
matches = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).match(descriptors, descriptors)
print("written_for_cv2: %d keypoints, %d self-matches, %s" % (len(keypoints), len(matches), enhanced_orb.__file__))
sys.exit(0 if len(keypoints) > 100 and len(matches) == len(keypoints) else 1)
