"""Vision: a stereo frame in, a `Percept` (cognition's contract) out; plus the debug overlay.

Each vision tick (10 Hz of simulated time by default) the episode loop does::

    if capture.due(t):
        frame = capture.grab(world.data)                 # ~2 renders
        percept = vision.perceive(frame, robot_holding=proprio.holding, robot_tcp=proprio.tcp)
        percept.robot = RobotPercept(...)                # filled by the robot side

Objects not found (or only partly visible, or in a dropped frame) come out ``seen=False``;
nothing is carried over from an earlier frame.  An object the robot's own proprioception says
it holds is reported held: at the gripper's TCP (from the robot's kinematics), zone "RWS",
with its state from the pixels when it can be seen, else ``seen=False``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import cv2
import numpy as np

from assistbot import catalogue
from assistbot.cognition.percept import STANDING_Z, HandPercept, ObjectPercept, Percept, away_from_hand
from assistbot.resources import LIBRARY_SCENES, TEMPLATES
from assistbot.task import OBJECT_STATES
from assistbot.vision import library
from assistbot.vision.capture import StereoFrame
from assistbot.vision.detect import HELD_DIST, MAX_TILT, Detections, Detector, axis_distance
from assistbot.world.layout import HANDOVER_ZONE_X, zone_of

HELD_OUT_Z = 0.14           # m above the table: a hand in the hand-over zone this high is raised toward the robot
IN_HAND_XY = 0.10           # a grasping hand this close (m, horizontally) to an object holds it ...
IN_HAND_END_XY = IN_HAND_XY + 0.05      # ... measured from the hand's end, which may lie past the object's axis
HIDDEN_FINGERS = 0.10       # m of a hand that the robot's arm can hide beyond the end seen (the fingers)
AT_TOP = 0.02               # m: a hand's end this far below an object's top, or higher, holds it from above
HOLDING = ("grasp_ag", "grasp_sg", "pour", "drink", "remove_stopper")   # postures of a hand with something in it
OFFERING = ("grasp_ag", "grasp_sg", "open_palm_request")   # postures of a hand that may be held out to the robot
#: the postures that use one object, and that object
USES = {"remove_stopper": "bottle", "pour": "bottle", "drink": "glass"}
STOPPER_SEEN = 0.04         # red touching the bottle, as a share of a stopper's expected area: closed
HAND_AT_TOP = 0.12          # m: a hand this close to the bottle's top may hide the stopper
LOW_CONFIDENCE = 0.3        # confidence of a state the pixels cannot show (stopper covered)
DRINK_Z = 0.25              # m: a glass lifted this high is at the face
HELD_TOP_XY = 0.06          # m: the top of an object in the robot's hand, horizontally from the TCP
HELD_TOP_Z = (0.02, 0.16)   # m: ... and above it (side grasps hold 5-8 cm above the base)


def _in_robot_hand(d, tcp) -> bool:
    """The robot's fingers hide an object's middle, so its silhouette is never whole: the object in
    the robot's own hand counts as seen when its top shows, upright, just above the hand (where the
    gripper's kinematics put it); its state then comes from the pixels above the fingers."""
    if tcp is None or d.top is None or not d.inside or d.tilt >= MAX_TILT:
        return False
    above = d.top - np.asarray(tcp, float)
    return bool(np.hypot(above[0], above[1]) < HELD_TOP_XY and HELD_TOP_Z[0] < above[2] < HELD_TOP_Z[1])


def _in_a_hand(d, hand) -> bool:
    """The person's hand at the object: one she turns or lays down in her hand is not one that fell."""
    return bool(hand.visible and hand.position is not None and d.position is not None
                and _norm(np.asarray(hand.position, float)[:2] - d.position[:2]) < IN_HAND_XY)


def _seen_away_from(d, tcp) -> bool:
    """The object the robot believes in its hand is seen, placed, away from the hand (`away_from_hand`):
    the grasp closed on something else (the person's fingers), or the object stayed behind. The percept
    then says where it is, not where the hand is."""
    if tcp is None or not d.visible or d.position is None:
        return False
    return away_from_hand(d.position, tcp)


def _norm(v: np.ndarray) -> float:
    """np.linalg.norm of a vector, as it computes it (sqrt of the vector's dot with itself)."""
    return math.sqrt(v.dot(v))


def _unseen(name: str) -> ObjectPercept:
    """Not seen this frame (state/position are placeholders that cognition ignores when seen=False)."""
    return ObjectPercept(name, "HWS", OBJECT_STATES[name][0], (0.0, 0.0, 0.0), 0.0, False)


@dataclass
class Timing:
    """Of the last frame: rendering (wall), processing (wall) and processing CPU time of this process
    (the CPU time is what a loaded, shared machine does not inflate)."""

    render_ms: float = 0.0
    process_ms: float = 0.0
    process_cpu_ms: float = 0.0


class Vision:
    """Segmentation + template matching + triangulation -> Percept (see module docstring)."""

    def __init__(self, root=None, library_data: tuple[dict, dict] | None = None) -> None:
        """root: the template library folder (default assets/templates); library_data: (classifiers,
        calibration) in memory instead (experiments)."""
        self.classifiers, self.calibration = library_data or library.load(root)
        self.hand_offset = {k: np.asarray(v, float) for k, v in self.calibration.get("hand_offset", {}).items()}
        self.detector = Detector(self.calibration)
        self.last: Detections | None = None
        self.timing = Timing()

    def perceive(self, frame: StereoFrame, robot_holding: str | None = None, robot_tcp=None) -> Percept:
        t0, c0 = time.perf_counter(), time.process_time()
        p = Percept(t=frame.t)
        if frame.dropped or frame.left is None:
            for o in catalogue.TASK_OBJECTS:
                p.objects[o] = _unseen(o)
            p.hand = HandPercept(seen=False, confidence=0.0)
            self.last = None
            return p
        det = self.detector(frame.left, frame.right, frame.cams, frame.body)
        self.last = det
        for name in catalogue.TASK_OBJECTS:
            d = det.objects[name]
            if not d.visible and not (robot_holding == name and _in_robot_hand(d, robot_tcp)):
                op = _unseen(name)
            else:
                state, conf, state_seen = self._state(name, d, det.hand)
                pos = tuple(round(float(v), 4) for v in d.position)
                op = ObjectPercept(name, zone_of(pos[0]), state, pos, round(conf, 3), True, state_seen)
            if d.lying and robot_holding != name and not _in_a_hand(d, det.hand):
                op = _unseen(name)      # fallen over: not standing anywhere the task can use it
                op.lying, op.position = True, tuple(round(float(v), 4) for v in d.position)
            if robot_holding == name and not _seen_away_from(d, robot_tcp):
                op.zone = "RWS"
                if robot_tcp is not None:
                    op.position = tuple(float(v) for v in np.asarray(robot_tcp, float))
            p.objects[name] = op
        p.hand = self._hand(det, p)
        self.timing.process_ms = (time.perf_counter() - t0) * 1000.0
        self.timing.process_cpu_ms = (time.process_time() - c0) * 1000.0
        self.timing.render_ms = frame.render_ms
        return p

    def _state(self, name: str, d, hand) -> tuple[str, float, bool]:
        """State, confidence, and whether the state is in view.  Bottle: red touching it in either
        camera is the stopper (closed); no red with the hand at the bottle's top (stereo: within
        `HAND_AT_TOP` m) means the stopper may be hidden in the hand: the state then comes with a low
        confidence, and as not in view if no camera shows red; else open."""
        if name != "bottle":
            # the robot's own arm across its image (the hand reaching past it, pouring over it) hides what tells
            # its state, its opening or the liquid in it: the reading is then a guess
            state, conf, _ = self.classifiers[name].classify(d.crop, d.feat)
            return state, conf, not d.covered
        hand_at_top = bool(hand.visible and _norm(hand.position - (d.position + [0, 0, 0.19])) < HAND_AT_TOP)
        # lifted in the person's hand (as `Detector._held` tells it): a grip from above covers the stopper
        # wherever vision puts the hand
        hand_at_top |= bool(hand.visible and not d.on_table and axis_distance(d, hand.position) < HELD_DIST)
        both = min(d.stopper) >= STOPPER_SEEN
        one = max(d.stopper) >= STOPPER_SEEN
        if both:
            return "closed", 0.95, True
        if one and hand_at_top:
            return "closed", 0.7, True     # the stopper shows beside the hand in one camera
        if not (one or hand_at_top):
            return "open", 0.9, True
        # the classifier only where the stopper's pixels do not decide, with a low confidence; with no
        # red in either camera and the hand over the top the stopper cannot be seen at all: the state
        # is then a guess (how often the library's scenes show such bottles closed), and says so
        state, conf, _ = self.classifiers[name].classify(d.crop, d.feat)
        return state, min(conf, LOW_CONFIDENCE), one

    def _looks_held_out(self, h) -> bool:
        """The library's held-out classifier (if the library has one) reads the hand as held out toward
        the robot: a person who holds out short of the hand-over zone (short arms, a seat farther back,
        a habit of holding things near) still holds out, and the arm and hand show it."""
        clf = self.classifiers.get(library.HELD_OUT)
        if clf is None:
            return False
        return clf.classify(h.crop, h.geo)[0] == "held_out"

    def _hand(self, det: Detections, p: Percept) -> HandPercept:
        h = det.hand
        glass = det.objects["glass"]
        if not h.visible:
            # the glass lifted to the face: the drinking hand merges with the face in the image
            if glass.position is not None and glass.position[2] > DRINK_Z and glass.extent > 0.3:
                pos = tuple(round(float(v), 4) for v in glass.position + np.array([0, 0, 0.05]))
                return HandPercept(posture="drink", position=pos, object_in_hand="glass", directed_at="glass", confidence=0.6)
            return HandPercept(seen=False, confidence=0.0)
        hand = self.classifiers["hand"]
        pr = hand.probabilities(h.crop, h.geo)[0]
        c = int(pr.argmax())
        lifted_near = [o for o in p.objects.values()
                       if o.seen and o.position[2] > STANDING_Z and _norm(np.asarray(o.position[:2]) - h.position[:2]) < IN_HAND_END_XY]
        if hand.classes[c] == "pointing" and h.at_glass:
            # a pointing finger stays clear of what it points at; a hand whose end touches the glass in
            # both images is at it, and the glass hides the hand (turning it, say): the forearm's end
            # then looks like a finger.  The likeliest other posture, with its (low) probability
            pr[c] = 0.0
            c = int(pr.argmax())
        o = min(lifted_near, key=lambda o: _norm(np.asarray(o.position[:2]) - h.position[:2])) if lifted_near else None
        if o is not None and (hand.classes[c] not in HOLDING or USES.get(hand.classes[c], o.type) != o.type):
            # an object lifted off the table right at the hand is in it, whatever the hand's outline looks
            # like (the robot's open hand next to it, asking for it, hides or extends the skin, and the
            # library's scenes have no robot hand there): from above if the hand's end is over its top.
            # A posture that uses another object (pulling a stopper off the glass held out) is a misreading
            above = h.position[2] > o.position[2] + catalogue.height(o.type) - AT_TOP
            c = hand.classes.index("grasp_ag" if above else "grasp_sg")
            pr[c] = max(float(pr[c]), o.confidence)   # as sure as the object is seen in it
        posture, conf = hand.classes[c], float(pr[c])
        X = h.position + self.hand_offset.get(posture, np.zeros(3))
        seen_objs = {n: np.array(o.position) for n, o in p.objects.items() if o.seen}
        hp = HandPercept(posture=posture, position=tuple(round(float(v), 4) for v in X), confidence=round(conf, 3),
                         end=tuple(round(float(v), 4) for v in h.position), end_hidden=bool(h.end_on_robot))
        target = USES.get(posture)
        if target:
            hp.directed_at = target
            if posture != "remove_stopper":
                hp.object_in_hand = target
        elif h.at_glass and not p.objects["glass"].seen and posture in ("reach", "grasp_ag", "grasp_sg"):
            # at a glass too tilted or covered to place: that glass, not the nearest object placed
            hp.directed_at = "glass"
            if posture != "reach":
                hp.object_in_hand = "glass"
        elif seen_objs:
            near = min(seen_objs, key=lambda n: _norm(seen_objs[n][:2] - X[:2]))
            if posture in ("grasp_ag", "grasp_sg") and _norm(seen_objs[near][:2] - X[:2]) < IN_HAND_END_XY:
                hp.object_in_hand = near
            elif posture in ("grasp_ag", "grasp_sg") and o is not None:
                # lifted right at the hand's end, it is in the hand: a hand holding from above hides its own
                # fingers behind what it holds, so its end is seen back at the wrist (a long hand's palm
                # then lies a hand's length behind the object)
                hp.object_in_hand = near = o.type
            if posture in ("reach", "grasp_ag", "grasp_sg"):
                hp.directed_at = near
            if posture == "pointing":
                d = X[:2] - h.proximal[:2]
                d = d / max(1e-6, float(np.linalg.norm(d)))

                def off(n):
                    v = seen_objs[n][:2] - X[:2]
                    along = float(v @ d)
                    return abs(float(v[0] * d[1] - v[1] * d[0])) if along > -0.05 else 9.0
                hp.pointed_at = min(seen_objs, key=off)
        # how far toward the robot the hand reaches: its end as seen; where the robot's arm hides the rest
        # of it (its fingers, next to the robot's hand reaching for what they hold), up to a hand's fingers
        # farther; and at least as far as the object in it
        reach_x = X[0] + (HIDDEN_FINGERS if h.end_on_robot else 0.0)
        held = p.objects.get(hp.object_in_hand) if hp.object_in_hand else None
        if held is not None and held.seen:   # what it holds, placed by its own silhouette: the glass held from
            reach_x = max(reach_x, held.position[0])   # above hides the fingers, and the end seen is the wrist
        # raised toward the robot, and either in the zone or held as people hold things out (a hand resting
        # on the table, read as an open palm, is neither)
        raised = posture in OFFERING and X[2] > HELD_OUT_Z
        hp.held_out = bool(raised and (reach_x > HANDOVER_ZONE_X[0] or self._looks_held_out(h)))
        if hp.object_in_hand and hp.held_out and not p.objects[hp.object_in_hand].seen:
            # held out but not placed (lifted objects are hard to place): in the hand's zone; one that is
            # seen keeps its own, which the hand's end (fingers around it, past the middle line) is not
            p.objects[hp.object_in_hand].zone = "HWS" if X[0] < 0 else "RWS"
        return hp

    # ------------------------------------------------------------------ debug view
    def overlay(self, frame: StereoFrame, percept: Percept, scale: int = 2) -> np.ndarray:
        """The left image with segmentation masks tinted, blobs boxed and the percept written on it (RGB)."""
        if frame.left is None:
            img = np.zeros((frame.cams[0].height, frame.cams[0].width, 3), np.uint8)
            img = cv2.resize(img, None, fx=scale, fy=scale)
            cv2.putText(img, f"t={frame.t:.1f}s frame dropped: nothing seen", (8, 20), cv2.FONT_HERSHEY_SIMPLEX, 0.5, (255, 255, 255), 1)
            return img
        img = frame.left.copy()
        tint = np.array([(0, 0, 0), (0, 255, 0), (255, 0, 0), (0, 255, 255), (200, 0, 255), (255, 160, 0), (255, 255, 0)], np.float32)
        if self.last is not None and self.last.labels is not None:
            lab = cv2.resize(self.last.labels[0], (img.shape[1], img.shape[0]), interpolation=cv2.INTER_NEAREST)
            sel = lab > 0
            img[sel] = (0.5 * img[sel] + 0.5 * tint[lab[sel]]).astype(np.uint8)
        img = cv2.resize(img, None, fx=scale, fy=scale, interpolation=cv2.INTER_NEAREST)
        cam = frame.cams[0]
        font = cv2.FONT_HERSHEY_SIMPLEX
        for name, o in percept.objects.items():
            d = self.last.objects.get(name) if self.last else None
            if d is not None and d.blobs[0] is not None:
                x, y, w, h = d.blobs[0].bbox
                col = (255, 255, 255) if o.seen else (128, 128, 128)
                cv2.rectangle(img, (x * scale, y * scale), ((x + w) * scale, (y + h) * scale), col, 1)
                if d.crop is not None:
                    t = cv2.resize((np.clip(d.crop, 0, 1) * 255).astype(np.uint8), None, fx=scale, fy=scale)
                    t = t[:img.shape[0], :img.shape[1]]
                    th, tw = t.shape
                    yy, xx = max(0, y * scale - th - 2), min(img.shape[1] - tw, (x + w) * scale + 2)
                    img[yy:yy + th, xx:xx + tw] = t[..., None]
            if o.seen:
                uv = cam.project(np.array(o.position))[0]
                if np.all(np.isfinite(uv)):
                    u, v = int(uv[0] * scale), int(uv[1] * scale)
                    cv2.circle(img, (u, v), 3, (255, 0, 0), -1)
                    cv2.putText(img, f"{name} {o.state} {o.zone} {o.confidence:.2f}", (u - 40, v + 14), font, 0.4, (0, 0, 0), 1)
        hnd = percept.hand
        if hnd.seen:
            uv = cam.project(np.array(hnd.position))[0]
            if np.all(np.isfinite(uv)):
                u, v = int(uv[0] * scale), int(uv[1] * scale)
                cv2.drawMarker(img, (u, v), (255, 0, 255), cv2.MARKER_CROSS, 10, 2)
                rel = " ".join(f"{k}={getattr(hnd, k)}" for k in ("object_in_hand", "pointed_at") if getattr(hnd, k))
                text = f"hand {hnd.posture} {hnd.confidence:.2f}{' held out' if hnd.held_out else ''} {rel}"
                cv2.putText(img, text, (u - 60, max(12, v - 8)), font, 0.4, (0, 0, 0), 1)
        cv2.putText(img, f"t={frame.t:.1f}s vision {self.timing.process_ms:.1f} ms", (6, img.shape[0] - 8), font, 0.45, (255, 255, 255), 1)
        return img


# ---------------------------------------------------------------------------- building the library
#: the share of a population library's scenes that show the default person; the others show people of
#: the given population seeds, so that the templates know bodies, seats and habits beside his
LIBRARY_DEFAULT_SHARE = 0.3


def build_library(seed: int = 0, n_scenes: int = LIBRARY_SCENES, root=None, progress=None, partners=(),
                  default_share: float = LIBRARY_DEFAULT_SHARE) -> list:
    """Calibrate, render library scenes, and write prototypes + examples to assets/templates/.

    The scenes show the default person, or with ``partners`` (population seeds, e.g.
    `population.LIBRARY_SEEDS`) a ``1 - default_share`` of them people drawn from those, each built
    in the physics."""
    from assistbot.task import HAND_POSTURES
    from assistbot.vision.calibration import calibrate
    from assistbot.vision.capture import StereoCapture
    from assistbot.vision.scenes import POSE_TOLERANCE, SceneSampler, by_person, pose

    partners = tuple(partners)
    cal = calibrate(seed)
    sampler = SceneSampler(seed, "library", partners or None, default_share)
    specs = [sampler.sample(HAND_POSTURES[i % len(HAND_POSTURES)]) for i in range(n_scenes)]
    people = {s.partner for s in specs}

    def frames():
        done = 0
        for world, group in by_person(specs, seed):
            with StereoCapture(world.model) as cap:
                for spec in group:
                    lab = pose(world, spec)
                    done += 1
                    if progress:
                        progress(done, n_scenes)
                    if spec.partner is not None and lab.pose_miss > POSE_TOLERANCE:
                        # another body could not pose it (out of that person's reach): the labels would
                        # describe a hand that is not there. The default person's scenes are his own postures.
                        continue
                    yield cap.grab(world.data), lab

    clfs, cal = fit_library(cal, frames(), seed)
    meta = {"seed": seed, "scenes": n_scenes, "examples": {k: len(c.y) for k, c in clfs.items()}}
    if partners:
        meta.update(people=len(people), default_share=default_share, partners=[min(partners), max(partners)])
    return library.save(root or TEMPLATES, clfs, cal, meta)


#: feature weights (after the template scores) per kind: the stopper and liquid features decide the states
WEIGHTS = {"bottle": [3, 1, 1, 0.5, 0.5], "glass": [3, 1, 2, 0.5, 0.5],
           "hand": None, library.HELD_OUT: None}


def fit_library(cal: dict, frames, seed: int = 0) -> tuple[dict, dict]:
    """Classifiers (and the calibration with the hand offsets) from labelled (StereoFrame, Labels) pairs."""
    det = Detector(cal)
    data = {k: ([], [], []) for k in library.KINDS}
    held_out: list[str] = []
    offsets: dict[str, list[np.ndarray]] = {}
    for f, lab in frames:
        d = det(f.left, f.right, f.cams, f.body)
        for name in catalogue.TASK_OBJECTS:
            o = d.objects[name]
            if o.visible:
                data[name][0].append(o.crop)
                data[name][1].append(o.feat)
                data[name][2].append(lab.objects[name]["state"])
        if d.hand.visible:
            data["hand"][0].append(d.hand.crop)
            data["hand"][1].append(d.hand.geo)
            data["hand"][2].append(lab.posture)
            held_out.append(library.CLASSES[library.HELD_OUT][int(lab.held_out)])
            offsets.setdefault(lab.posture, []).append(np.array(lab.hand_position) - d.hand.position)
    data[library.HELD_OUT] = (data["hand"][0], data["hand"][1], held_out)    # the hand's examples, labelled held out or not
    clfs = {k: library.build_classifier(k, *v, seed=seed, weights=WEIGHTS[k]) for k, v in data.items()}
    cal = dict(cal)
    # the grasp site relative to the seen distal end of the hand, per posture (median, m)
    cal["hand_offset"] = {k: [round(float(x), 4) for x in np.median(v, axis=0)] for k, v in sorted(offsets.items())}
    return clfs, cal
