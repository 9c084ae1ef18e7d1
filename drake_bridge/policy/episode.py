"""One pick-and-place episode: plan (perception, grasp, base, IK, RRT, TOPPRA), roll out in
simulation, write the files. `run_episode` is the entry point.

The plan, in order (segment names as in `EpisodeResult.trajectory.segments`):
  approach  RRT-Connect (lift + arm; base and fingers held) from home to the pre-grasp
            (grasp frame 10 cm back along the approach), fingers open
  descend   straight joint-space move to the grasp (checked with 2 mm scene padding: the open
            fingers pass close to the object and its support by design)
  close     dwell while the fingers close to the grasp's finger target
  lift      the lift joint up 12 cm, else 6 or 3 cm under something that hangs above (a
            straight vertical move; IK instead when the lift joint lacks travel), then, when
            the object is still within the carrying clearance, drawn back 10 cm along the
            approach; only its upper end is collision-checked, its lower end touches the
            support by design
  [tuck, drive, unfold]  only when no place location is reachable from the pick base: RRT to
            the arm's home pose, the base driven (straight, else lazy A* on the navigability
            lattice of navigation.py: through doorways to another room of a house), RRT out
  carry     RRT-Connect with the held object, carrying clearance as the policy says, to the
            pre-place (12 cm above the place pose)
  lower     straight down to the place pose (object 1 cm above the surface)
  release   dwell while the fingers open
  retreat   the gripper up 10 cm: by the lift joint, by IK when the lift is at its top, or
            a short dwell where it cannot rise
Every RRT path is shortcut, every move is timed by TOPPRA (timing.py), and the whole plan is
sampled every 10 ms into one cubic Hermite trajectory of [q, v] that the simulated robot
tracks (rollout.py). The robot appears at the pick base at home; a house task (the reference
in another room) is the drive above, as long as the house between the rooms is.
"""

import contextlib
import math
import os
import time

import numpy as np
from pydrake.geometry import Box, Capsule, Cylinder, Sphere
from pydrake.math import RigidTransform
from pydrake.multibody.tree import BodyIndex
from pydrake.trajectories import PiecewisePolynomial

from drake_bridge.policy import placement
from drake_bridge.policy.grasp import gripper_boxes, sample_grasps
from drake_bridge.policy.ik import solve_grasp_frame_ik
from drake_bridge.policy.navigation import nearest_equivalent_yaw, plan_base_path
from drake_bridge.policy.frames import FrameRenderer, camera_pose, flipbook_html
from drake_bridge.policy.output import (
    write_after_directives,
    write_json,
    write_png,
    write_text,
)
from drake_bridge.policy.rollout import Rollout
from drake_bridge.policy.rrt import PlanningTimeout, rrt_connect, shortcut
from drake_bridge.policy.scene import (
    ARM_PLANNING_JOINTS,
    BASE_JOINTS,
    FINGER_JOINTS,
    FINGER_OPEN_M,
    HELD_JOINT,
    X_GO_PARKED,
    PlanningModel,
    StaticScene,
    home_positions,
    load_scene_spec,
    target_default_pose,
    timing_plant,
)
from drake_bridge.policy.surfaces import GeometrySurfaces, environment_ids, shape_polygons
from drake_bridge.policy.timing import gripper_motion_stats, time_waypoints
from drake_bridge.policy.types import (
    PREDICATES,
    BadTask,
    EpisodeResult,
    GraspInfo,
    PolicyConfig,
    PolicyFailure,
    PoseError,
    TrajectoryInfo,
)
from drake_bridge.sim_plant import pose_json

#: Search breadth: base poses tried for picking, grasps (each also turned half a turn about
#: its approach) tried per base, place positions tried per base.
MAX_BASES = 6
MAX_GRASPS = 8
MAX_PLACES = 8
#: Place positions checked for room for the object (in preference order), and how many of
#: the clear ones, nearest the reference's edge first, are tried for a second base pose.
CHECKED_PLACES = 1000
DRIVE_PLACES = 3 * MAX_PLACES
#: Lift heights tried after the grasp: lift_height_m, half of it, a quarter.
LIFT_TRIES = 3
#: Small objects farther than this from the target and the reference (m, horizontally) are
#: left out of planning (and so of the rollout).
SMALL_OBJECT_SCOPE_M = 1.5
#: A reference smaller than this across (m) stands on something whose centre the place
#: base keeps away from.
SMALL_REFERENCE_M = 0.6
#: Scene padding of the straight descend to the grasp (m).
DESCEND_PADDING_M = 0.002
#: Commanded finger speed while closing or opening (m/s, each finger; the SDF allows 0.21).
FINGER_SPEED_M_S = 0.05
#: The plan is sampled at this period into the tracked trajectory (s).
SAMPLE_DT_S = 0.01
#: Margin around the planned swept volume inside which the simulation keeps scene contact (m).
CONTACT_REGION_INFLATE_M = 0.3
#: Frames per second of the flipbook animation.
FLIPBOOK_FPS = 4.0
#: Budget of the drive's lattice search (expansions) and the margin around the rooms' floor
#: bounds it may use (m).
NAV_MAX_EXPANSIONS = 40_000
NAV_BOUNDS_MARGIN_M = 0.2
#: The base far outside the scene: the robot out of every scene query.
PARK = {"base_x": -50.0, "base_y": -50.0, "base_yaw": 0.0}


class _Clock:
    """Wall time per phase (s), accumulated."""

    def __init__(self):
        self.seconds = {}

    @contextlib.contextmanager
    def phase(self, name):
        start = time.monotonic()
        try:
            yield
        finally:
            self.seconds[name] = self.seconds.get(name, 0.0) + time.monotonic() - start


class _Segment:
    """A piece of the plan: a move through planning configurations `path` of `model`, or a
    dwell of `dwell_s` at path[0]; fingers commanded from `fingers[0]` to `fingers[1]`."""

    def __init__(self, name, model, path, fingers, held, dwell_s=0.0, checked=True):
        self.name, self.model, self.path = name, model, path
        self.checked = checked  # its timed path is collision-checked (straight moves: no)
        self.fingers, self.held, self.dwell_s = fingers, held, dwell_s
        self.timed = None  # Chain over timing-plant positions, for moves


class Episode:
    """The planning state of one episode, step by step (run_episode calls them in order):
    perceive, sample_grasps, place_positions, plan (base poses, IK, RRT), time_segments,
    trajectory. Each step raises PolicyFailure with its reason when it cannot go on; the
    `clock` collects wall time per phase. Construction loads the scene and both planning
    models; BadTask when the task does not fit the scene."""

    def __init__(self, scene_dir, task, config, seed, clock=None, pose_error=None):
        """`pose_error`: the target's pose-estimation error (PoseError); None draws the one
        of `seed`."""
        clock = clock if clock is not None else _Clock()
        self.task, self.config, self.seed, self.clock = task, config, seed, clock
        self.pose_error = PoseError.draw(seed) if pose_error is None else pose_error
        self.rng = np.random.default_rng(seed)
        self.deadline = time.monotonic() + config.planning_budget_s
        with clock.phase("load"):
            self.spec = load_scene_spec(scene_dir)
            for name in (task.target, task.reference):
                if name not in self.spec.instances:
                    raise BadTask(f"{self.spec.directives_path}: no model instance named "
                                  f"{name!r}")
            if task.target == task.reference:
                raise BadTask("target and reference are the same instance")
            self.planning_spec = self.spec.subset(_planning_scope(self.spec, task))
            # The policy's belief: the target where its pose estimate puts it.
            self.X_WO_true = target_default_pose(self.spec, task.target)
            self.static = StaticScene(self.planning_spec, task.target, {task.reference})
            self.approach = PlanningModel(self.planning_spec, task.target, "world", config,
                                          self.pose_error.estimate(self.X_WO_true), self.static)
            self.carry = PlanningModel(self.planning_spec, task.target, "held", config,
                                       static=self.static)
        self.home = home_positions()
        self.welded = self.approach.welded
        self.base_poses = []
        self.grasp = None
        self.X_WO_place = None

    # ---------------------------------------------------------------- helpers
    def _check_time(self, what):
        if time.monotonic() > self.deadline:
            raise PolicyFailure("timeout", f"planning budget of "
                                f"{self.config.planning_budget_s:.0f} s spent ({what})")

    def q_at(self, model, base, fingers=FINGER_OPEN_M, arm=None, X_GO=None):
        """`model`'s q at home (or with `arm` joint values), the base at (x, y, yaw)."""
        values = dict(self.home)
        if arm is not None:
            values.update(arm)
        values.update(base_x=base[0], base_y=base[1], base_yaw=base[2])
        values.update({n: fingers for n in FINGER_JOINTS})
        return model.q_from(values, X_GO)

    def to_model(self, model, q_from_model, q_src, fingers=None, X_GO=None):
        """q_src (a configuration of q_from_model) as a configuration of `model`."""
        values = q_from_model.robot_values(q_src)
        if fingers is not None:
            values.update({n: fingers for n in FINGER_JOINTS})
        return model.q_from(values, X_GO)

    def ik(self, model, X_WG, seed, min_distance):
        self._check_time("IK")
        held = BASE_JOINTS + FINGER_JOINTS + ((HELD_JOINT,) if model.mode == "held" else ())
        with self.clock.phase("ik"):
            return solve_grasp_frame_ik(model, X_WG, seed, held, min_distance, self.rng)

    def raised(self, model, q, dz, X_WG_at_q, min_distance=0.005):
        """q with the gripper dz higher (X_WG_at_q: the grasp frame at q): by the lift joint
        when it has the travel, else by IK."""
        i = model.index["lift"]
        upper = model.plant.GetPositionUpperLimits()[i]
        if q[i] + dz <= upper - 1e-3:
            out = q.copy()
            out[i] += dz
            return out
        X = RigidTransform([0.0, 0.0, dz]).multiply(X_WG_at_q)
        return self.ik(model, X, q, min_distance)

    # ---------------------------------------------------------------- perception
    def perceive(self):
        a = self.approach
        with self.clock.phase("perception"):
            # A context of its own, the robot parked outside the scene: IK moves the model's
            # main context, and this query must see the scene alone for the whole episode.
            self.q_park = a.q_from(dict(self.home, **PARK))
            self.scene_context = a.diagram.CreateDefaultContext()
            plant_context = a.plant.GetMyMutableContextFromRoot(self.scene_context)
            a.plant.SetPositions(plant_context, self.q_park)
            self.query = a.plant.get_geometry_query_input_port().Eval(plant_context)
            self.X_WO0 = a.plant.EvalBodyPoseInWorld(plant_context, a.target_body)
            self.target_ids = set(a.plant.GetCollisionGeometriesForBody(a.target_body))
            robot_and_target = {a.robot, a.target_body.model_instance()}
            target_surfaces = GeometrySurfaces(self.query, sorted(self.target_ids,
                                                                  key=lambda g: g.get_value()))
            self.target_cloud = target_surfaces.sample(0.004, self.rng, drop_internal=True)
            if len(self.target_cloud) == 0:
                raise BadTask(f"target {self.task.target!r} has no collision geometry")
            ref_ids = a.geometries_of(self.task.reference)
            self.reference_cloud = GeometrySurfaces(self.query, ref_ids).sample(
                0.01, self.rng, drop_internal=True)
            if len(self.reference_cloud) == 0:
                raise BadTask(f"reference {self.task.reference!r} has no collision geometry")
            self.env = GeometrySurfaces(self.query,
                                        environment_ids(a.plant, self.query, robot_and_target))
            lo, hi = self.target_cloud.p.min(axis=0), self.target_cloud.p.max(axis=0)
            self.env_near_target = self.env.sample(0.005, self.rng,
                                                   region=(lo - 0.35, hi + 0.35))
            self.shape = placement.ObjectShape(self.target_cloud, self.X_WO0, self.rng)

    def support_centre_xy(self, item=None, env=None):
        """The horizontal centre of the scene body under `item` (a cloud; the target by
        default, `env` the scene's cloud around it), or None (on the floor or unknown)."""
        item = self.target_cloud if item is None else item
        cloud = self.env_near_target if env is None else env
        bottom = item.p[:, 2].min()
        lo, hi = item.p.min(axis=0), item.p.max(axis=0)
        under = ((cloud.n[:, 2] > placement.UP_NORMAL_Z) & (np.abs(cloud.p[:, 2] - bottom) < 0.02)
                 & np.all((cloud.p[:, :2] >= lo[:2]) & (cloud.p[:, :2] <= hi[:2]), axis=1))
        if not np.any(under):
            return None
        pieces = np.unique(cloud.piece[under])
        owner = self.approach.owner
        bodies = {owner(self.env.ids[k]) for k in pieces}
        boxes = [self.env.bounds(k) for k, gid in enumerate(self.env.ids)
                 if owner(gid) in bodies]
        boxes = [b for b in boxes if b is not None]
        lower = np.min([b[0] for b in boxes], axis=0)
        upper = np.max([b[1] for b in boxes], axis=0)
        if np.any(upper[:2] - lower[:2] > 4.0):  # the floor or a room: no useful centre
            return None
        return (lower[:2] + upper[:2]) / 2

    # ---------------------------------------------------------------- grasps and places
    def sample_grasps(self):
        a = self.approach
        with self.clock.phase("grasp"):
            q_open = self.q_at(a, (PARK["base_x"], PARK["base_y"], 0.0))
            boxes = gripper_boxes(a, q_open)
            a.set_q(self.q_park)
            p_com = self.X_WO0.multiply(a.target_body.CalcCenterOfMassInBodyFrame(
                a.plant_context))
            self.grasps = sample_grasps(self.target_cloud, self.env_near_target, boxes, p_com,
                                        self.rng, standoff_m=self.config.pregrasp_offset_m)
        if not self.grasps:
            raise PolicyFailure("no_grasp", f"no antipodal, collision-free grasp of "
                                f"{self.task.target}")

    def place_positions(self):
        with self.clock.phase("perception"):
            radius = self.shape.radius()
            pred = self.task.predicate
            if pred == "on":
                out = placement.on_positions(self.spec, self.task, self.static.body_pose,
                                             self.reference_cloud, radius,
                                             self.X_WO0.translation())
            elif pred == "inside":
                out = placement.inside_positions(self.spec, self.task, self.static.body_pose,
                                                 self.reference_cloud, radius)
            else:
                lo = self.reference_cloud.p.min(axis=0)
                hi = self.reference_cloud.p.max(axis=0)
                env = self.env.sample(0.01, self.rng, region=(lo - 0.4, hi + 0.4))
                out = placement.near_positions(self.reference_cloud, env, radius)
        if not out:
            raise PolicyFailure("ik", f"no place location {pred} {self.task.reference}")
        # Only positions where the object fits at some yaw, so that a cluttered middle of a
        # table does not use up the MAX_PLACES tried per base.
        with self.clock.phase("perception"):
            clear = [position for position in out[:CHECKED_PLACES]
                     if any(placement.object_clear(self.query, self.shape,
                                                   self.shape.pose_at(position, yaw),
                                                   self.target_ids)
                            for yaw in placement.YAWS_RAD)]
        if not clear:
            raise PolicyFailure("ik", f"no place location {pred} {self.task.reference} is clear "
                                f"of the objects already there ({len(out)} tried)")
        self.positions = clear

    # ---------------------------------------------------------------- configurations
    def solve_pick(self, base):
        """(grasp, q_pre, q_grasp, q_grasp_held, lift path, X_GO) from base, or None."""
        a, c = self.approach, self.carry
        for grasp in self.grasps[:MAX_GRASPS]:
            q_home = self.q_at(a, base, fingers=grasp.finger_open())
            for g in (grasp, grasp.flipped()):
                back = RigidTransform([0.0, 0.0, -self.config.pregrasp_offset_m])
                X_pre = g.X_WG.multiply(back)
                q_pre = self.ik(a, X_pre, q_home, 0.01)
                if q_pre is None or not a.checker.CheckConfigCollisionFree(q_pre):
                    continue
                q_grasp = self.ik(a, g.X_WG, q_pre, DESCEND_PADDING_M)
                if q_grasp is None or not self._free_with_padding(a, DESCEND_PADDING_M,
                                                                     [q_pre, q_grasp]):
                    continue
                X_GO = g.X_WG.inverse().multiply(self.X_WO0)
                q_held = self.to_model(c, a, q_grasp, fingers=g.width / 2, X_GO=X_GO)
                lift_path = self._lift(q_held, g.X_WG)
                if lift_path is None:
                    continue
                return g, q_pre, q_grasp, q_held, lift_path, X_GO
        return None

    def _lift(self, q_held, X_WG):
        """The configurations that take the held object off its support, or None: raised by
        lift_height_m, else half, else a quarter of it where something hangs above (a range
        hood over a stove, the next shelf); when the raised object is still within the
        carrying clearance of the scene (only the scene padding is kept), also drawn back
        along the approach by pregrasp_offset_m, out of the confined space."""
        c = self.carry
        back = RigidTransform([0.0, 0.0, -self.config.pregrasp_offset_m])
        for k in range(LIFT_TRIES):
            dz = self.config.lift_height_m / 2 ** k
            q_lift = self.raised(c, q_held, dz, X_WG)
            if q_lift is None:
                continue
            if c.checker.CheckConfigCollisionFree(q_lift):
                return [q_lift]
            scene_padding = self.config.env_padding_m
            if not self._free_with_padding(c, scene_padding, [q_lift]):
                continue
            X_up = RigidTransform([0.0, 0.0, dz]).multiply(X_WG)
            q_back = self.ik(c, X_up.multiply(back), q_lift, self.config.env_padding_m)
            if (q_back is not None and c.checker.CheckConfigCollisionFree(q_back)
                    and self._free_with_padding(c, scene_padding, [q_lift, q_back])):
                return [q_lift, q_back]
        return None

    @staticmethod
    def _free_with_padding(model, padding_m, path):
        """Whether the configuration (or the straight edge) `path` of `model` is
        collision-free with `padding_m` on every robot body."""
        with model.padding(padding_m) as checker:
            if len(path) == 1:
                return checker.CheckConfigCollisionFree(path[0])
            return checker.CheckEdgeCollisionFree(path[0], path[1])

    def solve_place(self, base, pick, positions):
        """(X_WO, q_preplace, q_place) for the first workable position from base, or None."""
        c = self.carry
        g, _, _, _, lift_path, X_GO = pick
        seed = lift_path[-1].copy()
        seed[c.indices(BASE_JOINTS)] = base
        for position in placement.by_reach(base, positions)[:MAX_PLACES]:
            for yaw in placement.YAWS_RAD:
                X_WO = self.shape.pose_at(position, yaw)
                if not placement.object_clear(self.query, self.shape, X_WO, self.target_ids):
                    continue
                X_WG = X_WO.multiply(X_GO.inverse())
                q_place = self.ik(c, X_WG, seed, 0.003)
                if q_place is None:
                    continue
                q_pre = self.raised(c, q_place, self.config.lift_height_m, X_WG)
                if q_pre is None or not c.checker.CheckConfigCollisionFree(q_pre):
                    continue
                return X_WO, q_pre, q_place
        return None

    def choose_configurations(self):
        """Base pose(s), grasp and the key configurations; raises PolicyFailure."""
        a = self.approach
        target_xy = self.X_WO0.translation()[:2]
        centre = self.support_centre_xy()
        preferred = None if centre is None else target_xy - centre
        with self.clock.phase("base"):
            bases = placement.base_candidates(
                a.checker, lambda x, y, yaw: self.q_at(a, (x, y, yaw)), target_xy, preferred)
        if not bases:
            raise PolicyFailure("no_base_pose", f"no collision-free base pose near "
                                f"{self.task.target}")
        # A place beyond any pick base's reach (another room): the first pick will do.
        far = min(np.linalg.norm(p.p_W[:2] - target_xy) for p in self.positions) > (
            2 * placement.MAX_REACH_M)
        first_pick = None
        for base in bases[:MAX_BASES]:
            pick = self.solve_pick(base)
            if pick is None:
                continue
            first_pick = first_pick or (base, pick)
            if far:
                break
            place = self.solve_place(base, pick, self.positions)
            if place is not None:
                self.base_poses = [base]
                return base, pick, base, place
        if first_pick is None:
            raise PolicyFailure("ik", f"no grasp of {self.task.target} solves IK from "
                                f"{min(len(bases), MAX_BASES)} base poses")
        base, pick = first_pick
        # A second base pose for placing, around each place position in turn: those nearest
        # the reference's edge first (a robot reaches the middle of a table with chairs
        # around it from nowhere).
        ref_lo = self.reference_cloud.p[:, :2].min(axis=0)
        ref_hi = self.reference_cloud.p[:, :2].max(axis=0)
        inset = [min(np.min(p.p_W[:2] - ref_lo), np.min(ref_hi - p.p_W[:2]))
                 for p in self.positions]
        by_edge = [self.positions[k] for k in np.argsort(inset, kind="stable")]
        # Away from the centre of what the reference stands on when it is a small thing (a
        # plate on a table: the table's centre), else from the reference's own centre.
        ref_xy = self.reference_cloud.p[:, :2].mean(axis=0)
        if np.all(ref_hi - ref_lo < SMALL_REFERENCE_M):
            lo, hi = self.reference_cloud.p.min(axis=0), self.reference_cloud.p.max(axis=0)
            env = self.env.sample(0.01, self.rng, region=(lo - 0.05, hi + 0.05))
            under = self.support_centre_xy(self.reference_cloud, env)
            ref_xy = ref_xy if under is None else under
        for position in by_edge[:DRIVE_PLACES]:
            with self.clock.phase("base"):
                bases2 = placement.base_candidates(
                    a.checker, lambda x, y, yaw: self.q_at(a, (x, y, yaw)), position.p_W[:2],
                    position.p_W[:2] - ref_xy)
            for base2 in bases2[:3]:
                place = self.solve_place(base2, pick, [position])
                if place is not None:
                    self.base_poses = [base, base2]
                    return base, pick, base2, place
        raise PolicyFailure("ik", f"no place pose {self.task.predicate} "
                            f"{self.task.reference} solves IK")

    # ---------------------------------------------------------------- motion
    def rrt(self, model, q_start, q_goal, joints, what):
        self._check_time(what)
        active = model.indices(joints)
        lower = model.plant.GetPositionLowerLimits().copy()
        upper = model.plant.GetPositionUpperLimits().copy()
        if "base_x" in joints:  # unbounded base joints: the box around both ends + 1.5 m
            for name in ("base_x", "base_y"):
                i = model.index[name]
                lower[i] = min(q_start[i], q_goal[i]) - 1.5
                upper[i] = max(q_start[i], q_goal[i]) + 1.5
            i = model.index["base_yaw"]
            lower[i], upper[i] = min(q_start[i], q_goal[i]) - math.pi, max(
                q_start[i], q_goal[i]) + math.pi
        with self.clock.phase("planning"):
            try:
                path = rrt_connect(model.checker, q_start, q_goal, active, lower, upper,
                                   self.rng, self.config.rrt_max_iterations, self.deadline)
                if path is None:
                    raise PolicyFailure("planning", f"RRT-Connect found no path ({what})")
                return shortcut(model.checker, path, active, self.rng,
                                self.config.shortcut_iterations, self.deadline)
            except PlanningTimeout:
                raise PolicyFailure("timeout", f"planning budget spent in RRT ({what})")

    def drive(self, model, q_from, q_to):
        """The base's path from q_from to q_to (navigation.py), inside the rooms' floor bounds."""
        self._check_time("drive")
        bounds = _room_bounds(self.spec)
        if bounds is not None:
            m = NAV_BOUNDS_MARGIN_M
            bounds = ((bounds[0][0] - m, bounds[0][1] - m), (bounds[1][0] + m, bounds[1][1] + m))
        stats = {}
        with self.clock.phase("planning"):
            try:
                path = plan_base_path(model.checker, q_from, q_to, model.indices(BASE_JOINTS),
                                      self.deadline, max_expansions=NAV_MAX_EXPANSIONS,
                                      xy_bounds=bounds, stats=stats)
            except PlanningTimeout:
                raise PolicyFailure("timeout", "planning budget spent driving the base")
        if path is None:
            raise PolicyFailure("planning", f"no drive for the base to the place pose "
                                f"({stats.get('outcome', 'no path')})")
        return path

    def plan(self):
        """The segments of the motion (module doc)."""
        a, c = self.approach, self.carry
        base, pick, base2, place = self.choose_configurations()
        g, q_pre, q_grasp, q_held, lift_path, X_GO = pick
        q_lift = lift_path[-1]
        X_WO, q_preplace, q_place = place
        self.grasp, self.X_GO, self.X_WO_place = g, X_GO, X_WO
        closed, opened = g.finger_target(), g.finger_open()
        self.q_start = self.q_at(a, base, fingers=opened)
        seg = [_Segment("approach", a, self.rrt(a, self.q_start, q_pre, ARM_PLANNING_JOINTS,
                                                "approach"), (opened,) * 2, False),
               _Segment("descend", a, [q_pre, q_grasp], (opened,) * 2, False),
               _Segment("close", a, [q_grasp], (opened, closed), False,
                        dwell_s=(opened - closed) / FINGER_SPEED_M_S + 0.5),
               _Segment("lift", c, [q_held] + lift_path, (closed,) * 2, True, checked=False)]
        if base2 != base:
            # Turn the short way: the place base's yaw (and with it the place configurations')
            # as the equivalent angle nearest the pick base's.
            i = c.index["base_yaw"]
            turn = nearest_equivalent_yaw(base2[2], base[2]) - base2[2]
            q_preplace, q_place = q_preplace.copy(), q_place.copy()
            q_preplace[i] += turn
            q_place[i] += turn
        if base2 == base:
            seg.append(_Segment("carry", c, self.rrt(c, q_lift, q_preplace, ARM_PLANNING_JOINTS,
                                                     "carry"), (closed,) * 2, True))
        else:
            seg.extend(self._drive_segments(q_lift, q_preplace, closed))
        q_open = q_place.copy()
        q_open[c.indices(FINGER_JOINTS)] = opened
        q_open = c.with_held_pose(q_open, X_GO_PARKED)
        # Up by the lift or, with the lift at its top (a sink reached from above), by IK; a
        # gripper that cannot rise stays where it let go.
        q_retreat = self.raised(c, q_open, self.config.retreat_offset_m,
                                X_WO.multiply(X_GO.inverse()))
        seg += [_Segment("lower", c, [q_preplace, q_place], (closed,) * 2, True),
                _Segment("release", c, [q_place], (closed, opened), True,
                         dwell_s=(opened - closed) / FINGER_SPEED_M_S + 0.3)]
        if q_retreat is not None and np.max(np.abs(q_retreat - q_open)) > 1e-6:
            seg.append(_Segment("retreat", c, [q_open, q_retreat], (opened,) * 2, False))
        else:
            seg.append(_Segment("retreat", c, [q_open], (opened,) * 2, False, dwell_s=0.1))
        self.segments = seg

    def _drive_segments(self, q_lift, q_preplace, closed):
        c = self.carry
        tuck = {n: self.home[n] for n in ARM_PLANNING_JOINTS}
        for lift in (0.6, 0.3, 0.0):
            tuck["lift"] = lift
            q_tuck1 = q_lift.copy()
            for n, v in tuck.items():
                q_tuck1[c.index[n]] = v
            if c.checker.CheckConfigCollisionFree(q_tuck1):
                break
        else:
            raise PolicyFailure("planning", "no collision-free carrying pose to drive with")
        q_tuck2 = q_tuck1.copy()
        q_tuck2[c.indices(BASE_JOINTS)] = q_preplace[c.indices(BASE_JOINTS)]
        return [_Segment("tuck", c, self.rrt(c, q_lift, q_tuck1, ARM_PLANNING_JOINTS, "tuck"),
                         (closed,) * 2, True),
                _Segment("drive", c, self.drive(c, q_tuck1, q_tuck2), (closed,) * 2, True),
                _Segment("unfold", c, self.rrt(c, q_tuck2, q_preplace, ARM_PLANNING_JOINTS,
                                               "unfold"), (closed,) * 2, True)]

    # ---------------------------------------------------------------- timing
    def time_segments(self):
        with self.clock.phase("toppra"):
            self.plant_free, robot = timing_plant()
            self.plant_held, _ = timing_plant(self.spec, self.task.target, self.X_GO)
            self.actuated = [self.plant_free.get_joint_actuator(i).joint().name()
                             for i in self.plant_free.GetJointActuatorIndices(robot)]
            for s in self.segments:
                if s.dwell_s > 0:
                    continue
                plant = self.plant_held if s.held else self.plant_free
                waypoints = [self._timing_q(plant, s.model, q) for q in s.path]
                template = s.path[0]

                def is_free(qt, s=s, plant=plant, template=template):
                    return s.model.checker.CheckConfigCollisionFree(
                        self._planning_q(plant, s.model, qt, template))

                s.timed = time_waypoints(plant, waypoints, self.config,
                                         is_free if len(s.path) > 2 and s.checked else None)
                if s.timed is None:
                    raise PolicyFailure("planning", f"TOPPRA found no timing ({s.name})")

    @staticmethod
    def _timing_q(plant, model, q):
        out = np.zeros(plant.num_positions())
        for name, i in model.index.items():
            out[plant.GetJointByName(name).position_start()] = q[i]
        return out

    @staticmethod
    def _planning_q(plant, model, qt, template):
        q = template.copy()
        for name, i in model.index.items():
            q[i] = qt[plant.GetJointByName(name).position_start()]
        return q

    def trajectory(self):
        """The whole plan as one PiecewisePolynomial of the actuated joints' positions
        (actuator order), plus the segment table and key times."""
        plant = self.plant_free
        order = [plant.GetJointByName(n).position_start() for n in self.actuated]
        fingers = [self.actuated.index(n) for n in FINGER_JOINTS]
        times, Q, V, table, marks = [], [], [], [], {}
        t0 = 0.0
        for s in self.segments:
            if s.dwell_s > 0:
                duration = s.dwell_s
                q_const = self._timing_q(plant, s.model, s.path[0])
                value = lambda t, q=q_const: q  # noqa: E731
                deriv = lambda t, q=q_const: np.zeros_like(q)  # noqa: E731
            else:
                duration = s.timed.end_time()
                value, deriv = s.timed.value, s.timed.derivative
            ramp = (abs(s.fingers[1] - s.fingers[0]) / FINGER_SPEED_M_S
                    if s.fingers[0] != s.fingers[1] else 0.0)
            n = max(2, int(math.ceil(duration / SAMPLE_DT_S)) + 1)
            for k, tau in enumerate(np.linspace(0.0, duration, n)):
                if times and k == 0:
                    continue  # the previous segment's last sample is this one's first
                q, v = np.asarray(value(tau))[order], np.asarray(deriv(tau))[order]
                if ramp > 0:
                    frac = min(1.0, tau / ramp)
                    q[fingers] = s.fingers[0] + frac * (s.fingers[1] - s.fingers[0])
                    v[fingers] = ((s.fingers[1] - s.fingers[0]) / ramp if tau < ramp else 0.0)
                else:
                    q[fingers], v[fingers] = s.fingers[0], 0.0
                times.append(t0 + tau)
                Q.append(q)
                V.append(v)
            table.append({"name": s.name, "start_s": round(t0, 4),
                          "duration_s": round(duration, 4)})
            marks[s.name] = (t0, t0 + duration)
            t0 += duration
        traj = PiecewisePolynomial.CubicHermite(np.array(times), np.array(Q).T, np.array(V).T)
        return traj, table, marks

    def contact_region(self, inflate=CONTACT_REGION_INFLATE_M):
        """The planned swept volume as world boxes (N x 2 x 3: lower, upper): one box per
        configuration along the planned paths (interpolated every 0.1 rad/m) around the robot's
        and the held object's collision geometry, one around the object at its start and at its
        place pose; every box inflated by `inflate` (m)."""
        boxes = []
        for s in self.segments:
            model = s.model
            robots = {model.robot, model.target_body.model_instance()} if s.held else {
                model.robot}
            ids = [g for b in range(model.plant.num_bodies())
                   for g in model.plant.GetCollisionGeometriesForBody(
                       model.plant.get_body(BodyIndex(b)))
                   if model.plant.get_body(BodyIndex(b)).model_instance() in robots]
            inspector = model.query(s.path[0]).inspector()
            radii = np.array([_bounding_radius(inspector.GetShape(g)) for g in ids])
            path = s.path if len(s.path) > 1 else s.path * 2
            for qa, qb in zip(path[:-1], path[1:]):
                n = max(1, int(np.ceil(np.max(np.abs(qb - qa)) / 0.1)))
                for t in np.linspace(0.0, 1.0, n + 1):
                    query = model.query(qa + t * (qb - qa))
                    centres = np.array([query.GetPoseInWorld(g).translation() for g in ids])
                    boxes.append(((centres - radii[:, None]).min(axis=0),
                                  (centres + radii[:, None]).max(axis=0)))
        for X in (self.X_WO0, self.X_WO_place):
            p = X.multiply(self.shape.P_O.T).T
            boxes.append((p.min(axis=0), p.max(axis=0)))
        boxes = np.array(boxes)
        boxes[:, 0] -= inflate
        boxes[:, 1] += inflate
        return boxes

    def static_geometry(self, instances):
        """The StaticScene pieces of `instances` (never the target's: the simulation holds it
        where it truly is, free)."""
        return [g for g in self.static.pieces if g.instance in instances]

    def instances_in(self, boxes):
        """Scene instances with collision geometry touching any of `boxes` (N x 2 x 3), and
        the target."""
        keep = {self.task.target}
        for k, gid in enumerate(self.env.ids):
            b = self.env.bounds(k)
            if b is None:
                continue
            if not np.any(np.all(b[0] <= boxes[:, 1], axis=1) &
                          np.all(b[1] >= boxes[:, 0], axis=1)):
                continue
            keep.add(self.approach.instance_of(gid))
        return keep

    def motion_info(self, table):
        """TrajectoryInfo over the moves (gripper speed from the timing plants)."""
        speed = accel = ratio = 0.0
        for s in self.segments:
            if s.timed is None:
                continue
            plant = self.plant_held if s.held else self.plant_free
            a, b, r = gripper_motion_stats(plant, s.timed)
            speed, accel, ratio = max(speed, a), max(accel, b), max(ratio, r)
        duration = sum(row["duration_s"] for row in table)
        return TrajectoryInfo(segments=table, duration_s=duration, max_gripper_speed_m_s=speed,
                              max_gripper_accel_m_s2=accel, max_joint_speed_ratio=ratio)


def _planning_scope(spec, task):
    """The instances the planning models hold: every one but the small objects (scene.json
    kind "manipuland") farther than SMALL_OBJECT_SCOPE_M from the target and from the
    reference's bounds. What a small object on a far shelf could change is nothing the
    robot reaches; a house's hundreds of them made each IK call and collision check slow.
    Without scene.json every instance stays."""
    def xy_and_radius(name):
        obj = spec.objects.get(name)
        if obj is None:
            return None
        xyz = obj.get("world_from_object", {}).get("xyz")
        bounds = spec.assets.get(obj.get("asset"), {}).get("bounds")
        if xyz is None:
            return None
        radius = 0.0 if bounds is None else 0.5 * float(
            np.linalg.norm(np.subtract(bounds[1], bounds[0])[:2]))
        return np.asarray(xyz[:2], dtype=float), radius

    anchors = [a for a in (xy_and_radius(task.target), xy_and_radius(task.reference)) if a]
    if len(anchors) < 2:
        return set(spec.instances)
    keep = set()
    for name in spec.instances:
        obj = spec.objects.get(name)
        here = xy_and_radius(name)
        if (obj is None or obj.get("kind") != "manipuland" or here is None
                or name in (task.target, task.reference)
                or any(np.linalg.norm(here[0] - xy) <= SMALL_OBJECT_SCOPE_M + r
                       for xy, r in anchors)):
            keep.add(name)
    return keep


def _bounding_radius(shape):
    """Radius of a sphere about the shape's frame origin that holds the shape (m)."""
    if isinstance(shape, Box):
        return 0.5 * float(np.linalg.norm([shape.width(), shape.depth(), shape.height()]))
    if isinstance(shape, Cylinder):
        return float(np.hypot(shape.radius(), shape.length() / 2))
    if isinstance(shape, Capsule):
        return shape.length() / 2 + shape.radius()
    if isinstance(shape, Sphere):
        return shape.radius()
    polygons = shape_polygons(shape)
    return float(max(np.linalg.norm(v, axis=1).max() for v, _ in polygons)) if polygons else 1.0


def _grasp_info(grasp, X_GO):
    return GraspInfo(world_from_grasp=pose_json(grasp.X_WG),
                     grasp_from_object=pose_json(X_GO),
                     contact_a_W=[float(v) for v in grasp.p_a],
                     contact_b_W=[float(v) for v in grasp.p_b],
                     width_m=float(grasp.width), finger_target_m=float(grasp.finger_target()),
                     score=float(grasp.score), top_down_cos=float(grasp.top_down))


def _room_bounds(spec):
    """The rooms' floor bounds ((x0, y0), (x1, y1)) from scene.json, or None."""
    polygons = [p for room in spec.rooms for p in room.get("floor_polygon", [])]
    if not polygons:
        return None
    p = np.array(polygons)
    return tuple(p.min(axis=0)), tuple(p.max(axis=0))


def run_episode(scene_dir, task, policy, out_dir, seed=0, frames=True, animation=True,
                pose_error=None):
    """Runs one pick-and-place episode of `policy` ("standard" or "degraded") for `task` (a
    PickPlaceTask) on the scene in `scene_dir`, writes `after_<policy>.dmd.yaml`, key frames
    `frame_<policy>_<k>_<label>.png` (when `frames`), the flipbook `rollout_<policy>.html`
    (when `frames` and `animation`) and `episode_<policy>.json` into `out_dir`, and returns
    the EpisodeResult. `seed` drives every random choice (grasp seeds, IK restarts, RRT) and
    draws the target's pose-estimation error (types.PoseError) unless `pose_error` gives it:
    the plan believes the estimate, the simulation holds the truth (scene.dmd.yaml).
    Raises BadTask for input that names no runnable episode (unknown policy, predicate or
    instance; a target that is its own reference or not a single free body)."""
    config = PolicyConfig.named(policy)
    if task.predicate not in PREDICATES:
        raise BadTask(f"unknown predicate {task.predicate!r}; expected one of {PREDICATES}")
    out_dir = os.path.abspath(out_dir)
    os.makedirs(out_dir, exist_ok=True)
    clock = _Clock()
    files, failure, message, excluded = {}, None, "executed", []
    grasp_info, trajectory_info, dropped_at, simulated = None, None, None, 0.0
    touched, hits = [], []
    episode = Episode(scene_dir, task, config, seed, clock, pose_error)
    X_WO_final = episode.X_WO_true  # where it stays when no rollout runs
    try:
        episode.perceive()
        episode.sample_grasps()
        episode.place_positions()
        episode.plan()
        grasp_info = _grasp_info(episode.grasp, episode.X_GO)
        episode.time_segments()
        traj, table, marks = episode.trajectory()
        trajectory_info = episode.motion_info(table)
        with clock.phase("rollout"):
            outcome, key, flip, excluded = _roll_out(episode, traj, marks)
        X_WO_final, dropped_at, simulated = (outcome.X_WO_final, outcome.dropped_at_s,
                                             outcome.simulated_s)
        touched, hits = outcome.carry_contacts, outcome.carry_hits
        if frames:
            with clock.phase("frames"):
                files.update(_write_frames(episode, outcome, key, flip, policy, out_dir,
                                           animation))
        if outcome.timed_out:
            failure, message = "timeout", (f"simulation budget of "
                                           f"{config.simulation_budget_s:.0f} s spent")
        elif dropped_at is not None:
            failure, message = "dropped", f"the object left the gripper at {dropped_at:.2f} s"
    except PolicyFailure as f:
        failure, message = f.reason, f.message
    with clock.phase("output"):
        target_body = episode.approach.target_body
        after = os.path.join(out_dir, f"after_{policy}.dmd.yaml")
        write_after_directives(episode.spec, task.target, target_body.name(), X_WO_final, after)
        files["after_directives"] = after
        files["episode"] = os.path.join(out_dir, f"episode_{policy}.json")
    result = EpisodeResult(
        policy=policy, task={"predicate": task.predicate, "target": task.target,
                             "reference": task.reference},
        seed=seed, success=failure is None, failure_reason=failure, message=message,
        timings_s={k: round(v, 3) for k, v in clock.seconds.items()},
        welded_instances=episode.welded,
        base_poses=[[float(v) for v in b] for b in episode.base_poses],
        grasp=grasp_info,
        planned_place_pose=None if episode.X_WO_place is None else pose_json(episode.X_WO_place),
        initial_poses={task.target: pose_json(episode.X_WO_true)},
        final_poses={task.target: pose_json(X_WO_final)},
        pose_error=episode.pose_error, carry_contacts=touched, carry_hits=hits,
        trajectory=trajectory_info, dropped_at_s=dropped_at, simulated_s=simulated,
        excluded_from_simulation=excluded, files=files)
    write_json(files["episode"], result)
    return result


def _roll_out(episode, traj, marks):
    """Simulates the plan (rollout.py) on the scene's instances that the planned motion comes
    near (contact_region, instances_in); returns (outcome, key frame times, flipbook times,
    instances left out of the simulation)."""
    keep = episode.instances_in(episode.contact_region())
    rollout = Rollout(episode.spec, episode.task.target, episode.static_geometry(keep),
                      episode.actuated, episode.approach.robot_values(episode.q_start))
    close_end, release_start = marks["close"][1], marks["release"][0]
    carry_name = "carry" if "carry" in marks else "unfold"
    end = traj.end_time() + episode.config.settle_after_s
    key = [("start", 0.0), ("grasped", close_end), ("carrying", sum(marks[carry_name]) / 2),
           ("placed", marks["release"][1]), ("end", end)]
    flip = [float(t) for t in np.arange(0.0, end, 1.0 / FLIPBOOK_FPS)]
    outcome = rollout.run(traj, (close_end + 0.2, release_start),
                          sorted({t for _, t in key} | set(flip)),
                          episode.config.settle_after_s, episode.config.simulation_budget_s)
    excluded = sorted(set(episode.spec.instances) - set(keep))
    return outcome, key, flip, excluded


def _write_frames(episode, outcome, key, flip, policy, out_dir, animation):
    """Key frames as PNG files and (when `animation`) the flipbook; returns role -> path."""
    files = {}
    focus = (episode.X_WO0.translation() + episode.X_WO_place.translation()) / 2
    # The planning models hold the scene's collision geometry only: frames need its visuals.
    model = PlanningModel(episode.planning_spec, episode.task.target, "held", episode.config)
    renderer = FrameRenderer(model, camera_pose(focus, episode.base_poses[0][:2],
                                                        _room_bounds(episode.spec)))
    records = outcome.records

    def nearest(t):
        return min(records, key=lambda r: abs(r[0] - t))

    for k, (label, t) in enumerate(key):
        time_s, values, X_WO = nearest(t)
        path = os.path.join(out_dir, f"frame_{policy}_{k}_{label}.png")
        write_png(path, renderer.render(values, X_WO))
        files[f"frame_{k}_{label}"] = path
    if animation:
        pages = []
        for t in flip:
            time_s, values, X_WO = nearest(t)
            pages.append((f"{policy} policy, t = {time_s:.2f} s", renderer.render(values, X_WO)))
        path = os.path.join(out_dir, f"rollout_{policy}.html")
        title = (f"{policy}: {episode.task.predicate}({episode.task.target}, "
                 f"{episode.task.reference})")
        write_text(path, flipbook_html(title, pages, FLIPBOOK_FPS))
        files["animation"] = path
    return files
