"""Vision: stereo head renders -> colour segmentation + template matching + triangulation -> Percept.

Parts (one idea per file):
  camera.py       pinhole models of the head cameras (K from fovy, pose from the head joints), triangulation
  capture.py      `StereoCapture`: both head cameras offscreen at a rate of simulated time, seeded dropout
  segment.py      calibrated HSV ranges compiled to an RGB look-up table; connected components per part mask
  calibration.py  `calibrate`: HSV ranges and static skin spots from labelled calibration renders
  detect.py       `Detector`: blobs -> stereo-matched objects and hand (arm root at the sleeve), 3-D positions,
                  visibility from the silhouette's extent, crops, features
  library.py      the template library (prototype PNGs, matchTemplate over a prototype mosaic) and the
                  classifiers (k-NN over template scores + features; hand postures: a small network)
  pipeline.py     `Vision.perceive(frame) -> Percept` (stopper rules, low confidence when the hand hides
                  it), `Vision.overlay`, `build_library`
  scenes.py       labelled scene posing for calibration, templates, tests and the benchmark

Frames: positions are table coordinates (m, origin at the table top centre, x toward the
robot, z up); an object's position is the centre of the base it stands on.
"""

from assistbot.vision.capture import CaptureConfig, StereoCapture, StereoFrame
from assistbot.vision.pipeline import Vision, build_library

__all__ = ["CaptureConfig", "StereoCapture", "StereoFrame", "Vision", "build_library"]
