"""Layout checks in Drake: drop spheres over a scene's rooms and report where they come to rest.

A generated house loads as welded architecture (floor slabs and walls); a sphere released above
each room's floor must land on that floor and stay in that room. Nothing here is cached: the
spheres are added to a fresh plant before it is finalized.
"""

import numpy as np
from pydrake.all import (
    AddMultibodyPlantSceneGraph,
    CoulombFriction,
    DiagramBuilder,
    LoadModelDirectives,
    Parser,
    ProcessModelDirectives,
    RigidTransform,
    Simulator,
    SpatialInertia,
    Sphere,
)

from drake_bridge.errors import BadRequest, ModelError
from drake_bridge.plant_cache import existing_file


def _spheres_arg(args):
    if not args.spheres:
        raise BadRequest("spheres must be a non-empty list of {name, xyz, radius}")
    for s in args.spheres:
        if not 0.01 <= s.radius <= 1.0:
            raise BadRequest(f"sphere {s.name!r}: radius must lie in [0.01, 1.0] m")
    if len({s.name for s in args.spheres}) != len(args.spheres):
        raise BadRequest("sphere names must be unique")
    return [(s.name, list(s.xyz), s.radius) for s in args.spheres]


def op_drop_spheres(args):
    """Loads the directives, adds one free sphere per request entry, simulates and reports the
    final sphere positions (and whether each came to rest)."""
    directives = existing_file(args.directives, "directives")
    package_xml = existing_file(args.package_xml, "package_xml")
    spheres = _spheres_arg(args)
    duration = args.duration
    if not 0.05 <= duration <= 10.0:
        raise BadRequest("duration must be between 0.05 and 10 s")

    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlantSceneGraph(builder, time_step=1e-3)
    parser = Parser(plant)
    if parser.package_map().Contains("drake_models"):
        parser.package_map().Remove("drake_models")
    if package_xml is not None:
        parser.package_map().AddPackageXml(package_xml)
    try:
        ProcessModelDirectives(LoadModelDirectives(directives), plant, parser)
    except RuntimeError as e:
        raise ModelError(f"Drake could not load {directives}: {e}") from e
    bodies = []
    for name, xyz, radius in spheres:
        if plant.HasModelInstanceNamed(name):
            raise BadRequest(f"sphere name {name!r} clashes with a model instance")
        instance = plant.AddModelInstance(name)
        body = plant.AddRigidBody(
            "ball", instance, SpatialInertia.SolidSphereWithMass(1.0, radius))
        plant.RegisterCollisionGeometry(
            body, RigidTransform(), Sphere(radius), "ball", CoulombFriction(0.8, 0.6))
        bodies.append((name, body, xyz, radius))
    plant.Finalize()
    diagram = builder.Build()
    simulator = Simulator(diagram)
    context = simulator.get_mutable_context()
    plant_context = plant.GetMyMutableContextFromRoot(context)
    for _, body, xyz, _ in bodies:
        plant.SetFreeBodyPose(plant_context, body, RigidTransform(np.array(xyz)))
    simulator.AdvanceTo(duration)
    result = []
    for name, body, xyz, radius in bodies:
        X = plant.EvalBodyPoseInWorld(plant_context, body)
        v = plant.EvalBodySpatialVelocityInWorld(plant_context, body)
        result.append({
            "name": name,
            "start": xyz,
            "xyz": [float(c) for c in X.translation()],
            "radius": radius,
            "speed": float(np.linalg.norm(v.translational())),
        })
    return {"spheres": result, "duration": duration}
