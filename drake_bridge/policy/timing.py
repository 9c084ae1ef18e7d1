"""Time-optimal timing of joint-space paths with TOPPRA (`pydrake.multibody.optimization.Toppra`).

The path through a segment's waypoints is a cubic spline with continuous second derivatives,
parameterised by joint-space arc length (end tangents along the end chords; the trajectory
starts and ends at rest because TOPPRA's path speed does). A spline can stray from
the collision-checked polyline, so it is checked at every `check_step` of joint motion; when it
collides (or TOPPRA fails on it) the segment falls back to straight lines between the waypoints,
each timed from rest to rest.

Constraints, on the timing plant (the robot, or the robot with the held object welded to its
grasp frame, so torques include the object's weight):
- joint velocity and acceleration limits from the SDFormat, times `config.joint_limit_scale`;
- actuator effort limits as joint torque limits (`AddJointTorqueLimit`, times the same scale);
- standard policy only: the grasp frame's translational speed
  (`AddFrameTranslationalSpeedLimit`) and spatial acceleration (`AddFrameAccelerationLimit`,
  angular and translational, each component bounded).
Grid points: `Toppra.CalcGridPoints` with at least 100 points, segments <= 0.05 of the path
parameter.
"""

import numpy as np
from pydrake.multibody.optimization import CalcGridPointsOptions, Toppra
from pydrake.trajectories import PathParameterizedTrajectory, PiecewisePolynomial


class Chain:
    """Trajectories played one after another (each from its own start time), as one."""

    def __init__(self, trajectories):
        self.parts = list(trajectories)
        self.offsets = np.concatenate(
            [[0.0], np.cumsum([p.end_time() - p.start_time() for p in self.parts])])

    def end_time(self):
        return float(self.offsets[-1])

    def _locate(self, t):
        k = int(np.clip(np.searchsorted(self.offsets, t, side="right") - 1, 0,
                        len(self.parts) - 1))
        part = self.parts[k]
        return part, part.start_time() + np.clip(t - self.offsets[k], 0.0,
                                                 part.end_time() - part.start_time())

    def value(self, t):
        part, tau = self._locate(t)
        return np.asarray(part.value(tau)).ravel()

    def derivative(self, t, order=1):
        part, tau = self._locate(t)
        return np.asarray(part.EvalDerivative(tau, order)).ravel()


def robot_limits(plant, scale):
    """(v_lo, v_hi, a_lo, a_hi, tau_lo, tau_hi) of the plant's velocities, scaled."""
    v_hi = scale * plant.GetVelocityUpperLimits()
    a_hi = scale * plant.GetAccelerationUpperLimits()
    tau_hi = np.full(plant.num_velocities(), np.inf)
    for index in plant.GetJointActuatorIndices():
        actuator = plant.get_joint_actuator(index)
        tau_hi[actuator.joint().velocity_start()] = scale * actuator.effort_limit()
    return -v_hi, v_hi, -a_hi, a_hi, -tau_hi, tau_hi


def toppra(plant, path, config):
    """The time-optimal trajectory along `path` (a Trajectory of the plant's positions), or
    None when TOPPRA finds none."""
    options = CalcGridPointsOptions(max_err=1e-3, max_iter=100, max_seg_length=0.01,
                                    min_points=100)
    gridpoints = Toppra.CalcGridPoints(path, options)
    solver = Toppra(path, plant, gridpoints)
    v_lo, v_hi, a_lo, a_hi, tau_lo, tau_hi = robot_limits(plant, config.joint_limit_scale)
    solver.AddJointVelocityLimit(v_lo, v_hi)
    solver.AddJointAccelerationLimit(a_lo, a_hi)
    if np.all(np.isfinite(tau_hi)):
        solver.AddJointTorqueLimit(tau_lo, tau_hi)
    frame = plant.GetFrameByName("grasp_frame")
    if config.gripper_speed_m_s is not None:
        solver.AddFrameTranslationalSpeedLimit(frame, config.gripper_speed_m_s)
    if config.gripper_linear_accel_m_s2 is not None:
        alpha, acc = config.gripper_angular_accel_rad_s2, config.gripper_linear_accel_m_s2
        upper = np.array([alpha, alpha, alpha, acc, acc, acc])
        solver.AddFrameAccelerationLimit(frame, -upper, upper)
    s_of_t = solver.SolvePathParameterization()
    if s_of_t is None:
        return None
    return PathParameterizedTrajectory(path, s_of_t)


def _spline(waypoints):
    q = np.array(waypoints)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(q, axis=0), axis=1))])
    if len(q) == 2:
        return PiecewisePolynomial.FirstOrderHold(s, q.T)
    # End tangents along the first and last chords at unit speed in s: a zero tangent would
    # make the path parameter degenerate at the ends and TOPPRA's accelerations wrong there.
    start = ((q[1] - q[0]) / (s[1] - s[0]))[:, None]
    end = ((q[-1] - q[-2]) / (s[-1] - s[-2]))[:, None]
    return PiecewisePolynomial.CubicWithContinuousSecondDerivatives(s, q.T, start, end)


def time_waypoints(plant, waypoints, config, is_free=None, check_step=0.02):
    """A timed trajectory (Chain) through `waypoints` (plant positions), or None.

    `is_free(q)`, when given, checks the smoothed path every `check_step` of joint motion."""
    waypoints = [np.asarray(w, dtype=float) for w in waypoints]
    kept = [waypoints[0]]
    for w in waypoints[1:]:
        if np.linalg.norm(w - kept[-1]) > 1e-9:
            kept.append(w)
    if len(kept) == 1:
        return None
    if len(kept) > 2:
        spline = _spline(kept)
        ok = True
        if is_free is not None:
            n = int(np.ceil(spline.end_time() / check_step)) + 1
            ok = all(is_free(np.asarray(spline.value(s)).ravel())
                     for s in np.linspace(0.0, spline.end_time(), n))
        if ok:
            timed = toppra(plant, spline, config)
            if timed is not None:
                return Chain([timed])
    parts = []
    for a, b in zip(kept[:-1], kept[1:]):
        timed = toppra(plant, _spline([a, b]), config)
        if timed is None:
            return None
        parts.append(timed)
    return Chain(parts)


def gripper_motion_stats(plant, trajectory, dt=0.005):
    """(max speed m/s, max translational acceleration m/s^2, max |v|/v_limit over joints) of
    the plant's grasp frame along `trajectory` (anything with value(t), derivative(t) and
    end_time()), sampled every dt; accelerations by finite differences."""
    context = plant.CreateDefaultContext()
    frame = plant.GetFrameByName("grasp_frame")
    times = np.arange(0.0, trajectory.end_time() + 1e-9, dt)
    p = []
    ratio = 0.0
    v_hi = plant.GetVelocityUpperLimits()
    for t in times:
        plant.SetPositions(context, trajectory.value(t))
        p.append(frame.CalcPoseInWorld(context).translation())
        v = trajectory.derivative(t, 1)
        finite = np.isfinite(v_hi) & (v_hi > 0)
        ratio = max(ratio, float(np.max(np.abs(v[finite]) / v_hi[finite])))
    p = np.array(p)
    if len(p) < 3:
        return 0.0, 0.0, ratio
    vel = np.diff(p, axis=0) / dt
    acc = np.diff(vel, axis=0) / dt
    return (float(np.max(np.linalg.norm(vel, axis=1))),
            float(np.max(np.linalg.norm(acc, axis=1))), ratio)
