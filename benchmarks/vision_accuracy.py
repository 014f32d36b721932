"""Vision accuracy and speed on labelled renders (issue 8), and on people the library never saw (issue 24).

Renders N (default 500) stereo pairs of random arrangements, object positions, hand postures
and head angles from the "bench" seed stream (the template library uses the "library"
stream, so no benchmark frame was used to build templates), runs the vision pipeline, and
prints per-class precision/recall, confusion matrices for object states and hand postures,
the accuracy per band of the reports' confidence, object position error (median, 95th
percentile) and milliseconds per stereo pair for rendering and for processing (right after the
pair's render, as in the loop; and the same pair again at once, with warm caches).  Labels come from WorldState and the posed scene spec.
An object counts when both cameras show >= 25 of its pixels (renderer segmentation); the hand
when both show >= 25 skin pixels within 6 cm of its grasp site.  Object states reported with a
low confidence (the stopper hidden in the hand) are listed apart from the scored ones; the
last lines give the state accuracy with and without them.

``--partners A:B`` scores the same number of scenes twice, side by side: with the default person
(whose poses the library was built from) and with people of the population seeds A..B (each scene's
person drawn from them and built in the physics: other arm lengths, seat, range of motion, hold-out
habit), per object state and hand posture with Wilson intervals. Scenes a body cannot pose (the hand
more than 2 cm off where its posture puts it: an object out of that person's reach) are not scored.

    .venv/bin/python benchmarks/vision_accuracy.py [--frames 500] [--seed 0] [--partners 1000:1099]
"""

from __future__ import annotations

import argparse
import sys
import time

GOALS = "goals: object state >= 98%, hand posture >= 95%, position median <= 2 cm / p95 <= 5 cm, processing <= 3 ms per pair"
UNSEEN_GOALS = "goals on unseen partners: hand posture >= 95%, object state >= 98%, object position median <= 2 cm"


def _seeds(text: str) -> range:
    from assistbot.errors import UserError
    from assistbot.human.population import parse_seed_range

    try:
        return parse_seed_range(text, "vision_accuracy", "--partners")
    except UserError as exc:
        print(exc, file=sys.stderr)
        raise SystemExit(2) from None


def _side_by_side(default, unseen, label: str) -> str:
    import numpy as np

    from assistbot.vision.evaluate import wilson
    from assistbot.vision.library import KINDS

    def rate(k: int, n: int) -> str:
        """k of n as a percentage with its 95% Wilson interval and n."""
        lo, hi = wilson(k, n)
        return f"{k / n * 100:5.1f}% [{lo * 100:4.1f},{hi * 100:5.1f}] {n:4d}" if n else f"{'-':>22}"

    def cell(score, kind, cls=None) -> str:
        pairs = [(t, p) for t, p in zip(score.truth[kind], score.pred[kind]) if cls is None or t == cls]
        return rate(sum(t == p for t, p in pairs), len(pairs))

    w = 22
    lines = [f"\n{'':<26} {'default person':>{w}}   {label:>{w}}",
             f"{'(recall [95% Wilson], n)':<26} {'':>{w}}   {'':>{w}}"]
    for kind, classes in KINDS.items():
        lines.append(f"{kind + ' (all)':<26} {cell(default, kind)}   {cell(unseen, kind)}")
        for c in classes:
            lines.append(f"  {c:<24} {cell(default, kind, c)}   {cell(unseen, kind, c)}")
    objs = ("bottle", "glass")
    lines.append(f"{'object state (both)':<26} {default.accuracy(objs) * 100:5.1f}%{'':>16}   {unseen.accuracy(objs) * 100:5.1f}%")
    held = (default.held_out_recall(), unseen.held_out_recall())
    lines.append(f"{'held out, reported so':<26} {rate(held[0][0], held[0][1])}   {rate(held[1][0], held[1][1])}")
    lines.append(f"{'not held out, reported so':<26} {rate(held[0][2], held[0][3])}   {rate(held[1][2], held[1][3])}")
    for name, attr in (("object position median", "pos_err"), ("hand position median", "hand_err")):
        a, b = (np.median(getattr(s, attr)) * 100 if getattr(s, attr) else float("nan") for s in (default, unseen))
        lines.append(f"{name:<26} {a:5.2f} cm{'':>14}   {b:5.2f} cm")
    lines.append(f"{'scenes scored / unposable':<26} {default.frames:>5} / {default.unposable:<14}   "
                 f"{unseen.frames:>5} / {unseen.unposable}")
    lines.append(f"{'people':<26} {default.people:>5}{'':>17}   {unseen.people:>5}")
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frames", type=int, default=500)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--partners", default=None, help="population seeds A:B to score beside the default person")
    args = ap.parse_args()
    from assistbot.vision.evaluate import run

    partners = _seeds(args.partners) if args.partners else None
    t0 = time.time()

    def progress(i: int, n: int) -> None:
        if i % 50 == 0 or i == n:
            print(f"\r{i}/{n} frames", end="", file=sys.stderr, flush=True)

    score = run(args.frames, args.seed, "bench", progress)
    print(file=sys.stderr)
    print(score.report())
    low = sum(len(v) for v in score.low_conf.values())
    low_ok = sum(sum(v) for v in score.low_conf.values())
    n = len(score.truth["bottle"]) + len(score.truth["glass"])
    acc = score.accuracy(("bottle", "glass"))
    print(f"\nobject state accuracy (bottle + glass): {acc * 100:.1f}% of {n} confident reports; "
          f"{(acc * n + low_ok) / max(1, n + low) * 100:.1f}% of all {n + low} seen (incl. {low} low-confidence)")
    print(GOALS)
    if partners is not None:
        unseen = run(args.frames, args.seed, "bench", progress, partners=partners)
        print(file=sys.stderr)
        print(f"\n--- people of population seeds {partners.start}:{partners.stop - 1} (none of them in the library) ---")
        print(unseen.report())
        print(_side_by_side(score, unseen, f"seeds {partners.start}:{partners.stop - 1}"))
        print(UNSEEN_GOALS)
    print(f"wall time {time.time() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
