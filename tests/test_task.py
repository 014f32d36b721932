"""The drinking task data: consistency, one utterance per pool, and coverage of all 24 arrangements."""

from __future__ import annotations

import itertools
from collections import deque

import pytest

from assistbot import task


def test_item_names_are_unique_and_dot_free():
    for items in (task.OL_ITEMS, task.OML_ITEMS, task.SUBGOALS, task.ASL_ITEMS, task.IL_ITEMS, task.AML_ITEMS, task.AEL_ITEMS):
        assert len(set(items)) == len(items)
        assert all("." not in i for i in items)


def test_associations_name_known_items():
    for c in task.ASL_CHAINS:
        assert set(c.primitives) <= set(task.OL_ITEMS)
        assert set(c.objects) <= set(task.OML_ITEMS)
        assert set(c.subgoals) <= set(task.SUBGOALS)
    for i in task.INTENTIONS:
        assert set(i.chains) <= set(task.ASL_ITEMS) and set(i.subgoals) <= set(task.SUBGOALS) and set(i.objects) <= set(task.OML_ITEMS)
    for e in task.ERRORS:
        assert set(e.intentions) <= set(task.IL_ITEMS) and set(e.chains) <= set(task.ASL_ITEMS) and set(e.objects) <= set(task.OML_ITEMS)
    for a in task.ROBOT_ACTIONS:
        assert set(a.intentions) <= set(task.IL_ITEMS) and set(a.objects) <= set(task.OML_ITEMS)
        assert set(a.present) <= set(task.SUBGOALS) and set(a.past) <= set(task.SUBGOALS) and set(a.errors) <= set(task.AML_ITEMS)
        assert a.target in (None, "held_out", *task.OBJECTS)
    for goal, pre in task.PRECONDITIONS.items():
        assert goal in task.SUBGOALS and all(task.SUBGOALS.index(p) < task.SUBGOALS.index(goal) for p in pre)


def test_seed_names_are_present():
    for name in ("Communicate-Error", "Grasp-hold-bottle-to-remove-cup", "Reach-and-turn-glass", "Reach-turn-and-hand-over-glass",
                 "Reach-grasp-open-bottle-fill-glass", "Reach-full-glass-to-hand-over", "Request-glass", "Request-bottle",
                 "Hand-over-bottle", "Receive-object", "Suggest-drink", "Wait"):
        assert name in task.AEL_ITEMS
    for name in ("Cannot-remove-stopper", "Pour-from-closed-bottle", "Pour-into-inverted-glass", "Drink-from-empty-glass"):
        assert name in task.AML_ITEMS


def test_grip_priors_are_weights_not_a_one_to_one_map():
    for (grip, obj), goals in task.GRIP_PRIORS.items():
        assert len([w for w in goals.values() if w > 0]) >= 2, (grip, obj)
    assert task.grip_prior("grasp_ag", "bottle", "hand-over") > task.grip_prior("grasp_ag", "bottle", "pour")
    assert task.grip_prior("grasp_sg", "bottle", "pour") > task.grip_prior("grasp_sg", "bottle", "hand-over")


def test_exactly_one_utterance_per_pool():
    pools = {"ASL": task.ASL_ITEMS, "IL": task.IL_ITEMS, "AML": task.AML_ITEMS, "AEL": task.AEL_ITEMS}
    assert set(task.UTTERANCES) == set(pools)
    for layer, items in pools.items():
        assert list(task.UTTERANCES[layer]) == list(items), layer
        for item, u in task.UTTERANCES[layer].items():
            assert u.layer == layer and u.item == item and u.text and ":" in u.tag
    assert set(task.TAG_RESPONSES.values()) <= set(task.PARTNER_RESPONSES)


# -- coverage: every arrangement reaches the drink, with an active and with a passive partner ------

def _moves(active: bool):
    for a in task.ROBOT_ACTIONS:
        if a.requires or a.effects:
            yield a.name, a.requires, a.effects, a.response
    if active:
        for h in task.HUMAN_INITIATIVES:
            yield "human: " + h["name"], h["requires"], h["effects"], None


def _solve(start: dict, active: bool) -> list[str] | None:
    key = lambda s: tuple(sorted(s.items()))  # noqa: E731
    seen = {key(start)}
    queue = deque([(start, [])])
    while queue:
        state, path = queue.popleft()
        if state["drunk"]:
            return path
        for name, requires, effects, response in _moves(active):
            if response is not None:
                assert response in task.PARTNER_RESPONSES
            if all(state[k] in allowed for k, allowed in requires.items()):
                nxt = {**state, **effects}
                if key(nxt) not in seen:
                    seen.add(key(nxt))
                    queue.append((nxt, path + [name]))
    return None


ARRANGEMENTS = list(itertools.product(task.ZONES, task.OBJECT_STATES["bottle"], task.ZONES, task.OBJECT_STATES["glass"]))


def test_there_are_24_arrangements():
    assert len(ARRANGEMENTS) == 24


@pytest.mark.parametrize("active", [True, False], ids=["active", "passive"])
def test_every_arrangement_leads_to_the_drink(active):
    for bz, bs, gz, gs in ARRANGEMENTS:
        start = {"bottle_zone": bz, "bottle_state": bs, "glass_zone": gz, "glass_state": gs, "drunk": False}
        path = _solve(start, active)
        assert path is not None, (start, active)
