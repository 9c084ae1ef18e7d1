"""The export conformance ops on hand-written MJCF and USDA files with known answers."""

import pytest

from drake_bridge import ops
from drake_bridge.errors import BadRequest, FileMissing, ModelError

CUBE_OBJ = """v -0.05 -0.05 -0.05
v 0.05 -0.05 -0.05
v 0.05 0.05 -0.05
v -0.05 0.05 -0.05
v -0.05 -0.05 0.05
v 0.05 -0.05 0.05
v 0.05 0.05 0.05
v -0.05 0.05 0.05
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
"""

MJCF = """<mujoco model="t">
  <compiler angle="radian" meshdir="." autolimits="true" inertiafromgeom="false"/>
  <option cone="elliptic" impratio="10"/>
  <asset><mesh name="cube" file="cube.obj"/></asset>
  <worldbody>
    <geom name="floor" type="box" size="2 2 0.05" pos="0 0 -0.05"/>
    <body name="box_0" pos="0 0 0.05">
      <freejoint name="box_0"/>
      <inertial pos="0 0 0" mass="0.8" diaginertia="0.001 0.001 0.001"/>
      <geom name="box_0/c000" type="mesh" mesh="cube"/>
      <geom name="box_0/v0" type="mesh" mesh="cube" contype="0" conaffinity="0" group="2"/>
    </body>
    <body name="cab_0" pos="1 0 0.05">
      <inertial pos="0 0 0" mass="2" diaginertia="0.01 0.01 0.01"/>
      <geom name="cab_0/c000" type="mesh" mesh="cube"/>
      <body name="cab_0/door" pos="0 0.1 0">
        <joint name="cab_0/hinge" type="hinge" axis="0 0 -1" range="0 1.5" damping="0.1"/>
        <inertial pos="0.1 0 0" mass="0.5" diaginertia="0.001 0.001 0.001"/>
        <geom name="cab_0/door/c000" type="box" size="0.1 0.005 0.05" pos="0.1 0 0"/>
      </body>
    </body>
  </worldbody>
  <contact><exclude body1="cab_0" body2="cab_0/door"/></contact>
</mujoco>
"""


@pytest.fixture
def mjcf(tmp_path):
    (tmp_path / "cube.obj").write_text(CUBE_OBJ)
    path = tmp_path / "scene.xml"
    path.write_text(MJCF)
    return str(path)


def test_mujoco_check_reports_bodies_joints_and_stability(mjcf):
    r = ops.call("mujoco_check", {"xml": mjcf, "seconds": 1.0})
    bodies = {b["name"]: b for b in r["bodies"]}
    assert set(bodies) == {"box_0", "cab_0", "cab_0/door"}
    box = bodies["box_0"]
    assert box["free"] and not bodies["cab_0"]["free"]
    assert box["mass"] == pytest.approx(0.8)
    assert (box["collision_geoms"], box["visual_geoms"]) == (1, 1)
    lo, hi = box["collision_aabb"]
    assert lo == pytest.approx([-0.05, -0.05, 0.0], abs=1e-6)
    assert hi == pytest.approx([0.05, 0.05, 0.1], abs=1e-6)
    # Resting on the floor: it barely moves and does not turn.
    assert r["finite"] is True
    assert box["displacement_m"] < 2e-3 and box["rotation_rad"] < 1e-3
    (hinge,) = r["joints"]
    assert hinge["type"] == "hinge" and hinge["limited"]
    assert hinge["range"] == pytest.approx([0.0, 1.5])
    assert hinge["axis_world"] == pytest.approx([0.0, 0.0, -1.0])
    assert r["simulated_seconds"] == pytest.approx(1.0, abs=r["timestep"])


def test_mujoco_probe_turns_a_hinge_within_its_range(mjcf):
    opened = ops.call("mujoco_check", {"xml": mjcf, "seconds": 1.0,
                                      "probe_joints": {"cab_0/hinge": 0.5}})
    assert 0.5 < opened["probe"]["cab_0/hinge"] <= 1.5 + 0.02
    pushed = ops.call("mujoco_check", {"xml": mjcf, "seconds": 1.0,
                                      "probe_joints": {"cab_0/hinge": -0.5}})
    assert -0.02 <= pushed["probe"]["cab_0/hinge"] <= 0.01


def test_mujoco_instability_is_reported_and_nothing_is_logged_to_disk(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    path = tmp_path / "unstable.xml"
    path.write_text('<mujoco><option gravity="0 0 -1e300"/><worldbody><body><freejoint/>'
                    '<geom type="box" size="0.05 0.05 0.05"/></body></worldbody></mujoco>')
    r = ops.call("mujoco_check", {"xml": str(path), "seconds": 0.1})
    assert r["finite"] is False
    assert "mjWARN_BADQACC" in r["warnings"]
    assert any("unstable" in m for m in r["messages"])
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()
    tiny = tmp_path / "tiny_arena.xml"
    tiny.write_text('<mujoco><size memory="20K"/><worldbody><geom type="plane" size="1 1 0.1"/>'
                    + "".join(f'<body pos="0 0 {0.05 + i * 0.1}"><freejoint/>'
                              '<geom type="box" size="0.05 0.05 0.05"/></body>' for i in range(30))
                    + "</worldbody></mujoco>")
    with pytest.raises(ModelError, match="out of memory"):
        ops.call("mujoco_check", {"xml": str(tiny), "seconds": 0.1})


def test_mujoco_check_errors(tmp_path, mjcf):
    with pytest.raises(FileMissing):
        ops.call("mujoco_check", {"xml": str(tmp_path / "none.xml")})
    with pytest.raises(BadRequest, match="seconds"):
        ops.call("mujoco_check", {"xml": mjcf, "seconds": -1})
    with pytest.raises(BadRequest, match="no joint named"):
        ops.call("mujoco_check", {"xml": mjcf, "seconds": 0.1, "probe_joints": {"x": 1}})
    bad = tmp_path / "bad.xml"
    bad.write_text(MJCF.replace('mesh="cube"/>', 'mesh="nope"/>', 1))
    with pytest.raises(ModelError, match="bad.xml"):
        ops.call("mujoco_check", {"xml": str(bad)})


USDA = """#usda 1.0
(
    defaultPrim = "World"
    kilogramsPerUnit = 1
    metersPerUnit = 1
    upAxis = "Z"
    customLayerData = { string prompt = "a \\"q\\" room" }
)

def Xform "World"
{
    def PhysicsScene "PhysicsScene" {}

    def Xform "floor"
    {
        def Mesh "c000" (prepend apiSchemas = ["PhysicsCollisionAPI", "PhysicsMeshCollisionAPI"])
        {
            uniform token physics:approximation = "convexHull"
            int[] faceVertexCounts = [3, 3, 3, 3]
            int[] faceVertexIndices = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]
            point3f[] points = [(0, 0, -0.1), (1, 0, -0.1), (0, 1, -0.1), (0, 0, 0)]
        }
    }

    def Xform "cab_0"
    {
        double3 xformOp:translate = (1, 2, 0)
        uniform token[] xformOpOrder = ["xformOp:translate"]

        def Xform "body" (prepend apiSchemas = ["PhysicsRigidBodyAPI", "PhysicsMassAPI",
                                                "PhysicsArticulationRootAPI"])
        {
            float physics:mass = 3
            def Mesh "c000" (prepend apiSchemas = ["PhysicsCollisionAPI", "PhysicsMeshCollisionAPI"])
            {
                uniform token physics:approximation = "convexHull"
                int[] faceVertexCounts = [3, 3, 3, 3]
                int[] faceVertexIndices = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]
                point3f[] points = [(0, 0, 0), (0.5, 0, 0), (0, 0.5, 0), (0, 0, 0.5)]
            }
        }

        def Xform "door" (prepend apiSchemas = ["PhysicsRigidBodyAPI", "PhysicsMassAPI"])
        {
            double3 xformOp:translate = (0, 0.5, 0)
            quatd xformOp:orient = (0.9238795325112867, 0, 0, 0.3826834323650898)
            uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:orient"]
            float physics:mass = 1
            def Mesh "c000" (prepend apiSchemas = ["PhysicsCollisionAPI", "PhysicsMeshCollisionAPI"])
            {
                uniform token physics:approximation = "convexHull"
                int[] faceVertexCounts = [3, 3, 3, 3]
                int[] faceVertexIndices = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]
                point3f[] points = [(0, 0, 0), (0.4, 0, 0), (0, 0.02, 0), (0, 0, 0.4)]
            }
        }

        def PhysicsRevoluteJoint "hinge"
        {
            uniform token physics:axis = "Z"
            rel physics:body0 = </World/cab_0/body>
            rel physics:body1 = </World/cab_0/door>
            point3f physics:localPos0 = (0, 0.5, 0)
            point3f physics:localPos1 = (0, 0, 0)
            float physics:lowerLimit = 0
            float physics:upperLimit = 100
        }
    }
}
"""


def test_usd_check_reads_metadata_bodies_and_joint_state(tmp_path):
    path = tmp_path / "scene.usda"
    path.write_text(USDA)
    r = ops.call("usd_check", {"usd": str(path), "static_prims": ["/World/floor"]})
    md = r["metadata"]
    assert (md["meters_per_unit"], md["kilograms_per_unit"], md["up_axis"]) == (1.0, 1.0, "Z")
    assert md["default_prim"] == "/World"
    assert md["custom_layer_data"]["prompt"] == 'a "q" room'
    assert r["physics_scenes"] == 1
    assert set(r["bodies"]) == {"/World/cab_0/body", "/World/cab_0/door"}
    assert r["bodies"]["/World/cab_0/body"]["mass"] == pytest.approx(3.0)
    assert r["bodies"]["/World/cab_0/door"]["colliders"] == 1
    lo, hi = r["bodies"]["/World/cab_0/body"]["collision_aabb"]
    assert lo == pytest.approx([1, 2, 0]) and hi == pytest.approx([1.5, 2.5, 0.5])
    assert r["static"]["/World/floor"]["colliders"] == 1
    (joint,) = r["joints"]
    assert joint["body0_ok"] and joint["body1_ok"]
    assert joint["axis_world"] == pytest.approx([0, 0, 1], abs=1e-6)
    # The door prim is turned 45 degrees about +Z: the joint sits at +45, inside [0, 100].
    assert joint["position_measured"] == pytest.approx(45.0, abs=1e-4)
    assert joint["frame_gap_m"] < 1e-9
    assert (joint["lower"], joint["upper"]) == (0.0, 100.0)
    assert [a["path"] for a in r["articulations"]] == ["/World/cab_0/body"]
    assert r["approximations"] == {"convexHull": 3}


def test_usd_check_flags_a_joint_to_nowhere(tmp_path):
    path = tmp_path / "broken.usda"
    path.write_text(USDA.replace("rel physics:body1 = </World/cab_0/door>",
                                 "rel physics:body1 = </World/cab_0/ghost>"))
    r = ops.call("usd_check", {"usd": str(path)})
    (joint,) = r["joints"]
    assert joint["body1_ok"] is False
    assert any(f["severity"] == "Error" and "Joint" in f["message"] + f["validator"]
               for f in r["findings"]), r["findings"]


def test_usd_check_errors(tmp_path):
    with pytest.raises(FileMissing):
        ops.call("usd_check", {"usd": str(tmp_path / "none.usda")})
    bad = tmp_path / "bad.usda"
    bad.write_text("#usda 1.0\ndef Xform \"World\" {\n")
    with pytest.raises(ModelError, match="bad.usda"):
        ops.call("usd_check", {"usd": str(bad)})
    with pytest.raises(BadRequest, match="static_prims"):
        ops.call("usd_check", {"usd": str(bad), "static_prims": "x"})
