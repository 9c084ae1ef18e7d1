"""scenesmith: a text prompt in, a simulation-ready indoor scene out.

    import scenesmith
    scene = scenesmith.generate("a bedroom with a bed", "out/bedroom", seed=0)
    plant, scene_graph = AddMultibodyPlantSceneGraph(DiagramBuilder(), 0.0)
    instances = scene.add_to_plant(plant)

`generate`, `evaluate` and `export` run the Rust library in-process (the GIL is released while
they work) and use the same Drake bridge and files as the `scenesmith` CLI; a scene directory
written by either loads with `scenesmith.load(dir)`.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from . import _native
from ._native import PromptError, ScenesmithError

__all__ = ["Scene", "generate", "load", "evaluate", "export", "ScenesmithError", "PromptError"]


@dataclass
class Scene:
    """A scene directory and what it holds.

    `paths` maps a file's role to its path: `directives` (scene.dmd.yaml),
    `directives_furniture_welded`, `package_xml`, `scene_json`, `metrics`, and the exports
    `mjcf`, `usd`, `glb` when they were written. `objects` are scene.json's objects (id,
    category, kind, room, asset, world_from_object, support, welded); `metrics` is metrics.json
    (empty when absent); `summary` is what `generate` reported (None for `load`)."""

    dir: Path
    package_name: str
    paths: dict[str, Path]
    objects: list[dict[str, Any]]
    metrics: dict[str, Any]
    summary: dict[str, Any] | None = field(default=None, repr=False)

    def add_to_plant(self, plant, parser=None) -> dict[str, Any]:
        """Registers the scene's package with `parser` (a new `Parser(plant)` when None) and
        processes its model directives into `plant` (not yet finalized). Returns the model
        instances the directives added, by model name, in the order they were added."""
        from pydrake.multibody.parsing import (
            LoadModelDirectives,
            Parser,
            ProcessModelDirectives,
        )

        if parser is None:
            parser = Parser(plant)
        packages = parser.package_map()
        if not packages.Contains(self.package_name):
            packages.AddPackageXml(str(self.paths["package_xml"]))
        elif Path(packages.GetPath(self.package_name)).resolve() != self.dir:
            # Two scenes whose directories share a name: the directives would silently load
            # the other scene's assets.
            raise ScenesmithError(
                f"the parser already maps package {self.package_name!r} to "
                f"{packages.GetPath(self.package_name)}, not {self.dir}; use a new Parser "
                f"(or scene directories with different names)")
        directives = LoadModelDirectives(str(self.paths["directives"]))
        infos = ProcessModelDirectives(directives, plant, parser)
        return {info.model_name: info.model_instance for info in infos}


_FILES = {
    "directives": "scene.dmd.yaml",
    "directives_furniture_welded": "scene_furniture_welded.dmd.yaml",
    "package_xml": "package.xml",
    "scene_json": "scene.json",
    "metrics": "metrics.json",
    "mjcf": "export/mujoco/scene.xml",
    "usd": "export/usd/scene.usda",
    "glb": "export/scene.glb",
}


def load(dir: str | os.PathLike, summary: dict[str, Any] | None = None) -> Scene:
    """The scene in `dir` (a directory `generate` or the CLI wrote)."""
    root = Path(dir).resolve()
    scene_json = root / "scene.json"
    if not scene_json.is_file():
        raise ScenesmithError(f"{root} is not a scene directory (no scene.json)")
    state = json.loads(scene_json.read_text())
    metrics_path = root / "metrics.json"
    metrics = json.loads(metrics_path.read_text()) if metrics_path.is_file() else {}
    paths = {role: root / rel for role, rel in _FILES.items() if (root / rel).is_file()}
    return Scene(root, state["package_name"], paths, state["objects"], metrics, summary)


def generate(prompt: str, out: str | os.PathLike, seed: int = 0, *, render: bool = True,
             stb: bool = True, drake_check: bool = True, exports: str = "all",
             lenient: bool = False, resume: bool = False) -> Scene:
    """Generates the scene of `prompt` into the directory `out` (the same files as
    `scenesmith generate PROMPT --out OUT --seed SEED`). `render=False` skips the annotated
    views, `stb=False` the stability simulations of metrics.json, `drake_check=False` loading
    the result in Drake; `exports` is "all", "none" or a comma-separated list of mjcf, usd,
    glb. Raises PromptError for a prompt the reader refuses, ScenesmithError otherwise."""
    summary = json.loads(_native.generate(str(prompt), os.fspath(out), seed, render, stb,
                                          drake_check, exports, lenient, resume))
    return load(out, summary)


def evaluate(dir: str | os.PathLike, *, stb: bool = True) -> dict[str, Any]:
    """Recomputes the metrics of the scene in `dir`, writes metrics.json and returns it."""
    return json.loads(_native.evaluate(os.fspath(dir), stb))


def export(dir: str | os.PathLike, formats: str = "all") -> list[dict[str, Any]]:
    """Writes the exports `formats` ("all" or a comma-separated list of mjcf, usd, glb) of
    the scene in `dir` into `dir/export`; returns what was written (format, main_file, files,
    bytes)."""
    return json.loads(_native.export(os.fspath(dir), formats))
