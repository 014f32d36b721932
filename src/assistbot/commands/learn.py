"""`assistbot learn SCENARIO --episodes N --out DIR`: episodes in a row with the same person, the robot learning
from each (`assistbot.cognition.learning`), and the learning curve."""

from __future__ import annotations

import argparse
from pathlib import Path

NAME = "learn"
HELP = "run a scenario N times in a row with the same person, learning the grip-to-chain weights from each: " \
       "learning.csv, learning.png and weights.json"
ORDER = 12

COLUMNS = ["episode", "seed", "weights", "success", "time_to_drink", "end_reason", "n_decisions", "n_failed_actions",
           "errors_communicated", "distance_from_priors"]


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("scenario", help="a scenario file or the name of a shipped one (see 'assistbot list')")
    p.add_argument("--episodes", type=int, default=5, help="how many episodes in a row (default 5)")
    p.add_argument("--out", type=Path, default=None, help="output folder (default: render/learn/<scenario name>)")
    p.add_argument("--seed", type=int, default=None,
                   help="the first episode's seed (default: the scenario's); episode i runs with seed + i")
    p.add_argument("--perception", choices=["vision", "oracle"], default="vision",
                   help="vision (the robot's cameras) or oracle (ground truth, for debugging)")
    p.add_argument("--set", dest="sets", action="append", default=[], metavar="PATH=VALUE",
                   help="override a parameter by dotted path, as 'assistbot run' does, e.g. --set human.partner=1042 "
                        "(repeatable)")
    p.add_argument("--compare", action="store_true",
                   help="also run each episode (the same seed) with the priors, without learning: rows with weights "
                        "'priors' beside the 'learnt' ones, and both in the plot")
    p.add_argument("--force", action="store_true", help="start over in a folder that holds an earlier learning run")


def run(args: argparse.Namespace) -> int:
    import csv

    from assistbot.cognition import Cognition, learning
    from assistbot.commands.run import scenario_with_sets
    from assistbot.episode import run_scenario
    from assistbot.episode.builder import split_overrides
    from assistbot.errors import UserError

    if args.episodes < 1:
        raise UserError("--episodes", str(args.episodes), "must be 1 or more")
    scenario, overrides = scenario_with_sets(args.scenario, args.sets)
    learning.check_learner(scenario.agent)
    split_overrides(overrides, "--set", scenario.agent)
    out = args.out or Path("render/learn") / scenario.name
    weights, table = out / "weights.json", out / "learning.csv"
    if out.exists() and not out.is_dir():
        raise UserError(str(out), "--out", "is a file; name a folder")
    if (weights.exists() or table.exists()) and not args.force:
        raise UserError(str(out), "--out", "holds an earlier learning run; pass --force to start over, or name another "
                                           "folder with --out")
    out.mkdir(parents=True, exist_ok=True)
    weights.unlink(missing_ok=True)
    priors = Cognition(overrides={"learning.rate": learning.LEARNING_RATE}).learned_weights()
    first = scenario.seed if args.seed is None else args.seed
    rows: list[dict] = []

    def row(i: int, kind: str, result, distance: float) -> None:
        rows.append({
            "episode": i + 1, "seed": first + i, "weights": kind, "success": result.success,
            "time_to_drink": "" if result.time_to_drink is None else round(result.time_to_drink, 2),
            "end_reason": result.end_reason, "n_decisions": len(result.decisions),
            "n_failed_actions": result.n_failed_actions,
            "errors_communicated": result.errors_communicated, "distance_from_priors": round(distance, 4),
        })
        r = rows[-1]
        print(f"episode {r['episode']} (seed {r['seed']}, {kind}): " +
              (f"drank at {r['time_to_drink']} s" if r["success"] else f"did not drink ({r['end_reason']})") +
              f", {r['n_failed_actions']} failed actions, weights {r['distance_from_priors']} from the priors", flush=True)
        with open(table, "w", newline="") as fh:   # rewritten after each episode: a stopped run keeps what it did
            w = csv.DictWriter(fh, fieldnames=COLUMNS)
            w.writeheader()
            w.writerows(rows)

    for i in range(args.episodes):
        result = run_scenario(scenario, out=None, perception=args.perception, seed=first + i, overrides=overrides,
                              video=False, learn=weights)
        tables, _ = learning.read_weights(weights)
        row(i, "learnt", result, learning.distance_from_priors(tables, priors))
        if args.compare:
            row(i, "priors", run_scenario(scenario, out=None, perception=args.perception, seed=first + i,
                                          overrides=overrides, video=False), 0.0)
    _plot(rows, out / "learning.png", scenario.name)
    print(f"wrote {table}, {out / 'learning.png'} and {weights}")
    return 0


def _plot(rows: list[dict], path: Path, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, figsize=(6, 6.5), sharex=True)
    for kind, marker in (("learnt", "o-"), ("priors", "s--")):
        mine = [r for r in rows if r["weights"] == kind]
        if not mine:
            continue
        drank = [(r["episode"], r["time_to_drink"]) for r in mine if r["success"]]
        failed = [r["episode"] for r in mine if not r["success"]]
        axes[0].plot([e for e, _ in drank], [t for _, t in drank], marker, label=f"{kind}: drank")
        if failed:
            axes[0].plot(failed, [0] * len(failed), "x", label=f"{kind}: did not drink")
        axes[1].plot([r["episode"] for r in mine], [r["n_failed_actions"] + r["errors_communicated"] for r in mine],
                     marker, label=kind)
        if kind == "learnt":
            axes[2].plot([r["episode"] for r in mine], [r["distance_from_priors"] for r in mine], marker)
    axes[0].set_ylabel("time to drink (s)")
    axes[0].legend(fontsize=8)
    axes[1].set_ylabel("failed actions +\nerrors said")
    axes[1].legend(fontsize=8)
    axes[2].set_ylabel("weights from priors")
    axes[2].set_xlabel("episode")
    axes[0].set_title(f"learning from the user: {title}")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
