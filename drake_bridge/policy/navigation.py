"""Base navigation: a collision-free path for the planar base joints (x, y, yaw) between two
base poses that may lie in different rooms of a house, found by lazy A* on a navigability
lattice, then shortened to a few straight edges.

Collision checks are the `SceneGraphCollisionChecker`'s, as in rrt.py: a configuration with
`CheckConfigCollisionFree`, an edge with `CheckEdgeCollisionFree` (straight in joint space,
checked every `edge_step_size` of the checker's distance). The joints outside the base keep
their start values along the whole path (start and goal must agree on them): the arm tucked,
the held object where it hangs.

The lattice: (x, y) on a grid of `resolution` metres anchored at the start's (x, y), the yaw in
`yaw_bins` headings anchored at the start's yaw (the base is holonomic, it need not face where
it goes). Moves: the 8 grid neighbours at the same heading, and one heading either way in
place. Cost: the xy length plus YAW_COST_M_PER_RAD per radian turned. Heuristic: the xy
distance to the goal plus the yaw cost of the yaw still to turn; admissible and consistent,
since every path must turn the base joint by exactly goal yaw - current yaw in the end.
Headings are unwrapped joint values (an integer heading index k, yaw = start yaw + k * 2pi /
yaw_bins), so the yaw joint moves continuously and ends exactly at the goal's value, however
far (in multiples of 2pi) that is from the start's; k stays within half a turn beyond the span
between the start and goal headings. Collision answers depend on k modulo yaw_bins only and are
shared between turns.

Lazy A* (no map is precomputed; a house is mostly never looked at): a state's configuration
is checked (memoised) and the edge from its parent checked only when it is popped from the
open list, once per expansion, never for the many states that are generated but never
expanded. When the edge fails, the state is offered again from every expanded neighbour whose
edge to it is not known to fail, so no path is lost to a parent pruned earlier. Every state
within GOAL_RADIUS_CELLS cells of the goal's xy offers the goal itself as a successor (the
remaining translation and the whole remaining yaw change), checked when that goal entry is
popped: one straight edge, else a turn in place to the goal's yaw followed by a straight move
at it (the way out of a goal pose tight against furniture). The path ends at the exact goal
configuration.

Shortening: from each kept vertex, the farthest later vertex that a collision-free straight
edge reaches (galloping search: 2, 4, 8, ... vertices ahead, then bisection), then one pass
dropping every interior vertex whose neighbours see each other. The output is a handful of
waypoints whose every edge has passed `CheckEdgeCollisionFree`.

Why not RRT-Connect over x, y, yaw (what episode.py did): paths through doorways in a house
are long and narrow; uniform sampling in the box around both ends rarely threads a 1 m door
between rooms several metres away, while the lattice search is complete at its resolution and
its cost grows with the area it has to look at, not with the narrowness of the passage.
"""

import heapq
import math
import time

import numpy as np

from drake_bridge.policy.rrt import PlanningTimeout

#: Cost of turning the base, metres of travel per radian.
YAW_COST_M_PER_RAD = 0.3
#: States within this many cells (xy) of the goal try to connect to it.
GOAL_RADIUS_CELLS = 1.5
#: Lattice moves (di, dj, dk): 8 grid neighbours at the same heading, then turns in place.
_MOVES = tuple((di, dj, 0) for di in (-1, 0, 1) for dj in (-1, 0, 1) if (di, dj) != (0, 0)) + (
    (0, 0, 1), (0, 0, -1))
_GOAL = "goal"


def _check_deadline(deadline):
    if deadline is not None and time.monotonic() > deadline:
        raise PlanningTimeout()


def nearest_equivalent_yaw(yaw, reference):
    """yaw + 2 pi n (n an integer) closest to `reference`: the goal yaw to ask for when the
    base should turn the short way (the yaw joint is continuous; joint values that differ by
    2 pi are the same pose but a different motion)."""
    return yaw + 2 * math.pi * round((reference - yaw) / (2 * math.pi))


def path_length(path, base_indices):
    """The xy length (m) of a path of full configurations (straight edges)."""
    ix, iy = int(base_indices[0]), int(base_indices[1])
    return float(sum(math.hypot(b[ix] - a[ix], b[iy] - a[iy]) for a, b in zip(path[:-1], path[1:])))


def plan_base_path(checker, q_start, q_goal, base_indices, deadline=None, *, resolution=0.1,
                   yaw_bins=8, max_expansions=200_000, yaw_cost=YAW_COST_M_PER_RAD,
                   xy_bounds=None, stats=None):
    """A collision-free path for the base joints from q_start to q_goal (full-plant q vectors
    that agree on every joint outside base_indices = [i_x, i_y, i_yaw]): a list of q vectors
    starting with q_start and ending with q_goal (exact copies) whose consecutive straight
    edges pass checker.CheckEdgeCollisionFree, or None when no path exists within the search
    limits (start or goal in collision, the reachable lattice exhausted, or `max_expansions`
    states expanded without reaching the goal). The yaw joint moves continuously from
    q_start's value to q_goal's (see nearest_equivalent_yaw to make it turn the short way).

    resolution: lattice step in x and y (m); yaw_bins: headings per turn; yaw_cost: metres of
    travel one radian of turning costs; xy_bounds: ((x_min, y_min), (x_max, y_max)) outside
    which the base centre may not go (lattice states; the start and goal themselves are not
    held to it), or None. `stats`, when a dict, receives the search's
    counters: expansions, config_checks, edge_checks (checker calls) and outcome ("straight",
    "found", "start_in_collision", "goal_in_collision", "exhausted", "max_expansions").

    Raises rrt.PlanningTimeout when time.monotonic() passes `deadline` (None = no deadline;
    looked at before every expansion and every edge check, shortening included); ValueError
    when q_start and q_goal differ outside the base joints."""
    q_start = np.array(q_start, dtype=float)
    q_goal = np.array(q_goal, dtype=float)
    ix, iy, iyaw = (int(i) for i in base_indices)
    others = np.ones(len(q_start), dtype=bool)
    others[[ix, iy, iyaw]] = False
    if q_goal.shape != q_start.shape or not np.array_equal(q_start[others], q_goal[others]):
        raise ValueError("q_start and q_goal differ outside the base joints")
    if resolution <= 0 or yaw_bins < 1:
        raise ValueError(f"bad lattice: resolution {resolution}, yaw_bins {yaw_bins}")
    if stats is None:
        stats = {}
    stats.update(expansions=0, config_checks=0, edge_checks=0, outcome=None)

    def finish(outcome, path):
        stats["outcome"] = outcome
        return path

    def edge_free(qa, qb):
        _check_deadline(deadline)
        stats["edge_checks"] += 1
        return bool(checker.CheckEdgeCollisionFree(qa, qb))

    _check_deadline(deadline)
    for q, outcome in ((q_start, "start_in_collision"), (q_goal, "goal_in_collision")):
        stats["config_checks"] += 1
        if not checker.CheckConfigCollisionFree(q):
            return finish(outcome, None)
    if edge_free(q_start, q_goal):
        return finish("straight", [q_start.copy(), q_goal.copy()])

    res = float(resolution)
    x0, y0, yaw0 = q_start[ix], q_start[iy], q_start[iyaw]
    xg, yg, yawg = q_goal[ix], q_goal[iy], q_goal[iyaw]
    dyaw = 2 * math.pi / yaw_bins
    k_goal = (yawg - yaw0) / dyaw
    k_lo = math.floor(min(0.0, k_goal)) - yaw_bins // 2
    k_hi = math.ceil(max(0.0, k_goal)) + yaw_bins // 2
    moves = _MOVES if yaw_bins > 1 else _MOVES[:8]
    move_cost = {m: res * math.hypot(m[0], m[1]) + yaw_cost * dyaw * abs(m[2]) for m in moves}
    goal_radius = GOAL_RADIUS_CELLS * res + 1e-9
    if xy_bounds is not None:
        (bx0, by0), (bx1, by1) = xy_bounds

    def q_of(s):
        i, j, k = s
        q = q_start.copy()
        q[ix] = x0 + i * res
        q[iy] = y0 + j * res
        q[iyaw] = yaw0 + k * dyaw
        return q

    def xy_to_goal(s):
        return math.hypot(x0 + s[0] * res - xg, y0 + s[1] * res - yg)

    def h(s):
        return xy_to_goal(s) + yaw_cost * abs(yawg - (yaw0 + s[2] * dyaw))

    config_memo = {}  # (i, j, k mod bins) -> free

    def state_free(s):
        key = (s[0], s[1], s[2] % yaw_bins)
        free = config_memo.get(key)
        if free is None:
            if xy_bounds is not None and not (bx0 <= x0 + s[0] * res <= bx1 and
                                              by0 <= y0 + s[1] * res <= by1):
                free = False
            else:
                stats["config_checks"] += 1
                free = bool(checker.CheckConfigCollisionFree(q_of(s)))
            config_memo[key] = free
        return free

    edge_memo = {}  # (i, j, k mod bins, move) -> free, stored both ways

    def lattice_edge_free(p, m):
        key = (p[0], p[1], p[2] % yaw_bins, m)
        free = edge_memo.get(key)
        if free is None:
            n = (p[0] + m[0], p[1] + m[1], p[2] + m[2])
            free = edge_free(q_of(p), q_of(n))
            edge_memo[key] = free
            edge_memo[(n[0], n[1], n[2] % yaw_bins, (-m[0], -m[1], -m[2]))] = free
        return free

    def edge_known_blocked(p, m):
        return edge_memo.get((p[0], p[1], p[2] % yaw_bins, m)) is False

    def connect(p):
        """[..., q_goal] from lattice state p: one straight edge, else turned in place to the
        goal's yaw first and then moved straight (a goal tight against furniture is often
        left only by backing away at its own yaw)."""
        q_p = q_of(p)
        if edge_free(q_p, q_goal):
            return [q_goal.copy()]
        q_turned = q_p.copy()
        q_turned[iyaw] = yawg
        if (q_turned[iyaw] != q_p[iyaw] and edge_free(q_p, q_turned) and
                edge_free(q_turned, q_goal)):
            return [q_turned, q_goal.copy()]
        return None

    start = (0, 0, 0)
    closed = {}  # state -> (g, parent)
    g_best = {start: 0.0}
    heap = []
    tie = 0

    def push(f, g, s, parent):
        nonlocal tie
        tie += 1
        # Equal f: the deeper entry first (fewer expansions on plateaus).
        heapq.heappush(heap, (f, -g, tie, s, parent))

    def reoffer(s):
        """s's edge from its best parent failed: offer s from every expanded neighbour."""
        best = math.inf
        for m in moves:
            p = (s[0] - m[0], s[1] - m[1], s[2] - m[2])
            if p in closed and not edge_known_blocked(p, m):
                g = closed[p][0] + move_cost[m]
                push(g + h(s), g, s, p)
                best = min(best, g)
        g_best[s] = best

    push(h(start), 0.0, start, None)
    while heap:
        _check_deadline(deadline)
        _, neg_g, _, s, parent = heapq.heappop(heap)
        g = -neg_g
        if s == _GOAL:
            tail = connect(parent)
            if tail is not None:
                path = tail[::-1]
                while parent is not None:
                    path.append(q_of(parent))
                    parent = closed[parent][1]
                path.reverse()
                path[0] = q_start.copy()
                return finish("found", _shorten(path, edge_free))
            continue
        if s in closed:
            continue
        if parent is not None:
            if not state_free(s):
                continue
            if not lattice_edge_free(parent, (s[0] - parent[0], s[1] - parent[1],
                                              s[2] - parent[2])):
                reoffer(s)
                continue
        if stats["expansions"] >= max_expansions:
            return finish("max_expansions", None)
        closed[s] = (g, parent)
        stats["expansions"] += 1
        d = xy_to_goal(s)
        if d <= goal_radius:
            push(g + d + yaw_cost * abs(yawg - (yaw0 + s[2] * dyaw)), g + d, _GOAL, s)
        for m in moves:
            n = (s[0] + m[0], s[1] + m[1], s[2] + m[2])
            if not k_lo <= n[2] <= k_hi or n in closed:
                continue
            if config_memo.get((n[0], n[1], n[2] % yaw_bins)) is False:
                continue
            g_n = g + move_cost[m]
            if g_n >= g_best.get(n, math.inf) - 1e-12:
                continue
            g_best[n] = g_n
            push(g_n + h(n), g_n, n, s)
    return finish("exhausted", None)


def _shorten(path, edge_free):
    """Drops the vertices that straight collision-free edges can skip (see module doc); every
    edge of the result has passed edge_free."""
    n = len(path)
    out, i = [path[0]], 0
    while i < n - 1:
        lo, hi, step = i + 1, None, 2  # path[i] -> path[lo] is free (a lattice edge)
        while True:
            j = min(i + step, n - 1)
            if j <= lo:
                break
            if edge_free(path[i], path[j]):
                lo = j
                if j == n - 1:
                    break
                step *= 2
            else:
                hi = j
                break
        if hi is not None:
            while hi - lo > 1:
                mid = (lo + hi) // 2
                if edge_free(path[i], path[mid]):
                    lo = mid
                else:
                    hi = mid
        out.append(path[lo])
        i = lo
    k = 1
    while k < len(out) - 1:
        if edge_free(out[k - 1], out[k + 1]):
            del out[k]
        else:
            k += 1
    return out
