"""The layered field architecture: Percept in, Decision out.

Layers (fields of `assistbot.fields`, items from `assistbot.task`):

- OL: observed motor primitives (memory of the act in progress);
- OML: object x state x zone memory (survives percept gaps);
- CSGL past / present / future: achieved, enabled-and-first, not-yet sub-goals;
- INI: the robot's initiative, rising slowly while the partner shows no act;
- URGE: the slow part of the initiative, building up over ~10 s while no action of the robot
  runs, whatever the partner does: from any state a decision follows;
- ASL: the partner's goal-directed action chain (from OL + OML + CSGL);
- IL: the partner's intention (from ASL + CSGL + OML);
- AFL: the memory of the robot's own actions that failed (the executor's reports), which keeps a
  failed action habituated in AEL while it stands;
- SUCCESS: up for a moment when an action of the robot's finished as it should, a sub-goal was
  reached or the partner was seen doing what the inferred intention predicts; with ``learning.rate`` > 0
  it gates the learning of the grip-to-chain weights (OL -> ASL);
- AML: mismatch of the intention with what is possible (IL + ASL/OML), and of what the robot did
  with what came of it: a failure reported while AFL remembers one of the same action;
- AEL: the complementary action (IL, OML, CSGL, AML, INI, URGE), one winner that
  sustains itself until the robot reports it finished or failed.

Decisions come from the field dynamics only: the percept becomes Gaussian
inputs; the read-out watches peaks (a decision is the AEL peak that stayed
above threshold for ``readout.hold`` s; an utterance is spoken once per rise
of a pool's peak in ASL, IL, AML, AEL).
"""

from __future__ import annotations

import math
from typing import Any, Iterable, Mapping

import numpy as np

from assistbot import task
from assistbot.cognition.config import LAYERS, CognitionConfig
from assistbot.cognition.percept import Decision, Percept, Said
from assistbot.fields import Network
from assistbot.interfaces import Status

SPOKEN_LAYERS = ("ASL", "IL", "AML", "AEL")
#: the AML items that are the partner's errors (not the robot's own failures or a fallen object)
PARTNER_ERRORS = frozenset(e.name for e in task.ERRORS)
#: the layers whose peaks a log (`trace`) and an episode's video show
LAYERS_SHOWN = ("ASL", "IL", "AML", "AEL", "CSGL_past", "CSGL_present", "CSGL_future")


def ol_items_of(percept: Percept) -> list[str]:
    """OL items evidenced by the hand percept (primitive + object it is directed at)."""
    h = percept.hand
    out: list[str] = []
    if not h.seen:
        return out
    p = h.posture
    if p == "reach" and h.directed_at:
        out.append(f"reach_{h.directed_at}")
    elif p in ("grasp_ag", "grasp_sg") and h.object_in_hand:
        out.append(f"{p}_{h.object_in_hand}")
    elif p == "pointing" and (h.pointed_at or h.directed_at):
        out.append(f"point_{h.pointed_at or h.directed_at}")
    elif p == "open_palm_request":
        out.append("open_hand_request")
    elif p in ("remove_stopper", "pour", "drink"):
        out.append(p)
    if h.held_out and h.object_in_hand:
        out.append(f"hold_out_{h.object_in_hand}")
    return out


class Cognition:
    """The architecture on one `Network`; feed `update(percept)`, read the returned `Decision`.

    ``config``: a `CognitionConfig`, a nested dict, or None for the default;
    ``overrides``: {path: value} applied on top. ``backend``/``seed`` go to the
    network. Time is the network's simulated time ``t`` (s).
    """

    def __init__(self, config: CognitionConfig | Mapping[str, Any] | None = None, overrides: Mapping[str, Any] | None = None,
                 backend: str = "auto", seed: int | None = 0) -> None:
        if isinstance(config, CognitionConfig):
            self.config = config.copy()
        else:
            self.config = CognitionConfig(config)
        if overrides:
            self.config.update(overrides)
        self.backend = backend
        self.seed = seed
        self._build()

    # -- construction -------------------------------------------------------------------
    def _build(self) -> None:
        self.net = Network.from_dict(self.config.network_dict(), backend=self.backend, seed=self.seed)
        self.layers = LAYERS
        self._thr_idx = {name: self.net.field(name).item_indices for name in LAYERS}
        # the spoken pools' centres in the network's state vector, read in one gather per update
        self._spoken_idx = np.concatenate([self.net.item_state_indices(L) for L in SPOKEN_LAYERS])
        self._spoken_names = [(L, item) for L in SPOKEN_LAYERS for item in LAYERS[L]]
        self._all_idx = np.concatenate([self.net.item_state_indices(L) for L in LAYERS])
        ends = np.cumsum([len(LAYERS[L]) for L in LAYERS])
        self._all_spans = {L: (int(e - len(LAYERS[L])), int(e)) for L, e in zip(LAYERS, ends)}
        self.reset()

    def set(self, path: str, value: Any) -> None:
        """Change one parameter (see `CognitionConfig`); the network is rebuilt and reset."""
        self.config.set(path, value)
        self._build()

    def reset(self) -> None:
        self.net.reset()
        self.net.clear_stimuli()
        s = self.config.data["stimulus"]
        for g in task.SUBGOALS:
            self.net.set_stimulus("CSGL_present", g, float(s["present_drive"][g]))
            self.net.set_stimulus("CSGL_future", g, float(s["future_drive"]))
        self.net.set_stimulus("INI", "take-initiative", float(s["ini_drive"]))
        self.net.set_stimulus("URGE", "urge", float(s["urge_drive"]))
        self.decision: str | None = None       # the committed AEL winner
        self.decision_t: float | None = None
        self.error: str | None = None
        n_spoken = len(self._spoken_names)
        self._upv = np.zeros(n_spoken, bool)       # pool counted as risen (spoken) and not yet gone
        self._since = np.full(n_spoken, -1.0)      # time since which the pool is above threshold, -1 if not
        self._release_until = -1.0
        self._habituation: dict[str, float] = {}  # action -> time released
        self._state_out_of_view: dict[str, str | None] = {}   # object -> state remembered when it went out of view
        self._failures: dict[str, float] = {}   # motion action -> time of its last reported failure (AFL input)
        self._pulses: dict[str, float] = {}     # AML mismatch -> time of the last failure report pulsing it
        self._lying_since: dict[str, float] = {}  # object -> since when it has been seen lying
        self._cleared: dict[str, float] = {}    # motion action -> time its failure memory was cleared
        self._succeeded_at = -math.inf          # when an action last finished as it should or a sub-goal was reached
        self._reached: set[str] = set()         # the sub-goals CSGL_past holds (a new one is a success)
        self._confirmed: set[str] = set()       # the intentions IL holds while OL sees their act (a new one too)
        # a partner's error the robot has told them of, and the chains ASL read when it decided to: told once, the
        # error is held down while the partner goes on with that act (`_apply_told_input`)
        self._told: tuple[str, frozenset[str]] | None = None
        self._error_reading: frozenset[str] = frozenset()
        self._pending: list[Said] = []
        self._new = False
        self._released: str | None = None
        self.log: list[Said] = []
        self.history: list[tuple[float, str, str]] = []  # (t, "decide"/"release", action)

    # -- input --------------------------------------------------------------------------
    def perceive(self, percept: Percept) -> None:
        """Turn a percept into held Gaussian inputs of OL and OML; release on finished/failed."""
        s = self.config.data["stimulus"]
        net = self.net
        # OL: the motor primitives seen now; a hand at rest clears the memory of the act
        h = percept.hand
        active = set(ol_items_of(percept))
        for item in task.OL_ITEMS:
            if item in active:
                amp = s["ol"] * h.confidence
            elif h.seen and h.posture == "none":
                amp = s["ol_rest"]
            else:
                amp = 0.0
            net.set_stimulus("OL", item, amp)
        # OML: each seen object at its (state, zone); evidence against its other items.
        # Proprioception wins over vision for the zone of the object in the robot's gripper (it is in RWS).
        held = percept.robot.holding
        for obj, states in task.OBJECT_STATES.items():
            o = percept.objects.get(obj)
            here, conf = None, 0.0
            if o is not None:
                zone = "RWS" if held == obj else o.zone
            if o is not None and o.seen and o.state_seen:
                here, conf = task.oml_item(obj, o.state, zone), o.confidence
                self._state_out_of_view.pop(obj, None)
            elif o is not None and o.seen:
                # the state out of view (the stopper under the hand; vision's state only a guess): the
                # object where it is seen now, in the state remembered when it went out of view (read
                # once: the memory's peak fades as the object's input moves to the new place)
                if obj not in self._state_out_of_view:
                    self._state_out_of_view[obj] = self._remembered_state(obj)
                remembered = self._state_out_of_view[obj]
                if remembered is not None:
                    here, conf = task.oml_item(obj, remembered, zone), 1.0
            for st in states:
                for z in task.ZONES:
                    item = task.oml_item(obj, st, z)
                    if here is None:
                        amp = 0.0
                    elif item == here:
                        amp = s["oml"] * conf
                    else:
                        amp = s["oml_against"] * conf
                    net.set_stimulus("OML", item, amp)
        # AML: an object seen lying on its side, once seen so for fallen_after s
        for obj, item in task.FALLS.items():
            o = percept.objects.get(obj)
            if o is not None and o.lying:
                self._lying_since.setdefault(obj, percept.t)
            else:
                self._lying_since.pop(obj, None)
            fell = obj in self._lying_since and percept.t - self._lying_since[obj] >= float(s["fallen_after"]) - 1e-9
            net.set_stimulus("AML", item, float(s["fallen"]) if fell else 0.0)
        if self._habituation:
            self._apply_release_inputs()
        r = percept.robot
        if r.status.ended and self.decision is not None and (r.action is None or r.action == self.decision):
            self.release(r.status)
        self._apply_failure_inputs()
        self._apply_success_input()
        self._apply_told_input()

    def release(self, why: Status = Status.SUCCEEDED) -> None:
        """End the current decision: a transient inhibition of AEL and a habituation of the released action."""
        if self.decision is None:
            return
        rel = self.config.data["release"]
        self._release_until = self.net.t + float(rel["duration"])
        self._habituation[self.decision] = self.net.t
        if self.decision in task.MOTION_ACTIONS:
            # the executor's report: a failure into AFL and AML (see _apply_failure_inputs), a success
            # clears the action's failure memory
            if why is Status.FAILED:
                self._failures[self.decision] = self.net.t
                self._pulses[task.FAILURE_OF[self.decision]] = self.net.t
            else:
                self._failures.pop(self.decision, None)
                self._cleared[self.decision] = self.net.t
                self._succeeded_at = self.net.t
        elif self.decision == "Communicate-Error" and why is Status.SUCCEEDED and self.error in PARTNER_ERRORS:
            self._told = (self.error, self._error_reading)
        self.history.append((self.net.t, f"release ({why.value})", self.decision))
        self._released = self.decision
        self.decision = None
        self.decision_t = None
        self.error = None
        self._apply_release_inputs()

    def _apply_failure_inputs(self) -> None:
        """Inputs from the executor's failure reports: into AFL at the failed action while its report is
        fresh (its memory forms then), into AML at the action's mismatch for a pulse; into AFL a clearing
        input after a success, or once a failure is FORGET_AFTER old."""
        st = self.config.data["stimulus"]
        t = self.net.t
        for a, t0 in list(self._failures.items()):
            if t - t0 >= float(st["forget_after"]):
                del self._failures[a]
                self._cleared[a] = t
        for a in task.MOTION_ACTIONS:
            amp = 0.0
            if a in self._failures and t - self._failures[a] < float(st["report_seconds"]):
                amp = float(st["failure_report"])
            elif a in self._cleared and t - self._cleared[a] < float(st["report_seconds"]):
                amp = float(st["success_clears"])
            self.net.set_stimulus("AFL", a, amp)
        self._cleared = {a: t0 for a, t0 in self._cleared.items() if t - t0 < float(st["report_seconds"])}
        for m in task.ACTION_FAILURES:
            on = m in self._pulses and t - self._pulses[m] < float(st["pulse_seconds"])
            self.net.set_stimulus("AML", m, float(st["failure_pulse"]) if on else 0.0)

    def _apply_success_input(self) -> None:
        """SUCCESS up for ``success_seconds`` after an action of the robot's finished as it should (the executor's
        report), CSGL_past newly holds a sub-goal, or the partner is seen doing what the intention IL holds
        predicts (its act in OL, `task.INTENTION_ACTS`): the gate of learning from the user."""
        st = self.config.data["stimulus"]
        reached = set(self.peaks("CSGL_past"))
        seen = set(self.peaks("OL"))
        confirmed = {i for i in self.peaks("IL") if seen.intersection(task.INTENTION_ACTS.get(i, ()))}
        if reached - self._reached or confirmed - self._confirmed:
            self._succeeded_at = self.net.t
        self._reached, self._confirmed = reached, confirmed
        on = self.net.t - self._succeeded_at < float(st["success_seconds"])
        self.net.set_stimulus("SUCCESS", "success", float(st["success_pulse"]) if on else 0.0)

    def _apply_told_input(self) -> None:
        """Into AML at a partner's error the robot has told them of, while ASL reads no chain it did not read then:
        said once, the error is not said again while the partner goes on with the act that showed it (a partner
        whose grips mean something else, say, who goes on holding the bottle out), and the robot answers what it
        infers as it would without the error. A new reading (the partner corrects, or does something else)
        ends it; a reading lost for a moment does not."""
        if self._told is None:
            return
        error, reading = self._told
        if set(self.peaks("ASL")) - reading:
            self._told = None
            self.net.set_stimulus("AML", error, 0.0)
        else:
            self.net.set_stimulus("AML", error, float(self.config.data["stimulus"]["told"]))

    def _apply_release_inputs(self) -> None:
        rel = self.config.data["release"]
        t = self.net.t
        self._habituation = {a: t0 for a, t0 in self._habituation.items() if t - t0 < 5 * float(rel["habituation_tau"])}
        releasing = t < self._release_until
        for a in task.AEL_ITEMS:
            amp = float(rel["inhibition"]) if releasing else 0.0
            if a in self._habituation:
                amp += float(rel["habituation"]) * math.exp(-(t - self._habituation[a]) / float(rel["habituation_tau"]))
            self.net.set_stimulus("AEL", a, amp)

    # -- time ---------------------------------------------------------------------------
    def advance(self, t_target: float, readout_every: int = 4) -> None:
        """Step the fields up to time ``t_target`` (s), reading peaks every few steps."""
        dt = self.net.dt
        n = int(round((t_target - self.net.t) / dt))
        while n > 0:
            k = min(n, readout_every)
            self.net.step(k)
            n -= k
            self._readout()

    def run(self, seconds: float) -> None:
        self.advance(self.net.t + seconds)

    def update(self, percept: Percept) -> Decision:
        """Run the fields up to ``percept.t`` on the inputs held so far, then take in the percept (it acts from
        ``percept.t`` on); return the decision and the utterances of peaks that rose meanwhile."""
        self.advance(percept.t)
        self.perceive(percept)
        return self.current()

    def between(self, t: float) -> Decision:
        """Step the fields up to ``t`` without a new percept; the decision and what rose meanwhile."""
        self.advance(t)
        return self.current()

    def decisions(self) -> list[tuple[float, str, str]]:
        return list(self.history)

    def trace(self) -> dict[str, Any]:
        """The peaks of the layers a log shows, at this instant."""
        return {"peaks": {L: self.peaks(L) for L in LAYERS_SHOWN}}

    def current(self) -> Decision:
        d = Decision(
            t=self.net.t,
            action=self.decision,
            target=self.target_of(self.decision),
            new=self._new,
            released=self._released,
            error=self.error,
            utterances=self._pending,
            peaks=self._all_peaks(),
        )
        self._pending = []
        self._new = False
        self._released = None
        return d

    # -- read-out -----------------------------------------------------------------------
    def _all_peaks(self) -> dict[str, list[str]]:
        """Items above threshold per layer, strongest first: one gather over all layers (this runs every tick)."""
        thr = float(self.config.data["readout"]["threshold"])
        u = self.net.state_u[self._all_idx].tolist()
        out = {}
        for layer, (a, b) in self._all_spans.items():
            above = [(v, item) for v, item in zip(u[a:b], LAYERS[layer]) if v > thr]
            out[layer] = [item for _, item in sorted(above, key=lambda p: -p[0])]
        return out

    def _remembered_state(self, obj: str) -> str | None:
        """The state of the strongest OML peak of ``obj`` (any zone), or None without one."""
        for item in self.peaks("OML"):
            for st in task.OBJECT_STATES[obj]:
                if any(item == task.oml_item(obj, st, z) for z in task.ZONES):
                    return st
        return None

    def peaks(self, layer: str) -> list[str]:
        return self.net.peaks(layer, float(self.config.data["readout"]["threshold"]))

    def _readout(self) -> None:
        ro = self.config.data["readout"]
        thr, off, hold = float(ro["threshold"]), float(ro["off"]), float(ro["hold"])
        t = self.net.t
        if self._release_until >= 0 and t >= self._release_until:
            self._release_until = -1.0
            self._apply_release_inputs()
        u = self.net.state_u[self._spoken_idx]
        above = u > thr
        since = self._since
        since[above & (since < 0)] = t
        since[~above] = -1.0
        up = self._upv
        up[u < off] = False
        rising = above & ~up & (t - since >= hold - 1e-9)
        if rising.any():
            for i in np.nonzero(rising)[0]:
                layer, item = self._spoken_names[i]
                if self._rose(layer, item, t):
                    up[i] = True

    def _rose(self, layer: str, item: str, t: float) -> bool:
        """A pool's peak has stayed up for ``hold``: speak (and for AEL, decide). False if not taken."""
        utt = task.UTTERANCES[layer][item]
        if layer == "AEL":
            if self.decision is None and t >= self._release_until:
                u = self.net.u("AEL")[self._thr_idx["AEL"]]
                if LAYERS["AEL"][int(np.argmax(u))] == item:
                    self.decision, self.decision_t, self._new = item, t, True
                    self.history.append((t, "decide", item))
                    if item == "Communicate-Error":
                        errs = self.peaks("AML")
                        self.error = errs[0] if errs else None
                        self._error_reading = frozenset(self.peaks("ASL"))
                        if self.error:
                            e = task.UTTERANCES["AML"][self.error]
                            utt = task.Utterance("AEL", item, f"{utt.text} {e.text}", e.tag)
                else:
                    return False
            else:
                return False
        said = Said(t, layer, item, utt.text, utt.tag)
        self._pending.append(said)
        self.log.append(said)
        return True

    def target_of(self, action: str | None) -> str | None:
        if action is None:
            return None
        target = task.ROBOT_ACTION_BY_NAME[action].target
        if target == "held_out":
            acts = self.net.activities("OL")
            return "bottle" if acts["hold_out_bottle"] >= acts["hold_out_glass"] else "glass"
        return target

    # -- learning from the user ----------------------------------------------------------
    @property
    def learns(self) -> bool:
        """Whether the grip-to-chain weights learn (``learning.rate`` > 0)."""
        return float(self.config.data["learning"]["rate"]) > 0

    def learned_weights(self) -> dict[str, dict[str, dict[str, float]]]:
        """The learning couplings' weights now, {coupling: {target item: {source item: weight}}} ({} without
        learning): what `assistbot.cognition.learning` writes to a weights file."""
        return self.net.learned_tables()

    def load_weights(self, tables: Mapping[str, Any]) -> None:
        """Put weights read back from a file into the learning couplings (a `FieldError` names what is wrong)."""
        for name, table in tables.items():
            self.net.set_table(name, table)

    # -- recording ----------------------------------------------------------------------
    def record(self, layers: Iterable[str] | None = None, every: int = 4, couplings: Iterable[str] = ()):
        return self.net.record(list(layers) if layers is not None else list(LAYERS), every=every, couplings=couplings)
