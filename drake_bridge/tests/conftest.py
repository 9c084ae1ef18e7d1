"""Fixtures: tiny scenes of boxes written by hand, so the bridge is tested on its own."""

import os
import sys
import textwrap

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
if ROOT not in sys.path:
    sys.path.insert(0, ROOT)

BOX_SDF = """<?xml version="1.0"?>
<sdf version="1.9" xmlns:drake="http://drake.mit.edu">
  <model name="{name}">
    <link name="body">
      <inertial><mass>1.0</mass>
        <inertia><ixx>0.01</ixx><ixy>0</ixy><ixz>0</ixz><iyy>0.01</iyy><iyz>0</iyz><izz>0.01</izz></inertia>
      </inertial>
      <collision name="c">
        <geometry><box><size>{sx} {sy} {sz}</size></box></geometry>
        <drake:proximity_properties>{contact}
          <drake:mu_dynamic>0.5</drake:mu_dynamic><drake:mu_static>0.6</drake:mu_static>
        </drake:proximity_properties>
      </collision>
    </link>
  </model>
</sdf>
"""

#: The contact model the project's SDFormat writer declares on every collision geometry.
COMPLIANT = """
          <drake:compliant_hydroelastic/>
          <drake:hydroelastic_modulus>1e8</drake:hydroelastic_modulus>
          <drake:hunt_crossley_dissipation>10</drake:hunt_crossley_dissipation>"""

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2"><name>{name}</name><version>0.0.0</version>
<description>test</description><maintainer email="t@t">t</maintainer><license>CC0</license></package>
"""


def write_scene(tmp_path, boxes, package="bridge_test", contact=COMPLIANT):
    """boxes: list of (instance name, (x, y, z), size (sx, sy, sz), welded); every box declares
    `contact` in its proximity properties (the project's compliant model unless given)."""
    (tmp_path / "package.xml").write_text(PACKAGE_XML.format(name=package))
    lines = ["directives:"]
    for name, xyz, size, welded in boxes:
        model_dir = tmp_path / "assets" / name
        model_dir.mkdir(parents=True, exist_ok=True)
        (model_dir / "model.sdf").write_text(
            BOX_SDF.format(name=name, sx=size[0], sy=size[1], sz=size[2], contact=contact))
        lines.append(f"- add_model:\n    name: {name}\n"
                     f"    file: package://{package}/assets/{name}/model.sdf")
        pose = (f"translation: [{xyz[0]}, {xyz[1]}, {xyz[2]}]\n"
                "        rotation: !Rpy {deg: [0.0, 0.0, 0.0]}")
        if welded:
            lines.append(f"- add_weld:\n    parent: world\n    child: {name}::body\n"
                         f"    X_PC:\n        {pose}")
        else:
            lines.append(f"    default_free_body_pose:\n      body:\n        base_frame: world\n"
                         f"        {pose}")
    path = tmp_path / "scene.dmd.yaml"
    path.write_text("\n".join(lines) + "\n")
    return {"directives": str(path), "package_xml": str(tmp_path / "package.xml")}


@pytest.fixture
def overlapping_scene(tmp_path):
    """A welded floor slab, a box resting on it, and a box overlapping the first by 4 mm."""
    return write_scene(tmp_path, [
        ("floor", (0.0, 0.0, -0.05), (4.0, 4.0, 0.1), True),
        ("box_a", (0.0, 0.0, 0.1), (0.2, 0.2, 0.2), False),
        ("box_b", (0.196, 0.0, 0.1), (0.2, 0.2, 0.2), False),
        ("box_far", (1.5, 1.5, 0.1), (0.2, 0.2, 0.2), False),
    ])


@pytest.fixture
def bridge_env():
    env = dict(os.environ)
    env["PYTHONPATH"] = ROOT + os.pathsep + env.get("PYTHONPATH", "")
    return env


def dedent(s):
    return textwrap.dedent(s).strip()
