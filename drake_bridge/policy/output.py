"""The files an episode writes, each by one writer, each to a temporary file then renamed:

- `after_<policy>.dmd.yaml`: the scene's own directives (loaded with Drake's
  `LoadModelDirectives`) with the target's `default_free_body_pose` replaced by its simulated
  final pose, written back by Drake's `yaml_dump_typed`; it loads like scene.dmd.yaml (with the
  scene's package.xml). Welded instances did not move, so their poses stay as they were.
- `frame_<policy>_<k>_<label>.png`: rendered frames (8-bit RGBA PNG, zlib from the stdlib).
- `rollout_<policy>.html`: the flipbook animation (frames.py; a self-contained page).
- `episode_<policy>.json`: `dataclasses.asdict(EpisodeResult)`.
"""

import copy
import dataclasses as dc
import json
import os
import struct
import zlib

import numpy as np
from pydrake.common.schema import Rotation, Transform
from pydrake.common.yaml import yaml_dump_typed
from pydrake.math import RollPitchYaw


def _write_atomic(path, data, mode="w"):
    tmp = path + ".tmp"
    with open(tmp, mode) as f:
        f.write(data)
    os.replace(tmp, path)


def write_after_directives(spec, target, body_name, X_WO, path):
    """The scene's directives with `target`'s free-body pose set to X_WO (see module doc)."""
    directives = copy.deepcopy(spec.directives)
    for directive in directives.directives:
        add_model = directive.add_model
        if add_model is not None and add_model.name == target:
            transform = Transform()
            transform.base_frame = "world"
            transform.translation = X_WO.translation()
            transform.rotation = Rotation(RollPitchYaw(X_WO.rotation()))
            poses = dict(add_model.default_free_body_pose)
            poses[body_name] = transform
            add_model.default_free_body_pose = poses
    header = (f"# {os.path.basename(path)}: {spec.directives_path} after the rollout; only "
              f"{target} moved (the policy welded every other instance).\n")
    _write_atomic(path, header + yaml_dump_typed(directives))


def write_png(path, rgba):
    """An H x W x 4 uint8 array as an RGBA PNG file."""
    _write_atomic(path, png_bytes(rgba), mode="wb")


def png_bytes(rgba):
    """An H x W x 4 uint8 array as the bytes of an RGBA PNG."""
    rgba = np.ascontiguousarray(rgba, dtype=np.uint8)
    height, width = rgba.shape[:2]
    raw = b"".join(b"\x00" + rgba[y].tobytes() for y in range(height))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    return (b"\x89PNG\r\n\x1a\n" +
            chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


def write_json(path, result):
    _write_atomic(path, json.dumps(dc.asdict(result), indent=1) + "\n")


def write_text(path, text):
    _write_atomic(path, text)
