"""Shared by `assistbot view` and `assistbot snapshot`: arrangement from a file or options, PNG writing."""

from __future__ import annotations

from pathlib import Path

from assistbot import catalogue
from assistbot.errors import UserError
from assistbot.world.arrangement import Arrangement


def add_arrangement_arguments(parser) -> None:
    parser.add_argument("scenario", nargs="?", help="scenario YAML file whose objects: mapping gives the arrangement")
    for name, states in catalogue.STATES.items():
        parser.add_argument(f"--{name}", metavar="ZONE:STATE[@x,y]", help=f"{name}, e.g. HWS:{states[0]} (states {', '.join(states)})")


def arrangement_from_args(args, default: Arrangement | None = None) -> Arrangement | None:
    options = [f"--{name}" for name in catalogue.TASK_OBJECTS]
    given = [getattr(args, name) for name in catalogue.TASK_OBJECTS]
    if args.scenario:
        if any(given):
            raise UserError("arguments", "/".join(options), "give either a scenario file or options, not both")
        path = Path(args.scenario)
        if not path.is_file():
            raise UserError(str(path), "file", "not found")
        import yaml

        try:
            doc = yaml.safe_load(path.read_text())
        except yaml.YAMLError as exc:
            raise UserError(str(path), "yaml", f"not valid YAML ({exc})".replace("\n", " ")) from None
        if not isinstance(doc, dict) or "objects" not in doc:
            raise UserError(str(path), "objects", "missing; give objects: {bottle: {zone, state}, glass: {zone, state}}")
        return Arrangement.from_mapping(doc["objects"], str(path))
    if any(given):
        if not all(given):
            missing = [o for o, g in zip(options, given) if not g]
            raise UserError("arguments", missing[0], f"give all of {', '.join(options)}")
        return Arrangement.from_options(*given)
    return default


def write_png(world, path: Path, camera: str = "scene_cam", width: int = 640, height: int = 480) -> Path:
    import imageio.v3 as iio

    from assistbot.world.render import Renderer

    path.parent.mkdir(parents=True, exist_ok=True)
    world.sync_liquid()
    with Renderer(world.model, width, height) as r:
        iio.imwrite(path, r.rgb(world.data, camera))
    return path
