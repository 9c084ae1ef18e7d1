"""Non-penetration projection in Drake: the reference the native (Rust) projection is checked
against.

    minimise  sum_i ||p_i - p0_i||^2      over the movable free bodies' translations p_i
    s.t.      d(g, h) >= min_distance     for every candidate geometry pair (one
                                          `DistanceConstraint` per pair closer than
                                          `candidate_distance` at the start)
              lowest point of each body >= floor_z   (the floor bound)
              optional per-instance XY half-planes (stay over the support surface)
    orientations and joint positions fixed.

Formulation, measured on this machine: one `MinimumDistanceLowerBoundConstraint` over all pairs
hits SNOPT's iteration limit at 50 bodies; one `DistanceConstraint` per candidate pair solves 50
bodies in ~1-2 s (and does not scale to 200, which is why the native projection exists). Floor
pairs are left to the bound: without it an optimiser may push a body through the slab.

Solvers: SNOPT, then IPOPT when SNOPT fails or is unavailable, then a push-out along the
penetration normals. Drake's SNOPT ignores SNOPT's own "Time limit" option, so each solve runs in
a forked child that is killed at the wall-clock limit.
"""

import multiprocessing
import time

import numpy as np
from pydrake.geometry import Box, Capsule, Convex, Cylinder, Ellipsoid, Mesh, Role, Sphere
from pydrake.multibody.inverse_kinematics import DistanceConstraint
from pydrake.solvers import IpoptSolver, MathematicalProgram, SnoptSolver, SolverOptions

from drake_bridge.errors import BadRequest
from drake_bridge.plant_cache import CACHE
from drake_bridge.protocol import in_range
from drake_bridge.sim_plant import apply_poses, free_bodies, instance_name, pose_json


def _shape_vertices(inspector, gid):
    """Vertices (geometry frame) of a shape or of its bounding box."""
    shape = inspector.GetShape(gid)
    if isinstance(shape, (Convex, Mesh)):
        hull = inspector.GetConvexHull(gid)
        return np.array([hull.vertex(i) for i in range(hull.num_vertices())])
    if isinstance(shape, Box):
        h = np.array([shape.width(), shape.depth(), shape.height()]) / 2.0
    elif isinstance(shape, Sphere):
        h = np.full(3, shape.radius())
    elif isinstance(shape, Cylinder):
        h = np.array([shape.radius(), shape.radius(), shape.length() / 2.0])
    elif isinstance(shape, Capsule):
        h = np.array([shape.radius(), shape.radius(), shape.length() / 2.0 + shape.radius()])
    elif isinstance(shape, Ellipsoid):
        h = np.array([shape.a(), shape.b(), shape.c()])
    else:
        return None  # half spaces and the like: unbounded, never a candidate
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    return signs * h


class _Geometry:
    def __init__(self, gid, body, vertices_W):
        self.gid = gid
        self.body = body
        self.lo = vertices_W.min(axis=0)
        self.hi = vertices_W.max(axis=0)


def _geometries(scene, pctx):
    plant = scene.plant
    inspector = scene.scene_graph.model_inspector()
    out = []
    for gid in inspector.GetAllGeometryIds(Role.kProximity):
        body = plant.GetBodyFromFrameId(inspector.GetFrameId(gid))
        v = _shape_vertices(inspector, gid)
        if v is None:
            continue
        X_WG = plant.EvalBodyPoseInWorld(pctx, body).multiply(inspector.GetPoseInFrame(gid))
        out.append(_Geometry(gid, body, (X_WG.rotation().matrix() @ v.T).T + X_WG.translation()))
    return out


def _penetrations(scene, ctx, movable_idx):
    """(depth, body_A, body_B, nhat_BA_W) for penetrating pairs that involve a movable body."""
    plant = scene.plant
    query = scene.scene_graph.get_query_output_port().Eval(scene.scene_graph_context(ctx))
    inspector = query.inspector()
    out = []
    for pp in query.ComputePointPairPenetration():
        ba = plant.GetBodyFromFrameId(inspector.GetFrameId(pp.id_A))
        bb = plant.GetBodyFromFrameId(inspector.GetFrameId(pp.id_B))
        if ba.model_instance() == bb.model_instance():
            continue
        if ba.index() not in movable_idx and bb.index() not in movable_idx:
            continue
        out.append((float(pp.depth), ba, bb, np.array(pp.nhat_BA_W)))
    return out


def _max_depth(pens):
    return max((p[0] for p in pens), default=0.0)


def _solve_with_deadline(solver, prog, q_vars, q_init, options, seconds):
    """Solves in a forked child killed after `seconds`; returns (status, q or None)."""
    def run():
        result = solver.Solve(prog, q_init, options)
        return str(result.get_solution_result()), bool(result.is_success()), \
            np.asarray(result.GetSolution(q_vars), dtype=float)

    if "fork" not in multiprocessing.get_all_start_methods():
        status, ok, q = run()
        return status, ok, q
    mp = multiprocessing.get_context("fork")
    receiver, sender = mp.Pipe(duplex=False)

    def child():
        try:
            sender.send(run())
        except Exception as e:  # noqa: BLE001 - reported to the parent as a status
            sender.send((f"exception: {type(e).__name__}: {e}", False, None))
        sender.close()

    proc = mp.Process(target=child, daemon=True)
    proc.start()
    sender.close()
    try:
        if receiver.poll(max(seconds, 0.0)):
            status, ok, q = receiver.recv()
        else:
            status, ok, q = "wall-clock limit", False, None
    except EOFError:
        status, ok, q = "solver process died", False, None
    finally:
        if proc.is_alive():
            proc.kill()
        proc.join()
        receiver.close()
    return status, ok, q


def _regions_arg(args, instances):
    """`args.regions` as arrays of half-plane rows [a, b, c] (a x + b y <= c)."""
    out = {}
    for name, rows in args.regions.items():
        if name not in instances:
            raise BadRequest(f"regions names {name!r}, which is not a free model instance")
        out[name] = np.array(rows, dtype=float).reshape(-1, 3)
    return out


def op_project(args):
    """Moves the movable free bodies to the nearest non-penetrating translations."""
    t0 = time.perf_counter()
    scene = CACHE.get(args)
    plant = scene.plant
    ctx = scene.context.Clone()
    pctx = plant.GetMyContextFromRoot(ctx)
    apply_poses(plant, pctx, args.poses)
    min_distance = in_range("min_distance", args.min_distance, 0.0)
    tolerance = in_range("tolerance", args.tolerance, 0.0)
    candidate_distance = in_range("candidate_distance", args.candidate_distance, 0.0)
    time_limit = in_range("time_limit", args.time_limit, 0.0)
    xy_only = args.xy_only
    solver_choice = args.solver
    floor_z = args.floor_z

    bodies = free_bodies(plant)
    by_instance = {}
    for b in bodies:
        by_instance.setdefault(instance_name(plant, b), []).append(b)
    all_idx = {b.index() for b in bodies}
    initial = _penetrations(scene, ctx, all_idx)
    movable_arg = args.movable
    if movable_arg is None:
        if len(by_instance) > 100:
            names = {instance_name(plant, b) for p in initial if p[0] > tolerance
                     for b in (p[1], p[2]) if b.index() in all_idx}
        else:
            names = set(by_instance)
    else:
        unknown = [n for n in movable_arg if n not in by_instance]
        if unknown:
            raise BadRequest(f"movable names instances that are not free: {unknown}")
        names = set(movable_arg)
    regions = _regions_arg(args, by_instance)
    movable = [b for b in bodies if instance_name(plant, b) in names]
    movable_idx = {b.index() for b in movable}
    initial = [p for p in initial if p[1].index() in movable_idx or p[2].index() in movable_idx]
    initial_depth = _max_depth(initial)

    q0 = plant.GetPositions(pctx).copy()
    trans = {b.index(): b.floating_positions_start() + 4 for b in movable}
    geoms = _geometries(scene, pctx)
    lowest = {}
    for g in geoms:
        if g.body.index() in movable_idx:
            lowest[g.body.index()] = min(lowest.get(g.body.index(), np.inf), g.lo[2])
    lb = q0.copy()
    ub = q0.copy()
    for b in movable:
        i = trans[b.index()]
        lb[i:i + 2] = -np.inf
        ub[i:i + 2] = np.inf
        z0 = q0[i + 2]
        z_floor = -np.inf
        if floor_z is not None and b.index() in lowest:
            z_floor = z0 + (floor_z - lowest[b.index()])
        if xy_only:
            lb[i + 2] = ub[i + 2] = max(z0, z_floor)
        else:
            lb[i + 2] = z_floor
            ub[i + 2] = np.inf

    report = {
        "movable": sorted(names),
        "initial_max_penetration_m": initial_depth,
        "attempts": [],
        "pairs": 0,
        "push_out_iterations": None,
    }

    def finish(q, solver_name):
        plant.SetPositions(pctx, q)
        pens = _penetrations(scene, ctx, movable_idx)
        disp = [float(np.linalg.norm(q[trans[b.index()]:trans[b.index()] + 3]
                                     - q0[trans[b.index()]:trans[b.index()] + 3])) for b in movable]
        report.update({
            "solver": solver_name,
            "poses": {n: {b.name(): pose_json(plant.EvalBodyPoseInWorld(pctx, b)) for b in bs}
                      for n, bs in sorted(by_instance.items())},
            "max_penetration_m": _max_depth(pens),
            "mean_displacement_m": float(np.mean(disp)) if disp else 0.0,
            "max_displacement_m": float(np.max(disp)) if disp else 0.0,
            "wall_s": time.perf_counter() - t0,
        })
        return report

    if initial_depth <= tolerance or not movable:
        return finish(q0, "none")

    inspector = scene.scene_graph.model_inspector()

    def candidates(q):
        """Geometry pairs within candidate_distance at q: one movable, not filtered, not the
        floor (the bound handles it)."""
        plant.SetPositions(pctx, q)
        gs = _geometries(scene, pctx)
        floor_ids = {id(g) for g in gs if floor_z is not None and g.body.index() not in all_idx
                     and g.hi[2] <= floor_z + 1e-6}
        out = set()
        for i, a in enumerate(gs):
            for b in gs[i + 1:]:
                if a.body.index() not in movable_idx and b.body.index() not in movable_idx:
                    continue
                if a.body.model_instance() == b.body.model_instance():
                    continue
                if id(a) in floor_ids or id(b) in floor_ids:
                    continue
                if np.any(a.lo - candidate_distance > b.hi) or np.any(b.lo - candidate_distance > a.hi):
                    continue
                if inspector.CollisionFiltered(a.gid, b.gid):
                    continue
                out.add((a.gid, b.gid) if a.gid.get_value() < b.gid.get_value() else (b.gid, a.gid))
        return out

    w = np.zeros(len(q0))
    for b in movable:
        w[trans[b.index()]:trans[b.index()] + 3] = 1.0

    def program(pairs):
        prog = MathematicalProgram()
        q = prog.NewContinuousVariables(len(q0), "q")
        prog.AddBoundingBoxConstraint(lb, ub, q)
        prog.AddQuadraticErrorCost(np.diag(w), q0, q)
        for gid_a, gid_b in sorted(pairs, key=lambda p: (p[0].get_value(), p[1].get_value())):
            prog.AddConstraint(DistanceConstraint(plant, (gid_a, gid_b), pctx, min_distance,
                                                  np.inf), q)
        for name, rows in regions.items():
            for b in by_instance[name]:
                if b.index() not in movable_idx:
                    continue
                i = trans[b.index()]
                prog.AddLinearConstraint(rows[:, :2], np.full(len(rows), -np.inf), rows[:, 2],
                                         q[i:i + 2])
        return prog, q

    q_start = np.clip(q0, lb, ub)
    pairs = candidates(q_start)
    chain = {"auto": ["snopt", "ipopt"], "snopt": ["snopt"], "ipopt": ["ipopt"],
             "push_out": []}[solver_choice]
    for name in chain:
        solver = SnoptSolver() if name == "snopt" else IpoptSolver()
        if not (solver.available() and solver.enabled()):
            report["attempts"].append({"solver": name, "status": "unavailable"})
            continue
        # Pairs are chosen at the start; a solution that moves bodies into new contact is
        # re-solved from there with those pairs added (a few rounds at most).
        q_from = q_start
        for _ in range(6):
            left = time_limit - (time.perf_counter() - t0)
            if left <= 0:
                break
            options = SolverOptions()
            if name == "ipopt":
                options.SetOption(IpoptSolver.id(), "max_wall_time", float(left))
                options.SetOption(IpoptSolver.id(), "print_level", 0)
            prog, q = program(pairs)
            t_solve = time.perf_counter()
            status, ok, q_sol = _solve_with_deadline(solver, prog, q, q_from, options, left)
            attempt = {"solver": name, "status": status, "success": ok, "pairs": len(pairs),
                       "seconds": time.perf_counter() - t_solve}
            report["attempts"].append(attempt)
            if q_sol is None or not np.all(np.isfinite(q_sol)):
                break
            q_sol = np.clip(q_sol, lb, ub)
            plant.SetPositions(pctx, q_sol)
            depth = _max_depth(_penetrations(scene, ctx, movable_idx))
            attempt["max_penetration_m"] = depth
            if depth <= tolerance:
                report["pairs"] = len(pairs)
                return finish(q_sol, name)
            more = candidates(q_sol) - pairs
            if not more:
                break
            pairs |= more
            q_from = q_sol
        plant.SetPositions(pctx, q0)

    report["pairs"] = len(pairs)
    return finish(_push_out(scene, ctx, movable, trans, lb, ub, q0, min_distance, tolerance,
                            xy_only, report), "push_out")


def _push_out(scene, ctx, movable, trans, lb, ub, q0, min_distance, tolerance, xy_only, report):
    """Last resort: move bodies apart along the penetration normals until nothing penetrates."""
    plant = scene.plant
    pctx = plant.GetMyContextFromRoot(ctx)
    movable_idx = set(trans)
    q = q0.copy()
    plant.SetPositions(pctx, q)
    for it in range(200):
        pens = _penetrations(scene, ctx, movable_idx)
        if _max_depth(pens) <= tolerance:
            break
        push = {}
        for depth, ba, bb, n_BA in pens:
            if depth <= tolerance:
                continue
            a_moves = ba.index() in movable_idx
            b_moves = bb.index() in movable_idx
            share = 0.5 if (a_moves and b_moves) else 1.0
            step = (depth + min_distance) * share
            if a_moves:
                push[ba.index()] = push.get(ba.index(), np.zeros(3)) + step * n_BA
            if b_moves:
                push[bb.index()] = push.get(bb.index(), np.zeros(3)) - step * n_BA
        for idx, p in push.items():
            if xy_only:
                p = np.array([p[0], p[1], 0.0])
            i = trans[idx]
            q[i:i + 3] = np.clip(q[i:i + 3] + p, lb[i:i + 3], ub[i:i + 3])
        plant.SetPositions(pctx, q)
    report["push_out_iterations"] = it + 1
    return q
