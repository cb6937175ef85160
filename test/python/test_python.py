"""The Python module enhanced_orb: the same results as the C++ enhanced_orb::ORB, cv2.ORB's interface,
and a Python exception for every bad input.

Run by scripts/test.sh (after `source devel/setup.bash`): python3 -m pytest test/python. The EuRoC
excerpts are read from ../shared (ENHANCED_ORB_EUROC_DIR, ENHANCED_ORB_MOVING_DIR override); the
C++ side is python_test_reference (ENHANCED_ORB_DUMP_TOOL, default devel/lib/enhanced_orb/python_test_reference).
"""
import os
import pathlib
import subprocess
import sys
import textwrap

import cv2
import numpy as np
import pytest

import enhanced_orb

ROOT = pathlib.Path(__file__).resolve().parents[2]
STATIC = pathlib.Path(os.environ.get("ENHANCED_ORB_EUROC_DIR", ROOT / "../shared/data/euroc/V1_01_easy_micro"))
MOVING = pathlib.Path(os.environ.get("ENHANCED_ORB_MOVING_DIR", ROOT / "../shared/data/euroc/MH_01_easy_moving"))
DUMP = pathlib.Path(os.environ.get("ENHANCED_ORB_DUMP_TOOL", ROOT / "devel/lib/enhanced_orb/python_test_reference"))


def frames(sequence, count):
    """The first `count` cam0 frames of a EuRoC folder; skips (or fails under
    ENHANCED_ORB_REQUIRE_DATA) when the data is not there."""
    found = sorted((sequence / "mav0/cam0/data").glob("*.png"))[:count]
    if len(found) < count:
        message = "fewer than %d EuRoC frames under %s" % (count, sequence)
        if os.environ.get("ENHANCED_ORB_REQUIRE_DATA"):
            pytest.fail(message)
        pytest.skip(message)
    return found


def gray(path):
    return cv2.imread(str(path), cv2.IMREAD_GRAYSCALE)


def rows(keypoints):
    return np.array([(k.pt[0], k.pt[1], k.size, k.angle, k.response, k.octave, k.class_id) for k in keypoints],
                    np.float64).reshape(-1, 7)


@pytest.mark.parametrize("preset,sequence,count,nfeatures", [
    ("default", MOVING, 12, 1000),   # judged moving from the second frame on: both selections
    ("default", STATIC, 6, 1000),    # a still camera
    ("paper", STATIC, 2, 0),         # every corner
    ("baseline", STATIC, 2, 500),
])
def test_same_keypoints_and_descriptors_as_the_cpp_adapter(tmp_path, preset, sequence, count, nfeatures):
    paths = frames(sequence, count)
    out = tmp_path / "cpp.yml"
    subprocess.run([str(DUMP), str(out), preset, str(nfeatures)] + [str(p) for p in paths], check=True)
    cpp = cv2.FileStorage(str(out), cv2.FILE_STORAGE_READ)
    orb = enhanced_orb.ORB_create(preset, nfeatures=nfeatures)
    moving = []
    for i, path in enumerate(paths):
        keypoints, descriptors = orb.detectAndCompute(gray(path), None)
        expected_rows = cpp.getNode("kp_%d" % i).mat()
        expected_desc = cpp.getNode("desc_%d" % i).mat()
        assert len(keypoints) > 0
        np.testing.assert_array_equal(rows(keypoints), expected_rows)
        np.testing.assert_array_equal(descriptors, expected_desc)
        assert orb.camera_moving == bool(cpp.getNode("moving_%d" % i).real())
        moving.append(orb.camera_moving)
    if sequence == MOVING and preset == "default":
        assert moving[0] is False and any(moving), "the moving excerpt should be judged moving after its first frame"
    if sequence == STATIC:
        assert not any(moving)


def test_outputs_are_what_cv2_gives():
    image = gray(frames(STATIC, 1)[0])
    orb = enhanced_orb.ORB_create(nfeatures=500)
    keypoints, descriptors = orb.detectAndCompute(image, None)
    assert isinstance(keypoints, tuple) and all(isinstance(k, cv2.KeyPoint) for k in keypoints)
    assert descriptors.dtype == np.uint8 and descriptors.shape == (len(keypoints), 32)
    assert 0 < len(keypoints) <= 500
    assert (orb.descriptorSize(), orb.descriptorType(), orb.defaultNorm()) == (32, cv2.CV_8U, cv2.NORM_HAMMING)
    drawn = cv2.drawKeypoints(image, keypoints, None)
    assert drawn.shape == image.shape + (3,)
    colour = cv2.cvtColor(image, cv2.COLOR_GRAY2BGR)
    k_colour, d_colour = enhanced_orb.ORB_create(nfeatures=500).detectAndCompute(colour, None)
    np.testing.assert_array_equal(rows(k_colour), rows(keypoints))
    np.testing.assert_array_equal(d_colour, descriptors)


def test_detect_then_compute_equals_detect_and_compute():
    image = gray(frames(STATIC, 1)[0])
    keypoints, descriptors = enhanced_orb.ORB_create().detectAndCompute(image, None)
    orb = enhanced_orb.ORB_create()
    detected = orb.detect(image)
    described, computed = orb.compute(image, detected)
    np.testing.assert_array_equal(rows(detected), rows(keypoints))
    np.testing.assert_array_equal(rows(described), rows(keypoints))
    np.testing.assert_array_equal(computed, descriptors)


def test_no_keypoint_where_the_mask_is_zero():
    image = gray(frames(STATIC, 1)[0])
    mask = np.zeros_like(image)
    mask[:, : image.shape[1] // 2] = 255
    keypoints, descriptors = enhanced_orb.ORB_create().detectAndCompute(image, mask)
    assert len(keypoints) > 100 and descriptors.shape[0] == len(keypoints)
    assert all(k.pt[0] < image.shape[1] // 2 for k in keypoints)
    none, nothing = enhanced_orb.ORB_create().detectAndCompute(image, np.zeros_like(image))
    assert none == () and nothing is None


def test_a_view_is_read_in_place_and_a_slice_as_its_pixels():
    image = gray(frames(STATIC, 1)[0])
    view = image[40:400, 100:700]
    k_view, d_view = enhanced_orb.ORB_create().detectAndCompute(view, None)
    k_copy, d_copy = enhanced_orb.ORB_create().detectAndCompute(view.copy(), None)
    np.testing.assert_array_equal(rows(k_view), rows(k_copy))
    np.testing.assert_array_equal(d_view, d_copy)


def test_clear_starts_a_new_stream():
    paths = frames(MOVING, 4)
    orb = enhanced_orb.ORB_create()
    for path in paths:
        orb.detect(gray(path))
    assert orb.camera_moving
    orb.clear()
    orb.detect(gray(paths[0]))
    assert not orb.camera_moving
    still = enhanced_orb.ORB_create(camera_motion="still")
    for path in paths:
        still.detect(gray(path))
        assert not still.camera_moving


CV2_SCRIPT = textwrap.dedent("""
    import sys
    import cv2
    import numpy as np

    a = cv2.imread(sys.argv[1], cv2.IMREAD_GRAYSCALE)
    b = cv2.imread(sys.argv[2], cv2.IMREAD_GRAYSCALE)
    orb = cv2.ORB_create(nfeatures=1000, scaleFactor=1.2, nlevels=8, edgeThreshold=31)
    ka, da = orb.detectAndCompute(a, None)
    kb, db = orb.detectAndCompute(b, None)
    matches = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).match(da, db)
    pa = np.float32([ka[m.queryIdx].pt for m in matches])
    pb = np.float32([kb[m.trainIdx].pt for m in matches])
    _, inliers = cv2.findHomography(pa, pb, cv2.RANSAC, 3.0)
    cv2.drawMatches(a, ka, b, kb, matches[:50], None)
    print(len(ka), len(matches), int(inliers.sum()))
""")


def test_a_cv2_matching_script_runs_with_only_the_create_line_changed(tmp_path):
    a, b = frames(STATIC, 2)
    # The one line changed: the import rides on it.
    ours = CV2_SCRIPT.replace("orb = cv2.ORB_create(", "import enhanced_orb; orb = enhanced_orb.ORB_create(")
    assert ours != CV2_SCRIPT
    counts = {}
    for name, text in (("cv2", CV2_SCRIPT), ("enhanced_orb", ours)):
        script = tmp_path / ("match_with_%s.py" % name)
        script.write_text(text)
        out = subprocess.run([sys.executable, str(script), str(a), str(b)], check=True, capture_output=True, text=True)
        counts[name] = [int(v) for v in out.stdout.split()]
    keypoints, matches, inliers = counts["enhanced_orb"]
    assert keypoints == 1000 and matches > 300 and inliers > matches // 2


def test_enhance_gives_the_image_and_its_status():
    image = gray(frames(STATIC, 1)[0])
    dark = (image // 8).astype(np.uint8)
    enhanced, status = enhanced_orb.enhance(dark)
    assert enhanced.dtype == np.uint8 and enhanced.shape == dark.shape
    assert set(status) == {"lambda", "mean_gray", "poor_quality", "inverted"}
    assert status["mean_gray"] == pytest.approx(dark.mean())
    assert enhanced.mean() > 2 * dark.mean()
    again, _ = enhanced_orb.enhance(cv2.cvtColor(dark, cv2.COLOR_GRAY2BGR))
    np.testing.assert_array_equal(again, enhanced)
    plain, _ = enhanced_orb.enhance(dark, tone_curve="stretch", tau=0.05)
    assert not np.array_equal(plain, enhanced)


def test_parameters_by_name_from_the_one_table():
    table = {row["name"]: row for row in enhanced_orb.params()}
    assert table["alpha"]["range"] == (0.0, 1.0) and table["alpha"]["default"] == "0.5"
    assert table["max_features"]["type"] == "int"
    assert {"default", "paper", "motion", "stretch", "baseline"} <= set(enhanced_orb.presets())
    orb = enhanced_orb.ORB_create("paper", nfeatures=300, scaleFactor=1.3, nlevels=6, fastThreshold=15, alpha=0.3)
    p = orb.getParams()
    assert (p["max_features"], p["n_levels"], p["fast_threshold"]) == ("300", "6", "15")
    assert float(p["scale_factor"]) == pytest.approx(1.3) and float(p["alpha"]) == pytest.approx(0.3)
    assert orb.getMaxFeatures() == 300
    orb.setMaxFeatures(200)
    assert orb.getMaxFeatures() == 200 and orb.getNLevels() == 6
    assert float(enhanced_orb.ORB_create(enhance=False).getParams()["alpha"]) == 0.5


@pytest.mark.parametrize("kwargs,named", [
    ({"alpha": 1.5}, "alpha"),
    ({"nfeatures": -1}, "max_features"),
    ({"max_features": 1.5}, "max_features"),
    ({"tone_curve": "sepia"}, "tone_curve"),
    ({"enhance": "maybe"}, "enhance"),
    ({"no_such_parameter": 1}, "no_such_parameter"),
    ({"alpha": [0.5]}, "alpha"),
    ({"edgeThreshold": 19}, "edgeThreshold"),
    ({"WTA_K": 3}, "WTA_K"),
    ({"nfeatures": 100, "max_features": 200}, "max_features"),
])
def test_a_bad_parameter_is_a_value_error_naming_it(kwargs, named):
    with pytest.raises(ValueError, match=named):
        enhanced_orb.ORB_create(**kwargs)


@pytest.mark.parametrize("kwargs,named", [({"alpha": 1.5}, "alpha"), ({"blur_ksize": 4}, "blur_ksize"),
                                          ({"tone_curve": 3}, "tone_curve"), ({"beta": None}, "beta")])
def test_enhance_checks_its_parameters_as_orb_create(kwargs, named):
    with pytest.raises(ValueError, match=named):
        enhanced_orb.enhance(np.zeros((64, 64), np.uint8), **kwargs)


def test_an_unknown_preset_is_a_value_error():
    with pytest.raises(ValueError, match="preset"):
        enhanced_orb.ORB_create("sharpest")


BAD_IMAGES = [
    (np.zeros((64, 64), np.float32), TypeError, "uint8"),
    (np.zeros((64, 64), np.uint16), TypeError, "uint8"),
    (np.zeros((64, 64, 2), np.uint8), ValueError, "shape"),
    (np.zeros((64, 64, 5), np.uint8), ValueError, "shape"),
    (np.zeros((2, 64, 64, 1), np.uint8), ValueError, "shape"),
    (np.zeros((64,), np.uint8), ValueError, "shape"),
    (np.zeros((0, 64), np.uint8), ValueError, "empty"),
    (np.zeros((128, 128), np.uint8)[:, ::2], ValueError, "contiguous"),
    (np.zeros((128, 64), np.uint8).T, ValueError, "contiguous"),
    (np.zeros((64, 64), np.uint8)[::-1], ValueError, "contiguous"),
    (np.zeros((64, 64, 3), np.uint8)[:, :, ::-1], ValueError, "contiguous"),
    (np.zeros((6000, 6000), np.uint8), ValueError, "pixels"),
    ("image.png", TypeError, ""),
    (None, TypeError, ""),
]


@pytest.mark.parametrize("image,error,says", BAD_IMAGES)
def test_a_bad_image_is_a_python_exception(image, error, says):
    orb = enhanced_orb.ORB_create()
    for call in (lambda: orb.detectAndCompute(image, None), lambda: orb.detect(image),
                 lambda: orb.compute(image, ()), lambda: enhanced_orb.enhance(image)):
        with pytest.raises(error, match=says):
            call()


@pytest.mark.parametrize("mask", [
    np.zeros((32, 64), np.uint8),
    np.zeros((64, 64), np.float32),
    np.zeros((64, 64, 3), np.uint8),
    np.zeros((128, 128), np.uint8)[::2, ::2],
    "mask",
])
def test_a_bad_mask_is_a_python_exception(mask):
    with pytest.raises((ValueError, TypeError), match="mask"):
        enhanced_orb.ORB_create().detectAndCompute(np.zeros((64, 64), np.uint8), mask)


def test_odd_but_valid_images_give_a_defined_result():
    orb = enhanced_orb.ORB_create()
    for image in (np.zeros((64, 64), np.uint8), np.full((480, 640), 255, np.uint8), np.zeros((1, 1), np.uint8),
                  np.zeros((7, 3000), np.uint8), np.random.default_rng(1).integers(0, 256, (64, 64, 4), np.uint8)):
        keypoints, descriptors = orb.detectAndCompute(image, None)
        assert (descriptors is None) == (len(keypoints) == 0)
    with pytest.raises(TypeError, match="KeyPoint"):
        orb.compute(np.zeros((64, 64), np.uint8), [(1.0, 2.0)])
    described, descriptors = orb.compute(np.zeros((64, 64), np.uint8), [cv2.KeyPoint(1, 1, 31)])
    assert described == () and descriptors is None


def test_the_lighting_example_runs_and_finds_more_correct_matches_than_cv2(capsys):
    folder = ROOT / "../shared/data/lighting/exposure_memorial"
    if not (folder / "pairs.csv").exists():
        if os.environ.get("ENHANCED_ORB_REQUIRE_DATA"):
            pytest.fail("no lighting set at %s" % folder)
        pytest.skip("no lighting set at %s" % folder)
    sys.path.insert(0, str(ROOT / "scripts/examples"))
    try:
        import lighting_pairs
    finally:
        sys.path.pop(0)
    lighting_pairs.main(folder, 1000)
    total = capsys.readouterr().out.strip().splitlines()[-1].split()
    ours, theirs = int(total[2]), int(total[4])
    assert total[1] == "enhanced_orb" and total[3] == "cv2.ORB"
    assert ours > theirs > 0
