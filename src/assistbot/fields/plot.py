"""Paper-style plots of recorded fields: input on top, activity below, over time."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from assistbot.fields.record import Recorder


def pyplot():
    """matplotlib.pyplot on the Agg backend (headless)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, path: str | Path) -> Path:
    """Lay out, write as PNG (creating the folder) and close a figure."""
    fig.tight_layout()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    pyplot().close(fig)
    return path


def plot_history(rec: Recorder, field: str, path: str | Path, title: str | None = None, threshold: float = 0.0) -> Path:
    """Two panels for one field: total input S (top) and activity u (bottom) over time.

    Fields with named items show one labelled line per item (the activity at
    its centre); fields without items show an image of u(x, t).
    """
    spec = rec.net.spec.fields[field]
    if spec.ndim != 1:
        from assistbot.fields.errors import FieldError

        raise FieldError(spec.where, "shape", "plot_history draws 1-D fields over time; plot_plane draws a 2-D one")
    plt = pyplot()
    t = rec.times
    fig, (ax_s, ax_u) = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    if spec.items:
        s_tr, u_tr = rec.item_traces(field, "s"), rec.item_traces(field, "u")
        cmap = plt.get_cmap("tab20" if len(spec.items) > 10 else "tab10")
        for i, item in enumerate(spec.items):
            color = cmap(i % cmap.N)
            ax_s.plot(t, s_tr[item], color=color, lw=1.4)
            ax_u.plot(t, u_tr[item], color=color, lw=1.4, label=item)
        ax_u.axhline(threshold, color="k", lw=0.6, ls="--")
        ax_u.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=7, frameon=False)
        ax_s.set_ylabel("input S")
        ax_u.set_ylabel("activity u")
    else:
        extent = (t[0], t[-1] if t[-1] > t[0] else t[0] + 1e-9, 0, spec.size * spec.dx)
        for ax, data, lab in ((ax_s, rec.s[field], "input S"), (ax_u, rec.u[field], "activity u")):
            im = ax.imshow(np.asarray(data).T, aspect="auto", origin="lower", extent=extent, cmap="viridis")
            fig.colorbar(im, ax=ax, label=lab)
            ax.set_ylabel("x")
    ax_u.set_xlabel("time (s)")
    ax_s.set_title(title or field)
    return save_figure(fig, path)


def plot_plane(panels: dict[str, np.ndarray], path: str | Path, threshold: float = 0.0) -> Path:
    """Snapshots of 2-D fields' activity side by side (x across, y up), the threshold as a contour."""
    plt = pyplot()
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.0), squeeze=False)
    for ax, (title, u) in zip(axes[0], panels.items()):
        im = ax.imshow(u, origin="lower", cmap="viridis", aspect="equal")
        if u.max() > threshold > u.min():
            ax.contour(u, levels=[threshold], colors="w", linewidths=0.8)
        fig.colorbar(im, ax=ax, label="activity u", shrink=0.8)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_title(title, fontsize=9)
    return save_figure(fig, path)


def plot_weights(rec: Recorder, coupling: str, path: str | Path, title: str | None = None) -> Path:
    """A learning coupling's table over time: one line per weight a_mj, labelled "source -> target"."""
    spec = rec.net.spec.coupling(coupling)
    src, tgt = rec.net.spec.fields[spec.source].items, rec.net.spec.fields[spec.target].items
    w = rec.weights[coupling]
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(8, 3.2))
    for i, t_item in enumerate(tgt):
        for j, s_item in enumerate(src):
            ax.plot(rec.times, w[:, i, j], lw=1.4, label=f"{s_item} -> {t_item}")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("weight a_mj")
    ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=7, frameon=False)
    ax.set_title(title or coupling)
    return save_figure(fig, path)
