"""The robot senses, it does not look up: the executor and its primitives run on a view of the physics
that lets through only the robot's own joints, actuators, sensors, sites and bodies.

Perception (here the labelled oracle, standing in for vision) is built outside that view, as the
episode runner does; anything on the robot's side that reads an object's or the person's state (a body
position, a contact's partner, the world's helpers) raises.
"""

from __future__ import annotations

import numpy as np
import pytest

from assistbot.episode.executor import RobotExecutor
from assistbot.episode.oracle import OraclePerception
from assistbot.human.controller import HumanController
from assistbot.robot.sim import CONTROL_DT
from assistbot.world import Arrangement, build_world


class LookedUp(AssertionError):
    """The robot's side read something that is not its own body."""


class _Rows:
    """An array of the physics through which only the given first-axis rows can be read or written."""

    def __init__(self, array: np.ndarray, rows: set[int], name: str) -> None:
        self._a, self._rows, self._name = array, rows, name

    def _check(self, key) -> None:
        k = key[0] if isinstance(key, tuple) else key
        if isinstance(k, slice):
            idx = range(*k.indices(len(self._a)))
        else:
            idx = np.atleast_1d(np.asarray(k)).ravel().tolist()
        bad = [int(i) for i in idx if int(i) not in self._rows]
        if bad:
            raise LookedUp(f"data.{self._name}[{bad[:5]}]: not the robot's own")

    def __getitem__(self, key):
        self._check(key)
        return self._a[key]

    def __setitem__(self, key, value):
        self._check(key)
        self._a[key] = value

    def __len__(self) -> int:
        return len(self._a)


class RobotOnlyData:
    """MjData as the robot's own sensors and actuators see it."""

    def __init__(self, model, data) -> None:
        self._data = data
        mine = lambda n: n is not None and n.startswith("robot_")  # noqa: E731
        joints = [j for j in range(model.njnt) if mine(model.joint(j).name)]
        qpos = {int(model.jnt_qposadr[j]) for j in joints}
        dofs = {int(model.jnt_dofadr[j]) for j in joints}
        sensors = [s for s in range(model.nsensor) if mine(model.sensor(s).name)]
        sensordata = {int(model.sensor_adr[s]) + k for s in sensors for k in range(int(model.sensor_dim[s]))}
        bodies = {b for b in range(model.nbody) if mine(model.body(b).name)}
        sites = {s for s in range(model.nsite) if int(model.site_bodyid[s]) in bodies}
        actuators = {a for a in range(model.nu) if mine(model.actuator(a).name)}
        self._allowed = {"qpos": qpos, "qvel": dofs, "ctrl": actuators, "sensordata": sensordata,
                         "site_xpos": sites, "site_xmat": sites, "xpos": bodies, "xmat": bodies}

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        if name not in self._allowed:
            raise LookedUp(f"data.{name}: the robot has no sensor for it")
        return _Rows(getattr(self._data, name), self._allowed[name], name)


class RobotOnlyWorld:
    """What the robot's side is given of the world: the model (its own description, read once for names
    and addresses) and the guarded data; none of the world's helpers."""

    def __init__(self, world) -> None:
        self.model = world.model
        self.data = RobotOnlyData(world.model, world.data)


def _run(arrangement, profile, action, seconds, say: str | None = None, seen=None):
    w = build_world(Arrangement.from_options(*arrangement), seed=0)
    human = HumanController(w, profile=profile, seed=0)
    perception = OraclePerception(w, human.appearance)
    robot = RobotExecutor(RobotOnlyWorld(w))
    n_sub = max(1, int(round(CONTROL_DT / w.model.opt.timestep)))
    began, held = False, set()
    for tick in range(int(seconds / CONTROL_DT)):
        t = w.time
        if tick % 5 == 0:
            p = perception.perceive(t, robot.proprioception())
            robot.see(seen(p) if seen is not None else p)
        if not began and t >= 1.0:
            robot.begin(action, t)
            held.add(("set out to grasp", robot.primitive.object))
            if say:
                human.hear(say, t)
            began = True
        robot.tick(t, CONTROL_DT)
        human.tick(t)
        w.step(n_sub)
        held.add(robot.holding())
        if began and robot.status.ended:
            break
    return w, robot, held - {None}


def test_the_guard_catches_a_look_up():
    w = build_world(Arrangement.from_options("RWS:open", "RWS:empty"), seed=0)
    data = RobotOnlyData(w.model, w.data)
    data.qpos[int(w.model.jnt_qposadr[w.model.joint("robot_j1").id])]    # its own joint: fine
    with pytest.raises(LookedUp):
        data.xpos[w.body_id["bottle"]]
    with pytest.raises(LookedUp):
        data.contact


def test_the_robot_fills_the_glass_on_its_own_senses():
    w, robot, held = _run(("RWS:open@0.20,0.12", "RWS:empty@0.20,-0.12"), "passive", "Reach-grasp-open-bottle-fill-glass", 40.0)
    assert robot.records[-1].status == "succeeded", robot.records[-1]
    assert w.state().glass_state == "full"
    assert held == {("set out to grasp", "bottle"), "bottle"} and robot.holding() is None


@pytest.mark.slow
def test_the_robot_takes_what_the_person_holds_out_and_knows_what_it_is_by_sight():
    """Receive-object starts before the robot knows which object it will take ("held_out"): the hand
    feels that it holds, the cameras (here the oracle) say what."""
    w, robot, held = _run(("HWS:closed", "RWS:empty"), "active", "Receive-object", 45.0, say="request:bottle")
    assert robot.records[-1].status == "succeeded", robot.records[-1]
    assert held == {("set out to grasp", "held_out"), "bottle"}
    assert w.state().objects["bottle"].zone == "RWS" and w.state().human_holds is None


def test_a_grasp_that_the_cameras_see_elsewhere_is_not_believed():
    """The hand feels a grasp but not of what: when the cameras keep seeing the bottle where it stood (a
    stand-in for vision seeing that the grasp closed on something else), the robot does not carry on
    pouring an empty hand: the action fails with the reason, and the robot no longer believes it holds it."""
    stood = {}

    def still_there(p):
        b = p.objects["bottle"]
        stood.setdefault("xy", b.position)
        b.position, b.seen = stood["xy"], True
        return p

    w, robot, held = _run(("RWS:open@0.20,0.12", "RWS:empty@0.20,-0.12"), "passive", "Reach-grasp-open-bottle-fill-glass",
                          40.0, seen=still_there)
    rec = robot.records[-1]
    assert rec.status == "failed" and "not in the hand" in rec.reason, rec
    assert w.state().glass_state == "empty"
    assert robot.holding() is None
