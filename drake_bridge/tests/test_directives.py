"""The bridge's directives loader builds the plant Drake's ProcessModelDirectives builds."""

import numpy as np
from pydrake.all import (
    DiagramBuilder,
    LoadModelDirectives,
    Parser,
    ProcessModelDirectives,
    Role,
    Simulator,
)
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig

from drake_bridge import directives
from drake_bridge.tests.conftest import COMPLIANT, write_scene

MESH_SDF = """<?xml version="1.0"?>
<sdf version="1.9" xmlns:drake="http://drake.mit.edu">
  <model name="wedge_asset">
    <link name="body">
      <inertial><mass>0.5</mass>
        <inertia><ixx>0.001</ixx><ixy>0</ixy><ixz>0</ixz><iyy>0.001</iyy><iyz>0</iyz><izz>0.001</izz></inertia>
      </inertial>
      <collision name="collision_000">
        <geometry><mesh><uri>collision_000.obj</uri><drake:declare_convex/></mesh></geometry>
        <drake:proximity_properties>{contact}
          <drake:mu_dynamic>0.4</drake:mu_dynamic><drake:mu_static>0.5</drake:mu_static>
        </drake:proximity_properties>
      </collision>
    </link>
    <link name="lid">
      <inertial><mass>0.1</mass>
        <inertia><ixx>0.0001</ixx><ixy>0</ixy><ixz>0</ixz><iyy>0.0001</iyy><iyz>0</iyz><izz>0.0001</izz></inertia>
      </inertial>
    </link>
    <joint name="hinge" type="revolute">
      <parent>body</parent><child>lid</child>
      <axis><xyz>1 0 0</xyz><limit><lower>0</lower><upper>1.5</upper></limit></axis>
    </joint>
  </model>
</sdf>
"""

WEDGE_OBJ = """v 0 0 0
v 0.2 0 0
v 0 0.2 0
v 0 0 0.1
v 0.2 0 0.1
v 0 0.2 0.1
f 1 3 2
f 4 5 6
f 1 2 5
f 1 5 4
f 1 4 6
f 1 6 3
f 2 3 6
f 2 6 5
"""


def _scene(tmp_path, extra=""):
    """A floor, two boxes, and a mesh model (relative URI, another model name in its file, a
    hinge with a default angle) added twice under two directive names."""
    files = write_scene(tmp_path, [
        ("floor", (0.0, 0.0, -0.05), (4.0, 4.0, 0.1), True),
        ("box_a", (0.0, 0.0, 0.1), (0.2, 0.2, 0.2), False),
        ("box_b", (0.5, 0.0, 0.3), (0.2, 0.2, 0.2), False),
    ])
    asset = tmp_path / "assets" / "wedge"
    asset.mkdir(parents=True)
    (asset / "model.sdf").write_text(MESH_SDF.format(contact=COMPLIANT))
    (asset / "collision_000.obj").write_text(WEDGE_OBJ)
    path = tmp_path / "scene.dmd.yaml"
    text = path.read_text()
    for i, x in enumerate((1.0, 1.5)):
        text += (f"- add_model:\n    name: wedge_{i}\n"
                 f"    file: package://bridge_test/assets/wedge/model.sdf\n"
                 f"    default_joint_positions:\n      hinge: [0.{i + 3}]\n"
                 f"    default_free_body_pose:\n      body:\n        base_frame: world\n"
                 f"        translation: [{x}, 0.0, 0.2]\n"
                 f"        rotation: !Rpy {{deg: [0.0, 10.0, 30.0]}}\n")
    path.write_text(text + extra)
    return files


def _build(files, loader):
    builder = DiagramBuilder()
    plant, scene_graph = AddMultibodyPlant(MultibodyPlantConfig(time_step=1e-3), builder)
    parser = Parser(plant)
    parser.package_map().AddPackageXml(files["package_xml"])
    loader(plant, parser, files["directives"])
    plant.Finalize()
    return builder.Build(), plant, scene_graph


def _parser(files):
    """A parser that knows the scene's package."""
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlant(MultibodyPlantConfig(time_step=1e-3), builder)
    parser = Parser(plant)
    parser.package_map().AddPackageXml(files["package_xml"])
    return parser


def _drake(plant, parser, path):
    ProcessModelDirectives(LoadModelDirectives(path), plant, parser)


def _assert_same_plants(a, b, seconds=0.3):
    (da, pa, sa), (db, pb, sb) = a, b
    assert pa.num_model_instances() == pb.num_model_instances()
    assert [pa.GetModelInstanceName(m) for m in map(_instance, range(pa.num_model_instances()))] \
        == [pb.GetModelInstanceName(m) for m in map(_instance, range(pb.num_model_instances()))]
    assert pa.num_bodies() == pb.num_bodies()
    assert pa.num_positions() == pb.num_positions()
    ia, ib = sa.model_inspector(), sb.model_inspector()
    ga, gb = ia.GetAllGeometryIds(Role.kProximity), ib.GetAllGeometryIds(Role.kProximity)
    assert len(ga) == len(gb) > 0
    for x, y in zip(ga, gb):
        assert ia.GetName(x) == ib.GetName(y)
        assert str(ia.GetProximityProperties(x)) == str(ib.GetProximityProperties(y))
        assert type(ia.GetShape(x)) is type(ib.GetShape(y))
    ca, cb = da.CreateDefaultContext(), db.CreateDefaultContext()
    qa = pa.GetPositions(pa.GetMyContextFromRoot(ca))
    qb = pb.GetPositions(pb.GetMyContextFromRoot(cb))
    assert np.array_equal(qa, qb)
    Simulator(da, ca).AdvanceTo(seconds)
    Simulator(db, cb).AdvanceTo(seconds)
    qa = pa.GetPositions(pa.GetMyContextFromRoot(ca))
    qb = pb.GetPositions(pb.GetMyContextFromRoot(cb))
    assert np.array_equal(qa, qb)
    return qa


def _instance(i):
    from pydrake.multibody.tree import ModelInstanceIndex
    return ModelInstanceIndex(i)


def test_models_parsed_from_text_make_the_plant_drake_makes(tmp_path):
    files = _scene(tmp_path)
    fast = _build(files, directives.add_directives)
    q = _assert_same_plants(_build(files, _drake), fast)
    # The loader took its own path (not the fallback), and the state is a real one: the
    # hinges start at their directive angles and the raised box has fallen.
    assert directives._plan(LoadModelDirectives(files["directives"]), _parser(files)) is not None
    plant = fast[1]
    ctx = plant.CreateDefaultContext()
    for i, angle in enumerate((0.3, 0.4)):
        hinge = plant.GetJointByName("hinge", plant.GetModelInstanceByName(f"wedge_{i}"))
        assert abs(hinge.get_angle(ctx) - angle) < 1e-12
    assert len(q) == plant.num_positions()


def test_directives_it_does_not_know_go_through_drake(tmp_path):
    extra = ("- add_frame:\n    name: shelf_frame\n    X_PF:\n      base_frame: world\n"
             "      translation: [0.0, 0.0, 1.0]\n")
    files = _scene(tmp_path, extra)
    assert directives._plan(LoadModelDirectives(files["directives"]), _parser(files)) is None
    _assert_same_plants(_build(files, _drake), _build(files, directives.add_directives))


def test_relative_uris_become_file_uris_and_others_stay():
    text = ("<uri>a/b.obj</uri><uri> c.gltf </uri><uri>package://p/x.obj</uri>"
            "<uri>file:///abs/y.obj</uri><uri>/abs/z.obj</uri>")
    out = directives._absolute_uris(text, "/scene/assets/m")
    assert out == ("<uri>file:///scene/assets/m/a/b.obj</uri>"
                   "<uri>file:///scene/assets/m/c.gltf</uri>"
                   "<uri>package://p/x.obj</uri><uri>file:///abs/y.obj</uri>"
                   "<uri>file:///abs/z.obj</uri>")
