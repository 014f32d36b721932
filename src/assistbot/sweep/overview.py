"""Several sweeps side by side, split by one parameter: `assistbot report DIR DIR ... --by agent --out OUT`.

Each sweep varies one thing (a perturbation, say) besides ``by``; the overview puts them in one figure and one
Markdown file, so that a comparison spread over several sweep folders (``make dnf-vs-fsm``: one per perturbation)
reads at a glance:

    overview.md    per sweep, the table of `report._by_table` (success with its Wilson CI, time to drink, failed
                   actions per episode, errors told, the share of cued decisions that ignored the cue, the decisions
                   taken with no cue showing), one row per (level, value of ``by``)
    overview.png   one column per swept parameter: success rate (Wilson 95% CI) on top, robot actions failed per
                   episode below, one line per value of ``by``
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from assistbot.errors import UserError
from assistbot.sweep.report import _by_table, _fmt_value, _key, _numeric, _ordered, load_results, rate_errorbars, table_rows, varied_params


def write_overview(results_dirs: list[str | Path], by: str, out: str | Path) -> list[Path]:
    """Write overview.md and overview.png into ``out``; return their paths."""
    out_dir = Path(out)
    panels: list[tuple[str, str, list[dict[str, Any]]]] = []  # (sweep name, factor, rows)
    md = [f"# {len(results_dirs)} sweeps by {by}", ""]
    for d in results_dirs:
        params, rows = load_results(d)
        if by not in params:
            raise UserError(str(d), "--by", f"{by} is not a swept parameter there; its parameters: {', '.join(params)}")
        name = Path(d).stem if Path(d).suffix == ".csv" else Path(d).name
        factors = varied_params(params, rows, skip=(by,))
        scenarios = list(dict.fromkeys(r["scenario"] for r in rows))
        seeds = max(len({r.get("seed") for r in rows if r["scenario"] == s}) for s in scenarios)
        md += [f"## {name}", "", f"{len(rows)} episodes: {len(scenarios)} scenarios x {seeds} seed(s), "
               f"{' x '.join(factors) or '(nothing else varied)'} x {by}.", ""]
        for f in factors:
            md += _by_table(rows, f, by) + [""]
            panels.append((name, f, rows))
    out_dir.mkdir(parents=True, exist_ok=True)
    page = out_dir / "overview.md"
    png = out_dir / "overview.png"
    md += [f"![{by} over every sweep]({png.name})", ""]
    page.write_text("\n".join(md), encoding="utf-8")
    _plot(panels, by, png)
    return [page, png]


def _plot(panels: list[tuple[str, str, list[dict[str, Any]]]], by: str, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = max(1, len(panels))
    fig, axes = plt.subplots(2, n, figsize=(3.6 * n, 6.0), constrained_layout=True, squeeze=False)
    for j, (name, factor, rows) in enumerate(panels):
        values = _ordered([r.get(factor) for r in rows])
        numeric = _numeric(values)
        x_of = {_key(v): (v if numeric else i) for i, v in enumerate(values)}
        top, bottom = axes[0][j], axes[1][j]
        for b in _ordered([r.get(by) for r in rows]):
            cells = table_rows([r for r in rows if _key(r.get(by)) == _key(b)], factor)
            xs = [x_of[_key(v)] for v, _ in cells]
            top.errorbar(xs, [c.rate for _, c in cells], yerr=rate_errorbars(cells), marker="o", capsize=3, label=f"{by} = {_fmt_value(b)}")
            bottom.plot(xs, [c.failed_mean for _, c in cells], marker="^", label=f"{by} = {_fmt_value(b)}")
        top.set_title(name, fontsize=10)
        top.set_ylim(-0.05, 1.05)
        bottom.set_xlim(top.get_xlim())
        bottom.set_ylim(bottom=0)
        bottom.set_xlabel(factor)
        for ax in (top, bottom):
            ax.grid(alpha=0.3)
            if not numeric:
                ax.set_xticks(range(len(values)), [_fmt_value(v) for v in values], rotation=20)
        if j == 0:
            top.set_ylabel("success rate (95% Wilson CI)")
            bottom.set_ylabel("robot actions failed per episode")
            top.legend(fontsize=8)
    fig.savefig(path, dpi=100)
    plt.close(fig)
