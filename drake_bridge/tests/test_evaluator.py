"""The evaluator's state tools and built-in predicates on a hand-written scene of boxes.

The scene (frames at each object's bottom centre, +z up):
- floor_0: a welded slab, top at z = 0 (kind architecture);
- table_0: welded, a 1.0 x 0.6 m top (surface at z = 0.77) on four legs;
- mug_0: a free 8 x 8 x 10 cm convex mesh resting on the table top;
- coaster_0 on the table top, cup_0 on the coaster (on the table through one object);
- crate_0: a free 30 cm box on the floor 2 m away, sunk 3 mm into the floor;
- bin_0: an open box of five thin pieces, yawed 30 deg, with block_0 inside it.
"""

import json
import math

import numpy as np
import pytest

from drake_bridge.errors import BadRequest
from drake_bridge.evaluator import (
    category_matches,
    evaluate,
    get_distance,
    get_object_info,
    get_spatial_relation,
    get_support,
    judge,
    list_objects,
    load_state,
)
from drake_bridge.evaluator.geometry import box_inside_fraction, footprint_fraction

PACKAGE = "evaluator_test"

MODEL = """<?xml version="1.0"?>
<sdf version="1.9" xmlns:drake="http://drake.mit.edu">
  <model name="{name}">
    <link name="body">
      <inertial><pose>0 0 {com_z} 0 0 0</pose><mass>{mass}</mass>
        <inertia><ixx>0.01</ixx><ixy>0</ixy><ixz>0</ixz><iyy>0.01</iyy><iyz>0</iyz><izz>0.01</izz></inertia>
      </inertial>{collisions}
    </link>
  </model>
</sdf>
"""

COLLISION = """
      <collision name="c{k}">
        <pose>{x} {y} {z} 0 0 0</pose>
        <geometry>{geometry}</geometry>
        <drake:proximity_properties>
          <drake:compliant_hydroelastic/>
          <drake:hydroelastic_modulus>1e8</drake:hydroelastic_modulus>
          <drake:hunt_crossley_dissipation>10</drake:hunt_crossley_dissipation>
          <drake:mu_dynamic>0.5</drake:mu_dynamic><drake:mu_static>0.6</drake:mu_static>
        </drake:proximity_properties>
      </collision>"""

BIN_YAW_DEG = 30.0


def _box_obj(sx, sy, sz):
    """An OBJ box with its bottom face at z = 0 (a convex collision piece, as scenes write)."""
    lines = [f"v {x} {y} {z}" for x in (-sx / 2, sx / 2) for y in (-sy / 2, sy / 2)
             for z in (0.0, sz)]
    faces = [(1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)]
    return "\n".join(lines + [f"f {a} {b} {c} {d}" for a, b, c, d in faces]) + "\n"


def _write_model(root, name, pieces=(), mesh=None, mass=1.0):
    """pieces: ((x, y, z) centre, (sx, sy, sz) size) boxes; mesh: the size of one OBJ box."""
    model_dir = root / "assets" / name
    model_dir.mkdir(parents=True)
    collisions = []
    for k, (centre, size) in enumerate(pieces):
        geometry = "<box><size>{} {} {}</size></box>".format(*size)
        collisions.append(COLLISION.format(k=k, x=centre[0], y=centre[1], z=centre[2],
                                           geometry=geometry))
    if mesh is not None:
        (model_dir / "collision_000.obj").write_text(_box_obj(*mesh))
        geometry = ("<mesh><uri>collision_000.obj</uri><drake:declare_convex/></mesh>")
        collisions.append(COLLISION.format(k=len(collisions), x=0, y=0, z=0, geometry=geometry))
    (model_dir / "model.sdf").write_text(MODEL.format(
        name=name, mass=mass, com_z=0.05, collisions="".join(collisions)))


def _box(size):
    return [((0.0, 0.0, size[2] / 2), size)]


def _bin_pieces(sx=0.4, sy=0.3, sz=0.25, t=0.01):
    wall = sz - t
    return [((0, 0, t / 2), (sx, sy, t)),
            ((sx / 2 - t / 2, 0, t + wall / 2), (t, sy, wall)),
            ((-sx / 2 + t / 2, 0, t + wall / 2), (t, sy, wall)),
            ((0, sy / 2 - t / 2, t + wall / 2), (sx - 2 * t, t, wall)),
            ((0, -sy / 2 + t / 2, t + wall / 2), (sx - 2 * t, t, wall))]


def _table_pieces():
    legs = [((x, y, 0.365), (0.05, 0.05, 0.73)) for x in (-0.45, 0.45) for y in (-0.25, 0.25)]
    return [((0, 0, 0.75), (1.0, 0.6, 0.04))] + legs


def _in_bin(x, y, z):
    """A point of the bin's frame in the world (the bin stands at (-1.5, 1.0, 0), yawed)."""
    c, s = math.cos(math.radians(BIN_YAW_DEG)), math.sin(math.radians(BIN_YAW_DEG))
    return (-1.5 + c * x - s * y, 1.0 + s * x + c * y, z)


#: id -> (category, kind, world position, yaw deg, welded)
OBJECTS = {
    "floor_0": ("floor", "architecture", (0.0, 0.0, 0.0), 0.0, True),
    "table_0": ("table", "furniture", (0.0, 0.0, 0.0), 0.0, True),
    "mug_0": ("mug", "manipuland", (0.2, 0.05, 0.77), 0.0, False),
    "coaster_0": ("coaster", "manipuland", (-0.3, 0.0, 0.77), 0.0, False),
    "cup_0": ("cup", "manipuland", (-0.3, 0.0, 0.785), 0.0, False),
    "crate_0": ("crate", "furniture", (2.0, 2.0, -0.003), 0.0, False),
    "bin_0": ("bin", "furniture", (-1.5, 1.0, 0.0), BIN_YAW_DEG, False),
    "block_0": ("block", "manipuland", _in_bin(0.05, 0.0, 0.01), BIN_YAW_DEG, False),
}


def _directives(poses):
    lines = ["directives:"]
    for name, (_, _, _, _, welded) in OBJECTS.items():
        (x, y, z), yaw = poses[name]
        pose = (f"translation: [{x}, {y}, {z}]\n"
                f"        rotation: !Rpy {{deg: [0.0, 0.0, {yaw}]}}")
        lines.append(f"- add_model:\n    name: {name}\n"
                     f"    file: package://{PACKAGE}/assets/{name}/model.sdf")
        if welded:
            lines.append(f"- add_weld:\n    parent: world\n    child: {name}::body\n"
                         f"    X_PC:\n        {pose}")
        else:
            lines.append("    default_free_body_pose:\n      body:\n        base_frame: world\n"
                         f"        {pose}")
    return "\n".join(lines) + "\n"


@pytest.fixture(scope="module")
def scene_dir(tmp_path_factory):
    root = tmp_path_factory.mktemp("evaluator_scene")
    (root / "package.xml").write_text(
        f'<?xml version="1.0"?>\n<package format="2"><name>{PACKAGE}</name>'
        '<version>0.0.0</version><description>test</description>'
        '<maintainer email="t@t">t</maintainer><license>CC0</license></package>\n')
    _write_model(root, "floor_0", [((0, 0, -0.05), (6.0, 6.0, 0.1))], mass=100.0)
    _write_model(root, "table_0", _table_pieces(), mass=20.0)
    _write_model(root, "mug_0", mesh=(0.08, 0.08, 0.10), mass=0.3)
    _write_model(root, "coaster_0", _box((0.14, 0.14, 0.015)), mass=0.05)
    _write_model(root, "cup_0", _box((0.06, 0.06, 0.09)), mass=0.2)
    _write_model(root, "crate_0", _box((0.3, 0.3, 0.3)), mass=3.0)
    _write_model(root, "bin_0", _bin_pieces(), mass=1.5)
    _write_model(root, "block_0", _box((0.08, 0.08, 0.08)), mass=0.4)
    objects = []
    for name, (category, kind, xyz, yaw, welded) in OBJECTS.items():
        objects.append({"id": name, "category": category, "kind": kind, "room": "room_0",
                        "asset": name, "welded": welded,
                        "support": {"type": "floor", "room": "room_0"}})
    (root / "scene.json").write_text(json.dumps({"objects": objects, "assets": {}}))
    poses = {name: (xyz, yaw) for name, (_, _, xyz, yaw, _) in OBJECTS.items()}
    (root / "scene.dmd.yaml").write_text(_directives(poses))
    # The policy's after-file: the same directives, the mug put down on the floor.
    poses["mug_0"] = ((1.0, -1.0, 0.0), 0.0)
    (root / "after_test.dmd.yaml").write_text(_directives(poses))
    return root


@pytest.fixture(scope="module")
def state(scene_dir):
    return load_state(scene_dir)


def test_objects_and_info(state):
    assert [o["id"] for o in list_objects(state, category="table")["objects"]] == ["table_0"]
    assert len(list_objects(state)["objects"]) == len(OBJECTS)
    mug = get_object_info(state, "mug_0")
    assert mug["free"] and mug["category"] == "mug" and mug["mass_kg"] == pytest.approx(0.3)
    assert mug["world_aabb"]["min"] == pytest.approx([0.16, 0.01, 0.77])
    assert mug["world_aabb"]["max"] == pytest.approx([0.24, 0.09, 0.87])
    assert not get_object_info(state, "table_0")["free"]
    json.dumps(mug)


def test_distance_signs(state):
    touching = get_distance(state, "mug_0", "table_0")
    assert abs(touching["signed_distance_m"]) < 1e-6
    # The crate (corner at x = y = 1.85, 30 cm tall) is nearest a table leg (corner at
    # 0.475, 0.275), not the table top above its height.
    apart = get_distance(state, "crate_0", "table_0")["signed_distance_m"]
    assert apart == pytest.approx(math.hypot(1.85 - 0.475, 1.85 - 0.275), abs=1e-6)
    sunk = get_distance(state, "crate_0", "floor_0")
    assert sunk["signed_distance_m"] == pytest.approx(-0.003, abs=1e-6)
    assert sunk["normal_W"] == pytest.approx([0.0, 0.0, 1.0], abs=1e-6)


def test_spatial_relation(state):
    mug_table = get_spatial_relation(state, "mug_0", "table_0")
    assert mug_table["axes"]["z"]["side"] == "above"
    assert "above" in mug_table["relations"]
    assert mug_table["vertical_gap_m"] == pytest.approx(0.0, abs=1e-6)
    assert mug_table["footprint_overlap_fraction"] == pytest.approx(1.0)
    crate_table = get_spatial_relation(state, "crate_0", "table_0")
    assert {"right", "front"} <= set(crate_table["relations"])
    assert crate_table["footprint_overlap_fraction"] == 0.0
    # Rotation-aware: in the yawed bin's frame the block lies 5 cm toward the bin's +x.
    block_bin = get_spatial_relation(state, "block_0", "bin_0")
    assert block_bin["axes"]["x"]["side"] == "overlapping"
    assert block_bin["b_surface_under_a"]["gap_m"] == pytest.approx(0.0, abs=1e-6)


def test_support(state):
    mug = get_support(state, "mug_0")
    assert [s["id"] for s in mug["supporters"]] == ["table_0"]
    assert mug["supporters"][0]["surface_overlap_fraction"] == pytest.approx(1.0)
    assert mug["supporters"][0]["normal_W"][2] == pytest.approx(1.0, abs=1e-6)
    assert [s["id"] for s in get_support(state, "cup_0")["supporters"]] == ["coaster_0"]
    assert [s["id"] for s in get_support(state, "crate_0")["supporters"]] == ["floor_0"]
    json.dumps(mug)


@pytest.mark.parametrize("predicate,target,reference,holds", [
    ("on", "mug", "table", True),
    ("on", "crate", "table", False),
    ("on", "cup", "table", True),      # on the coaster, which is on the table
    ("on", "table", "mug", False),
    ("inside", "block", "bin", True),
    ("inside", "mug", "bin", False),
    ("near", "mug", "table", True),
    ("near", "crate", "table", False),
])
def test_evaluate(state, predicate, target, reference, holds):
    verdict = evaluate(state, predicate, target, reference)
    assert verdict["holds"] is holds, verdict["reason"]
    assert [p["holds"] for p in verdict["pairs"]] == [holds]
    json.dumps(verdict)


def test_on_evidence(state):
    pair = evaluate(state, "on", "cup", "table")["pairs"][0]
    assert pair["evidence"]["via"]["id"] == "coaster_0"
    # Directly, the cup stands a coaster's thickness (15 mm) above the table top.
    assert pair["evidence"]["bottom_gap_m"] == pytest.approx(0.015, abs=1e-6)
    inside = evaluate(state, "inside", "block", "bin")["pairs"][0]["evidence"]
    assert inside["volume_inside_fraction"] == pytest.approx(1.0)


def test_after_directives_flip_on(scene_dir):
    """A policy's after-file (same directives, the mug moved to the floor) is judged as its
    own state: the mug is no longer on the table."""
    task = {"predicate": "on", "target": "mug", "reference": "table"}
    assert judge(scene_dir, task)["holds"]
    after = judge(scene_dir, task, dmd="after_test.dmd.yaml")
    assert not after["holds"]
    assert "no part of table_0 lies under mug_0" in after["reason"]
    state = load_state(scene_dir, "after_test.dmd.yaml")
    assert [s["id"] for s in get_support(state, "mug_0")["supporters"]] == ["floor_0"]


def test_bad_input_gives_a_verdict(state):
    verdict = evaluate(state, "on", "giraffe", "table")
    assert not verdict["holds"] and "giraffe" in verdict["reason"] and verdict["pairs"] == []
    with pytest.raises(BadRequest):
        evaluate(state, "under", "mug", "table")
    with pytest.raises(BadRequest):
        get_distance(state, "mug_0", "giraffe_0")


def test_category_matching():
    assert category_matches("coffee table", "coffee_table")
    assert category_matches("table", "coffee_table")
    assert not category_matches("tab", "coffee_table")
    assert not category_matches("coffee table", "table")


def test_geometry_fractions():
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    half = np.array([[0.5, -1], [2, -1], [2, 2], [0.5, 2]], dtype=float)
    assert footprint_fraction([square], [half]) == pytest.approx(0.5)
    # A unit cube shifted half its width out of another: half its volume inside.
    assert box_inside_fraction(np.eye(3), [0.5, 0, 0], [0, 0, 0], [1, 1, 1],
                               [0, 0, 0], [1, 1, 1]) == pytest.approx(0.5)
    # Rotated 90 deg about x, a 1 x 1 x 2 box fits a 1 x 2 x 1 box exactly.
    R = np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]], dtype=float)
    assert box_inside_fraction(R, [0, 0, 0], [0, 0, 0], [1, 1, 2],
                               [0, -2, 0], [1, 0, 1]) == pytest.approx(1.0)
