"""RRT-Connect with randomized shortcutting, on a subset of a planning model's joints.

Collision checks are the `SceneGraphCollisionChecker`'s: a configuration with
`CheckConfigCollisionFree`, an edge with `CheckEdgeCollisionFree` (straight in joint space,
checked every `edge_step_size` of the checker's distance, 0.02 rad). The joints outside `active`
keep their start values along the whole path (start and goal must agree on them).

RRT-Connect (Kuffner and LaValle 2000): two trees, from the start and from the goal; each round
one tree extends by at most STEP towards a uniform sample inside the joint limits and the other
tree greedily connects to the new node; the trees swap roles. Then shortcutting: for
`shortcut_iterations` rounds, two random points along the path (by arc length) are joined by a
straight edge when it is collision-free, and the part between them is dropped; finally every
vertex that a straight edge can skip is dropped.
"""

import time

import numpy as np

STEP = 0.35  # max extension per RRT step, in the active joints' Euclidean norm (rad / m)


class PlanningTimeout(Exception):
    """The wall-clock deadline passed while planning."""


def _steer(q_from, q_to, step):
    d = q_to - q_from
    n = np.linalg.norm(d)
    return q_to.copy() if n <= step else q_from + d * (step / n)


class _Tree:
    def __init__(self, q_root_active, capacity):
        self.q = np.zeros((capacity, len(q_root_active)))
        self.q[0] = q_root_active
        self.parent = np.full(capacity, -1, dtype=int)
        self.n = 1

    def nearest(self, q):
        return int(np.argmin(np.sum((self.q[: self.n] - q) ** 2, axis=1)))

    def add(self, q, parent):
        if self.n == len(self.q):
            self.q = np.vstack([self.q, np.zeros_like(self.q)])
            self.parent = np.concatenate([self.parent, np.full(len(self.parent), -1)])
        self.q[self.n] = q
        self.parent[self.n] = parent
        self.n += 1
        return self.n - 1

    def path_to_root(self, i):
        out = []
        while i >= 0:
            out.append(self.q[i].copy())
            i = self.parent[i]
        return out


def rrt_connect(checker, q_start, q_goal, active, lower, upper, rng, max_iterations,
                deadline=None):
    """A collision-free path [q_start, ..., q_goal] (full configurations) or None."""
    active = np.asarray(active)

    def full(qa):
        q = q_start.copy()
        q[active] = qa
        return q

    def edge_free(qa, qb):
        return checker.CheckEdgeCollisionFree(full(qa), full(qb))

    if not (checker.CheckConfigCollisionFree(q_start) and
            checker.CheckConfigCollisionFree(q_goal)):
        return None
    a0, b0 = q_start[active], q_goal[active]
    if edge_free(a0, b0):
        return [q_start.copy(), q_goal.copy()]
    lo, hi = lower[active], upper[active]
    tree_a, tree_b = _Tree(a0, 1024), _Tree(b0, 1024)
    a_is_start = True
    for _ in range(max_iterations):
        if deadline is not None and time.monotonic() > deadline:
            raise PlanningTimeout()
        sample = rng.uniform(lo, hi)
        i = tree_a.nearest(sample)
        q_new = _steer(tree_a.q[i], sample, STEP)
        if edge_free(tree_a.q[i], q_new):
            i_new = tree_a.add(q_new, i)
            # Connect: tree_b walks towards q_new until it reaches it or is blocked.
            j = tree_b.nearest(q_new)
            while True:
                q_next = _steer(tree_b.q[j], q_new, STEP)
                if not edge_free(tree_b.q[j], q_next):
                    break
                j = tree_b.add(q_next, j)
                if np.allclose(q_next, q_new):
                    half_a = tree_a.path_to_root(i_new)[::-1]
                    half_b = tree_b.path_to_root(j)[1:]
                    path = half_a + half_b
                    if not a_is_start:
                        path = path[::-1]
                    path[0], path[-1] = a0, b0
                    return [full(q) for q in path]
        tree_a, tree_b = tree_b, tree_a
        a_is_start = not a_is_start
    return None


def shortcut(checker, path, active, rng, iterations, deadline=None):
    """Randomized shortcutting of a path of full configurations (see module doc)."""
    active = np.asarray(active)
    path = [q.copy() for q in path]
    for _ in range(iterations):
        if len(path) < 3 or (deadline is not None and time.monotonic() > deadline):
            break
        seg = np.array([np.linalg.norm(path[k + 1][active] - path[k][active])
                        for k in range(len(path) - 1)])
        cum = np.concatenate([[0.0], np.cumsum(seg)])
        s1, s2 = np.sort(rng.uniform(0.0, cum[-1], 2))
        k1 = min(int(np.searchsorted(cum, s1, side="right")) - 1, len(seg) - 1)
        k2 = min(int(np.searchsorted(cum, s2, side="right")) - 1, len(seg) - 1)
        if k1 == k2:
            continue

        def point(s, k):
            t = 0.0 if seg[k] == 0 else (s - cum[k]) / seg[k]
            return path[k] + t * (path[k + 1] - path[k])

        q1, q2 = point(s1, k1), point(s2, k2)
        if checker.CheckEdgeCollisionFree(q1, q2):
            path = path[: k1 + 1] + [q1, q2] + path[k2 + 1:]
    # Drop vertices that sit (numerically) on their neighbours, then skip every vertex the
    # path can do without (from each kept vertex, straight to the farthest one in free space):
    # few, long segments make a smooth spline for timing.
    dense = [path[0]]
    for q in path[1:]:
        if np.linalg.norm(q - dense[-1]) > 1e-6:
            dense.append(q)
    out, i = [dense[0]], 0
    while i < len(dense) - 1:
        j = len(dense) - 1
        while j > i + 1 and not checker.CheckEdgeCollisionFree(dense[i], dense[j]):
            j -= 1
        out.append(dense[j])
        i = j
    return out


def path_is_collision_free(checker, path):
    """Every edge of the path checked by the checker (its own edge step)."""
    return all(checker.CheckEdgeCollisionFree(a, b) for a, b in zip(path[:-1], path[1:]))
