"""The episode inspector: one self-contained HTML page per run, what the robot saw, thought, said and did.

`write_inspector(run_dir)` reads a run folder's files (summary.json, log.jsonl, fields.npz, video.mp4) and
writes ``inspect.html`` beside them: the video with a time cursor shared by the field heat maps (one per
layer, items labelled; a click on a pool plots its activity u and input S against the threshold), the
percept at the cursor, and one timeline of decisions, utterances, robot actions (with failure reasons)
and the person's behaviours; a click on an event seeks the video. The plotting library (plotly.js) is
inlined, and the video is referenced by its file name beside the page, so the page opens from disk with
no network. ``assistbot run`` writes it; ``assistbot inspect RUN_DIR`` rebuilds it.
"""

from __future__ import annotations

import base64
import json
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from assistbot.errors import UserError

PAGE = "inspect.html"
#: activity is sent to the page as int16 in units of 1/QUANTUM (0.01 of activity): well below what a heat map shows
QUANTUM = 100.0
#: field positions per item the heat maps keep (a peak spans several; the page's rows are a few pixels each)
ROWS_PER_ITEM = 5


def write_inspector(run_dir: str | Path) -> Path:
    """Build ``inspect.html`` in ``run_dir`` from the run's files; returns its path."""
    run = Path(run_dir)
    summary_path = run / "summary.json"
    if not summary_path.exists():
        raise UserError(str(run), "summary.json", "not a finished run folder (no summary.json); run 'assistbot run' first")
    try:
        summary = json.loads(summary_path.read_text(encoding="utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise UserError(str(summary_path), "-", f"cannot read the summary: {exc}") from None
    data = {
        "summary": _summary(summary),
        "video": "video.mp4" if (run / "video.mp4").exists() else None,
        "actions": summary.get("actions", []),
        **_log(run / "log.jsonl"),
        "fields": _fields(run / "fields.npz"),
    }
    # the data first: the library's text is not searched for the data's marker; "</" in neither ends a script
    page = (_template().replace("/*DATA*/", json.dumps(data, separators=(",", ":")).replace("</", "<\\/"))
            .replace("/*PLOTLY*/", _plotly_js().replace("</script", "<\\/script")))
    out = run / PAGE
    tmp = out.with_name(out.name + ".tmp")
    tmp.write_text(page, encoding="utf-8")
    tmp.replace(out)
    return out


def _template() -> str:
    return resources.files(__package__).joinpath("page.html").read_text(encoding="utf-8")


def _plotly_js() -> str:
    from plotly.offline import get_plotlyjs

    return get_plotlyjs()


def _summary(s: dict) -> dict:
    keys = ("scenario", "seed", "perception", "success", "end_reason", "end_detail", "time", "time_to_drink",
            "spilled_fraction", "min_distance_human", "touched_person")
    return {k: s.get(k) for k in keys}


def _log(path: Path) -> dict[str, Any]:
    """Events and percepts from log.jsonl: decisions, utterances, the person's behaviours, world events, and the
    percept of every perception tick (compact rows)."""
    decisions, said, person, world, ticks = [], [], [], [], []
    if path.exists():
        for line in path.read_text(encoding="utf-8").splitlines():
            row = json.loads(line)
            kind, t = row.get("kind"), row.get("t", 0.0)
            if kind == "decide":
                decisions.append({"t": t, "action": row["action"]})
            elif kind == "say":
                said.append({"t": t, "text": row["text"], "source": f"{row['layer']}:{row['item']}"})
            elif kind == "human":
                person.append({"t": t, "what": row["what"], "behaviour": row["behaviour"]})
            elif kind == "world":
                world.append({"t": t, "event": row.get("event"),
                              "detail": {k: v for k, v in row.items() if k not in ("t", "kind", "event", "last_good")}})
            elif kind == "tick":
                p = row["percept"]
                truth = row.get("truth")
                ticks.append([t, {o: [v["zone"], v["state"], v["seen"], v["conf"]] for o, v in p["objects"].items()},
                              [p["hand"]["posture"], p["hand"]["object"], p["hand"]["held_out"], p["hand"]["seen"]],
                              row.get("decision"),
                              row.get("human"),
                              None if truth is None else
                              [{o: [v["zone"], v["state"]] for o, v in truth["objects"].items()},
                               [truth["hand"]["posture"], truth["hand"]["object"], truth["hand"]["held_out"]]]])
    return {"decisions": decisions, "said": said, "person": person, "world": world, "ticks": ticks}


def _fields(path: Path) -> dict[str, Any] | None:
    """Per layer: times, item labels and centres, the activity over the field (samples x kept positions), u and S
    at the item centres and each coupling's part of S there (items x samples); every array as `_int16`."""
    if not path.exists():
        return None
    with np.load(path) as z:
        t = z["t"].astype(float)
        layers = sorted({k.split(".")[0] for k in z.files if k != "t"})
        out: dict[str, Any] = {"t": [round(float(v), 3) for v in t], "quantum": QUANTUM, "layers": {}}
        for layer in layers:
            u = z[f"{layer}.u"].astype(np.float32)
            items, idx = [str(i) for i in z[f"{layer}.items"]], [int(i) for i in z[f"{layer}.item_idx"]]
            keep = np.arange(0, u.shape[1], max(1, u.shape[1] // max(1, ROWS_PER_ITEM * len(items))))
            out["layers"][layer] = {
                "items": items,
                "item_idx": idx,
                "rows": keep.tolist(),      # the field positions the heat map shows
                "u": _int16(u[:, keep]),
                "u_items": _int16(z[f"{layer}.u_items"].T),
                "s_items": _int16(z[f"{layer}.s_items"].T),
                # each incoming coupling's part of S at the items, where recorded and not all zero
                "inputs": {k.split(".in.", 1)[1]: _int16(z[k].T) for k in z.files if k.startswith(f"{layer}.in.") and np.any(z[k])},
            }
    return out


def _int16(a: np.ndarray) -> str:
    """An array as little-endian int16 in units of 1/QUANTUM, row-major, base64 (the page decodes it)."""
    q = np.clip(np.round(np.asarray(a, np.float32) * QUANTUM), -32767, 32767).astype("<i2")
    return base64.b64encode(np.ascontiguousarray(q).tobytes()).decode("ascii")

