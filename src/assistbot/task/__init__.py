"""assistbot.task: the drinking task as plain data (see `assistbot.task.drinking`).

Imports nothing of the project. Cognition builds its connection tables from
these associations; the human model reacts to utterance tags; the robot
realises `ROBOT_ACTIONS`.
"""

from assistbot.task.drinking import (
    AEL_ITEMS,
    AML_ITEMS,
    ASL_CHAINS,
    ASL_ITEMS,
    ERRORS,
    FAILURE_OF,
    FINAL_GOAL,
    GRIP_PRIORS,
    HAND_POSTURES,
    HOLDERS,
    HUMAN_INITIATIVES,
    IL_ITEMS,
    MOTION_ACTIONS,
    INTENTIONS,
    OBJECT_STATES,
    OBJECTS,
    OL_ITEMS,
    OML_ITEMS,
    PARTNER_RESPONSES,
    PRECONDITIONS,
    ROBOT_ACTION_BY_NAME,
    ROBOT_ACTIONS,
    SHORT_NAMES,
    SUBGOALS,
    ACHIEVED_BY,
    ACTION_FAILURES,
    FALLS,
    AGAINST_REQUIREMENT,
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
