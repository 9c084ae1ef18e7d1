"""The pick-and-place policy (drake_bridge/policy) on a small scene written here by hand.

The scene: a welded floor; two 0.6 x 0.6 m tables 0.72 m high side by side (table_a, table_b,
free bodies in the directives like a generated scene's furniture); a 6 x 6 x 10 cm block
(block_0) on table_a near its edge; far away a 2.6 m column with a second block on top
(block_high, out of the arm's reach). One variant adds an open bin (bin_0) on table_b, another
a 25 cm barrier on table_a between the block and table_b. The main task: put block_0 on
table_b.

What is pinned: grasps are antipodal (closing axis along a face normal, jaw width the block's)
and the robot holding them is collision-free; IK reaches every key configuration within its
tolerances; an RRT path around the block is collision-free at every 0.02 rad step; TOPPRA
trajectories keep the joint velocity, acceleration and torque limits and the standard
policy's gripper speed and acceleration limits; the standard episode leaves the block resting
on table_b and writes loadable after-directives, PNG frames, the flipbook and the JSON;
"inside" and "near" put it in and beside the bin; the degraded episode runs and moves its
gripper faster; with a pose estimate 2 cm off, the carrying clearance takes the standard
policy's block over the barrier while the degraded policy's hits it and is knocked away;
fingers that never squeeze are reported as a drop; an out-of-reach target fails with a
reason; unknown instances, predicates and policies are input errors.
"""

import dataclasses as dc
import json
import math
import os
import time

import numpy as np
import pytest
from pydrake.multibody.parsing import LoadModelDirectives, Parser, ProcessModelDirectives
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph
from pydrake.multibody.tree import MultibodyForces
from pydrake.math import RigidTransform
from pydrake.systems.framework import DiagramBuilder

from drake_bridge.policy import (
    FAILURE_REASONS,
    BadTask,
    Episode,
    PickPlaceTask,
    PolicyConfig,
    PoseError,
    run_episode,
)
from drake_bridge.policy.grasp import MAX_WIDTH_M
from drake_bridge.policy.ik import POS_TOL_M, ROT_TOL_DEG, solve_grasp_frame_ik
from drake_bridge.policy.rrt import path_is_collision_free, rrt_connect, shortcut
from drake_bridge.policy.scene import ARM_PLANNING_JOINTS, BASE_JOINTS, FINGER_JOINTS
from drake_bridge.policy.timing import robot_limits, time_waypoints

TABLE_TOP_M = 0.72
TABLE_SIZE_M = 0.6
TABLE_A_XY = (1.0, -0.05)
TABLE_B_XY = (1.0, 0.65)
BLOCK_XY = (0.85, 0.05)
BLOCK_SIZE_M = (0.06, 0.06, 0.10)
TASK = PickPlaceTask("on", "block_0", "table_b")
BIN_XY = (0.85, 0.55)
BIN_INNER_M = 0.16
BIN_WALL_M = 0.06
BARRIER_Y_M = 0.18
BARRIER_SIZE_M = (0.6, 0.04, 0.25)

MODEL = """<?xml version="1.0"?>
<sdf version="1.9" xmlns:drake="http://drake.mit.edu">
  <model name="{name}">
    <link name="body">
      <inertial><pose>{com} 0 0 0</pose><mass>{mass}</mass>
        <inertia><ixx>{ixx}</ixx><ixy>0</ixy><ixz>0</ixz><iyy>{iyy}</iyy><iyz>0</iyz><izz>{izz}</izz></inertia>
      </inertial>
{geometry}
    </link>
  </model>
</sdf>
"""

#: A box with the contact properties the project's SDFormat writer declares.
BOX = """      <collision name="{name}">
        <pose>{x} {y} {z} 0 0 0</pose>
        <geometry><box><size>{sx} {sy} {sz}</size></box></geometry>
        <drake:proximity_properties>
          <drake:compliant_hydroelastic/>
          <drake:hydroelastic_modulus>1e8</drake:hydroelastic_modulus>
          <drake:hunt_crossley_dissipation>10</drake:hunt_crossley_dissipation>
          <drake:mu_dynamic>0.5</drake:mu_dynamic><drake:mu_static>0.6</drake:mu_static>
        </drake:proximity_properties>
      </collision>
      <visual name="{name}">
        <pose>{x} {y} {z} 0 0 0</pose>
        <geometry><box><size>{sx} {sy} {sz}</size></box></geometry>
        <material><diffuse>{rgba}</diffuse></material>
      </visual>"""

PACKAGE = """<?xml version="1.0"?>
<package format="2"><name>{name}</name><version>0.0.0</version>
<description>policy test scene</description><maintainer email="t@t">t</maintainer><license>CC0</license></package>
"""


def box_model(name, boxes, mass, rgba="0.6 0.45 0.3 1"):
    """One body made of boxes [(x, y, z, sx, sy, sz)] (body frame: z up, origin on the floor
    under it); the inertia of the boxes' bounding box filled with `mass`."""
    lo = [min(b[i] - b[i + 3] / 2 for b in boxes) for i in range(3)]
    hi = [max(b[i] + b[i + 3] / 2 for b in boxes) for i in range(3)]
    sx, sy, sz = (hi[i] - lo[i] for i in range(3))
    geometry = "\n".join(BOX.format(name=f"box_{k}", x=b[0], y=b[1], z=b[2], sx=b[3], sy=b[4],
                                    sz=b[5], rgba=rgba) for k, b in enumerate(boxes))
    com = " ".join(str((lo[i] + hi[i]) / 2) for i in range(3))
    return MODEL.format(name=name, mass=mass, com=com, geometry=geometry,
                        ixx=mass * (sy**2 + sz**2) / 12, iyy=mass * (sx**2 + sz**2) / 12,
                        izz=mass * (sx**2 + sy**2) / 12)


def table_boxes(size, height, top=0.04, leg=0.05):
    boxes = [(0.0, 0.0, height - top / 2, size, size, top)]
    for cx in (-1, 1):
        for cy in (-1, 1):
            boxes.append((cx * (size / 2 - leg / 2), cy * (size / 2 - leg / 2),
                          (height - top) / 2, leg, leg, height - top))
    return boxes


def bin_boxes():
    """An open box: a 1 cm floor and four 1 cm walls BIN_WALL_M high around a BIN_INNER_M
    square."""
    w, inner, h = 0.01, BIN_INNER_M, BIN_WALL_M
    side = inner + 2 * w
    return [(0.0, 0.0, w / 2, side, side, w),
            ((inner + w) / 2, 0.0, h / 2, w, side, h), (-(inner + w) / 2, 0.0, h / 2, w, side, h),
            (0.0, (inner + w) / 2, h / 2, inner, w, h), (0.0, -(inner + w) / 2, h / 2, inner, w, h)]


def write_policy_scene(scene_dir, with_bin=False, with_barrier=False):
    """The scene of the module doc in `scene_dir` (plus bin_0 on table_b or the barrier on
    table_a when asked); its package is named after the directory, as a generated scene's
    is."""
    name = os.path.basename(scene_dir)
    os.makedirs(scene_dir, exist_ok=True)
    with open(os.path.join(scene_dir, "package.xml"), "w") as f:
        f.write(PACKAGE.format(name=name))
    block = [(0.0, 0.0, BLOCK_SIZE_M[2] / 2, *BLOCK_SIZE_M)]
    models = {
        "floor": (box_model("floor", [(0, 0, -0.05, 6.0, 6.0, 0.1)], 100.0, "0.8 0.8 0.8 1"),
                  None),
        "table_a": (box_model("table_a", table_boxes(TABLE_SIZE_M, TABLE_TOP_M), 20.0),
                    (*TABLE_A_XY, 0.0)),
        "table_b": (box_model("table_b", table_boxes(TABLE_SIZE_M, TABLE_TOP_M), 20.0),
                    (*TABLE_B_XY, 0.0)),
        "block_0": (box_model("block_0", block, 0.3, "0.8 0.1 0.1 1"),
                    (*BLOCK_XY, TABLE_TOP_M)),
        "column": (box_model("column", [(0, 0, 1.3, 0.2, 0.2, 2.6)], 50.0), (-1.5, -1.5, 0.0)),
        "block_high": (box_model("block_high", block, 0.3), (-1.5, -1.5, 2.6)),
    }
    if with_bin:
        models["bin_0"] = (box_model("bin_0", bin_boxes(), 0.5, "0.2 0.4 0.8 1"),
                           (*BIN_XY, TABLE_TOP_M))
    if with_barrier:
        models["barrier"] = (box_model("barrier", [(0, 0, BARRIER_SIZE_M[2] / 2,
                                                    *BARRIER_SIZE_M)], 5.0, "0.3 0.6 0.3 1"),
                             (TABLE_A_XY[0], BARRIER_Y_M, TABLE_TOP_M))
    lines = ["directives:"]
    for model, (sdf, xyz) in models.items():
        os.makedirs(os.path.join(scene_dir, "assets", model), exist_ok=True)
        with open(os.path.join(scene_dir, "assets", model, "model.sdf"), "w") as f:
            f.write(sdf)
        lines.append(f"- add_model:\n    name: {model}\n"
                     f"    file: package://{name}/assets/{model}/model.sdf")
        if xyz is None:
            lines.append(f"- add_weld:\n    parent: world\n    child: {model}::body")
        else:
            lines.append("    default_free_body_pose:\n      body:\n        base_frame: world\n"
                         f"        translation: [{xyz[0]}, {xyz[1]}, {xyz[2]}]\n"
                         "        rotation: !Rpy {deg: [0.0, 0.0, 0.0]}")
    with open(os.path.join(scene_dir, "scene.dmd.yaml"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return scene_dir


@pytest.fixture(scope="module")
def scene_dir(tmp_path_factory):
    return write_policy_scene(str(tmp_path_factory.mktemp("policy") / "scene"))


@pytest.fixture(scope="module")
def bin_scene_dir(tmp_path_factory):
    return write_policy_scene(str(tmp_path_factory.mktemp("policy_bin") / "scene"),
                              with_bin=True)


@pytest.fixture(scope="module")
def barrier_scene_dir(tmp_path_factory):
    return write_policy_scene(str(tmp_path_factory.mktemp("policy_barrier") / "scene"),
                              with_barrier=True)


@pytest.fixture(scope="module")
def planned(scene_dir):
    """The standard policy's plan for TASK (no rollout), with an exact pose estimate."""
    episode = Episode(scene_dir, TASK, PolicyConfig.named("standard"), seed=0,
                      pose_error=PoseError())
    episode.perceive()
    episode.sample_grasps()
    episode.place_positions()
    episode.plan()
    episode.time_segments()
    return episode


@pytest.fixture(scope="module")
def standard_run(scene_dir, tmp_path_factory):
    out = tmp_path_factory.mktemp("standard")
    start = time.monotonic()
    result = run_episode(scene_dir, TASK, "standard", str(out), seed=0)
    return result, time.monotonic() - start


def test_grasps_are_antipodal_on_the_block_and_collision_free_when_held(planned):
    grasps = planned.grasps
    assert grasps, "no grasp sampled"
    block_centre = np.array([*BLOCK_XY, TABLE_TOP_M + BLOCK_SIZE_M[2] / 2])
    for g in grasps:
        # The jaw closes across two opposite faces: its closing axis (grasp frame y) is a face
        # normal (x or y: the block stands unrotated), one contact on each of those faces
        # (within the sampler's 4 mm line tolerance), the width the block's.
        y_G = g.X_WG.rotation().matrix()[:, 1]
        axis = int(np.argmax(np.abs(y_G)))
        assert axis in (0, 1) and abs(y_G[axis]) > math.cos(math.radians(0.1)), y_G
        faces = sorted([g.p_a[axis], g.p_b[axis]])
        np.testing.assert_allclose(faces, [block_centre[axis] - BLOCK_SIZE_M[axis] / 2,
                                           block_centre[axis] + BLOCK_SIZE_M[axis] / 2],
                                   atol=1e-6)
        assert g.width == pytest.approx(BLOCK_SIZE_M[axis], abs=0.001)
        assert g.width <= MAX_WIDTH_M
        centre = g.X_WG.translation()
        assert np.all(np.abs(centre - block_centre) <= np.array(BLOCK_SIZE_M) / 2 + 1e-6)
    # Top-down approaches are favoured: the best grasp points (nearly) straight down.
    assert grasps[0].top_down > math.cos(math.radians(5.0))
    # The robot holding the chosen grasp, fingers open, touches nothing (exact check: the
    # collision checker on the full geometry, scene padding).
    q_grasp = planned.segments[1].path[-1]
    assert planned.approach.checker.CheckConfigCollisionFree(q_grasp)


def test_ik_reaches_every_key_configuration_within_tolerance(planned):
    seg = {s.name: s for s in planned.segments}
    a, c = planned.approach, planned.carry
    g = planned.grasp
    pre = g.X_WG.multiply(RigidTransform([0.0, 0.0, -planned.config.pregrasp_offset_m]))
    X_WG_place = planned.X_WO_place.multiply(planned.X_GO.inverse())
    checks = [
        (a, seg["descend"].path[0], pre),
        (a, seg["descend"].path[-1], g.X_WG),
        (c, seg["lift"].path[-1],
         RigidTransform([0, 0, planned.config.lift_height_m]).multiply(g.X_WG)),
        (c, seg["lower"].path[0],
         RigidTransform([0, 0, planned.config.lift_height_m]).multiply(X_WG_place)),
        (c, seg["lower"].path[-1], X_WG_place),
    ]
    for model, q, X_goal in checks:
        lower, upper = model.plant.GetPositionLowerLimits(), model.plant.GetPositionUpperLimits()
        assert np.all(q >= lower - 1e-6) and np.all(q <= upper + 1e-6)
        X = model.X_WG(q)
        # IK's tolerances: a 2 mm box around the position, 2 degrees of orientation.
        assert np.max(np.abs(X.translation() - X_goal.translation())) <= POS_TOL_M + 1e-5
        angle = X.rotation().InvertAndCompose(X_goal.rotation()).ToAngleAxis().angle()
        assert angle <= math.radians(ROT_TOL_DEG) + 1e-5
    # Pre-grasp, lift and pre-place are free with the checker's clearances (2.5 cm around the
    # gripper and the held block in the standard policy).
    assert a.checker.CheckConfigCollisionFree(seg["descend"].path[0])
    assert c.checker.CheckConfigCollisionFree(seg["lift"].path[-1])
    assert c.checker.CheckConfigCollisionFree(seg["lower"].path[0])
    # The held block sits where the plan puts it.
    X_WO = c.X_WB(seg["lower"].path[-1], c.target_body)
    np.testing.assert_allclose(X_WO.translation(), planned.X_WO_place.translation(), atol=4e-3)


def _gripper_ik(planned, p_W):
    """The grasp's gripper orientation at p_W, solved from the pick base (approach model)."""
    a = planned.approach
    X = RigidTransform(planned.grasp.X_WG.rotation(), p_W)
    return solve_grasp_frame_ik(a, X, planned.q_start, BASE_JOINTS + FINGER_JOINTS, 0.01)


def test_rrt_path_around_the_block_is_collision_free_at_every_edge_step(planned):
    """Gripper low on either side of the standing block: the straight joint-space edge runs
    through the block, RRT-Connect must go over it."""
    a = planned.approach
    z = TABLE_TOP_M + 0.07
    q_a = _gripper_ik(planned, np.array([BLOCK_XY[0], BLOCK_XY[1] - 0.15, z]))
    q_b = _gripper_ik(planned, np.array([BLOCK_XY[0], BLOCK_XY[1] + 0.15, z]))
    assert q_a is not None and q_b is not None
    assert not a.checker.CheckEdgeCollisionFree(q_a, q_b)
    active = a.indices(ARM_PLANNING_JOINTS)
    rng = np.random.default_rng(1)
    lower, upper = a.plant.GetPositionLowerLimits(), a.plant.GetPositionUpperLimits()
    path = rrt_connect(a.checker, q_a, q_b, active, lower, upper, rng, 4000)
    assert path is not None
    path = shortcut(a.checker, path, active, rng, 100)
    np.testing.assert_array_equal(path[0], q_a)
    np.testing.assert_array_equal(path[-1], q_b)
    assert path_is_collision_free(a.checker, path)
    # Independently of the checker's edge routine: every 0.02 rad step is a free configuration.
    held = np.setdiff1d(np.arange(len(q_a)), active)
    for qa, qb in zip(path[:-1], path[1:]):
        np.testing.assert_array_equal(qa[held], q_a[held])
        n = int(np.ceil(np.max(np.abs(qb - qa)) / 0.02)) + 1
        for t in np.linspace(0.0, 1.0, n):
            assert a.checker.CheckConfigCollisionFree(qa + t * (qb - qa))


def _check_limits(plant, trajectory, config, dt=0.002):
    """Along a timed trajectory: the largest ratios of joint speed, joint acceleration and
    joint torque (inverse dynamics, gravity included) to their scaled limits; the largest
    gripper (grasp frame) speed, m/s; the largest component of its angular (rad/s^2) and of its
    translational (m/s^2) acceleration, both measured and expressed in the world."""
    v_lo, v_hi, a_lo, a_hi, tau_lo, tau_hi = robot_limits(plant, config.joint_limit_scale)
    context = plant.CreateDefaultContext()
    frame = plant.GetFrameByName("grasp_frame")
    body = frame.body()
    p_BG = frame.GetFixedPoseInBodyFrame().translation()
    forces = MultibodyForces(plant)
    ratios = np.zeros(3)
    speed = alpha = accel = 0.0
    for t in np.arange(0.0, trajectory.end_time(), dt):
        q, v = trajectory.value(t), trajectory.derivative(t, 1)
        vdot = trajectory.derivative(t, 2)
        plant.SetPositions(context, q)
        plant.SetVelocities(context, v)
        plant.CalcForceElementsContribution(context, forces)
        tau = plant.CalcInverseDynamics(context, vdot, forces)
        ratios = np.maximum(ratios, [np.max(np.abs(v) / v_hi), np.max(np.abs(vdot) / a_hi),
                                     np.max(np.abs(tau) / tau_hi)])
        speed = max(speed, np.linalg.norm(frame.CalcSpatialVelocityInWorld(context)
                                          .translational()))
        A_WB = plant.CalcSpatialAccelerationsFromVdot(context, vdot)[body.index()]
        w = plant.EvalBodySpatialVelocityInWorld(context, body).rotational()
        r = plant.EvalBodyPoseInWorld(context, body).rotation().multiply(p_BG)
        a_G = A_WB.translational() + np.cross(A_WB.rotational(), r) + np.cross(
            w, np.cross(w, r))
        alpha = max(alpha, np.max(np.abs(A_WB.rotational())))
        accel = max(accel, np.max(np.abs(a_G)))
    return ratios, speed, alpha, accel


def test_toppra_trajectories_keep_joint_torque_and_gripper_limits(planned):
    config = planned.config
    moves = [s for s in planned.segments if s.timed is not None]
    assert {s.name for s in moves} >= {"approach", "descend", "lift", "carry", "lower"}
    for s in moves:
        plant = planned.plant_held if s.held else planned.plant_free
        ratios, speed, alpha, accel = _check_limits(plant, s.timed, config)
        # TOPPRA holds its constraints at grid points; between them a few percent over is
        # the interpolation's.
        assert ratios[0] <= 1.01, (s.name, "joint speed", ratios[0])
        assert ratios[1] <= 1.05, (s.name, "joint acceleration", ratios[1])
        assert ratios[2] <= 1.05, (s.name, "torque", ratios[2])
        assert speed <= config.gripper_speed_m_s * 1.02, (s.name, "gripper speed", speed)
        assert alpha <= config.gripper_angular_accel_rad_s2 * 1.05, (s.name, "alpha", alpha)
        assert accel <= config.gripper_linear_accel_m_s2 * 1.05, (s.name, "accel", accel)
        # Starts and ends at rest, at the planned waypoints.
        for t, q in ((0.0, s.path[0]), (s.timed.end_time(), s.path[-1])):
            assert np.max(np.abs(s.timed.derivative(t, 1))) < 1e-6
            np.testing.assert_allclose(s.timed.value(t), planned._timing_q(plant, s.model, q),
                                       atol=1e-9)
    # The same path without the gripper limits (the degraded policy) is timed faster.
    carry = next(s for s in moves if s.name == "carry")
    plant = planned.plant_held
    waypoints = [planned._timing_q(plant, carry.model, q) for q in carry.path]
    faster = time_waypoints(plant, waypoints, PolicyConfig.named("degraded"))
    assert faster.end_time() <= carry.timed.end_time() + 1e-6


def test_standard_episode_leaves_the_block_resting_on_table_b(standard_run, scene_dir):
    result, seconds = standard_run
    assert result.success, (result.failure_reason, result.message)
    assert result.failure_reason is None
    assert seconds < 120.0
    assert result.welded_instances == ["block_high", "column", "table_a", "table_b"]
    X_WO = result.final_poses["block_0"]
    x, y, z = X_WO.xyz
    # On table_b's top: the block's footprint inside the top, its bottom on it, upright.
    half = TABLE_SIZE_M / 2 - BLOCK_SIZE_M[0] / 2
    assert abs(x - TABLE_B_XY[0]) <= half and abs(y - TABLE_B_XY[1]) <= half, (x, y)
    assert z == pytest.approx(TABLE_TOP_M, abs=0.005)
    w = X_WO.wxyz[0]
    tilt = 2 * math.degrees(math.acos(min(1.0, math.hypot(w, X_WO.wxyz[3]))))
    assert tilt < 5.0
    assert result.simulated_s == pytest.approx(result.trajectory.duration_s + 1.0, abs=0.05)

    # The after-directives load like scene.dmd.yaml (scene package only) and put the block
    # where the simulation left it.
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlantSceneGraph(builder, time_step=0.001)
    parser = Parser(plant)
    parser.package_map().AddPackageXml(os.path.join(scene_dir, "package.xml"))
    ProcessModelDirectives(LoadModelDirectives(result.files["after_directives"]), plant, parser)
    plant.Finalize()
    context = plant.CreateDefaultContext()
    block = plant.GetBodyByName("body", plant.GetModelInstanceByName("block_0"))
    np.testing.assert_allclose(plant.EvalBodyPoseInWorld(context, block).translation(),
                               [x, y, z], atol=1e-6)
    assert plant.num_positions() == 7 * 5  # the free bodies of scene.dmd.yaml, still free

    with open(result.files["episode"]) as f:
        data = json.load(f)
    assert data["success"] is True and data["policy"] == "standard"
    assert data["final_poses"]["block_0"]["xyz"] == pytest.approx([x, y, z])
    assert set(data["timings_s"]) >= {"load", "grasp", "ik", "planning", "toppra", "rollout"}
    frames = [p for k, p in result.files.items() if k.startswith("frame_")]
    assert len(frames) == 5
    for path in frames + [result.files["animation"]]:
        assert os.path.getsize(path) > 1000
    for path in frames:
        with open(path, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n"
    assert json.dumps(dc.asdict(result))  # JSON-serialisable as it stands


def _state_check():
    """scripts/robot_state_check.py's `check`."""
    import sys
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
    from robot_state_check import check
    return check


def test_the_benchmarks_independent_state_check_reads_the_states_of_an_episode(
        standard_run, scene_dir):
    """scripts/robot_state_check.py (the check bench_robot_eval.py holds the evaluator
    against) on the start and the end of the standard episode."""
    check = _state_check()
    result, _ = standard_run
    after = result.files["after_directives"]
    assert check(scene_dir, "scene.dmd.yaml", "on", "block_0", "table_a")[0]
    assert not check(scene_dir, "scene.dmd.yaml", "on", "block_0", "table_b")[0]
    assert not check(scene_dir, "scene.dmd.yaml", "near", "block_0", "table_b")[0]
    holds, evidence = check(scene_dir, after, "on", "block_0", "table_b")
    assert holds and evidence["below"] == ["table_b"], evidence
    assert not check(scene_dir, after, "on", "block_0", "table_a")[0]
    assert not check(scene_dir, after, "inside", "block_0", "table_b")[0]  # no walls around


def test_inside_puts_the_block_on_the_bin_floor(bin_scene_dir, tmp_path):
    result = run_episode(bin_scene_dir, PickPlaceTask("inside", "block_0", "bin_0"),
                         "standard", str(tmp_path), seed=0, frames=False)
    assert result.success, (result.failure_reason, result.message)
    check = _state_check()
    holds, evidence = check(bin_scene_dir, result.files["after_directives"], "inside",
                            "block_0", "bin_0")
    assert holds and evidence["walls"] == 4, evidence
    x, y, z = result.final_poses["block_0"].xyz
    half = BIN_INNER_M / 2 - BLOCK_SIZE_M[0] / 2
    assert abs(x - BIN_XY[0]) <= half and abs(y - BIN_XY[1]) <= half, (x, y)
    assert z == pytest.approx(TABLE_TOP_M + 0.01, abs=0.005)  # on the 1 cm bin floor


def test_near_puts_the_block_beside_the_bin_on_its_table(bin_scene_dir, tmp_path):
    result = run_episode(bin_scene_dir, PickPlaceTask("near", "block_0", "bin_0"),
                         "standard", str(tmp_path), seed=0, frames=False)
    assert result.success, (result.failure_reason, result.message)
    x, y, z = result.final_poses["block_0"].xyz
    assert z == pytest.approx(TABLE_TOP_M, abs=0.005)  # on table_b, beside the bin
    assert abs(x - TABLE_B_XY[0]) <= TABLE_SIZE_M / 2 and abs(y - TABLE_B_XY[1]) <= (
        TABLE_SIZE_M / 2)
    # The gap between the block's and the bin's footprints (axis-aligned squares) is at most
    # 15 cm, and positive.
    reach = (BIN_INNER_M / 2 + 0.01) + BLOCK_SIZE_M[0] / 2
    gap = max(abs(x - BIN_XY[0]), abs(y - BIN_XY[1])) - reach
    assert 0.0 < gap <= 0.15, gap


def test_degraded_episode_runs_with_a_faster_gripper(standard_run, scene_dir, tmp_path):
    standard, _ = standard_run
    result = run_episode(scene_dir, TASK, "degraded", str(tmp_path), seed=0, frames=False)
    assert result.failure_reason in (None,) + FAILURE_REASONS
    assert result.trajectory is not None, result.message
    limit = PolicyConfig.named("standard").gripper_speed_m_s
    assert (result.trajectory.max_gripper_speed_m_s > limit * 1.05 or
            result.trajectory.duration_s <= standard.trajectory.duration_s)
    assert (result.trajectory.max_gripper_speed_m_s >=
            standard.trajectory.max_gripper_speed_m_s)
    assert os.path.isfile(os.path.join(str(tmp_path), "after_degraded.dmd.yaml"))


def test_the_degraded_policy_fails_for_lack_of_carrying_clearance(barrier_scene_dir, tmp_path):
    """Scripted: the pose estimate puts the block 2 cm higher than it stands, so it hangs 2 cm
    lower in the gripper than both plans believe: less than the standard policy's carrying
    clearance (2.5 cm), more than the scene padding the degraded policy keeps (5 mm). Both
    carry it over the barrier; the standard policy's block clears it and rests on table_b, the
    degraded policy's hits it and is knocked out of the gripper."""
    error = PoseError(dz_m=0.02)
    standard = run_episode(barrier_scene_dir, TASK, "standard", str(tmp_path), seed=0,
                           frames=False, pose_error=error)
    assert standard.success, (standard.failure_reason, standard.message)
    assert standard.carry_contacts == ["table_a", "table_b"]  # lifted off one, lowered on one
    assert standard.carry_hits == []
    x, y, z = standard.final_poses["block_0"].xyz
    assert abs(y - TABLE_B_XY[1]) < TABLE_SIZE_M / 2 and z == pytest.approx(TABLE_TOP_M,
                                                                               abs=0.005)

    degraded = run_episode(barrier_scene_dir, TASK, "degraded", str(tmp_path), seed=0,
                           frames=False, pose_error=error)
    assert "barrier" in degraded.carry_hits
    assert degraded.failure_reason == "dropped", (degraded.failure_reason, degraded.message)
    x, y, z = degraded.final_poses["block_0"].xyz
    assert not (abs(y - TABLE_B_XY[1]) < TABLE_SIZE_M / 2 and abs(z - TABLE_TOP_M) < 0.005)


def test_out_of_reach_target_fails_with_a_reason(scene_dir, tmp_path):
    """block_high stands 2.6 m up: every grasp is out of the arm's reach."""
    result = run_episode(scene_dir, PickPlaceTask("on", "block_high", "table_b"), "standard",
                         str(tmp_path), seed=0)
    assert not result.success
    assert result.failure_reason in ("ik", "no_base_pose")
    assert result.final_poses["block_high"].xyz == pytest.approx((-1.5, -1.5, 2.6))
    assert os.path.isfile(result.files["after_directives"])


@pytest.mark.parametrize("task, policy", [
    (PickPlaceTask("on", "teapot_0", "table_b"), "standard"),
    (PickPlaceTask("on", "block_0", "table_c"), "standard"),
    (PickPlaceTask("under", "block_0", "table_b"), "standard"),
    (PickPlaceTask("on", "block_0", "table_b"), "reckless"),
    (PickPlaceTask("on", "block_0", "block_0"), "standard"),
])
def test_bad_tasks_are_input_errors(scene_dir, tmp_path, task, policy):
    """Unknown instances, predicates or policies, and a target that is its own reference."""
    with pytest.raises(BadTask):
        run_episode(scene_dir, task, policy, str(tmp_path))


def test_fingers_that_stop_short_of_the_block_are_reported_as_a_drop(scene_dir, tmp_path,
                                                                      monkeypatch):
    """Scripted failure: the closed-finger target 1 cm outside the block's faces, so the jaw
    never squeezes it; the block stays behind when the gripper lifts, and the rollout must say
    "dropped" (not success) and leave the block on table_a."""
    import drake_bridge.policy.grasp as grasp
    monkeypatch.setattr(grasp, "SQUEEZE_M", -0.01)
    result = run_episode(scene_dir, TASK, "standard", str(tmp_path), seed=0, frames=False)
    assert result.failure_reason == "dropped", result.message
    assert not result.success
    assert result.dropped_at_s is not None
    x, y, z = result.final_poses["block_0"].xyz
    assert abs(x - TABLE_A_XY[0]) < TABLE_SIZE_M / 2 and abs(y - TABLE_A_XY[1]) < TABLE_SIZE_M / 2
    assert z == pytest.approx(TABLE_TOP_M, abs=0.01)
