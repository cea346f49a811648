"""A feature plugin written in Python: motion energy, where the frame changed since the last one.

It registers itself when imported or named in a configuration's `plugins:` list:

    build/attend run --set plugins=[examples/python/motion_energy.py] \
        --set 'features=[{name: colour_contrast}, {name: motion_energy, weight: 2, blur: 9}]'

or, from Python, `import motion_energy` before the pipeline is made (attend_example.py).
"""

import numpy as np

import attend


class MotionEnergy:
    """Absolute grey-level change since the previous frame, box-blurred."""

    # Options and their defaults: read from the feature's entry in the configuration, each
    # with its default's type (an unknown key or a wrong type is a configuration error).
    options = {"blur": 5}

    def __init__(self, blur):
        if blur < 1 or blur % 2 == 0:
            raise ValueError(f"blur must be odd and positive, not {blur}")
        self.blur = blur
        self.previous = None

    def begin_sequence(self, info):
        self.previous = None

    def compute(self, context):
        grey = context.left.astype(np.float32).mean(axis=2)
        change = np.zeros_like(grey) if self.previous is None else np.abs(grey - self.previous)
        # A frame's arrays are valid during compute() only: keep a copy (astype made one).
        self.previous = grey
        return box_blur(change, self.blur)


def box_blur(image, size):
    """The mean over size x size windows (edges replicated), by summed-area table."""
    pad = size // 2
    padded = np.pad(image, pad, mode="edge")
    table = np.pad(padded.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
    h, w = image.shape
    window = (table[size:size + h, size:size + w] - table[:h, size:size + w]
              - table[size:size + h, :w] + table[:h, :w])
    return window / float(size * size)


attend.register_feature("motion_energy", MotionEnergy)
