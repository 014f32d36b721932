"""assistbot.cognition: the seed's layered field architecture (OL, OML, CSGL, ASL, IL, AML, AEL).

``Cognition(config).update(percept) -> Decision``. Wired on `assistbot.fields`
from the data of `assistbot.task`. `oracle_percept` is the labelled ground-truth
perception for tests; `load_timeline` reads percept timelines (YAML).
"""

from assistbot.cognition.architecture import Cognition, ol_items_of
from assistbot.cognition.config import LAYERS, CognitionConfig, default_config
from assistbot.cognition.oracle import ORACLE_LABEL, oracle_percept
from assistbot.cognition.percept import Decision, HandPercept, ObjectPercept, Percept, RobotPercept, Said
from assistbot.cognition.timeline import Timeline, load_timeline, timeline_from_dict

__all__ = [
    "Cognition", "CognitionConfig", "Decision", "HandPercept", "LAYERS", "ORACLE_LABEL", "ObjectPercept", "Percept",
    "RobotPercept", "Said", "Timeline", "default_config", "load_timeline", "ol_items_of", "oracle_percept", "timeline_from_dict",
]
