"""An independent geometric check of a pick-and-place goal in a scene state, for
bench_robot_eval.py: how often does the built-in evaluator (drake_bridge/evaluator) agree with
a check that reaches its verdict another way?

The built-in evaluator compares boxes and footprints; this check probes the scene with points
(Drake's signed distance to a point, on the state loaded with Drake's default plant from the
directives as written) and knows nothing of the evaluator's code:

- below(t): the first other scene instance met going down from t's centre of mass in 2 mm
  steps, at most 3 cm under the bottom of t's box.
- on(t, r): t's collision geometry within 5 mm of r's (signed distance, the contact the task
  statement's threshold allows), and below(t) is r, or is something that is itself on r (one
  level: a fruit on a plate on the table is on the table).
- inside(t, r): below(...) is r or something inside r, and at the height of t's centre of
  mass, probes along +x, -x, +y and -y (5 mm steps, within r's bounding box) meet r in at least
  three of the four directions: r's walls stand around t.
- near(t, r): signed distance between t and r at most 0.15 m.

The bounding boxes are the world boxes around Drake's oriented boxes
(`QueryObject.ComputeObbInWorld`). Used as a library
(`check(scene_dir, directives, predicate, target, reference)` -> (holds, evidence)) or from
the command line on one state.
"""

import argparse
import json
import os

import numpy as np
from pydrake.geometry import Role
from pydrake.multibody.parsing import LoadModelDirectives, Parser, ProcessModelDirectives
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.systems.framework import DiagramBuilder

#: Raised whenever a verdict rule changes: bench_robot_eval.py's cached verdicts of an older
#: version are computed again.
VERSION = 2
CONTACT_M = 0.005
NEAR_M = 0.15
DOWN_STEP_M = 0.002
DOWN_REACH_M = 0.03
SIDE_STEP_M = 0.005
WALLS_NEEDED = 3


class State:
    """A scene state: the directives loaded in Drake's default plant (scene package only)."""

    def __init__(self, scene_dir, directives):
        builder = DiagramBuilder()
        plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(), builder)
        parser = Parser(plant)
        parser.package_map().AddPackageXml(os.path.join(scene_dir, "package.xml"))
        path = directives if os.path.isabs(directives) else os.path.join(scene_dir, directives)
        ProcessModelDirectives(LoadModelDirectives(path), plant, parser)
        plant.Finalize()
        diagram = builder.Build()
        context = diagram.CreateDefaultContext()
        self.plant = plant
        self.plant_context = plant.GetMyContextFromRoot(context)
        self.query = plant.get_geometry_query_input_port().Eval(self.plant_context)
        inspector = self.query.inspector()
        self.instance_of = {}
        for g in inspector.GetAllGeometryIds(Role.kProximity):
            body = plant.GetBodyFromFrameId(inspector.GetFrameId(g))
            self.instance_of[g] = plant.GetModelInstanceName(body.model_instance())
        self._obbs = {}
        self.approximated = 0
        self.pairs_skipped = 0

    def ids(self, instance):
        return [g for g, name in self.instance_of.items() if name == instance]

    def _obb(self, g):
        """(X_WB, half widths) of geometry g's oriented box, cached."""
        if g not in self._obbs:
            obb = self.query.ComputeObbInWorld(g)
            if obb is None:
                raise ValueError(f"{self.instance_of[g]}: no bounding box for geometry {g}")
            self._obbs[g] = (obb.pose(), np.asarray(obb.half_width()))
        return self._obbs[g]

    def box(self, instance):
        """(lo, hi): the world box around the instance's collision geometry."""
        lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
        signs = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
        for g in self.ids(instance):
            X, half = self._obb(g)
            corners = X.multiply((signs * half).T).T
            lo, hi = np.minimum(lo, corners.min(axis=0)), np.maximum(hi, corners.max(axis=0))
        return lo, hi

    def com(self, instance):
        plant = self.plant
        model = plant.GetModelInstanceByName(instance)
        return plant.CalcCenterOfMassPositionInWorld(self.plant_context, [model])

    def instances_at(self, p, exclude):
        """The instances (not in `exclude`) whose collision geometry contains point p. Where
        Drake cannot compute the distance to a point for some mesh in range (a degenerate
        edge), the geometries whose oriented box contains p count instead (`approximated`)."""
        out = set()
        try:
            found = [d.id_G for d in self.query.ComputeSignedDistanceToPoint(p, 0.0)
                     if d.distance <= 0.0]
        except RuntimeError:
            self.approximated += 1
            found = [g for g in self.instance_of
                     if np.all(np.abs(self._obb(g)[0].inverse().multiply(p)) <= self._obb(g)[1])]
        for g in found:
            name = self.instance_of.get(g)
            if name is not None and name not in exclude:
                out.add(name)
        return out

    def below(self, instance):
        """The first other instances met going down from the instance's centre of mass, to
        DOWN_REACH_M under the bottom of its box, and the depth (m) under the centre of mass at
        which they were met; (set(), None) when none. (From the centre of mass, not from the
        box's bottom: the box around a turned object's oriented boxes reaches below it.)"""
        c = self.com(instance)
        lo, _ = self.box(instance)
        steps = int(np.ceil((c[2] - lo[2] + DOWN_REACH_M) / DOWN_STEP_M))
        for k in range(steps + 1):
            p = np.array([c[0], c[1], c[2] - k * DOWN_STEP_M])
            found = self.instances_at(p, {instance})
            if found:
                return found, k * DOWN_STEP_M
        return set(), None

    def distance(self, a, b):
        """The signed distance (m) between instances a and b: the least over their pairs of
        collision geometries (a pair Drake cannot compute is skipped and counted in
        `pairs_skipped`)."""
        best = np.inf
        for ga in self.ids(a):
            for gb in self.ids(b):
                try:
                    d = self.query.ComputeSignedDistancePairClosestPoints(ga, gb).distance
                except RuntimeError:
                    self.pairs_skipped += 1
                    continue
                best = min(best, d)
        return float(best)

    def walls_around(self, instance, reference):
        """In how many of the four horizontal directions from the instance's centre of mass a
        probe meets the reference within the reference's box."""
        c = self.com(instance)
        lo, hi = self.box(reference)
        met = 0
        for axis, sign in ((0, 1), (0, -1), (1, 1), (1, -1)):
            p = c.copy()
            while lo[axis] - 1e-9 <= p[axis] <= hi[axis] + 1e-9:
                if reference in self.instances_at(p, {instance}):
                    met += 1
                    break
                p[axis] += sign * SIDE_STEP_M
        return met


def _on(state, target, reference, depth=1):
    under, gap = state.below(target)
    d = state.distance(target, reference)
    if reference in under and d <= CONTACT_M:
        return True, {"below": sorted(under), "depth_m": gap, "distance_m": d}
    if depth > 0:
        for other in sorted(under - {reference}):
            holds, _ = _on(state, other, reference, depth - 1)
            if holds:
                return True, {"below": sorted(under), "depth_m": gap, "via": other}
    return False, {"below": sorted(under), "depth_m": gap, "distance_m": d}


def _inside(state, target, reference):
    under, gap = state.below(target)
    walls = state.walls_around(target, reference)
    base = reference in under or any(
        state.walls_around(o, reference) >= WALLS_NEEDED for o in under - {reference})
    return base and walls >= WALLS_NEEDED, {"below": sorted(under), "depth_m": gap,
                                           "walls": walls}


def check(scene_dir, directives, predicate, target, reference):
    """(holds, evidence) for predicate(target, reference) in the state `directives` of the scene
    in `scene_dir`."""
    state = State(scene_dir, directives)
    if predicate == "on":
        holds, evidence = _on(state, target, reference)
    elif predicate == "inside":
        holds, evidence = _inside(state, target, reference)
    elif predicate == "near":
        d = state.distance(target, reference)
        holds, evidence = d <= NEAR_M, {"distance_m": d}
    else:
        raise ValueError(f"unknown predicate {predicate!r}")
    if state.approximated:
        evidence["points_by_box"] = state.approximated
    if state.pairs_skipped:
        evidence["pairs_skipped"] = state.pairs_skipped
    return holds, evidence


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene_dir")
    ap.add_argument("directives", help="scene.dmd.yaml or an after-file")
    ap.add_argument("predicate", choices=("on", "inside", "near"))
    ap.add_argument("target")
    ap.add_argument("reference")
    args = ap.parse_args(argv)
    holds, evidence = check(args.scene_dir, args.directives, args.predicate, args.target,
                            args.reference)
    print(json.dumps({"holds": holds, "evidence": evidence}))


if __name__ == "__main__":
    main()
