"""The typed boundary of the pick-and-place policy: the task, the two policies' settings, the
episode result, and the one exception that carries a failure reason.

Every type is a plain dataclass; `dataclasses.asdict(result)` is JSON-serialisable as it stands
(floats, strings, lists, dicts, None). Units SI: m, s, rad, kg; poses as `Pose` (xyz in m,
unit quaternion wxyz), always of a body in the world frame unless the name says otherwise.
"""

import dataclasses as dc
import math
from typing import Dict, List, Optional

import numpy as np
from pydrake.math import RigidTransform, RotationMatrix

from drake_bridge.protocol import Pose

#: The predicates a task may name.
PREDICATES = ("on", "inside", "near")

#: The policies `run_episode` knows.
POLICIES = ("standard", "degraded")

#: Why an episode failed, a fixed set (`EpisodeResult.failure_reason` is one of these or None):
#: no_base_pose  no collision-free base pose reaches the target (or the place location)
#: no_grasp      no antipodal, collision-free grasp of the target was found
#: ik            grasps exist but no pre-grasp/grasp/lift/pre-place/place configuration solves
#:               (or the reference offers no place location for the predicate)
#: planning      RRT-Connect or TOPPRA failed between solved configurations
#: dropped       the object left the gripper while it was carried (simulated)
#: timeout       the planning or simulation wall-clock budget ran out
FAILURE_REASONS = ("no_base_pose", "no_grasp", "ik", "planning", "dropped", "timeout")


class PolicyFailure(Exception):
    """An episode ended early for one of FAILURE_REASONS; `message` says what and where."""

    def __init__(self, reason, message):
        assert reason in FAILURE_REASONS, reason
        super().__init__(f"{reason}: {message}")
        self.reason = reason
        self.message = message


class BadTask(ValueError):
    """The task cannot be run on this scene at all (an unknown instance, a target that is not a
    single free body, an unknown predicate or policy): an input error, not a policy failure."""


@dc.dataclass
class PickPlaceTask:
    """Move `target` (a free object's model instance name, e.g. "mug_0") so that
    `predicate(target, reference)` holds: "on" the reference's top surface, "inside" the
    reference (a container), or "near" it (within 15 cm, placement.NEAR_GAP_M, on the surface
    it stands on)."""

    predicate: str
    target: str
    reference: str


@dc.dataclass
class PolicyConfig:
    """What a policy is. The standard and the degraded policy differ only in the fields marked
    (*), the carrying clearance and the gripper limits; everything else is shared so that a
    difference in outcome has one cause.

    Clearances (SceneGraphCollisionChecker padding, m): `env_padding_m` between every robot
    body and the scene in every phase; while carrying, the gripper (body, fingers) and the held
    object get `carry_padding_m` (*) instead. Gripper limits (*) are TOPPRA constraints on the
    `grasp_frame`: translational speed (m/s) and spatial acceleration, each component of the
    angular (rad/s^2) and translational (m/s^2) part bounded, measured and expressed in the
    world; all None in the degraded policy. Standard values: 2.5 cm carrying clearance,
    0.35 m/s, 4 rad/s^2, 1.5 m/s^2. Joint velocity, acceleration and actuator torque limits
    come from the robot's SDFormat in both policies, scaled by `joint_limit_scale` so the PD
    tracking keeps a margin."""

    name: str
    carry_padding_m: Optional[float]  # (*)
    gripper_speed_m_s: Optional[float]  # (*)
    gripper_angular_accel_rad_s2: Optional[float]  # (*)
    gripper_linear_accel_m_s2: Optional[float]  # (*)
    env_padding_m: float = 0.005
    joint_limit_scale: float = 0.8
    #: Straight Cartesian moves: pre-grasp stand-off along the approach, lift and pre-place
    #: height above the grasp / place pose, retreat after release (m).
    pregrasp_offset_m: float = 0.10
    lift_height_m: float = 0.12
    retreat_offset_m: float = 0.10
    #: Planner settings.
    edge_step_rad: float = 0.02
    rrt_max_iterations: int = 4000
    shortcut_iterations: int = 150
    #: Wall-clock budgets (s): planning (everything before the rollout) and simulation.
    planning_budget_s: float = 90.0
    simulation_budget_s: float = 150.0
    #: Simulated time after the last commanded motion (s).
    settle_after_s: float = 1.0

    @staticmethod
    def named(name):
        """The settings of policy `name` ("standard" or "degraded")."""
        if name == "standard":
            return PolicyConfig(name="standard", carry_padding_m=0.025, gripper_speed_m_s=0.35,
                                gripper_angular_accel_rad_s2=4.0, gripper_linear_accel_m_s2=1.5)
        if name == "degraded":
            return PolicyConfig(name="degraded", carry_padding_m=None, gripper_speed_m_s=None,
                                gripper_angular_accel_rad_s2=None, gripper_linear_accel_m_s2=None)
        raise BadTask(f"unknown policy {name!r}; expected one of {POLICIES}")


#: The target's pose-estimation error (see PoseError): standard deviation and bound of each
#: horizontal component, of the vertical one (m) and of the yaw (rad).
POSE_ERROR_SIGMA_M = (0.005, 0.005, 0.003)
POSE_ERROR_BOUND_M = (0.010, 0.010, 0.006)
POSE_ERROR_SIGMA_RAD = math.radians(2.0)
POSE_ERROR_BOUND_RAD = math.radians(4.0)


@dc.dataclass
class PoseError:
    """How far the policy's estimate of the target's pose is from the truth, as a depth
    camera's estimate would be off: the estimate is the true pose (scene.dmd.yaml's) moved by
    (dx_m, dy_m, dz_m) in the world and turned by `dyaw_rad` about the vertical through the
    body's origin. The policy plans everything (grasp, place, the held object's pose in the
    gripper) with the estimate; the simulation holds the truth. Both policies of an episode
    seed meet the same error, so it is no cause of a difference between them; the carrying
    clearance is what absorbs it."""

    dx_m: float = 0.0
    dy_m: float = 0.0
    dz_m: float = 0.0
    dyaw_rad: float = 0.0

    @staticmethod
    def draw(seed):
        """The error of episode seed `seed`: each component normal with its POSE_ERROR_SIGMA,
        clipped to its bound; drawn from a generator of its own, so that neither the policy
        nor its other random choices change it."""
        rng = np.random.default_rng([int(seed), 0x905E])
        d = np.clip(rng.normal(0.0, POSE_ERROR_SIGMA_M), np.negative(POSE_ERROR_BOUND_M),
                    POSE_ERROR_BOUND_M)
        yaw = np.clip(rng.normal(0.0, POSE_ERROR_SIGMA_RAD), -POSE_ERROR_BOUND_RAD,
                      POSE_ERROR_BOUND_RAD)
        return PoseError(*(float(v) for v in d), float(yaw))

    def estimate(self, X_WO):
        """The estimate of true pose X_WO (a RigidTransform)."""
        R = RotationMatrix.MakeZRotation(self.dyaw_rad).multiply(X_WO.rotation())
        return RigidTransform(R, X_WO.translation() + [self.dx_m, self.dy_m, self.dz_m])


@dc.dataclass
class GraspInfo:
    """The grasp the episode used. `world_from_grasp`: the gripper's `grasp_frame` (+z the
    approach direction, +y the right finger's opening direction) at the grasp; `grasp_from_object`:
    the object's body frame in the grasp frame (fixed while it is held); the two contact points
    (m, world) and their distance `width_m`; `finger_target_m`: the commanded finger position
    when closed (each finger; below width/2 so the PD squeezes)."""

    world_from_grasp: Pose
    grasp_from_object: Pose
    contact_a_W: List[float]
    contact_b_W: List[float]
    width_m: float
    finger_target_m: float
    score: float
    top_down_cos: float


@dc.dataclass
class TrajectoryInfo:
    """The planned (TOPPRA-timed) motion: per segment name and duration, total duration, and
    the largest gripper (`grasp_frame`) speed and translational acceleration along it, sampled
    every 5 ms (m/s, m/s^2)."""

    segments: List[Dict[str, object]]
    duration_s: float
    max_gripper_speed_m_s: float
    max_gripper_accel_m_s2: float
    max_joint_speed_ratio: float


@dc.dataclass
class EpisodeResult:
    """What happened. `success` means the episode executed (a plan was found and the simulated
    rollout carried the object to its release without dropping it); whether the predicate holds
    afterwards is for the evaluator to judge from `after_<policy>.dmd.yaml`.

    `timings_s`: wall seconds per phase (load, perception, grasp, base, ik, planning, toppra,
    rollout, frames, output). `welded_instances`: the scene instances whose free body the
    policy welded for speed (every one but the target; instances the directives weld already
    are not listed); `excluded_from_simulation`: the scene instances the rollout left out
    altogether, their collision geometry being more than 0.3 m from the planned motion (or,
    for small objects, more than 1.5 m from the target and the reference: left out of
    planning too).
    `base_poses`: the base (x m, y m, yaw rad) used for picking and, if different, for placing.
    `grasp`: the grasp used. `planned_place_pose`: where the plan puts the object;
    `final_poses`: the simulated end state of the free bodies (the target); `pose_error`: how
    far the policy's estimate of the target's start was from `initial_poses` (the truth);
    `carry_contacts`: the scene instances the object touched from the grasp to the release
    (rollout.py: its two supports, and whatever the carried object hit); `carry_hits`: those
    it touched neither at the grasp nor at the release, what it hit; `dropped_at_s`:
    when the drop was detected; `simulated_s`: simulated time. `files`: role -> absolute
    path."""

    policy: str
    task: Dict[str, str]
    seed: int
    success: bool
    failure_reason: Optional[str]
    message: str
    timings_s: Dict[str, float]
    welded_instances: List[str]
    base_poses: List[List[float]]
    grasp: Optional[GraspInfo]
    planned_place_pose: Optional[Pose]
    initial_poses: Dict[str, Pose]
    final_poses: Dict[str, Pose]
    pose_error: PoseError
    carry_contacts: List[str]
    carry_hits: List[str]
    trajectory: Optional[TrajectoryInfo]
    dropped_at_s: Optional[float]
    simulated_s: float
    excluded_from_simulation: List[str]
    files: Dict[str, str]
