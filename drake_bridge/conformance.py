"""Conformance ops for the exports: load the MJCF in MuJoCo and simulate it, open the USD with
usd-core and read its physics schema back. They report facts (counts, masses, joints, bounds,
displacements, validator findings); the Rust side compares them with the scene and decides.

MuJoCo and usd-core are imported on first use, so the bridge starts without them.
"""

import math
import time

import numpy as np

from drake_bridge.errors import BadRequest, ModelError
from drake_bridge.plant_cache import existing_file
from drake_bridge.protocol import in_range

# MuJoCo joint types (mjtJoint).
_MJ_JOINT = {0: "free", 1: "ball", 2: "slide", 3: "hinge"}


def _path_arg(path, key):
    path = existing_file(path, key)
    if path is None:
        raise BadRequest(f"argument {key!r} must be a path string")
    return path


def _mj_name(model, kind, index):
    """The name of a MuJoCo object; `world` for body 0 and `#<index>` for an unnamed one."""
    import mujoco

    name = mujoco.mj_id2name(model, kind, index)
    if name:
        return name
    if kind == mujoco.mjtObj.mjOBJ_BODY and index == 0:
        return "world"
    return f"#{index}"


def _aabb(points):
    if len(points) == 0:
        return None
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    return [pts.min(axis=0).tolist(), pts.max(axis=0).tolist()]


def _quat_angle(q0, q1):
    """Angle of the rotation between two unit quaternions (w, x, y, z), radians."""
    d = abs(float(np.dot(q0, q1)))
    return 2.0 * math.acos(min(1.0, d))


def _mj_geom_points(model, data, g):
    """World-frame vertices of a mesh geom (the geom's own frame for other types: its centre)."""
    if model.geom_type[g] == 7:  # mjGEOM_MESH
        m = model.geom_dataid[g]
        adr, num = model.mesh_vertadr[m], model.mesh_vertnum[m]
        local = model.mesh_vert[adr:adr + num]
        return data.geom_xpos[g] + local @ data.geom_xmat[g].reshape(3, 3).T
    return data.geom_xpos[g].reshape(1, 3)


def op_mujoco_check(args):
    """Loads an MJCF file, reports its bodies and joints, simulates `seconds` and reports how far
    every free body moved and whether the state stayed finite.

    args: xml (path), seconds (default 5), probe_joints ({joint: torque}, optional: applies a
    constant generalized force to those hinge/slide joints during the run and reports their
    final positions).

    MuJoCo's warnings are collected into the reply's `messages` instead of MuJoCo's default
    (stderr plus a MUJOCO_LOG.TXT in the working directory).
    """
    import mujoco

    messages = []
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(lambda msg: messages.append(str(msg).strip()))
    try:
        result = _mujoco_check(args)
    except mujoco.FatalError as e:
        raise ModelError(f"MuJoCo failed on {args.xml}: {e}") from e
    finally:
        mujoco.set_mju_user_warning(previous)
    result["messages"] = messages
    return result


def _mujoco_check(args):
    import mujoco

    path = _path_arg(args.xml, "xml")
    seconds = in_range("seconds", args.seconds, 0.0, 120.0)
    probe = args.probe_joints
    t0 = time.perf_counter()
    try:
        model = mujoco.MjModel.from_xml_path(path)
    except ValueError as e:
        raise ModelError(f"MuJoCo could not load {path}: {e}") from e
    load_s = time.perf_counter() - t0
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)

    geom_body = model.geom_bodyid
    collides = (model.geom_contype != 0) | (model.geom_conaffinity != 0)
    bodies = []
    for b in range(1, model.nbody):
        mine = np.nonzero(geom_body == b)[0]
        coll = [int(g) for g in mine if collides[g]]
        vis = [int(g) for g in mine if not collides[g]]
        coll_pts = [_mj_geom_points(model, data, g) for g in coll]
        vis_pts = [_mj_geom_points(model, data, g) for g in vis]
        jnt = [j for j in range(model.njnt) if model.jnt_bodyid[j] == b]
        bodies.append({
            "name": _mj_name(model, mujoco.mjtObj.mjOBJ_BODY, b),
            "parent": _mj_name(model, mujoco.mjtObj.mjOBJ_BODY, int(model.body_parentid[b])),
            "mass": float(model.body_mass[b]),
            "free": any(model.jnt_type[j] == 0 for j in jnt),
            "collision_geoms": len(coll),
            "visual_geoms": len(vis),
            "collision_aabb": _aabb(np.concatenate(coll_pts)) if coll_pts else None,
            "visual_aabb": _aabb(np.concatenate(vis_pts)) if vis_pts else None,
            "friction": sorted({float(model.geom_friction[g][0]) for g in coll}),
        })
    joints = []
    for j in range(model.njnt):
        kind = _MJ_JOINT.get(int(model.jnt_type[j]), "unknown")
        if kind == "free":
            continue
        joints.append({
            "name": _mj_name(model, mujoco.mjtObj.mjOBJ_JOINT, j),
            "type": kind,
            "body": _mj_name(model, mujoco.mjtObj.mjOBJ_BODY, int(model.jnt_bodyid[j])),
            "limited": bool(model.jnt_limited[j]),
            "range": [float(v) for v in model.jnt_range[j]],
            "damping": float(model.dof_damping[model.jnt_dofadr[j]]),
            "qpos0": float(model.qpos0[model.jnt_qposadr[j]]),
            "axis_world": [float(v) for v in data.xaxis[j]],
        })

    probe_dofs = {}
    for name, force in probe.items():
        j = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
        if j < 0:
            raise BadRequest(f"no joint named {name!r} in {path}")
        probe_dofs[name] = (int(model.jnt_dofadr[j]), int(model.jnt_qposadr[j]), float(force))

    free_bodies = [i + 1 for i, b in enumerate(bodies) if b["free"]]
    x0 = {b: data.xpos[b].copy() for b in free_bodies}
    q0 = {b: data.xquat[b].copy() for b in free_bodies}
    steps = int(round(seconds / model.opt.timestep))
    finite = True
    t1 = time.perf_counter()
    for i in range(steps):
        for dof, _, force in probe_dofs.values():
            data.qfrc_applied[dof] = force
        mujoco.mj_step(model, data)
        if i % 25 == 0 and not (np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel))):
            finite = False
            break
    sim_s = time.perf_counter() - t1
    finite = finite and bool(np.all(np.isfinite(data.qpos)) and np.all(np.isfinite(data.qvel)))
    for b in free_bodies:
        rec = bodies[b - 1]
        if finite:
            rec["displacement_m"] = float(np.linalg.norm(data.xpos[b] - x0[b]))
            rec["rotation_rad"] = _quat_angle(q0[b], data.xquat[b])
            rec["final_pos"] = [float(v) for v in data.xpos[b]]
            rec["initial_pos"] = [float(v) for v in x0[b]]
        else:
            rec["displacement_m"] = None
            rec["rotation_rad"] = None
            rec["final_pos"] = None
            rec["initial_pos"] = [float(v) for v in x0[b]]
    depth = [-float(data.contact.dist[i]) for i in range(data.ncon) if data.contact.dist[i] < 0]
    warnings = {}
    for w in mujoco.mjtWarning.__members__.values():
        if w.value < mujoco.mjtWarning.mjNWARNING.value and data.warning[w.value].number > 0:
            warnings[w.name] = int(data.warning[w.value].number)
    # MuJoCo resets the state when it turns non-finite or huge and only leaves a warning.
    finite = finite and not any(w.startswith("mjWARN_BADQ") for w in warnings)
    return {
        "mujoco": mujoco.__version__,
        "load_seconds": load_s,
        "sim_seconds": sim_s,
        "simulated_seconds": float(data.time),
        "timestep": float(model.opt.timestep),
        "counts": {"bodies": int(model.nbody - 1), "geoms": int(model.ngeom),
                   "joints": int(model.njnt), "meshes": int(model.nmesh)},
        "bodies": bodies,
        "joints": joints,
        "finite": finite,
        "warnings": warnings,
        "contacts_at_end": int(data.ncon),
        "arena_bytes": int(model.narena),
        "arena_peak_bytes": int(data.maxuse_arena),
        "max_penetration_at_end_m": max(depth) if depth else 0.0,
        "probe": {name: float(data.qpos[qadr]) for name, (_, qadr, _) in probe_dofs.items()},
    }


def _usd_points_world(xf_cache, prim):
    from pxr import UsdGeom

    pts = UsdGeom.Mesh(prim).GetPointsAttr().Get()
    if pts is None or len(pts) == 0:
        return np.zeros((0, 3))
    m = np.array(xf_cache.GetLocalToWorldTransform(prim), dtype=float)  # row-vector convention
    p = np.asarray(pts, dtype=float)
    return p @ m[:3, :3] + m[3, :3]


def _gf_rotate(m, v):
    """Direction v (3,) through a Gf.Matrix4d (row-vector convention), normalised."""
    a = np.array(m, dtype=float)
    w = np.asarray(v, dtype=float) @ a[:3, :3]
    n = np.linalg.norm(w)
    return (w / n).tolist() if n > 0 else [0.0, 0.0, 0.0]


def _quat_to_matrix(q):
    """Gf.Quatf/Quatd -> 3x3 rotation (column-vector convention)."""
    w = q.GetReal()
    x, y, z = q.GetImaginary()
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def _world_frame(xf_cache, stage, body_path, local_pos, local_rot):
    """World rotation (3x3, column convention) and origin of a joint frame on a body (or on the
    world when the body path is empty)."""
    R_local = _quat_to_matrix(local_rot)
    p_local = np.asarray(local_pos, dtype=float)
    if not body_path or str(body_path) == "":
        return R_local, p_local
    prim = stage.GetPrimAtPath(body_path)
    if not prim.IsValid():
        return None, None
    m = np.array(xf_cache.GetLocalToWorldTransform(prim), dtype=float)
    R_body = m[:3, :3].T  # row-vector matrix -> column convention
    scale = np.linalg.norm(R_body, axis=0)
    R_body = R_body / scale
    return R_body @ R_local, m[3, :3] + R_body @ (p_local * scale)


_AXIS = {"X": 0, "Y": 1, "Z": 2}


def _joint_record(stage, xf_cache, kind, path, desc, bodies):
    axis_letter = str(getattr(desc, "axis", "")).split(".")[-1] if hasattr(desc, "axis") else ""
    rec = {"path": str(path), "type": kind,
           "body0": str(desc.body0), "body1": str(desc.body1),
           "body0_ok": str(desc.body0) == "" or str(desc.body0) in bodies,
           "body1_ok": str(desc.body1) in bodies}
    R0, p0 = _world_frame(xf_cache, stage, desc.body0, desc.localPose0Position,
                          desc.localPose0Orientation)
    R1, p1 = _world_frame(xf_cache, stage, desc.body1, desc.localPose1Position,
                          desc.localPose1Orientation)
    if R0 is not None and R1 is not None:
        # Offset of frame 1 from frame 0, in frame 0; a prismatic joint's position is the part
        # along its axis, anything else is a gap between frames that should coincide.
        d = R0.T @ (p1 - p0)
        if axis_letter in _AXIS:
            k = _AXIS[axis_letter]
            rec["axis"] = axis_letter
            rec["axis_world"] = R1[:, k].tolist()
            # Relative rotation of frame 1 in frame 0: for a revolute joint a turn about the axis.
            R = R0.T @ R1
            a, b = (k + 1) % 3, (k + 2) % 3
            if kind == "prismatic":
                rec["position_measured"] = float(d[k])
                d[k] = 0.0
            elif kind == "revolute":
                rec["position_measured"] = math.degrees(math.atan2(R[b, a], R[a, a]))
            rec["off_axis_rad"] = float(math.acos(max(-1.0, min(1.0, R[k, k]))))
        rec["frame_gap_m"] = float(np.linalg.norm(d))
    if hasattr(desc, "limit"):
        rec["limit_enabled"] = bool(desc.limit.enabled)
        rec["lower"] = float(desc.limit.lower)
        rec["upper"] = float(desc.limit.upper)
    if hasattr(desc, "drive") and desc.drive is not None:
        rec["drive_damping"] = float(desc.drive.damping)
        rec["drive_stiffness"] = float(desc.drive.stiffness)
    return rec


def op_usd_check(args):
    """Opens a USD stage with usd-core and reports what a UsdPhysics consumer sees: stage
    metadata, validator findings, rigid bodies with their mass and colliders, static colliders,
    joints (targets, limits, world axis, measured position), articulations, and the world bounds
    of every collider and visual mesh.

    args: usd (path), static_prims (optional list of prim paths: colliders and visuals outside
    rigid bodies are grouped under the longest matching one, else under their top-level prim).
    """
    from pxr import Tf, Usd, UsdGeom, UsdPhysics, UsdValidation

    path = _path_arg(args.usd, "usd")
    groups = args.static_prims
    # Longest first, so a link prim wins over its object prim.
    groups = sorted(groups, key=len, reverse=True)

    def static_owner(prim_path):
        for g in groups:
            if prim_path == g or prim_path.startswith(g + "/"):
                return g
        parts = prim_path.split("/")
        return "/".join(parts[:3]) if len(parts) >= 3 else prim_path

    t0 = time.perf_counter()
    try:
        stage = Usd.Stage.Open(path)
    except Tf.ErrorException as e:
        raise ModelError(f"usd-core could not open {path}: {e}") from e
    if stage is None:
        raise ModelError(f"usd-core could not open {path}")
    open_s = time.perf_counter() - t0

    default_prim = stage.GetDefaultPrim()
    meta = {
        "meters_per_unit": float(UsdGeom.GetStageMetersPerUnit(stage)),
        "kilograms_per_unit": float(UsdPhysics.GetStageKilogramsPerUnit(stage)),
        "up_axis": str(UsdGeom.GetStageUpAxis(stage)),
        "default_prim": str(default_prim.GetPath()) if default_prim else None,
        "has_authored_meters_per_unit": UsdGeom.StageHasAuthoredMetersPerUnit(stage),
        "custom_layer_data": {k: str(v) for k, v in stage.GetRootLayer().customLayerData.items()},
    }
    composition_errors = [str(e) for e in stage.GetCompositionErrors()] \
        if hasattr(stage, "GetCompositionErrors") else []

    reg = UsdValidation.ValidationRegistry()
    validators = reg.GetOrLoadValidatorsByName([m.name for m in reg.GetAllValidatorMetadata()])
    findings = []
    for e in UsdValidation.ValidationContext(validators).Validate(stage):
        sites = []
        for s in e.GetSites():
            if s.IsPrim():
                sites.append(str(s.GetPrim().GetPath()))
            elif s.IsProperty():
                sites.append(str(s.GetProperty().GetPath()))
        findings.append({"validator": e.GetValidator().GetMetadata().name if e.GetValidator()
                         else e.GetName(),
                         "severity": str(e.GetType()).split(".")[-1],
                         "message": e.GetMessage(), "sites": sites[:5]})

    T = UsdPhysics.ObjectType
    parsed = UsdPhysics.UsdPhysicsLoadStageFromPrimRange(stage, ["/"])

    def items(kind):
        paths, descs = parsed.get(kind, ([], []))
        return list(zip(paths, descs))

    counts = {str(k).split(".")[-1]: len(v[0]) for k, v in parsed.items()}
    xf_cache = UsdGeom.XformCache()
    friction = {str(p): [float(d.staticFriction), float(d.dynamicFriction)]
                for p, d in items(T.RigidBodyMaterial)}

    bodies = {}
    for p, d in items(T.RigidBody):
        prim = stage.GetPrimAtPath(p)
        mass_api = UsdPhysics.MassAPI(prim)
        has_mass = prim.HasAPI(UsdPhysics.MassAPI)

        def get(attr):
            v = attr.Get() if attr and attr.HasAuthoredValue() else None
            return v

        mass = get(mass_api.GetMassAttr()) if has_mass else None
        diag = get(mass_api.GetDiagonalInertiaAttr()) if has_mass else None
        com = get(mass_api.GetCenterOfMassAttr()) if has_mass else None
        bodies[str(p)] = {
            "kinematic": bool(d.kinematicBody),
            "enabled": bool(d.rigidBodyEnabled),
            "mass": float(mass) if mass is not None else None,
            "diagonal_inertia": [float(v) for v in diag] if diag is not None else None,
            "center_of_mass": [float(v) for v in com] if com is not None else None,
            "colliders": 0,
            "collision_aabb": None,
            "visual_aabb": None,
            "filtered": sorted(str(f) for f in d.filteredCollisions),
        }

    shapes = []
    for kind in (T.MeshShape, T.CubeShape, T.SphereShape, T.CapsuleShape, T.CylinderShape,
                 T.ConeShape, T.PlaneShape, T.CustomShape):
        for p, d in items(kind):
            shapes.append((str(kind).split(".")[-1], p, d))

    collider_pts = {}
    static_colliders = {}
    approximations = {}
    unbound = 0
    for kind, p, d in shapes:
        body = str(d.rigidBody)
        prim = stage.GetPrimAtPath(p)
        approx = str(getattr(d, "approximation", "")) if kind == "MeshShape" else kind
        approximations[approx] = approximations.get(approx, 0) + 1
        if not d.materials:
            unbound += 1
        pts = _usd_points_world(xf_cache, prim) if kind == "MeshShape" else np.zeros((0, 3))
        if body and body in bodies:
            bodies[body]["colliders"] += 1
            collider_pts.setdefault(body, []).append(pts)
        else:
            rec = static_colliders.setdefault(static_owner(str(p)), {"colliders": 0, "pts": []})
            rec["colliders"] += 1
            rec["pts"].append(pts)
    for body, pts in collider_pts.items():
        bodies[body]["collision_aabb"] = _aabb(np.concatenate(pts))

    # Visual meshes: every Mesh prim that is not a collider, grouped by the nearest rigid body
    # ancestor (or the top-level object for static geometry).
    collider_paths = {str(p) for _, p, _ in shapes}
    visual_pts = {}
    for prim in stage.Traverse():
        if not prim.IsA(UsdGeom.Mesh) or str(prim.GetPath()) in collider_paths:
            continue
        owner = None
        anc = prim.GetParent()
        while anc and anc.IsValid() and str(anc.GetPath()) != "/":
            if str(anc.GetPath()) in bodies:
                owner = str(anc.GetPath())
                break
            anc = anc.GetParent()
        if owner is None:
            owner = static_owner(str(prim.GetPath()))
        visual_pts.setdefault(owner, []).append(_usd_points_world(xf_cache, prim))
    visual_aabb = {k: _aabb(np.concatenate(v)) for k, v in visual_pts.items()}
    for b, rec in bodies.items():
        rec["visual_aabb"] = visual_aabb.get(b)

    joints = []
    for kind, name in ((T.RevoluteJoint, "revolute"), (T.PrismaticJoint, "prismatic"),
                       (T.FixedJoint, "fixed"), (T.SphericalJoint, "spherical"),
                       (T.D6Joint, "d6"), (T.DistanceJoint, "distance")):
        for p, d in items(kind):
            joints.append(_joint_record(stage, xf_cache, name, p, d, bodies))

    articulations = [{"path": str(p), "roots": [str(r) for r in d.rootPrims],
                      "bodies": [str(b) for b in d.articulatedBodies],
                      "joints": [str(j) for j in d.articulatedJoints]}
                     for p, d in items(T.Articulation)]
    return {
        "usd": ".".join(map(str, Usd.GetVersion())),
        "open_seconds": open_s,
        "seconds": time.perf_counter() - t0,
        "metadata": meta,
        "composition_errors": composition_errors,
        "findings": findings,
        "counts": counts,
        "physics_scenes": len(items(T.Scene)),
        "bodies": bodies,
        "static": {k: {"colliders": v["colliders"], "collision_aabb": _aabb(np.concatenate(v["pts"])),
                       "visual_aabb": visual_aabb.get(k)}
                   for k, v in static_colliders.items()},
        "approximations": approximations,
        "colliders_without_material": unbound,
        "materials": friction,
        "joints": joints,
        "articulations": articulations,
    }
