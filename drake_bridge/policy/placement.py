"""Where the object goes and where the robot stands: place candidates per predicate and base
pose candidates around a point.

Place candidates (object body poses X_WO, the object upright as it started, turned about the
world z axis by 0, +90, -90 or 180 degrees, its lowest point PLACE_GAP_M above the surface):
- "on": the reference's top. From scene.json when the reference's asset lists surfaces (the
  one named "top", else the highest): a GRID_M grid over the surface rectangle inset by the
  object's footprint radius + 2 cm (a surface too small for that, such as a plate's flat
  well: its centre alone, when the reference itself is wider than the footprint). Otherwise from the reference's collision surface: the
  upward-facing points (normal z > 0.95) within 1 cm of the highest one, a grid over them,
  kept where the object's footprint is supported (every footprint point within 2 cm of a top
  point). Centres first; positions within MIN_MOVE_M of the object's start are skipped (the
  object should visibly move even when it already stands on the reference).
- "inside": the container's inside. scene.json's surface named "inside" (or a sink's "basin")
  when present, a grid over it as for "on", else the upward-facing points of the reference below its rim (2 cm under its top)
  near its horizontal centre: their highest z is the inner floor.
- "near": on the surface the reference stands on (the upward-facing scene points at the
  reference's lowest z, within 1.5 cm), with a gap between the object's and the reference's
  footprints of 2 cm to NEAR_GAP_M - 3 cm; gaps near 5 cm first.
Each candidate is still to be checked: `object_clear` (the object's sampled surface at least
PLACE_CLEARANCE_M from the scene, by signed distance to points) and then IK with the held
object (minimum distance) decide.

Base candidates: the arm's vertical axis (5 cm behind the base centre) at ARM_DISTANCES_M
from the point, in 24 directions, the base facing the point or, when that collides, side on
to it or square to the room; nearest first, then the directions closest to `preferred_dir` (away from the
supporting furniture's centre). A candidate must be collision-free at home (the checker,
scene padding) and hold every `also_reach` point within MAX_REACH_M of the arm axis.
"""

import dataclasses as dc
import math

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

NEAR_GAP_M = 0.15
PLACE_GAP_M = 0.01
PLACE_CLEARANCE_M = 0.006
MIN_MOVE_M = 0.15
GRID_M = 0.04
YAWS_RAD = (0.0, math.pi / 2, -math.pi / 2, math.pi)
ARM_AXIS_BEHIND_BASE_M = 0.05
ARM_DISTANCES_M = (0.5, 0.55, 0.6, 0.65, 0.7, 0.75)
#: The base's heading at a candidate, relative to facing the point: facing it, then side on
#: (the arm stands 0.35 m behind the base's front but 0.25 m from its sides, so side on it
#: reaches 10 cm further over a table).
BASE_TURNS_RAD = (0.0, math.pi / 2, -math.pi / 2)
#: Then square to the room (rooms and their furniture are axis-aligned: a base square to a
#: table fits beside a chair where a turned one does not).
ROOM_YAWS_RAD = (0.0, math.pi / 2, math.pi, -math.pi / 2)
MAX_REACH_M = 0.85
#: Horizontal distances from the arm axis at which a place pose is tried, and the comfortable
#: one (a top-down grasp at table height reaches about 0.8 m).
PLACE_REACH_M = (0.3, 0.78)
COMFORT_REACH_M = 0.55
UP_NORMAL_Z = 0.95


@dc.dataclass
class PlacePosition:
    """A place location: the point (world, m) under the object's footprint centre on the
    surface, and the surface height."""

    p_W: np.ndarray
    surface_z: float


class ObjectShape:
    """The target's sampled surface in its body frame O, for footprints and clearances."""

    def __init__(self, cloud, X_WO0, rng, max_points=160):
        P_O = X_WO0.inverse().multiply(cloud.p.T).T
        self.P_O = P_O
        pick = rng.choice(len(P_O), size=min(max_points, len(P_O)), replace=False)
        self.P_O_sparse = P_O[pick]
        self.R_WO0 = X_WO0.rotation()

    def rotation(self, yaw):
        return RotationMatrix.MakeZRotation(yaw).multiply(self.R_WO0)

    def radius(self):
        """Largest horizontal distance of the object's surface from its footprint centre
        (upright as it started), m."""
        P = (self.R_WO0.matrix() @ self.P_O.T).T
        centre = (P[:, :2].max(axis=0) + P[:, :2].min(axis=0)) / 2
        return float(np.max(np.linalg.norm(P[:, :2] - centre, axis=1)))

    def pose_at(self, place, yaw):
        """X_WO with the footprint centre over place.p_W and the lowest point PLACE_GAP_M above
        the surface."""
        R = self.rotation(yaw)
        P = (R.matrix() @ self.P_O.T).T
        centre = (P[:, :2].max(axis=0) + P[:, :2].min(axis=0)) / 2
        p = np.array([place.p_W[0] - centre[0], place.p_W[1] - centre[1],
                      place.surface_z + PLACE_GAP_M - P[:, 2].min()])
        return RigidTransform(R, p)


def object_clear(query, shape, X_WO, ignore_ids, clearance=PLACE_CLEARANCE_M):
    """True when every sparse surface point of the object at X_WO is at least `clearance` from
    every scene geometry not in ignore_ids (signed distance to a point)."""
    for p in X_WO.multiply(shape.P_O_sparse.T).T:
        for d in query.ComputeSignedDistanceToPoint(p, clearance):
            if d.id_G not in ignore_ids and d.distance < clearance:
                return False
    return True


def _supported(points_xy, support_xy, radius, tol=0.02):
    """Every footprint point (centre and 8 on a circle of 0.7 radius) within tol of a support
    point."""
    angles = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    ring = 0.7 * radius * np.stack([np.cos(angles), np.sin(angles)], axis=1)
    out = []
    for c in points_xy:
        foot = np.vstack([c, c + ring])
        d = np.min(np.linalg.norm(foot[:, None, :] - support_xy[None, :, :], axis=2), axis=1)
        out.append(bool(np.all(d < tol)))
    return np.array(out, dtype=bool)


def _grid(lower, upper, step=GRID_M):
    xs = np.arange(lower[0], upper[0] + 1e-9, step)
    ys = np.arange(lower[1], upper[1] + 1e-9, step)
    if len(xs) == 0 or len(ys) == 0:
        return np.zeros((0, 2))
    return np.array([(x, y) for x in xs for y in ys])


def _json_surface(spec, reference, wanted):
    surfaces = spec.surfaces(reference)
    if not surfaces:
        return None
    if wanted in surfaces:
        return surfaces[wanted]
    if wanted == "top":
        return max(surfaces.values(), key=lambda s: s["center"][2])
    return None


def _surface_positions(body_pose, reference, surface, radius, reference_cloud):
    """A GRID_M grid over a scene.json surface of the reference inset by the object's footprint
    radius + 2 cm, centres first (a surface too small for that, such as a plate's flat well:
    its centre alone, when the reference itself is wider than the footprint)."""
    X_WR = body_pose(reference, surface.get("link"))
    half = np.array(surface["size"][:2]) / 2 - (radius + 0.02)
    if np.any(half < 0):
        extent = reference_cloud.p[:, :2].max(axis=0) - reference_cloud.p[:, :2].min(axis=0)
        if np.any(extent / 2 < radius + 0.005):
            return []
        half = np.maximum(half, 0.0)
    centre = np.array(surface["center"], dtype=float)
    grid = _grid(-half, half)
    grid = grid[np.argsort(np.linalg.norm(grid, axis=1), kind="stable")]
    local = np.column_stack([grid + centre[:2], np.full(len(grid), centre[2])])
    return [PlacePosition(p, float(p[2])) for p in X_WR.multiply(local.T).T]


def on_positions(spec, task, body_pose, reference_cloud, radius, start_p_W):
    """Place positions on the reference's top (see module doc), best first. `body_pose(instance,
    link)`: a scene body's world pose (StaticScene.body_pose)."""
    surface = _json_surface(spec, task.reference, "top")
    if surface is not None:
        out = _surface_positions(body_pose, task.reference, surface, radius, reference_cloud)
    else:
        up = reference_cloud.n[:, 2] > UP_NORMAL_Z
        if not np.any(up):
            return []
        top_z = float(reference_cloud.p[up, 2].max())
        top = reference_cloud.p[up & (reference_cloud.p[:, 2] > top_z - 0.01)]
        lo, hi = top[:, :2].min(axis=0), top[:, :2].max(axis=0)
        grid = _grid(lo + radius, hi - radius)
        if len(grid) == 0:
            return []
        grid = grid[_supported(grid, top[:, :2], radius)]
        grid = grid[np.argsort(np.linalg.norm(grid - (lo + hi) / 2, axis=1), kind="stable")]
        out = [PlacePosition(np.array([x, y, top_z]), top_z) for x, y in grid]
    return [c for c in out if np.linalg.norm(c.p_W[:2] - start_p_W[:2]) >= MIN_MOVE_M]


def inside_positions(spec, task, body_pose, reference_cloud, radius):
    """Place positions inside the container (see module doc), best first, or []."""
    surface = (_json_surface(spec, task.reference, "inside")
               or _json_surface(spec, task.reference, "basin"))
    if surface is not None:
        return _surface_positions(body_pose, task.reference, surface, radius, reference_cloud)
    P, n = reference_cloud.p, reference_cloud.n
    top_z = float(P[:, 2].max())
    centre = (P[:, :2].max(axis=0) + P[:, :2].min(axis=0)) / 2
    floor = (n[:, 2] > UP_NORMAL_Z) & (P[:, 2] < top_z - 0.02) & (
        np.linalg.norm(P[:, :2] - centre, axis=1) < 0.03)
    if not np.any(floor):
        return []
    z = float(P[floor, 2].max())
    return [PlacePosition(np.array([centre[0], centre[1], z]), z)]


def near_positions(reference_cloud, env_cloud, radius):
    """Place positions beside the reference on the surface it stands on (see module doc)."""
    P = reference_cloud.p
    z = float(P[:, 2].min())
    up = (env_cloud.n[:, 2] > UP_NORMAL_Z) & (np.abs(env_cloud.p[:, 2] - z) < 0.015)
    if not np.any(up):
        return []
    support = env_cloud.p[up, :2]
    ref_xy = P[:, :2]
    lo = ref_xy.min(axis=0) - radius - NEAR_GAP_M
    hi = ref_xy.max(axis=0) + radius + NEAR_GAP_M
    grid = _grid(lo, hi, GRID_M / 2)
    if len(grid) == 0:
        return []
    gap = np.array([np.min(np.linalg.norm(ref_xy - g, axis=1)) for g in grid]) - radius
    keep = (gap >= 0.02) & (gap <= NEAR_GAP_M - 0.03)
    grid, gap = grid[keep], gap[keep]
    if len(grid) == 0:
        return []
    ok = _supported(grid, support, radius)
    grid, gap = grid[ok], gap[ok]
    order = np.argsort(np.abs(gap - 0.05), kind="stable")
    return [PlacePosition(np.array([grid[i, 0], grid[i, 1], z]), z) for i in order]


def base_candidates(checker, q_home_at, target_xy, preferred_dir=None, also_reach=()):
    """Collision-free base poses (x, y, yaw) around target_xy (see module doc), best first.
    `q_home_at(x, y, yaw)` is the planning q at home with the base there."""
    angles = np.linspace(0.0, 2 * np.pi, 24, endpoint=False)
    if preferred_dir is not None and np.linalg.norm(preferred_dir) > 1e-9:
        phi = math.atan2(preferred_dir[1], preferred_dir[0])
        dist = np.abs((angles - phi + np.pi) % (2 * np.pi) - np.pi)
        angles = angles[np.argsort(dist, kind="stable")]
    out = []
    for d in ARM_DISTANCES_M:
        for a in angles:
            u = np.array([math.cos(a), math.sin(a)])  # from the target towards the base
            axis = np.asarray(target_xy) + d * u
            if any(np.linalg.norm(np.asarray(p)[:2] - axis) > MAX_REACH_M for p in also_reach):
                continue
            facing = math.atan2(-u[1], -u[0])
            for yaw in [facing + turn for turn in BASE_TURNS_RAD] + list(ROOM_YAWS_RAD):
                base = axis + ARM_AXIS_BEHIND_BASE_M * np.array([math.cos(yaw), math.sin(yaw)])
                if checker.CheckConfigCollisionFree(q_home_at(base[0], base[1], yaw)):
                    out.append((float(base[0]), float(base[1]), float(yaw)))
                    break
    return out


def arm_distance(base, p_W):
    """Horizontal distance (m) of p_W from the arm's vertical axis with the base at base."""
    x, y, yaw = base
    axis = np.array([x, y]) - ARM_AXIS_BEHIND_BASE_M * np.array([math.cos(yaw), math.sin(yaw)])
    return float(np.linalg.norm(np.asarray(p_W)[:2] - axis))


def by_reach(base, positions):
    """The positions within PLACE_REACH_M of the arm axis, those at a comfortable distance
    (within 10 cm of COMFORT_REACH_M) first, each group in its given (preference) order."""
    out = [(abs(arm_distance(base, p.p_W) - COMFORT_REACH_M) > 0.1, k, p)
           for k, p in enumerate(positions)
           if PLACE_REACH_M[0] <= arm_distance(base, p.p_W) <= PLACE_REACH_M[1]]
    return [p for _, _, p in sorted(out, key=lambda e: (e[0], e[1]))]
