"""A scene's state as the evaluator reads it: one directives file (`scene.dmd.yaml`, or a policy's
`after_<policy>.dmd.yaml` of the same scene) loaded into Drake's default plant, scene.json's
records, and each object's collision pieces with their vertices.

Objects are model instances (instance name = object id). An object's frame O is its *base
body*: the body of the instance that is no child of a joint inside the instance (the free body
of a free object, the body welded to the world of a welded one, the carcass of a cabinet).
The state is read-only: the poses are the directives' (default free-body poses, default joint
positions).
"""

import dataclasses
import json
import os
import re

import numpy as np
from pydrake.geometry import Box, Capsule, Convex, Cylinder, Ellipsoid, Mesh, Sphere
from pydrake.multibody.parsing import LoadModelDirectives, Parser, ProcessModelDirectives
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.multibody.tree import ModelInstanceIndex, default_model_instance, world_model_instance
from pydrake.systems.framework import DiagramBuilder

from drake_bridge.errors import BadRequest, FileMissing, ModelError
from drake_bridge.evaluator.geometry import convex_hull_2d

#: The plant's time step, s (Drake's default `MultibodyPlantConfig` otherwise).
TIME_STEP_S = 0.001
#: Directions sampled on round shapes (spheres, cylinders, capsules, ellipsoids) for their
#: vertex sets: azimuths per ring and rings per hemisphere.
_ROUND_AZIMUTHS = 16
_ROUND_RINGS = 4


@dataclasses.dataclass
class Piece:
    """One collision geometry of an object: its id, name, and vertices in the geometry frame G
    (a convex hull's vertices, a box's corners, or samples on a round shape; k x 3, m)."""

    geometry_id: object
    name: str
    p_GV: np.ndarray


class SceneState:
    """A loaded scene state. Build it with `load_state`."""

    def __init__(self, scene_dir, directives_path, package_xml, diagram, plant, scene_graph,
                 objects, assets):
        self.scene_dir = scene_dir
        self.directives_path = directives_path
        self.package_xml = package_xml
        self.diagram = diagram
        self.plant = plant
        self.scene_graph = scene_graph
        self.context = diagram.CreateDefaultContext()
        self.plant_context = plant.GetMyContextFromRoot(self.context)
        self.query = scene_graph.get_query_output_port().Eval(
            scene_graph.GetMyContextFromRoot(self.context))
        #: scene.json's object records by id (empty for a scene without scene.json).
        self.objects = objects
        #: scene.json's asset records by id.
        self.assets = assets
        #: Object ids: the model instances that have bodies, in instance order.
        self.ids = []
        self._instances = {}
        for i in range(plant.num_model_instances()):
            index = ModelInstanceIndex(i)
            if index in (world_model_instance(), default_model_instance()):
                continue
            if plant.GetBodyIndices(index):
                name = plant.GetModelInstanceName(index)
                self.ids.append(name)
                self._instances[name] = index
        self._pieces = {}
        self._vertices_W = {}
        self._hulls_xy = {}

    # -- identity -------------------------------------------------------------------------

    def instance(self, object_id):
        """The model instance of `object_id`; BadRequest naming the file when there is none."""
        index = self._instances.get(object_id)
        if index is None:
            raise BadRequest(f"no object {object_id!r} in {self.directives_path}")
        return index

    def record(self, object_id):
        """scene.json's record of `object_id`, or a stand-in read from the id when the scene
        has no record of it (hand-written directives): category = id without its counter."""
        self.instance(object_id)
        found = self.objects.get(object_id)
        if found is not None:
            return found
        return {"id": object_id, "category": re.sub(r"_[0-9a-z]+$", "", object_id),
                "kind": "unknown"}

    def category(self, object_id):
        return self.record(object_id).get("category")

    def kind(self, object_id):
        return self.record(object_id).get("kind")

    # -- bodies and poses -----------------------------------------------------------------

    def bodies(self, object_id):
        return [self.plant.get_body(b) for b in self.plant.GetBodyIndices(self.instance(object_id))]

    def base_body(self, object_id):
        """The body that defines the object's frame O (see the module doc)."""
        instance = self.instance(object_id)
        children = set()
        for j in self.plant.GetJointIndices(instance):
            joint = self.plant.get_joint(j)
            if joint.parent_body().model_instance() == instance:
                children.add(joint.child_body().index())
        bodies = self.bodies(object_id)
        return next((b for b in bodies if b.index() not in children), bodies[0])

    def X_WO(self, object_id):
        """The object's frame in the world (a RigidTransform)."""
        return self.plant.EvalBodyPoseInWorld(self.plant_context, self.base_body(object_id))

    def is_free(self, object_id):
        return bool(self.base_body(object_id).is_floating_base_body())

    def mass_kg(self, object_id):
        return float(sum(b.default_mass() for b in self.bodies(object_id)))

    # -- collision geometry ---------------------------------------------------------------

    def pieces(self, object_id):
        """The object's collision pieces (every body's proximity geometries)."""
        if object_id not in self._pieces:
            inspector = self.query.inspector()
            out = []
            for body in self.bodies(object_id):
                for gid in self.plant.GetCollisionGeometriesForBody(body):
                    p_GV = _shape_vertices(inspector, gid)
                    if p_GV is not None:
                        out.append(Piece(gid, inspector.GetName(gid), p_GV))
            self._pieces[object_id] = out
        return self._pieces[object_id]

    def piece_vertices_W(self, object_id):
        """Per piece, its vertices in the world (a list of k x 3 arrays, same order as
        `pieces`)."""
        if object_id not in self._vertices_W:
            out = []
            for piece in self.pieces(object_id):
                X_WG = self.query.GetPoseInWorld(piece.geometry_id)
                out.append(piece.p_GV @ X_WG.rotation().matrix().T + X_WG.translation())
            self._vertices_W[object_id] = out
        return self._vertices_W[object_id]

    def piece_hulls_xy(self, object_id):
        """Per piece, the convex hull of its world vertices projected on the world x-y plane
        (counter-clockwise; same order as `pieces`)."""
        if object_id not in self._hulls_xy:
            self._hulls_xy[object_id] = [convex_hull_2d(v[:, :2])
                                         for v in self.piece_vertices_W(object_id)]
        return self._hulls_xy[object_id]

    def vertices_W(self, object_id):
        """All the object's collision vertices in the world (N x 3; empty without geometry)."""
        pieces = self.piece_vertices_W(object_id)
        return np.vstack(pieces) if pieces else np.zeros((0, 3))

    def vertices_in(self, object_id, X_WF):
        """All the object's collision vertices expressed in frame F, given X_WF."""
        X_FW = X_WF.inverse()
        return self.vertices_W(object_id) @ X_FW.rotation().matrix().T + X_FW.translation()

    def box_in_own_frame(self, object_id):
        """(lo, hi): the object's oriented box, the bounds of its collision vertices (all links
        at their current positions) in its own frame O."""
        p_OV = self.vertices_in(object_id, self.X_WO(object_id))
        if len(p_OV) == 0:
            raise BadRequest(f"object {object_id!r} has no collision geometry")
        return p_OV.min(axis=0), p_OV.max(axis=0)

    def world_aabb(self, object_id):
        """(lo, hi) of the object's collision vertices in the world, or None without geometry."""
        p_WV = self.vertices_W(object_id)
        if len(p_WV) == 0:
            return None
        return p_WV.min(axis=0), p_WV.max(axis=0)


def load_state(scene_dir, dmd="scene.dmd.yaml"):
    """Loads `dmd` (a path relative to `scene_dir`, or an absolute one: a policy's
    `after_<policy>.dmd.yaml` may live elsewhere) with the package map of
    `<scene_dir>/package.xml` into Drake's default plant (`MultibodyPlantConfig` at
    TIME_STEP_S), plus `<scene_dir>/scene.json` when it exists.

    FileMissing names a missing file; ModelError names the directives Drake could not load."""
    scene_dir = os.path.abspath(scene_dir)
    directives_path = dmd if os.path.isabs(dmd) else os.path.join(scene_dir, dmd)
    package_xml = os.path.join(scene_dir, "package.xml")
    for path, what in ((directives_path, "directives"), (package_xml, "package.xml")):
        if not os.path.isfile(path):
            raise FileMissing(f"{what} file not found: {path}")
    objects, assets = {}, {}
    scene_json = os.path.join(scene_dir, "scene.json")
    if os.path.isfile(scene_json):
        try:
            with open(scene_json) as f:
                data = json.load(f)
        except (OSError, ValueError) as e:
            raise ModelError(f"cannot read {scene_json}: {e}") from e
        objects = {o["id"]: o for o in data.get("objects", []) if "id" in o}
        assets = data.get("assets", {})

    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(time_step=TIME_STEP_S), builder)
    parser = Parser(plant)
    # The scene needs no remote model package, and this machine may be offline.
    if parser.package_map().Contains("drake_models"):
        parser.package_map().Remove("drake_models")
    parser.package_map().AddPackageXml(package_xml)
    try:
        ProcessModelDirectives(LoadModelDirectives(directives_path), plant, parser)
        plant.Finalize()
    except RuntimeError as e:
        raise ModelError(f"Drake could not load {directives_path}: {e}") from e
    diagram = builder.Build()
    return SceneState(scene_dir, directives_path, package_xml, diagram, plant, scene_graph,
                      objects, assets)


def category_matches(noun, category):
    """Whether an object of `category` answers to `noun`: compared lower-case with underscores
    as spaces, equal or ending in the noun's words ("table" and "coffee table" both match
    "coffee_table"; "tab" does not)."""
    if not noun or not category:
        return False
    noun_words = noun.strip().lower().replace("_", " ").split()
    category_words = category.strip().lower().replace("_", " ").split()
    return bool(noun_words) and category_words[-len(noun_words):] == noun_words


def matching_ids(state, noun):
    """Ids of the objects a noun names, in state order: category (or scene.json's `name`)
    matches, architecture excluded (as the task check on the Rust side does)."""
    out = []
    for object_id in state.ids:
        record = state.record(object_id)
        if record.get("kind") == "architecture":
            continue
        names = [record.get("category"), record.get("name")]
        if any(category_matches(noun, n) for n in names if n):
            out.append(object_id)
    return out


def _shape_vertices(inspector, gid):
    """Vertices of a geometry in its own frame (k x 3), or None for shapes without a bounded
    vertex set (half spaces)."""
    shape = inspector.GetShape(gid)
    if isinstance(shape, (Convex, Mesh)):
        hull = inspector.GetConvexHull(gid)
        return np.array([hull.vertex(i) for i in range(hull.num_vertices())], dtype=float)
    if isinstance(shape, Box):
        half = np.array([shape.width(), shape.depth(), shape.height()]) / 2.0
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
        return signs * half
    if isinstance(shape, Sphere):
        return _round_samples([shape.radius()] * 3, 0.0)
    if isinstance(shape, Ellipsoid):
        return _round_samples([shape.a(), shape.b(), shape.c()], 0.0)
    if isinstance(shape, Capsule):
        return _round_samples([shape.radius()] * 3, shape.length() / 2.0)
    if isinstance(shape, Cylinder):
        r, h = shape.radius(), shape.length() / 2.0
        t = 2.0 * np.pi * np.arange(_ROUND_AZIMUTHS) / _ROUND_AZIMUTHS
        ring = np.stack([r * np.cos(t), r * np.sin(t)], axis=1)
        return np.vstack([np.column_stack([ring, np.full(len(ring), z)]) for z in (-h, h)])
    return None


def _round_samples(radii, half_length):
    """Points on an ellipsoid with semi-axes `radii`, its upper half raised and lower half
    lowered by `half_length` (a capsule when half_length > 0)."""
    points = [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]
    t = 2.0 * np.pi * np.arange(_ROUND_AZIMUTHS) / _ROUND_AZIMUTHS
    for k in range(-_ROUND_RINGS + 1, _ROUND_RINGS):
        elevation = 0.5 * np.pi * k / _ROUND_RINGS
        for a in t:
            points.append([np.cos(elevation) * np.cos(a), np.cos(elevation) * np.sin(a),
                           np.sin(elevation)])
    points = np.array(points) * np.asarray(radii)
    points[:, 2] += np.sign(points[:, 2]) * half_length
    if half_length > 0:
        equator = points[np.abs(points[:, 2]) < 1e-12]
        points = np.vstack([points, equator + [0, 0, half_length], equator - [0, 0, half_length]])
    return points
