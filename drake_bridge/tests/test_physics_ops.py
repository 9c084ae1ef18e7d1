"""The physics ops (settle, simulate, project) on hand-written box scenes with known answers."""

import pytest

from drake_bridge import ops
from drake_bridge.errors import BadRequest
from drake_bridge.tests.conftest import write_scene

FLOOR = ("floor", (0.0, 0.0, -0.05), (4.0, 4.0, 0.1), True)


def _z(result, name):
    return result["poses"][name]["body"]["xyz"][2]


def test_box_dropped_on_a_table_lands_on_it(tmp_path):
    # Table top: 0.6 x 0.6 slab with its top at z = 0.7; the box starts 2 cm above it.
    scene = write_scene(tmp_path, [
        FLOOR,
        ("table", (0.0, 0.0, 0.675), (0.6, 0.6, 0.05), True),
        ("box", (0.05, 0.0, 0.7 + 0.05 + 0.02), (0.1, 0.1, 0.1), False),
    ])
    r = ops.call("settle", dict(scene, floor_z=0.0))
    assert r["at_rest"] and not r["timed_out"]
    assert r["sim_time"] < 1.5, "a 2 cm drop comes to rest quickly"
    assert _z(r, "box") == pytest.approx(0.75, abs=1e-3)
    assert r["poses"]["box"]["body"]["xyz"][:2] == pytest.approx([0.05, 0.0], abs=1e-3)
    m = r["motion"]["box"]
    assert m["displacement_m"] == pytest.approx(0.02, abs=1e-3)
    assert m["rotation_rad"] < 0.01
    assert r["max_penetration_m"] < 5e-4


def test_overhanging_box_falls_off_and_the_stack_below_stays(tmp_path):
    # A box resting on a pedestal, and a second box balanced on its edge with most of it over
    # the side: the top one falls to the floor, the bottom one stays.
    scene = write_scene(tmp_path, [
        FLOOR,
        ("pedestal", (0.0, 0.0, 0.25), (0.2, 0.2, 0.5), True),
        ("base", (0.0, 0.0, 0.55), (0.1, 0.1, 0.1), False),
        ("top", (0.13, 0.0, 0.651), (0.2, 0.1, 0.1), False),
    ])
    r = ops.call("settle", dict(scene, floor_z=0.0, max_time=3.0))
    assert _z(r, "top") < 0.2, "the overhanging box fell"
    assert r["motion"]["top"]["displacement_m"] > 0.3
    assert r["motion"]["base"]["displacement_m"] < 5e-3


def test_simulate_runs_the_whole_duration_and_point_contact_is_selectable(tmp_path):
    scene = write_scene(tmp_path, [FLOOR, ("box", (0.0, 0.0, 0.05), (0.1, 0.1, 0.1), False)])
    r = ops.call("simulate", dict(scene, duration=0.3))
    assert r["sim_time"] == pytest.approx(0.3)
    assert r["steps"] == 300
    assert r["motion"]["box"]["displacement_m"] < 1e-3
    p = ops.call("simulate", dict(scene, duration=0.1, contact={"model": "point"}))
    assert p["contact"]["model"] == "point"
    with pytest.raises(BadRequest, match="contact.model"):
        ops.call("simulate", dict(scene, contact={"model": "magic"}))
    with pytest.raises(BadRequest, match="unknown field"):
        ops.call("simulate", dict(scene, contact={"stiffness": 1}))


def _hydroelastic_geometries(scene_args, model):
    from drake_bridge.protocol import ContactArgs
    from drake_bridge.sim_plant import build_sim_scene
    from pydrake.geometry import Role
    cfg = ContactArgs(model=model)
    loaded = build_sim_scene(scene_args["directives"], scene_args["package_xml"], cfg, 1e-3)
    inspector = loaded.scene_graph.model_inspector()
    ids = inspector.GetAllGeometryIds(Role.kProximity)
    return sum(1 for g in ids
               if inspector.GetProximityProperties(g).HasGroup("hydroelastic")), len(ids)


def test_the_bridge_simulates_the_files_as_written(tmp_path):
    # Files that declare no hydroelastic properties stay without them: nothing is injected.
    (tmp_path / "bare").mkdir()
    (tmp_path / "compliant").mkdir()
    bare = write_scene(tmp_path / "bare", [FLOOR, ("box", (0.0, 0.0, 0.05), (0.1, 0.1, 0.1), False)],
                       contact="")
    assert _hydroelastic_geometries(bare, "as_written") == (0, 2)
    compliant = write_scene(tmp_path / "compliant",
                            [FLOOR, ("box", (0.0, 0.0, 0.05), (0.1, 0.1, 0.1), False)])
    assert _hydroelastic_geometries(compliant, "as_written") == (2, 2)
    # The plant is Drake's default one: hydroelastic with point fallback, 1 ms.
    from drake_bridge.protocol import ContactArgs
    from drake_bridge.sim_plant import build_sim_scene
    loaded = build_sim_scene(compliant["directives"], compliant["package_xml"],
                             ContactArgs(model="as_written"), 1e-3)
    assert str(loaded.plant.get_contact_model()).endswith("kHydroelasticWithFallback")
    point = build_sim_scene(compliant["directives"], compliant["package_xml"],
                            ContactArgs(model="point"), 1e-3)
    assert str(point.plant.get_contact_model()).endswith("kPoint")


def test_settle_takes_initial_poses(tmp_path):
    scene = write_scene(tmp_path, [FLOOR, ("box", (0.0, 0.0, 0.05), (0.1, 0.1, 0.1), False)])
    r = ops.call("settle", dict(scene, poses={"box": {"body": {"xyz": [1.0, 0.5, 0.3],
                                                              "wxyz": [1, 0, 0, 0]}}}))
    assert r["poses"]["box"]["body"]["xyz"] == pytest.approx([1.0, 0.5, 0.05], abs=1e-3)
    with pytest.raises(BadRequest, match="not a free body"):
        ops.call("settle", dict(scene, poses={"floor": {"body": {"xyz": [0, 0, 0],
                                                                "wxyz": [1, 0, 0, 0]}}}))


@pytest.fixture
def deep_overlap(tmp_path):
    """Four boxes piled into each other on the floor, one box far away, one on a welded shelf."""
    return write_scene(tmp_path, [
        FLOOR,
        ("a", (0.00, 0.00, 0.05), (0.1, 0.1, 0.1), False),
        ("b", (0.06, 0.01, 0.05), (0.1, 0.1, 0.1), False),
        ("c", (0.02, 0.07, 0.05), (0.1, 0.1, 0.1), False),
        ("d", (0.05, 0.05, 0.08), (0.1, 0.1, 0.1), False),
        ("far", (1.5, 1.5, 0.05), (0.1, 0.1, 0.1), False),
    ])


@pytest.mark.parametrize("solver", ["snopt", "ipopt", "push_out"])
def test_projection_separates_and_leaves_the_rest(deep_overlap, solver):
    before = ops.call("load", deep_overlap)
    r = ops.call("project", dict(deep_overlap, solver=solver))
    assert r["initial_max_penetration_m"] > 0.03
    assert r["solver"] == solver
    assert r["max_penetration_m"] <= 1e-4
    start = {m["name"]: m["free_bodies"]["body"] for m in before["model_instances"]
             if not m["welded"]}
    for name, pose in start.items():
        after = r["poses"][name]["body"]
        assert after["wxyz"] == pytest.approx(pose["wxyz"], abs=1e-9), "orientation kept"
        lowest = after["xyz"][2] - 0.05
        assert lowest >= -1e-6, f"{name} pushed into the floor"
    assert r["poses"]["far"]["body"]["xyz"] == pytest.approx(start["far"]["xyz"], abs=1e-4)


def test_projection_without_overlap_moves_nothing(tmp_path):
    scene = write_scene(tmp_path, [FLOOR, ("a", (0.0, 0.0, 0.05), (0.1, 0.1, 0.1), False),
                                   ("b", (0.2, 0.0, 0.05), (0.1, 0.1, 0.1), False)])
    r = ops.call("project", scene)
    assert r["solver"] == "none"
    assert r["max_displacement_m"] == 0.0


def test_projection_options(deep_overlap):
    xy = ops.call("project", dict(deep_overlap, xy_only=True, solver="snopt"))
    for name in "abc":
        assert xy["poses"][name]["body"]["xyz"][2] == pytest.approx(0.05, abs=1e-9)
    # Only `d` may move: the others stay exactly where they were.
    only_d = ops.call("project", dict(deep_overlap, movable=["d"], solver="push_out"))
    assert only_d["movable"] == ["d"]
    assert only_d["poses"]["a"]["body"]["xyz"] == pytest.approx([0.0, 0.0, 0.05])
    # A region that keeps `d`'s origin at x <= 0.05 (it is at 0.05).
    region = ops.call("project", dict(deep_overlap, regions={"d": [[1.0, 0.0, 0.05]]},
                                     solver="snopt"))
    assert region["poses"]["d"]["body"]["xyz"][0] <= 0.05 + 1e-6
    with pytest.raises(BadRequest, match="not free"):
        ops.call("project", dict(deep_overlap, movable=["floor"]))


def test_projection_wall_clock_limit_falls_back_to_push_out(deep_overlap):
    r = ops.call("project", dict(deep_overlap, time_limit=1e-3))
    assert r["solver"] == "push_out"
    assert r["max_penetration_m"] <= 1e-4
    statuses = [a["status"] for a in r["attempts"]]
    assert not statuses or "wall-clock limit" in statuses[0]
    assert r["wall_s"] < 30


def test_physics_ops_are_registered():
    assert {"project", "settle", "simulate"} <= set(ops.OPS)


def test_a_solve_past_its_wall_clock_limit_is_killed():
    import time

    from pydrake.solvers import MathematicalProgram, SnoptSolver, SolverOptions

    from drake_bridge.projection import _solve_with_deadline

    prog = MathematicalProgram()
    x = prog.NewContinuousVariables(2)

    def slow_cost(v):
        time.sleep(0.05)
        return (v[0] - 1.0) ** 2 + (v[1] + 2.0) ** 2

    prog.AddCost(slow_cost, vars=x)
    t0 = time.perf_counter()
    status, ok, q = _solve_with_deadline(SnoptSolver(), prog, x, [0.0, 0.0], SolverOptions(), 0.3)
    assert status == "wall-clock limit" and not ok and q is None
    assert time.perf_counter() - t0 < 2.0
    status, ok, q = _solve_with_deadline(SnoptSolver(), prog, x, [0.9, -1.9], SolverOptions(), 60)
    assert ok and q == pytest.approx([1.0, -2.0], abs=1e-4)


def test_rest_by_position_takes_small_motion_only():
    from pydrake.math import RigidTransform, RollPitchYaw

    from drake_bridge.settle import _moved_less

    here = RigidTransform([0.1, 0.2, 0.3])
    assert _moved_less(here, RigidTransform([0.1002, 0.2, 0.3]), 2.5e-4, 2.5e-3)
    assert not _moved_less(here, RigidTransform([0.1003, 0.2, 0.3]), 2.5e-4, 2.5e-3)
    turned = RigidTransform(RollPitchYaw(0.0, 0.0, 0.004), [0.1, 0.2, 0.3])
    assert not _moved_less(here, turned, 2.5e-4, 2.5e-3)


def test_a_box_on_a_table_is_at_rest_before_the_end(tmp_path):
    # Simulated for 5 s with the early stop: a box set down on a slab stops within 2 s.
    scene = write_scene(tmp_path, [
        FLOOR,
        ("box", (0.0, 0.0, 0.05), (0.1, 0.1, 0.1), False),
    ])
    r = ops.call("simulate", dict(scene, duration=5.0, stop_at_rest=True))
    assert r["at_rest"] and r["sim_time"] < 2.0
    assert r["motion"]["box"]["displacement_m"] < 1e-3


class _DivergingSimulator:
    """A pydrake Simulator that fails as Drake does when a state goes non-finite, once
    simulated time passes `at` (or with another error)."""

    def __init__(self, real, at, message):
        self._real, self._at, self._message = real, at, message

    def Initialize(self):
        self._real.Initialize()

    def AdvanceTo(self, t):
        if t > self._at:
            raise RuntimeError(self._message)
        self._real.AdvanceTo(t)


def test_a_simulation_that_goes_non_finite_is_reported_not_raised(tmp_path, monkeypatch):
    from drake_bridge import settle
    scene = write_scene(tmp_path, [FLOOR, ("box", (0.0, 0.0, 0.05), (0.1, 0.1, 0.1), False)])
    nan = ("SceneGraph encountered a non-finite value (e.g., NaN or infinity) on a pose "
           "input port.")
    real = settle.Simulator
    monkeypatch.setattr(settle, "Simulator",
                        lambda d, c: _DivergingSimulator(real(d, c), 0.7, nan))
    r = ops.call("simulate", dict(scene, duration=5.0, stop_at_rest=False))
    assert r["diverged"] and not r["at_rest"]
    # The reply holds the last rest window's start: finite poses and motion.
    assert r["sim_time"] == pytest.approx(0.5)
    assert r["motion"]["box"]["displacement_m"] < 1e-3
    assert _z(r, "box") == pytest.approx(0.05, abs=1e-3)
    # Any other failure of the simulator is still an error.
    monkeypatch.setattr(settle, "Simulator",
                        lambda d, c: _DivergingSimulator(real(d, c), 0.2, "out of memory"))
    with pytest.raises(Exception, match="out of memory"):
        ops.call("simulate", dict(scene, duration=1.0))


def test_a_verdict_is_fixed_only_when_the_rest_of_the_time_cannot_change_it():
    from drake_bridge.settle import _verdict_fixed

    bound = (0.01, 0.1)
    # Creeping 0.2 mm per 0.5 s window (0.4 mm/s) with 4 s to go: 1 mm + 1.6 mm < 5 mm.
    fixed, pace = _verdict_fixed((1e-3, 0.01), (2e-4, 1e-3), (2e-4, 1e-3), 0.5, 4.0, bound)
    assert fixed and pace == pytest.approx([4e-4, 2e-3])
    # The same creep from 4 mm away would pass half the threshold by the end.
    assert not _verdict_fixed((4e-3, 0.01), (2e-4, 1e-3), (2e-4, 1e-3), 0.5, 4.0, bound)[0]
    # Tipping at a uniform 0.01 rad/s^2 from rest: 5 mrad after 1 s, windows of 1.25 and
    # 3.75 mrad, 125 mrad at 5 s. Extrapolated with its growth it is not fixed.
    assert not _verdict_fixed((1e-4, 0.005), (0.0, 3.75e-3), (0.0, 1.25e-3), 0.5, 4.0, bound)[0]
    # Chatter a little larger than the window before, 1 s to go: 4 + 9 mrad.
    assert _verdict_fixed((1e-4, 0.004), (0.0, 3e-3), (0.0, 2e-3), 0.5, 1.0, bound)[0]
    # Fallen and lying still: unstable whatever the rest of the time does ...
    assert _verdict_fixed((0.4, 1.2), (0.0, 0.0), (0.0, 0.0), 0.5, 4.0, bound)[0]
    # ... but not while it still rolls away.
    assert not _verdict_fixed((0.4, 1.2), (0.1, 1.0), (0.1, 1.0), 0.5, 4.0, bound)[0]


def test_a_stability_run_stops_early_but_never_before_a_falling_box_has_fallen(tmp_path):
    scene = write_scene(tmp_path, [
        FLOOR,
        ("pedestal", (0.0, 0.0, 0.25), (0.2, 0.2, 0.5), True),
        ("base", (0.0, 0.0, 0.55), (0.1, 0.1, 0.1), False),
        ("top", (0.13, 0.0, 0.651), (0.2, 0.1, 0.1), False),
    ])
    verdict = {"max_displacement_m": 0.01, "max_rotation_rad": 0.1}
    r = ops.call("simulate", dict(scene, duration=5.0, stop_at_rest=True, floor_z=0.0,
                                  rest_speed=5e-4, rest_angular_speed=5e-3, rest_time=0.5,
                                  verdict=verdict))
    assert r["sim_time"] < 4.0, "stopped before the end"
    assert r["at_rest"] or r["bounded"]
    assert r["motion"]["top"]["displacement_m"] > 0.3, "the overhanging box fell first"
    assert r["motion"]["base"]["displacement_m"] < 5e-3
