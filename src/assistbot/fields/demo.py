"""A small network that shows the three behaviours the architecture is built from.

- ``selection``: two inputs of different strength compete; the stronger wins
  (input-driven regime: the peak decays when its input goes).
- ``memory``: the same competition in the self-sustained regime; the winner's
  peak stays after both inputs are removed.
- ``target``: fed through weak couplings (eq. 4) by two source fields; it
  rises only while both sources hold a peak at the same time.

And a second, spatial network, coupled the way DFT toolkits couple fields
(a Gaussian kernel over a source's whole output):

- ``continuous``: a ring of 100 positions sees two bumps; through a
  continuous coupling a selective ring picks the stronger one and keeps it;
- ``plane``: two 1-D cues, expanded along the other axis, meet in a 2-D
  field, which forms a peak only where they cross; the peak's x is read
  back out into a 1-D field by the max over y.

And a third, that learns (a memory trace and a gated Hebbian coupling):

- ``goal``: a side grip first means "pour" (the prior table); three trials
  in which a side grip went with a hand-over that worked (the gate open)
  teach the coupling otherwise, and then the side grip alone selects
  "hand-over"; the goal field's memory trace keeps a preshape of what it chose;
- ``weights``: the learned table over time.
"""

from __future__ import annotations

from pathlib import Path

from assistbot.fields.network import Network
from assistbot.fields.plot import plot_history, plot_plane, plot_weights

ITEMS = ["A", "B", "C", "D"]


def _field(A: float, w_inhib: float) -> dict:
    return {"items": ITEMS, "spacing": 10, "tau": 0.05, "h": -3.0, "beta": 4.0,
            "kernel": {"A": A, "sigma": 2.0, "w_inhib": w_inhib}, "input_sigma": 2.0}


def demo_spec() -> dict:
    return {
        "dt": 0.005,
        "fields": {
            "selection": _field(1.0, 1.0),
            "memory": _field(3.0, 1.0),
            "source_1": _field(3.0, 1.0),
            "source_2": _field(3.0, 1.0),
            "target": _field(3.0, 1.0),
        },
        "couplings": [
            # each source alone lifts the target by k*a = 1.8 from h = -3: below threshold
            {"source": "source_1", "target": "target", "k": 0.6, "table": {"B": {"B": 3.0}}},
            {"source": "source_2", "target": "target", "k": 0.6, "table": {"B": {"C": 3.0}}},
        ],
    }


def _line(size: int, A: float, w_inhib: float, periodic: bool = False) -> dict:
    return {"size": size, "tau": 0.05, "h": -3.0, "beta": 4.0, "periodic": periodic,
            "kernel": {"A": A, "sigma": 2.0, "w_inhib": w_inhib}}


def spatial_spec() -> dict:
    """Continuous couplings: a ring read by a selective ring, two cues meeting in a plane, read out along x."""
    return {
        "dt": 0.005,
        "fields": {
            "sensor": _line(100, 1.0, 0.2, periodic=True),   # input-driven: follows its inputs
            "choice": _line(100, 2.5, 0.6, periodic=True),   # selective and self-sustained
            "cue_x": _line(60, 1.0, 0.5),
            "cue_y": _line(40, 1.0, 0.5),
            "plane": {"shape": [40, 60], "tau": 0.05, "h": -3.0, "beta": 4.0,
                      "kernel": {"A": 0.4, "sigma": 1.5, "w_inhib": 0.01}},
            "readout_x": _line(60, 1.0, 0.5),
        },
        "couplings": [
            {"source": "sensor", "target": "choice", "kernel": {"A": 4.0, "sigma": 2.0, "normalize": True}},
            # each cue alone lifts a ridge by 2 from h = -3: below threshold; where two ridges cross, a peak
            {"source": "cue_x", "target": "plane", "kernel": {"A": 2.0, "sigma": 0}, "expand": "y"},
            {"source": "cue_y", "target": "plane", "kernel": {"A": 2.0, "sigma": 0}, "expand": "x"},
            {"source": "plane", "target": "readout_x", "kernel": {"A": 5.0, "sigma": 1.0, "normalize": True},
             "project": {"op": "max", "over": "y"}},
        ],
    }


def run_spatial_demo(out: Path, backend: str = "auto") -> list[Path]:
    """Two bumps for the ring (0-1.5 s, then removed), cue x alone (1.5-3 s), both cues (3-4.5 s)."""
    net = Network.from_dict(spatial_spec(), backend=backend)
    rec = net.record(["sensor", "choice", "cue_x", "cue_y", "readout_x"], every=4)
    net.set_stimulus_at("sensor", "weaker", 30.0, 4.0, 3.0)
    net.set_stimulus_at("sensor", "stronger", 70.0, 5.0, 3.0)
    net.run(1.5)
    net.clear_stimuli("sensor")
    net.set_stimulus_at("cue_x", "cue", 20.0, 5.0, 1.5)
    net.run(1.5)
    alone = net.u("plane").copy()
    net.set_stimulus_at("cue_y", "cue", 25.0, 5.0, 1.5)
    net.run(1.5)
    titles = {
        "sensor": "sensor (ring): two bumps, 30 weaker, 70 stronger, removed at 1.5 s",
        "choice": "choice (ring, continuous coupling from sensor): selects 70 and keeps it",
        "readout_x": "readout_x: max over y of the plane; a peak at x = 20 once both cues are on (3 s)",
    }
    out.mkdir(parents=True, exist_ok=True)
    paths = [plot_history(rec, name, out / f"{name}.png", title=title) for name, title in titles.items()]
    paths.append(plot_plane({"cue x alone (3 s): a ridge below threshold": alone,
                             "cues x = 20 and y = 25 (4.5 s): one peak where they cross": net.u("plane")},
                            out / "plane.png"))
    return paths


def learning_spec() -> dict:
    """A grip field, a goal field with a memory trace, a success gate; grip -> goal learns."""
    field = {"tau": 0.05, "h": -3.0, "kernel": {"A": 1.0, "sigma": 2.0, "w_inhib": 0.5}}
    return {
        "dt": 0.005,
        "fields": {
            "grip": {"items": ["above", "side"], **field},
            "goal": {"items": ["hand-over", "pour"], **field,
                     "memory": {"tau_build": 1.0, "tau_decay": 10.0, "amplitude": 0.5}},
            "success": {"items": ["yes"], "tau": 0.05, "h": -3.0},
        },
        "couplings": [{"source": "grip", "target": "goal", "k": 1.0,
                       "table": {"hand-over": {"above": 4.0}, "pour": {"side": 4.0}},
                       "learn": {"rate": 4.0, "decay": 1.0, "gate": "success.yes", "bounds": [0, 4]}}],
    }


def run_learning_demo(out: Path, backend: str = "auto") -> list[Path]:
    """A side grip alone (0-1 s), three taught trials of 1.5 s each (side grip, hand-over, success), the side
    grip alone again (7.5-8.5 s), with 0.5 s of rest after each."""
    net = Network.from_dict(learning_spec(), backend=backend)
    rec = net.record(every=4)

    def trial(teach: bool, seconds: float) -> None:
        net.set_stimulus("grip", "side", 5.0)
        if teach:
            net.set_stimulus("goal", "hand-over", 6.0)
            net.set_stimulus("success", "yes", 5.0)
        net.run(seconds)
        net.clear_stimuli()
        net.run(0.5)

    trial(False, 1.0)
    for _ in range(3):
        trial(True, 1.5)
    trial(False, 1.0)
    out.mkdir(parents=True, exist_ok=True)
    return [
        plot_history(rec, "goal", out / "goal.png",
                     title="goal: a side grip means pour (0-1 s); taught three times (1.5-7 s) that it\n"
                           "meant a hand-over, the side grip alone then selects hand-over (7.5 s)"),
        plot_weights(rec, "grip->goal", out / "weights.png",
                     title="grip->goal, learnt while a side grip went with a hand-over that worked"),
    ]


def run_demo(out: Path, backend: str = "auto") -> list[Path]:
    """Run the scripted 6 s demo and the spatial one; write one PNG per field shown; returns the paths."""
    net = Network.from_dict(demo_spec(), backend=backend)
    rec = net.record(every=4)
    for name in ("selection", "memory"):
        net.set_stimulus(name, "A", 4.0)
        net.set_stimulus(name, "C", 5.0)
    net.set_stimulus("source_1", "B", 5.0)  # 0-1.5 s: source 1 alone
    net.run(1.5)
    for name in ("selection", "memory"):
        net.clear_stimuli(name)  # inputs removed: the selection decays, the memory stays
    net.clear_stimuli("source_1")
    net.reset_field("source_1")
    net.set_stimulus("source_2", "C", 5.0)  # 1.5-3 s: source 2 alone
    net.run(1.5)
    net.set_stimulus("source_1", "B", 5.0)  # 3-4.5 s: both: the target rises
    net.run(1.5)
    net.clear_stimuli()
    net.reset_field("source_1")
    net.reset_field("source_2")
    net.run(1.5)
    titles = {
        "selection": "selection: stronger input C wins; decays once inputs are removed (1.5 s)",
        "memory": "memory: C wins and stays self-sustained after the inputs are removed (1.5 s)",
        "source_1": "source 1: peak at B during 0-1.5 s and 3-4.5 s",
        "source_2": "source 2: peak at C from 1.5 s to 4.5 s",
        "target": "target: rises only when both sources hold peaks (3-4.5 s)",
    }
    out.mkdir(parents=True, exist_ok=True)
    paths = [plot_history(rec, name, out / f"{name}.png", title=title) for name, title in titles.items()]
    return paths + run_spatial_demo(out, backend) + run_learning_demo(out, backend)
