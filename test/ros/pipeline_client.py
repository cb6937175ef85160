"""What the rostests that feed the pipeline hand-made frames share: the frames and the client that
sends them to /cam0/image_raw and watches /cam0/keypoints."""
import threading

import numpy as np
import rospy
from sensor_msgs.msg import Image

from enhanced_orb.msg import KeypointArray

W, H = 160, 120
# How long a test waits for an output that must come: long enough that a loaded machine alone cannot
# fail it (a frame takes milliseconds), so a failure means the output never came.
OUTPUT_S = 60.0


def scene(w=W, h=H, seed=3):
    """A gray scene of random rectangles: corners at every scale."""
    rng = np.random.RandomState(seed)
    gray = np.full((h, w), 100, np.uint8)
    for _ in range(40):
        x, y = rng.randint(0, max(w - 10, 1)), rng.randint(0, max(h - 10, 1))
        gray[y:y + rng.randint(5, 30), x:x + rng.randint(5, 30)] = rng.randint(0, 256)
    return gray


def image(encoding, pixels, width=None, height=None, step=None, data=None):
    """An Image of `pixels`; width, height, step and data may be overridden to make it malformed."""
    pixels = np.ascontiguousarray(pixels)
    msg = Image()
    msg.encoding = encoding
    msg.height = pixels.shape[0] if height is None else height
    msg.width = (pixels.shape[1] if pixels.ndim > 1 else 0) if width is None else width
    raw = pixels.tobytes()
    msg.step = (len(raw) // msg.height if msg.height else 0) if step is None else step
    msg.data = raw if data is None else data
    return msg


class PipelineClient:
    def __init__(self):
        self.lock = threading.Lock()
        self.stamps = set()
        self.next_stamp = 1
        rospy.Subscriber("/cam0/keypoints", KeypointArray, self.on_keypoints, queue_size=50)
        self.pub = rospy.Publisher("/cam0/image_raw", Image, queue_size=10)

    def on_keypoints(self, msg):
        with self.lock:
            self.stamps.add(msg.header.stamp)

    def connected(self, seconds=OUTPUT_S):
        """Whether the whole chain is connected: the pipeline subscribed its input (it does once its
        outputs have subscribers) and a frame has come through to keypoints. The chain's inner
        connections are made in their own time after the input's: a frame sent before they are can
        be lost, so frames are sent, a second apart, until one arrives."""
        deadline = rospy.Time.now() + rospy.Duration(seconds)
        while self.pub.get_num_connections() == 0 and rospy.Time.now() < deadline:
            rospy.sleep(0.1)
        while rospy.Time.now() < deadline:
            if self.processed(self.send(image("mono8", scene())), 1.0):
                return True
        return False

    def send(self, msg):
        """Publishes `msg` with a stamp of its own; returns the stamp."""
        msg.header.stamp = rospy.Time(self.next_stamp)
        msg.header.frame_id = "cam0"
        self.next_stamp += 1
        self.pub.publish(msg)
        return msg.header.stamp

    def wait_until(self, condition, seconds):
        """Whether `condition()` (called under the lock) holds within `seconds`."""
        deadline = rospy.Time.now() + rospy.Duration(seconds)
        while rospy.Time.now() < deadline:
            with self.lock:
                if condition():
                    return True
            rospy.sleep(0.05)
        return False

    def processed(self, stamp, seconds):
        return self.wait_until(lambda: stamp in self.stamps, seconds)
