"""The seed's figures from a field recording: ASL and AEL input/activity (Fig. 3 B, C), CSGL past/present/future
(Fig. 4/5 B). They need the recording, the decision history (to mark it) and a name for the titles, whether the
run was a timeline replay or a closed-loop episode."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Iterable

from assistbot.fields.plot import pyplot as _pyplot, save_figure

History = Iterable[tuple[float, str, str]]


def plot_csgl(rec: Any, history: History, path: str | Path, title: str) -> Path:
    """Three panels, CSGL past / present / future: activity at each sub-goal over time."""
    plt = _pyplot()
    t = rec.times
    fig, axes = plt.subplots(3, 1, figsize=(8, 6), sharex=True)
    for ax, layer, label in zip(axes, ("CSGL_past", "CSGL_present", "CSGL_future"), ("CSGL - Past", "CSGL - Present", "CSGL - Future")):
        for item, trace in rec.item_traces(layer, "u").items():
            ax.plot(t, trace, lw=1.4, label=item)
        ax.axhline(0.0, color="k", lw=0.6, ls="--")
        ax.set_ylabel(label)
    axes[0].legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=7, frameon=False)
    _mark_decisions(history, axes)
    axes[-1].set_xlabel("time (s)")
    axes[0].set_title(title)
    return save_figure(fig, path)


def plot_layer(rec: Any, history: History, layer: str, path: str | Path, title: str) -> Path:
    """Input (top) and activity (bottom) of one layer, one line per item, decisions marked."""
    plt = _pyplot()
    t = rec.times
    fig, (ax_s, ax_u) = plt.subplots(2, 1, figsize=(9, 5.5), sharex=True)
    s_tr, u_tr = rec.item_traces(layer, "s"), rec.item_traces(layer, "u")
    items = list(u_tr)
    cmap = plt.get_cmap("tab20" if len(items) > 10 else "tab10")
    for i, item in enumerate(items):
        color = cmap(i % cmap.N)
        ax_s.plot(t, s_tr[item], color=color, lw=1.3)
        ax_u.plot(t, u_tr[item], color=color, lw=1.3, label=item)
    ax_u.axhline(0.0, color="k", lw=0.6, ls="--")
    ax_s.set_ylabel("input S")
    ax_u.set_ylabel("activity u")
    ax_u.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=7, frameon=False)
    _mark_decisions(history, (ax_s, ax_u))
    ax_u.set_xlabel("time (s)")
    ax_s.set_title(title)
    return save_figure(fig, path)


def _mark_decisions(history: History, axes) -> None:
    for t, kind, action in history:
        for ax in axes:
            ax.axvline(t, color="tab:red" if kind == "decide" else "0.6", lw=0.8, ls=":")
        if kind == "decide":
            axes[0].annotate(action, (t, 1.0), xycoords=("data", "axes fraction"), fontsize=6, rotation=90,
                             va="top", ha="right", color="tab:red")


#: the figures `write_figures` writes: file -> (layer, what it shows); the CSGL's three layers share one
FIGURES = {
    "asl.png": ("ASL", "action simulation layer (ASL) - input and activity"),
    "ael.png": ("AEL", "action execution layer (AEL) - input and activity"),
    "csgl.png": ("CSGL", "CSGL past / present / future"),
    "il.png": ("IL", "intention layer (IL)"),
    "aml.png": ("AML", "action monitoring layer (AML)"),
    "oml.png": ("OML", "object memory layer (OML)"),
}


def write_figures(name: str, recorder: Any, history: History, out: str | Path) -> list[Path]:
    """All figures of a field recording into ``out`` (FIGURES): ASL, AEL, IL, AML (input + activity), CSGL, OML."""
    out, h = Path(out), list(history)
    return [plot_csgl(recorder, h, out / file, f"{name}: {what}") if layer == "CSGL"
            else plot_layer(recorder, h, layer, out / file, f"{name}: {what}")
            for file, (layer, what) in FIGURES.items()]
