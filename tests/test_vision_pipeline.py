"""Vision: cameras from the model, dropped frames, held objects, the template command, accuracy on a seeded set."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from assistbot.cli import main
from assistbot.errors import UserError
from assistbot.scenario import load_scenario
from assistbot.vision import CaptureConfig, StereoCapture, Vision
from assistbot.vision.camera import CameraModel, triangulate
from assistbot.vision.evaluate import run as evaluate
from assistbot.vision.scenes import SceneSampler, pose
from assistbot.world import PAPER_ARRANGEMENTS, build_world

# Accuracy goals of issue 8 and the margin this test allows on its small set (60 frames, where one
# frame is ~1.7%).  Measured on this set: state 97.5%, posture 98.3%, median 0.8 cm, p95 1.8 cm
# (the 500-frame benchmark: state 99.4%, posture 95.6%, whose 95% interval is about +-2 points).
GOAL_OBJECT, GOAL_POSTURE, GOAL_MEDIAN_CM, GOAL_P95_CM = 0.98, 0.95, 2.0, 5.0
MARGIN_OBJECT, MARGIN_POSTURE, MARGIN_MEDIAN_CM, MARGIN_P95_CM = 0.04, 0.04, 0.0, 0.0

@pytest.fixture(scope="module")
def world():
    return build_world(PAPER_ARRANGEMENTS["fig3"], 0)


def test_cameras_come_from_the_model_and_the_head_joints(world):
    m, d = world.model, world.data
    d.qpos[m.jnt_qposadr[m.joint("robot_head_pan").id]] = 0.3
    import mujoco
    mujoco.mj_forward(m, d)
    L = CameraModel.from_data(m, d, "head_cam_left", 320, 240)
    R = CameraModel.from_data(m, d, "head_cam_right", 320, 240)
    assert np.isclose(np.linalg.norm(L.C - R.C), 0.12, atol=1e-6)
    assert np.isclose(L.K[1, 1], 120 / np.tan(np.radians(m.cam_fovy[m.camera("head_cam_left").id]) / 2))
    X = np.array([[-0.2, 0.1, 0.05], [0.15, -0.2, 0.0]])
    Y = triangulate(L, R, L.project(X), R.project(X))
    assert np.allclose(X, Y, atol=1e-9)
    world.reset()


def test_capture_rate_is_simulated_time(world):
    with StereoCapture(world.model, CaptureConfig(rate=10.0)) as cap:
        ticks = [t for t in np.arange(0, 1.0, 0.02) if cap.due(float(t))]
    assert len(ticks) == 10


def test_dropped_frame_is_not_seen(world):
    vision = Vision()
    with StereoCapture(world.model, CaptureConfig(dropout=1.0, seed=1)) as cap:
        f = cap.grab(world.data)
    p = vision.perceive(f)
    assert f.dropped and f.left is None
    assert not p.objects["bottle"].seen and not p.objects["glass"].seen and not p.hand.seen
    p.validate()


def test_object_in_the_robot_gripper_is_held_or_unseen_not_misplaced(world):
    spec = SceneSampler(5, "test").sample("none")
    spec.robot_holds = "glass"
    lab = pose(world, spec)
    tcp = world.site_pos("robot_tcp")
    tcp[2] -= 0.75
    vision = Vision()
    with StereoCapture(world.model) as cap:
        p = vision.perceive(cap.grab(world.data), robot_holding="glass", robot_tcp=tcp)
    g = p.objects["glass"]
    assert g.zone == "RWS"
    if g.seen:
        assert np.linalg.norm(np.array(g.position) - tcp) < 0.05
    assert lab.objects["glass"]["held_by"] == "robot"


@pytest.mark.parametrize("seed,name,dz", [(1, "bottle", -0.06), (0, "glass", 0.0), (3, "bottle", 0.08), (4, "glass", -0.06)])
def test_object_behind_the_robot_arm_is_unseen_or_in_place_not_misplaced(seed, name, dz):
    """The robot's gripper put (by IK) on the line from the left camera to the object, in front of
    its middle, base (dz < 0) or top: the object is reported unseen or within 3 cm of where it
    stands.  (1, bottle, -0.06) hides the base in both cameras: before vision knew where its own arm
    is, the arm's edge under the bottle was placed on the table and the bottle reported 6 cm too far."""
    import mujoco

    from assistbot.world import layout
    from assistbot.world.render import SEGMENT_LABELS
    from assistbot.world.scripted import ik
    w = build_world(PAPER_ARRANGEMENTS["fig3"], 0)
    label = {v: k for k, v in SEGMENT_LABELS.items()}[name]
    lab = pose(w, SceneSampler(seed, "test").sample("none"))
    truth = np.array(lab.objects[name]["position"])
    with StereoCapture(w.model, threaded=False) as cap:
        before = int(np.count_nonzero(cap.segmentation(w.data)[0] == label))
        eye = w.data.cam_xpos[w.model.camera("head_cam_left").id].copy()
        middle = truth + np.array([0.0, 0.0, layout.TABLE_Z + 0.05 + dz])
        q = ik(w, "robot_tcp", eye + 0.6 * (middle - eye), None, joints=tuple(f"robot_j{i}" for i in range(1, 8)), iters=300)
        for j, v in q.items():
            w.data.qpos[w.model.jnt_qposadr[w.model.joint(j).id]] = v
        mujoco.mj_kinematics(w.model, w.data)
        after = int(np.count_nonzero(cap.segmentation(w.data)[0] == label))
        o = Vision().perceive(cap.grab(w.data)).objects[name]
    assert after < 0.9 * before          # the arm hides part of it
    if o.seen:
        assert np.linalg.norm(np.array(o.position) - truth) < 0.03, (o.position, truth)


def test_a_glass_the_robot_arm_lies_across_has_its_state_out_of_view():
    """The robot's hand reaching past an inverted glass, its arm across the glass's top in both cameras: what
    tells the state, the glass's opening or the liquid in it, is hidden, and the glass was read as empty so (a
    turn of it given up as "already upright"). Its state is then out of view; with the arm at rest, in view."""
    import mujoco

    from assistbot.world import Arrangement, layout
    from assistbot.world.scripted import ik
    w = build_world(Arrangement.from_options("HWS:closed@-0.22,-0.12", "RWS:inverted@0.20,-0.125"), 0)
    mujoco.mj_forward(w.model, w.data)
    with StereoCapture(w.model, threaded=False) as cap:
        at_rest = Vision().perceive(cap.grab(w.data)).objects["glass"]
        beyond = np.array([0.20 - 0.08, -0.125, layout.TABLE_Z + 0.10])     # 8 cm past the glass toward the person
        q = ik(w, "robot_tcp", beyond, None, joints=tuple(f"robot_j{i}" for i in range(1, 8)), iters=300)
        for j, v in q.items():
            w.data.qpos[w.model.jnt_qposadr[w.model.joint(j).id]] = v
        mujoco.mj_kinematics(w.model, w.data)
        across = Vision().perceive(cap.grab(w.data)).objects["glass"]
    assert at_rest.seen and at_rest.state_seen and at_rest.state == "inverted"
    assert across.seen and not across.state_seen


def test_standing_object_with_its_base_hidden_in_one_camera_is_placed_not_dropped(world):
    """The robot's gripper in front of a standing object's base in one camera (a grey bar over its
    silhouette's lowest part): placed where the other camera sees its base, not reported unseen;
    with the base hidden in both cameras, nothing places it: unseen."""
    from assistbot.vision.detect import Detector
    from assistbot.vision.library import load_calibration
    lab = pose(world, SceneSampler(3, "test").sample("none"))
    det = Detector(load_calibration())
    with StereoCapture(world.model) as cap:
        f = cap.grab(world.data)

    def hide_base(img, blob, frac):
        x, y, w, h = blob.bbox
        img = img.copy()
        img[y + int((1 - frac) * h):y + h + 2, max(0, x - 2):x + w + 2] = 90
        return img

    for name in ("bottle", "glass"):
        truth = np.array(lab.objects[name]["position"])
        whole = det(f.left, f.right, f.cams).objects[name]
        assert whole.visible
        for frac in (0.25, 0.35):
            right = hide_base(f.right, whole.blobs[1], frac)
            one = det(f.left, right, f.cams).objects[name]
            assert one.visible and one.on_table and np.linalg.norm(one.position[:2] - truth[:2]) < 0.015, (name, frac)
            both = det(hide_base(f.left, whole.blobs[0], frac), right, f.cams).objects[name]
            assert not both.visible, (name, frac)
    world.reset()


def test_missing_library_is_a_user_error_naming_the_command(tmp_path, capsys):
    with pytest.raises(UserError, match="assistbot templates"):
        Vision(root=tmp_path)
    assert main(["templates", "--check", "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "assistbot templates" in err[0]


def test_templates_command_is_deterministic(tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    assert main(["templates", "--scenes", "18", "--out", str(a)]) == 0
    assert main(["templates", "--scenes", "18", "--out", str(b)]) == 0
    names = sorted(p.name for p in a.iterdir())
    assert names == sorted(p.name for p in b.iterdir()) and "index.json" in names
    for n in names:
        assert (a / n).read_bytes() == (b / n).read_bytes(), n


def test_working_hand_touching_the_resting_arm_in_the_image_is_found_not_the_resting_arm(world):
    """Scenes where the working hand, grasping an object, touches the resting left arm in the image:
    one skin blob unless the calibrated static skin is taken out.  The hand is found where it is;
    without the static skin cells and the arm's root, the same frames put it at the resting arm."""
    from assistbot.vision.detect import Detector
    from assistbot.vision.library import load_calibration
    cal = load_calibration()
    bare = {k: v for k, v in cal.items() if k not in ("static_skin_cells", "arm_root")}
    sampler = SceneSampler(1, "test")
    specs = [sampler.sample(("reach", "pointing", "grasp_ag", "grasp_sg")[i % 4]) for i in range(23)]
    with StereoCapture(world.model) as cap:
        for spec in (specs[18], specs[22]):
            assert spec.posture == "grasp_ag"
            lab = pose(world, spec)
            f = cap.grab(world.data)
            truth = np.array(lab.hand_position)
            found = Detector(cal)(f.left, f.right, f.cams).hand
            assert found.visible and np.linalg.norm(found.position - truth) < 0.06
            merged = Detector(bare)(f.left, f.right, f.cams).hand
            assert not merged.visible or np.linalg.norm(merged.position - truth) > 0.2
    world.reset()


def test_a_hand_raised_to_the_stopper_and_cut_by_the_top_of_the_view_is_the_hand_not_the_face(world, monkeypatch):
    """Pulling the stopper, the hand is raised over the bottle and the top of both head cameras' images cuts its
    skin, as it cuts the face of a person bending her head.  Skin cut there is taken for the face only beyond
    the table's edge: these hands are seen and read as pulling the stopper.  Cut skin dropped wherever it
    lies (the rule before), none of them is seen."""
    from assistbot.vision import detect
    from assistbot.vision.calibration import _SEG

    vision = Vision()
    sampler = SceneSampler(3, "test")
    specs = [sampler.sample("remove_stopper") for _ in range(40)]
    with StereoCapture(world.model, threaded=False) as cap:
        for k in (1, 18, 21, 22, 35, 39):
            lab = pose(world, specs[k])
            f = cap.grab(world.data)
            truth = np.array(lab.hand_position)
            for seg, cam in zip(cap.segmentation(world.data), f.cams):   # the hand's own skin reaches the top rows
                u = cam.project(truth)[0][0]
                assert np.any(seg[:2, max(0, int(u) - 40):int(u) + 40] == _SEG["skin"]), k
            hand = vision.perceive(f).hand
            assert hand.seen and hand.posture == "remove_stopper", (k, hand.posture)
            assert np.linalg.norm(np.array(hand.position) - truth) < 0.15, k
            with monkeypatch.context() as m:
                m.setattr(detect, "TABLE_HALF_X", -10.0)       # every skin blob cut by the top taken for the face
                assert not vision.detector(f.left, f.right, f.cams).hand.visible, k
    world.reset()


def test_a_hand_whose_fingers_one_camera_loses_is_placed_by_the_other():
    """The open hand held out, its fingers taken off the right image (painted the table's colour, as pale
    fingers on the pale table come apart from the palm there): the two views' ends then lie on different rows,
    and triangulated as one point they put the hand toward the cameras. The hand is placed where the whole
    pair puts it; with the correspondence check taken out, several cm off."""
    import cv2

    from assistbot.vision import detect
    from assistbot.vision.calibration import _SEG
    from assistbot.vision.library import load_calibration
    det = detect.Detector(load_calibration())
    world = build_world(PAPER_ARRANGEMENTS["fig3"], 0)
    pose(world, SceneSampler(2, "test").sample("open_palm_request"))
    with StereoCapture(world.model, threaded=False) as cap:
        f = cap.grab(world.data)
        seg = cap.segmentation(world.data)[1]
    whole = det(f.left, f.right, f.cams).hand
    assert whole.visible
    rows = np.arange(seg.shape[0])[:, None]
    fingers = (seg == _SEG["skin"]) & (rows > whole.uv[1] - 6)
    table = np.median(f.right[(seg == _SEG["table"]) & (np.abs(rows - whole.uv[1]) < 15)], axis=0)
    right = f.right.copy()
    right[cv2.dilate(fingers.astype(np.uint8), np.ones((3, 3), np.uint8)) > 0] = table
    cut = det(f.left, right, f.cams).hand
    assert cut.visible and np.linalg.norm(cut.position - whole.position) < 0.02
    one_point = detect._one_point
    try:
        detect._one_point = lambda ends, roots, skin: ends
        unchecked = det(f.left, right, f.cams).hand
    finally:
        detect._one_point = one_point
    assert unchecked.visible and np.linalg.norm(unchecked.position - whole.position) > 0.03


def test_the_view_that_lost_the_fingers_takes_its_end_from_the_other():
    """Skin rows as partner 1060's open hand showed them: the left view down to the fingers (row 82), the right
    one down to the palm (row 66); the disparity grows along the arm, 24 px at the shoulder end to 30 at the
    fingers. The right view's end is put on the left's row at the disparity carried on along the arm."""
    from assistbot.vision.detect import _one_point

    def arm(last_row: float, disparity_at) -> np.ndarray:
        return np.array([(u - disparity_at(v), v) for v in np.arange(22.5, last_row + 1, 2.0)
                         for u in np.arange(200.5 + 0.1 * (v - 22.5), 216.5 + 0.1 * (v - 22.5), 2.0)])

    def disparity(v):
        return 24.0 + 0.1 * (v - 22.5)

    left, right = arm(82.5, lambda v: 0.0), arm(66.5, disparity)
    ends = [np.array([212.0, 78.0]), np.array([192.0, 62.0])]
    roots = [np.array([208.0, 24.0]), np.array([184.0, 24.0])]
    kept, placed = _one_point(ends, roots, [left, right])
    assert np.allclose(kept, ends[0])
    assert placed[1] == ends[0][1] and abs(placed[0] - (ends[0][0] - disparity(78.0))) < 0.5
    # the other way round: the right view the fuller one
    placed, kept = _one_point(ends[::-1], roots[::-1], [right, left])
    assert np.allclose(kept, ends[0]) and placed[1] == ends[0][1] and abs(placed[0] - (ends[0][0] - disparity(78.0))) < 0.5
    # both views' skin reaching the rows of both ends (fingers round a glass, each view seeing them its own way):
    # each end is its own view's, kept
    whole = arm(82.5, disparity)
    assert all(np.array_equal(a, b) for a, b in zip(_one_point(ends, roots, [left, whole]), ends))


def test_seeded_labelled_set_meets_goals_minus_margin():
    s = evaluate(60, seed=7, purpose="test")
    assert s.accuracy(("bottle", "glass")) >= GOAL_OBJECT - MARGIN_OBJECT, s.report()
    assert s.accuracy("hand") >= GOAL_POSTURE - MARGIN_POSTURE, s.report()
    assert np.median(s.pos_err) * 100 <= GOAL_MEDIAN_CM + MARGIN_MEDIAN_CM, s.report()
    assert np.percentile(s.pos_err, 95) * 100 <= GOAL_P95_CM + MARGIN_P95_CM, s.report()


def test_a_pair_processed_again_gives_the_same_percept(world):
    """Vision keeps no state between pairs: the benchmark's second, warm-cache pass over a pair
    measures the same work, and a replayed frame is perceived as it was."""
    s = SceneSampler(9, "test")
    v = Vision()
    with StereoCapture(world.model) as cap:
        for posture in ("grasp_ag", "pointing"):
            pose(world, s.sample(posture))
            f = cap.grab(world.data)
            first, again = v.perceive(f), v.perceive(f)
            assert first.hand.seen and first == again
    world.reset()


def test_new_postures_pose_their_objects():
    """remove_stopper / pour / drink scenes: the labels name the object and its state fits the act."""
    w = build_world(PAPER_ARRANGEMENTS["fig3"], 0)
    s = SceneSampler(3, "test")
    for posture, obj, state in (("remove_stopper", "bottle", "closed"), ("pour", "bottle", "open"), ("drink", "glass", None)):
        lab = pose(w, s.sample(posture))
        assert lab.posture == posture and lab.directed_at == obj
        if state:
            assert lab.objects[obj]["state"] == state
    # the glass at the mouth: high above the table
    assert lab.objects["glass"]["position"][2] > 0.3


def test_turning_scene_holds_the_inverted_glass_mid_turn_in_a_side_grip():
    """The person's turn-glass behaviour, posed: the glass lifted in the hand and rolled part of the way;
    its state label is WorldState's: inverted while the glass points within 45 deg of down, then not."""
    import dataclasses

    from assistbot.human.behaviours import TURN_LIFT
    from assistbot.world import Arrangement, Placement
    w = build_world(PAPER_ARRANGEMENTS["fig3"], 0)
    arr = Arrangement(bottle=Placement("HWS", "closed", (-0.30, 0.15)), glass=Placement("HWS", "inverted", (-0.28, -0.12)))
    spec = SceneSampler(3, "test").sample("grasp_sg")
    upright = np.zeros(3)
    for variant, fraction in (("table", 0.5), ("turning", 0.5)):
        lab = pose(w, dataclasses.replace(spec, arrangement=arr, target="glass", variant=variant, reach_fraction=fraction))
        axis = w.data.xmat[w.body_id["glass"]].reshape(3, 3)[:, 2].copy()
        if variant == "table":
            upright, z0 = axis, lab.objects["glass"]["position"][2]
            continue
        assert lab.posture == "grasp_sg" and lab.object_in_hand == "glass"
        assert np.degrees(np.arccos(np.clip(axis @ upright, -1, 1))) == pytest.approx(90, abs=5)   # half of half a turn
        assert lab.objects["glass"]["position"][2] > z0 + 0.5 * TURN_LIFT
        assert lab.objects["glass"]["state"] == w.state().glass_state == "empty"
    early = pose(w, dataclasses.replace(spec, arrangement=arr, target="glass", variant="turning", reach_fraction=0.1))
    assert early.objects["glass"]["state"] == w.state().glass_state == "inverted"


def test_a_lifted_bottle_whose_stopper_no_camera_shows_has_its_state_out_of_view(world):
    """Held from above, the stopper is under the fingers: vision's state is then a guess (wrong in
    most of these scenes), and the percept says the state is out of view; a stopper in view is
    reported closed, in view."""
    from assistbot.vision.pipeline import LOW_CONFIDENCE, STOPPER_SEEN
    s = SceneSampler(5, "test")
    v = Vision()
    hidden = shown = 0
    with StereoCapture(world.model) as cap:
        for _ in range(40):
            spec = s.sample("grasp_ag")
            if spec.target != "bottle" or spec.variant == "table":
                continue
            pose(world, spec)
            b = v.perceive(cap.grab(world.data)).objects["bottle"]
            if not b.seen:
                continue
            if max(v.last.objects["bottle"].stopper) < STOPPER_SEEN:
                hidden += 1
                assert not b.state_seen and b.confidence <= LOW_CONFIDENCE
            else:
                shown += 1
                assert b.state_seen and b.state == "closed"
    assert hidden >= 3 and shown >= 1


def test_a_hand_that_holds_a_lifted_bottle_may_hide_its_stopper_by_the_same_measure():
    """The detector keeps a lifted bottle as seen when the hand is within HELD_DIST of its axis; the
    state then treats the stopper as possibly in that hand, by the same axis distance: with no red in
    view the state is out of view, not "open".  A hand just above and beside the bottle's top, 22 cm from
    its middle (where the state once measured from) but under 16 from its axis, is such a hand."""
    from assistbot.vision.detect import HELD_DIST, Detector, HandDetection, ObjectDetection, axis_distance
    from assistbot.vision.pipeline import LOW_CONFIDENCE
    v = Vision()
    for hand_at, held in (((0.30, 0.15, 0.31), True), ((0.30, 0.45, 0.31), False)):
        bottle = ObjectDetection("bottle", False, np.array([0.30, 0.0, 0.07]), extent=0.8, tilt=0.1, stopper=(0.0, 0.0),
                                 feat=np.array([0, 0, 0, 0.1, 0.07], np.float32))
        bottle.inside = True
        hand = HandDetection(True, np.array(hand_at))
        assert (axis_distance(bottle, hand.position) < HELD_DIST) == held
        Detector._held(bottle, hand)
        assert bottle.visible == held
        state, conf, seen = v._state("bottle", bottle, hand)
        if held:
            assert not seen and conf <= LOW_CONFIDENCE
        else:
            assert (state, seen) == ("open", True)


def test_segmentation_labels_split_skin_and_shirt(world):
    from assistbot.world.render import SEGMENT_LABELS, Renderer
    inv = {v: k for k, v in SEGMENT_LABELS.items()}
    with Renderer(world.model, 160, 120) as r:
        seg = r.segmentation(world.data, "head_cam_left")
    assert {inv["skin"], inv["shirt"]} <= set(np.unique(seg).tolist())


def test_accuracy_interval_narrows_with_the_set_and_contains_the_accuracy():
    from assistbot.vision.evaluate import wilson
    lo, hi = wilson(47, 50)
    assert lo < 47 / 50 < hi < 1.0
    lo5, hi5 = wilson(470, 500)
    assert hi5 - lo5 < (hi - lo) / 2.5     # ten times the frames: about a third of the width
    assert abs(lo5 - 0.9155) < 0.002 and abs(hi5 - 0.9577) < 0.002   # the textbook Wilson interval
    assert all(np.isnan(wilson(0, 0)))


def test_accuracy_by_confidence_sorts_each_report_into_its_band():
    from assistbot.vision.evaluate import Score
    s = Score()
    # (truth, predicted, confidence): two unsure reports, one wrong; three sure ones, all right; a band's top is in it
    for t, p, c in (("reach", "pointing", 0.4), ("reach", "reach", 0.6), ("none", "none", 0.95), ("pour", "pour", 1.0),
                    ("drink", "drink", 0.9)):
        s.truth["hand"].append(t)
        s.pred["hand"].append(p)
        s.conf["hand"].append(c)
    (l0, h0, n0, a0), (_, _, n1, a1), (_, h2, n2, a2) = s.by_confidence("hand")
    assert (l0, h0, h2) == (0.0, 0.6, 1.0)
    assert (n0, a0) == (2, 0.5) and (n1, a1) == (1, 1.0) and (n2, a2) == (2, 1.0)
    assert "0.0-0.6: 50.0% of 2" in s.report()
    assert s.by_confidence("bottle")[0][2] == 0 and "none" in s.report()


def test_finger_parts_find_one_long_thin_finger_not_fingers_held_together():
    import cv2

    from assistbot.vision.detect import finger_parts
    palm = np.zeros((40, 40), np.uint8)
    cv2.circle(palm, (12, 20), 8, 1, -1)
    pointing = palm.copy()
    pointing[19:21, 20:36] = 1            # an index finger: 2 px wide, 16 px long
    open_hand = palm.copy()
    open_hand[14:27, 20:32] = 1           # fingers held together: one wide part
    cm = 0.5                               # cm per px
    fp, fo = finger_parts(pointing.view(bool), cm), finger_parts(open_hand.view(bool), cm)
    assert fp[2] >= 15 * cm > fo[2]       # the longest thin piece: the finger (3-px opening)
    assert fp[1] >= 32 * cm * cm * 0.9    # ... and it is the finger's whole area
    assert not finger_parts(np.zeros((0, 0), bool), cm).any()


def _opencv_hog(c: np.ndarray) -> np.ndarray:
    """`outline_hog` by OpenCV: central differences (Sobel, ksize 1), their polar form (cartToPolar),
    the magnitudes summed per 8-px cell and 6 unsigned orientation bins (np.bincount), normalised."""
    import cv2
    mag, ang = cv2.cartToPolar(cv2.Sobel(c, cv2.CV_32F, 1, 0, ksize=1), cv2.Sobel(c, cv2.CV_32F, 0, 1, ksize=1))
    h, w = c.shape
    cell = ((np.arange(h)[:, None] // 8) * (w // 8) + np.arange(w)[None, :] // 8).ravel() * 6
    b = (ang.ravel() * (6 / np.pi)).astype(np.intp) % 6
    out = np.bincount(cell + b, mag.ravel(), (h // 8) * (w // 8) * 6).astype(np.float32)
    return out / (np.linalg.norm(out) + 1e-3)


def _opencv_finger_parts(m: np.ndarray, cm: float) -> np.ndarray:
    """`finger_parts` by OpenCV: what morphologyEx's opening by a 3-px and a 5-px disc removes, its
    connected components: the total area, the largest piece's area and its box's diagonal."""
    import cv2
    out = np.zeros(6, np.float32)
    for k, size in enumerate((3, 5)):
        thin = cv2.subtract(m, cv2.morphologyEx(m, cv2.MORPH_OPEN, cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (size, size))))
        n, _, st, _ = cv2.connectedComponentsWithStats(thin, connectivity=8)
        if n > 1:
            j = 1 + int(np.argmax(st[1:, cv2.CC_STAT_AREA]))
            out[3 * k:3 * k + 3] = (float(st[1:, cv2.CC_STAT_AREA].sum()) * cm * cm, float(st[j, cv2.CC_STAT_AREA]) * cm * cm,
                                    np.hypot(st[j, cv2.CC_STAT_WIDTH], st[j, cv2.CC_STAT_HEIGHT]) * cm)
    return out


def test_hand_features_are_opencvs_bit_for_bit():
    """The gradient histogram and the thin parts (compiled) give OpenCV's Sobel/cartToPolar and
    morphologyEx/connectedComponents values, on random masks and crops (every gradient direction,
    pieces of every shape); a crop that is not whole cells is refused."""
    import cv2

    from assistbot.vision.detect import HOG_BINS, HOG_CELL, finger_parts, outline_hog
    assert (HOG_CELL, HOG_BINS) == (8, 6)     # the reference's cells and bins
    rng = np.random.default_rng(8)
    for i in range(150):
        m = (rng.random((int(rng.integers(12, 70)), int(rng.integers(12, 70)))) < rng.uniform(0.3, 0.9)).astype(np.uint8)
        c = cv2.resize(m.astype(np.float32), (24, 24), interpolation=cv2.INTER_AREA) if i % 2 else rng.random((24, 24), np.float32)
        assert np.array_equal(outline_hog(c), _opencv_hog(c)), i
        assert np.array_equal(finger_parts(m.view(bool), 0.4), _opencv_finger_parts(m, 0.4)), i
    with pytest.raises(ValueError):
        outline_hog(np.zeros((20, 24), np.float32))


def test_robot_arm_image_is_where_the_capsules_project():
    """`RobotBody.covers` (compiled) agrees with the capsules projected by the camera's model: a pixel
    is covered where it lies within a capsule's image radius of its projected axis, over random arm
    poses and pixels (those within a hair of an edge left out: the two sum in different orders)."""
    import mujoco

    from assistbot.vision.body import MARGIN_PX, RobotBody
    w = build_world(PAPER_ARRANGEMENTS["fig3"], 0)
    rng = np.random.default_rng(4)
    answers = []
    with StereoCapture(w.model) as cap:
        for _ in range(40):
            for i in range(1, 8):
                w.data.qpos[w.model.jnt_qposadr[w.model.joint(f"robot_j{i}").id]] = rng.uniform(-1.2, 1.2)
            mujoco.mj_kinematics(w.model, w.data)
            body = RobotBody.of(w.model, w.data)
            for cam in cap.cameras(w.data):
                za, zb = (body.a - cam.C) @ cam.R[2], (body.b - cam.C) @ cam.R[2]     # the ends' depths
                front = (za > 1e-6) & (zb > 1e-6)
                ua, ub = cam.project(body.a[front]), cam.project(body.b[front])
                rad = cam.K[0, 0] * body.r[front] / np.minimum(za, zb)[front] + MARGIN_PX
                for _ in range(5):
                    pts = rng.uniform((0, 0), (cam.width, cam.height), (int(rng.integers(1, 4)), 2))
                    d = ub - ua
                    t = np.clip(((pts[:, None] - ua) * d).sum(-1) / np.maximum((d * d).sum(-1), 1e-12), 0.0, 1.0)
                    gap = np.linalg.norm(pts[:, None] - (ua + t[..., None] * d), axis=-1) - rad     # (points, capsules)
                    if np.abs(gap).min(initial=1.0) < 1e-6:
                        continue
                    answers.append(body.covers(cam, pts))
                    assert answers[-1] == bool((gap < 0).any())
    assert len(answers) > 350 and 0.2 < np.mean(answers) < 0.8


def test_robot_body_covers_the_arms_pixels_in_the_render():
    """The capsules stand for the arm as the renderer draws it: most of the arm's rendered pixels
    (segmentation label "robot", the base left out) lie on them, and most of their pixels are arm."""
    import mujoco

    from assistbot.vision.body import RobotBody
    from assistbot.world.render import SEGMENT_LABELS
    from assistbot.world.scripted import ik
    w = build_world(PAPER_ARRANGEMENTS["fig3"], 0)
    robot = {v: k for k, v in SEGMENT_LABELS.items()}["robot"]
    with StereoCapture(w.model) as cap:
        q = ik(w, "robot_tcp", np.array([0.1, 0.05, 0.95]), None, joints=tuple(f"robot_j{i}" for i in range(1, 8)), iters=300)
        for j, v in q.items():
            w.data.qpos[w.model.jnt_qposadr[w.model.joint(j).id]] = v
        mujoco.mj_kinematics(w.model, w.data)
        body, cam = RobotBody.of(w.model, w.data), cap.cameras(w.data)[0]
        seg = cap.segmentation(w.data)[0]
    vv, uu = np.mgrid[0:cam.height:2, 0:cam.width:2]
    on = np.array([body.covers(cam, p) for p in np.column_stack([uu.ravel() + 0.5, vv.ravel() + 0.5])]).reshape(vv.shape)
    arm = seg[::2, ::2] == robot
    arm[int(0.75 * arm.shape[0]):] = False          # the image's bottom rows: the robot's base and torus
    on_low = on.copy()
    on_low[int(0.75 * on.shape[0]):] = False
    assert arm.sum() > 500
    assert (arm & on).sum() / arm.sum() > 0.85
    assert (arm & on_low).sum() / on_low.sum() > 0.7


def test_a_hand_turning_the_glass_behind_it_is_not_read_as_pointing_at_the_bottle():
    """Active user, inverted glass on her side: the robot reaches for the bottle while she turns the
    glass. The glass then hides her hand in both cameras and the forearm's end, at the glass's edge,
    looks like a pointing finger (that reading made the robot say "You are pointing at the bottle.
    You want the bottle."). A hand whose end touches the glass is at it, not pointing past it."""
    from assistbot.episode.builder import build_episode

    sc = dataclasses.replace(load_scenario("active-inverted-glass-hws"), time_limit=12.0)
    ep = build_episode(sc, "vision")
    try:
        ep.run()
    finally:
        ep.perception.close()
    turning = [e for e in ep.log if e["kind"] == "tick" and e["human"] == "turn_glass" and e["t"] > 8.0]
    assert len(turning) > 30                      # she is still turning it at 12 s
    read = [e["percept"]["hand"]["posture"] for e in turning if e["percept"]["hand"]["seen"]]
    assert len(read) > 30 and read.count("pointing") <= 1, read
    said = [e["tag"] for e in ep.log if e["kind"] == "say"]
    assert "understood:point_bottle" not in said and "infer:get_bottle" not in said, said


@pytest.mark.parametrize("seen_at, away", [((0.21, 0.02, 0.0), False), ((0.05, 0.20, 0.0), True), (None, False)])
def test_the_object_in_the_robots_hand_is_placed_at_the_hand_unless_seen_elsewhere(seen_at, away):
    """Vision places what the robot believes it holds at the robot's hand; seen placed far from it (the
    grasp closed on something else), it reports where it sees it."""
    from assistbot.vision.detect import ObjectDetection
    from assistbot.vision.pipeline import _seen_away_from

    tcp = np.array([0.20, 0.0, 0.08])
    d = ObjectDetection("bottle", seen_at is not None, None if seen_at is None else np.array(seen_at))
    assert _seen_away_from(d, tcp) == away


@pytest.mark.parametrize("name", ["bottle", "glass"])
def test_an_object_lying_on_its_side_is_reported_lying_and_standing_ones_are_not(name):
    """Lying across the cameras' lines of sight (its axis along the table's y): on the table, its silhouette
    near horizontal in both images: `lying`, not seen standing. The other object, standing, is not lying."""
    import mujoco
    w = build_world(PAPER_ARRANGEMENTS["fig3"], 0)
    with StereoCapture(w.model) as cap:
        p = Vision().perceive(cap.grab(w.data))
        assert not any(o.lying for o in p.objects.values())
        adr = w.model.jnt_qposadr[w.model.body(name).jntadr[0]]
        q = np.zeros(4)
        mujoco.mju_axisAngle2Quat(q, np.array([1.0, 0.0, 0.0]), np.pi / 2)
        w.data.qpos[adr + 3:adr + 7] = q
        w.data.qpos[adr + 2] += 0.04
        for _ in range(300):
            mujoco.mj_step(w.model, w.data)
        assert abs(w.data.xmat[w.body_id[name]][8]) < 0.2           # it does lie
        p = Vision().perceive(cap.grab(w.data))
    o = p.objects[name]
    assert o.lying and not o.seen
    assert np.hypot(*(np.array(o.position[:2]) - w.data.xpos[w.body_id[name]][:2])) < 0.1
    other = p.objects["glass" if name == "bottle" else "bottle"]
    assert other.seen and not other.lying


class _Reads:
    """A hand classifier that reads every hand as ``posture`` (the likeliest), the other classes unlikely."""

    def __init__(self, classes, posture):
        self.classes, self.posture = list(classes), posture

    def probabilities(self, crop, geo):
        pr = np.full((1, len(self.classes)), 0.01)
        pr[0, self.classes.index(self.posture)] = 0.9
        return pr


@pytest.mark.parametrize("lifted, posture, read", [("glass", "remove_stopper", "grasp_ag"), ("glass", "pour", "grasp_ag"),
                                                   ("bottle", "remove_stopper", "remove_stopper"), ("bottle", "drink", "grasp_ag")])
def test_a_posture_that_uses_another_object_than_the_one_lifted_at_the_hand_is_a_misreading(lifted, posture, read):
    """The person holds the glass out from above: its outline, hand over a cylinder's top, may read as pulling
    a stopper; but the glass has none. A posture that uses one object (remove_stopper and pour the bottle,
    drink the glass) with the other lifted at the hand is read as holding what is lifted; with its own
    object lifted there (pulling the stopper of the bottle the robot holds up) it stands."""
    from assistbot import catalogue
    from assistbot.cognition.percept import ObjectPercept, Percept
    from assistbot.vision.detect import Detections, HandDetection, ObjectDetection

    v = Vision()
    v.classifiers = {**v.classifiers, "hand": _Reads(v.classifiers["hand"].classes, posture)}
    base = 0.10                              # the lifted object's base above the table
    end = np.array([-0.04, -0.04, base + catalogue.height(lifted) + 0.02])   # over its top: a grip from above
    det = Detections(objects={n: ObjectDetection(n, False, None) for n in catalogue.TASK_OBJECTS},
                     hand=HandDetection(True, position=end, proximal=end - np.array([0.25, 0.0, 0.05])))
    objs = {"bottle": ObjectPercept("bottle", "RWS", "closed", (0.2, 0.1, 0.0)),
            "glass": ObjectPercept("glass", "RWS", "empty", (0.2, -0.1, 0.0))}
    objs[lifted] = ObjectPercept(lifted, "HWS", objs[lifted].state, (-0.04, -0.04, base))
    hp = v._hand(det, Percept(t=1.0, objects=objs))
    assert hp.posture == read
    if read != posture:
        assert hp.object_in_hand == lifted


def _lifted_height_errors(world, posture: str, n: int) -> list[float]:
    """Signed height errors (m) of the objects the posed hand holds up in ``posture``, as vision places them."""
    s = SceneSampler(11, "test")
    v = Vision()
    errors = []
    with StereoCapture(world.model) as cap:
        while len(errors) < n:
            spec = s.sample(posture)
            if spec.variant not in ("lifted", "held_out") or spec.target is None:
                continue
            lab = pose(world, spec)
            o = v.perceive(cap.grab(world.data)).objects[spec.target]
            if o.seen and lab.pose_miss <= 0.02:
                errors.append(float(o.position[2] - lab.objects[spec.target]["position"][2]))
    return errors


def test_an_object_held_up_from_above_is_placed_at_the_height_of_its_base():
    """A hand over an object's top hides part of it, and the silhouette's centroid then lies low (the
    glass came out 3.3 cm low, and the robot's fingers closed under its base); the base's rim, which
    the hand does not hide, places it within a centimetre."""
    errors = np.array(_lifted_height_errors(build_world(PAPER_ARRANGEMENTS["fig3"], 0), "grasp_ag", 12))
    assert np.median(np.abs(errors)) < 0.01 and np.abs(errors).max() < 0.02


def test_a_glass_lifted_at_a_grasping_hand_whose_end_is_seen_back_at_the_wrist_is_in_that_hand():
    """A long hand holding the glass from above hides its fingers behind the glass: the hand's end is seen at the
    wrist, 13 cm behind the glass's axis (and the hand's centre, a grip's offset further back, farther still). The
    glass lifted right at that end is in the hand: the robot must not take the hand for an empty one (it carried
    the bottle it was offering into the glass she held out, which fell)."""
    from assistbot.cognition.percept import ObjectPercept, Percept
    from assistbot.vision.detect import Detections, HandDetection, ObjectDetection

    v = Vision()
    v.classifiers = {**v.classifiers, "hand": _Reads(v.classifiers["hand"].classes, "grasp_ag")}
    glass = np.array([-0.236, 0.159, 0.05])            # its base 5 cm above the table
    end = glass + np.array([-0.13, 0.0, 0.09])
    det = Detections(objects={n: ObjectDetection(n, False, None) for n in ("bottle", "glass")},
                     hand=HandDetection(True, position=end, proximal=end - np.array([0.25, 0.0, 0.05])))
    objs = {"bottle": ObjectPercept("bottle", "RWS", "open", (0.2, 0.12, 0.0)),
            "glass": ObjectPercept("glass", "HWS", "empty", tuple(glass))}
    hp = v._hand(det, Percept(t=1.0, objects=objs))
    assert hp.posture == "grasp_ag" and hp.object_in_hand == "glass", hp
