#!/usr/bin/env python3
"""MuJoCo solver-option sweep for the MJCF export: runs every exported scene under several
option sets and prints STB (free objects moving < 1 cm and turning < 0.1 rad), the worst
displacement, non-finite runs, the deepest contact penetration at the end and the wall time.

The scenes are the exports the export benchmark wrote (scripts/bench_exports.py, default
/tmp/scenesmith_bench_exports/*). Each variant is a copy of scene.xml with the <option> element
and the collision geom defaults replaced (written next to the original so mesh paths resolve,
removed afterwards); --tilt turns gravity off vertical (a sloped world, where soft contacts
creep), --drop lifts every free body before the run to make settling harder, and
displacement is then measured from where the body stood before it was lifted.

Usage: scripts/bench_mujoco_solver.py [--scenes GLOB] [--tilt 5] [--drop 0.005] [--seconds 5]
"""

import argparse
import glob
import math
import os
import re
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, ROOT)

from drake_bridge.conformance import op_mujoco_check  # noqa: E402

# name: (option attributes, collision default attributes)
VARIANTS = {
    "mujoco defaults": ('timestep="0.002"',
                        'condim="3" solref="0.02 1" solimp="0.9 0.95 0.001 0.5 2" margin="0"'),
    "pyramidal, impratio 1, condim 4": (
        'timestep="0.002" integrator="implicitfast" cone="pyramidal" impratio="1"',
        'condim="4" solref="0.02 1" solimp="0.95 0.99 0.001 0.5 2" margin="0"'),
    "elliptic, impratio 1, condim 4": (
        'timestep="0.002" integrator="implicitfast" cone="elliptic" impratio="1"',
        'condim="4" solref="0.02 1" solimp="0.95 0.99 0.001 0.5 2" margin="0"'),
    "elliptic, impratio 10, condim 3": (
        'timestep="0.002" integrator="implicitfast" cone="elliptic" impratio="10"',
        'condim="3" solref="0.02 1" solimp="0.95 0.99 0.001 0.5 2" margin="0"'),
    "chosen (elliptic, impratio 10, condim 4)": (
        'timestep="0.002" integrator="implicitfast" cone="elliptic" impratio="10"',
        'condim="4" solref="0.02 1" solimp="0.95 0.99 0.001 0.5 2" margin="0"'),
    "chosen + noslip 10": (
        'timestep="0.002" integrator="implicitfast" cone="elliptic" impratio="10" '
        'noslip_iterations="10"',
        'condim="4" solref="0.02 1" solimp="0.95 0.99 0.001 0.5 2" margin="0"'),
    "chosen, timestep 5 ms": (
        'timestep="0.005" integrator="implicitfast" cone="elliptic" impratio="10"',
        'condim="4" solref="0.02 1" solimp="0.95 0.99 0.001 0.5 2" margin="0"'),
    "chosen, margin 1 mm": (
        'timestep="0.002" integrator="implicitfast" cone="elliptic" impratio="10"',
        'condim="4" solref="0.02 1" solimp="0.95 0.99 0.001 0.5 2" margin="0.001"'),
}


def variant_xml(xml, option, collision, drop, tilt_deg):
    if tilt_deg:
        t = math.radians(tilt_deg)
        option += f' gravity="{9.81 * math.sin(t)} 0 {-9.81 * math.cos(t)}"'
    xml = re.sub(r"<option [^>]*/>", f"<option {option}/>", xml, count=1)

    def fix_default(m):
        geom = m.group(0)
        for attr in ("condim", "solref", "solimp", "margin"):
            geom = re.sub(rf' {attr}="[^"]*"', "", geom)
        return geom.replace("<geom ", f"<geom {collision} ", 1)

    xml = re.sub(r'(?<=<default class="collision">)\s*<geom [^>]*/>', fix_default, xml, count=1)
    if drop:
        def lift(m):
            x, y, z = (float(v) for v in m.group(2).split())
            return f'{m.group(1)}pos="{x} {y} {z + drop}"{m.group(3)}'
        xml = re.sub(r'(<body name="[^"]*" )pos="([^"]*)"([^>]*>\s*<freejoint)', lift, xml)
    return xml


def creep(option, collision, tilt_deg=15.0, seconds=5.0):
    """Creep on a slope below the friction angle: a 0.3 kg box (mu 0.4) and a 0.25 kg upright
    cylinder (mu 0.35) on a plane with gravity tilted `tilt_deg` (tan 15 deg = 0.27 < mu), so
    with exact Coulomb friction neither moves. Returns their displacement after `seconds`, m."""
    import mujoco

    t = math.radians(tilt_deg)
    geom = re.sub(r'margin="[^"]*"', "", collision)
    xml = f"""<mujoco><option {option} gravity="{9.81 * math.sin(t)} 0 {-9.81 * math.cos(t)}"/>
      <worldbody>
        <geom type="box" size="2 2 0.05" pos="0 0 -0.05" friction="0.4 0.005 0.0001" {geom}/>
        <body pos="0 0 0.05"><freejoint/>
          <geom type="box" size="0.05 0.04 0.05" mass="0.3" friction="0.4 0.005 0.0001" {geom}/>
        </body>
        <body pos="0.5 0 0.05"><freejoint/>
          <geom type="cylinder" size="0.04 0.05" mass="0.25" friction="0.35 0.005 0.0001" {geom}/>
        </body>
      </worldbody></mujoco>"""
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    x0 = d.xpos.copy()
    while d.time < seconds:
        mujoco.mj_step(m, d)
    return [math.dist(d.xpos[i], x0[i]) for i in (1, 2)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", default="/tmp/scenesmith_bench_exports/*")
    ap.add_argument("--drop", type=float, default=0.0, help="lift free bodies by this, m")
    ap.add_argument("--seconds", type=float, default=5.0)
    ap.add_argument("--tilt", type=float, default=0.0,
                    help="tilt gravity by this many degrees (a sloped world: tests creep)")
    ap.add_argument("--only", default="", help="semicolon-separated variant names")
    ap.add_argument("--creep-only", action="store_true", help="only the slope-creep test")
    a = ap.parse_args()
    scenes = sorted(p for p in glob.glob(os.path.join(a.scenes, "export/mujoco/scene.xml")))
    names = [n for n in VARIANTS if not a.only or n in a.only.split(";")]
    if a.creep_only:
        scenes = []
    elif not scenes:
        print(f"no exported scenes under {a.scenes}; run scripts/bench_exports.py first")
        return 1
    if scenes:
        print(f"{len(scenes)} scenes, {a.seconds} s each, free bodies lifted "
              f"{a.drop * 1e3:.1f} mm, gravity tilted {a.tilt} deg")
        print("variant | STB | worst disp mm | worst rot rad | non-finite | max pen mm | wall s")
        print("--- | --- | --- | --- | --- | --- | ---")
    for name in names if scenes else []:
        option, collision = VARIANTS[name]
        free = stable = nonfinite = 0
        worst_d = worst_r = pen = 0.0
        wall = 0.0
        for path in scenes:
            text = open(path).read()
            tmp = os.path.join(os.path.dirname(path), ".bench_variant.xml")
            with open(tmp, "w") as f:
                f.write(variant_xml(text, option, collision, a.drop, a.tilt))
            try:
                t0 = time.perf_counter()
                r = op_mujoco_check({"xml": tmp, "seconds": a.seconds})
                wall += time.perf_counter() - t0
            finally:
                os.remove(tmp)
            nonfinite += not r["finite"]
            pen = max(pen, r["max_penetration_at_end_m"])
            for b in r["bodies"]:
                if not b["free"]:
                    continue
                free += 1
                if b["final_pos"] is None:
                    d = rot = float("inf")
                else:
                    # From where the object stood before it was lifted.
                    x0 = b["initial_pos"]
                    d = math.dist(b["final_pos"], [x0[0], x0[1], x0[2] - a.drop])
                    rot = b["rotation_rad"]
                worst_d, worst_r = max(worst_d, d), max(worst_r, rot)
                stable += d < 0.01 and rot < 0.1
        print(f"{name} | {stable}/{free} = {100 * stable / max(1, free):.2f} % | "
              f"{worst_d * 1e3:.1f} | {worst_r:.3f} | {nonfinite} | {pen * 1e3:.2f} | {wall:.1f}")
        sys.stdout.flush()
    print()
    print("slope creep (gravity tilted 15 deg, below the friction angle; 5 s)")
    print("variant | box mm | cylinder mm")
    print("--- | --- | ---")
    for name in names:
        box, cyl = creep(*VARIANTS[name])
        print(f"{name} | {box * 1e3:.2f} | {cyl * 1e3:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
