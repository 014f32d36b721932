"""The closed loop end to end with the labelled ORACLE perception (ground truth, not vision).

This isolates physics + cognition + robot + human from vision: the seed's Fig. 3-4
storyline must play out in order and end with the person drinking. (The same with
vision is tests/test_episode_e2e.py.) Slow: run by .ci/run and `make test-all`.
"""

from __future__ import annotations

from functools import lru_cache

import pytest

from assistbot.episode import run_scenario

from _closed_loop_checks import check_fig3_4, check_fig5

pytestmark = pytest.mark.slow


@lru_cache(maxsize=None)
def episode(name: str):
    return run_scenario(name, perception="oracle", video=False)


def test_paper_fig3_4_with_oracle_perception_ends_with_the_drink_in_the_seeds_order():
    r = episode("paper-fig3-4")
    assert r.perception == "oracle"
    check_fig3_4(r)


def test_paper_fig5_passive_user_with_oracle_perception():
    check_fig5(episode("paper-fig5"))
