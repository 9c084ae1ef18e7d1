"""Gravity settling and fixed-length simulation of a scene's free bodies.

`settle` runs a discrete plant (1 ms, SAP-family "lagged" approximation by default) until every
free body has stayed slower than the rest thresholds for `rest_time` seconds, or `max_time`
simulated seconds, or `wall_limit` wall seconds, or a body's state goes non-finite
(`diverged`: the poses and motion are then those at the last rest window's start); it returns
the final free-body poses and how far each instance moved. `simulate` is the same loop for a
fixed duration (the STB metric). With a `verdict` bound (the STB thresholds), it also stops
once the rest of the duration cannot change any body's verdict (`bounded`; see `_verdict_fixed`).
Neither decides what is removed: the caller reads the motions and applies its own rules.
"""

import time

import numpy as np
from pydrake.all import Simulator

from drake_bridge.protocol import Motion, SettleReply, in_range
from drake_bridge.sim_plant import SIM_CACHE, apply_poses, free_bodies, instance_name, pose_json


def _max_penetration(scene, ctx):
    """Deepest overlap between two different model instances where one can move, metres."""
    plant = scene.plant
    query = scene.scene_graph.get_query_output_port().Eval(scene.scene_graph_context(ctx))
    inspector = query.inspector()
    deepest = 0.0
    for pp in query.ComputePointPairPenetration():
        ba = plant.GetBodyFromFrameId(inspector.GetFrameId(pp.id_A))
        bb = plant.GetBodyFromFrameId(inspector.GetFrameId(pp.id_B))
        if ba.model_instance() == bb.model_instance():
            continue
        deepest = max(deepest, float(pp.depth))
    return deepest


def _fell(plant, pctx, body, floor_z):
    """True once a body has dropped half a metre below the floor."""
    return floor_z is not None and plant.EvalBodyPoseInWorld(pctx, body).translation()[2] < floor_z - 0.5


def _moved_less(X0, X1, distance, angle):
    """True when pose X1 is within `distance` metres and `angle` radians of X0."""
    if float(np.linalg.norm(X1.translation() - X0.translation())) >= distance:
        return False
    return float(X0.rotation().InvertAndCompose(X1.rotation()).ToAngleAxis().angle()) < angle


# A bounded stop leaves every body at most this fraction of the way to a verdict threshold,
# counting what its motion of the last two windows, extrapolated, would add by the end.
VERDICT_MARGIN = 0.5


def _turned(X0, X1):
    return float(X0.rotation().InvertAndCompose(X1.rotation()).ToAngleAxis().angle())


def _verdict_fixed(total, window, before, window_s, left, bound):
    """True when one body's verdict cannot change over the `left` seconds to go.

    `total` is its (displacement, rotation) from the start, `window` and `before` its motion over
    the last two rest windows of `window_s` seconds, `bound` the (displacement, rotation)
    thresholds. What the rest of the time could add is extrapolated window by window from the
    larger of the two windows, growing each window by as much as the last one grew (a body
    tipping over speeds up: uniform acceleration is extrapolated exactly; chatter that happens
    to grow is extrapolated as if it kept growing, which only delays the stop). A body
    qualifies when that keeps it under VERDICT_MARGIN of both thresholds to the end; or when it
    is past a threshold by more than that could bring back and all but still (a tumbler
    rolling away keeps the simulation going, for MD and XD). Returns the extrapolated motion
    per second of the time left too, so the caller can add it.
    """
    n = left / window_s
    extra = []
    for k in range(2):
        growth = max(0.0, window[k] - before[k])
        extra.append(max(window[k], before[k]) * n + growth * n * (n + 1.0) / 2.0)
    stays = all(total[k] + extra[k] < VERDICT_MARGIN * bound[k] for k in range(2))
    gone = (any(total[k] - extra[k] > (2.0 - VERDICT_MARGIN) * bound[k] for k in range(2))
            and all(extra[k] < VERDICT_MARGIN * bound[k] for k in range(2)))
    pace = [e / left if left > 0 else 0.0 for e in extra]
    return stays or gone, pace


def _run(args, duration):
    """Runs a protocol.SettleArgs / SimulateArgs for `duration` simulated seconds."""
    time_step = in_range("time_step", args.time_step, 1e-4, 1e-2)
    in_range("duration", duration, 0.0, 600.0)
    rest_speed = in_range("rest_speed", args.rest_speed, 0.0)
    rest_angular_speed = in_range("rest_angular_speed", args.rest_angular_speed, 0.0)
    rest_time = in_range("rest_time", args.rest_time, 0.0)
    interval = in_range("check_interval", args.check_interval, time_step)
    wall_limit = in_range("wall_limit", args.wall_limit, 0.0)
    stop_at_rest = args.stop_at_rest
    floor_z = args.floor_z

    t_wall = time.perf_counter()
    scene = SIM_CACHE.get(args, args.contact, time_step)
    build_s = time.perf_counter() - t_wall
    plant = scene.plant
    ctx = scene.context.Clone()
    pctx = plant.GetMyContextFromRoot(ctx)
    apply_poses(plant, pctx, args.poses)
    bodies = free_bodies(plant)
    start = {b.index(): plant.EvalBodyPoseInWorld(pctx, b) for b in bodies}

    simulator = Simulator(scene.diagram, ctx)
    simulator.Initialize()
    t_sim = time.perf_counter()
    t = 0.0
    quiet_for = 0.0
    at_rest = False
    timed_out = False
    v_max = w_max = 0.0
    # Rest is either every body slower than the thresholds for `rest_time`, or every body
    # within `rest_time` x the thresholds of where it was `rest_time` ago: a light object
    # chattering in place (a book in a drawer, at 5 mm/s and 0.2 mm) is at rest too. Two
    # still windows in a row: something that only starts to tip moves little in its first.
    window_t0, window_poses, still_windows = 0.0, dict(start), 0
    window_motion = {}
    rates = {}
    bounded = False
    verdict = args.verdict if stop_at_rest else None
    diverged = False
    while t < duration - 1e-12:
        t_next = min(duration, t + interval)
        try:
            simulator.AdvanceTo(t_next)
        except RuntimeError as e:
            if "non-finite" not in str(e):
                raise
            # A body's state went NaN: stop, and put every body back where it was at the
            # last window's start (finite), so the reply holds the motion up to there.
            diverged = True
            for b in bodies:
                plant.SetFreeBodyPose(pctx, b, window_poses[b.index()])
            plant.SetVelocities(pctx, np.zeros(plant.num_velocities()))
            t = window_t0
            break
        t = t_next
        v_max = w_max = 0.0
        for b in bodies:
            if _fell(plant, pctx, b, floor_z):
                continue  # fell out of the scene; it will not come to rest
            V = plant.EvalBodySpatialVelocityInWorld(pctx, b)
            v_max = max(v_max, float(np.linalg.norm(V.translational())))
            w_max = max(w_max, float(np.linalg.norm(V.rotational())))
        quiet_for = quiet_for + interval if (v_max < rest_speed and w_max < rest_angular_speed) else 0.0
        window_end = t - window_t0 >= rest_time - 1e-9
        if window_end:
            now = {b.index(): plant.EvalBodyPoseInWorld(pctx, b) for b in bodies}
            window_still = all(
                _fell(plant, pctx, b, floor_z)
                or _moved_less(window_poses[b.index()], now[b.index()],
                               rest_speed * rest_time, rest_angular_speed * rest_time)
                for b in bodies)
            still_windows = still_windows + 1 if window_still else 0
            before_motion = window_motion
            window_motion = {
                b.index(): (float(np.linalg.norm(now[b.index()].translation()
                                                 - window_poses[b.index()].translation())),
                            _turned(window_poses[b.index()], now[b.index()]))
                for b in bodies}
            window_t0, window_poses = t, now
            if verdict is not None and before_motion:
                bound = (verdict.max_displacement_m, verdict.max_rotation_rad)
                rates, bounded = {}, True
                for b in bodies:
                    if _fell(plant, pctx, b, floor_z):
                        continue
                    i = b.index()
                    total = (float(np.linalg.norm(now[i].translation() - start[i].translation())),
                             _turned(start[i], now[i]))
                    fixed, r = _verdict_fixed(total, window_motion[i], before_motion[i],
                                              rest_time, duration - t, bound)
                    if not fixed:
                        bounded = False
                        break
                    rates[i] = tuple(r)
        if quiet_for >= rest_time - 1e-9 or still_windows >= 2:
            at_rest = True
            if stop_at_rest:
                break
        else:
            at_rest = False
            if window_end and bounded:
                break
        if time.perf_counter() - t_wall > wall_limit:
            timed_out = True
            break
    sim_s = time.perf_counter() - t_sim

    poses = {}
    motion = {}
    for b in bodies:
        X0 = start[b.index()]
        X = plant.EvalBodyPoseInWorld(pctx, b)
        name = instance_name(plant, b)
        poses.setdefault(name, {})[b.name()] = pose_json(X)
        disp = float(np.linalg.norm(X.translation() - X0.translation()))
        rot = _turned(X0, X)
        m = motion.setdefault(name, Motion(displacement_m=0.0, rotation_rad=0.0,
                                           start_z=float(X0.translation()[2]),
                                           end_z=float(X.translation()[2])))
        m.displacement_m = max(m.displacement_m, disp)
        m.rotation_rad = max(m.rotation_rad, rot)
        if bounded and not at_rest:
            r = rates.get(b.index(), (0.0, 0.0))
            m.speed_bound = max(m.speed_bound, r[0])
            m.angular_speed_bound = max(m.angular_speed_bound, r[1])
    steps = int(round(t / time_step))
    return SettleReply(
        poses=poses,
        motion=motion,
        sim_time=t,
        steps=steps,
        at_rest=at_rest and not diverged,
        timed_out=timed_out,
        diverged=diverged,
        bounded=bounded and not at_rest and not diverged and not timed_out,
        max_speed=v_max,
        max_angular_speed=w_max,
        max_penetration_m=_max_penetration(scene, ctx),
        free_bodies=len(bodies),
        contact=args.contact,
        time_step=time_step,
        build_s=build_s,
        sim_s=sim_s,
        wall_s=time.perf_counter() - t_wall,
        ms_per_step=1e3 * sim_s / steps if steps else 0.0,
        cache={"hits": SIM_CACHE.hits, "misses": SIM_CACHE.misses},
    )


def op_settle(args):
    """protocol.SettleArgs: simulates until rest (or `max_time`); final free-body poses."""
    return _run(args, args.max_time)


def op_simulate(args):
    """protocol.SimulateArgs: simulates `duration` seconds; how far every free body moved."""
    return _run(args, args.duration)
