"""Bridge operations. Each takes its protocol dataclass of arguments and returns its reply
(a protocol dataclass, or data of that shape); `call` validates both at the boundary."""

import importlib.metadata
import sys

import numpy as np
from pydrake.geometry import Role
from pydrake.multibody.tree import ModelInstanceIndex

from drake_bridge import BRIDGE_VERSION, PROTOCOL, asset_checks, layout_checks, projection, robot_ops, settle
from drake_bridge.conformance import op_mujoco_check, op_usd_check
from drake_bridge.errors import BadRequest
from drake_bridge.plant_cache import CACHE
from drake_bridge.protocol import SIGNATURES, dump, in_range, parse
from drake_bridge.sim_plant import apply_poses, instance_name, is_free, pose_json


def drake_version():
    try:
        return importlib.metadata.version("drake")
    except importlib.metadata.PackageNotFoundError:
        return "unknown"


def _package_version(name):
    try:
        return importlib.metadata.version(name)
    except importlib.metadata.PackageNotFoundError:
        return None


def op_ping(args):
    return {"pong": True, "protocol": PROTOCOL, "bridge": BRIDGE_VERSION,
            "drake": drake_version()}


def op_versions(args):
    from pydrake.solvers import IpoptSolver, SnoptSolver

    return {
        "python": ".".join(map(str, sys.version_info[:3])),
        "drake": drake_version(),
        "numpy": _package_version("numpy"),
        "mujoco": _package_version("mujoco"),
        "usd_core": _package_version("usd-core"),
        "snopt": {"available": SnoptSolver().available(), "enabled": SnoptSolver().enabled()},
        "ipopt": {"available": IpoptSolver().available(), "enabled": IpoptSolver().enabled()},
    }


def op_load(args):
    """Model instances, bodies, joints and free bodies (with their default poses)."""
    scene = CACHE.get(args)
    plant = scene.plant
    ctx = scene.plant_context()
    instances = []
    for i in range(plant.num_model_instances()):
        mi = ModelInstanceIndex(i)
        name = plant.GetModelInstanceName(mi)
        if name in ("WorldModelInstance", "DefaultModelInstance"):
            continue
        bodies = [plant.get_body(b) for b in plant.GetBodyIndices(mi)]
        joints = [plant.get_joint(j) for j in plant.GetJointIndices(mi)]
        free = [b for b in bodies if is_free(b)]
        instances.append({
            "name": name,
            "bodies": [b.name() for b in bodies],
            "mass": float(sum(b.default_mass() for b in bodies)),
            "joints": [{"name": j.name(), "type": j.type_name(),
                        "lower": [float(v) for v in j.position_lower_limits()],
                        "upper": [float(v) for v in j.position_upper_limits()]}
                       for j in joints if j.num_positions() > 0 and not j.name().startswith("$")
                       and j.type_name() in ("revolute", "prismatic")],
            "free_bodies": {b.name(): pose_json(plant.EvalBodyPoseInWorld(ctx, b))
                            for b in free},
            "welded": len(free) == 0,
        })
    inspector = scene.scene_graph.model_inspector()
    return {
        "directives": scene.directives_path,
        "num_model_instances": len(instances),
        "num_bodies": plant.num_bodies() - 1,
        "num_positions": plant.num_positions(),
        "num_collision_geometries": len(inspector.GetAllGeometryIds(Role.kProximity)),
        "model_instances": instances,
        "cache": {"hits": CACHE.hits, "misses": CACHE.misses},
    }


def _positions_arg(args, scene):
    """A context with the request's free-body poses (`args.poses`) over the defaults."""
    ctx = scene.context.Clone()
    apply_poses(scene.plant, scene.plant_context(ctx), args.poses)
    return ctx


def penetration_pairs(scene, ctx, threshold):
    """Object pairs penetrating deeper than `threshold` metres (deepest contact per pair).

    Uses ComputePointPairPenetration, which (unlike the signed-distance query) does not abort on
    exactly touching box pairs.
    """
    plant = scene.plant
    sg_ctx = scene.scene_graph_context(ctx)
    query = scene.scene_graph.get_query_output_port().Eval(sg_ctx)
    inspector = query.inspector()
    deepest = {}
    for pp in query.ComputePointPairPenetration():
        ba = plant.GetBodyFromFrameId(inspector.GetFrameId(pp.id_A))
        bb = plant.GetBodyFromFrameId(inspector.GetFrameId(pp.id_B))
        a, b = instance_name(plant, ba), instance_name(plant, bb)
        if a == b:
            continue
        key = tuple(sorted((a, b)))
        if pp.depth > deepest.get(key, {"depth": -1.0})["depth"]:
            first_is_a = key[0] == a
            deepest[key] = {
                "a": key[0], "b": key[1],
                "body_a": (ba if first_is_a else bb).name(),
                "body_b": (bb if first_is_a else ba).name(),
                "depth": float(pp.depth),
                "normal": [float(v) for v in (pp.nhat_BA_W if first_is_a else -pp.nhat_BA_W)],
            }
    pairs = [p for p in deepest.values() if p["depth"] > threshold]
    pairs.sort(key=lambda p: (-p["depth"], p["a"], p["b"]))
    return pairs


def _threshold(args, default):
    t = default if args.threshold is None else args.threshold
    return in_range("threshold", t, 0.0)


def op_penetrations(args):
    scene = CACHE.get(args)
    ctx = _positions_arg(args, scene)
    pairs = penetration_pairs(scene, ctx, _threshold(args, 0.0))
    return {"pairs": pairs}


def op_collision_report(args):
    """COL: fraction of objects (non-static model instances) penetrating > threshold."""
    scene = CACHE.get(args)
    ctx = _positions_arg(args, scene)
    threshold = _threshold(args, 1e-3)
    plant = scene.plant
    static = set(args.static_instances)
    names = []
    for i in range(plant.num_model_instances()):
        name = plant.GetModelInstanceName(ModelInstanceIndex(i))
        if name in ("WorldModelInstance", "DefaultModelInstance") or name in static:
            continue
        names.append(name)
    pairs = penetration_pairs(scene, ctx, threshold)
    penetrating = sorted(({p["a"] for p in pairs} | {p["b"] for p in pairs}) - static)
    depths = [p["depth"] for p in pairs]
    n = len(names)
    return {
        "objects": n,
        "penetrating_objects": penetrating,
        "col_percent": 100.0 * len(penetrating) / n if n else 0.0,
        "mean_depth_m": float(np.mean(depths)) if depths else 0.0,
        "max_depth_m": float(max(depths)) if depths else 0.0,
        "threshold_m": threshold,
        "pairs": pairs,
    }


OPS = {
    **asset_checks.OPS,
    **robot_ops.OPS,
    "ping": op_ping,
    "versions": op_versions,
    "load": op_load,
    "penetrations": op_penetrations,
    "collision_report": op_collision_report,
    "project": projection.op_project,
    "settle": settle.op_settle,
    "simulate": settle.op_simulate,
    "mujoco_check": op_mujoco_check,
    "usd_check": op_usd_check,
    "drop_spheres": layout_checks.op_drop_spheres,
}


def call(op, raw_args):
    """Runs operation `op` on JSON arguments and returns its JSON reply, both validated against
    the op's protocol types (BadRequest for bad arguments, an internal error for a bad reply)."""
    if op not in OPS:
        raise BadRequest(f"unknown op {op!r}; known ops: {', '.join(sorted(OPS))}")
    args_type, reply_type = SIGNATURES[op]
    return dump(reply_type, OPS[op](parse(args_type, raw_args)), where=f"reply to {op}")
