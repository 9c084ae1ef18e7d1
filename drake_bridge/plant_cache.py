"""Finalized plants built from a directives file, cached by content so a scene is parsed once."""

import hashlib
import os
from collections import OrderedDict

from pydrake.all import (
    AddMultibodyPlantSceneGraph,
    DiagramBuilder,
    Parser,
)

from drake_bridge.directives import add_directives
from drake_bridge.errors import FileMissing, ModelError


class LoadedScene:
    """A built diagram with its plant, scene graph and a default context."""

    def __init__(self, diagram, plant, scene_graph, directives_path, time_step):
        self.diagram = diagram
        self.plant = plant
        self.scene_graph = scene_graph
        self.directives_path = directives_path
        self.time_step = time_step
        self.context = diagram.CreateDefaultContext()

    def plant_context(self, context=None):
        return self.plant.GetMyContextFromRoot(context or self.context)

    def scene_graph_context(self, context=None):
        return self.scene_graph.GetMyContextFromRoot(context or self.context)


def existing_file(path, what):
    """The absolute path of an existing file; FileMissing naming `what` otherwise."""
    if path is None:
        return None
    path = os.path.abspath(path)
    if not os.path.isfile(path):
        raise FileMissing(f"{what} file not found: {path}")
    return path


def _digest(paths):
    h = hashlib.blake2b(digest_size=16)
    for p in paths:
        if p is None:
            h.update(b"-")
            continue
        h.update(p.encode())
        with open(p, "rb") as f:
            h.update(f.read())
    return h.hexdigest()


def build_scene(directives_path, package_xml=None, time_step=1e-3):
    """Parses a directives file into a finalized plant (not cached)."""
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=time_step)
    parser = Parser(plant)
    # Never let Drake try to download its remote model package: this machine is offline.
    if parser.package_map().Contains("drake_models"):
        parser.package_map().Remove("drake_models")
    if package_xml is None:
        candidate = os.path.join(os.path.dirname(directives_path), "package.xml")
        if os.path.isfile(candidate):
            package_xml = candidate
    if package_xml is not None:
        parser.package_map().AddPackageXml(package_xml)
    try:
        # The same plant as `ProcessModelDirectives` builds, each SDFormat file parsed from
        # its text (see drake_bridge/directives.py): a 230-object room loads in 0.7 s, not 7 s.
        add_directives(plant, parser, directives_path)
        plant.Finalize()
    except (RuntimeError, OSError) as e:
        raise ModelError(f"Drake could not load {directives_path}: {e}") from e
    diagram = builder.Build()
    return LoadedScene(diagram, plant, scene_graph, directives_path, time_step)


class PlantCache:
    """Least-recently-used cache of built scenes keyed by file content."""

    def __init__(self, capacity=8):
        self.capacity = capacity
        self._entries = OrderedDict()
        self.hits = 0
        self.misses = 0

    def get(self, files, time_step=1e-3):
        """The plant of `files` (a protocol.SceneFiles)."""
        directives = existing_file(files.directives, "directives")
        package_xml = existing_file(files.package_xml, "package_xml")
        key = (_digest([directives, package_xml]), time_step)
        if key in self._entries:
            self._entries.move_to_end(key)
            self.hits += 1
            return self._entries[key]
        self.misses += 1
        loaded = build_scene(directives, package_xml, time_step)
        self._entries[key] = loaded
        while len(self._entries) > self.capacity:
            self._entries.popitem(last=False)
        return loaded


#: The plants of the `load`, `penetrations`, `collision_report` and `project` requests.
CACHE = PlantCache()
