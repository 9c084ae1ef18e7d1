"""The bridge protocol's types: one dataclass per operation's arguments and per reply.

The Rust client declares the same types (src/physics/protocol/) and renders them as JSON Schema
into protocol.schema.json beside this file; tests/test_schema.py checks these dataclasses
against it, field by field. `parse` validates a request's arguments at the boundary (an unknown
key, a missing one or a wrong type is a BadRequest naming the field); `dump` turns a reply
dataclass into JSON-ready data and checks it against its own declaration, so a reply that
breaks the protocol fails here, not as a silent default on the other side.

Units are the wire's: metres, seconds, kilograms, radians.
"""

import dataclasses
import math
import types
import typing
from dataclasses import dataclass, field
from typing import Literal, Optional, Union

from drake_bridge.errors import BadRequest, BridgeError

# --------------------------------------------------------------------------- validation


class ProtocolViolation(BridgeError):
    """A reply that does not match its declared type (a bug in the bridge)."""

    type_name = "internal"


def _fail(where, message, error):
    raise error(f"{where}: {message}")


def _check(tp, value, where, error):
    """Validates `value` against annotation `tp`; returns it with dataclasses built."""
    origin = typing.get_origin(tp)
    if tp is typing.Any:
        return value
    if origin in (Union, types.UnionType):
        options = typing.get_args(tp)
        if value is None:
            if type(None) in options:
                return None
            _fail(where, "must not be null", error)
        inner = [t for t in options if t is not type(None)]
        if len(inner) != 1:
            raise TypeError(f"unsupported union {tp}")
        return _check(inner[0], value, where, error)
    if origin is Literal:
        allowed = typing.get_args(tp)
        if value not in allowed:
            _fail(where, f"must be one of {', '.join(map(repr, allowed))}, not {value!r}", error)
        return value
    if tp is bool:
        if not isinstance(value, bool):
            _fail(where, f"must be true or false, not {value!r}", error)
        return value
    if tp is int:
        if isinstance(value, bool) or not isinstance(value, int):
            _fail(where, f"must be an integer, not {value!r}", error)
        return value
    if tp is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            _fail(where, f"must be a number, not {value!r}", error)
        if not math.isfinite(value):
            _fail(where, f"must be finite, not {value!r}", error)
        return float(value)
    if tp is str:
        if not isinstance(value, str):
            _fail(where, f"must be a string, not {value!r}", error)
        return value
    if origin is list:
        (item,) = typing.get_args(tp)
        if not isinstance(value, (list, tuple)):
            _fail(where, "must be a list", error)
        return [_check(item, v, f"{where}[{i}]", error) for i, v in enumerate(value)]
    if origin is tuple:
        items = typing.get_args(tp)
        if not isinstance(value, (list, tuple)) or len(value) != len(items):
            _fail(where, f"must be a list of {len(items)} values", error)
        return tuple(_check(t, v, f"{where}[{i}]", error) for i, (t, v) in enumerate(zip(items, value)))
    if origin is dict:
        key, item = typing.get_args(tp)
        if not isinstance(value, dict):
            _fail(where, "must be an object", error)
        out = {}
        for k, v in value.items():
            if not isinstance(k, str):
                _fail(where, f"key {k!r} must be a string", error)
            out[k] = _check(item, v, f"{where}[{k!r}]", error)
        return out
    if dataclasses.is_dataclass(tp):
        if dataclasses.is_dataclass(value):
            value = dataclasses.asdict(value)
        if not isinstance(value, dict):
            _fail(where, "must be an object", error)
        hints = typing.get_type_hints(tp)
        fields = {f.name: f for f in dataclasses.fields(tp)}
        unknown = sorted(set(value) - set(fields))
        if unknown:
            _fail(where, f"unknown field(s) {unknown}; known: {sorted(fields)}", error)
        kwargs = {}
        for name, f in fields.items():
            if name in value:
                kwargs[name] = _check(hints[name], value[name], f"{where}.{name}", error)
            elif f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
                _fail(where, f"missing field {name!r}", error)
        return tp(**kwargs)
    raise TypeError(f"unsupported annotation {tp!r} at {where}")


def parse(cls, raw, where="args"):
    """A request's arguments as `cls`; a BadRequest naming the field when they do not fit."""
    return _check(cls, raw, where, BadRequest)


def dump(cls, reply, where="reply"):
    """A reply dataclass as JSON-ready data, checked against `cls`."""
    checked = _check(cls, reply, where, ProtocolViolation)
    return _to_json(checked)


def _to_json(value):
    if dataclasses.is_dataclass(value):
        return {f.name: _to_json(getattr(value, f.name)) for f in dataclasses.fields(value)}
    if isinstance(value, (list, tuple)):
        return [_to_json(v) for v in value]
    if isinstance(value, dict):
        return {k: _to_json(v) for k, v in value.items()}
    return value


def in_range(name, value, lo=None, hi=None):
    """`value` when it lies in [lo, hi]; a BadRequest naming `name` otherwise."""
    if (lo is not None and value < lo) or (hi is not None and value > hi):
        lo_s = "-inf" if lo is None else lo
        hi_s = "inf" if hi is None else hi
        raise BadRequest(f"{name} must lie in [{lo_s}, {hi_s}], not {value}")
    return value


# --------------------------------------------------------------------------- common types

Vec3 = tuple[float, float, float]
Aabb = tuple[Vec3, Vec3]


@dataclass(kw_only=True)
class Pose:
    """A pose: translation in metres, unit quaternion [w, x, y, z] (Drake's order)."""

    xyz: Vec3
    wxyz: tuple[float, float, float, float]


#: instance -> body -> world_from_body
Poses = dict[str, dict[str, Pose]]


@dataclass(kw_only=True)
class SceneFiles:
    directives: str
    package_xml: Optional[str] = None


@dataclass(kw_only=True)
class CacheStats:
    hits: int
    misses: int


@dataclass(kw_only=True)
class NoArgs:
    pass


# --------------------------------------------------------------------------- scene ops


@dataclass(kw_only=True)
class PingReply:
    pong: bool
    protocol: int
    bridge: str
    drake: str


@dataclass(kw_only=True)
class SolverStatus:
    available: bool
    enabled: bool


@dataclass(kw_only=True)
class VersionsReply:
    python: str
    drake: str
    numpy: Optional[str]
    mujoco: Optional[str]
    usd_core: Optional[str]
    snopt: SolverStatus
    ipopt: SolverStatus


@dataclass(kw_only=True)
class LoadedJoint:
    name: str
    type: str
    lower: list[float]
    upper: list[float]


@dataclass(kw_only=True)
class LoadedInstance:
    name: str
    bodies: list[str]
    mass: float
    joints: list[LoadedJoint]
    free_bodies: dict[str, Pose]
    welded: bool


@dataclass(kw_only=True)
class LoadReply:
    directives: str
    num_model_instances: int
    num_bodies: int
    num_positions: int
    num_collision_geometries: int
    model_instances: list[LoadedInstance]
    cache: CacheStats


@dataclass(kw_only=True)
class PenetrationsArgs(SceneFiles):
    poses: Optional[Poses] = None
    threshold: Optional[float] = None


@dataclass(kw_only=True)
class PenetrationPair:
    a: str
    b: str
    body_a: str
    body_b: str
    depth: float
    normal: Vec3


@dataclass(kw_only=True)
class PenetrationsReply:
    pairs: list[PenetrationPair]


@dataclass(kw_only=True)
class CollisionReportArgs(SceneFiles):
    poses: Optional[Poses] = None
    threshold: Optional[float] = None
    static_instances: list[str] = field(default_factory=list)


@dataclass(kw_only=True)
class CollisionReportReply:
    objects: int
    penetrating_objects: list[str]
    col_percent: float
    mean_depth_m: float
    max_depth_m: float
    threshold_m: float
    pairs: list[PenetrationPair]


@dataclass(kw_only=True)
class SphereDrop:
    name: str
    xyz: Vec3
    radius: float = 0.1


@dataclass(kw_only=True)
class DropSpheresArgs(SceneFiles):
    spheres: list[SphereDrop]
    duration: float = 1.5


@dataclass(kw_only=True)
class DroppedSphere:
    name: str
    start: Vec3
    xyz: Vec3
    radius: float
    speed: float


@dataclass(kw_only=True)
class DropSpheresReply:
    spheres: list[DroppedSphere]
    duration: float


# --------------------------------------------------------------------------- simulation


@dataclass(kw_only=True)
class ContactArgs:
    model: Literal["as_written", "point"]
    approximation: Optional[Literal["lagged", "similar", "sap", "tamsi"]] = None


def _as_written():
    return ContactArgs(model="as_written")


@dataclass(kw_only=True)
class VerdictBound:
    max_displacement_m: float
    max_rotation_rad: float


@dataclass(kw_only=True)
class SimulationArgs(SceneFiles):
    poses: Optional[Poses] = None
    time_step: float = 1e-3
    rest_speed: float = 2e-3
    rest_angular_speed: float = 2e-2
    rest_time: float = 0.25
    check_interval: float = 0.01
    wall_limit: float = 600.0
    contact: ContactArgs = field(default_factory=_as_written)
    floor_z: Optional[float] = None
    verdict: Optional[VerdictBound] = None


@dataclass(kw_only=True)
class SettleArgs(SimulationArgs):
    max_time: float = 3.0
    stop_at_rest: bool = True


@dataclass(kw_only=True)
class SimulateArgs(SimulationArgs):
    duration: float = 5.0
    stop_at_rest: bool = False


@dataclass(kw_only=True)
class Motion:
    displacement_m: float
    rotation_rad: float
    start_z: float
    end_z: float
    speed_bound: float = 0.0
    angular_speed_bound: float = 0.0


@dataclass(kw_only=True)
class SettleReply:
    poses: Poses
    motion: dict[str, Motion]
    sim_time: float
    steps: int
    at_rest: bool
    timed_out: bool
    max_speed: float
    max_angular_speed: float
    max_penetration_m: float
    free_bodies: int
    contact: ContactArgs
    time_step: float
    build_s: float
    sim_s: float
    wall_s: float
    ms_per_step: float
    cache: CacheStats
    diverged: bool = False
    bounded: bool = False


@dataclass(kw_only=True)
class ProjectArgs(SceneFiles):
    poses: Optional[Poses] = None
    solver: Literal["auto", "snopt", "ipopt", "push_out"] = "auto"
    min_distance: float = 1e-5
    tolerance: float = 1e-4
    candidate_distance: float = 0.05
    time_limit: float = 60.0
    xy_only: bool = False
    floor_z: Optional[float] = 0.0
    movable: Optional[list[str]] = None
    regions: dict[str, list[Vec3]] = field(default_factory=dict)


@dataclass(kw_only=True)
class SolverAttempt:
    solver: str
    status: str
    success: Optional[bool] = None
    pairs: Optional[int] = None
    seconds: Optional[float] = None
    max_penetration_m: Optional[float] = None


@dataclass(kw_only=True)
class ProjectReply:
    poses: Poses
    movable: list[str]
    solver: str
    initial_max_penetration_m: float
    max_penetration_m: float
    mean_displacement_m: float
    max_displacement_m: float
    pairs: int
    attempts: list[SolverAttempt]
    push_out_iterations: Optional[int]
    wall_s: float


# --------------------------------------------------------------------------- asset checks


@dataclass(kw_only=True)
class AssetModel:
    name: str
    sdf: str
    footprint: Optional[float] = None
    efforts: Optional[dict[str, float]] = None


@dataclass(kw_only=True)
class AssetsLoadArgs:
    models: list[AssetModel]


@dataclass(kw_only=True)
class AssetJoint:
    name: str
    type: str
    lower: float
    upper: float


@dataclass(kw_only=True)
class AssetSummary:
    ok: bool
    error: Optional[str] = None
    bodies: Optional[int] = None
    mass: Optional[float] = None
    joints: Optional[list[AssetJoint]] = None
    collision_geometries: Optional[int] = None


@dataclass(kw_only=True)
class AssetsLoadReply:
    models: dict[str, AssetSummary]


@dataclass(kw_only=True)
class AssetsDropArgs:
    models: list[AssetModel]
    duration: float = 2.0
    time_step: float = 1e-3


@dataclass(kw_only=True)
class DropOutcome:
    tilt_rad: float
    rotation_rad: float
    horizontal_m: float
    vertical_m: float


@dataclass(kw_only=True)
class AssetsDropReply:
    duration: float
    time_step: float
    models: dict[str, DropOutcome]


@dataclass(kw_only=True)
class AssetsPushArgs:
    models: list[AssetModel]
    duration: float = 1.0
    time_step: float = 1e-3
    force_scale: float = 2.0


@dataclass(kw_only=True)
class PushedJoint:
    type: str
    position: float
    lower: float
    upper: float
    effort: float


@dataclass(kw_only=True)
class PushOutcome:
    joints: dict[str, PushedJoint]
    self_penetration_m: float
    self_penetration_pair: Optional[tuple[str, str]]


@dataclass(kw_only=True)
class AssetsPushReply:
    duration: float
    time_step: float
    models: dict[str, PushOutcome]


# --------------------------------------------------------------------------- conformance


@dataclass(kw_only=True)
class MujocoCheckArgs:
    xml: str
    seconds: float = 5.0
    probe_joints: dict[str, float] = field(default_factory=dict)


@dataclass(kw_only=True)
class MujocoCounts:
    bodies: int
    geoms: int
    joints: int
    meshes: int


@dataclass(kw_only=True)
class MujocoBody:
    name: str
    parent: str
    mass: float
    free: bool
    collision_geoms: int
    visual_geoms: int
    collision_aabb: Optional[Aabb]
    visual_aabb: Optional[Aabb]
    friction: list[float]
    displacement_m: Optional[float] = None
    rotation_rad: Optional[float] = None
    final_pos: Optional[Vec3] = None
    initial_pos: Optional[Vec3] = None


@dataclass(kw_only=True)
class MujocoJoint:
    name: str
    type: str
    body: str
    limited: bool
    range: tuple[float, float]
    damping: float
    qpos0: float
    axis_world: Vec3


@dataclass(kw_only=True)
class MujocoCheckReply:
    mujoco: str
    load_seconds: float
    sim_seconds: float
    simulated_seconds: float
    timestep: float
    counts: MujocoCounts
    bodies: list[MujocoBody]
    joints: list[MujocoJoint]
    finite: bool
    warnings: dict[str, int]
    contacts_at_end: int
    arena_bytes: int
    arena_peak_bytes: int
    max_penetration_at_end_m: float
    probe: dict[str, float]
    messages: list[str]


@dataclass(kw_only=True)
class UsdCheckArgs:
    usd: str
    static_prims: list[str] = field(default_factory=list)


@dataclass(kw_only=True)
class UsdMetadata:
    meters_per_unit: float
    kilograms_per_unit: float
    up_axis: str
    default_prim: Optional[str]
    has_authored_meters_per_unit: bool
    custom_layer_data: dict[str, str]


@dataclass(kw_only=True)
class UsdFinding:
    validator: str
    severity: str
    message: str
    sites: list[str]


@dataclass(kw_only=True)
class UsdBody:
    kinematic: bool
    enabled: bool
    mass: Optional[float]
    diagonal_inertia: Optional[Vec3]
    center_of_mass: Optional[Vec3]
    colliders: int
    collision_aabb: Optional[Aabb]
    visual_aabb: Optional[Aabb]
    filtered: list[str]


@dataclass(kw_only=True)
class UsdStatic:
    colliders: int
    collision_aabb: Optional[Aabb]
    visual_aabb: Optional[Aabb]


@dataclass(kw_only=True)
class UsdJoint:
    path: str
    type: str
    body0: str
    body1: str
    body0_ok: bool
    body1_ok: bool
    axis: Optional[str] = None
    axis_world: Optional[Vec3] = None
    position_measured: Optional[float] = None
    off_axis_rad: Optional[float] = None
    frame_gap_m: Optional[float] = None
    limit_enabled: Optional[bool] = None
    lower: Optional[float] = None
    upper: Optional[float] = None
    drive_damping: Optional[float] = None
    drive_stiffness: Optional[float] = None


@dataclass(kw_only=True)
class UsdArticulation:
    path: str
    roots: list[str]
    bodies: list[str]
    joints: list[str]


@dataclass(kw_only=True)
class UsdCheckReply:
    usd: str
    open_seconds: float
    seconds: float
    metadata: UsdMetadata
    composition_errors: list[str]
    findings: list[UsdFinding]
    counts: dict[str, int]
    physics_scenes: int
    bodies: dict[str, UsdBody]
    static: dict[str, UsdStatic]
    approximations: dict[str, int]
    colliders_without_material: int
    materials: dict[str, tuple[float, float]]
    joints: list[UsdJoint]
    articulations: list[UsdArticulation]


# --------------------------------------------------------------------------- robot (robot_ops.py)


@dataclass
class EpisodeArgs:
    scene_dir: str
    predicate: Literal["on", "inside", "near"]
    target: str
    reference: str
    policy: Literal["standard", "degraded"]
    out_dir: str
    seed: int
    frames: bool


@dataclass
class EpisodeReply:
    success: bool
    failure_reason: Optional[str]
    message: str
    timings_s: dict[str, float]
    simulated_s: float
    max_gripper_speed: float
    welded: int
    carry_hits: list[str]
    after: Optional[str]
    files: list[str]


@dataclass
class JudgeArgs:
    scene_dir: str
    directives: str
    predicate: Literal["on", "inside", "near"]
    targets: list[str]
    references: list[str]


@dataclass
class PairVerdict:
    target: str
    reference: str
    holds: bool
    reason: str
    evidence: dict[str, float]


@dataclass
class JudgeReply:
    pairs: list[PairVerdict]
    thresholds: dict[str, float]


@dataclass
class EvalToolArgs:
    scene_dir: str
    directives: str
    tool: Literal["list_objects", "get_object_info", "get_distance", "get_spatial_relation",
                  "get_support", "observe_scene", "observe_objects"]
    object_id: Optional[str] = None
    other_id: Optional[str] = None
    category: Optional[str] = None
    object_ids: list[str] = field(default_factory=list)


@dataclass
class ToolImage:
    name: str
    png_base64: str


@dataclass
class EvalToolReply:
    result_json: str
    images: list[ToolImage]


# --------------------------------------------------------------------------- the operations

#: op name -> (argument type, reply type); the handlers are registered in drake_bridge.ops.
SIGNATURES = {
    "ping": (NoArgs, PingReply),
    "versions": (NoArgs, VersionsReply),
    "load": (SceneFiles, LoadReply),
    "penetrations": (PenetrationsArgs, PenetrationsReply),
    "collision_report": (CollisionReportArgs, CollisionReportReply),
    "drop_spheres": (DropSpheresArgs, DropSpheresReply),
    "project": (ProjectArgs, ProjectReply),
    "settle": (SettleArgs, SettleReply),
    "simulate": (SimulateArgs, SettleReply),
    "assets_load": (AssetsLoadArgs, AssetsLoadReply),
    "assets_drop": (AssetsDropArgs, AssetsDropReply),
    "assets_push": (AssetsPushArgs, AssetsPushReply),
    "mujoco_check": (MujocoCheckArgs, MujocoCheckReply),
    "usd_check": (UsdCheckArgs, UsdCheckReply),
    "policy_episode": (EpisodeArgs, EpisodeReply),
    "judge_task": (JudgeArgs, JudgeReply),
    "evaluator_tool": (EvalToolArgs, EvalToolReply),
}
