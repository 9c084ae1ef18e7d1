"""drop_spheres: a sphere released over a floor lands on it; bad requests are refused."""

import pytest

from drake_bridge import ops
from drake_bridge.errors import BadRequest
from drake_bridge.tests.conftest import write_scene


def test_sphere_lands_on_the_floor(tmp_path):
    scene = write_scene(tmp_path, [("floor", (0.0, 0.0, -0.05), (4.0, 4.0, 0.1), True)])
    out = ops.call("drop_spheres", dict(scene, spheres=[
        {"name": "ball_a", "xyz": [0.5, -0.5, 1.0], "radius": 0.1},
        {"name": "ball_far", "xyz": [5.0, 5.0, 1.0], "radius": 0.1},
    ], duration=1.0))
    by_name = {s["name"]: s for s in out["spheres"]}
    assert by_name["ball_a"]["xyz"][2] == pytest.approx(0.1, abs=5e-3)
    assert by_name["ball_a"]["xyz"][0] == pytest.approx(0.5, abs=1e-2)
    # Nothing under the second ball: it falls past the floor.
    assert by_name["ball_far"]["xyz"][2] < -1.0


def test_bad_spheres_are_refused(tmp_path):
    scene = write_scene(tmp_path, [("floor", (0.0, 0.0, -0.05), (4.0, 4.0, 0.1), True)])
    with pytest.raises(BadRequest, match="non-empty list"):
        ops.call("drop_spheres", dict(scene, spheres=[]))
    with pytest.raises(BadRequest, match="radius"):
        ops.call("drop_spheres", dict(scene, spheres=[{"name": "b", "xyz": [0, 0, 1], "radius": 5}]))
    with pytest.raises(BadRequest, match="clashes"):
        ops.call("drop_spheres", dict(scene, spheres=[{"name": "floor", "xyz": [0, 0, 1]}]))
    with pytest.raises(BadRequest, match="unique"):
        ops.call("drop_spheres", dict(scene, spheres=[
            {"name": "b", "xyz": [0, 0, 1]}, {"name": "b", "xyz": [1, 0, 1]}]))
