#!/usr/bin/env python3
"""What simulating a generated scene costs a Drake user: per scene directory, the contact
surfaces and polygons at rest and the wall time of one 1 ms step of the whole scene, loaded
as the README tells users to load it (Drake's default plant config), and under point contact.

    .venv/bin/python scripts/bench_contact.py out/kitchen out/bedroom [--seconds 0.3]

Prints a Markdown table; the heaviest category pairs by contact polygons follow each row with
--pairs. Run it with nothing else on the machine: the step times are wall times.
"""

import argparse
import collections
import os
import re
import sys
import time

from pydrake.all import (
    DiagramBuilder,
    HydroelasticContactRepresentation,
    LoadModelDirectives,
    Parser,
    ProcessModelDirectives,
    Simulator,
)
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig


def build(scene_dir, contact_model=None):
    """Diagram, plant and scene graph of a scene directory in Drake's default plant config
    (or with `contact_model` set)."""
    config = MultibodyPlantConfig(time_step=1e-3)
    if contact_model:
        config.contact_model = contact_model
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(config, builder)
    parser = Parser(plant)
    parser.package_map().AddPackageXml(os.path.join(scene_dir, "package.xml"))
    ProcessModelDirectives(
        LoadModelDirectives(os.path.join(scene_dir, "scene.dmd.yaml")), plant, parser)
    plant.Finalize()
    return builder.Build(), plant, scene_graph


def step_ms(scene_dir, seconds, contact_model=None):
    """Wall milliseconds per 1 ms step over `seconds` simulated."""
    diagram, _, _ = build(scene_dir, contact_model)
    sim = Simulator(diagram)
    sim.Initialize()
    t0 = time.perf_counter()
    sim.AdvanceTo(seconds)
    return 1e3 * (time.perf_counter() - t0) / (seconds / 1e-3)


def category(name):
    """`plate_3::collision_002` -> `plate`."""
    return re.sub(r"_\d+$", "", name.split("::")[0])


def contacts(scene_dir):
    """(free bodies, hydroelastic surfaces, polygons, polygons per category pair) after 10 ms."""
    diagram, plant, scene_graph = build(scene_dir)
    sim = Simulator(diagram)
    sim.Initialize()
    sim.AdvanceTo(0.01)
    ctx = scene_graph.GetMyContextFromRoot(sim.get_context())
    query = scene_graph.get_query_output_port().Eval(ctx)
    inspector = query.inspector()
    surfaces = query.ComputeContactSurfaces(HydroelasticContactRepresentation.kPolygon)
    pairs = collections.Counter()
    for s in surfaces:
        a, b = sorted([category(inspector.GetName(s.id_M())),
                       category(inspector.GetName(s.id_N()))])
        pairs[(a, b)] += s.num_faces()
    free = len(plant.GetFloatingBaseBodies())
    return free, len(surfaces), sum(pairs.values()), pairs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scenes", nargs="+", help="scene directories")
    ap.add_argument("--seconds", type=float, default=0.3, help="simulated seconds per timing")
    ap.add_argument("--pairs", type=int, default=0, help="heaviest category pairs to list")
    args = ap.parse_args()
    print("| scene | free bodies | contact surfaces | contact polygons | ms/step Drake defaults "
          "| ms/step point |")
    print("|---|---|---|---|---|---|")
    for d in args.scenes:
        if not os.path.isfile(os.path.join(d, "scene.dmd.yaml")):
            print(f"{d}: no scene.dmd.yaml", file=sys.stderr)
            return 2
        free, n_surfaces, polygons, pairs = contacts(d)
        hydro = step_ms(d, args.seconds)
        point = step_ms(d, args.seconds, "point")
        print(f"| {os.path.basename(os.path.normpath(d))} | {free} | {n_surfaces} | {polygons} "
              f"| {hydro:.1f} | {point:.1f} |", flush=True)
        for (a, b), n in pairs.most_common(args.pairs):
            print(f"|   {a} / {b} | | | {n} | | |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
