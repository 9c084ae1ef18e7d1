"""Drake-side checks of single assets, batched: many models in one plant per request.

Ops (registered in ops.OPS):
  assets_load  {"models": [{"name", "sdf"}]}
      -> per model: ok / error, bodies, mass, joints (type, limits), proximity geometries.
  assets_drop  {"models": [{"name", "sdf", "footprint"}], "duration": 2.0, "time_step": 1e-3}
      -> each model dropped alone (spaced apart) onto a floor at z = 0; per model the root
         body's tilt (rad), horizontal and vertical displacement (m) after `duration`.
  assets_push  {"models": [{"name", "sdf", "efforts": {joint: N or N m}}], "duration": 1.0,
                "force_scale": 2.0}
      -> each model welded in place, a constant generalized force on every joint (the given
         effort, or force_scale x the child's weight x its lever arm), self-collision between
         the model's own links turned on; per joint the final position and limits, per model
         the deepest penetration between two of its links over the run.

Models are laid out on a grid whose pitch is the largest `footprint` (a model's horizontal
extent in metres, default 3) plus a metre, so they never touch each other.
"""

import dataclasses
import math
import os

import numpy as np
from pydrake.all import (
    AddMultibodyPlantSceneGraph,
    Box,
    CollisionFilterDeclaration,
    CoulombFriction,
    DiagramBuilder,
    GeometrySet,
    Parser,
    RigidTransform,
    Simulator,
)
from pydrake.geometry import Role

from drake_bridge.errors import BadRequest, FileMissing, ModelError
from drake_bridge.protocol import in_range

GRAVITY = 9.81


def _models(args):
    """The request's models (protocol.AssetModel) with absolute, existing sdf paths."""
    if not args.models:
        raise BadRequest("models must be a non-empty list of {name, sdf}")
    out = []
    seen = set()
    for m in args.models:
        if m.name in seen:
            raise BadRequest(f"model name {m.name!r} appears twice")
        seen.add(m.name)
        path = os.path.abspath(m.sdf)
        if not os.path.isfile(path):
            raise FileMissing(f"model file not found: {path}")
        out.append(dataclasses.replace(m, sdf=path))
    return out


def _new_plant(time_step):
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=time_step)
    parser = Parser(plant)
    if parser.package_map().Contains("drake_models"):
        parser.package_map().Remove("drake_models")
    parser.SetAutoRenaming(True)
    # A model that only loads with warnings (invalid inertia, unknown elements) is a broken
    # asset: make warnings errors.
    parser.SetStrictParsing()
    return builder, plant, scene_graph, parser


def _add(plant, parser, model):
    """Adds one model file; returns its model instance, renamed to the model's name."""
    instances = parser.AddModels(model.sdf)
    if len(instances) != 1:
        raise ModelError(f"{model.sdf}: expected one model, got {len(instances)}")
    plant.RenameModelInstance(instances[0], model.name)
    return instances[0]


def _bodies(plant, mi):
    return [plant.get_body(b) for b in plant.GetBodyIndices(mi)]


def _joints(plant, mi):
    return [plant.get_joint(j) for j in plant.GetJointIndices(mi)
            if plant.get_joint(j).num_positions() == 1
            and plant.get_joint(j).type_name() in ("revolute", "prismatic")]


def _summary(plant, scene_graph, mi):
    inspector = scene_graph.model_inspector()
    bodies = _bodies(plant, mi)
    geoms = 0
    for b in bodies:
        geoms += len(inspector.GetGeometries(plant.GetBodyFrameIdOrThrow(b.index()), Role.kProximity))
    return {
        "ok": True,
        "bodies": len(bodies),
        "mass": float(sum(b.default_mass() for b in bodies)),
        "joints": [{"name": j.name(), "type": j.type_name(),
                    "lower": float(j.position_lower_limits()[0]),
                    "upper": float(j.position_upper_limits()[0])} for j in _joints(plant, mi)],
        "collision_geometries": geoms,
    }


def op_assets_load(args):
    """Loads every model; one plant for all, falling back to one per model to name failures."""
    models = _models(args)
    try:
        _, plant, scene_graph, parser = _new_plant(0.0)
        instances = [(_add(plant, parser, m), m) for m in models]
        plant.Finalize()
        return {"models": {m.name: _summary(plant, scene_graph, mi) for mi, m in instances}}
    except (RuntimeError, ModelError):
        pass
    out = {}
    for m in models:
        try:
            _, plant, scene_graph, parser = _new_plant(0.0)
            mi = _add(plant, parser, m)
            plant.Finalize()
            out[m.name] = _summary(plant, scene_graph, mi)
        except (RuntimeError, ModelError) as e:
            out[m.name] = {"ok": False, "error": str(e)}
    return {"models": out}


def _grid(n, spacing):
    cols = max(1, math.ceil(math.sqrt(n)))
    return [((i % cols) * spacing, (i // cols) * spacing) for i in range(n)]


def _spacing(models):
    """Grid pitch: the largest `footprint` (horizontal extent, m) given, plus a metre."""
    sizes = [m.footprint for m in models]
    if any(s is not None and s <= 0 for s in sizes):
        raise BadRequest("footprint must be a positive number of metres")
    return float(max((s for s in sizes if s is not None), default=3.0)) + 1.0


def op_assets_drop(args):
    models = _models(args)
    duration = in_range("duration", args.duration, 0.0, 30.0)
    time_step = in_range("time_step", args.time_step, 1e-4, 1e-2)
    builder, plant, scene_graph, parser = _new_plant(time_step)
    try:
        instances = [(_add(plant, parser, m), m) for m in models]
    except RuntimeError as e:
        raise ModelError(f"could not load the models: {e}") from e
    spacing = _spacing(models)
    points = _grid(len(instances), spacing)
    max_x = max(p[0] for p in points)
    max_y = max(p[1] for p in points)
    X_floor = RigidTransform([max_x / 2.0, max_y / 2.0, -0.05])
    plant.RegisterCollisionGeometry(plant.world_body(), X_floor,
                                    Box(max_x + 2.0 * spacing, max_y + 2.0 * spacing, 0.1),
                                    "floor", CoulombFriction(0.6, 0.5))
    roots = []
    for (mi, m), (x, y) in zip(instances, points):
        root = _bodies(plant, mi)[0]
        # drake >= 1.52 renamed SetDefaultFreeBodyPose to SetDefaultFloatingBaseBodyPose.
        set_pose = getattr(plant, "SetDefaultFloatingBaseBodyPose", None) or plant.SetDefaultFreeBodyPose
        set_pose(root, RigidTransform([x, y, 0.001]))
        roots.append((root, m, (x, y)))
    plant.Finalize()
    diagram = builder.Build()
    simulator = Simulator(diagram)
    ctx = simulator.get_mutable_context()
    pctx = plant.GetMyMutableContextFromRoot(ctx)
    start = {m.name: plant.EvalBodyPoseInWorld(pctx, root) for root, m, _ in roots}
    simulator.AdvanceTo(duration)
    out = {}
    for root, m, _ in roots:
        X0 = start[m.name]
        X = plant.EvalBodyPoseInWorld(pctx, root)
        z_axis = X.rotation().matrix()[:, 2]
        tilt = float(math.acos(max(-1.0, min(1.0, z_axis[2]))))
        d = X.translation() - X0.translation()
        out[m.name] = {
            "tilt_rad": tilt,
            "rotation_rad": float(X0.rotation().InvertAndCompose(X.rotation()).ToAngleAxis().angle()),
            "horizontal_m": float(np.hypot(d[0], d[1])),
            "vertical_m": float(d[2]),
        }
    return {"duration": duration, "time_step": time_step, "models": out}


def _lever(plant, pctx, joint):
    """Distance from the joint axis to the child's centre of mass (revolute), metres."""
    child = joint.child_body()
    X_WC = plant.EvalBodyPoseInWorld(pctx, child)
    p_com_W = X_WC.multiply(child.CalcCenterOfMassInBodyFrame(pctx))
    X_WJ = joint.frame_on_child().CalcPoseInWorld(pctx)
    axis_W = X_WJ.rotation().multiply(joint.revolute_axis())
    r = p_com_W - X_WJ.translation()
    return float(np.linalg.norm(r - axis_W * np.dot(r, axis_W)))


def op_assets_push(args):
    models = _models(args)
    duration = in_range("duration", args.duration, 0.0, 30.0)
    time_step = in_range("time_step", args.time_step, 1e-4, 1e-2)
    scale = in_range("force_scale", args.force_scale, 0.0, 100.0)
    builder, plant, scene_graph, parser = _new_plant(time_step)
    try:
        instances = [(_add(plant, parser, m), m) for m in models]
    except RuntimeError as e:
        raise ModelError(f"could not load the models: {e}") from e
    points = _grid(len(instances), _spacing(models))
    for (mi, m), (x, y) in zip(instances, points):
        plant.WeldFrames(plant.world_frame(), _bodies(plant, mi)[0].body_frame(), RigidTransform([x, y, 0.0]))
    # Links of one model may collide with each other: what a drawer or door would hit.
    plant.set_adjacent_bodies_collision_filters(False)
    plant.Finalize()
    inspector = scene_graph.model_inspector()
    geometry_of = {}
    for mi, m in instances:
        ids = []
        for b in _bodies(plant, mi):
            ids += inspector.GetGeometries(plant.GetBodyFrameIdOrThrow(b.index()), Role.kProximity)
        geometry_of[m.name] = ids
        scene_graph.collision_filter_manager().Apply(CollisionFilterDeclaration().AllowWithin(GeometrySet(ids)))
    diagram = builder.Build()
    simulator = Simulator(diagram)
    ctx = simulator.get_mutable_context()
    pctx = plant.GetMyMutableContextFromRoot(ctx)
    tau = np.zeros(plant.num_velocities())
    plan = []
    for mi, m in instances:
        efforts = m.efforts or {}
        for j in _joints(plant, mi):
            child_weight = j.child_body().default_mass() * GRAVITY
            if j.name() in efforts:
                f = float(efforts[j.name()])
            elif j.type_name() == "prismatic":
                f = scale * child_weight + 1.0
            else:
                f = scale * child_weight * max(_lever(plant, pctx, j), 0.05) + 0.1
            tau[j.velocity_start()] = f
            plan.append((m.name, j, f))
    plant.get_applied_generalized_force_input_port().FixValue(pctx, tau)
    owner = {}
    for name, ids in geometry_of.items():
        for g in ids:
            owner[g] = name
    deepest = {name: {"depth": 0.0, "pair": None} for name in geometry_of}
    sg_ctx = scene_graph.GetMyContextFromRoot(ctx)
    t = 0.0
    step = 0.02
    while t < duration - 1e-12:
        t = min(duration, t + step)
        simulator.AdvanceTo(t)
        query = scene_graph.get_query_output_port().Eval(sg_ctx)
        for pp in query.ComputePointPairPenetration():
            a, b = owner.get(pp.id_A), owner.get(pp.id_B)
            if a is None or a != b:
                continue
            if pp.depth > deepest[a]["depth"]:
                fa = inspector.GetName(inspector.GetFrameId(pp.id_A))
                fb = inspector.GetName(inspector.GetFrameId(pp.id_B))
                deepest[a] = {"depth": float(pp.depth), "pair": [fa, fb]}
    out = {name: {"joints": {}, "self_penetration_m": deepest[name]["depth"],
                  "self_penetration_pair": deepest[name]["pair"]} for name in geometry_of}
    for name, j, f in plan:
        out[name]["joints"][j.name()] = {
            "type": j.type_name(),
            "position": float(j.GetOnePosition(pctx)),
            "lower": float(j.position_lower_limits()[0]),
            "upper": float(j.position_upper_limits()[0]),
            "effort": f,
        }
    return {"duration": duration, "time_step": time_step, "models": out}


OPS = {
    "assets_load": op_assets_load,
    "assets_drop": op_assets_drop,
    "assets_push": op_assets_push,
}
