"""Scoring vision against labelled scenes: per-class precision/recall, confusions, position errors, timings.

Used by benchmarks/vision_accuracy.py and by the tests.  Labels come from `scenes.pose`
(WorldState + the posed spec); the scenes come from a seed stream the library never uses.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from assistbot import catalogue
from assistbot.vision.library import KINDS
from assistbot.vision.pipeline import LOW_CONFIDENCE
from assistbot.vision.scenes import POSE_TOLERANCE


@dataclass
class Score:
    truth: dict[str, list[str]] = field(default_factory=lambda: {k: [] for k in KINDS})
    pred: dict[str, list[str]] = field(default_factory=lambda: {k: [] for k in KINDS})
    conf: dict[str, list[float]] = field(default_factory=lambda: {k: [] for k in KINDS})   # the scored reports' confidences
    pos_err: list[float] = field(default_factory=list)
    pos_err_lifted: list[float] = field(default_factory=list)    # objects off the table (in a hand)
    hand_err: list[float] = field(default_factory=list)
    held_out: list[tuple[bool, bool]] = field(default_factory=list)   # (truth, reported) of a hand seen holding out
    low_conf: dict[str, list[bool]] = field(default_factory=lambda: {o: [] for o in catalogue.TASK_OBJECTS})   # correct?
    unseen: dict[str, int] = field(default_factory=lambda: {k: 0 for k in KINDS})
    render_ms: list[float] = field(default_factory=list)
    process_ms: list[float] = field(default_factory=list)
    process_cpu_ms: list[float] = field(default_factory=list)
    process_warm_ms: list[float] = field(default_factory=list)   # the same pair processed again at once
    frames: int = 0
    unposable: int = 0          # scenes the person's body could not pose (`POSE_TOLERANCE`): not scored
    people: int = 1             # how many different people the scenes showed

    def add(self, percept, labels, visible: dict[str, bool]) -> None:
        self.frames += 1
        for o in catalogue.TASK_OBJECTS:
            if not visible[o]:
                continue
            op = percept.objects[o]
            if not op.seen:
                self.unseen[o] += 1
                continue
            err = float(np.linalg.norm(np.array(op.position) - np.array(labels.objects[o]["position"])))
            self.pos_err.append(err)
            if labels.objects[o]["position"][2] > 0.02:
                self.pos_err_lifted.append(err)
            if op.confidence <= LOW_CONFIDENCE:
                self.low_conf[o].append(op.state == labels.objects[o]["state"])
                continue
            self.truth[o].append(labels.objects[o]["state"])
            self.pred[o].append(op.state)
            self.conf[o].append(float(op.confidence))
        if visible["hand"]:
            if not percept.hand.seen:
                self.unseen["hand"] += 1
            else:
                self.truth["hand"].append(labels.posture)
                self.pred["hand"].append(percept.hand.posture)
                self.conf["hand"].append(float(percept.hand.confidence))
                self.hand_err.append(float(np.linalg.norm(np.array(percept.hand.position) - np.array(labels.hand_position))))
                self.held_out.append((bool(labels.held_out), bool(percept.hand.held_out)))

    def accuracy(self, kind: str | tuple[str, ...]) -> float:
        kinds = (kind,) if isinstance(kind, str) else kind
        t = sum((self.truth[k] for k in kinds), [])
        p = sum((self.pred[k] for k in kinds), [])
        return float(np.mean([a == b for a, b in zip(t, p)])) if t else float("nan")

    def held_out_recall(self) -> tuple[int, int, int, int]:
        """(held out and so reported, held out, not held out but reported so, not held out) over the hands seen:
        whether the robot notices a thing held out to it, and how often it takes a hand at work for one."""
        hit = sum(t and r for t, r in self.held_out)
        pos = sum(t for t, _ in self.held_out)
        false = sum(r and not t for t, r in self.held_out)
        return hit, pos, false, len(self.held_out) - pos

    def by_confidence(self, kind: str, edges=(0.6, 0.9)) -> list[tuple[float, float, int, float]]:
        """Accuracy per confidence band (lo, hi]: (lo, hi, reports, accuracy), from the lowest band; how
        far a report's confidence (which weighs cognition's input) says how likely it is right."""
        c = np.array(self.conf[kind])
        ok = np.array([a == b for a, b in zip(self.truth[kind], self.pred[kind])], bool)
        bounds = (0.0, *edges, 1.0)
        out = []
        for lo, hi in zip(bounds[:-1], bounds[1:]):
            sel = (c > lo) & (c <= hi)
            out.append((lo, hi, int(sel.sum()), float(ok[sel].mean()) if sel.any() else float("nan")))
        return out

    def interval(self, kind: str | tuple[str, ...]) -> tuple[float, float]:
        """The accuracy's 95% Wilson score interval: how far a set of this size pins it down (at
        500 frames about +-2 points for the hand, where one frame is 0.2 of a point)."""
        kinds = (kind,) if isinstance(kind, str) else kind
        n = sum(len(self.truth[k]) for k in kinds)
        return wilson(self.accuracy(kind) * n if n else 0.0, n)

    def confusion(self, kind: str) -> np.ndarray:
        cl = KINDS[kind]
        M = np.zeros((len(cl), len(cl)), int)
        for a, b in zip(self.truth[kind], self.pred[kind]):
            M[cl.index(a), cl.index(b)] += 1
        return M

    def report(self) -> str:
        lines = [f"frames (stereo pairs): {self.frames} of {self.people} {'person' if self.people == 1 else 'people'}"
                 + (f"; {self.unposable} more scenes the body could not pose (hand > {POSE_TOLERANCE * 100:.0f} cm off), not scored"
                    if self.unposable else "")]
        for kind in KINDS:
            M = self.confusion(kind)
            cl = KINDS[kind]
            n = M.sum()
            lo, hi = self.interval(kind)
            lines.append(f"\n{kind}: accuracy {self.accuracy(kind) * 100:.1f}% (95% interval {lo * 100:.1f}-{hi * 100:.1f}) "
                         f"over {n} seen (+{self.unseen[kind]} visible but reported unseen)")
            lines.append(f"  {'class':<18} {'precision':>9} {'recall':>7} {'n':>5}")
            for i, c in enumerate(cl):
                prec = M[i, i] / M[:, i].sum() if M[:, i].sum() else float("nan")
                rec = M[i, i] / M[i].sum() if M[i].sum() else float("nan")
                lines.append(f"  {c:<18} {prec * 100:>8.1f}% {rec * 100:>6.1f}% {M[i].sum():>5}")
            w = max(len(c) for c in cl)
            lines.append("  confusion (rows truth, columns predicted): " + " ".join(c[:8] for c in cl))
            for i, c in enumerate(cl):
                lines.append(f"  {c:<{w}} " + " ".join(f"{v:>8}" for v in M[i]))
            lines.append("  accuracy by the report's confidence: " + "; ".join(
                f"{lo:.1f}-{hi:.1f}: {acc * 100:.1f}% of {k}" if k else f"{lo:.1f}-{hi:.1f}: none"
                for lo, hi, k, acc in self.by_confidence(kind)))
        for o, v in self.low_conf.items():
            if v:
                lines.append(f"{o}: {len(v)} seen with a low-confidence state (<= {LOW_CONFIDENCE}: stopper hidden), "
                             f"not scored above; {sum(v)} of them right")
        hit, pos, false, neg = self.held_out_recall()
        if pos or neg:
            (lo, hi), (flo, fhi) = wilson(hit, pos), wilson(false, neg)
            lines.append(f"\nheld out: {hit} of {pos} hands holding out reported so ({hit / max(pos, 1) * 100:.1f}%, 95% interval "
                         f"{lo * 100:.1f}-{hi * 100:.1f}); {false} of {neg} others reported held out ({false / max(neg, 1) * 100:.1f}%, "
                         f"{flo * 100:.1f}-{fhi * 100:.1f})")
        e = np.array(self.pos_err) * 100
        if e.size:
            lines.append(f"\nobject position error: median {np.median(e):.2f} cm, 95th percentile {np.percentile(e, 95):.2f} cm, "
                         f"max {e.max():.1f} cm (n={e.size})")
        e = np.array(self.pos_err_lifted) * 100
        if e.size:
            lines.append(f"  of which lifted in a hand: median {np.median(e):.2f} cm, "
                         f"95th percentile {np.percentile(e, 95):.2f} cm (n={e.size})")
        e = np.array(self.hand_err) * 100
        if e.size:
            lines.append(f"hand position error (grasp site): median {np.median(e):.2f} cm, "
                         f"95th percentile {np.percentile(e, 95):.2f} cm (n={e.size})")
        if self.render_ms:
            lines.append(f"ms per stereo pair: rendering {np.median(self.render_ms):.2f} (median), "
                         f"processing {np.median(self.process_ms):.2f} (median), {np.percentile(self.process_ms, 95):.2f} (95th)")
        if self.process_cpu_ms:
            lines.append(f"processing CPU time per stereo pair: {np.median(self.process_cpu_ms):.2f} ms (median), "
                         f"{np.percentile(self.process_cpu_ms, 95):.2f} (95th) -- wall times above include waiting for a shared CPU")
        if self.process_warm_ms:
            lines.append(f"processing the same pair again at once: {np.median(self.process_warm_ms):.2f} ms (median) -- the code's "
                         "own cost with its data and code in the CPU caches, which each render evicts; the goal is for the figure above")
        return "\n".join(lines)


def wilson(k: float, n: int, z: float = 1.96) -> tuple[float, float]:
    """The Wilson score interval of a proportion k/n (nan, nan for n = 0)."""
    if n == 0:
        return float("nan"), float("nan")
    p = k / n
    mid = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return float(mid - half), float(mid + half)


def visibility(segs, cams=None, hand=None, min_px: int = 25, hand_px: int = 25) -> dict[str, bool]:
    """Which labelled things both cameras show with at least min_px pixels (from the renderer's
    segmentation); the hand: skin pixels within 6 cm of the grasp site's projection in both cameras."""
    from assistbot.world.render import SEGMENT_LABELS
    inv = {v: k for k, v in SEGMENT_LABELS.items()}
    vis = {}
    for name in catalogue.TASK_OBJECTS:
        vis[name] = all(int(np.count_nonzero(s == inv[name])) >= min_px for s in segs)
    vis["hand"] = True
    if cams is not None and hand is not None:
        for s, cam in zip(segs, cams):
            uv = cam.project(np.asarray(hand))[0]
            if not np.all(np.isfinite(uv)):
                vis["hand"] = False
                continue
            rad = cam.K[0, 0] * 0.06 / max(0.1, float(np.linalg.norm(np.asarray(hand) - cam.C)))
            yy, xx = np.ogrid[:s.shape[0], :s.shape[1]]
            near = (xx - uv[0]) ** 2 + (yy - uv[1]) ** 2 < rad ** 2
            vis["hand"] &= int(np.count_nonzero(near & (s == inv["skin"]))) >= hand_px
    return vis


def run(n: int, seed: int = 0, purpose: str = "bench", progress=None, root=None,
        partners: Sequence[int] | None = None) -> Score:
    """Score vision on ``n`` scenes of the ``purpose`` seed stream: of the default person, or (``partners``,
    population seeds) each of a person drawn from them, built in the physics (`human.population`)."""
    from assistbot.vision.capture import StereoCapture
    from assistbot.vision.pipeline import Vision
    from assistbot.vision.scenes import SceneSampler, by_person, pose

    vision = Vision(root)
    sampler = SceneSampler(seed, purpose, partners)
    specs = [sampler.sample() for _ in range(n)]
    score = Score(people=len({s.partner for s in specs}))
    done = 0
    for world, group in by_person(specs, seed):
        with StereoCapture(world.model) as cap:
            for spec in group:
                done += 1
                lab = pose(world, spec)
                if lab.pose_miss > POSE_TOLERANCE:
                    score.unposable += 1
                    continue
                f = cap.grab(world.data)
                vis = visibility(cap.segmentation(world.data), f.cams, lab.hand_position)
                percept = vision.perceive(f)
                score.add(percept, lab, vis)
                score.render_ms.append(f.render_ms)
                score.process_ms.append(vision.timing.process_ms)
                score.process_cpu_ms.append(vision.timing.process_cpu_ms)
                vision.perceive(f)
                score.process_warm_ms.append(vision.timing.process_ms)
                if progress:
                    progress(done, n)
    return score
