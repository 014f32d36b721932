"""Motion primitives: small objects that realise the robot's AEL actions in the physics.

A primitive is a list of phases (move the TCP along a minimum-jerk profile,
close or open the hand, wait for a condition). ``start(target_xy)`` begins
it; ``tick(dt, target_xy) -> Progress`` is called once per control tick with
the current perception of the action's target (table x, y of the object or
the human's hand, or None when it is not seen). The perception feeds the
primitive's `TargetField`; the field's peak is the x, y the arm goes to,
while heights and approach orientations come from the primitive.

Every phase has a time limit; a primitive that cannot do its job ends
FAILED with a reason (unreachable target, target beyond the hand-over zone,
IK without solution, nothing in the hand, object slipped, human did not take
the object, stopper not removed, glass not seen).

The primitives (all friction grasps from the side, no welds):
  ReachAndGrasp, ReachGraspLift   grasp (and lift) an object standing in the RWS
  TurnGlass                       grasp the inverted glass, roll it 180 deg in the air, put it down upright
  PlaceInRWS                      grasp, carry, put down upright at ``spot``
  Pour                            grasp the open bottle, tilt it 140 deg beside and above the glass at
                                  ``locate("glass")`` (mouth over the glass centre), hold, tilt back,
                                  put the bottle back where it stood
  HoldBottleForStopper            grasp the closed bottle, hold it out upright at the middle line, wait
                                  for ``stopper_removed()``, put it back
  HandOver, TurnAndHandOver       carry (HandOver: held by its upper part; TurnAndHandOver: turned first)
                                  and hold out in the hand-over zone; let go once the
                                  wrist feels the person take it (`WaitForTake`); withdraw
  Receive                         grasp what the human holds out (target: the human's hand), wait until
                                  the human lets go, put it down in the RWS
  TakeFromTable                   show a spot both reach with the open hand, wait until something is set
                                  down there, take it to the RWS
  Request, Retract                open hand held out palm up near the middle line; back to rest

One module per primitive; `base` holds the `Primitive` they derive from, the phases they are made of
are `assistbot.robot.phases`. Shared by several primitives: `geometry` (the objects as the hand
grasps them, side-grasp poses), `places` (where objects are held out and put down), the phase
sequences `reaching`, `putting_down`, `handing_over`, and the `carry_over` phase.

Callbacks a caller passes as keywords (every primitive accepts them; see `Primitive.__init__`):
``human_holds()``, ``locate(name)``, ``stopper_removed()``. They come from perception.
"""


from assistbot.interfaces import Status
from assistbot.robot.phases import Move, Phase
from assistbot.robot.primitives.base import Primitive
from assistbot.robot.primitives.geometry import (
    GRASP_HEIGHT,
    LIFT,
    RADIUS,
    WALL_TOP,
    held_grasp_height,
    offer_grasp_height,
    side_grasp_pose,
)
from assistbot.robot.primitives.hand_over import HandOver
from assistbot.robot.primitives.handing_over import OFFER_PHASE
from assistbot.robot.primitives.hold_bottle_for_stopper import HoldBottleForStopper
from assistbot.robot.primitives.place_in_rws import PlaceInRWS
from assistbot.robot.primitives.places import HOLD_OUT_XY, free_rws_spot, offer_point
from assistbot.robot.primitives.pour import Pour
from assistbot.robot.primitives.putting_down import put_down_at
from assistbot.robot.primitives.reach_and_grasp import ReachAndGrasp
from assistbot.robot.primitives.reach_grasp_lift import ReachGraspLift
from assistbot.robot.primitives.reaching import reach_and_grasp_phases, retract_phases
from assistbot.robot.primitives.receive import Receive
from assistbot.robot.primitives.request import Request
from assistbot.robot.primitives.retract import Retract
from assistbot.robot.primitives.take_from_table import TakeFromTable
from assistbot.robot.primitives.turn_and_hand_over import TurnAndHandOver
from assistbot.robot.primitives.turn_glass import TurnGlass
from assistbot.robot.progress import Progress

__all__ = [
    "GRASP_HEIGHT", "HOLD_OUT_XY", "LIFT", "OFFER_PHASE", "RADIUS", "WALL_TOP",
    "HandOver", "HoldBottleForStopper", "Move", "Phase", "PlaceInRWS", "Pour", "Primitive", "Progress", "ReachAndGrasp",
    "ReachGraspLift", "Receive", "Request", "Retract", "Status", "TakeFromTable", "TurnAndHandOver", "TurnGlass",
    "free_rws_spot", "held_grasp_height", "offer_grasp_height", "offer_point", "put_down_at", "reach_and_grasp_phases", "retract_phases",
    "side_grasp_pose",
]
