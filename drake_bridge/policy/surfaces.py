"""Point clouds sampled on collision surfaces: the "segmented point cloud" of a candidate object
(its own collision pieces, labelled by construction) and of the scene around it.

Every collision geometry becomes convex polygons with outward normals: a `Convex` or `Mesh`
through Drake's own convex hull (`GetConvexHull()`, the hull Drake collides with for a
`drake:declare_convex` OBJ), a `Box` exactly, a `Cylinder` as a 24-sided prism, a `Sphere` as a
latitude-longitude polyhedron, a `Capsule` as the prism of its bounding cylinder. Other shapes
(half spaces, ellipsoids) are skipped: a generated scene has none. Points are spread uniformly
by area at a given spacing (one point per spacing^2 of area, at least one per polygon).

Multi-piece bodies: a point on one piece that lies more than 1 mm inside another piece of the
same body is on an internal face (two hulls of a decomposition touching) and is dropped; what
is left is the body's outer surface.
"""

import dataclasses as dc

import numpy as np
from pydrake.geometry import Box, Capsule, Convex, Cylinder, Mesh, Role, Sphere

INTERNAL_TOL_M = 0.001


@dc.dataclass
class Cloud:
    """Points `p` (N x 3, m) with outward unit normals `n` (N x 3), both in the world frame;
    `piece[i]` indexes the convex piece (collision geometry) point i lies on."""

    p: np.ndarray
    n: np.ndarray
    piece: np.ndarray

    def __len__(self):
        return len(self.p)

    def subset(self, mask):
        return Cloud(self.p[mask], self.n[mask], self.piece[mask])


def _box_polygons(half):
    out = []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = np.zeros(3)
            n[axis] = sign
            u, v = [a for a in range(3) if a != axis]
            corners = []
            for cu, cv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                c = np.zeros(3)
                c[axis] = sign * half[axis]
                c[u], c[v] = cu * half[u], cv * half[v]
                corners.append(c)
            out.append((np.array(corners), n))
    return out


def _prism_polygons(radius, half_length, sides=24):
    angles = np.linspace(0.0, 2 * np.pi, sides, endpoint=False)
    ring = np.stack([radius * np.cos(angles), radius * np.sin(angles)], axis=1)
    out = []
    for z, sign in ((half_length, 1.0), (-half_length, -1.0)):
        out.append((np.column_stack([ring, np.full(sides, z)]), np.array([0.0, 0.0, sign])))
    for i in range(sides):
        a, b = ring[i], ring[(i + 1) % sides]
        quad = np.array([[*a, -half_length], [*b, -half_length], [*b, half_length],
                         [*a, half_length]])
        mid = (a + b) / 2
        out.append((quad, np.array([*(mid / np.linalg.norm(mid)), 0.0])))
    return out


def _sphere_polygons(radius, n_lat=8, n_lon=16):
    out = []
    lats = np.linspace(-np.pi / 2, np.pi / 2, n_lat + 1)
    lons = np.linspace(0.0, 2 * np.pi, n_lon + 1)

    def point(lat, lon):
        return radius * np.array([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon),
                                  np.sin(lat)])

    for i in range(n_lat):
        for j in range(n_lon):
            quad = np.array([point(lats[i], lons[j]), point(lats[i], lons[j + 1]),
                             point(lats[i + 1], lons[j + 1]), point(lats[i + 1], lons[j])])
            centre = quad.mean(axis=0)
            out.append((quad, centre / np.linalg.norm(centre)))
    return out


def shape_polygons(shape):
    """Convex polygons (vertices k x 3, outward unit normal) of `shape` in its own frame, or []
    for a shape this module does not sample."""
    if isinstance(shape, Box):
        return _box_polygons(np.array([shape.width(), shape.depth(), shape.height()]) / 2)
    if isinstance(shape, Cylinder):
        return _prism_polygons(shape.radius(), shape.length() / 2)
    if isinstance(shape, Capsule):
        return _prism_polygons(shape.radius(), shape.length() / 2 + shape.radius())
    if isinstance(shape, Sphere):
        return _sphere_polygons(shape.radius())
    if isinstance(shape, (Convex, Mesh)):
        hull = shape.GetConvexHull()
        out = []
        for f in range(hull.num_elements()):
            element = hull.element(f)
            vertices = np.array([hull.vertex(element.vertex(i))
                                 for i in range(element.num_vertices())])
            out.append((vertices, np.asarray(hull.face_normal(f))))
        return out
    return []


def clip_polygon(vertices, lower, upper):
    """The part of a convex polygon inside the box [lower, upper] (Sutherland-Hodgman)."""
    poly = list(vertices)
    for axis in range(3):
        for bound, keep_below in ((upper[axis], True), (lower[axis], False)):
            if not poly:
                return np.zeros((0, 3))
            out = []
            for i, a in enumerate(poly):
                b = poly[(i + 1) % len(poly)]
                a_in = a[axis] <= bound if keep_below else a[axis] >= bound
                b_in = b[axis] <= bound if keep_below else b[axis] >= bound
                if a_in:
                    out.append(a)
                if a_in != b_in:
                    t = (bound - a[axis]) / (b[axis] - a[axis])
                    out.append(a + t * (b - a))
            poly = out
    return np.array(poly) if poly else np.zeros((0, 3))


def sample_polygon(vertices, spacing, rng):
    """Points spread uniformly over a convex polygon, about one per spacing^2 of area."""
    if len(vertices) < 3:
        return np.zeros((0, 3))
    a = vertices[0]
    tris = [(a, vertices[i], vertices[i + 1]) for i in range(1, len(vertices) - 1)]
    areas = np.array([0.5 * np.linalg.norm(np.cross(b - a, c - a)) for a, b, c in tris])
    total = areas.sum()
    if total <= 1e-12:
        return np.zeros((0, 3))
    count = max(1, int(round(total / spacing**2)))
    which = rng.choice(len(tris), size=count, p=areas / total)
    r1, r2 = rng.random(count), rng.random(count)
    flip = r1 + r2 > 1.0
    r1[flip], r2[flip] = 1.0 - r1[flip], 1.0 - r2[flip]
    tri = np.array(tris)[which]
    return tri[:, 0] + r1[:, None] * (tri[:, 1] - tri[:, 0]) + r2[:, None] * (tri[:, 2] - tri[:, 0])


class GeometrySurfaces:
    """The polygons of a set of collision geometries posed in the world (from a QueryObject)."""

    def __init__(self, query, geometry_ids):
        inspector = query.inspector()
        self.ids = list(geometry_ids)
        self.polygons = []  # per geometry: list of (vertices_W, normal_W)
        for gid in self.ids:
            X_WG = query.GetPoseInWorld(gid)
            R, p = X_WG.rotation().matrix(), X_WG.translation()
            self.polygons.append([(v @ R.T + p, R @ n)
                                  for v, n in shape_polygons(inspector.GetShape(gid))])

    def bounds(self, k):
        """World AABB (lower, upper) of geometry k."""
        if not self.polygons[k]:
            return None
        v = np.concatenate([poly for poly, _ in self.polygons[k]])
        return v.min(axis=0), v.max(axis=0)

    def planes(self, k):
        """Face planes (normals N x 3, offsets N) of geometry k: inside where n.x <= d."""
        normals = np.array([n for _, n in self.polygons[k]])
        offsets = np.array([n @ v[0] for v, n in self.polygons[k]])
        return normals, offsets

    def sample(self, spacing, rng, region=None, drop_internal=False):
        """A Cloud over these geometries; only the parts inside `region` ((lower, upper) world
        AABB) when given; internal faces dropped when asked (for one body's pieces)."""
        ps, ns, pieces = [], [], []
        for k, polys in enumerate(self.polygons):
            if region is not None:
                b = self.bounds(k)
                if b is None or np.any(b[0] > region[1]) or np.any(b[1] < region[0]):
                    continue
            for vertices, normal in polys:
                if region is not None:
                    vertices = clip_polygon(vertices, region[0], region[1])
                pts = sample_polygon(vertices, spacing, rng)
                if len(pts):
                    ps.append(pts)
                    ns.append(np.tile(normal, (len(pts), 1)))
                    pieces.append(np.full(len(pts), k))
        if not ps:
            return Cloud(np.zeros((0, 3)), np.zeros((0, 3)), np.zeros(0, dtype=int))
        cloud = Cloud(np.concatenate(ps), np.concatenate(ns), np.concatenate(pieces))
        if drop_internal and len(self.polygons) > 1:
            keep = np.ones(len(cloud), dtype=bool)
            for k in range(len(self.polygons)):
                if not self.polygons[k]:
                    continue
                normals, offsets = self.planes(k)
                inside = np.all(cloud.p @ normals.T - offsets < -INTERNAL_TOL_M, axis=1)
                keep &= ~(inside & (cloud.piece != k))
            cloud = cloud.subset(keep)
        return cloud


def body_collision_ids(plant, body):
    return list(plant.GetCollisionGeometriesForBody(body))


def environment_ids(plant, query, exclude_instances):
    """Every collision geometry whose body's model instance is not in `exclude_instances`."""
    inspector = query.inspector()
    out = []
    for gid in inspector.GetAllGeometryIds(Role.kProximity):
        body = plant.GetBodyFromFrameId(inspector.GetFrameId(gid))
        if body is None or body.model_instance() not in exclude_instances:
            out.append(gid)
    return out
