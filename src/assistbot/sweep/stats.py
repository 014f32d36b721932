"""Confidence intervals for a sweep's summary: Wilson for success rates, Student t for means."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence


def wilson(successes: int, n: int, confidence: float = 0.95) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion; (0, 1) when n = 0.

    Unlike the normal approximation it stays inside [0, 1] and is sensible for 0 or n successes
    out of a few episodes, which is what a sweep cell usually holds.
    """
    if n <= 0:
        return (0.0, 1.0)
    from scipy.stats import norm

    z = float(norm.ppf(0.5 + confidence / 2))
    p = successes / n
    denom = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z / denom * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    lo = 0.0 if successes == 0 else max(0.0, centre - half)  # exact ends: no -1e-17 below a rate of 0
    hi = 1.0 if successes == n else min(1.0, centre + half)
    return (min(lo, p), max(hi, p))


def mean_ci(values: Sequence[float], confidence: float = 0.95) -> tuple[float, float, float]:
    """(mean, low, high) with a Student t interval; NaN bounds with fewer than two values, NaN mean with none."""
    xs = [float(v) for v in values if v is not None and math.isfinite(float(v))]
    if not xs:
        return (math.nan, math.nan, math.nan)
    m = sum(xs) / len(xs)
    if len(xs) < 2:
        return (m, math.nan, math.nan)
    from scipy.stats import t

    sd = math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1))
    half = float(t.ppf(0.5 + confidence / 2, len(xs) - 1)) * sd / math.sqrt(len(xs))
    return (m, m - half, m + half)


@dataclass
class Cell:
    """The episodes that share one value (or one pair of values) of the swept parameters."""

    n: int
    successes: int
    rate: float
    rate_low: float
    rate_high: float
    ttd_mean: float  # time to drink, over the episodes that drank
    ttd_low: float
    ttd_high: float
    errors_mean: float
    spilled_mean: float
    decisions_mean: float = math.nan  # AEL decisions per episode
    min_distance: float = math.nan  # closest the robot came to the human's head/torso over these episodes, m
    failed_mean: float = math.nan  # robot actions that failed per episode (a decision the world did not bear out)
    ignored_share: float = math.nan  # of the decisions taken with a cue of the person's showing, those that ignored it
    uncued_mean: float = math.nan  # decisions per episode taken with no cue showing (the seed's fallback)

    @classmethod
    def of(cls, rows: Sequence[dict]) -> "Cell":
        n = len(rows)
        s = sum(1 for r in rows if r.get("success") is True)
        lo, hi = wilson(s, n)
        ttd = mean_ci([r["time_to_drink"] for r in rows if r.get("success") is True and r.get("time_to_drink") is not None])
        errs = [float(r["errors_communicated"]) for r in rows if r.get("errors_communicated") is not None]
        spill = [float(r["spilled_fraction"]) for r in rows if r.get("spilled_fraction") is not None]
        dec = [float(r["n_decisions"]) for r in rows if r.get("n_decisions") is not None]
        dist = [float(r["min_distance_human"]) for r in rows if r.get("min_distance_human") is not None]
        failed = [float(r["n_failed_actions"]) for r in rows if r.get("n_failed_actions") is not None]
        cued = [r for r in rows if r.get("ignored_cues") is not None and r.get("answered_cues") is not None]
        ignored = sum(float(r["ignored_cues"]) for r in cued)
        with_cue = ignored + sum(float(r["answered_cues"]) for r in cued)
        uncued = [float(r["uncued_decisions"]) for r in rows if r.get("uncued_decisions") is not None]
        return cls(n=n, successes=s, rate=s / n if n else math.nan, rate_low=lo, rate_high=hi,
                   ttd_mean=ttd[0], ttd_low=ttd[1], ttd_high=ttd[2],
                   errors_mean=sum(errs) / len(errs) if errs else math.nan,
                   spilled_mean=sum(spill) / len(spill) if spill else math.nan,
                   decisions_mean=sum(dec) / len(dec) if dec else math.nan, min_distance=min(dist) if dist else math.nan,
                   failed_mean=sum(failed) / len(failed) if failed else math.nan,
                   ignored_share=ignored / with_cue if with_cue else math.nan,
                   uncued_mean=sum(uncued) / len(uncued) if uncued else math.nan)
