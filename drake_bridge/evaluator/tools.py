"""The evaluator's state tools: plain functions over a loaded `SceneState`, each returning a
JSON-serialisable dict (metres, world frame W unless a field names another frame).

- `list_objects(state, category=None)`: ids, categories, kinds.
- `get_object_info(state, id)`: category, pose, world AABB, mass, free or not, scene.json support.
- `get_distance(state, a, b)`: signed distance between the two objects' collision geometry
  (Drake, per pair of pieces), negative when they penetrate, with the closest points.
- `get_spatial_relation(state, a, b)`: where a is relative to b, rotation-aware (a's vertices in
  b's frame), footprint overlap, vertical gap.
- `get_support(state, id)`: what the object rests on, with contact normals and surface overlap.

Also the measurements the built-in evaluator shares with them (`signed_distance`, `contacts`,
`surface_under`).
"""

import math

import numpy as np

from drake_bridge.errors import BadRequest, ModelError
from drake_bridge.evaluator.geometry import footprint_fraction, interval_gaps
from drake_bridge.evaluator.state import matching_ids

#: get_support: largest signed distance, m, at which two objects count as in contact.
SUPPORT_CONTACT_M = 0.002
#: get_support: largest angle, deg, between +z and a contact normal (pointing from the
#: supporter to the object) for the contact to hold the object up rather than touch its side.
SUPPORT_MAX_NORMAL_TILT_DEG = 45.0
#: A support piece counts as "under" a subject when its top is at most this far above the
#: subject's lowest point, m (resting objects sink a little into compliant contact).
SURFACE_PENETRATION_M = 0.005
#: Pieces whose tops lie within this band below the highest piece under a subject form the
#: surface it rests on, m (a table top made of several slabs, a shelf board and its lip).
SURFACE_BAND_M = 0.02
#: get_spatial_relation: overlap along an axis smaller than this still counts as "beside"
#: (touching objects penetrate slightly), m.
RELATION_TOUCH_M = 0.005

#: Relation words of the signed axes of the reference frame (+x right, +y front, +z up: the
#: asset canonical frame, seen from the object itself).
_WORDS = {("x", 1): "right", ("x", -1): "left", ("y", 1): "front", ("y", -1): "behind",
          ("z", 1): "above", ("z", -1): "below"}


def _vec(v):
    return [float(c) for c in v]


# -- measurements ---------------------------------------------------------------------------

def _piece_aabbs(state, object_id):
    vertices = state.piece_vertices_W(object_id)
    if not vertices:
        return np.zeros((0, 3)), np.zeros((0, 3))
    return (np.array([v.min(axis=0) for v in vertices]),
            np.array([v.max(axis=0) for v in vertices]))


def _aabb_gaps(lo_a, hi_a, lo_b, hi_b):
    """Euclidean gaps between every box of set A and every box of set B (|A| x |B|); 0 where
    they overlap. A lower bound on the distance between what the boxes hold."""
    d = np.maximum(lo_a[:, None, :] - hi_b[None, :, :], lo_b[None, :, :] - hi_a[:, None, :])
    return np.linalg.norm(np.maximum(d, 0.0), axis=2)


def _oriented(state, pair, a_ids):
    """(distance, p_W on a, p_W on b, unit normal from b toward a) of a SignedDistancePair
    whose id_A or id_B belongs to a (`a_ids`, a set of geometry ids)."""
    X_WA = state.query.GetPoseInWorld(pair.id_A)
    X_WB = state.query.GetPoseInWorld(pair.id_B)
    p_WCa = X_WA.multiply(pair.p_ACa)
    p_WCb = X_WB.multiply(pair.p_BCb)
    normal = np.asarray(pair.nhat_BA_W)       # outward from B, toward A
    if pair.id_A in a_ids:
        return pair.distance, p_WCa, p_WCb, normal
    return pair.distance, p_WCb, p_WCa, -normal


def piece_pairs(state, a, b, max_distance=math.inf):
    """Signed distances between a's and b's pieces: a list of (distance, piece of a, piece of
    b, p_W on a, p_W on b, normal from b toward a), nearest first. With a finite
    `max_distance`, only the pairs within it (pieces whose boxes are farther are skipped);
    without, every pair that can be the nearest."""
    pieces_a, pieces_b = state.pieces(a), state.pieces(b)
    if not pieces_a or not pieces_b:
        return []
    gaps = _aabb_gaps(*_piece_aabbs(state, a), *_piece_aabbs(state, b))
    order = np.argsort(gaps, axis=None)
    a_ids = {p.geometry_id for p in pieces_a}
    out = []
    best = math.inf
    for flat in order:
        i, j = np.unravel_index(flat, gaps.shape)
        bound = max_distance if math.isfinite(max_distance) else best
        if gaps[i, j] > bound:
            break
        try:
            pair = state.query.ComputeSignedDistancePairClosestPoints(
                pieces_a[i].geometry_id, pieces_b[j].geometry_id)
        except RuntimeError as e:
            raise ModelError(f"{state.directives_path}: Drake computes no signed distance "
                             f"between {pieces_a[i].name} and {pieces_b[j].name}: {e}") from e
        d, p_a, p_b, n = _oriented(state, pair, a_ids)
        best = min(best, d)
        if d <= max_distance:
            out.append((float(d), pieces_a[i], pieces_b[j], p_a, p_b, n))
    out.sort(key=lambda r: r[0])
    return out


def signed_distance(state, a, b):
    """The nearest piece pair of a and b (see `piece_pairs`), or None without geometry."""
    pairs = piece_pairs(state, a, b)
    return pairs[0] if pairs else None


def contacts(state, object_id, max_distance):
    """Other objects within `max_distance` (signed, m) of `object_id`: {other id: piece pairs
    (as `piece_pairs`) within it}."""
    box = state.world_aabb(object_id)
    if box is None:
        return {}
    out = {}
    for other in state.ids:
        if other == object_id:
            continue
        other_box = state.world_aabb(other)
        if other_box is None:
            continue
        gap = _aabb_gaps(box[0][None], box[1][None], other_box[0][None], other_box[1][None])
        if gap[0, 0] > max_distance:
            continue
        pairs = piece_pairs(state, object_id, other, max_distance)
        if pairs:
            out[other] = pairs
    return out


def surface_under(state, subject, support):
    """The surface of `support` that `subject` rests on or hovers over, or None.

    The surface height is the highest top (max z of a piece's vertices) among support pieces
    that lie under the subject's footprint and whose top is at most SURFACE_PENETRATION_M
    above the subject's lowest point; the surface is every support piece whose top lies within
    SURFACE_BAND_M below that height. Returns {"surface_z_m", "bottom_z_m" (subject's lowest
    point), "gap_m" (bottom - surface), "footprint_fraction" (of the subject's footprint over
    the surface)}."""
    subject_vertices = state.vertices_W(subject)
    support_vertices = state.piece_vertices_W(support)
    if len(subject_vertices) == 0 or not support_vertices:
        return None
    subject_hulls = state.piece_hulls_xy(subject)
    support_hulls = state.piece_hulls_xy(support)
    bottom = float(subject_vertices[:, 2].min())
    lo_xy, hi_xy = subject_vertices[:, :2].min(axis=0), subject_vertices[:, :2].max(axis=0)
    tops = np.array([v[:, 2].max() for v in support_vertices])
    under = []
    for k, vertices in enumerate(support_vertices):
        if tops[k] > bottom + SURFACE_PENETRATION_M:
            continue
        apart = (vertices[:, :2].max(axis=0) < lo_xy) | (vertices[:, :2].min(axis=0) > hi_xy)
        if np.any(apart):
            continue
        if footprint_fraction(subject_hulls, [support_hulls[k]]) > 0.0:
            under.append(k)
    if not under:
        return None
    height = float(max(tops[k] for k in under))
    band = [support_hulls[k] for k in range(len(tops))
            if height - SURFACE_BAND_M <= tops[k] <= height + 1e-9]
    return {"surface_z_m": height, "bottom_z_m": bottom, "gap_m": bottom - height,
            "footprint_fraction": footprint_fraction(subject_hulls, band)}


def tilt_deg(state, object_id):
    """Angle between the object's z axis and the world's +z, deg."""
    z_W = state.X_WO(object_id).rotation().matrix()[:, 2]
    return math.degrees(math.acos(max(-1.0, min(1.0, float(z_W[2])))))


# -- tools ----------------------------------------------------------------------------------

def list_objects(state, category=None):
    """The scene's objects: {"objects": [{"id", "category", "kind"}]}, only those a noun
    `category` names when given (see state.category_matches; architecture excluded then)."""
    ids = state.ids if category is None else matching_ids(state, category)
    return {"objects": [{"id": i, "category": state.category(i), "kind": state.kind(i)}
                        for i in ids]}


def get_object_info(state, object_id):
    """One object: {"id", "category", "kind", "room", "asset", "world_from_object" {"xyz",
    "wxyz"} (its frame O, the base body), "world_aabb" {"min", "max"} (collision geometry, or
    None), "box_in_object_frame" {"min", "max"}, "mass_kg" (all bodies), "free" (O is a free
    body), "bodies", "support" (scene.json's record, or None)}."""
    record = state.record(object_id)
    X_WO = state.X_WO(object_id)
    q = X_WO.rotation().ToQuaternion()
    aabb = state.world_aabb(object_id)
    box = state.box_in_own_frame(object_id) if aabb is not None else None
    return {
        "id": object_id,
        "category": record.get("category"),
        "kind": record.get("kind"),
        "room": record.get("room"),
        "asset": record.get("asset"),
        "world_from_object": {"xyz": _vec(X_WO.translation()),
                              "wxyz": [float(q.w()), float(q.x()), float(q.y()), float(q.z())]},
        "world_aabb": None if aabb is None else {"min": _vec(aabb[0]), "max": _vec(aabb[1])},
        "box_in_object_frame": None if box is None else {"min": _vec(box[0]), "max": _vec(box[1])},
        "mass_kg": state.mass_kg(object_id),
        "free": state.is_free(object_id),
        "bodies": [b.name() for b in state.bodies(object_id)],
        "support": record.get("support"),
    }


def get_distance(state, a, b):
    """Signed distance between a's and b's collision geometry, m (negative: penetration depth):
    {"a", "b", "signed_distance_m", "closest_point_on_a_W", "closest_point_on_b_W",
    "normal_W" (unit, from b toward a: moving a along it increases the distance), "pieces"
    [a's piece, b's piece]}; distance None when either has no collision geometry."""
    state.instance(a)
    state.instance(b)
    nearest = signed_distance(state, a, b)
    if nearest is None:
        return {"a": a, "b": b, "signed_distance_m": None}
    d, piece_a, piece_b, p_a, p_b, normal = nearest
    return {"a": a, "b": b, "signed_distance_m": d,
            "closest_point_on_a_W": _vec(p_a), "closest_point_on_b_W": _vec(p_b),
            "normal_W": _vec(normal), "pieces": [piece_a.name, piece_b.name]}


def get_spatial_relation(state, a, b):
    """Where a is relative to b, in b's frame (rotation-aware: a's collision vertices expressed
    in b's object frame, against b's own oriented box; +x right, +y front, +z up as b sees it).

    Returns {"a", "b", "frame", "axes": {"x"|"y"|"z": {"gap_m" (> 0 clearance, < 0 overlap
    length), "side" (the word for a's side of b, or "overlapping" when their extents along the
    axis overlap by more than RELATION_TOUCH_M)}}, "relations" (the side words that are not
    "overlapping"), "footprint_overlap_fraction" (of
    a's world x-y footprint over b's), "vertical_gap_m" (a's lowest point minus b's top under
    a, or minus b's highest point when no part of b is under a), "b_surface_under_a"
    (`surface_under`, or None), "a_bottom_z_m", "b_top_z_m"}."""
    X_WB = state.X_WO(b)
    p_BVa = state.vertices_in(a, X_WB)
    if len(p_BVa) == 0:
        raise BadRequest(f"object {a!r} in {state.directives_path} has no collision geometry")
    b_lo, b_hi = state.box_in_own_frame(b)
    gaps, sides = interval_gaps(p_BVa.min(axis=0), p_BVa.max(axis=0), b_lo, b_hi)
    axes, relations = {}, []
    for k, axis in enumerate("xyz"):
        beside = gaps[k] >= -RELATION_TOUCH_M
        word = _WORDS[(axis, int(sides[k]))] if beside else "overlapping"
        axes[axis] = {"gap_m": float(gaps[k]), "side": word}
        if beside:
            relations.append(word)
    surface = surface_under(state, a, b)
    a_bottom = float(state.vertices_W(a)[:, 2].min())
    b_top = float(state.vertices_W(b)[:, 2].max())
    reference_z = surface["surface_z_m"] if surface is not None else b_top
    return {
        "a": a, "b": b, "frame": f"{b} (object frame: +x right, +y front, +z up)",
        "axes": axes, "relations": relations,
        "footprint_overlap_fraction": footprint_fraction(state.piece_hulls_xy(a),
                                                         state.piece_hulls_xy(b)),
        "vertical_gap_m": a_bottom - reference_z,
        "b_surface_under_a": surface,
        "a_bottom_z_m": a_bottom, "b_top_z_m": b_top,
    }


def get_support(state, object_id):
    """What the object rests on. Supporters: objects within SUPPORT_CONTACT_M (signed) whose
    contact normal (from the supporter to the object) is within SUPPORT_MAX_NORMAL_TILT_DEG of
    +z, most overlapped first. Where two faces touch exactly Drake reports no normal (NaN); such
    a contact holds the object up when the supporter's surface under the object is within
    SUPPORT_CONTACT_M of its lowest point, and its normal is then reported as +z with
    "normal_estimated": true.

    Returns {"id", "supported", "supporters": [{"id", "category", "signed_distance_m",
    "normal_W", "normal_estimated", "normal_tilt_deg", "contact_point_W",
    "surface_overlap_fraction" (of the object's footprint over the supporter's surface under
    it), "surface_z_m"}], "side_contacts": [{"id", "signed_distance_m", "normal_W"}] (touching,
    not holding up; normal None when Drake gave none), "scene_json_support" (the record the
    scene was generated with)}."""
    min_normal_z = math.cos(math.radians(SUPPORT_MAX_NORMAL_TILT_DEG))
    supporters, side = [], []
    for other, pairs in contacts(state, object_id, SUPPORT_CONTACT_M).items():
        surface = surface_under(state, object_id, other)
        touches_surface = surface is not None and surface["gap_m"] <= SUPPORT_CONTACT_M
        holding = []
        for d, _, _, p_on_object, _, normal in pairs:
            if np.all(np.isfinite(normal)):
                if normal[2] >= min_normal_z:
                    holding.append((d, p_on_object, normal, False))
            elif touches_surface:
                holding.append((d, p_on_object, np.array([0.0, 0.0, 1.0]), True))
        if not holding:
            d, normal = pairs[0][0], pairs[0][5]
            side.append({"id": other, "signed_distance_m": d,
                         "normal_W": _vec(normal) if np.all(np.isfinite(normal)) else None})
            continue
        _, p_on_object, normal, estimated = max(holding, key=lambda h: (not h[3], h[2][2]))
        supporters.append({
            "id": other, "category": state.category(other),
            "signed_distance_m": min(h[0] for h in holding),
            "normal_W": _vec(normal), "normal_estimated": estimated,
            "normal_tilt_deg": math.degrees(math.acos(min(1.0, float(normal[2])))),
            "contact_point_W": _vec(p_on_object),
            "surface_overlap_fraction": surface["footprint_fraction"] if surface else 0.0,
            "surface_z_m": surface["surface_z_m"] if surface else None,
        })
    supporters.sort(key=lambda s: -s["surface_overlap_fraction"])
    return {"id": object_id, "supported": bool(supporters), "supporters": supporters,
            "side_contacts": side,
            "scene_json_support": state.record(object_id).get("support")}
