"""`assistbot partners`: a contact sheet of people drawn from the partner population, and their attributes."""

from __future__ import annotations

NAME = "partners"
HELP = "render people of the partner population (one still each, holding out the open hand) with their attributes"
ORDER = 22

#: simulated seconds the person holds out the open hand before the picture
POSE_SECONDS = 3.0
COLUMNS = 4


def add_arguments(parser) -> None:
    parser.add_argument("--n", type=int, default=12, help="how many partners (default 12)")
    parser.add_argument("--first", type=int, default=0, help="the first partner seed (default 0): partners FIRST .. FIRST+N-1")
    parser.add_argument("--out", default="render/partners", help="output folder (default render/partners)")
    parser.add_argument("--camera", default="scene_cam", help="camera name (default scene_cam: from the person's right)")
    parser.add_argument("--size", default="400x300", help="WIDTHxHEIGHT of each still (default 400x300)")


def _caption(p) -> list[str]:
    b = p.body
    lines = [f"partner {p.seed}",
             f"arm {b.upper_arm:.2f}/{b.forearm:.2f}  shoulder {b.shoulder_height:.2f}",
             f"seat back {100 * b.seat_back:.0f} cm, side {100 * b.seat_side:+.0f} cm"]
    impair = []
    if b.rom:
        impair.append(f"ROM -{100 * b.rom:.0f}%")
    if p.tremor_amplitude:
        impair.append(f"tremor {1000 * p.tremor_amplitude:.0f} mm {p.tremor_frequency:.1f} Hz")
    if p.drop_chance:
        impair.append(f"drops {100 * p.drop_chance:.0f}%")
    if p.hesitation:
        impair.append(f"hesitates {p.hesitation:.1f} s")
    lines.append(", ".join(impair) or "no impairment")
    lines.append(f"speed x{p.speed_factor:.2f}, reacts x{p.reaction_factor:.2f}")
    return lines


def still(p, camera: str, width: int, height: int):
    """The scene with partner ``p`` holding out the open hand, captioned with their attributes (an RGB image)."""
    import cv2

    from assistbot.human.controller import HumanController
    from assistbot.human.script import parse_human
    from assistbot.world import Arrangement, build_world
    from assistbot.world.render import Renderer

    world = build_world(Arrangement.from_options("HWS:open", "RWS:empty"), body=p.body)
    person = HumanController(world, config=parse_human({"profile": "passive", "partner": p}))
    person.start("request", hold=POSE_SECONDS + 1.0)
    person.run(POSE_SECONDS)
    world.sync_liquid()
    with Renderer(world.model, width, height) as r:
        img = r.rgb(world.data, camera).copy()
    for i, line in enumerate(_caption(p)):
        y = 16 + 15 * i
        cv2.putText(img, line, (6, y), cv2.FONT_HERSHEY_SIMPLEX, 0.42, (0, 0, 0), 3, cv2.LINE_AA)
        cv2.putText(img, line, (6, y), cv2.FONT_HERSHEY_SIMPLEX, 0.42, (255, 255, 255), 1, cv2.LINE_AA)
    return img


def run(args) -> int:
    import csv
    from pathlib import Path

    import imageio.v3 as iio
    import numpy as np

    from assistbot.errors import UserError
    from assistbot.human.population import sample_partner
    from assistbot.world import CAMERAS

    if args.n < 1:
        raise UserError("arguments", "--n", f"at least 1 partner, got {args.n}")
    if args.first < 0:
        raise UserError("arguments", "--first", f"a partner seed is >= 0, got {args.first}")
    if args.camera not in CAMERAS:
        raise UserError("arguments", "--camera", f"unknown camera {args.camera!r}; use one of {', '.join(CAMERAS)}")
    try:
        width, height = (int(v) for v in args.size.lower().split("x"))
    except ValueError:
        raise UserError("arguments", "--size", f"expected WIDTHxHEIGHT, got {args.size!r}") from None
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    people = [sample_partner(s) for s in range(args.first, args.first + args.n)]
    tiles = []
    for p in people:
        tiles.append(still(p, args.camera, width, height))
        print(f"partner {p.seed}", flush=True)
    rows = -(-len(tiles) // COLUMNS)
    cols = min(COLUMNS, len(tiles))
    sheet = np.full((rows * height, cols * width, 3), 255, np.uint8)
    for i, img in enumerate(tiles):
        r, c = divmod(i, COLUMNS)
        sheet[r * height:(r + 1) * height, c * width:(c + 1) * width] = img
    iio.imwrite(out / "partners.png", sheet)
    with open(out / "partners.csv", "w", newline="") as f:
        keys = list(people[0].to_dict())
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for p in people:
            w.writerow(p.to_dict())
    print(out / "partners.png")
    print(out / "partners.csv")
    return 0
