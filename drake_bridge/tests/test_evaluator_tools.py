"""The LLM evaluator's tools through the bridge op `evaluator_tool` (llm_tools.run_tool, vision),
on test_evaluator.py's scene of boxes (collision geometry only, so the renderer draws it from
its collision geometry).

Every reply goes through `ops.call`, which validates it against protocol.EvalToolReply.
"""

import base64
import json
import math
import os
import struct
import zlib

import numpy as np
import pytest

from drake_bridge import ops, robot_ops
from drake_bridge.errors import BadRequest
from drake_bridge.evaluator.llm_tools import clean
from drake_bridge.tests.test_evaluator import OBJECTS, scene_dir  # noqa: F401 (fixture)

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _call(scene_dir, tool, directives="scene.dmd.yaml", **kw):  # noqa: F811
    reply = ops.call("evaluator_tool", dict(scene_dir=str(scene_dir), directives=directives,
                                            tool=tool, **kw))
    return json.loads(reply["result_json"]), reply["images"]


def _decode_png(png):
    """H x W x 4 uint8 of an 8-bit RGBA PNG whose rows are unfiltered (as png_bytes writes)."""
    assert png[:8] == PNG_SIGNATURE
    pos, idat, size = 8, b"", None
    while pos < len(png):
        (length,), kind = struct.unpack(">I", png[pos:pos + 4]), png[pos + 4:pos + 8]
        data = png[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", data[:10])
            assert (depth, colour) == (8, 6)
            size = (width, height)
        elif kind == b"IDAT":
            idat += data
        pos += 12 + length
    width, height = size
    rows = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(height, 1 + 4 * width)
    assert np.all(rows[:, 0] == 0)
    return rows[:, 1:].reshape(height, width, 4)


def _images(images):
    return {i["name"]: _decode_png(base64.b64decode(i["png_base64"])) for i in images}


def test_the_op_is_registered_with_its_protocol_types():
    assert ops.OPS["evaluator_tool"] is robot_ops.op_evaluator_tool
    assert robot_ops.OPS["evaluator_tool"] is robot_ops.op_evaluator_tool


def test_list_objects_filters_by_category(scene_dir):  # noqa: F811
    result, images = _call(scene_dir, "list_objects")
    assert [o["id"] for o in result["objects"]] == list(OBJECTS) and images == []
    result, _ = _call(scene_dir, "list_objects", category="table")
    assert result["objects"] == [{"id": "table_0", "category": "table", "kind": "furniture"}]
    result, _ = _call(scene_dir, "list_objects", category="giraffe")
    assert result["objects"] == [] and "mug" in result["note"]


def test_state_tools_measure_the_scene(scene_dir):  # noqa: F811
    info, _ = _call(scene_dir, "get_object_info", object_id="mug_0")
    assert info["mass_kg"] == pytest.approx(0.3) and info["free"] is True
    assert info["world_aabb"]["min"] == pytest.approx([0.16, 0.01, 0.77])
    distance, _ = _call(scene_dir, "get_distance", object_id="mug_0", other_id="table_0")
    assert abs(distance["signed_distance_m"]) < 1e-4
    apart, _ = _call(scene_dir, "get_distance", object_id="crate_0", other_id="table_0")
    assert apart["signed_distance_m"] == pytest.approx(math.hypot(1.375, 1.575), abs=1e-4)
    relation, _ = _call(scene_dir, "get_spatial_relation", object_id="mug_0",
                        other_id="table_0")
    assert "above" in relation["relations"]
    support, _ = _call(scene_dir, "get_support", object_id="mug_0")
    assert support["supported"] is True
    assert [s["id"] for s in support["supporters"]] == ["table_0"]
    assert support["supporters"][0]["category"] == "table"


def test_results_are_rounded_plain_json():
    # A NaN normal (Drake gives none where faces touch exactly) must not reach json.dumps.
    value = clean({"d": np.float64(0.123456789), "n": [np.nan, -np.inf, np.float32(-1e-9)],
                   "ok": np.bool_(True), "k": np.int64(3), "v": np.array([1.0, 2.5])})
    assert value == {"d": 0.1235, "n": [None, None, 0.0], "ok": True, "k": 3, "v": [1.0, 2.5]}
    assert json.dumps(value, allow_nan=False) == ('{"d": 0.1235, "n": [null, null, 0.0], '
                                                  '"ok": true, "k": 3, "v": [1.0, 2.5]}')


def test_the_after_directives_are_their_own_state(scene_dir):  # noqa: F811
    support, _ = _call(scene_dir, "get_support", object_id="mug_0",
                       directives=os.path.join(str(scene_dir), "after_test.dmd.yaml"))
    assert [s["id"] for s in support["supporters"]] == ["floor_0"]


@pytest.mark.parametrize("tool,kw,words", [
    ("get_support", {"object_id": "giraffe_0"}, ["'giraffe_0'", "mug_0"]),
    ("get_object_info", {}, ["needs object_id"]),
    ("get_distance", {"object_id": "mug_0"}, ["needs other_id"]),
    ("get_distance", {"object_id": "mug_0", "other_id": "mugg_0"}, ["'mugg_0'", "mug_0"]),
    ("get_spatial_relation", {"object_id": "mug_0", "other_id": "mug_0"},
     ["two different objects", "'mug_0'"]),
    ("observe_objects", {}, ["needs object_ids"]),
    ("observe_objects", {"object_ids": ["mug_0", "zebra_1"]}, ["'zebra_1'"]),
])
def test_bad_arguments_are_errors_the_model_reads(scene_dir, tool, kw, words):  # noqa: F811
    result, images = _call(scene_dir, tool, **kw)
    assert set(result) == {"error"} and images == []
    for word in words:
        assert word in result["error"]


def test_a_missing_scene_directory_is_a_bad_request(tmp_path):
    with pytest.raises(BadRequest, match="scene directory not found"):
        _call(tmp_path / "nowhere", "list_objects")


def test_states_are_cached_by_file_and_mtime(scene_dir):  # noqa: F811
    _call(scene_dir, "list_objects")
    key = next(reversed(robot_ops._TOOL_STATES))
    state = robot_ops._TOOL_STATES[key]
    _call(scene_dir, "get_support", object_id="mug_0")
    assert robot_ops._TOOL_STATES[key] is state
    # A rewritten directives file (new mtime) is a new state; at most two are kept.
    path = os.path.join(str(scene_dir), "scene.dmd.yaml")
    stat = os.stat(path)
    os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns + 10**9))
    try:
        _call(scene_dir, "list_objects")
        assert key not in list(robot_ops._TOOL_STATES)[-1:]
        _call(scene_dir, "list_objects", directives="after_test.dmd.yaml")
        assert len(robot_ops._TOOL_STATES) == robot_ops.TOOL_STATES_KEPT
    finally:
        os.utime(path, ns=(stat.st_atime_ns, stat.st_mtime_ns))


def test_observe_scene_draws_the_room(scene_dir):  # noqa: F811
    result, images = _call(scene_dir, "observe_scene")
    pictures = _images(images)
    assert list(pictures) == ["scene_top", "scene_oblique"]
    assert [v["image"] for v in result["views"]] == list(pictures)
    for rgba in pictures.values():
        assert rgba.shape == (384, 512, 4)
        assert len(np.unique(rgba[:, :, :3].reshape(-1, 3), axis=0)) > 20


def test_observe_objects_frames_and_outlines_the_asked_object(scene_dir):  # noqa: F811
    mug, mug_images = _call(scene_dir, "observe_objects", object_ids=["mug_0"])
    crate, crate_images = _call(scene_dir, "observe_objects", object_ids=["crate_0"])
    assert mug["outline_colours"] == {"mug_0": "red"}
    for result in (mug, crate):
        assert [v["image"] for v in result["views"]] == ["objects_oblique", "objects_top"]
        for view in result["views"]:
            # Framed with a margin: the object fills a good part of the image, not all of it.
            pixels = next(iter(view["visible_pixels"].values()))
            assert 0.01 * 512 * 384 < pixels < 0.6 * 512 * 384
    mug_pictures, crate_pictures = _images(mug_images), _images(crate_images)
    red = np.array([230, 25, 35])
    for name, rgba in mug_pictures.items():
        assert rgba.shape == (384, 512, 4)
        assert len(np.unique(rgba[:, :, :3].reshape(-1, 3), axis=0)) > 5
        assert np.any(np.all(rgba[:, :, :3] == red, axis=2)), f"{name} has no red outline"
        # The framed object sits at the image centre; a mug and a crate look different there.
        centre = (slice(172, 212), slice(236, 276), slice(0, 3))
        difference = np.abs(rgba[centre].astype(int) - crate_pictures[name][centre].astype(int))
        assert difference.mean() > 20


def test_observe_objects_outlines_each_object_in_its_colour(scene_dir):  # noqa: F811
    result, images = _call(scene_dir, "observe_objects", object_ids=["mug_0", "table_0"])
    assert result["outline_colours"] == {"mug_0": "red", "table_0": "blue"}
    oblique = result["views"][0]["visible_pixels"]
    assert oblique["mug_0"] > 0 and oblique["table_0"] > oblique["mug_0"]
    rgba = _images(images)["objects_oblique"][:, :, :3]
    assert np.any(np.all(rgba == [230, 25, 35], axis=2))
    assert np.any(np.all(rgba == [30, 90, 230], axis=2))
