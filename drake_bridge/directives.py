"""Loads a model directives file into a plant, each SDFormat file parsed from its text.

Drake's `ProcessModelDirectives` parses every `add_model` by file name, and libsdformat's file
loader rebuilds its whole schema description on each call: about 20 ms a file, whatever the
file holds (measured on drake 1.58: a one-box model 21.8 ms by file name, 0.9 ms from the same
text). A 200-object room is parsed in every settle subset and stability island under both
contact models, so that was a fifth of a run's bridge time. Here each file is read, its
relative URIs made absolute and its top-level model given the directive's name, and parsed
with `Parser.AddModelsFromString`; the poses, joint positions and welds follow the directives
as `ProcessModelDirectives` applies them. The plant holds the same models, geometries,
proximity properties and default state, in the same order (`tests/test_directives.py`
compares both plants body by body and their simulations step by step).

Directives this module does not know (`add_frame`, `add_directives`, collision filter groups,
model instances, a pose relative to another frame, a non-SDFormat file, a file with several
models) send the whole file through `ProcessModelDirectives` instead.
"""

import os
import re

from pydrake.all import LoadModelDirectives, ProcessModelDirectives

_URI = re.compile(r"<uri>\s*([^<]*?)\s*</uri>")
_MODEL = re.compile(r"<model\s+name\s*=\s*\"[^\"]*\"")


def _absolute_uris(text, base_dir):
    """`text` with every `<uri>` that is a path made a `file://` URI, relative ones under
    `base_dir` (Drake refuses paths in a model parsed from a string)."""

    def absolute(m):
        uri = m.group(1)
        if "://" in uri:
            return m.group(0)
        return f"<uri>file://{os.path.normpath(os.path.join(base_dir, uri))}</uri>"

    return _URI.sub(absolute, text)


def _model_text(path, name):
    """The SDFormat text of `path` with its only model named `name`, or None when the file
    holds no or several models."""
    with open(path, encoding="utf-8") as f:
        text = f.read()
    if len(_MODEL.findall(text)) != 1 or text.count("<model") != 1:
        return None
    text = _MODEL.sub(f'<model name="{name}"', text, count=1)
    return _absolute_uris(text, os.path.dirname(path))


def _is_world(frame):
    return frame is None or frame in ("", "world")


def _plan(directives, parser):
    """Each directive as ("model", AddModel, text) or ("weld", AddWeld, None); None when one of
    them is not of the kinds handled here."""
    steps = []
    for d in directives.directives:
        if d.add_model is not None and all(
            x is None
            for x in (d.add_weld, d.add_frame, d.add_directives, d.add_model_instance,
                      d.add_collision_filter_group)):
            m = d.add_model
            if not m.file.endswith(".sdf"):
                return None
            if any(not _is_world(t.base_frame) for t in m.default_free_body_pose.values()):
                return None
            path = parser.package_map().ResolveUrl(m.file)
            text = _model_text(path, m.name)
            if text is None:
                return None
            steps.append(("model", m, text))
        elif d.add_weld is not None and all(
            x is None
            for x in (d.add_model, d.add_frame, d.add_directives, d.add_model_instance,
                      d.add_collision_filter_group)):
            steps.append(("weld", d.add_weld, None))
        else:
            return None
    return steps


def _frame(plant, scoped):
    """The frame `instance::frame` (or `world`)."""
    if scoped == "world":
        return plant.world_frame()
    instance, _, frame = scoped.rpartition("::")
    if not instance:
        return plant.GetFrameByName(frame)
    return plant.GetFrameByName(frame, plant.GetModelInstanceByName(instance))


def _set_default_pose(plant, body, X_WB):
    """The body's default pose in the world (the method was renamed in drake 1.52)."""
    if hasattr(plant, "SetDefaultFloatingBaseBodyPose"):
        plant.SetDefaultFloatingBaseBodyPose(body, X_WB)
    else:
        plant.SetDefaultFreeBodyPose(body, X_WB)


def add_directives(plant, parser, directives_path):
    """Adds the models and welds of `directives_path` to `plant` (not finalized)."""
    add_model_directives(plant, parser, LoadModelDirectives(directives_path))


def add_model_directives(plant, parser, directives):
    """Adds the models and welds of `directives` (a loaded `ModelDirectives`) to `plant` (not
    finalized), as `ProcessModelDirectives` would."""
    steps = _plan(directives, parser)
    if steps is None:
        ProcessModelDirectives(directives, plant, parser)
        return
    for kind, d, text in steps:
        if kind == "weld":
            X_PC = d.X_PC.GetDeterministicValue() if d.X_PC is not None else None
            parent, child = _frame(plant, d.parent), _frame(plant, d.child)
            if X_PC is None:
                plant.WeldFrames(parent, child)
            else:
                plant.WeldFrames(parent, child, X_PC)
            continue
        (instance,) = parser.AddModelsFromString(text, "sdf")
        for joint, q in d.default_joint_positions.items():
            plant.GetJointByName(joint, instance).set_default_positions(q)
        for body, pose in d.default_free_body_pose.items():
            _set_default_pose(plant, plant.GetBodyByName(body, instance),
                              pose.GetDeterministicValue())
