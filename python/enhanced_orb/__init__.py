"""enhanced_orb from Python: ORB features that survive bad light, as a drop-in for cv2.ORB.

    import enhanced_orb
    orb = enhanced_orb.ORB_create(nfeatures=1000)      # was cv2.ORB_create(nfeatures=1000)
    keypoints, descriptors = orb.detectAndCompute(image, None)

The package also holds the generated ROS messages (enhanced_orb.msg).
"""
from enhanced_orb.features import ORB, ORB_create, enhance, params, presets

__all__ = ["ORB", "ORB_create", "enhance", "params", "presets"]
