"""All parameters of the cognitive architecture in one nested dict, addressable by dotted path.

`default_config()` builds it from `assistbot.task`: the fields (tau, h,
kernel ...), the couplings (gain ``k`` and table a_mj copied from the task's
association weights), the percept-to-stimulus amplitudes, the read-out and
the release of decisions. `CognitionConfig.set("fields.AEL.h", -4)`,
``set("k", 0.8)`` (global coupling scale), ``set("couplings.IL->AEL.table.Request-glass.Give-glass", 1.2)``
or ``set("readout.hold", 0.2)`` change one value; a leading ``cognition.`` is
accepted so sweep files can address ``cognition.k``. Unknown paths raise
`UserError` naming the path and what is known there.

Field regimes (see eq. 1-3): "memory" fields keep a peak without input
(self-excitation A*sigma*sqrt(2 pi) well above -h): OML (objects), AEL
(the decision until released). "Detection" fields form peaks only while
driven: OL (a trace of the acts seen, fading over tau), CSGL past/future (several peaks),
CSGL present, ASL, IL, AML (one winner each, global inhibition).
"""

from __future__ import annotations

import copy
from typing import Any, Mapping

from assistbot import task
from assistbot.errors import UserError

WHERE = "cognition config"
#: positions per item: beyond this a layer's size (items x spacing) costs memory and time for no finer behaviour
MAX_SPACING = 200

#: layer -> items, in the order they lie along the field
LAYERS: dict[str, tuple[str, ...]] = {
    "OL": task.OL_ITEMS,
    "OML": task.OML_ITEMS,
    "CSGL_past": task.SUBGOALS,
    "CSGL_present": task.SUBGOALS,
    "CSGL_future": task.SUBGOALS,
    "INI": ("take-initiative",),
    "URGE": ("urge",),
    "ASL": task.ASL_ITEMS,
    "IL": task.IL_ITEMS,
    "AFL": task.MOTION_ACTIONS,
    "SUCCESS": ("success",),
    "AML": task.AML_ITEMS,
    "AEL": task.AEL_ITEMS,
}


def _field(tau: float, h: float, A: float, w_inhib: float, sigma: float = 1.5, input_sigma: float = 1.5) -> dict[str, Any]:
    return {"tau": tau, "h": h, "beta": 4.0, "u0": 0.0, "kernel": {"A": A, "sigma": sigma, "w_inhib": w_inhib},
            "input_sigma": input_sigma, "noise": 0.0}


def _table(rows: Mapping[str, Mapping[str, float]]) -> dict[str, dict[str, float]]:
    return {t: {s: float(w) for s, w in row.items() if w != 0} for t, row in rows.items() if any(w != 0 for w in row.values())}


def default_config() -> dict[str, Any]:
    """The architecture's parameters, tables built from the task's association weights."""
    fields = {
        # memory fields: a peak once formed stays without input
        # OL: a trace of the motor acts seen, decaying over ~tau once the act is no longer seen
        "OL": _field(0.25, -3.0, 0.8, 0.0, input_sigma=2.0),
        # OML: memory; percept inputs are wide (sigma 4), so that evidence against an item reaches the
        # flanks of its peak, not just its centre.  Its items are 25 positions apart (its own spacing:
        # the global one does not apply to it): a peak left alone (the other object's memory erased by
        # conflicting views: the glass turned in the gripper, seen inverted, then empty) is ~22 wide
        # (Amari: (A sigma sqrt(pi/2) + h) / w_inhib) and at 10 apart lit its neighbour item (an open
        # bottle in the RWS became one in the HWS too).  Couplings read items at their centres, so
        # the wider spacing leaves the peaks and what they drive as they were
        "OML": {**_field(0.1, -3.0, 4.0, 0.2, input_sigma=4.0), "spacing": 25},
        # CSGL: driven by evidence and task drive, several peaks (past, future) or one (present)
        "CSGL_past": _field(0.1, -3.0, 0.8, 0.0),
        "CSGL_present": _field(0.1, -3.0, 0.8, 0.6),
        "CSGL_future": _field(0.1, -3.0, 0.8, 0.0),
        # the robot's initiative: rises slowly while the partner shows no motor act
        "INI": _field(1.0, -3.0, 0.0, 0.0),
        # the slow part of the initiative: builds up over ~10 s while no action runs, whatever the partner
        # shows, so that a partner who holds still (a passive one, or one waiting with something held out)
        # never leaves the robot without a decision; a running action keeps it down
        "URGE": _field(10.0, -3.0, 0.0, 0.0),
        # action simulation, intention, monitoring: one winner each, only while driven
        "ASL": _field(0.08, -3.0, 0.8, 0.6),
        "IL": _field(0.08, -3.0, 0.8, 0.6),
        # action failure layer: the memory of an action of the robot's that failed, formed slowly from the
        # executor's failure report (so that it is not there yet when that report reaches AML) and kept
        # while the situation stands; cleared when the action succeeds, forgotten after a while
        "AFL": {**_field(2.5, -3.0, 4.0, 0.2, input_sigma=1.0), "spacing": 25},
        "AML": _field(0.05, -3.0, 0.8, 0.6),
        # the robot's sense of success: up for a moment when an action of its own finished as it should or a
        # sub-goal was reached; the gate of learning from the user (`learning`)
        "SUCCESS": _field(0.05, -3.0, 0.0, 0.0),
        # action execution: competition, and the winner sustains itself until released
        "AEL": _field(0.12, -4.5, 4.0, 1.0),
    }
    chains = task.ASL_CHAINS
    intents = task.INTENTIONS
    errors = task.ERRORS
    actions = task.ROBOT_ACTIONS
    pre = task.PRECONDITIONS
    couplings = {
        "OML->CSGL_past": ("OML", "CSGL_past", 5.0, {g: {o: 1.0 for o in obs} for g, obs in task.ACHIEVED_BY.items()}),
        # present: achieved goals leave it, achieved preconditions enable the next ones
        "CSGL_past->CSGL_present": ("CSGL_past", "CSGL_present", 1.0,
                                    {g: {**{p: 2.0 / len(pre[g]) for p in pre[g]}, g: -8.0} for g in task.SUBGOALS}),
        "CSGL_past->CSGL_future": ("CSGL_past", "CSGL_future", 1.0, {g: {g: -8.0} for g in task.SUBGOALS}),
        "CSGL_present->CSGL_future": ("CSGL_present", "CSGL_future", 1.0, {g: {g: -8.0} for g in task.SUBGOALS}),
        "OL->INI": ("OL", "INI", 1.0, {"take-initiative": {i: -8.0 for i in task.OL_ITEMS}}),
        "OL->ASL": ("OL", "ASL", 1.2, {c.name: c.primitives for c in chains}),
        "OML->ASL": ("OML", "ASL", 1.2, {c.name: c.objects for c in chains}),
        "CSGL_present->ASL": ("CSGL_present", "ASL", 1.2, {c.name: c.subgoals for c in chains}),
        "ASL->IL": ("ASL", "IL", 1.6, {i.name: i.chains for i in intents}),
        "CSGL_present->IL": ("CSGL_present", "IL", 1.6, {i.name: i.subgoals for i in intents}),
        "OML->IL": ("OML", "IL", 1.6, {i.name: i.objects for i in intents}),
        "IL->AML": ("IL", "AML", 2.0, {e.name: e.intentions for e in errors}),
        # a failure reported while the memory of an earlier one of the same action stands: a mismatch
        "AFL->AML": ("AFL", "AML", 1.0, {m: {a: 2.0 for a, f in task.FAILURE_OF.items() if f == m} for m in task.ACTION_FAILURES}),
        "ASL->AML": ("ASL", "AML", 2.0, {e.name: e.chains for e in errors}),
        "OML->AML": ("OML", "AML", 2.0, {e.name: e.objects for e in errors}),
        "IL->AEL": ("IL", "AEL", 1.3, {a.name: a.intentions for a in actions}),
        # an action's own object evidence, and evidence against it where its requirements are not met
        "OML->AEL": ("OML", "AEL", 1.3, {a.name: {**{o: task.AGAINST_REQUIREMENT for o in task.facts_against(a)}, **a.objects}
                                         for a in actions}),
        "CSGL_present->AEL": ("CSGL_present", "AEL", 1.3, {a.name: a.present for a in actions}),
        "CSGL_past->AEL": ("CSGL_past", "AEL", 1.3, {a.name: a.past for a in actions}),
        "AML->AEL": ("AML", "AEL", 1.3, {a.name: {**a.errors, **a.failures} for a in actions}),
        # the failed action habituates for as long as its failure is remembered
        "AFL->AEL": ("AFL", "AEL", 1.3, {a: {a: -1.0} for a in task.MOTION_ACTIONS}),
        "INI->AEL": ("INI", "AEL", 1.3, {a.name: {"take-initiative": a.initiative} for a in actions}),
        "AEL->URGE": ("AEL", "URGE", 1.0, {"urge": {a.name: -5.0 for a in actions}}),
        "URGE->AEL": ("URGE", "AEL", 1.3, {a.name: {"urge": 2.0 * a.initiative} for a in actions}),
    }
    return {
        "dt": 0.005,
        "spacing": 10,
        "k": 1.0,
        "fields": fields,
        "couplings": {name: {"source": s, "target": t, "k": k, "table": _table(tab)} for name, (s, t, k, tab) in couplings.items()},
        "stimulus": {
            "ol": 6.0,            # an observed motor primitive (times confidence)
            "ol_rest": -5.0,       # hand at rest: the act is over, its trace fades faster
            "oml": 8.0,           # an object seen in a state and zone
            "oml_against": -10.0,  # the same object seen elsewhere / in another state
            "ini_drive": 4.0,     # tonic drive of the initiative node
            "urge_drive": 5.0,    # tonic drive of the urge node: it crosses threshold ~9 s after an action ends
            # the executor's report of a failed action: into AFL at the action for report_seconds (the
            # memory forms after ~2.3 s), and into AML at the action's mismatch for pulse_seconds (below
            # threshold alone, above it with the memory of an earlier failure of the same action)
            "failure_report": 5.0, "report_seconds": 3.0,
            # into AML at a partner's error once told, while the partner goes on with the act that showed it
            "told": -6.0,
            "failure_pulse": 2.0, "pulse_seconds": 1.5,
            "success_clears": -20.0,  # into AFL at an action that finished (for report_seconds): its failure is past
            # into SUCCESS when a motion action finished as it should, a sub-goal was newly reached or the partner
            # was seen doing what the inferred intention predicts
            "success_pulse": 5.0, "success_seconds": 1.5,
            "forget_after": 90.0,     # s after its last failure an action's memory is let go
            # an object seen lying on its side, into AML at its fall once seen so for fallen_after s (a
            # misread frame, or a tipping object that rights itself, is not a fall)
            "fallen": 5.0, "fallen_after": 1.0,
            # task drive of the present sub-goals: open before turn (priority), fill and hand-over only when enabled
            "present_drive": {"Open-bottle": 3.8, "Turn-glass": 3.5, "Fill-glass": 1.7, "Hand-over-full-glass": 1.7},
            "future_drive": 4.0,
        },
        "readout": {
            "threshold": 0.5,     # centre activity above which a pool counts as a peak
            "off": 0.0,           # ... and below which it counts as gone (hysteresis for "once per rise")
            "hold": 0.1,          # s a peak must stay up before it is a decision / is spoken
        },
        # learning from the user: which chain of the partner a grip on an object means (the OL -> ASL weights
        # of the grip items), learnt while SUCCESS is up, from the grip in hand (GRIP) and the chain ASL read
        # last (its memory trace); see `assistbot.cognition.learning`. rate 0: no learning, no GRIP, no trace
        "learning": {
            "rate": 0.0,            # per s; `--learn` sets it to learning.LEARNING_RATE
            "decay": 1.0,           # per s: a grip's weight onto the chain read relaxes toward rate/decay ...
            "highest": 1.0,         # ... within [0, highest], the priors' own range,
            "keep": 0.5,            # ... keeping half its prior: a reading given up once is not unlearnt outright
            "post_threshold": 0.05,  # a chain whose trace is below this took no part and keeps its weight
            "trace_build": 0.2,     # s: ASL's trace builds within a reading held this long ...
            "reading_memory": 2.0,  # s: ... and fades soon once another reading has replaced it
            "grip_hold": 6.0,       # OL -> GRIP: a grip seen sets the grip in hand ...
            "grip_end": -8.0,       # ... and ends any other, as a reach, a pointing or a request does
        },
        "release": {
            "inhibition": -10.0,  # input to all of AEL while a finished/failed decision is released
            "duration": 0.3,      # s
            "habituation": -3.0,  # input at the released action, decaying ...
            "habituation_tau": 4.0,  # ... with this time constant (s), so the same act is not repeated at once
        },
    }


class CognitionConfig:
    """The nested parameter dict with dotted-path access (see the module docstring)."""

    def __init__(self, data: Mapping[str, Any] | None = None) -> None:
        self.data: dict[str, Any] = copy.deepcopy(dict(data)) if data is not None else default_config()

    @staticmethod
    def _parts(path: str) -> list[str]:
        if not isinstance(path, str) or not path:
            raise UserError(WHERE, str(path), "a parameter path is a dotted string like 'fields.AEL.h'")
        if path.startswith("cognition."):
            path = path[len("cognition."):]
        return path.split(".")

    def _walk(self, path: str, create_leaf: bool = False) -> tuple[dict, str]:
        parts = self._parts(path)
        node: Any = self.data
        for i, p in enumerate(parts[:-1]):
            if not isinstance(node, dict) or p not in node:
                known = ", ".join(sorted(node)) if isinstance(node, dict) else "(a value, not a group)"
                raise UserError(WHERE, path, f"unknown key {p!r} at '{'.'.join(parts[:i]) or '(top)'}'; known: {known}")
            node = node[p]
        leaf = parts[-1]
        if not isinstance(node, dict):
            raise UserError(WHERE, path, f"'{'.'.join(parts[:-1])}' is a value, not a group")
        if leaf not in node:
            if create_leaf and self._is_table_entry(parts):
                return node, leaf
            raise UserError(WHERE, path, f"unknown key {leaf!r}; known: {', '.join(sorted(node))}")
        if isinstance(node[leaf], dict):
            raise UserError(WHERE, path, f"is a group; give one of: {', '.join(sorted(node[leaf]))}")
        return node, leaf

    def _is_table_entry(self, parts: list[str]) -> bool:
        # couplings.<name>.table.<target item>.<source item>: any item pair of the two layers may be set
        if len(parts) != 5 or parts[0] != "couplings" or parts[2] != "table":
            return False
        c = self.data["couplings"][parts[1]]
        if parts[3] not in LAYERS[c["target"]]:
            raise UserError(WHERE, ".".join(parts), f"unknown item {parts[3]!r} of {c['target']}; known: {', '.join(LAYERS[c['target']])}")
        if parts[4] not in LAYERS[c["source"]]:
            raise UserError(WHERE, ".".join(parts), f"unknown item {parts[4]!r} of {c['source']}; known: {', '.join(LAYERS[c['source']])}")
        return True

    def get(self, path: str) -> Any:
        node, leaf = self._walk(path)
        return node[leaf]

    def set(self, path: str, value: Any) -> None:
        parts = self._parts(path)
        if len(parts) == 5 and parts[0] == "couplings" and parts[2] == "table" and parts[1] in self.data["couplings"]:
            table = self.data["couplings"][parts[1]]["table"]
            if parts[3] not in table and parts[3] in LAYERS[self.data["couplings"][parts[1]]["target"]]:
                table[parts[3]] = {}
        node, leaf = self._walk(path, create_leaf=True)
        old = node.get(leaf)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise UserError(WHERE, path, f"must be a number, got {value!r}")
        if isinstance(old, int) and not isinstance(old, bool) and leaf == "spacing":
            if not (2 <= value <= MAX_SPACING) or int(value) != value:
                raise UserError(WHERE, path, f"must be a whole number from 2 to {MAX_SPACING}, got {value!r}")
            value = int(value)
        node[leaf] = value

    def paths(self) -> list[str]:
        """Every settable leaf path."""
        out: list[str] = []

        def walk(node: Any, prefix: str) -> None:
            for key, v in node.items():
                p = f"{prefix}.{key}" if prefix else key
                if isinstance(v, dict):
                    walk(v, p)
                elif not isinstance(v, str):
                    out.append(p)

        walk(self.data, "")
        return out

    def update(self, overrides: Mapping[str, Any]) -> "CognitionConfig":
        for path, value in overrides.items():
            self.set(path, value)
        return self

    def network_dict(self) -> dict[str, Any]:
        """The `assistbot.fields.Network.from_dict` description, global ``k`` folded into each coupling."""
        d = self.data
        fields = {name: {"items": list(LAYERS[name]), "spacing": int(d["spacing"]), **copy.deepcopy(p)} for name, p in d["fields"].items()}
        couplings = [
            {"name": name, "source": c["source"], "target": c["target"], "k": float(d["k"]) * float(c["k"]),
             "table": copy.deepcopy(c["table"])}
            for name, c in d["couplings"].items()
        ]
        if float(d["learning"]["rate"]) > 0:
            self._add_learning(fields, couplings)
        return {"dt": d["dt"], "fields": fields, "couplings": couplings}

    def _add_learning(self, fields: dict[str, Any], couplings: list[dict[str, Any]]) -> None:
        """What learning from the user adds; none of it drives a field the architecture decides with, so the
        decisions are the priors' until a weight has moved."""
        d = self.data
        learn = d["learning"]
        # GRIP: the grip in hand, a memory of the grip seen as an object was taken, held through what is done with
        # it (a hold-out, a pour, a rest while the robot takes it) and ended by another grip on the same object or
        # a new act (reach, pointing, request); a grip read on the other object meanwhile (the hand with the bottle
        # beside the glass) leaves it be (a memory field as OML is: its own wide spacing and a little global
        # inhibition keep a peak from spreading)
        fields["GRIP"] = {"items": list(task.OL_GRIP_ITEMS), **_field(0.1, -3.0, 4.0, 0.2, input_sigma=1.0), "spacing": 25}
        hold, end = float(learn["grip_hold"]), float(learn["grip_end"])
        new_acts = [i for i in task.OL_ITEMS if i.startswith(("reach_", "point_")) or i == "open_hand_request"]
        same_object = {f"{g}_{o}": [f"{h}_{p}" for h, p in task.GRIP_PRIORS if p == o and h != g] for g, o in task.GRIP_PRIORS}
        couplings.append({"name": "OL->GRIP", "source": "OL", "target": "GRIP", "k": 1.0,
                          "table": {g: {**{o: end for o in same_object[g]}, **{a: end for a in new_acts}, g: hold}
                                    for g in task.OL_GRIP_ITEMS}})
        # ASL's trace, for the learning rule only: amplitude 0 keeps it out of the field's dynamics
        fields["ASL"]["memory"] = {"tau_build": float(learn["trace_build"]), "tau_decay": float(learn["reading_memory"]),
                                   "amplitude": 0.0, "threshold": 0.5}
        ol_asl = next(c for c in couplings if c["name"] == "OL->ASL")
        ol_asl["learn"] = {"rate": float(learn["rate"]), "decay": float(learn["decay"]), "gate": "SUCCESS.success",
                           "bounds": [0.0, float(learn["highest"])], "keep": float(learn["keep"]), "traces": "post",
                           "pre": "GRIP",
                           "targets": {grip: list(chains) for grip, chains in task.GRIP_CHAINS.items()},
                           "post_threshold": float(learn["post_threshold"])}

    def copy(self) -> "CognitionConfig":
        return CognitionConfig(self.data)


def check_overrides(overrides: Mapping[str, Any], where: str) -> None:
    """Overrides of the field architecture (paths without ``cognition.``): each a number the configuration takes,
    all together a network the field library accepts (finite, stable steps). A mistake is a UserError naming the
    override's path."""
    from assistbot.fields.errors import FieldError
    from assistbot.fields.spec import NetworkSpec

    cfg = CognitionConfig()
    for path, value in overrides.items():
        try:
            cfg.set(path, value)
        except UserError as exc:
            raise UserError(where, f"cognition.{path}", exc.message) from None
    try:
        NetworkSpec.from_dict(cfg.network_dict())
    except FieldError as exc:
        named = [p for p in overrides if p == exc.key or p.endswith("." + exc.key)] or list(overrides)
        raise UserError(where, ", ".join(f"cognition.{p}" for p in named), f"{exc.message} (in {exc.where})") from None
