"""The executor's reach targets come from the Percept: what the person holds out is a target,
what they hold for themselves is not followed toward them."""

from __future__ import annotations

import pytest

from assistbot.cognition.percept import HandPercept, ObjectPercept, Percept
from assistbot.episode.executor import LIFTED_MEMORY, RobotExecutor
from assistbot.world import PAPER_ARRANGEMENTS, build_world


@pytest.fixture(scope="module")
def executor():
    return RobotExecutor(build_world(PAPER_ARRANGEMENTS["fig3"], 0))


def _percept(hand: HandPercept) -> Percept:
    return Percept(t=1.0, objects={"glass": ObjectPercept("glass", "HWS", "full", (-0.12, -0.03, 0.18)),
                                   "bottle": ObjectPercept("bottle", "RWS", "open", (0.2, 0.1, 0.0))}, hand=hand)


def test_an_object_the_person_drinks_from_is_not_a_target(executor):
    executor.see(_percept(HandPercept("drink", (-0.15, -0.03, 0.3), object_in_hand="glass", held_out=False)))
    assert executor._target_xy("glass") is None
    assert executor._target_xy("bottle") == (0.2, 0.1)


def test_an_object_held_out_to_the_robot_is_a_target(executor):
    executor.see(_percept(HandPercept("grasp_ag", (-0.1, -0.03, 0.2), object_in_hand="glass", held_out=True)))
    assert executor._target_xy("glass") == (-0.12, -0.03)
    assert executor._target_xy("held_out") == (-0.12, -0.03)


def test_a_standing_object_is_a_target(executor):
    executor.see(_percept(HandPercept("none", seen=True)))
    assert executor._target_xy("glass") == (-0.12, -0.03)


def _frames(executor, hands, t0=10.0):
    executor._hand_seen.clear()
    for k, h in enumerate(hands):
        p = _percept(h)
        p.t = t0 + 0.1 * k
        executor.see(p)


def _hand(posture, grip_x, end_x, held_out=None, hidden=False):
    """A hand whose posture read places its grip at ``grip_x`` and whose end is seen at ``end_x``."""
    held = posture in ("grasp_ag", "grasp_sg") if held_out is None else held_out
    return HandPercept(posture, (grip_x, 0.1, 0.24), object_in_hand="glass" if held else None, held_out=held,
                       end=(end_x, 0.1, 0.24), end_hidden=hidden)


def test_a_still_hand_whose_posture_flickers_still_holds_out(executor):
    # the posture read flickers (each class puts the grip elsewhere) and the robot's approaching hand
    # hides the end in some frames: the hand's end, where seen, has not moved
    hands = []
    for k in range(10):
        if k % 3 == 2:
            hands.append(_hand("grasp_ag", -0.14, -0.145, hidden=True))     # end cut short by the robot's hand
        else:
            hands.append(_hand("pointing" if k % 2 else "remove_stopper", -0.06 - 0.03 * (k % 2), -0.095))
    _frames(executor, hands)
    assert executor._offered()


def test_a_hand_paused_on_its_way_is_still_but_not_yet_held_out(executor):
    # she has lifted the bottle at her side and pauses before holding it out: still (offered), but the robot's
    # hand must not set off toward it yet (`HoldBottleForStopper` waits for held_out)
    paused = [HandPercept("grasp_ag", (-0.24, -0.16, 0.1), object_in_hand="bottle", held_out=False)] * 10
    _frames(executor, paused)
    assert executor._offered() and not executor._held_out()
    _frames(executor, [HandPercept("grasp_ag", (-0.06, -0.03, 0.2), object_in_hand="bottle", held_out=True)] * 10)
    assert executor._offered() and executor._held_out()


def test_a_hand_drawing_back_no_longer_holds_out(executor):
    hands = [_hand("reach", -0.10 - 0.02 * k, -0.10 - 0.02 * k, held_out=False) for k in range(10)]
    _frames(executor, hands)
    assert not executor._offered()
    _frames(executor, [_hand("pour", -0.1, -0.1, held_out=False)] + [_hand("grasp_ag", -0.1, -0.1)] * 9)
    assert not executor._offered()


def test_a_hand_that_has_just_poured_is_not_offering(executor):
    # poured, then holds the bottle still a moment above the table on its way to put it down
    executor._used_at = -float("inf")
    _frames(executor, [_hand("pour", -0.1, -0.1, held_out=False)], t0=10.0)
    _frames(executor, [_hand("reach", -0.13, -0.13, held_out=False)] * 15, t0=10.1)
    assert not executor._offered()
    # held still long after the pour: that is holding out
    _frames(executor, [_hand("grasp_ag", -0.13, -0.13)] * 10, t0=14.0)
    assert executor._offered()


def _holding(obj):
    return HandPercept("grasp_ag", (-0.1, 0.1, 0.2), object_in_hand=obj, held_out=obj is not None)


def test_a_hand_seen_holding_another_object_is_not_free_to_take_one(executor):
    _frames(executor, [_holding("glass")] * 10)
    assert executor._hand_busy("bottle")          # it holds the glass: it cannot take the bottle
    assert not executor._hand_busy("glass")       # the glass itself: already taken, or being taken


def test_a_hand_beside_an_object_standing_on_the_table_is_free(executor):
    # read as holding the bottle, which the same frames see standing on the table: the hand that has just
    # put it down rests beside it
    _frames(executor, [_holding("bottle")] * 10)
    assert not executor._hand_busy("glass")


def test_a_single_misread_frame_does_not_make_the_hand_busy(executor):
    _frames(executor, [_holding(None)] * 7 + [_holding("glass")] + [_holding(None)] * 2)
    assert not executor._hand_busy("bottle")


def test_a_hand_reaching_or_closing_is_placed_and_a_resting_one_is_not(executor):
    executor.see(_percept(HandPercept("grasp_sg", (-0.06, -0.05, 0.17), end_hidden=True)))
    assert executor._reaching_hand() == (-0.06, -0.05, 0.17)
    executor.see(_percept(HandPercept("none", (-0.3, -0.2, 0.1))))
    assert executor._reaching_hand() is None
    executor.see(_percept(HandPercept("reach", (-0.1, -0.05, 0.2), seen=False)))
    assert executor._reaching_hand() is None


def test_a_lost_frame_keeps_what_the_last_frame_showed(executor):
    # a frame that saw nothing (dropped, or both cameras blocked) between frames showing the glass held
    # out: the person still holds it out, and the robot reaches for where it was
    held_out = HandPercept("grasp_ag", (-0.1, -0.03, 0.2), object_in_hand="glass", held_out=True)
    executor.see(_percept(held_out))
    lost = Percept(t=1.1, objects={"glass": ObjectPercept("glass", seen=False),
                                   "bottle": ObjectPercept("bottle", seen=False)}, hand=HandPercept(seen=False))
    executor.see(lost)
    assert executor._human_holds("glass")
    assert executor._target_xy("held_out") == (-0.12, -0.03)
    # a frame that sees the hand empty ends it
    executor.see(_percept(HandPercept("none", seen=True)))
    assert not executor._human_holds("glass")


def test_a_lifted_object_is_grasped_no_lower_than_its_own_base_or_the_hand_over_it_says(executor):
    # the glass held out from above, placed by its own silhouette at 0.18 m (a hand over its top hides part of it,
    # and vision then places it low); the hand puts its base at 0.20: the higher decides
    hand = HandPercept("grasp_ag", (-0.1, -0.03, 0.18 + 0.1 + 0.02), object_in_hand="glass", held_out=True)
    executor.see(_percept(hand))
    assert executor._lifted("held_out") == pytest.approx(0.20)
    assert executor._lifted("glass") == pytest.approx(0.20)


def test_a_lifted_object_hidden_by_the_robots_hand_keeps_the_height_last_seen_then_the_hands(executor):
    seen = _percept(HandPercept("grasp_ag", (-0.1, -0.03, 0.28), object_in_hand="glass", held_out=True))
    seen.t = 20.0
    executor.see(seen)
    # the robot's hand comes in front of the glass: only her hand is seen, 5 cm lower than it holds the glass
    for t in (20.5, 22.0, 20.0 + LIFTED_MEMORY):
        hidden = _percept(HandPercept("grasp_ag", (-0.1, -0.03, 0.18 + 0.1 - 0.05), object_in_hand="glass", held_out=True))
        hidden.objects["glass"] = ObjectPercept("glass", "HWS", "full", (0.0, 0.0, 0.0), seen=False)
        hidden.t = t
        executor.see(hidden)
        assert executor._lifted("held_out") == pytest.approx(0.18), t
    # long unseen: from the hand that holds it
    hidden.t = 20.0 + LIFTED_MEMORY + 0.5
    executor.see(hidden)
    assert executor._lifted("held_out") == pytest.approx(0.13)
