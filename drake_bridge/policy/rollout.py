"""The closed-loop rollout: the plan played on the robot in a Drake simulation of the scene.

The simulation plant: Drake's default `MultibodyPlantConfig` at a 1 ms time step (hydroelastic
contact with point fallback, Drake's default discrete approximation), the target the only free
scene body, the robot at its start configuration. The rest of the scene is welded: its
collision geometry is registered on the world body (scene.StaticScene: a break-room scene of
777 pieces took 1.59 s of wall time per simulated second parsed as welded bodies, 0.71 s on the
world body; the robot alone in the room 0.74 s). The
robot's `desired_state` input is a `TrajectorySource` of [q, v] of its 13 joints in actuator
order (the PD actuators of the SDFormat track it); its actuation input adds gravity
compensation of the robot's own links (`CalcGravityGeneralizedForces`, not of a held object).

Drop detection: inside the carrying window (from the end of the grasp closing + 0.2 s to the
start of the release) the object's pose in the grasp frame is compared every CHECK_DT_S of
simulated time with its pose at the window's start; a drift above DROP_DRIFT_M means the
object left the gripper ("dropped"). After a drop the simulation runs `settle_after_s` more
and stops. At the same instants, from the grasp's end to the release, the scene instances in
contact with the object are collected (`carry_contacts`): the support it is lifted off and the
one it is lowered onto are expected there; `carry_hits` are the others, those it touched
neither at the first nor at the last of these instants: what the carried object hit.

Frames: the rollout records the robot's joint positions and the object's pose at the requested
times; frames.py renders them from the full welded scene afterwards, so the simulation plant
need not hold what it cannot touch (episode.py leaves out of it every scene instance that lies
outside the planned swept volume).
"""

import dataclasses as dc
import time

import numpy as np
from pydrake.multibody.parsing import Parser
from pydrake.multibody.plant import AddMultibodyPlant, MultibodyPlantConfig
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import BasicVector, DiagramBuilder, LeafSystem
from pydrake.systems.primitives import TrajectorySource

from drake_bridge.policy.scene import ROBOT_URL, add_scene, configure_parser, register_static

TIME_STEP_S = 0.001
CHECK_DT_S = 0.02
DROP_DRIFT_M = 0.03


class _GravityCompensation(LeafSystem):
    """u = -tau_g(q) on the robot's actuators (actuator order), from the plant's state."""

    def __init__(self, plant, robot):
        super().__init__()
        self._plant = plant
        self._context = plant.CreateDefaultContext()
        self._dofs = [plant.get_joint_actuator(i).joint().velocity_start()
                      for i in plant.GetJointActuatorIndices(robot)]
        self.DeclareVectorInputPort("state", plant.num_multibody_states())
        self.DeclareVectorOutputPort("actuation", BasicVector(len(self._dofs)), self._calc)

    def _calc(self, context, output):
        self._plant.SetPositionsAndVelocities(self._context,
                                              self.get_input_port(0).Eval(context))
        tau_g = self._plant.CalcGravityGeneralizedForces(self._context)
        output.SetFromVector(-tau_g[self._dofs])


@dc.dataclass
class RolloutOutcome:
    """The simulated end: the target's final pose X_WO, its final speed (m/s), the time the
    drop was detected (s) or None, the simulated time (s), the recorded states (time, robot
    joint name -> position, X_WO) and whether the wall-clock budget ran out."""

    X_WO_final: object
    carry_contacts: list
    carry_hits: list
    final_speed_m_s: float
    dropped_at_s: object
    simulated_s: float
    records: list
    timed_out: bool


class Rollout:
    """The simulation diagram of one episode (see module doc)."""

    def __init__(self, spec, target, static, actuated_names, q_start):
        """spec: the scene (only its `target` instance is parsed); static: the pieces
        (scene.StaticGeometry) of the welded scene to simulate; q_start: joint name -> value of the robot's start
        configuration."""
        builder = DiagramBuilder()
        plant, _ = AddMultibodyPlant(MultibodyPlantConfig(time_step=TIME_STEP_S), builder)
        parser = Parser(plant)
        configure_parser(parser, spec)
        (robot,) = parser.AddModels(url=ROBOT_URL)
        _, self.target_body = add_scene(plant, parser, spec.subset({target}), target, "free",
                                        robot)
        self._static_owner = register_static(plant, static)
        plant.Finalize()
        self.plant, self.robot, self.builder = plant, robot, builder
        names = [plant.get_joint_actuator(i).joint().name()
                 for i in plant.GetJointActuatorIndices(robot)]
        assert names == list(actuated_names), (names, actuated_names)
        self.joint_names = names
        gravity = builder.AddSystem(_GravityCompensation(plant, robot))
        builder.Connect(plant.get_state_output_port(), gravity.get_input_port(0))
        builder.Connect(gravity.get_output_port(0), plant.get_actuation_input_port(robot))
        self.q_start = q_start

    def run(self, trajectory, carry_window, record_times, settle_after_s, budget_s):
        """Simulates `trajectory` (a PiecewisePolynomial of the 13 actuated positions) to its end
        plus `settle_after_s`. `carry_window`: (start, end) in s or None; `record_times`: the
        times (s) at which to record the state for frames (a time past the end is recorded at
        the end)."""
        source = self.builder.AddSystem(TrajectorySource(trajectory, output_derivative_order=1))
        self.builder.Connect(source.get_output_port(),
                             self.plant.get_desired_state_input_port(self.robot))
        diagram = self.builder.Build()
        simulator = Simulator(diagram)
        context = simulator.get_mutable_context()
        plant, body = self.plant, self.target_body
        plant_context = plant.GetMyMutableContextFromRoot(context)
        q = plant.GetPositions(plant_context)
        for name, value in self.q_start.items():
            q[plant.GetJointByName(name, self.robot).position_start()] = value
        plant.SetPositions(plant_context, q)
        grasp_frame = plant.GetFrameByName("grasp_frame", self.robot)
        simulator.Initialize()

        end = trajectory.end_time() + settle_after_s
        records, pending = [], sorted(record_times)
        X_GO_ref, dropped_at, timed_out = None, None, False
        touched, first, last = set(), None, set()
        deadline = time.monotonic() + budget_s
        t = 0.0
        while True:
            while pending and pending[0] <= t + 1e-9:
                pending.pop(0)
                records.append(self._record(t, plant_context))
            if t >= end - 1e-9:
                break
            t = min(end, t + CHECK_DT_S)
            simulator.AdvanceTo(t)
            # Contacts from the grasp's end (the window opens 0.2 s after it) to the release.
            if carry_window is not None and carry_window[0] - 0.2 <= t <= carry_window[1]:
                last = self._touching(plant_context)
                first = last if first is None else first
                touched |= last
            if carry_window is not None and dropped_at is None and (
                    carry_window[0] <= t <= carry_window[1]):
                X_GO = grasp_frame.CalcPoseInWorld(plant_context).inverse().multiply(
                    plant.EvalBodyPoseInWorld(plant_context, body))
                if X_GO_ref is None:
                    X_GO_ref = X_GO
                elif np.linalg.norm(X_GO.translation() - X_GO_ref.translation()) > DROP_DRIFT_M:
                    dropped_at = t
                    end = min(end, t + settle_after_s)
            if time.monotonic() > deadline:
                timed_out = True
                break
        if pending:
            records.append(self._record(t, plant_context))
        V = plant.EvalBodySpatialVelocityInWorld(plant_context, body)
        return RolloutOutcome(
            X_WO_final=plant.EvalBodyPoseInWorld(plant_context, body),
            carry_contacts=sorted(touched), carry_hits=sorted(touched - (first or set()) - last),
            final_speed_m_s=float(np.linalg.norm(V.translational())),
            dropped_at_s=dropped_at, simulated_s=t, records=records, timed_out=timed_out)

    def _touching(self, plant_context):
        """The names of the scene instances (not the robot) in contact with the target now."""
        plant = self.plant
        results = plant.get_contact_results_output_port().Eval(plant_context)
        inspector = plant.get_geometry_query_input_port().Eval(plant_context).inspector()
        pairs = [(results.point_pair_contact_info(i).point_pair().id_A,
                  results.point_pair_contact_info(i).point_pair().id_B)
                 for i in range(results.num_point_pair_contacts())]
        for i in range(results.num_hydroelastic_contacts()):
            surface = results.hydroelastic_contact_info(i).contact_surface()
            pairs.append((surface.id_M(), surface.id_N()))
        target = set(plant.GetCollisionGeometriesForBody(self.target_body))
        out = set()
        for a, b in pairs:
            if (a in target) == (b in target):
                continue
            other = b if a in target else a
            if other in self._static_owner:
                out.add(self._static_owner[other][0])
                continue
            instance = plant.GetBodyFromFrameId(inspector.GetFrameId(other)).model_instance()
            if instance != self.robot:
                out.add(plant.GetModelInstanceName(instance))
        return out

    def _record(self, t, plant_context):
        q = self.plant.GetPositions(plant_context)
        values = {n: float(q[self.plant.GetJointByName(n, self.robot).position_start()])
                  for n in self.joint_names}
        return t, values, self.plant.EvalBodyPoseInWorld(plant_context, self.target_body)
