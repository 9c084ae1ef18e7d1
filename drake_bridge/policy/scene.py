"""The scene and the robot as the policy loads them: which files, which instances, which bodies
are welded, and the three plants built from them.

Welding (for speed, in every plant the policy builds): every floating body of the scene except
the target's is welded to the world at its directive pose (`default_free_body_pose`), and every
scene joint (cabinet doors and drawers) is replaced by a weld at its default position. The
target is the only free scene body of the simulation plant. Contact properties stay as written
in the scene's SDFormat files; the simulation plant is Drake's default `MultibodyPlantConfig`
(hydroelastic with point fallback, Drake's default discrete approximation) at 1 ms.

Plants:
- two *planning models* (`PlanningModel`, a `RobotDiagram` with a
  `SceneGraphCollisionChecker`), built once per episode. Mode "world": the target welded where
  it stands (before the grasp); the robot's 13 joints are the only degrees of freedom. Mode
  "held": the target hangs from the grasp frame on a 6-dof joint whose positions planners
  never move (carrying; any grasp without a rebuild), its collisions with the gripper filtered.
- a *timing plant* for TOPPRA: the robot alone, or with the held object welded to its grasp
  frame (so torque limits see the object's weight).
- the *simulation plant* (rollout.py): the welded scene (or the part of it the planned motion
  comes near, SceneSpec.subset), the free target, the robot.
"""

import contextlib
import copy
import dataclasses as dc
import json
import os
from typing import Dict, List

import numpy as np
from pydrake.common import Parallelism
from pydrake.common.eigen_geometry import AngleAxis
from pydrake.common.yaml import yaml_load
from pydrake.common import MemoryFile
from pydrake.geometry import CollisionFilterDeclaration, Convex, GeometrySet, InMemoryMesh
from pydrake.math import RigidTransform
from pydrake.multibody.parsing import LoadModelDirectives, Parser
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.multibody.tree import (
    BodyIndex,
    PrismaticJoint,
    QuaternionFloatingJoint,
    RevoluteJoint,
)
from pydrake.planning import RobotDiagramBuilder, SceneGraphCollisionChecker
from pydrake.systems.framework import DiagramBuilder

from drake_bridge.directives import add_model_directives
from drake_bridge.policy.types import BadTask

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
ROBOT_PACKAGE_XML = os.path.join(ROOT, "sdf_templates", "package.xml")
ROBOT_URL = "package://scenesmith_robots/mobile_iiwa/mobile_iiwa.sdf"
SCENARIO = os.path.join(ROOT, "sdf_templates", "mobile_iiwa", "scenario.yaml")
SCENARIO_NAME = "mobile_iiwa_in_scene"
ROBOT = "mobile_iiwa"

BASE_JOINTS = ("base_x", "base_y", "base_yaw")
ARM_JOINTS = tuple(f"iiwa_joint_{i}" for i in range(1, 8))
FINGER_JOINTS = ("right_finger_joint", "left_finger_joint")
#: The joints the arm planner moves (base and fingers held).
ARM_PLANNING_JOINTS = ("lift",) + ARM_JOINTS
#: Bodies that make up "the gripper" for clearances and grasp checks.
GRIPPER_BODIES = ("gripper_body", "right_finger", "left_finger")
#: Finger position when open (each finger, m): the WSG 50 stroke is 2 x 0.055 m.
FINGER_OPEN_M = 0.055
#: The joint that holds the carried object in the "held" planning model.
HELD_JOINT = "held_object"
#: The held object's pose in the grasp frame when the model should carry nothing: far below the
#: floor, out of every collision query.
X_GO_PARKED = RigidTransform([0.0, 0.0, -100.0])


def home_positions():
    """The robot's home configuration (joint name -> value), read from the scenario's
    `default_joint_positions`: the one place "home" is defined. Base joints included (the
    scenario's placeholder base pose; the policy overrides it)."""
    data = yaml_load(filename=SCENARIO)
    for directive in data[SCENARIO_NAME]["directives"]:
        add_model = directive.get("add_model")
        if add_model is not None and add_model.get("name") == ROBOT:
            return {name: float(values[0])
                    for name, values in add_model["default_joint_positions"].items()}
    raise RuntimeError(f"{SCENARIO}: no add_model named {ROBOT}")


@dc.dataclass
class SceneSpec:
    """A scene directory as the policy reads it: the directives, the package, and scene.json's
    objects and assets when the file exists (hand-written scenes may lack it)."""

    scene_dir: str
    directives_path: str
    package_xml: str
    directives: object  # pydrake ModelDirectives
    instances: List[str]
    objects: Dict[str, dict]
    assets: Dict[str, dict]
    rooms: List[dict]

    def add_model(self, instance):
        """The AddModel directive of `instance`."""
        for directive in self.directives.directives:
            if directive.add_model is not None and directive.add_model.name == instance:
                return directive.add_model
        raise BadTask(f"{self.directives_path}: no model instance named {instance!r}")

    def surfaces(self, instance):
        """scene.json's support surfaces of `instance`'s asset (id -> surface dict, object
        frame), empty when unknown."""
        obj = self.objects.get(instance)
        if obj is None:
            return {}
        asset = self.assets.get(obj.get("asset"), {})
        return {s["id"]: s for s in asset.get("surfaces", [])}

    def subset(self, keep):
        """This scene with only the instances in `keep` (their add_model directives, and the
        add_weld directives between kept instances or the world)."""
        def kept(frame_name):
            return frame_name == "world" or frame_name.split("::")[0] in keep

        directives = copy.deepcopy(self.directives)
        out = []
        for d in directives.directives:
            if d.add_model is not None and d.add_model.name not in keep:
                continue
            if d.add_weld is not None and not (kept(d.add_weld.parent) and
                                               kept(d.add_weld.child)):
                continue
            out.append(d)
        directives.directives = out
        return dc.replace(self, directives=directives,
                          instances=[n for n in self.instances if n in keep])

    def support(self, instance):
        """scene.json's support of `instance` ({"type": "object", "parent": ..., "surface": ...}
        or another type), or None when unknown."""
        obj = self.objects.get(instance)
        return None if obj is None else obj.get("support")


def load_scene_spec(scene_dir):
    """Reads `<scene_dir>/scene.dmd.yaml`, `package.xml` and (optional) `scene.json`."""
    scene_dir = os.path.abspath(scene_dir)
    directives_path = os.path.join(scene_dir, "scene.dmd.yaml")
    package_xml = os.path.join(scene_dir, "package.xml")
    for path in (directives_path, package_xml):
        if not os.path.isfile(path):
            raise BadTask(f"scene file not found: {path}")
    directives = LoadModelDirectives(directives_path)
    instances = [d.add_model.name for d in directives.directives if d.add_model is not None]
    objects, assets, rooms = {}, {}, []
    scene_json = os.path.join(scene_dir, "scene.json")
    if os.path.isfile(scene_json):
        with open(scene_json) as f:
            data = json.load(f)
        objects = {o["id"]: o for o in data.get("objects", [])}
        assets = data.get("assets", {})
        rooms = data.get("rooms", [])
    return SceneSpec(scene_dir, directives_path, package_xml, directives, instances, objects,
                     assets, rooms)


def configure_parser(parser, spec):
    """Robot and scene packages in the parser's map; Drake's remote model package removed (the
    machine may be offline and nothing here uses it)."""
    package_map = parser.package_map()
    if package_map.Contains("drake_models"):
        package_map.Remove("drake_models")
    package_map.AddPackageXml(ROBOT_PACKAGE_XML)
    package_map.AddPackageXml(spec.package_xml)


def _weld_scene_joints(plant, scene_instances):
    """Replaces every non-weld joint of the scene instances by a weld at its default position
    (revolute and prismatic joints; others are an error naming the model)."""
    for index in list(plant.GetJointIndices()):
        joint = plant.get_joint(index)
        if joint.model_instance() not in scene_instances or joint.type_name() == "weld":
            continue
        if isinstance(joint, RevoluteJoint):
            X_FM = RigidTransform(AngleAxis(joint.get_default_angle(), joint.revolute_axis()),
                                  np.zeros(3))
        elif isinstance(joint, PrismaticJoint):
            X_FM = RigidTransform(joint.get_default_translation() * joint.translation_axis())
        else:
            raise BadTask(f"{plant.GetModelInstanceName(joint.model_instance())}: joint "
                          f"{joint.name()!r} of type {joint.type_name()} cannot be welded")
        for a in list(plant.GetJointActuatorIndices()):
            if plant.get_joint_actuator(a).joint().index() == index:
                plant.RemoveJointActuator(plant.get_joint_actuator(a))
        frame_on_parent, frame_on_child = joint.frame_on_parent(), joint.frame_on_child()
        plant.RemoveJoint(joint)
        plant.WeldFrames(frame_on_parent, frame_on_child, X_FM)


def _floating_bodies(plant, instances):
    """Bodies of `instances` that are no joint's child: Finalize() would make them free."""
    children = set()
    for index in plant.GetJointIndices():
        children.add(plant.get_joint(index).child_body().index())
    out = []
    for instance in instances:
        for index in plant.GetBodyIndices(instance):
            if index not in children and index != plant.world_body().index():
                out.append(plant.get_body(index))
    return out


def add_scene(plant, parser, spec, target, target_mode, robot=None, X_WO_world=None):
    """Adds the scene's directives to `plant` (not finalized) and welds it.

    target_mode: "free" (the target stays a free body), "world" (welded where the directives put
    it, or at `X_WO_world` when given: the policy's estimate) or "held" (attached to `robot`'s
    grasp frame by a 6-dof `QuaternionFloatingJoint` named HELD_JOINT, whose 7 positions are
    the object's pose in the grasp frame, so one planning model serves every grasp). Returns
    (welded instance names sorted, the target's body)."""
    add_model_directives(plant, parser, spec.directives)
    instances = [plant.GetModelInstanceByName(name) for name in spec.instances]
    if not plant.HasModelInstanceNamed(target):
        raise BadTask(f"{spec.directives_path}: no model instance named {target!r}")
    target_instance = plant.GetModelInstanceByName(target)
    _weld_scene_joints(plant, set(instances))
    target_bodies = _floating_bodies(plant, [target_instance])
    if len(target_bodies) != 1 or len(plant.GetBodyIndices(target_instance)) != 1:
        raise BadTask(f"target {target!r} is not a single free body")
    (target_body,) = target_bodies
    welded = set()
    for body in _floating_bodies(plant, instances):
        if body.index() == target_body.index():
            continue
        plant.WeldFrames(plant.world_frame(), body.body_frame(),
                         plant.GetDefaultFloatingBaseBodyPose(body))
        welded.add(plant.GetModelInstanceName(body.model_instance()))
    if target_mode == "world":
        plant.WeldFrames(plant.world_frame(), target_body.body_frame(),
                         plant.GetDefaultFloatingBaseBodyPose(target_body)
                         if X_WO_world is None else X_WO_world)
    elif target_mode == "held":
        plant.AddJoint(QuaternionFloatingJoint(
            HELD_JOINT, plant.GetFrameByName("grasp_frame", robot), target_body.body_frame()))
    else:
        assert target_mode == "free", target_mode
    return sorted(welded), target_body


@dc.dataclass(frozen=True)
class StaticGeometry:
    """One collision geometry of a welded scene body: its model instance and body names, its
    pose in the world X_WG, its shape and its proximity properties."""

    instance: str
    body: str
    X_WG: object
    shape: object
    properties: object


class StaticScene:
    """The scene welded where the directives put it, the target left out, as data: the
    collision geometry of every other body (`pieces`, StaticGeometry), each body's world pose
    and the welded instances' names. A small object (a manipuland) of more than
    HULL_MIN_PIECES convex pieces is one piece, their convex hull (`hulled`): a cup's 36 wall
    segments are one; never the target, `keep_exact` (the reference) or what holds the target
    (a piece whose box contains the target's origin), whose insides the policy reaches into.
    Drake filters every pair of world geometry explicitly, so the pieces' number costs
    quadratically at load (a set café of 2148 pieces, 68 of its small objects hulled to 280:
    one planning model 26 s -> 1.3 s, an episode 117 s -> 41 s). Parsed once per episode; the planning models and the
    simulation register its pieces on the world body instead of parsing the scene again as
    welded bodies: Drake keeps only geometry on the world body in its static broadphase tree
    and out of the per-query pose updates, while geometry of a body welded to the world is
    handled as moving (a planning query or simulation step over a room of 777 such pieces
    costs about twice the time; drake issue 24888 reports the same)."""

    def __init__(self, spec, target, keep_exact=()):
        """`keep_exact`: instances never replaced by their hull (the task's reference)."""
        # Parsed as the directives leave it (free bodies at their default poses, joints at
        # their default positions), not welded: welding every body to the world makes Drake
        # filter every pair of their geometries, a cost quadratic in the pieces (12 s of 14
        # for a dining room of 2148 pieces).
        builder = DiagramBuilder()
        plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.0)
        parser = Parser(plant)
        configure_parser(parser, spec)
        add_model_directives(plant, parser, spec.directives)
        if not plant.HasModelInstanceNamed(target):
            raise BadTask(f"{spec.directives_path}: no model instance named {target!r}")
        target_instance = plant.GetModelInstanceByName(target)
        scene = [plant.GetModelInstanceByName(name) for name in spec.instances]
        self.welded = sorted({plant.GetModelInstanceName(b.model_instance())
                              for b in _floating_bodies(plant, scene)
                              if b.model_instance() != target_instance})
        plant.Finalize()
        context = plant.CreateDefaultContext()
        inspector = scene_graph.model_inspector()
        p_WT = plant.EvalBodyPoseInWorld(
            context, plant.get_body(plant.GetBodyIndices(target_instance)[0])).translation()
        self.pieces, self._poses, self._first_body = [], {}, {}
        self.hulled = []
        for index in range(plant.num_bodies()):
            body = plant.get_body(BodyIndex(index))
            if body.model_instance() == target_instance or index == 0:
                continue
            instance = plant.GetModelInstanceName(body.model_instance())
            X_WB = plant.EvalBodyPoseInWorld(context, body)
            self._poses[(instance, body.name())] = X_WB
            self._first_body.setdefault(instance, body.name())
            pieces = [StaticGeometry(instance, body.name(),
                                     X_WB.multiply(inspector.GetPoseInFrame(gid)),
                                     inspector.GetShape(gid).Clone(),
                                     inspector.GetProximityProperties(gid))
                      for gid in plant.GetCollisionGeometriesForBody(body)]
            if (len(pieces) > HULL_MIN_PIECES and instance not in keep_exact
                    and spec.objects.get(instance, {}).get("kind") == "manipuland"
                    and not _holds(pieces, p_WT)):
                pieces = [_hull(pieces)]
                self.hulled.append(instance)
            self.pieces.extend(pieces)

    def body_pose(self, instance, body=None):
        """X_WB of the named body of `instance` (its first body when `body` is None or not
        one of its bodies)."""
        if (instance, body) not in self._poses:
            body = self._first_body[instance]
        return self._poses[(instance, body)]


HULL_MIN_PIECES = 4


def _holds(pieces, p_W, margin=0.02):
    """Whether the box around `pieces` contains the point p_W (grown by `margin`)."""
    points = np.vstack([_hull_vertices(g) for g in pieces])
    return bool(np.all(points.min(axis=0) - margin <= p_W) and
                np.all(p_W <= points.max(axis=0) + margin))


def _hull_vertices(g):
    """The world positions of the vertices of a piece's convex hull (N x 3)."""
    hull = g.shape.GetConvexHull()
    local = np.array([hull.vertex(i) for i in range(hull.num_vertices())])
    return g.X_WG.multiply(local.T).T


def _hull(pieces):
    """One StaticGeometry: the convex hull of `pieces` (all Convex, of one body), in the world
    frame, with the first piece's properties."""
    lines, offset = [], 1
    for g in pieces:
        hull = g.shape.GetConvexHull()
        for v in _hull_vertices(g):
            lines.append(f"v {v[0]:.6f} {v[1]:.6f} {v[2]:.6f}")
        for e in range(hull.num_elements()):
            face = hull.element(e)
            lines.append("f " + " ".join(str(offset + face.vertex(j))
                                         for j in range(face.num_vertices())))
        offset += hull.num_vertices()
    first = pieces[0]
    mesh = InMemoryMesh(mesh_file=MemoryFile("\n".join(lines) + "\n", ".obj",
                                             f"{first.instance}_hull.obj"))
    return StaticGeometry(first.instance, first.body, RigidTransform(), Convex(mesh),
                          first.properties)


def register_static(plant, pieces):
    """Registers `pieces` (StaticGeometry) on the world body of `plant` (not finalized);
    returns {geometry id: (instance name, body name)}."""
    owner = {}
    for k, g in enumerate(pieces):
        gid = plant.RegisterCollisionGeometry(plant.world_body(), g.X_WG, g.shape,
                                              f"{g.instance}::{g.body}::static_{k}",
                                              g.properties)
        owner[gid] = (g.instance, g.body)
    return owner


def target_default_pose(spec, target):
    """X_WO of the target as the directives place it (default_free_body_pose)."""
    add_model = spec.add_model(target)
    poses = add_model.default_free_body_pose
    if len(poses) != 1:
        raise BadTask(f"target {target!r} has no single default_free_body_pose")
    (transform,) = poses.values()
    if transform.base_frame not in (None, "", "world"):
        raise BadTask(f"target {target!r}: pose relative to {transform.base_frame!r}")
    return transform.GetDeterministicValue()


class PlanningModel:
    """The robot in the welded scene with a `SceneGraphCollisionChecker` (edge step
    `config.edge_step_rad` in the checker's joint-space distance: rad for revolute joints, m for
    prismatic ones; one checking context: the planner checks one edge at a time).

    Mode "world": the target welded where it stands (or at `X_WO_world`, the policy's
    estimate of where it stands); q = the robot's 13 joints. Mode "held":
    the target hangs from the grasp frame on HELD_JOINT; q = 13 joints + the 7 positions of
    that joint (`with_held_pose` sets them; planners never move them). The held object belongs
    to the robot (its collisions with the arm and base are checked); its collisions with the
    gripper bodies and the last arm link are filtered in the scene graph itself, so IK's
    minimum-distance constraints and the checker see the same filter.

    Paddings: `config.env_padding_m` between every robot body and the scene; in mode "held"
    with a carry padding, the gripper bodies and the held object get `config.carry_padding_m`
    instead."""

    def __init__(self, spec, target, mode, config, X_WO_world=None, static=None):
        assert mode in ("world", "held"), mode
        self.mode = mode
        builder = RobotDiagramBuilder(time_step=0.0)
        plant, parser = builder.plant(), builder.parser()
        configure_parser(parser, spec)
        (self.robot,) = parser.AddModels(url=ROBOT_URL)
        if static is None:
            self.static_owner = {}
            self.welded, self.target_body = add_scene(plant, parser, spec, target, mode,
                                                      self.robot, X_WO_world)
        else:
            _, self.target_body = add_scene(plant, parser, spec.subset({target}), target, mode,
                                            self.robot, X_WO_world)
            self.welded = static.welded
            self.static_owner = register_static(plant, static.pieces)
        plant.Finalize()
        expected = plant.num_positions(self.robot) + (7 if mode == "held" else 0)
        if plant.num_positions() != expected:
            raise BadTask(f"{spec.directives_path}: scene degrees of freedom remain after "
                          "welding")
        self.gripper_bodies = [plant.GetBodyByName(n, self.robot) for n in GRIPPER_BODIES]
        if mode == "held":
            target_set = GeometrySet(plant.GetCollisionGeometriesForBody(self.target_body))
            hand = self.gripper_bodies + [plant.GetBodyByName("iiwa_link_7", self.robot)]
            hand_set = GeometrySet([g for b in hand
                                    for g in plant.GetCollisionGeometriesForBody(b)])
            builder.scene_graph().collision_filter_manager().Apply(
                CollisionFilterDeclaration().ExcludeBetween(target_set, hand_set))
        self.diagram = builder.Build()
        self.plant = plant
        robots = [self.robot]
        if mode == "held":
            robots.append(self.target_body.model_instance())
        self.checker = SceneGraphCollisionChecker(
            model=self.diagram, robot_model_instances=robots,
            edge_step_size=config.edge_step_rad, env_collision_padding=config.env_padding_m,
            self_collision_padding=0.0, implicit_context_parallelism=Parallelism(1))
        if mode == "held":
            for body in hand:
                self.checker.SetCollisionFilteredBetween(body.index(),
                                                         self.target_body.index(), True)
        self._paddings = (config.env_padding_m,
                          config.carry_padding_m if mode == "held" else None)
        self._set_own_paddings()
        self.context = self.diagram.CreateDefaultContext()
        self.plant_context = plant.GetMyMutableContextFromRoot(self.context)
        self.index = {}
        for name in BASE_JOINTS + ("lift",) + ARM_JOINTS + FINGER_JOINTS:
            self.index[name] = plant.GetJointByName(name, self.robot).position_start()
        self.held_start = (plant.GetJointByName(HELD_JOINT).position_start()
                           if mode == "held" else None)
        self.grasp_frame = plant.GetFrameByName("grasp_frame", self.robot)

    def owner(self, geometry_id):
        """(model instance name, body name) of a collision geometry (for a StaticScene piece
        on the world body: the scene body it belongs to)."""
        if geometry_id in self.static_owner:
            return self.static_owner[geometry_id]
        inspector = self.diagram.scene_graph().model_inspector()
        body = self.plant.GetBodyFromFrameId(inspector.GetFrameId(geometry_id))
        return self.plant.GetModelInstanceName(body.model_instance()), body.name()

    def instance_of(self, geometry_id):
        return self.owner(geometry_id)[0]

    def geometries_of(self, instance):
        """The collision geometries of a welded scene instance."""
        if self.static_owner:
            return [g for g, (name, _) in self.static_owner.items() if name == instance]
        model = self.plant.GetModelInstanceByName(instance)
        return [g for b in self.plant.GetBodyIndices(model)
                for g in self.plant.GetCollisionGeometriesForBody(self.plant.get_body(b))]

    def _set_own_paddings(self):
        env, carry = self._paddings
        self.checker.SetPaddingAllRobotEnvironmentPairs(env)
        if carry is not None:
            for body in self.gripper_bodies + [self.target_body]:
                self.checker.SetPaddingOneRobotBodyAllEnvironmentPairs(body.index(), carry)

    @contextlib.contextmanager
    def padding(self, padding_m):
        """The checker with `padding_m` between every robot body and the scene inside the
        block (a move that must pass close by design); the model's own paddings after it."""
        self.checker.SetPaddingAllRobotEnvironmentPairs(padding_m)
        try:
            yield self.checker
        finally:
            self._set_own_paddings()

    def indices(self, names):
        """Positions of the named robot joints in q (HELD_JOINT names its 7 positions)."""
        out = []
        for n in names:
            if n == HELD_JOINT:
                out.extend(range(self.held_start, self.held_start + 7))
            else:
                out.append(self.index[n])
        return np.array(out, dtype=int)

    def q_from(self, values, X_GO=None):
        """A full q from a joint name -> value dict (every robot joint named) and, in mode
        "held", the object's pose in the grasp frame (parked out of reach when None)."""
        q = np.zeros(self.plant.num_positions())
        for name, value in values.items():
            q[self.index[name]] = value
        if self.mode == "held":
            q = self.with_held_pose(q, X_GO if X_GO is not None else X_GO_PARKED)
        return q

    def with_held_pose(self, q, X_GO):
        """q with the held object at X_GO (its body frame in the grasp frame)."""
        q = q.copy()
        quat = X_GO.rotation().ToQuaternion()
        q[self.held_start:self.held_start + 7] = [quat.w(), quat.x(), quat.y(), quat.z(),
                                                  *X_GO.translation()]
        return q

    def robot_values(self, q):
        """Joint name -> value of the robot's 13 joints in q."""
        return {name: float(q[i]) for name, i in self.index.items()}

    def set_q(self, q):
        self.plant.SetPositions(self.plant_context, q)

    def X_WG(self, q):
        """The grasp frame's pose in the world at q."""
        self.set_q(q)
        return self.grasp_frame.CalcPoseInWorld(self.plant_context)

    def X_WB(self, q, body):
        self.set_q(q)
        return self.plant.EvalBodyPoseInWorld(self.plant_context, body)

    def query(self, q):
        self.set_q(q)
        return self.plant.get_geometry_query_input_port().Eval(self.plant_context)


def timing_plant(spec=None, target=None, X_GO=None):
    """The robot alone (or with the target welded to its grasp frame at X_GO), finalized,
    for TOPPRA; the returned plant has exactly the robot's 13 positions."""
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlantSceneGraph(builder, time_step=0.0)
    parser = Parser(plant)
    package_map = parser.package_map()
    if package_map.Contains("drake_models"):
        package_map.Remove("drake_models")
    package_map.AddPackageXml(ROBOT_PACKAGE_XML)
    (robot,) = parser.AddModels(url=ROBOT_URL)
    if X_GO is not None:
        package_map.AddPackageXml(spec.package_xml)
        parser.SetAutoRenaming(True)
        (held,) = parser.AddModels(url=spec.add_model(target).file)
        (body_index,) = plant.GetBodyIndices(held)
        plant.WeldFrames(plant.GetFrameByName("grasp_frame", robot),
                         plant.get_body(body_index).body_frame(), X_GO)
    plant.Finalize()
    return plant, robot
