"""Unit tests of policy parts that need no scene: the point grid of the grasp sampler's
collision filter and the base candidates' headings."""

import math

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from drake_bridge.policy import placement
from drake_bridge.policy.grasp import PointGrid, _grid_hits_boxes


def test_point_grid_returns_every_point_inside_a_box():
    rng = np.random.default_rng(3)
    points = rng.uniform(-0.5, 0.5, size=(5000, 3))
    grid = PointGrid(points, cell=0.04)
    lower, upper = np.array([-0.11, 0.02, -0.3]), np.array([0.07, 0.19, -0.05])
    inside = points[np.all((points >= lower) & (points <= upper), axis=1)]
    found = grid.in_box(lower, upper)
    found_inside = found[np.all((found >= lower) & (found <= upper), axis=1)]
    assert len(inside) > 0
    assert sorted(map(tuple, inside)) == sorted(map(tuple, found_inside))
    assert len(grid.in_box([2.0, 2.0, 2.0], [2.1, 2.1, 2.1])) == 0


def test_grid_box_test_matches_a_pass_over_every_point():
    rng = np.random.default_rng(5)
    points = rng.uniform(-0.3, 0.3, size=(4000, 3))
    grid = PointGrid(points)
    boxes = [(RigidTransform(RotationMatrix.MakeZRotation(0.4), [0.0, 0.03, 0.0]),
              np.array([0.01, 0.01, 0.03]))]
    for k in range(40):
        X_WG = RigidTransform(RotationMatrix.MakeXRotation(0.1 * k), rng.uniform(-0.3, 0.3, 3))
        R, c = X_WG.rotation().matrix(), X_WG.translation()
        X_GB, half = boxes[0]
        local = ((points - c) @ R - X_GB.translation()) @ X_GB.rotation().matrix()
        brute = bool(np.any(np.all(np.abs(local) <= half + 0.008, axis=1)))
        assert _grid_hits_boxes(grid, X_WG, boxes, 0.008) == brute


class _FacingCollides:
    """A stand-in collision checker: every base pose whose heading points at the origin
    collides (a table in the way of the base's front), side-on ones are free."""

    def __init__(self):
        self.poses = []

    def CheckConfigCollisionFree(self, q):
        x, y, yaw = q
        self.poses.append((x, y, yaw))
        to_origin = math.atan2(-y, -x)
        return abs((yaw - to_origin + math.pi) % (2 * math.pi) - math.pi) > 0.1


def test_a_base_that_cannot_face_the_point_stands_side_on_with_its_arm_at_the_distance():
    checker = _FacingCollides()
    bases = placement.base_candidates(checker, lambda x, y, yaw: (x, y, yaw), (0.0, 0.0))
    assert bases
    for base in bases:
        d = placement.arm_distance(base, (0.0, 0.0, 0.0))
        assert any(abs(d - a) < 1e-9 for a in placement.ARM_DISTANCES_M), d
        to_origin = math.atan2(-base[1], -base[0])
        turn = abs((base[2] - to_origin + math.pi) % (2 * math.pi) - math.pi)
        assert abs(turn - math.pi / 2) < 0.2, turn
