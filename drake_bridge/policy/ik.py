"""Inverse kinematics of the grasp frame with collision avoidance.

`InverseKinematics` on a planning model's plant (joint limits on): the grasp frame's position
within POS_TOL_M and orientation within ROT_TOL_DEG of the goal, the named joints held at their
seed values (the base, the fingers, a held object's joint), and a small quadratic cost to stay
near the seed. Two stages, because SNOPT can spend seconds proving a far goal unreachable
under collision constraints:
1. kinematics only, from the seed and up to `restarts` perturbed seeds (uniform +-0.3 rad/m on
   the free joints, from `rng`): no solution means unreachable, at once;
2. the same plus a minimum signed distance between every pair of unfiltered geometries
   (robot-scene and robot-robot; `AddMinimumDistanceLowerBoundConstraint`, influence distance
   1 cm beyond the bound), from the stage-1 solution and then from the seed.
SNOPT (Drake's default for these programs) with its major iterations capped at
MAJOR_ITERATIONS.
"""

import math

import numpy as np
from pydrake.multibody.inverse_kinematics import InverseKinematics
from pydrake.solvers import SnoptSolver, SolverOptions

POS_TOL_M = 0.002
ROT_TOL_DEG = 2.0
MAJOR_ITERATIONS = 300

_SOLVER = SnoptSolver()
_OPTIONS = SolverOptions()
_OPTIONS.SetOption(_SOLVER.solver_id(), "Major iterations limit", MAJOR_ITERATIONS)


def _program(model, X_WG, q_seed, held, min_distance_m, pos_tol_m, rot_tol_deg):
    plant = model.plant
    ik = InverseKinematics(plant, model.plant_context, with_joint_limits=True)
    q = ik.q()
    p = X_WG.translation()
    ik.AddPositionConstraint(frameB=model.grasp_frame, p_BQ=np.zeros(3),
                             frameA=plant.world_frame(), p_AQ_lower=p - pos_tol_m,
                             p_AQ_upper=p + pos_tol_m)
    ik.AddOrientationConstraint(frameAbar=plant.world_frame(), R_AbarA=X_WG.rotation(),
                                frameBbar=model.grasp_frame,
                                R_BbarB=X_WG.rotation().Identity(),
                                theta_bound=math.radians(rot_tol_deg))
    if min_distance_m is not None:
        ik.AddMinimumDistanceLowerBoundConstraint(min_distance_m, 0.01)
    prog = ik.get_mutable_prog()
    for i in held:
        prog.AddBoundingBoxConstraint(q_seed[i], q_seed[i], q[i])
    prog.AddQuadraticErrorCost(0.01 * np.eye(len(q_seed)), q_seed, q)
    return prog, q


def _solve(prog, q, seeds):
    for seed in seeds:
        prog.SetInitialGuess(q, seed)
        result = _SOLVER.Solve(prog, None, _OPTIONS)
        if result.is_success():
            return result.GetSolution(q)
    return None


def solve_grasp_frame_ik(model, X_WG, q_seed, held_joints, min_distance_m, rng=None,
                         restarts=2, pos_tol_m=POS_TOL_M, rot_tol_deg=ROT_TOL_DEG):
    """A configuration putting `model`'s grasp frame at X_WG with every geometry pair at least
    `min_distance_m` apart, or None. `held_joints`: joint names fixed at their q_seed values."""
    plant = model.plant
    held = model.indices(held_joints)
    free = np.setdiff1d(np.arange(len(q_seed)), held)
    lower, upper = plant.GetPositionLowerLimits(), plant.GetPositionUpperLimits()
    rng = rng if rng is not None else np.random.default_rng(0)
    seeds = [q_seed]
    for _ in range(restarts):
        s = q_seed.copy()
        s[free] = np.clip(s[free] + rng.uniform(-0.3, 0.3, len(free)), lower[free], upper[free])
        seeds.append(s)
    prog, q = _program(model, X_WG, q_seed, held, None, pos_tol_m, rot_tol_deg)
    q_kin = _solve(prog, q, seeds)
    if q_kin is None:
        return None
    prog, q = _program(model, X_WG, q_seed, held, min_distance_m, pos_tol_m, rot_tol_deg)
    return _solve(prog, q, [q_kin, q_seed])
