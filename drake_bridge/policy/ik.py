"""Inverse kinematics of the grasp frame with collision avoidance.

`InverseKinematics` on a planning model's plant (joint limits on): the grasp frame's position
within POS_TOL_M and orientation within ROT_TOL_DEG of the goal, the named joints held at their
seed values (the base, the fingers, a held object's joint), and a small quadratic cost to stay
near the seed. Two stages, because SNOPT can spend seconds proving a far goal unreachable
under collision constraints:
1. kinematics only, from the seed, up to `restarts` perturbed seeds (uniform +-0.3 rad/m on
   the free joints, from `rng`) and, when asked (`wide`), WIDE_RESTARTS widely perturbed
   ones, each run pulled
   towards its own seed so that the solutions differ in posture; no solution from the near
   seeds means unreachable, at once; the first solution that keeps the minimum distance
   (checked once) is the answer;
2. otherwise the same plus a minimum signed distance between every pair of unfiltered
   geometries (robot-scene and robot-robot; `AddMinimumDistanceLowerBoundConstraint`,
   influence distance 1 cm beyond the bound), from the first stage-1 solution and then the
   seed (for a `wide` search from the first DISTANCE_STARTS stage-1 solutions), at most
   DISTANCE_MAJOR_ITERATIONS each: many poses are tried, most near furniture, and a run that
   fails near a cluttered table took 9 to 18 s at 300 iterations.
SNOPT (Drake's default for these programs) with its major iterations capped at
MAJOR_ITERATIONS in stage 1.
"""

import math

import numpy as np
from pydrake.multibody.inverse_kinematics import InverseKinematics
from pydrake.solvers import SnoptSolver, SolverOptions

POS_TOL_M = 0.002
ROT_TOL_DEG = 2.0
MAJOR_ITERATIONS = 300
#: Stage 2's cap and starts: under minimum-distance constraints near a cluttered shelf one
#: SNOPT run of 300 iterations took 6 s of CPU and failed.
DISTANCE_MAJOR_ITERATIONS = 60
DISTANCE_STARTS = 2
#: Stage-1 restarts with wide perturbations (+-1 rad/m) after the near ones.
WIDE_RESTARTS = 4

_SOLVER = SnoptSolver()
_OPTIONS = SolverOptions()
_OPTIONS.SetOption(_SOLVER.solver_id(), "Major iterations limit", MAJOR_ITERATIONS)
_DISTANCE_OPTIONS = SolverOptions()
_DISTANCE_OPTIONS.SetOption(_SOLVER.solver_id(), "Major iterations limit",
                            DISTANCE_MAJOR_ITERATIONS)


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


def _clear_by(model, q, min_distance_m):
    """True when every unfiltered geometry pair of `model` at q is at least min_distance_m
    apart (the constraint stage 2 would impose, checked once)."""
    query = model.query(q)
    return all(p.distance >= min_distance_m
               for p in query.ComputeSignedDistancePairwiseClosestPoints(min_distance_m))


def _solve(prog, q, seeds, options=None):
    for seed in seeds:
        prog.SetInitialGuess(q, seed)
        result = _SOLVER.Solve(prog, None, options or _OPTIONS)
        if result.is_success():
            return result.GetSolution(q)
    return None


def solve_grasp_frame_ik(model, X_WG, q_seed, held_joints, min_distance_m, rng=None,
                         restarts=4, pos_tol_m=POS_TOL_M, rot_tol_deg=ROT_TOL_DEG, wide=False):
    """A configuration putting `model`'s grasp frame at X_WG with every geometry pair at least
    `min_distance_m` apart, or None. `held_joints`: joint names fixed at their q_seed values.
    `wide`: also try WIDE_RESTARTS far postures (a pre-grasp, reached by a planner; not a
    configuration that must stay near its seed, as the end of a straight move)."""
    plant = model.plant
    held = model.indices(held_joints)
    free = np.setdiff1d(np.arange(len(q_seed)), held)
    lower, upper = plant.GetPositionLowerLimits(), plant.GetPositionUpperLimits()
    rng = rng if rng is not None else np.random.default_rng(0)
    seeds = [q_seed]
    for k in range(restarts + (WIDE_RESTARTS if wide else 0)):
        spread = 0.3 if k < restarts else 1.0
        s = q_seed.copy()
        s[free] = np.clip(s[free] + rng.uniform(-spread, spread, len(free)), lower[free],
                          upper[free])
        seeds.append(s)
    # Stage 1 from each seed, its cost pulling towards that seed: different arm postures
    # (elbow up or out), of which the first clear one is taken without stage 2.
    solutions = []
    for k, seed in enumerate(seeds):
        if k > restarts and not solutions:
            return None  # the near seeds found no kinematic solution: out of reach
        prog, q = _program(model, X_WG, seed, held, None, pos_tol_m, rot_tol_deg)
        solution = _solve(prog, q, [seed])
        if solution is None:
            continue
        if min_distance_m is None or _clear_by(model, solution, min_distance_m):
            return solution
        solutions.append(solution)
    if not solutions:
        return None
    prog, q = _program(model, X_WG, q_seed, held, min_distance_m, pos_tol_m, rot_tol_deg)
    if wide:
        return _solve(prog, q, solutions[:DISTANCE_STARTS], _DISTANCE_OPTIONS)
    return _solve(prog, q, [solutions[0], q_seed], _DISTANCE_OPTIONS)
