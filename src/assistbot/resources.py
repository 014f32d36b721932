"""Where the files that travel with the package are: the MJCF scene, the vision templates and the
shipped scenarios. They live inside the package (``assistbot/assets``, ``assistbot/scenarios``), so
an installed wheel has them as much as a checkout does (whose top-level ``assets`` and ``scenarios``
are links to these folders); they are found through `importlib.resources`, not the repository layout."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

_PACKAGE = resources.files("assistbot")

#: the MJCF models (scene.xml includes the others)
MJCF = Path(str(_PACKAGE / "assets" / "mjcf"))
#: the vision template library and the colour calibration (`assistbot templates` writes them)
TEMPLATES = Path(str(_PACKAGE / "assets" / "templates"))
#: labelled scenes the shipped template library is learnt from (2160 per hand posture)
LIBRARY_SCENES = 19440
#: the shipped scenarios, their sweeps and percept timelines
SCENARIOS = Path(str(_PACKAGE / "scenarios"))
