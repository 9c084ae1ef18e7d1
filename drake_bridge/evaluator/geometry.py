"""Plain numpy geometry the evaluator's tools share: 2-D convex hulls and footprint overlap,
per-axis interval gaps, and the volume fraction of one oriented box inside another.

Nothing here knows Drake or a scene: points in, numbers out. Footprint areas are estimated on a
grid (`FOOTPRINT_GRID` cells per side over the subject's footprint) because the footprints are
unions of convex pieces; the box fraction is exact along one axis and sampled on the other two.
"""

import numpy as np

#: Cells per side of the grid a footprint fraction is sampled on (the fraction's resolution is
#: about 1 / FOOTPRINT_GRID of the subject's footprint width).
FOOTPRINT_GRID = 40
#: Lines per side of the grid a box-inside-box fraction is sampled on.
BOX_GRID = 32
#: Tolerance of the point-in-polygon test, m^2 (a cross product; absorbs round-off).
_IN_POLYGON_EPS = 1e-10


def convex_hull_2d(points):
    """The convex hull of 2-D points, counter-clockwise, collinear points dropped (Andrew's
    monotone chain). Fewer than three points, or collinear ones, give a degenerate hull of at
    most two points."""
    pts = np.unique(np.asarray(points, dtype=float).reshape(-1, 2), axis=0)
    if len(pts) < 3:
        return pts

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in pts[::-1]:
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def polygon_area(hull):
    """Area of a counter-clockwise polygon, m^2 (0 for a degenerate one)."""
    if len(hull) < 3:
        return 0.0
    x, y = hull[:, 0], hull[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def in_convex_polygon(hull, points):
    """Boolean mask: which of `points` (N x 2) lie in the counter-clockwise convex `hull`
    (boundary included). A degenerate hull contains nothing."""
    points = np.asarray(points, dtype=float).reshape(-1, 2)
    if len(hull) < 3:
        return np.zeros(len(points), dtype=bool)
    edges = np.roll(hull, -1, axis=0) - hull                       # m x 2
    rel = points[:, None, :] - hull[None, :, :]                    # N x m x 2
    cross = edges[None, :, 0] * rel[:, :, 1] - edges[None, :, 1] * rel[:, :, 0]
    return np.all(cross >= -_IN_POLYGON_EPS, axis=1)


def in_any(hulls, points):
    """Boolean mask: which of `points` lie in at least one of `hulls`."""
    mask = np.zeros(len(points), dtype=bool)
    for hull in hulls:
        mask |= in_convex_polygon(hull, points)
    return mask


def footprint_fraction(subject_hulls, support_hulls, grid=FOOTPRINT_GRID):
    """Fraction of the subject's footprint (the union of `subject_hulls`, 2-D convex polygons in
    one plane) that lies over the union of `support_hulls`, in [0, 1].

    Sampled at the centres of a grid x grid lattice over the subject's bounding rectangle. A
    subject with no area (a vertical sheet seen from above) is judged by its hull vertices
    instead."""
    subject_hulls = [h for h in subject_hulls if len(h) > 0]
    if not subject_hulls:
        return 0.0
    corners = np.vstack(subject_hulls)
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    u = (np.arange(grid) + 0.5) / grid
    xs = lo[0] + u * (hi[0] - lo[0])
    ys = lo[1] + u * (hi[1] - lo[1])
    lattice = np.stack(np.meshgrid(xs, ys, indexing="ij"), axis=-1).reshape(-1, 2)
    samples = lattice[in_any(subject_hulls, lattice)]
    if len(samples) == 0:
        samples = corners
    return float(np.mean(in_any(support_hulls, samples)))


def interval_gaps(a_lo, a_hi, b_lo, b_hi):
    """Per-axis signed gaps between boxes A = [a_lo, a_hi] and B = [b_lo, b_hi] (same frame):
    for each axis, (gap, side) where gap > 0 is the clearance between the intervals and gap < 0
    the length of their overlap; side is +1 when A lies toward +axis of B (judged by the larger
    of the two one-sided gaps), -1 otherwise."""
    a_lo, a_hi, b_lo, b_hi = (np.asarray(v, dtype=float) for v in (a_lo, a_hi, b_lo, b_hi))
    plus = a_lo - b_hi     # A beyond B's +face
    minus = b_lo - a_hi    # A beyond B's -face
    gaps = np.maximum(plus, minus)
    sides = np.where(plus >= minus, 1, -1)
    return gaps, sides


def box_inside_fraction(R_RT, p_RT, t_lo, t_hi, r_lo, r_hi, grid=BOX_GRID):
    """Fraction of the volume of box T = [t_lo, t_hi] (in frame T) that lies inside box
    R = [r_lo, r_hi] (in frame R), where frame T's pose in R is (R_RT, p_RT).

    Exact along T's z axis (each sample line is clipped against R's slabs, Liang-Barsky),
    sampled on a grid x grid lattice over T's x-y face."""
    t_lo, t_hi, r_lo, r_hi = (np.asarray(v, dtype=float) for v in (t_lo, t_hi, r_lo, r_hi))
    u = (np.arange(grid) + 0.5) / grid
    xs = t_lo[0] + u * (t_hi[0] - t_lo[0])
    ys = t_lo[1] + u * (t_hi[1] - t_lo[1])
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    starts_T = np.stack([gx.ravel(), gy.ravel(), np.full(gx.size, t_lo[2])], axis=1)
    starts_R = starts_T @ np.asarray(R_RT).T + np.asarray(p_RT)
    direction_R = np.asarray(R_RT) @ np.array([0.0, 0.0, t_hi[2] - t_lo[2]])
    s0 = np.zeros(len(starts_R))
    s1 = np.ones(len(starts_R))
    for k in range(3):
        o, d = starts_R[:, k], direction_R[k]
        if abs(d) < 1e-12:
            inside = (o >= r_lo[k]) & (o <= r_hi[k])
            s1 = np.where(inside, s1, 0.0)
            continue
        a, b = (r_lo[k] - o) / d, (r_hi[k] - o) / d
        s0 = np.maximum(s0, np.minimum(a, b))
        s1 = np.minimum(s1, np.maximum(a, b))
    return float(np.mean(np.clip(s1 - s0, 0.0, 1.0)))
