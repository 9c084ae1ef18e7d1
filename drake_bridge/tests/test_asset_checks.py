"""The asset checks on hand-written models with known outcomes."""

import pytest

from drake_bridge import ops
from drake_bridge.errors import BadRequest, FileMissing

INERTIA = "<inertia><ixx>{i}</ixx><ixy>0</ixy><ixz>0</ixz><iyy>{i}</iyy><iyz>0</iyz><izz>{i}</izz></inertia>"


def link(name, pose, box, mass=1.0, box_pose="0 0 0 0 0 0", extra=""):
    i = mass * (box[0] ** 2 + box[1] ** 2 + box[2] ** 2) / 12.0
    return f"""
    <link name="{name}"><pose>{pose}</pose>
      <inertial><pose>{box_pose}</pose><mass>{mass}</mass>{INERTIA.format(i=i)}</inertial>
      <collision name="c"><pose>{box_pose}</pose><geometry><box><size>{box[0]} {box[1]} {box[2]}</size></box></geometry></collision>
      {extra}
    </link>"""


def model(tmp_path, name, body):
    path = tmp_path / f"{name}.sdf"
    path.write_text(f'<?xml version="1.0"?><sdf version="1.9"><model name="{name}">{body}</model></sdf>')
    return {"name": name, "sdf": str(path), "footprint": 1.0}


def slide(parent, child, upper):
    return f"""<joint name="{child}_slide" type="prismatic"><parent>{parent}</parent><child>{child}</child>
      <axis><xyz>0 1 0</xyz><limit><lower>0</lower><upper>{upper}</upper><effort>100</effort></limit>
      <dynamics><damping>2</damping></dynamics></axis></joint>"""


@pytest.fixture
def crate(tmp_path):
    return model(tmp_path, "crate", link("body", "0 0 0 0 0 0", (0.4, 0.4, 0.4), 5.0, "0 0 0.2 0 0 0"))


@pytest.fixture
def topple(tmp_path):
    # A small foot with a heavy block far off to the side: the centre of mass is outside the foot.
    body = f"""<link name="body">
      <inertial><pose>0.4 0 0.5 0 0 0</pose><mass>10</mass>{INERTIA.format(i=0.1)}</inertial>
      <collision name="foot"><pose>0 0 0.05 0 0 0</pose><geometry><box><size>0.1 0.1 0.1</size></box></geometry></collision>
      <collision name="arm"><pose>0.25 0 0.5 0 0 0</pose><geometry><box><size>0.5 0.05 0.05</size></box></geometry></collision>
    </link>"""
    return model(tmp_path, "topple", body)


@pytest.fixture
def drawer_unit(tmp_path):
    body = link("body", "0 0 0 0 0 0", (0.6, 0.5, 0.1), 10.0, "0 0 0.05 0 0 0")
    body += link("drawer", "0 0 0.3 0 0 0", (0.4, 0.4, 0.1), 2.0)
    body += slide("body", "drawer", 0.3)
    return model(tmp_path, "drawer_unit", body)


@pytest.fixture
def clashing(tmp_path):
    # The "door" sits inside the body: self-collision as soon as filters are off.
    body = link("body", "0 0 0 0 0 0", (0.6, 0.5, 0.6), 10.0, "0 0 0.3 0 0 0")
    body += link("door", "0 0.2 0.3 0 0 0", (0.5, 0.2, 0.5), 2.0)
    body += slide("body", "door", 0.01)
    return model(tmp_path, "clashing", body)


def test_load_reports_every_model_and_names_the_broken_one(tmp_path, crate, drawer_unit):
    broken = model(tmp_path, "broken", link("body", "0 0 0 0 0 0", (0.2, 0.2, 0.2), -1.0))
    out = ops.call("assets_load", {"models": [crate, drawer_unit, broken]})["models"]
    assert out["crate"]["ok"] and out["crate"]["mass"] == pytest.approx(5.0)
    assert out["drawer_unit"]["joints"] == [
        {"name": "drawer_slide", "type": "prismatic", "lower": 0.0, "upper": pytest.approx(0.3)}]
    assert out["drawer_unit"]["collision_geometries"] == 2
    assert out["broken"]["ok"] is False and out["broken"]["error"]


def test_drop_keeps_a_crate_upright_and_catches_a_topple(crate, topple):
    out = ops.call("assets_drop", {"models": [crate, topple], "duration": 1.0, "time_step": 2e-3})["models"]
    assert out["crate"]["rotation_rad"] < 0.01
    assert abs(out["crate"]["vertical_m"]) < 0.005
    assert out["topple"]["rotation_rad"] > 0.3


def test_push_opens_a_drawer_to_its_limit_and_reports_self_collision(drawer_unit, clashing):
    out = ops.call("assets_push", {"models": [drawer_unit, clashing], "duration": 0.5})["models"]
    j = out["drawer_unit"]["joints"]["drawer_slide"]
    assert j["position"] == pytest.approx(0.3, abs=0.01)
    assert out["drawer_unit"]["self_penetration_m"] < 1e-3
    assert out["clashing"]["self_penetration_m"] > 0.01
    assert sorted(out["clashing"]["self_penetration_pair"]) == ["clashing::body", "clashing::door"]


def test_ops_are_registered_and_validate_arguments(tmp_path):
    for name in ("assets_load", "assets_drop", "assets_push"):
        assert name in ops.OPS
    with pytest.raises(BadRequest, match="non-empty list"):
        ops.call("assets_load", {"models": []})
    with pytest.raises(FileMissing):
        ops.call("assets_load", {"models": [{"name": "x", "sdf": str(tmp_path / "none.sdf")}]})
    with pytest.raises(BadRequest, match="duration"):
        ops.call("assets_drop", {"models": [{"name": "x", "sdf": __file__}], "duration": -1})
