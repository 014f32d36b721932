"""Physics and rendering speed of the assistbot scene.

Prints simulated seconds per wall second for the full scene with the liquid and with the
particles taken out of the simulation (disabled collisions, frozen), and milliseconds per
offscreen frame at 320x240 and 640x480 for the scene camera and a head camera.
Goal: physics >= 5x real time with the particles on a 2-core CPU.
Run: .venv/bin/python benchmarks/physics_speed.py
"""

from __future__ import annotations

import time

import mujoco

from assistbot.world import PAPER_ARRANGEMENTS, Arrangement, build_world
from assistbot.world.render import Renderer, gl_backend

SIM_SECONDS = 4.0


def physics(arrangement, particles: bool) -> tuple[float, float]:
    w = build_world(arrangement)
    if not particles:  # take the liquid out: no collisions, weightless, never moves
        m = w.model
        m.geom_contype[w.particle_geoms] = 0
        m.geom_conaffinity[w.particle_geoms] = 0
        m.body_gravcomp[w.particle_bodies] = 1.0
    w.step(50)  # warm up
    n = int(SIM_SECONDS / w.model.opt.timestep)
    t = time.perf_counter()
    w.step(n)
    wall = time.perf_counter() - t
    return SIM_SECONDS / wall, wall / n * 1e3


def frames(width: int, height: int, camera: str, n: int = 20, shadows: bool = False) -> float:
    w = build_world(PAPER_ARRANGEMENTS["fig3"])
    with Renderer(w.model, width, height, shadows=shadows) as r:
        r.rgb(w.data, camera)
        t = time.perf_counter()
        for _ in range(n):
            w.step(5)
            r.rgb(w.data, camera)
        return (time.perf_counter() - t) / n * 1e3


def main() -> None:
    print(f"mujoco {mujoco.__version__}, GL backend {gl_backend()}, {SIM_SECONDS:g} s simulated per case")
    cases = {
        "fig3 (closed bottle HWS, inverted glass RWS)": PAPER_ARRANGEMENTS["fig3"],
        "full glass RWS, open bottle HWS": Arrangement.from_options("HWS:open", "RWS:full"),
    }
    for label, arr in cases.items():
        for particles in (True, False):
            rt, ms = physics(arr, particles)
            tag = "with particles   " if particles else "without particles"
            print(f"physics {tag} {label}: {rt:5.1f} x real time ({ms:.3f} ms per 2 ms step)")
    for cam in ("scene_cam", "head_cam_left"):
        for (wd, ht) in ((320, 240), (640, 480)):
            print(f"render {cam:13s} {wd}x{ht}: {frames(wd, ht, cam):6.1f} ms per frame (incl. 5 physics steps ~ 2 ms)")
    print(f"render scene_cam     640x480 with shadows: {frames(640, 480, 'scene_cam', 5, True):6.1f} ms per frame")
    print("note: a closed bottle's stopper weld costs ~0.15 ms per step (measured by switching it off);"
          " the particle contacts ~0.2 ms")


if __name__ == "__main__":
    main()
