"""`assistbot report DIR`: a sweep's results as tables with confidence intervals, plots and Markdown.

Writes into DIR/report/ (or ``out``):

    report.md                    the summary: overall, one table per parameter, heatmaps, decision sequences
    report.html                  the same as a page, with every episode's row (linked to its inspector page
                                 when the sweep kept its run folder: `assistbot sweep --keep-runs`)
    summary.csv                  every table row of report.md (factor, value, n, rate with its Wilson CI, ...)
    success_vs_<path>.png        success rate (Wilson 95% CI) and time to drink (t 95% CI) per value
    heatmap_<path1>__<path2>.png success rate over two parameters, each cell annotated with its n

A parameter's table pools every other parameter and every seed: it is the marginal effect.
"""

from __future__ import annotations

import csv
import itertools
import math
from collections import Counter, defaultdict
from pathlib import Path
from typing import Any

from assistbot import catalogue
from assistbot.errors import UserError
from assistbot.sweep.results import param_columns, parse_value, read_rows
from assistbot.sweep.stats import Cell

TEXT_COLUMNS = ("job_id", "scenario", "perception", "end_reason", "end_detail", "decisions", "scenario_sha")
MAX_HEATMAPS = 6


def load_results(results_dir: str | Path) -> tuple[list[str], list[dict[str, Any]]]:
    """(swept paths, typed rows) of a sweep folder (or of a results.csv file)."""
    d = Path(results_dir)
    path = d if d.suffix == ".csv" else d / "results.csv"
    if not path.exists():
        raise UserError(str(d), "results.csv", "not found; run 'assistbot sweep ... --out DIR' first")
    header, raw = read_rows(path)
    if not raw:
        raise UserError(str(path), "rows", "no finished episodes yet")
    params = param_columns(header)
    rows = []
    for r in raw:
        rows.append({k: (v if k in TEXT_COLUMNS else parse_value(v)) for k, v in r.items()})
    return params, rows


def _key(v: Any) -> Any:
    return tuple(v) if isinstance(v, list) else v


def _fmt_value(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:g}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_fmt_value(c) for c in v) + "]"
    return str(v)


def _ordered(values: list[Any]) -> list[Any]:
    uniq = list(dict.fromkeys(_key(v) for v in values))
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in uniq):
        return sorted(uniq)
    return uniq


def _numeric(values: list[Any]) -> bool:
    return all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)


def _f(x: float, digits: int = 2) -> str:
    return "–" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{digits}f}"


def _ci(lo: float, hi: float, digits: int = 2) -> str:
    return "–" if math.isnan(lo) or math.isnan(hi) else f"[{lo:.{digits}f}, {hi:.{digits}f}]"


def _safe(path: str) -> str:
    return "".join(c if c.isalnum() or c in "._-" else "_" for c in path)


def varied_params(params: list[str], rows: list[dict], skip: tuple[str, ...] = ()) -> list[str]:
    """The swept parameters, but for ``skip``, that take more than one value in ``rows``."""
    return [p for p in params if p not in skip and len(_ordered([r.get(p) for r in rows])) > 1]


def rate_errorbars(cells: list[tuple[Any, Cell]]) -> list[list[float]]:
    """Matplotlib's ``yerr`` for the success rates of ``cells``: the distances down and up to the Wilson bounds."""
    return [[max(0.0, c.rate - c.rate_low) for _, c in cells], [max(0.0, c.rate_high - c.rate) for _, c in cells]]


def table_rows(rows: list[dict], factor: str) -> list[tuple[Any, Cell]]:
    groups: dict[Any, list[dict]] = defaultdict(list)
    for r in rows:
        groups[_key(r.get(factor))].append(r)
    return [(v, Cell.of(groups[v])) for v in _ordered([r.get(factor) for r in rows])]


def _by_table(rows: list[dict], factor: str, by: str) -> list[str]:
    """``factor``'s values x ``by``'s values: success (Wilson), time to drink, failed actions per episode, the
    share of decisions taken with a cue of the person's showing that ignored it, and the decisions per episode
    taken with none showing (`assistbot.episode.cues`)."""
    out = [f"| {factor} | {by} | n | drank | success rate | 95% CI (Wilson) | time to drink (s) | 95% CI (t) | "
           "failed actions per episode | errors communicated | cue ignored (share of cued decisions) | "
           "decisions without a cue per episode |", "|---|---|---:|---:|---:|---|---:|---|---:|---:|---:|---:|"]
    for v in _ordered([r.get(factor) for r in rows]):
        for b, c in table_rows([r for r in rows if _key(r.get(factor)) == v], by):
            out.append(f"| {_fmt_value(v)} | {_fmt_value(b)} | {c.n} | {c.successes} | {_f(c.rate)} | "
                       f"{_ci(c.rate_low, c.rate_high)} | {_f(c.ttd_mean, 1)} | {_ci(c.ttd_low, c.ttd_high, 1)} | "
                       f"{_f(c.failed_mean)} | {_f(c.errors_mean)} | {_f(c.ignored_share)} | {_f(c.uncued_mean)} |")
    return out


def _markdown_table(factor: str, cells: list[tuple[Any, Cell]]) -> list[str]:
    out = [f"| {factor} | n | drank | success rate | 95% CI (Wilson) | time to drink (s) | 95% CI (t) | decisions | "
           "errors communicated | spilled | min distance (m) |",
           "|---|---:|---:|---:|---|---:|---|---:|---:|---:|---:|"]
    for v, c in cells:
        out.append(f"| {_fmt_value(v)} | {c.n} | {c.successes} | {_f(c.rate)} | {_ci(c.rate_low, c.rate_high)} | "
                   f"{_f(c.ttd_mean, 1)} | {_ci(c.ttd_low, c.ttd_high, 1)} | {_f(c.decisions_mean, 1)} | "
                   f"{_f(c.errors_mean)} | {_f(c.spilled_mean, 3)} | {_f(c.min_distance, 3)} |")
    return out


def _plot_param(rows: list[dict], param: str, scenarios: list[str], path: Path, by: str | None = None) -> None:
    """Success and time to drink against ``param``: one line per scenario, or per value of ``by`` (then with two
    more panels: the robot actions that failed per episode, and the share of cued decisions that ignored the cue)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    values = _ordered([r.get(param) for r in rows])
    numeric = _numeric(values)
    xs_of = {v: (v if numeric else i) for i, v in enumerate(values)}
    fig, axes = plt.subplots(1, 4 if by else 2, figsize=(19 if by else 10, 3.8), constrained_layout=True)
    ax1, ax2 = axes[0], axes[1]
    if by:
        groups = [(f"{by} = {_fmt_value(b)}", [r for r in rows if _key(r.get(by)) == b]) for b in _ordered([r.get(by) for r in rows])]
    else:
        groups = [(s, [r for r in rows if r["scenario"] == s]) for s in scenarios] if len(scenarios) > 1 else [("all", rows)]
    for label, grp in groups:
        if by:
            cells_f = table_rows(grp, param)
            axes[2].plot([xs_of[v] for v, _ in cells_f], [c.failed_mean for _, c in cells_f], marker="^", label=label)
            axes[3].plot([xs_of[v] for v, _ in cells_f], [c.ignored_share for _, c in cells_f], marker="v", label=label)
        cells = [(v, c) for v, c in table_rows(grp, param)]
        xs = [xs_of[v] for v, _ in cells]
        rate = [c.rate for _, c in cells]
        ax1.errorbar(xs, rate, yerr=rate_errorbars(cells), marker="o", capsize=4, label=label if len(groups) > 1 else None)
        ttd = [(xs_of[v], c) for v, c in cells if not math.isnan(c.ttd_mean)]
        if ttd:
            tx = [x for x, _ in ttd]
            ty = [c.ttd_mean for _, c in ttd]
            terr = [[0 if math.isnan(c.ttd_low) else max(0.0, c.ttd_mean - c.ttd_low) for _, c in ttd],
                    [0 if math.isnan(c.ttd_high) else max(0.0, c.ttd_high - c.ttd_mean) for _, c in ttd]]
            ax2.errorbar(tx, ty, yerr=terr, marker="s", capsize=4, label=label if len(groups) > 1 else None)
    ax1.set_ylim(-0.05, 1.05)
    ax1.set_ylabel("success rate (95% Wilson CI)")
    ax2.set_ylabel("time to drink, s (mean, 95% CI)")
    ax2.set_xlim(ax1.get_xlim())  # the same values in the same places
    if not ax2.lines:
        ax2.text(0.5, 0.5, "no episode drank", ha="center", va="center", transform=ax2.transAxes, color="grey")
    if by:
        axes[2].set_ylabel("robot actions failed per episode (mean)")
        axes[3].set_ylabel("cued decisions that ignored the cue (share)")
        axes[3].set_ylim(-0.05, 1.05)
        for ax in axes[2:]:
            ax.set_xlim(ax1.get_xlim())
    for ax in axes:
        ax.set_xlabel(param)
        ax.grid(alpha=0.3)
        if not numeric:
            ax.set_xticks(range(len(values)), [_fmt_value(v) for v in values], rotation=20)
        if len(groups) > 1:
            ax.legend(fontsize=8)
    fig.suptitle(f"success vs {param} (n = {len(rows)} episodes; other parameters and seeds pooled)", fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _plot_heatmap(rows: list[dict], p1: str, p2: str, path: Path) -> None:
    """Success rate over two parameters; beside it the mean time to drink when any episode drank."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    v1, v2 = _ordered([r.get(p1) for r in rows]), _ordered([r.get(p2) for r in rows])
    rate = np.full((len(v2), len(v1)), np.nan)
    ttd = np.full((len(v2), len(v1)), np.nan)
    count = np.zeros((len(v2), len(v1)), dtype=int)
    groups: dict[tuple, list[dict]] = defaultdict(list)
    for r in rows:
        groups[(_key(r.get(p1)), _key(r.get(p2)))].append(r)
    for (a, b), grp in groups.items():
        i, j = v2.index(b), v1.index(a)
        c = Cell.of(grp)
        rate[i, j], ttd[i, j], count[i, j] = c.rate, c.ttd_mean, c.n
    panels = [("success rate", rate, dict(cmap="viridis", vmin=0, vmax=1), "{:.2f}")]
    if np.isfinite(ttd).any():
        panels.append(("mean time to drink, s", ttd, dict(cmap="magma_r"), "{:.1f}"))
    w = 1.2 * len(v1) + 3
    fig, axes = plt.subplots(1, len(panels), figsize=(w * len(panels), 0.8 * len(v2) + 2.2), constrained_layout=True,
                             squeeze=False)
    for ax, (label, data, style, fmt) in zip(axes[0], panels):
        im = ax.imshow(data, origin="lower", aspect="auto", **style)
        lo, hi = np.nanmin(data), np.nanmax(data)
        for i in range(len(v2)):
            for j in range(len(v1)):
                if count[i, j]:
                    val = data[i, j]
                    text = ("–" if not np.isfinite(val) else fmt.format(val)) + f"\nn={count[i, j]}"
                    bright = np.isfinite(val) and hi > lo and (val - lo) / (hi - lo) > 0.6
                    ax.text(j, i, text, ha="center", va="center", fontsize=8, color="black" if bright else "white")
        ax.set_xticks(range(len(v1)), [_fmt_value(v) for v in v1])
        ax.set_yticks(range(len(v2)), [_fmt_value(v) for v in v2])
        ax.set_xlabel(p1)
        ax.set_ylabel(p2)
        fig.colorbar(im, ax=ax, label=label)
        ax.set_title(f"{label} over {p1} x {p2}", fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _sequence(text: str | None) -> list[str]:
    return [a.strip() for a in (text or "").split(">") if a.strip()]


def _expect_section(rows: list[dict], factors: list[str], expect: str) -> list[str]:
    """Per value of each factor: how many episodes made exactly the expected AEL decision sequence."""
    from assistbot.sweep.stats import wilson

    want = _sequence(expect)
    prefix = bool(want) and want[-1] == "..."  # "A > B > ..." : the sequence starts with A, B
    if prefix:
        want = want[:-1]

    def made(seq: list[str]) -> bool:
        return seq[: len(want)] == want if prefix else seq == want

    what = "the first AEL decisions, in order" if prefix else "the whole AEL sequence, in order"
    md = ["## Expected decision sequence", "", f"Expected: `{' > '.join(want)}{' > ...' if prefix else ''}` ({what}).", ""]
    for factor in factors or ["scenario"]:
        md += [f"| {factor} | n | made it | rate | 95% CI (Wilson) |", "|---|---:|---:|---:|---|"]
        groups: dict[Any, list[dict]] = defaultdict(list)
        for r in rows:
            groups[_key(r.get(factor))].append(r)
        for v in _ordered([r.get(factor) for r in rows]):
            grp = groups[v]
            k = sum(1 for r in grp if made(_sequence(r.get("decisions"))))
            lo, hi = wilson(k, len(grp))
            md.append(f"| {_fmt_value(v)} | {len(grp)} | {k} | {_f(k / len(grp))} | {_ci(lo, hi)} |")
        md.append("")
    return md


#: the swept paths that together name an arrangement (the task space's first axis)
ARRANGEMENT_PATHS = tuple(f"objects.{o}.{k}" for o in catalogue.TASK_OBJECTS for k in ("zone", "state"))
#: an overlap with the person deeper than this (m), or a spilled fraction at least this, is a failure
#: of the episode even when the person drank
TOUCH_LIMIT = 0.01
SPILL_LIMIT = 0.10


def arrangement_of(row: dict) -> str:
    """'bottle HWS closed, glass RWS inverted' from a row's swept object paths (missing ones as '?')."""
    return ", ".join(f"{o} {row.get(f'objects.{o}.zone', '?')} {row.get(f'objects.{o}.state', '?')}" for o in catalogue.TASK_OBJECTS)


def end_kind(row: dict) -> str:
    """The end reason without its detail ('object fell: bottle' -> 'object fell')."""
    return str(row.get("end_reason") or "?").split(":", 1)[0]


def _task_space_section(rows: list[dict], params: list[str]) -> tuple[list[str], list[list[Any]]]:
    """Per arrangement, and per arrangement x profile (drank / episodes): where the task space fails."""
    if not any(p in params for p in ARRANGEMENT_PATHS):
        return [], []
    for r in rows:
        r["arrangement"] = arrangement_of(r)
    cells = table_rows(rows, "arrangement")
    md = ["## Per arrangement", "", "All profiles and seeds pooled.", ""] + _markdown_table("arrangement", cells) + [""]
    summary = [["arrangement", _fmt_value(v), c.n, c.successes, c.rate, c.rate_low, c.rate_high, c.ttd_mean, c.ttd_low,
                c.ttd_high, c.decisions_mean, c.errors_mean, c.spilled_mean, c.min_distance] for v, c in cells]
    if "human.profile" in params:
        profiles = _ordered([r.get("human.profile") for r in rows])
        groups: dict[tuple, list[dict]] = defaultdict(list)
        for r in rows:
            groups[(r["arrangement"], r.get("human.profile"))].append(r)
        md += ["## Arrangement x profile", "",
               "Episodes that drank of those run (seeds pooled); **bold**: fewer than two thirds drank.", "",
               "| arrangement | " + " | ".join(str(p) for p in profiles) + " |", "|---|" + "---:|" * len(profiles)]
        weak = 0
        for a, _ in cells:
            out = []
            for pr in profiles:
                grp = groups.get((a, pr), [])
                k = sum(1 for r in grp if r.get("success") is True)
                text = f"{k}/{len(grp)}" if grp else "–"
                if grp and 3 * k < 2 * len(grp):
                    text, weak = f"**{text}**", weak + 1
                out.append(text)
            md.append(f"| {a} | " + " | ".join(out) + " |")
        md += ["", f"Arrangement-profile pairs where fewer than two thirds drank: {weak} of {len(cells) * len(profiles)}.", ""]
    return md, summary


def _partner_classes() -> dict[str, tuple[Any, list[str]]]:
    """The partner population's attributes a ``human.partner`` sweep is split by: name -> (the class of a
    partner's value, the classes in order)."""
    def tertile(lo: float, hi: float, v: float, names=("small", "middle", "large")) -> str:
        return names[min(2, int(3 * (v - lo) / (hi - lo)))]

    from assistbot.human import population as P

    def reach(p):
        return tertile(P.UPPER_ARM_RANGE[0] + P.FOREARM_RANGE[0], P.UPPER_ARM_RANGE[1] + P.FOREARM_RANGE[1],
                       p.body.upper_arm + p.body.forearm, ("short", "middle", "long"))

    yes_no = ["no", "yes"]
    return {
        "arm length": (reach, ["short", "middle", "long"]),
        "shoulder height": (lambda p: tertile(*P.SHOULDER_HEIGHT_RANGE, p.body.shoulder_height, ("low", "middle", "high")),
                            ["low", "middle", "high"]),
        "seat back": (lambda p: tertile(0.0, P.SEAT_BACK_MAX, p.body.seat_back, ("near", "middle", "far")), ["near", "middle", "far"]),
        "seat aside": (lambda p: tertile(-P.SEAT_SIDE_MAX, P.SEAT_SIDE_MAX, p.body.seat_side, ("right", "middle", "left")),
                       ["right", "middle", "left"]),
        "reduced range of motion": (lambda p: yes_no[p.body.rom > 0], yes_no),
        "tremor": (lambda p: yes_no[p.tremor_amplitude > 0], yes_no),
        "weakness (lets go)": (lambda p: yes_no[p.drop_chance > 0], yes_no),
        "hesitation": (lambda p: yes_no[p.hesitation > 0], yes_no),
        "holds out": (lambda p: tertile(-P.HOLD_OUT_REGION[2], P.HOLD_OUT_REGION[2], p.hold_out_dz, ("low", "middle", "high")),
                      ["low", "middle", "high"]),
    }


def _partner_section(rows: list[dict], params: list[str]) -> list[str]:
    """A ``human.partner`` sweep by the partners' attributes (`assistbot.human.population`): which bodies,
    impairments and habits fail."""
    if "human.partner" not in params:
        return []
    from assistbot.human.population import parse_partner

    people = {}
    for r in rows:
        v = r.get("human.partner")
        if v is not None and v not in people:
            people[v] = parse_partner(v, "results.csv", "human.partner")
    md = ["## By partner attribute", "",
          f"{len(people)} partners of the population (`assistbot.human.population`), each episode counted under "
          "its partner's class of each attribute (tertiles of the population's range, or whether the impairment "
          "is present).", "",
          "| attribute | class | n | drank | success rate | 95% CI (Wilson) | time to drink (s) | 95% CI (t) |",
          "|---|---|---:|---:|---:|---|---:|---|"]
    for name, (classify, order) in _partner_classes().items():
        groups: dict[str, list[dict]] = defaultdict(list)
        for r in rows:
            if r.get("human.partner") in people:
                groups[classify(people[r["human.partner"]])].append(r)
        for cls in order:
            if groups.get(cls):
                c = Cell.of(groups[cls])
                md.append(f"| {name} | {cls} | {c.n} | {c.successes} | {_f(c.rate)} | {_ci(c.rate_low, c.rate_high)} | "
                          f"{_f(c.ttd_mean, 1)} | {_ci(c.ttd_low, c.ttd_high, 1)} |")
    return md + [""]


def _failure_section(rows: list[dict]) -> list[str]:
    """How episodes ended, by kind, and the limits a drinking episode must also keep."""
    from assistbot.sweep.stats import wilson

    kinds = Counter(end_kind(r) for r in rows)
    md = ["## Failure kinds", "", "| end reason | episodes | share | 95% CI (Wilson) |", "|---|---:|---:|---|"]
    for kind, n in kinds.most_common():
        lo, hi = wilson(n, len(rows))
        md.append(f"| {kind} | {n} | {_f(n / len(rows))} | {_ci(lo, hi)} |")
    detail = Counter(f"{r.get('end_reason')}: {r.get('end_detail')}" for r in rows
                     if end_kind(r) not in ("drink", "time limit") and r.get("end_detail"))
    if detail:
        md += ["", "| what ended them | episodes |", "|---|---:|"]
        md += [f"| {text} | {n} |" for text, n in detail.most_common(10)]
    depth = [float(r["touch_depth"]) for r in rows if isinstance(r.get("touch_depth"), (int, float))]
    force = [float(r["touch_force"]) for r in rows if isinstance(r.get("touch_force"), (int, float))]
    spill = [float(r["spilled_fraction"]) for r in rows if isinstance(r.get("spilled_fraction"), (int, float))]
    md += ["", "| limit | episodes over it | worst |", "|---|---:|---:|"]
    if depth:
        md.append(f"| overlap with the person > {100 * TOUCH_LIMIT:.0f} cm | {sum(d > TOUCH_LIMIT for d in depth)} | "
                  f"{100 * max(depth):.1f} cm |")
        md.append(f"| any overlap with the person | {sum(d > 0 for d in depth)} | "
                  f"{max(force) if force else 0:.1f} N (largest contact force) |")
    if spill:
        md.append(f"| spilled >= {100 * SPILL_LIMIT:.0f} % | {sum(x >= SPILL_LIMIT for x in spill)} | {100 * max(spill):.1f} % |")
    md.append("")
    return md


def write_report(results_dir: str | Path, out: str | Path | None = None, expect: str | None = None,
                 by: str | None = None) -> list[Path]:
    """Write report.md, summary.csv and the plots; return the written paths (report.md first).

    ``by``: a swept parameter (``agent``, say) whose values each other factor is split by: a table per
    factor with a row per pair of values, and plots with a line per value of ``by``.

    ``expect``: an AEL decision sequence ("A > B > C"); the report then counts, per parameter value,
    the episodes that made exactly that sequence (e.g. the seed's, to see which k still reproduces it).
    """
    results_dir = Path(results_dir)
    params, rows = load_results(results_dir)
    out_dir = Path(out) if out is not None else (results_dir.parent if results_dir.suffix == ".csv" else results_dir) / "report"
    out_dir.mkdir(parents=True, exist_ok=True)
    if by is not None and by not in params:
        raise UserError("--by", by, f"not a swept parameter of {results_dir}; its parameters: {', '.join(params) or '(none)'}")
    scenarios = list(dict.fromkeys(r["scenario"] for r in rows))
    # partners are many: the report splits them by attribute (`_partner_section`), not one row each
    factors = (["scenario"] if len(scenarios) > 1 else []) + [p for p in params if p != "human.partner"]
    varied = varied_params(params, rows, skip=("human.partner",))
    written: list[Path] = []
    overall = Cell.of(rows)
    seeds = sorted({r["seed"] for r in rows if r.get("seed") is not None})
    perceptions = sorted({r.get("perception") or "?" for r in rows})
    md = [f"# Sweep report: {results_dir}", "",
          f"{len(rows)} episodes; scenarios: {', '.join(scenarios)}; perception: {', '.join(perceptions)}; "
          f"seeds: {len(seeds)} ({', '.join(str(s) for s in seeds[:10])}{', ...' if len(seeds) > 10 else ''}).", "",
          f"**Overall:** {overall.successes}/{overall.n} drank, success rate {_f(overall.rate)} "
          f"{_ci(overall.rate_low, overall.rate_high)} (95% Wilson); "
          + (f"time to drink {_f(overall.ttd_mean, 1)} s {_ci(overall.ttd_low, overall.ttd_high, 1)} "
             "(95% t, over the episodes that drank)." if overall.successes else "no episode drank."), "",
          "Each table pools the other parameters and all seeds (the marginal effect of one parameter).", ""]
    summary: list[list[Any]] = []
    for factor in factors:
        cells = table_rows(rows, factor)
        md += [f"## {factor}", ""] + _markdown_table(factor, cells) + [""]
        for v, c in cells:
            summary.append([factor, _fmt_value(v), c.n, c.successes, c.rate, c.rate_low, c.rate_high,
                            c.ttd_mean, c.ttd_low, c.ttd_high, c.decisions_mean, c.errors_mean, c.spilled_mean,
                            c.min_distance])
        if by is not None and factor != by:
            md += [f"### {factor}, by {by}", ""] + _by_table(rows, factor, by) + [""]
        if factor in varied:
            png = out_dir / f"success_vs_{_safe(factor)}.png"
            _plot_param(rows, factor, scenarios, png, by=by if factor != by else None)
            written.append(png)
            md += [f"![success vs {factor}]({png.name})", ""]
    space_md, space_summary = _task_space_section(rows, params)
    md += space_md + _partner_section(rows, params)
    summary += space_summary
    pairs = list(itertools.combinations(varied, 2))[:MAX_HEATMAPS]
    if pairs:
        md += ["## Heatmaps", ""]
        if len(scenarios) > 1:
            md += ["(all scenarios pooled)", ""]
    for p1, p2 in pairs:
        png = out_dir / f"heatmap_{_safe(p1)}__{_safe(p2)}.png"
        _plot_heatmap(rows, p1, p2, png)
        written.append(png)
        md += [f"![success over {p1} x {p2}]({png.name})", ""]
    if expect:
        md += _expect_section(rows, factors, expect)
    seqs = Counter(r.get("decisions") or "(none)" for r in rows)
    md += ["## Decision sequences (AEL)", "", "| sequence | episodes | drank |", "|---|---:|---:|"]
    for seq, n in seqs.most_common(10):
        drank = sum(1 for r in rows if (r.get("decisions") or "(none)") == seq and r.get("success") is True)
        md.append(f"| {seq} | {n} | {drank} |")
    md += [""] + _failure_section(rows)
    report = out_dir / "report.md"
    report.write_text("\n".join(md), encoding="utf-8")
    page = out_dir / "report.html"
    page.write_text(_html_report(md, rows, params, results_dir, out_dir), encoding="utf-8")
    summary_path = out_dir / "summary.csv"
    with open(summary_path, "w", encoding="utf-8", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(["factor", "value", "n", "drank", "success_rate", "rate_low", "rate_high", "time_to_drink_mean",
                    "time_to_drink_low", "time_to_drink_high", "decisions_mean", "errors_communicated_mean",
                    "spilled_mean", "min_distance_human"])
        for r in summary:
            w.writerow(["" if isinstance(x, float) and math.isnan(x) else (round(x, 6) if isinstance(x, float) else x) for x in r])
    return [report, page, summary_path] + written


def _html_report(md: list[str], rows: list[dict], params: list[str], results_dir: Path, out_dir: Path) -> str:
    """report.md as a page, followed by one row per episode, linked to its run folder's inspector page when the
    sweep kept it (``runs/<job id>/inspect.html`` beside results.csv)."""
    import html
    import os

    import markdown

    from assistbot.sweep.runner import RUNS

    base = results_dir.parent if results_dir.suffix == ".csv" else results_dir
    cols = ["scenario", *params, "seed", "success", "end_reason", "time_to_drink", "decisions"]
    head = "".join(f"<th>{html.escape(c)}</th>" for c in ["episode", *cols])
    body = []
    for r in sorted(rows, key=lambda r: (str(r.get("scenario")), str(r.get("job_id")))):
        job = str(r.get("job_id", ""))
        page = base / RUNS / job / "inspect.html"
        link = (f'<a href="{html.escape(os.path.relpath(page, out_dir))}">{html.escape(job)}</a>' if page.exists()
                else html.escape(job))
        cells = "".join(f"<td>{html.escape(_fmt_value(r.get(c)))}</td>" for c in cols)
        body.append(f"<tr class=\"{'ok' if r.get('success') is True else 'bad'}\"><td>{link}</td>{cells}</tr>")
    kept = any((base / RUNS / str(r.get("job_id", "")) / "inspect.html").exists() for r in rows)
    note = ("Each episode links to its inspector page." if kept else
            "Run the sweep with --keep-runs to keep each episode's run folder and link its inspector page here.")
    style = ("body{font:14px/1.45 system-ui,sans-serif;max-width:1200px;margin:1em auto;padding:0 1em}"
             "table{border-collapse:collapse;font-size:12px;margin:.5em 0}td,th{padding:2px 7px;border-bottom:1px solid #ddd}"
             "tr.bad td:nth-child(2){color:#a11}img{max-width:100%}")
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'><title>" + html.escape(md[0].lstrip("# ")) + "</title>"
            f"<style>{style}</style></head><body>" + markdown.markdown("\n".join(md), extensions=["tables"])
            + f"<h2>Episodes</h2><p>{note}</p><table><tr>{head}</tr>{''.join(body)}</table></body></html>\n")
