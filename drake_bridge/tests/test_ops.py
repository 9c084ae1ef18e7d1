"""The bridge operations on hand-written scenes with known answers."""

import pytest

from drake_bridge import ops
from drake_bridge.errors import BadRequest, FileMissing, ModelError
from drake_bridge.tests.conftest import write_scene


def test_load_reports_instances_free_bodies_and_poses(overlapping_scene):
    result = ops.call("load", overlapping_scene)
    names = {m["name"]: m for m in result["model_instances"]}
    assert set(names) == {"floor", "box_a", "box_b", "box_far"}
    assert names["floor"]["welded"] is True
    assert names["box_a"]["welded"] is False
    pose = names["box_b"]["free_bodies"]["body"]
    assert pose["xyz"] == pytest.approx([0.196, 0.0, 0.1])
    assert pose["wxyz"] == pytest.approx([1.0, 0.0, 0.0, 0.0])
    assert result["num_bodies"] == 4
    assert result["num_collision_geometries"] == 4


def test_plant_is_cached_by_content(overlapping_scene):
    ops.CACHE._entries.clear()
    misses = ops.CACHE.misses
    ops.call("load", overlapping_scene)
    ops.call("load", overlapping_scene)
    assert ops.CACHE.misses == misses + 1
    assert ops.CACHE.hits >= 1


def test_penetrations_find_the_known_overlap(overlapping_scene):
    pairs = ops.call("penetrations", dict(overlapping_scene, threshold=1e-4))["pairs"]
    assert [(p["a"], p["b"]) for p in pairs] == [("box_a", "box_b")]
    assert pairs[0]["depth"] == pytest.approx(0.004, abs=1e-6)


def test_collision_report_counts_objects_not_architecture(overlapping_scene):
    report = ops.call("collision_report", dict(overlapping_scene, static_instances=["floor"]))
    assert report["objects"] == 3
    assert report["penetrating_objects"] == ["box_a", "box_b"]
    assert report["col_percent"] == pytest.approx(200.0 / 3.0)
    assert report["max_depth_m"] == pytest.approx(0.004, abs=1e-6)


def test_collision_report_never_counts_the_static_floor(tmp_path):
    # Pairs name their instances in sorted order, so the floor ("m_floor") is "b" of one pair
    # and "a" of the other: a set difference that binds to one side only shows.
    scene = write_scene(tmp_path, [
        ("box_low", (0.0, 0.0, 0.097), (0.2, 0.2, 0.2), False),
        ("m_floor", (0.0, 0.0, -0.05), (4.0, 4.0, 0.1), True),
        ("sunk_box", (1.0, 0.0, 0.095), (0.2, 0.2, 0.2), False),
    ])
    report = ops.call("collision_report", dict(scene, static_instances=["m_floor"]))
    assert sorted((p["a"], p["b"]) for p in report["pairs"]) == [
        ("box_low", "m_floor"), ("m_floor", "sunk_box")]
    assert report["objects"] == 2
    assert report["penetrating_objects"] == ["box_low", "sunk_box"]
    assert report["col_percent"] == pytest.approx(100.0)
    assert report["max_depth_m"] == pytest.approx(0.005, abs=1e-6)


def test_pose_override_resolves_the_overlap(overlapping_scene):
    args = dict(overlapping_scene,
                poses={"box_b": {"body": {"xyz": [0.25, 0.0, 0.1], "wxyz": [1, 0, 0, 0]}}})
    assert ops.call("penetrations", args)["pairs"] == []


def test_errors_are_actionable(tmp_path, overlapping_scene):
    with pytest.raises(BadRequest, match="missing field 'directives'"):
        ops.call("load", {})
    with pytest.raises(FileMissing, match="not found"):
        ops.call("load", {"directives": str(tmp_path / "nope.yaml")})
    broken = tmp_path / "broken.dmd.yaml"
    broken.write_text("directives:\n- add_model:\n    name: x\n    file: package://bridge_test/none.sdf\n")
    with pytest.raises(ModelError, match="broken.dmd.yaml"):
        ops.call("load", {"directives": str(broken), "package_xml": overlapping_scene["package_xml"]})
    with pytest.raises(BadRequest, match="no model instance"):
        ops.call("penetrations", dict(overlapping_scene, poses={"ghost": {}}))


def test_versions_lists_solvers():
    v = ops.call("versions", {})
    assert v["drake"].count(".") == 2
    assert set(v["snopt"]) == {"available", "enabled"}
