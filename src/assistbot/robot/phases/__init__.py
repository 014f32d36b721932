"""The phases motion primitives are made of (`base.Phase`): moves of the hand, rolls of the wrist, grips,
waits, the put-down by feel, and bookkeeping steps."""

from assistbot.robot.phases.base import Phase
from assistbot.robot.phases.bookkeeping import HoldAt, RememberPlace, SetCarrying
from assistbot.robot.phases.grip import OPENED, FreeIdleFingers, Grip, Open
from assistbot.robot.phases.lower_until_supported import LowerUntilSupported
from assistbot.robot.phases.move import REACH_WAIT, UNREACHABLE_PATIENCE, Move, unreachable
from assistbot.robot.phases.relative import BackOff, Relative, Rise, RiseClear, TakeFromUnder
from assistbot.robot.phases.roll import Roll, Unroll
from assistbot.robot.phases.wait import Wait, WaitFor
from assistbot.robot.phases.wait_for_let_go import WaitForLetGo
from assistbot.robot.phases.wait_for_take import WaitForTake

__all__ = ["OPENED", "REACH_WAIT", "UNREACHABLE_PATIENCE", "BackOff", "FreeIdleFingers", "Grip", "HoldAt", "LowerUntilSupported", "Move",
           "Open", "Phase", "Relative", "RememberPlace", "Rise", "RiseClear", "Roll", "SetCarrying", "TakeFromUnder", "Unroll", "Wait",
           "WaitFor", "WaitForLetGo", "WaitForTake", "unreachable"]
