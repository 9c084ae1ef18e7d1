"""Base navigation (drake_bridge/policy/navigation.py) between two rooms.

The world (the real robot model and SceneGraphCollisionChecker, through PlanningModel, as the
policy builds it): a welded floor; 2 m walls around a 5.6 x 3.0 m floor; a wall at x = 2.8 m
splitting it into room A (west) and room B (east), with a 1.0 m door at y = 1.8 .. 2.8 m (the
"closed" variant has no door); the robot at home (arm folded, 0.5 m wide at yaw 0). Start
(1.2, 0.8) in room A, goal (4.4, 0.8) in room B: the straight line runs through the wall.

What is pinned: the path through the door starts and ends at the exact start and goal, passes
the checker on every edge and at every 0.02 step, moves only the base joints, is a handful of
waypoints, and is at least as long as the shortest detour the door allows (at most 25 % longer);
the search is lazy (checks far fewer configurations than the lattice has); a closed wall gives
None by exhausting the reachable lattice, and a small `max_expansions` gives None after exactly
that many expansions; the yaw joint moves continuously to the goal's exact value when it is
more than half a turn from the start's, turning monotonically where turning is free, and
stays continuous through +-pi where the path needs a heading beyond it; a goal tight in a
corner at a yaw between the lattice's headings is reached exactly; a past deadline, and a
deadline that passes during the search, raise PlanningTimeout. Where the point is the search
rather than the geometry, a disc robot among rectangles (a fake checker) stands in.
"""

import math
import time

import numpy as np
import pytest

from drake_bridge.policy.navigation import nearest_equivalent_yaw, path_length, plan_base_path
from drake_bridge.policy.rrt import PlanningTimeout
from drake_bridge.policy.scene import (
    BASE_JOINTS,
    PlanningModel,
    home_positions,
    load_scene_spec,
)
from drake_bridge.policy.types import PolicyConfig
from drake_bridge.tests.conftest import write_scene

WALL_X = 2.8
WALL_T = 0.1
DOOR_Y = (1.8, 2.8)
ROOM_X, ROOM_Y = 5.6, 3.0
WALL_H = 2.0
START = (1.2, 0.8, 0.0)
GOAL = (4.4, 0.8, 0.0)
BASE_HALF_WIDTH_M = 0.25  # the base box is 0.6 x 0.5 m: a 0.25 m disc about its centre


def _walls(door):
    z = WALL_H / 2
    boxes = [
        ("floor", (ROOM_X / 2, ROOM_Y / 2, -0.05), (ROOM_X + 2, ROOM_Y + 2, 0.1), True),
        ("wall_s", (ROOM_X / 2, -WALL_T / 2, z), (ROOM_X + 2 * WALL_T, WALL_T, WALL_H), True),
        ("wall_n", (ROOM_X / 2, ROOM_Y + WALL_T / 2, z), (ROOM_X + 2 * WALL_T, WALL_T, WALL_H),
         True),
        ("wall_w", (-WALL_T / 2, ROOM_Y / 2, z), (WALL_T, ROOM_Y, WALL_H), True),
        ("wall_e", (ROOM_X + WALL_T / 2, ROOM_Y / 2, z), (WALL_T, ROOM_Y, WALL_H), True),
        # PlanningModel wants one free target body: a small box in room A's corner.
        ("target", (0.3, 2.7, 0.05), (0.1, 0.1, 0.1), False),
    ]
    if door:
        lo, hi = DOOR_Y
        boxes += [("divider_s", (WALL_X, lo / 2, z), (WALL_T, lo, WALL_H), True),
                  ("divider_n", (WALL_X, (hi + ROOM_Y) / 2, z), (WALL_T, ROOM_Y - hi, WALL_H),
                   True)]
    else:
        boxes.append(("divider", (WALL_X, ROOM_Y / 2, z), (WALL_T, ROOM_Y, WALL_H), True))
    return boxes


def _model(tmp_path_factory, door):
    name = "nav_door" if door else "nav_closed"
    scene_dir = tmp_path_factory.mktemp(name)
    write_scene(scene_dir, _walls(door), package=name)
    return PlanningModel(load_scene_spec(str(scene_dir)), "target", "world",
                         PolicyConfig.named("standard"))


@pytest.fixture(scope="module")
def door_model(tmp_path_factory):
    return _model(tmp_path_factory, door=True)


@pytest.fixture(scope="module")
def closed_model(tmp_path_factory):
    return _model(tmp_path_factory, door=False)


def _q(model, base):
    return model.q_from(dict(home_positions(), base_x=base[0], base_y=base[1],
                             base_yaw=base[2]))


def _yaws(path, base_indices):
    return np.array([q[base_indices[2]] for q in path])


def _assert_valid_path(checker, path, q_start, q_goal, base_indices, step=0.02):
    np.testing.assert_array_equal(path[0], q_start)
    np.testing.assert_array_equal(path[-1], q_goal)
    others = np.setdiff1d(np.arange(len(q_start)), base_indices)
    for qa, qb in zip(path[:-1], path[1:]):
        np.testing.assert_array_equal(qa[others], q_start[others])
        assert checker.CheckEdgeCollisionFree(qa, qb)
        # Independently of the checker's edge routine: free at every `step` of joint motion.
        n = int(np.ceil(np.max(np.abs(qb - qa)) / step)) + 1
        for t in np.linspace(0.0, 1.0, n):
            assert checker.CheckConfigCollisionFree(qa + t * (qb - qa))


# ---------------------------------------------------------------- the real robot and checker
def test_path_through_the_door(door_model):
    m = door_model
    base = m.indices(BASE_JOINTS)
    q_start, q_goal = _q(m, START), _q(m, GOAL)
    assert not m.checker.CheckEdgeCollisionFree(q_start, q_goal)  # the wall is in the way
    stats = {}
    t0 = time.monotonic()
    path = plan_base_path(m.checker, q_start, q_goal, base, time.monotonic() + 60.0,
                          stats=stats)
    seconds = time.monotonic() - t0
    assert path is not None, stats
    assert stats["outcome"] == "found"
    _assert_valid_path(m.checker, path, q_start, q_goal, base)
    assert 3 <= len(path) <= 8, len(path)  # shortened: a handful of waypoints
    # The base's 0.25 m inscribed disc must fit the door where the centre crosses x = WALL_X:
    # the centre then has y >= 1.8 + 0.25, so the path is at least two legs of this length.
    leg = math.hypot(WALL_X - START[0], DOOR_Y[0] + BASE_HALF_WIDTH_M - START[1])
    straight = math.hypot(GOAL[0] - START[0], GOAL[1] - START[1])
    length = path_length(path, base)
    assert length >= 2 * leg - 1e-6 > straight
    assert length <= 1.25 * 2 * leg, length
    # Lazy: far fewer configurations checked than the lattice over the floor has states
    # (56 x 30 cells, 8 headings), each state checked at most once.
    assert stats["config_checks"] < 56 * 30 * 8 / 4, stats
    assert stats["config_checks"] <= stats["expansions"] * 10 + 10
    assert seconds < 30.0


def test_closed_wall_gives_none_by_exhausting_the_room(closed_model):
    m = closed_model
    base = m.indices(BASE_JOINTS)
    stats = {}
    t0 = time.monotonic()
    path = plan_base_path(m.checker, _q(m, START), _q(m, GOAL), base, None, stats=stats)
    assert path is None
    # Room A's reachable lattice (about 20 x 24 cells, 9 unwrapped headings) ran out.
    assert stats["outcome"] == "exhausted", stats
    assert stats["expansions"] < 20_000
    assert time.monotonic() - t0 < 30.0


def test_max_expansions_bounds_the_search(door_model):
    m = door_model
    stats = {}
    path = plan_base_path(m.checker, _q(m, START), _q(m, GOAL), m.indices(BASE_JOINTS), None,
                          max_expansions=100, stats=stats)
    assert path is None
    assert stats["outcome"] == "max_expansions" and stats["expansions"] == 100


def test_goal_yaw_more_than_half_a_turn_away(door_model):
    """The goal's yaw joint value is 4 rad from the start's: the base turns +4 rad, through
    the door, and ends at exactly 4.0 (not at 4.0 - 2 pi, and with no 2 pi jump)."""
    m = door_model
    base = m.indices(BASE_JOINTS)
    goal = (GOAL[0], GOAL[1], 4.0)
    q_start, q_goal = _q(m, START), _q(m, goal)
    assert m.checker.CheckConfigCollisionFree(q_goal)
    path = plan_base_path(m.checker, q_start, q_goal, base, time.monotonic() + 60.0)
    assert path is not None
    _assert_valid_path(m.checker, path, q_start, q_goal, base)
    yaws = _yaws(path, base)
    assert yaws[-1] == 4.0
    steps = np.abs(np.diff(yaws))
    assert np.all(steps < math.pi), yaws  # no edge turns half a turn or more
    # Turning back and forth is paid for: at most two headings (2 x 45 deg) more than needed.
    assert np.sum(steps) <= 4.0 + 2 * (2 * math.pi / 8) + 1e-9, yaws


def test_goal_tight_in_a_corner_off_the_lattice(door_model):
    """A goal 2 mm (plus the checker's padding) from both walls of room B's south-east corner,
    turned 160 degrees (between the lattice's 45 degree headings): reached exactly, the last
    lattice state left by a checked edge (a base pose chosen next to furniture is like it)."""
    m = door_model
    base = m.indices(BASE_JOINTS)
    yaw = math.radians(160.0)

    def free(x, y):
        return m.checker.CheckConfigCollisionFree(_q(m, (x, y, yaw)))

    def boundary(f, free_end, blocked_end):  # bisection between a free and a blocked value
        for _ in range(25):
            mid = (free_end + blocked_end) / 2
            free_end, blocked_end = (mid, blocked_end) if f(mid) else (free_end, mid)
        return free_end

    y = boundary(lambda v: free(4.4, v), 1.2, 0.2) + 0.002
    x = boundary(lambda v: free(v, y), 4.4, ROOM_X) - 0.002
    q_start, q_goal = _q(m, START), _q(m, (x, y, yaw))
    assert m.checker.CheckConfigCollisionFree(q_goal)
    assert not free(x + 0.01, y) and not free(x, y - 0.01)  # tight on both walls
    path = plan_base_path(m.checker, q_start, q_goal, base, time.monotonic() + 60.0)
    assert path is not None
    _assert_valid_path(m.checker, path, q_start, q_goal, base)


# ---------------------------------------------------------------- a disc robot (fake checker)
class DiscChecker:
    """A disc of `radius` at (q[0], q[1]) among axis-aligned rectangles (x0, y0, x1, y1);
    q[3] (an arm joint) changes nothing, nor does q[2] (yaw) except inside `yaw_band` =
    (x_half, y_half, centre, half_width): where |x| < x_half and |y| < y_half the yaw must be
    within half_width of centre modulo 2 pi. Edges sampled every 1 cm and every 0.02 rad.
    Counts calls and sleeps `delay` s per configuration (a slow scene)."""

    def __init__(self, rects, radius=0.3, delay=0.0, yaw_band=None):
        self.rects, self.radius, self.delay, self.yaw_band = rects, radius, delay, yaw_band
        self.calls = 0

    def CheckConfigCollisionFree(self, q):
        self.calls += 1
        if self.delay:
            time.sleep(self.delay)
        if self.yaw_band is not None:
            x_half, y_half, centre, half_width = self.yaw_band
            off = (q[2] - centre + math.pi) % (2 * math.pi) - math.pi
            if abs(q[0]) < x_half and abs(q[1]) < y_half and abs(off) > half_width:
                return False
        for x0, y0, x1, y1 in self.rects:
            dx = max(x0 - q[0], 0.0, q[0] - x1)
            dy = max(y0 - q[1], 0.0, q[1] - y1)
            if math.hypot(dx, dy) < self.radius:
                return False
        return True

    def CheckEdgeCollisionFree(self, qa, qb):
        n = max(1, int(np.ceil(max(np.linalg.norm(qb[:2] - qa[:2]) / 0.01,
                                   abs(qb[2] - qa[2]) / 0.02))))
        return all(self.CheckConfigCollisionFree(qa + t * (qb - qa))
                   for t in np.linspace(0.0, 1.0, n + 1))


BASE = np.array([0, 1, 2])
#: A 4 m wall across x = 0 from y = -2 to 2 (open around its ends).
WALL = [(-0.05, -2.0, 0.05, 2.0)]
#: A closed 1 x 1 m box (inner) around (5, 0).
BOX = [(4.4, -0.6, 5.6, -0.5), (4.4, 0.5, 5.6, 0.6), (4.4, -0.6, 4.5, 0.6), (5.5, -0.6, 5.6, 0.6)]


def test_yaw_wraps_continuously_and_turns_monotonically_when_turning_is_free():
    """Start yaw 3.0, goal yaw -3.5: 0.22 rad apart as angles but 6.5 rad as joint values.
    The base must turn -6.5 rad continuously, through -pi (no 2 pi jump there or at the end),
    monotonically and no more than 6.5 rad in all (the yaw is free here), around the wall."""
    checker = DiscChecker(WALL)
    q_start = np.array([-1.0, 0.3, 3.0, 0.7])
    q_goal = np.array([1.0, -0.4, -3.5, 0.7])
    assert not checker.CheckEdgeCollisionFree(q_start, q_goal)
    path = plan_base_path(checker, q_start, q_goal, BASE, None)
    assert path is not None
    _assert_valid_path(checker, path, q_start, q_goal, BASE, step=0.01)
    yaws = _yaws(path, BASE)
    assert yaws[0] == 3.0 and yaws[-1] == -3.5
    assert np.all(np.diff(yaws) <= 1e-12), yaws
    assert np.sum(np.abs(np.diff(yaws))) == pytest.approx(6.5)
    # Around the wall's end (y = -2 - radius) and back: longer than both legs to that corner.
    corner = (0.0, -2.3)
    assert path_length(path, BASE) >= (math.dist(q_start[:2], corner) +
                                       math.dist(corner, q_goal[:2]) - 1e-6)
    # The short way round, when the caller asks for it.
    assert nearest_equivalent_yaw(-3.0, 3.0) == pytest.approx(-3.0 + 2 * math.pi)
    assert nearest_equivalent_yaw(0.5, -0.2) == 0.5


def test_yaw_beyond_pi_where_the_path_needs_it():
    """A door in a long wall that the base passes only turned 3.6 +- 0.35 rad (modulo 2 pi):
    from yaw 2.0 to yaw 5.0 the lattice heading 2.0 + 2 x 45 deg = 3.57 (beyond pi) threads
    it. Joint values stay continuous there (a planner that wrapped headings to (-pi, pi]
    would jump to -2.71 in the door), increase monotonically and end at exactly 5.0."""
    wall = [(-0.05, -10.0, 0.05, -0.5), (-0.05, 0.5, 0.05, 10.0)]
    checker = DiscChecker(wall, yaw_band=(0.4, 1.0, 3.6, 0.35))
    q_start = np.array([-1.5, 0.0, 2.0, 0.0])
    q_goal = np.array([1.5, 0.0, 5.0, 0.0])
    assert not checker.CheckEdgeCollisionFree(q_start, q_goal)
    path = plan_base_path(checker, q_start, q_goal, BASE, None)
    assert path is not None
    _assert_valid_path(checker, path, q_start, q_goal, BASE, step=0.01)
    yaws = _yaws(path, BASE)
    assert yaws[-1] == 5.0
    assert np.all(np.diff(yaws) >= -1e-12), yaws
    assert np.sum(np.abs(np.diff(yaws))) == pytest.approx(3.0)
    assert np.any((yaws > math.pi) & (yaws < 4.0)), yaws  # a waypoint in the door's band


def test_unreachable_goal_and_bounds_give_none():
    q_start = np.array([0.0, 0.0, 0.0, 0.0])
    # The goal inside a closed box on an open plane: only max_expansions ends the search.
    checker = DiscChecker(BOX)
    stats = {}
    assert plan_base_path(checker, q_start, np.array([5.0, 0.0, 0.0, 0.0]), BASE, None,
                          max_expansions=3000, stats=stats) is None
    assert stats["outcome"] == "max_expansions" and stats["expansions"] == 3000
    # xy_bounds that cut the start off from the goal: the bounded lattice is exhausted.
    stats = {}
    assert plan_base_path(DiscChecker(WALL), np.array([-1.0, 0.0, 0.0, 0.0]),
                          np.array([1.0, 0.0, 0.0, 0.0]), BASE, None, yaw_bins=1,
                          xy_bounds=((-3.0, -1.0), (3.0, 1.0)), stats=stats) is None
    assert stats["outcome"] == "exhausted"
    # A goal in collision: None without a search.
    stats = {}
    assert plan_base_path(checker, q_start, np.array([4.45, 0.0, 0.0, 0.0]), BASE, None,
                          stats=stats) is None
    assert stats["outcome"] == "goal_in_collision" and stats["expansions"] == 0
    # Start and goal must agree outside the base joints.
    with pytest.raises(ValueError):
        plan_base_path(checker, q_start, np.array([1.0, 0.0, 0.0, 0.5]), BASE, None)


def test_deadline_raises_planning_timeout(door_model):
    m = door_model
    with pytest.raises(PlanningTimeout):
        plan_base_path(m.checker, _q(m, START), _q(m, GOAL), m.indices(BASE_JOINTS),
                       time.monotonic() - 1.0)
    # A deadline that passes during the search (1 ms per configuration, the goal unreachable):
    # raised promptly, not after the search budget.
    checker = DiscChecker(BOX, delay=0.001)
    t0 = time.monotonic()
    with pytest.raises(PlanningTimeout):
        plan_base_path(checker, np.array([3.5, 0.0, 0.0, 0.0]), np.array([5.0, 0.0, 0.0, 0.0]),
                       BASE, time.monotonic() + 0.3)
    assert time.monotonic() - t0 < 1.5
