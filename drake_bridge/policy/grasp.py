"""Antipodal grasp sampling for the parallel-jaw gripper, on the target's sampled surface.

A candidate starts at a surface point p_a with outward normal n_a. The closing axis is -n_a; the
opposite contact p_b is where that line leaves the object (the farthest cloud point within
LINE_TOL_M of the line), and it must face the other way: n_b . (-n_a) >= cos(FRICTION_CONE).
The width (p_a - p_b along n_a) must fit in the stroke less a clearance on each side
(<= MAX_WIDTH_M). The gripper's `grasp_frame` G closes along the contact normal: +y = n_a
(the right finger on p_a), its origin half the width inside p_a, its approach +z
perpendicular to y: first the one
closest to straight down, then turned about y in ROTATIONS_DEG steps (top-down approaches
score higher), and each also held shallower: the frame moved back along the approach by each of
DEPTHS_M, so the contacts sit nearer the finger tips and the tips stay clear of what the object
stands in (an apple in a fruit bowl, a can on a board). Closing axes within VERTICAL_AXIS_DEG
of vertical are skipped (they would pinch the object between table-level finger tips).

Collision check of the open gripper (each finger OPEN_MARGIN_M beyond its contact, at most
55 mm from the centre line): the gripper's collision boxes (body,
fingers, and the last arm link's cylinder as its bounding box), inflated by ENV_MARGIN_M, must
hold no point of the scene's surface cloud near the object (bucketed in 4 cm cells: each box
is tested against the points of the cells it touches); inflated by TARGET_MARGIN_M they
must hold no point of the target's own cloud. Sampled surfaces of 4-5 mm spacing cannot pass
through a 18 mm finger unseen, so this is a reliable filter; the exact check follows in IK
(minimum distance) and in the collision checker.

Score (higher is better): top_down + 0.3 * antipodal alignment - 2.0 * horizontal distance of
the grasp centre from the object's centre of mass (m) - 1.0 * its vertical distance (m) - 2.0 *
the depth offset (m).
"""

import dataclasses as dc
import math

import numpy as np
from pydrake.common.eigen_geometry import AngleAxis
from pydrake.geometry import Box, Capsule, Cylinder
from pydrake.math import RigidTransform, RotationMatrix

from drake_bridge.policy.scene import FINGER_JOINTS, FINGER_OPEN_M, GRIPPER_BODIES

STROKE_M = 2 * FINGER_OPEN_M
SIDE_CLEARANCE_M = 0.008
MAX_WIDTH_M = STROKE_M - 2 * SIDE_CLEARANCE_M
LINE_TOL_M = 0.004
FRICTION_CONE_DEG = 20.0
VERTICAL_AXIS_DEG = 25.0
ROTATIONS_DEG = (0.0, 30.0, -30.0, 60.0, -60.0, 90.0, -90.0)
#: How far the grasp frame may sit back along the approach from the contacts' centre (m): the
#: finger pads reach 30 mm past the frame's origin, so 20 mm leaves the contacts 10 mm from
#: the tips.
DEPTHS_M = (0.0, 0.012, 0.02)
ENV_MARGIN_M = 0.008
TARGET_MARGIN_M = 0.003
#: The closed finger target is this far inside each contact: the finger PD (2000 N/m in the
#: SDF) then squeezes with about 30 N per finger, below the 80 N limit.
SQUEEZE_M = 0.015
#: The narrowest jaw width taken: the fingers can squeeze it by the full SQUEEZE_M (a 9 mm
#: cup rim, closed to the stops, is held with 9 N and slips).
MIN_WIDTH_M = 2 * SQUEEZE_M
#: The fingers open this far beyond each contact for the approach (m), not the whole stroke:
#: an apple in a bowl leaves little room beside it.
OPEN_MARGIN_M = 0.012


@dc.dataclass
class Grasp:
    """A grasp candidate: X_WG the grasp frame in the world, contacts p_a (right finger) and p_b
    (left finger) in the world, jaw width (m), score, and cos of the angle between the approach
    and straight down."""

    X_WG: RigidTransform
    p_a: np.ndarray
    p_b: np.ndarray
    width: float
    score: float
    top_down: float

    def finger_target(self):
        return max(0.0, self.width / 2 - SQUEEZE_M)

    def finger_open(self):
        """Each finger's position while the gripper approaches, before closing and after
        releasing: the jaw width plus OPEN_MARGIN_M a side, at most fully open."""
        return min(FINGER_OPEN_M, self.width / 2 + OPEN_MARGIN_M)

    def flipped(self):
        """The same grasp with the gripper turned half a turn about its approach axis (the
        fingers swap sides; the jaw is symmetric)."""
        X = self.X_WG.multiply(RigidTransform(RotationMatrix.MakeZRotation(math.pi)))
        return dc.replace(self, X_WG=X, p_a=self.p_b, p_b=self.p_a)


def gripper_boxes(model, q_open):
    """The gripper's collision shapes as boxes in the grasp frame G at q_open (fingers fully
    open): list of (X_GB, half extents, side), side +1 or -1 for a finger on +y or -y, 0 for
    the rest. Cylinders and capsules become their bounding boxes."""
    plant = model.plant
    query = model.query(q_open)
    inspector = query.inspector()
    X_WG = model.X_WG(q_open)
    bodies = [plant.GetBodyByName(n, model.robot) for n in GRIPPER_BODIES + ("iiwa_link_7",)]
    fingers = {plant.GetJointByName(n, model.robot).child_body().index() for n in FINGER_JOINTS}
    out = []
    for body in bodies:
        for gid in plant.GetCollisionGeometriesForBody(body):
            shape = inspector.GetShape(gid)
            if isinstance(shape, Box):
                half = np.array([shape.width(), shape.depth(), shape.height()]) / 2
            elif isinstance(shape, Cylinder):
                half = np.array([shape.radius(), shape.radius(), shape.length() / 2])
            elif isinstance(shape, Capsule):
                half = np.array([shape.radius(), shape.radius(),
                                 shape.length() / 2 + shape.radius()])
            else:
                raise ValueError(f"gripper geometry {inspector.GetName(gid)}: unsupported shape")
            X_GB = X_WG.inverse().multiply(query.GetPoseInWorld(gid))
            side = float(np.sign(X_GB.translation()[1])) if body.index() in fingers else 0.0
            out.append((X_GB, half, side))
    return out


def _boxes_open_to(boxes, finger_open):
    """`boxes` (gripper_boxes at fully open fingers) with the fingers at finger_open (m)."""
    out = []
    for X_GB, half, side in boxes:
        if side != 0.0:
            shift = side * (finger_open - FINGER_OPEN_M)
            X_GB = RigidTransform(X_GB.rotation(), X_GB.translation() + [0.0, shift, 0.0])
        out.append((X_GB, half))
    return out


def _any_inside(points_G, boxes, margin):
    """True when any point (N x 3, grasp frame) lies inside any box inflated by margin."""
    for X_GB, half in boxes:
        R, p = X_GB.rotation().matrix(), X_GB.translation()
        local = (points_G - p) @ R
        if np.any(np.all(np.abs(local) <= half + margin, axis=1)):
            return True
    return False


class PointGrid:
    """Points bucketed in cubic cells of `cell` m, for the points near a box without a pass
    over the whole cloud."""

    def __init__(self, points, cell=0.04):
        self.cell = cell
        self.cells = {}
        if len(points) == 0:
            return
        keys = np.floor(points / cell).astype(np.int64)
        order = np.lexsort(keys.T[::-1])
        keys, points = keys[order], points[order]
        starts = np.flatnonzero(np.any(np.diff(keys, axis=0) != 0, axis=1)) + 1
        bounds = np.concatenate([[0], starts, [len(points)]])
        for a, b in zip(bounds[:-1], bounds[1:]):
            self.cells[tuple(keys[a])] = points[a:b]

    def in_box(self, lower, upper):
        """The points of the cells that the axis-aligned box [lower, upper] touches."""
        lo = np.floor(np.asarray(lower) / self.cell).astype(np.int64)
        hi = np.floor(np.asarray(upper) / self.cell).astype(np.int64)
        found = [self.cells[(i, j, k)]
                 for i in range(lo[0], hi[0] + 1)
                 for j in range(lo[1], hi[1] + 1)
                 for k in range(lo[2], hi[2] + 1) if (i, j, k) in self.cells]
        return np.concatenate(found) if found else np.zeros((0, 3))


def _grid_hits_boxes(grid, X_WG, boxes, margin):
    """True when any point of `grid` (world frame) lies inside any gripper box (grasp frame,
    X_WG) inflated by margin."""
    R_WG, p_WG = X_WG.rotation().matrix(), X_WG.translation()
    for X_GB, half in boxes:
        R = R_WG @ X_GB.rotation().matrix()
        centre = p_WG + R_WG @ X_GB.translation()
        reach = np.abs(R) @ (half + margin)
        points = grid.in_box(centre - reach, centre + reach)
        if len(points) and np.any(np.all(np.abs((points - centre) @ R) <= half + margin,
                                         axis=1)):
            return True
    return False


def _frame(y_G, z_G, centre):
    x_G = np.cross(y_G, z_G)
    return RigidTransform(RotationMatrix(np.column_stack([x_G, y_G, z_G])), centre)


def sample_grasps(target_cloud, env_cloud, boxes, p_com_W, rng, max_grasps=20,
                  max_seeds=2500, standoff_m=None):
    """Up to `max_grasps` collision-free antipodal grasps from at most `max_seeds` seed points
    of the target cloud (a Cloud, world frame) drawn with `rng`: the best of each approach
    tilt in turn (straight down, 30, 60, 90 degrees from it; the tilts in the order of their
    best scores), so that a bottle under a range hood is offered side grasps among the first.
    With `standoff_m`, the open gripper must also be clear of the scene that far back along
    the approach (the pre-grasp)."""
    P, N = target_cloud.p, target_cloud.n
    cos_cone = math.cos(math.radians(FRICTION_CONE_DEG))
    sin_vertical = math.sin(math.radians(VERTICAL_AXIS_DEG))
    down = np.array([0.0, 0.0, -1.0])
    order = rng.permutation(len(P))[:max_seeds]
    candidates = []
    for i in order:
        p_a, n_a = P[i], N[i]
        axis = -n_a  # from p_a into the object, towards p_b
        v = P - p_a
        t = v @ axis
        lateral = np.linalg.norm(v - np.outer(t, axis), axis=1)
        on_line = (lateral < LINE_TOL_M) & (t > MIN_WIDTH_M)
        if not np.any(on_line):
            continue
        j = np.flatnonzero(on_line)[np.argmax(t[on_line])]
        width = float(t[j])
        alignment = float(N[j] @ axis)
        if width > MAX_WIDTH_M or alignment < cos_cone:
            continue
        p_b = P[j]
        # The jaw closes along the contact normal: the right finger's pad on p_a's face, the
        # grasp centre half the width inside it (p_b lies within LINE_TOL_M of that line).
        y_G = n_a / np.linalg.norm(n_a)
        centre = p_a - y_G * width / 2
        z0 = down - (down @ y_G) * y_G
        if np.linalg.norm(z0) < sin_vertical:
            continue
        z0 /= np.linalg.norm(z0)
        d = centre - p_com_W
        for angle in ROTATIONS_DEG:
            z_G = AngleAxis(math.radians(angle), y_G).rotation() @ z0
            top_down = float(z_G @ down)
            score = (top_down + 0.3 * alignment - 2.0 * float(np.linalg.norm(d[:2]))
                     - 1.0 * abs(float(d[2])))
            for depth in DEPTHS_M:
                candidates.append((score - 2.0 * depth, top_down,
                                   _frame(y_G, z_G, centre - depth * z_G), p_a, p_b, width))
    candidates.sort(key=lambda c: -c[0])

    env_grid = PointGrid(env_cloud.p)
    tilts = {}  # tilt bucket -> grasps, best first
    for score, top_down, X_WG, p_a, p_b, width in candidates:
        bucket = int(round(math.degrees(math.acos(max(-1.0, min(1.0, top_down)))) / 30.0))
        found = tilts.setdefault(bucket, [])
        if len(found) >= max_grasps:
            if len(tilts) == 4 and all(len(g) >= max_grasps for g in tilts.values()):
                break
            continue
        if any(np.linalg.norm(g.X_WG.translation() - X_WG.translation()) < 0.01 and
               g.X_WG.rotation().InvertAndCompose(X_WG.rotation()).ToAngleAxis().angle()
               < math.radians(20.0) for g in found):
            continue
        R, c = X_WG.rotation().matrix(), X_WG.translation()
        opened = _boxes_open_to(boxes, min(FINGER_OPEN_M, width / 2 + OPEN_MARGIN_M))
        if _grid_hits_boxes(env_grid, X_WG, opened, ENV_MARGIN_M):
            continue
        if _any_inside((P - c) @ R, opened, TARGET_MARGIN_M):
            continue
        if standoff_m is not None and _grid_hits_boxes(
                env_grid, X_WG.multiply(RigidTransform([0.0, 0.0, -standoff_m])), opened,
                ENV_MARGIN_M):
            continue
        found.append(Grasp(X_WG, p_a, p_b, width, score, top_down))
    ranked = sorted((g for g in tilts.values() if g), key=lambda g: -g[0].score)
    out = [g for k in range(max_grasps) for grasps in ranked if k < len(grasps)
           for g in [grasps[k]]]
    return out[:max_grasps]
