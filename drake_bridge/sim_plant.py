"""Plants for simulation (settling, stability) with a chosen contact configuration, cached by
file content and configuration; plus the pose helpers the physics ops share.

The bridge injects no contact model: the scene files declare theirs (every collision geometry
compliant hydroelastic, modulus 1e8 Pa, Hunt-Crossley dissipation >= 10 s/m; see README,
"Physics"). "as_written" loads them into Drake's default plant (`MultibodyPlantConfig()` with
the requested time step: hydroelastic with point fallback, Drake's default discrete contact
approximation), exactly as a user who follows the README does. "point" is SceneEval's protocol
(point contact on the same files), for comparison with published numbers.
"""

import os
from collections import OrderedDict

import numpy as np
from pydrake.all import (
    DiagramBuilder,
    Parser,
    RigidTransform,
)
from pydrake.common.eigen_geometry import Quaternion
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig

from drake_bridge.directives import add_directives
from drake_bridge.errors import BadRequest, ModelError
from drake_bridge.plant_cache import LoadedScene, _digest, existing_file
from drake_bridge.protocol import Pose

def is_free(body):
    """True for a floating base body (the API was renamed in drake 1.52)."""
    if hasattr(body, "is_floating_base_body"):
        return body.is_floating_base_body()
    return body.is_floating()


def free_bodies(plant):
    """Every floating base body, in body-index order."""
    return [plant.get_body(i) for i in plant.GetFloatingBaseBodies()]


def instance_name(plant, body):
    return plant.GetModelInstanceName(body.model_instance())


def build_sim_scene(directives_path, package_xml, contact, time_step):
    """A finalized plant of a directives file with `contact` (a protocol.ContactArgs)."""
    builder = DiagramBuilder()
    config = MultibodyPlantConfig(time_step=time_step)
    if contact.model == "point":
        config.contact_model = "point"
    if contact.approximation is not None:
        config.discrete_contact_approximation = contact.approximation
    plant, scene_graph = AddMultibodyPlant(config, builder)
    parser = Parser(plant)
    if parser.package_map().Contains("drake_models"):
        parser.package_map().Remove("drake_models")
    if package_xml is None:
        candidate = os.path.join(os.path.dirname(directives_path), "package.xml")
        if os.path.isfile(candidate):
            package_xml = candidate
    if package_xml is not None:
        parser.package_map().AddPackageXml(package_xml)
    try:
        add_directives(plant, parser, directives_path)
        plant.Finalize()
    except (RuntimeError, OSError) as e:
        raise ModelError(f"Drake could not load {directives_path}: {e}") from e
    diagram = builder.Build()
    return LoadedScene(diagram, plant, scene_graph, directives_path, time_step)


class SimCache:
    """Least-recently-used cache of simulation plants keyed by file content and configuration."""

    def __init__(self, capacity=4):
        self.capacity = capacity
        self._entries = OrderedDict()
        self.hits = 0
        self.misses = 0

    def get(self, files, contact, time_step):
        """The plant of `files` (protocol.SceneFiles) with `contact` (protocol.ContactArgs)."""
        directives = existing_file(files.directives, "directives")
        package_xml = existing_file(files.package_xml, "package_xml")
        key = (_digest([directives, package_xml]), contact.model, contact.approximation, time_step)
        if key in self._entries:
            self._entries.move_to_end(key)
            self.hits += 1
            return self._entries[key]
        self.misses += 1
        loaded = build_sim_scene(directives, package_xml, contact, time_step)
        self._entries[key] = loaded
        while len(self._entries) > self.capacity:
            self._entries.popitem(last=False)
        return loaded


SIM_CACHE = SimCache()


def pose_json(X):
    """A RigidTransform as a protocol.Pose."""
    q = X.rotation().ToQuaternion()
    return Pose(xyz=tuple(float(v) for v in X.translation()),
                wxyz=(float(q.w()), float(q.x()), float(q.y()), float(q.z())))


def pose_from_json(pose, where):
    """A protocol.Pose as a RigidTransform; BadRequest unless its quaternion is unit length."""
    w, x, y, z = pose.wxyz
    if abs(np.linalg.norm([w, x, y, z]) - 1.0) > 1e-6:
        raise BadRequest(f"bad pose for {where}: quaternion is not unit length")
    return RigidTransform(Quaternion(w, x, y, z), np.array(pose.xyz, dtype=float))


def apply_poses(plant, plant_context, poses):
    """Sets free-body poses from a protocol.Poses (instance -> body -> Pose), if given."""
    if poses is None:
        return
    for inst_name, bodies in poses.items():
        if not plant.HasModelInstanceNamed(inst_name):
            raise BadRequest(f"no model instance named {inst_name!r}")
        mi = plant.GetModelInstanceByName(inst_name)
        for body_name, pose in bodies.items():
            if not plant.HasBodyNamed(body_name, mi):
                raise BadRequest(f"no body {body_name!r} in {inst_name!r}")
            body = plant.GetBodyByName(body_name, mi)
            if not is_free(body):
                raise BadRequest(f"{inst_name}::{body_name} is not a free body")
            plant.SetFreeBodyPose(plant_context, body, pose_from_json(pose, f"{inst_name}::{body_name}"))


def free_poses(plant, plant_context, bodies):
    out = {}
    for b in bodies:
        out.setdefault(instance_name(plant, b), {})[b.name()] = pose_json(
            plant.EvalBodyPoseInWorld(plant_context, b))
    return out
