"""The evaluator's vision tools: pictures of a scene state for an LLM to look at.

    observe_scene(state)              -> info, [("scene_top", rgba), ("scene_oblique", rgba)]
    observe_objects(state, ["mug_0"]) -> info, [("objects_oblique", rgba), ("objects_top", rgba)]

The renderer is Drake's `RenderEngineVtk` (headless), added to fresh contexts of the state's own
diagram, so the pictures show exactly the poses the state tools measure. Two contexts, two
views of the room:

- *top* (plan) views look straight down, +y up in the image, +x right; the walls are drawn
  (they outline the room) and ceiling objects are hidden (they would hide what is under them);
- *oblique* views look down at OBLIQUE_ELEVATION_DEG; the walls are hidden (they would hide the
  room from any camera outside it).

`observe_objects` frames the asked objects' collision boxes grown by FRAME_MARGIN, cuts away
whatever lies between the camera and that box (the camera's near clipping plane sits at the
box), washes out the colours of every other object, and outlines each asked object in its
own colour (from a label image rendered with the same camera). Its oblique camera is the one of
SEARCH_VIEWS that shows the asked objects best. The info says which colour is which object
and how many pixels of each object each view shows (0: hidden behind something in the box).

An object with no visual geometry (hand-written test scenes) is drawn from its collision
geometry in a flat colour. Rendering is cached per state (`renderer`).
"""

import math
import weakref

import numpy as np
from pydrake.geometry import (
    ClippingRange,
    ColorRenderCamera,
    MakeRenderEngineVtk,
    PerceptionProperties,
    RenderCameraCore,
    RenderEngineVtkParams,
    RenderLabel,
    Rgba,
    Role,
)
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.systems.sensors import CameraInfo

from drake_bridge.errors import BadRequest

#: Image width, height, px.
IMAGE_SIZE = (512, 384)
#: Vertical field of view, rad.
FOV_Y_RAD = 0.8
#: Elevation of the oblique cameras above the horizontal, deg.
OBLIQUE_ELEVATION_DEG = 40.0
#: Azimuth of the whole-scene oblique camera, seen from the scene's centre, deg (x toward y):
#: from the front-left corner, so the room reads left to right.
SCENE_AZIMUTH_DEG = -120.0
#: observe_objects frames the asked objects' box grown by this fraction of its size per side
#: (0.5: half the box on every side), and at least MIN_FRAME_M across.
FRAME_MARGIN = 0.5
MIN_FRAME_M = 0.4
#: observe_objects tries these oblique views, (azimuth turn from the room's side, elevation),
#: deg, on label images of SEARCH_SIZE px, and keeps the one that shows the asked objects best.
SEARCH_VIEWS = ((0.0, OBLIQUE_ELEVATION_DEG), (45.0, OBLIQUE_ELEVATION_DEG),
                (-45.0, OBLIQUE_ELEVATION_DEG), (0.0, 20.0), (0.0, 65.0),
                (90.0, OBLIQUE_ELEVATION_DEG), (-90.0, OBLIQUE_ELEVATION_DEG),
                (180.0, OBLIQUE_ELEVATION_DEG))
SEARCH_SIZE = (128, 96)
#: Fraction of the image kept free at its borders when fitting a box.
BORDER = 0.04
#: Clipping range of the whole-scene cameras, m.
SCENE_CLIP_M = (0.05, 100.0)
#: Scene kinds (scene.json) hidden from top views, and body names of architecture hidden from
#: oblique views (substring match, lower case).
TOP_HIDDEN_KINDS = ("ceiling",)
OBLIQUE_HIDDEN_ARCHITECTURE = ("wall", "ceiling")
#: Outline colours of asked objects, in order: (name, RGB).
HIGHLIGHTS = (("red", (230, 25, 35)), ("blue", (30, 90, 230)), ("green", (20, 170, 60)),
              ("orange", (250, 140, 0)), ("magenta", (210, 40, 200)), ("cyan", (0, 190, 210)))
#: Outline width, px.
OUTLINE_PX = 2
#: Flat colours of objects drawn from their collision geometry, by scene kind.
_FALLBACK_RGBA = {"architecture": (0.85, 0.85, 0.82), "furniture": (0.62, 0.45, 0.30),
                  "wall": (0.5, 0.5, 0.6), "ceiling": (0.9, 0.9, 0.7)}
_FALLBACK_OTHER = (0.30, 0.55, 0.75)

_RENDERERS = weakref.WeakKeyDictionary()


class _View:
    """One context of the state's diagram with a VTK renderer in it."""

    def __init__(self, state, hidden_geometries, fallback):
        scene_graph = state.scene_graph
        self.context = state.diagram.CreateDefaultContext()
        sg_context = scene_graph.GetMyMutableContextFromRoot(self.context)
        source = state.plant.get_source_id()
        for gid, properties in fallback:
            scene_graph.AssignRole(sg_context, source, gid, properties)
        for gid in hidden_geometries:
            scene_graph.RemoveRole(sg_context, source, gid, Role.kPerception)
        scene_graph.AddRenderer(sg_context, "vtk", MakeRenderEngineVtk(RenderEngineVtkParams()))
        self.query = scene_graph.get_query_output_port().Eval(sg_context)
        self.world = scene_graph.world_frame_id()


class SceneRenderer:
    """Renders a state's objects from any camera; see the module doc. Build with `renderer`."""

    def __init__(self, state):
        self.state = state
        plant, inspector = state.plant, state.scene_graph.model_inspector()
        #: Render label value -> index into state.ids.
        self._label_lut = np.full(1 << 16, -1, dtype=np.int32)
        fallback, top_hidden, oblique_hidden = [], [], []
        #: What each view leaves out (reported with its images): object ids, body names.
        self.top_hidden_ids, self.oblique_hidden_bodies = [], []
        for k, object_id in enumerate(state.ids):
            kind = state.kind(object_id)
            seen = []
            for body in state.bodies(object_id):
                frame = plant.GetBodyFrameIdOrThrow(body.index())
                perception = inspector.GetGeometries(frame, Role.kPerception)
                if not perception:
                    # Drawn from its collision geometry; labelled like the plant labels bodies.
                    label = RenderLabel(int(body.index()))
                    for gid in plant.GetCollisionGeometriesForBody(body):
                        fallback.append((gid, _flat_properties(kind, label)))
                        perception.append(gid)
                    self._label_lut[int(label)] = k
                for gid in perception:
                    properties = inspector.GetPerceptionProperties(gid)
                    if properties is not None and properties.HasProperty("label", "id"):
                        self._label_lut[int(properties.GetProperty("label", "id"))] = k
                seen.append((body, perception))
            if kind in TOP_HIDDEN_KINDS:
                self.top_hidden_ids.append(object_id)
                top_hidden += [g for _, gs in seen for g in gs]
            if kind == "architecture":
                for body, gs in seen:
                    if any(w in body.name().lower() for w in OBLIQUE_HIDDEN_ARCHITECTURE):
                        oblique_hidden += gs
                        self.oblique_hidden_bodies.append(f"{object_id}::{body.name()}")
        self.views = {"top": _View(state, top_hidden, fallback),
                      "oblique": _View(state, oblique_hidden, fallback)}
        width, height = IMAGE_SIZE
        self.tan_y = math.tan(FOV_Y_RAD / 2.0)
        self.tan_x = self.tan_y * width / height

    def render(self, view, X_WC, clip_m):
        """(H x W x 4 uint8 colour, H x W int32 index into state.ids or -1) from camera X_WC
        of `view` ("top" or "oblique") with clipping range clip_m (near, far)."""
        v = self.views[view]
        camera = _camera(IMAGE_SIZE, clip_m)
        color = np.array(v.query.RenderColorImage(camera, v.world, X_WC).data, copy=True)
        return color, self.labels(view, X_WC, clip_m)

    def labels(self, view, X_WC, clip_m, size=IMAGE_SIZE):
        """The H x W int32 image of indices into state.ids (-1: no object) of a camera."""
        v = self.views[view]
        image = v.query.RenderLabelImage(_camera(size, clip_m), v.world, X_WC)
        return self._label_lut[np.array(image.data)[:, :, 0].astype(np.int64) & 0xFFFF]

    def fit(self, lo, hi, forward, near_at_box=False):
        """(X_WC, clip range) of a camera looking along `forward` (unit, world) at the box
        (lo, hi), as close as it can be with the whole box in the image. With near_at_box the
        near clipping plane touches the box's nearest corner (what is in front is cut away)."""
        center = 0.5 * (np.asarray(lo) + np.asarray(hi))
        R_WC = _camera_rotation(forward)
        right, down, f = R_WC[:, 0], R_WC[:, 1], R_WC[:, 2]
        corners = np.array([[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1])
                            for z in (lo[2], hi[2])]) - center
        along = corners @ f
        keep = 1.0 - BORDER
        distance = max(np.max(np.abs(corners @ right) / (self.tan_x * keep) - along),
                       np.max(np.abs(corners @ down) / (self.tan_y * keep) - along))
        p_WC = center - distance * f
        if near_at_box:
            near = max(0.01, float(np.min(along + distance)) - 0.01)
            clip = (near, near + 4.0 * float(np.linalg.norm(hi - lo)) + 10.0)
        else:
            clip = SCENE_CLIP_M
        return RigidTransform(RotationMatrix(R_WC), p_WC), clip


def renderer(state):
    """The state's SceneRenderer, built on first use (about 1 s for a furnished room)."""
    found = _RENDERERS.get(state)
    if found is None:
        found = _RENDERERS[state] = SceneRenderer(state)
    return found


def observe_scene(state):
    """A top view and an oblique view of the whole scene: (info, [(name, rgba)])."""
    r = renderer(state)
    top_ids = [i for i in state.ids if i not in r.top_hidden_ids]
    views = []
    images = []
    for name, view, ids, forward in (
            ("scene_top", "top", top_ids, np.array([0.0, 0.0, -1.0])),
            ("scene_oblique", "oblique", state.ids, _oblique_forward(SCENE_AZIMUTH_DEG))):
        box = _union_box(state, ids)
        if box is None:
            continue
        X_WC, clip = r.fit(*box, forward)
        color, _ = r.render(view, X_WC, clip)
        images.append((name, color))
        views.append(_view_info(name, view, X_WC, box, r))
    return {"views": views, "note": _NOTE_SCENE}, images


def observe_objects(state, object_ids):
    """An oblique and a top view framing `object_ids` (known ids, at least one), the other
    objects washed out and each asked object outlined in its colour: (info, [(name, rgba)])."""
    r = renderer(state)
    box = _union_box(state, object_ids)
    if box is None:
        raise BadRequest(f"objects {', '.join(object_ids)} have no collision geometry to frame")
    lo, hi = _grown(*box)
    colours = {i: HIGHLIGHTS[k % len(HIGHLIGHTS)] for k, i in enumerate(object_ids)}
    index = {i: state.ids.index(i) for i in object_ids}
    forward = _clearest_oblique(r, state, lo, hi, [index[i] for i in object_ids])
    views, images = [], []
    for name, view, forward in (("objects_oblique", "oblique", forward),
                                ("objects_top", "top", np.array([0.0, 0.0, -1.0]))):
        X_WC, clip = r.fit(lo, hi, forward, near_at_box=True)
        color, labels = r.render(view, X_WC, clip)
        masks = {i: labels == index[i] for i in object_ids}
        images.append((name, _highlight(color, masks, colours)))
        info = _view_info(name, view, X_WC, (lo, hi), r)
        info["visible_pixels"] = {i: int(m.sum()) for i, m in masks.items()}
        views.append(info)
    return {"objects": list(object_ids),
            "outline_colours": {i: c[0] for i, c in colours.items()},
            "views": views, "note": _NOTE_OBJECTS}, images


_NOTE_SCENE = ("scene_top looks straight down (+x right, +y up in the image; ceiling objects "
               "hidden); scene_oblique looks down at an angle with the walls hidden.")
_NOTE_OBJECTS = ("The asked objects are drawn in colour with an outline of their colour; every "
                 "other object is washed out (pale). Whatever stood between the camera and the "
                 "framed box is cut away. objects_top looks straight down (+x right, +y up); "
                 "objects_oblique looks down at an angle with the walls hidden. visible_pixels "
                 "0 means the object is hidden in that view.")


# -- helpers -----------------------------------------------------------------------------

def _clearest_oblique(r, state, lo, hi, indices):
    """The oblique view direction onto the box (lo, hi) that shows most of the objects
    `indices` (sum of log pixel counts on small label images, so every object counts). The
    candidates start on the room's side of the box (a shelf's open side faces the room) and
    turn around it; the first of equal scores wins."""
    scene_box = _union_box(state, state.ids)
    to_room = 0.5 * (scene_box[0] + scene_box[1])[:2] - 0.5 * (lo + hi)[:2]
    start = math.degrees(math.atan2(to_room[1], to_room[0]))
    best = None
    for turn, elevation in SEARCH_VIEWS:
        forward = _oblique_forward(start + turn, elevation)
        X_WC, clip = r.fit(lo, hi, forward, near_at_box=True)
        labels = r.labels("oblique", X_WC, clip, SEARCH_SIZE)
        score = sum(math.log1p(int(np.count_nonzero(labels == k))) for k in indices)
        if best is None or score > best[0] + 1e-9:
            best = (score, forward)
    return best[1]


def _camera(size, clip_m):
    core = RenderCameraCore("vtk", CameraInfo(size[0], size[1], FOV_Y_RAD),
                            ClippingRange(*clip_m), RigidTransform())
    return ColorRenderCamera(core, False)


def _flat_properties(kind, label):
    rgb = _FALLBACK_RGBA.get(kind, _FALLBACK_OTHER)
    properties = PerceptionProperties()
    properties.AddProperty("phong", "diffuse", Rgba(*rgb, 1.0))
    properties.AddProperty("label", "id", label)
    return properties


def _camera_rotation(forward):
    """R_WC of a camera looking along `forward` (Drake's camera frame: +z forward, +x right,
    +y down in the image); looking straight down, +x of the world is right in the image."""
    z = np.asarray(forward, dtype=float) / np.linalg.norm(forward)
    x = np.cross(z, [0.0, 0.0, 1.0])
    if np.linalg.norm(x) < 1e-6:
        x = np.array([1.0, 0.0, 0.0])
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def _oblique_forward(azimuth_deg, elevation_deg=OBLIQUE_ELEVATION_DEG):
    """The view direction of a camera at `azimuth_deg` (seen from its target, x toward y)
    looking down at `elevation_deg`."""
    a, e = math.radians(azimuth_deg), math.radians(elevation_deg)
    return -np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])


def _union_box(state, object_ids):
    """(lo, hi) around the objects' collision geometry in the world, or None without any."""
    boxes = [b for b in (state.world_aabb(i) for i in object_ids) if b is not None]
    if not boxes:
        return None
    return (np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0))


def _grown(lo, hi):
    """The box grown by FRAME_MARGIN of its size per side, at least MIN_FRAME_M on each axis."""
    center, half = 0.5 * (lo + hi), 0.5 * (hi - lo) * (1.0 + 2.0 * FRAME_MARGIN)
    half = np.maximum(half, 0.5 * MIN_FRAME_M)
    return center - half, center + half


def _highlight(color, masks, colours):
    """Everything outside the masks washed out; each mask outlined (just outside it) in its
    colour."""
    out = color.copy()
    focus = np.zeros(color.shape[:2], dtype=bool)
    for m in masks.values():
        focus |= m
    rgb = out[:, :, :3].astype(np.float32)
    grey = rgb @ np.array([0.299, 0.587, 0.114], dtype=np.float32)
    # Half desaturated, then washed out toward white: shapes stay readable, colours do not
    # compete with the asked objects'.
    pale = 0.45 * (0.5 * rgb + 0.5 * grey[:, :, None]) + 0.55 * 230.0
    out[~focus, :3] = pale[~focus].astype(np.uint8)
    # Larger objects first; a ring may cover another asked object only if that one is larger
    # (a cushion's ring shows on its sofa, the sofa's ring stays off the cushion).
    order = sorted(masks, key=lambda i: -int(masks[i].sum()))
    for k, object_id in enumerate(order):
        smaller = np.zeros_like(focus)
        for other in order[k + 1:]:
            smaller |= masks[other]
        ring = _dilate(masks[object_id], OUTLINE_PX) & ~masks[object_id] & ~smaller
        out[ring, :3] = colours[object_id][1]
    return out


def _dilate(mask, r):
    padded = np.pad(mask, r)
    h, w = mask.shape
    out = np.zeros_like(mask)
    for dy in range(2 * r + 1):
        for dx in range(2 * r + 1):
            out |= padded[dy:dy + h, dx:dx + w]
    return out


def _view_info(name, view, X_WC, box, r):
    hidden = r.top_hidden_ids if view == "top" else r.oblique_hidden_bodies
    return {"image": name, "view": view,
            "camera_xyz": [float(c) for c in X_WC.translation()],
            "looking_at": [float(c) for c in 0.5 * (box[0] + box[1])],
            "hidden": list(hidden)}
