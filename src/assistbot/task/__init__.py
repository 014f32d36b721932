"""assistbot.task: the drinking task as plain data (see `assistbot.task.drinking`).

Imports nothing of the project but the object catalogue (`assistbot.catalogue`). Cognition builds its connection tables from
these associations; the human model reacts to utterance tags; the robot
realises `ROBOT_ACTIONS`.
"""

from assistbot.task.drinking import (
    ACHIEVED_BY,
    ACTION_FAILURES,
    AEL_ITEMS,
    AGAINST_REQUIREMENT,
    AML_ITEMS,
    ASL_CHAINS,
    ASL_ITEMS,
    DRINK_FRACTION,
    ERRORS,
    FAILURE_OF,
    FALLS,
    FINAL_GOAL,
    GRIP_CHAINS,
    GRIP_PRIORS,
    HAND_POSTURES,
    HOLDERS,
    HUMAN_INITIATIVES,
    IL_ITEMS,
    INTENTION_ACTS,
    INTENTIONS,
    MOTION_ACTIONS,
    OBJECT_STATES,
    OBJECTS,
    OL_GRIP_ITEMS,
    OL_ITEMS,
    OML_ITEMS,
    PARTNER_RESPONSES,
    PRECONDITIONS,
    ROBOT_ACTION_BY_NAME,
    ROBOT_ACTIONS,
    SHORT_NAMES,
    SUBGOALS,
    TAG_RESPONSES,
    UTTERANCES,
    ZONES,
    Chain,
    Error,
    Intention,
    RobotAction,
    Utterance,
    facts_against,
    grip_prior,
    oml_item,
)

__all__ = [n for n in dir() if not n.startswith("_")]
