"""The cv2-style half of enhanced_orb: cv2.ORB's methods and keywords over the C++ core.

Parameters are the package's own, by their ROS names (enhanced_orb.params() lists them with their
types, ranges, defaults and meanings, from the one table the nodelets and tools read), and
cv2.ORB_create's keywords, which map onto them. An image is viewed in place when its rows are
contiguous; keypoints are cv2.KeyPoint tuples and descriptors N x 32 uint8 arrays, as cv2 gives.
"""
import cv2
import numpy as np

from enhanced_orb import _enhanced_orb

# cv2.ORB_create's keywords that name one of the package's parameters.
_CV2_NAMES = {
    "nfeatures": "max_features",
    "scaleFactor": "scale_factor",
    "nlevels": "n_levels",
    "fastThreshold": "fast_threshold",
}
# cv2.ORB_create's keywords whose value is fixed here: the value this package computes with, and
# what else it would take. scoreType takes both of cv2's: the budget's selection ranks corners by
# its own rules (docs/ALGORITHM.md) whichever is asked for.
_CV2_FIXED = {
    "edgeThreshold": ((31,), "31 (the 31 x 31 rBRIEF patch)"),
    "patchSize": ((31,), "31 (the 31 x 31 rBRIEF patch)"),
    "firstLevel": ((0,), "0"),
    "WTA_K": ((2,), "2 (256 binary tests)"),
    "scoreType": ((cv2.ORB_HARRIS_SCORE, cv2.ORB_FAST_SCORE), "cv2.ORB_HARRIS_SCORE or cv2.ORB_FAST_SCORE"),
}


def _text(name, value):
    """A Python value as the text the parameter table reads; the table checks type and range."""
    if isinstance(value, (bool, np.bool_)):
        return "true" if value else "false"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    if isinstance(value, str):
        return value
    raise ValueError("%s: %r is not a bool, number or name" % (name, value))


def _values(params):
    """The keywords of ORB_create or enhance as {ROS name: text}, cv2's keywords mapped."""
    values = {}
    for key, value in params.items():
        if key in _CV2_FIXED:
            allowed, what = _CV2_FIXED[key]
            if value not in allowed:
                raise ValueError("%s = %r is not supported: enhanced_orb takes %s" % (key, value, what))
            continue
        name = _CV2_NAMES.get(key, key)
        if name in values:
            raise ValueError("%s is given twice (as %s and %s)" % (name, name, key))
        values[name] = _text(key, value)
    return values


def _keypoints(rows):
    return tuple(
        cv2.KeyPoint(x, y, size, angle, response, int(octave), int(class_id))
        for x, y, size, angle, response, octave, class_id in rows.tolist()
    )


def _keypoint_rows(keypoints):
    rows = np.empty((len(keypoints), 7), np.float64)
    for i, k in enumerate(keypoints):
        if not isinstance(k, cv2.KeyPoint):
            raise TypeError("keypoints must be cv2.KeyPoint objects, got %s" % type(k).__name__)
        rows[i] = (k.pt[0], k.pt[1], k.size, k.angle, k.response, k.octave, k.class_id)
    return rows


class ORB:
    """cv2.ORB's interface over enhanced_orb::ORB (the C++ cv::Feature2D adapter).

    The images detected on are taken as one camera's frames in order: with camera_motion auto (the
    default) they decide whether the camera is judged moving. For images that are not one stream,
    call clear() before each, or pass camera_motion="still".
    """

    def __init__(self, preset="default", **params):
        self._preset = preset
        self._core = _enhanced_orb.Orb(preset, _values(params))

    def detect(self, image, mask=None):
        rows, _ = self._core.detect_and_compute(image, mask, False)
        return _keypoints(rows)

    def compute(self, image, keypoints, descriptors=None):
        """Descriptors of given keypoints; those that cannot be described are left out."""
        rows, descriptors = self._core.compute(image, _keypoint_rows(keypoints))
        return _keypoints(rows), descriptors

    def detectAndCompute(self, image, mask=None, descriptors=None, useProvidedKeypoints=False):
        if useProvidedKeypoints:
            raise ValueError("useProvidedKeypoints: call compute(image, keypoints) instead")
        rows, descriptors = self._core.detect_and_compute(image, mask, True)
        return _keypoints(rows), descriptors

    def clear(self):
        """Forgets the stream of images seen so far: the next image is judged as a new stream's first."""
        self._core.clear()

    @property
    def camera_moving(self):
        """Whether the last image detected on got the moving camera's selection."""
        return self._core.camera_moving

    def getParams(self):
        """Every parameter by its ROS name, as text the parameter table reads back."""
        return self._core.params()

    def getMaxFeatures(self):
        return int(self._core.params()["max_features"])

    def setMaxFeatures(self, nfeatures):
        self._set(max_features=nfeatures)

    def getScaleFactor(self):
        return float(self._core.params()["scale_factor"])

    def getNLevels(self):
        return int(self._core.params()["n_levels"])

    def getFastThreshold(self):
        return int(self._core.params()["fast_threshold"])

    def _set(self, **params):
        values = self._core.params()
        values.update(_values(params))
        self._core = _enhanced_orb.Orb(self._preset, values)

    def descriptorSize(self):
        return _enhanced_orb.DESCRIPTOR_BYTES

    def descriptorType(self):
        return cv2.CV_8U

    def defaultNorm(self):
        return cv2.NORM_HAMMING

    def getDefaultName(self):
        return "Feature2D.EnhancedORB"

    def empty(self):
        return False

    def __repr__(self):
        return "<enhanced_orb.ORB preset=%r max_features=%d>" % (self._preset, self.getMaxFeatures())


def ORB_create(preset="default", **params):
    """enhanced_orb's ORB: a preset by name, then parameters by name (see params()), or cv2's."""
    return ORB(preset, **params)


def enhance(image, preset="default", **params):
    """The enhanced 8-bit gray image and its status (lambda, mean_gray, poor_quality, inverted)."""
    return _enhanced_orb.enhance(image, preset, _values(params))


def params():
    """The parameter table: one dict per parameter (name, type, range, default, meaning)."""
    return _enhanced_orb.param_table()


def presets():
    """The presets ORB_create and enhance take by name."""
    return _enhanced_orb.preset_names()
