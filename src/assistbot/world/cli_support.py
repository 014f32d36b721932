"""Shared by `assistbot view` and `assistbot snapshot`: arrangement from a file or options, PNG writing."""

from __future__ import annotations

from pathlib import Path

from assistbot.errors import UserError
from assistbot.world.arrangement import Arrangement


def add_arrangement_arguments(parser) -> None:
    parser.add_argument("scenario", nargs="?", help="scenario YAML file whose objects: mapping gives the arrangement")
    parser.add_argument("--bottle", metavar="ZONE:STATE[@x,y]", help="bottle, e.g. HWS:closed (states closed, open)")
    parser.add_argument("--glass", metavar="ZONE:STATE[@x,y]", help="glass, e.g. RWS:inverted (states inverted, empty, full)")


def arrangement_from_args(args, default: Arrangement | None = None) -> Arrangement | None:
    if args.scenario:
        if args.bottle or args.glass:
            raise UserError("arguments", "--bottle/--glass", "give either a scenario file or options, not both")
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
    if args.bottle or args.glass:
        if not (args.bottle and args.glass):
            raise UserError("arguments", "--glass" if args.bottle else "--bottle", "give both --bottle and --glass")
        return Arrangement.from_options(args.bottle, args.glass)
    return default


def write_png(world, path: Path, camera: str = "scene_cam", width: int = 640, height: int = 480) -> Path:
    import imageio.v3 as iio

    from assistbot.world.render import Renderer

    path.parent.mkdir(parents=True, exist_ok=True)
    world.sync_liquid()
    with Renderer(world.model, width, height) as r:
        iio.imwrite(path, r.rgb(world.data, camera))
    return path
