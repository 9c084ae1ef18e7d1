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
    LoadModelDirectives,
    Parser,
    ProcessModelDirectives,
    RigidTransform,
)
from pydrake.common.eigen_geometry import Quaternion
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig

from drake_bridge.errors import BadRequest, ModelError
from drake_bridge.plant_cache import LoadedScene, _digest, _file_arg

#: Defaults of the `contact` argument (`approximation` None: Drake's default).
DEFAULT_CONTACT = {
    "model": "as_written",
    "approximation": None,
}


def contact_config(args):
    """The validated `contact` argument merged over the defaults."""
    given = args.get("contact") or {}
    if not isinstance(given, dict):
        raise BadRequest("contact must be an object")
    unknown = set(given) - set(DEFAULT_CONTACT)
    if unknown:
        raise BadRequest(f"unknown contact keys {sorted(unknown)}; known: {sorted(DEFAULT_CONTACT)}")
    cfg = dict(DEFAULT_CONTACT, **given)
    if cfg["model"] not in ("as_written", "point"):
        raise BadRequest("contact.model must be 'as_written' or 'point'")
    if cfg["approximation"] not in (None, "lagged", "similar", "sap", "tamsi"):
        raise BadRequest("contact.approximation must be null, lagged, similar, sap or tamsi")
    return cfg


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


def build_sim_scene(directives_path, package_xml, cfg, time_step):
    builder = DiagramBuilder()
    config = MultibodyPlantConfig(time_step=time_step)
    if cfg["model"] == "point":
        config.contact_model = "point"
    if cfg["approximation"] is not None:
        config.discrete_contact_approximation = cfg["approximation"]
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
        ProcessModelDirectives(LoadModelDirectives(directives_path), plant, parser)
        plant.Finalize()
    except RuntimeError as e:
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

    def get(self, args, cfg, time_step):
        directives = _file_arg(args, "directives")
        package_xml = _file_arg(args, "package_xml", required=False)
        key = (_digest([directives, package_xml]), tuple(sorted(cfg.items())), time_step)
        if key in self._entries:
            self._entries.move_to_end(key)
            self.hits += 1
            return self._entries[key]
        self.misses += 1
        loaded = build_sim_scene(directives, package_xml, cfg, time_step)
        self._entries[key] = loaded
        while len(self._entries) > self.capacity:
            self._entries.popitem(last=False)
        return loaded


SIM_CACHE = SimCache()


def pose_json(X):
    q = X.rotation().ToQuaternion()
    return {"xyz": [float(v) for v in X.translation()],
            "wxyz": [float(q.w()), float(q.x()), float(q.y()), float(q.z())]}


def pose_from_json(pose, where):
    try:
        w, x, y, z = (float(v) for v in pose["wxyz"])
        xyz = np.array([float(v) for v in pose["xyz"]], dtype=float)
        if xyz.shape != (3,):
            raise ValueError("xyz needs three numbers")
        q = Quaternion(w, x, y, z)
        if abs(np.linalg.norm([w, x, y, z]) - 1.0) > 1e-6:
            raise ValueError("quaternion is not unit length")
        return RigidTransform(q, xyz)
    except (KeyError, TypeError, ValueError) as e:
        raise BadRequest(f"bad pose for {where}: {e}") from e


def apply_poses(plant, plant_context, poses):
    """Sets free-body poses from {"instance": {"body": {xyz, wxyz}}}."""
    if poses is None:
        return
    if not isinstance(poses, dict):
        raise BadRequest("poses must map instance names to {body: {xyz, wxyz}}")
    for inst_name, bodies in poses.items():
        if not plant.HasModelInstanceNamed(inst_name):
            raise BadRequest(f"no model instance named {inst_name!r}")
        if not isinstance(bodies, dict):
            raise BadRequest(f"poses[{inst_name!r}] must map body names to poses")
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


def number(args, key, default, lo=None, hi=None):
    v = args.get(key, default)
    if not isinstance(v, (int, float)) or isinstance(v, bool) or not np.isfinite(v):
        raise BadRequest(f"{key} must be a number")
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise BadRequest(f"{key} must lie in [{lo}, {hi}]")
    return float(v)
