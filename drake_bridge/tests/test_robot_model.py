"""The mobile iiwa of sdf_templates/ checked with Drake, the consumer it is written for.

What is pinned: the data-sheet figures (KUKA LBR iiwa 14 R820 joint ranges, speeds and torques,
link offsets, weight; Schunk WSG 50 stroke and force) survive parsing; every joint is actuated;
every inertia is physically valid; the home pose is free of self-collision; the hardware_sim
style scenario loads with Drake's own YAML and directive loaders, holds the robot at home for
1 s under gravity, and a grasp target in front of the base is reachable by IK.
"""

import dataclasses as dc
import math
import os
import typing

import numpy as np
import pytest

from pydrake.common.yaml import yaml_load_typed
from pydrake.lcm import DrakeLcmParams
from pydrake.manipulation import (
    ApplyDriverConfigs,
    IiwaDriver,
    SchunkWsgDriver,
    ZeroForceDriver,
)
from pydrake.multibody.inverse_kinematics import InverseKinematics
from pydrake.multibody.parsing import (
    ModelDirective,
    ModelDirectives,
    Parser,
    ProcessModelDirectives,
)
from pydrake.multibody.plant import (
    AddMultibodyPlant,
    AddMultibodyPlantSceneGraph,
    MultibodyPlantConfig,
)
from pydrake.solvers import Solve
from pydrake.systems.analysis import ApplySimulatorConfig, Simulator, SimulatorConfig
from pydrake.systems.framework import DiagramBuilder
from pydrake.systems.lcm import ApplyLcmBusConfig
from pydrake.systems.sensors import CameraConfig
from pydrake.visualization import ApplyVisualizationConfig, VisualizationConfig

from drake_bridge.tests.conftest import ROOT, write_scene

TEMPLATES = os.path.join(ROOT, "sdf_templates")
PACKAGE_XML = os.path.join(TEMPLATES, "package.xml")
ROBOT_URL = "package://scenesmith_robots/mobile_iiwa/mobile_iiwa.sdf"
SCENARIO = os.path.join(TEMPLATES, "mobile_iiwa", "scenario.yaml")
SCENARIO_NAME = "mobile_iiwa_in_scene"
ROBOT = "mobile_iiwa"

ARM_JOINTS = [f"iiwa_joint_{i}" for i in range(1, 8)]
ARM_LINKS = [f"iiwa_link_{i}" for i in range(0, 8)]
BASE_JOINTS = ["base_x", "base_y", "base_yaw"]
FINGER_JOINTS = ["right_finger_joint", "left_finger_joint"]

# KUKA LBR iiwa 14 R820 data sheet, per axis A1..A7.
RANGE_DEG = [170, 120, 170, 120, 170, 120, 175]
SPEED_DEG_S = [85, 85, 100, 75, 130, 135, 135]
TORQUE_NM = [320, 320, 176, 176, 110, 40, 40]
ARM_MASS_KG = 29.5
# Axis 2 above the arm base, axis 2 -> 4, axis 4 -> 6, axis 6 -> flange (m).
ARM_OFFSETS_M = [0.36, 0.42, 0.40, 0.126]
# Schunk WSG 50 data sheet: total stroke and gripping force.
WSG_STROKE_M = 0.110
WSG_FORCE_N = 80.0


@dc.dataclass
class Scenario:
    """The YAML schema of drake/examples/hardware_sim (the Python `Scenario` there), restated
    because pydrake does not ship it: the field names, types and defaults must match."""

    random_seed: int = 0
    simulation_duration: float = math.inf
    simulator_config: SimulatorConfig = dc.field(default_factory=lambda: SimulatorConfig(
        max_step_size=1e-3, accuracy=1e-2, target_realtime_rate=1.0))
    plant_config: MultibodyPlantConfig = dc.field(default_factory=MultibodyPlantConfig)
    directives: typing.List[ModelDirective] = dc.field(default_factory=list)
    lcm_buses: typing.Mapping[str, DrakeLcmParams] = dc.field(
        default_factory=lambda: dict(default=DrakeLcmParams()))
    model_drivers: typing.Mapping[str, typing.Union[
        IiwaDriver, SchunkWsgDriver, ZeroForceDriver]] = dc.field(default_factory=dict)
    cameras: typing.Mapping[str, CameraConfig] = dc.field(default_factory=dict)
    visualization: VisualizationConfig = dc.field(default_factory=VisualizationConfig)


def load_scenario(overrides="{}"):
    scenario = yaml_load_typed(schema=Scenario, filename=SCENARIO, child_name=SCENARIO_NAME,
                               defaults=Scenario())
    return yaml_load_typed(schema=Scenario, data=overrides, defaults=scenario)


def home_positions():
    """The scenario's `default_joint_positions` of the robot: the one place "home" is defined."""
    for directive in load_scenario().directives:
        if directive.add_model is not None and directive.add_model.name == ROBOT:
            return {name: values[0]
                    for name, values in directive.add_model.default_joint_positions.items()}
    raise AssertionError(f"{SCENARIO}: no add_model named {ROBOT}")


class Robot:
    """The robot alone (no scene) in a plant with a scene graph, finalized."""

    def __init__(self):
        builder = DiagramBuilder()
        self.plant, self.scene_graph = AddMultibodyPlantSceneGraph(builder, time_step=0.001)
        parser = Parser(self.plant)
        parser.SetStrictParsing()  # a warning (an unknown drake: tag, say) fails the parse
        parser.package_map().AddPackageXml(PACKAGE_XML)
        (self.model,) = parser.AddModels(url=ROBOT_URL)
        self.plant.Finalize()
        self.diagram = builder.Build()
        self.context = self.diagram.CreateDefaultContext()
        self.plant_context = self.plant.GetMyMutableContextFromRoot(self.context)

    def joint(self, name):
        return self.plant.GetJointByName(name, self.model)

    def frame(self, name):
        return self.plant.GetFrameByName(name, self.model)

    def set_positions(self, positions):
        for name, value in positions.items():
            joint = self.joint(name)
            q = self.plant.GetPositions(self.plant_context)
            q[joint.position_start()] = value
            self.plant.SetPositions(self.plant_context, q)

    def query(self):
        return self.scene_graph.get_query_output_port().Eval(
            self.scene_graph.GetMyContextFromRoot(self.context))


@pytest.fixture(scope="module")
def robot():
    return Robot()


def test_every_joint_is_actuated_with_the_published_limits(robot):
    plant = robot.plant
    # Planar base (x, y, yaw), lift, seven arm axes, two fingers.
    assert plant.num_positions(robot.model) == 13
    assert plant.num_velocities(robot.model) == 13
    actuated = {plant.get_joint_actuator(i).joint().name(): plant.get_joint_actuator(i)
                for i in plant.GetJointActuatorIndices(robot.model)}
    assert sorted(actuated) == sorted(BASE_JOINTS + ["lift"] + ARM_JOINTS + FINGER_JOINTS)
    for name, actuator in actuated.items():
        assert actuator.has_controller(), f"{name}: no PD gains (drake:controller_gains)"
        assert actuator.get_controller_gains().p > 0, name
        assert np.all(robot.joint(name).acceleration_upper_limits() > 0), name

    for name, range_deg, speed, torque in zip(ARM_JOINTS, RANGE_DEG, SPEED_DEG_S, TORQUE_NM):
        joint = robot.joint(name)
        assert joint.type_name() == "revolute", name
        np.testing.assert_allclose(joint.position_upper_limits(), [math.radians(range_deg)],
                                   atol=1e-6, err_msg=name)
        np.testing.assert_allclose(joint.position_lower_limits(), [-math.radians(range_deg)],
                                   atol=1e-6, err_msg=name)
        np.testing.assert_allclose(joint.velocity_upper_limits(), [math.radians(speed)],
                                   atol=1e-6, err_msg=name)
        assert actuated[name].effort_limit() == torque, name

    for name in FINGER_JOINTS:
        joint = robot.joint(name)
        assert joint.type_name() == "prismatic", name
        assert joint.position_lower_limits()[0] == 0.0
        assert joint.position_upper_limits()[0] == pytest.approx(WSG_STROKE_M / 2)
        assert actuated[name].effort_limit() == WSG_FORCE_N
    lift = robot.joint("lift")
    assert lift.type_name() == "prismatic"
    assert lift.position_upper_limits()[0] - lift.position_lower_limits()[0] == pytest.approx(0.6)


def test_arm_weighs_the_data_sheet_mass_and_every_inertia_is_physically_valid(robot):
    plant = robot.plant
    arm_mass = sum(plant.GetBodyByName(name, robot.model).default_mass() for name in ARM_LINKS)
    assert arm_mass == pytest.approx(ARM_MASS_KG, rel=0.10)
    for index in plant.GetBodyIndices(robot.model):
        body = plant.get_body(index)
        assert body.default_mass() > 0, body.name()
        assert body.default_spatial_inertia().IsPhysicallyValid(), body.name()
    base = plant.GetBodyByName("base_link", robot.model)
    assert base.default_mass() == pytest.approx(60.0)


def test_straight_arm_puts_the_flange_the_published_length_above_the_carriage(robot):
    robot.set_positions({name: 0.0 for name in ARM_JOINTS})
    X_CF = robot.plant.CalcRelativeTransform(
        robot.plant_context, robot.frame("lift_carriage"), robot.frame("flange"))
    np.testing.assert_allclose(X_CF.translation(), [0.0, 0.0, sum(ARM_OFFSETS_M)], atol=1e-3)
    # Axis 2, 4 and 6 at their published heights too (our link frames sit on the axes).
    expected = np.cumsum(ARM_OFFSETS_M[:3])
    for link, height in zip(["iiwa_link_2", "iiwa_link_4", "iiwa_link_6"], expected):
        p_CL = robot.plant.CalcRelativeTransform(
            robot.plant_context, robot.frame("lift_carriage"), robot.frame(link)).translation()
        assert p_CL[2] == pytest.approx(height, abs=1e-3), link


def test_home_pose_is_free_of_self_collision_with_a_margin(robot):
    robot.set_positions(home_positions())
    query = robot.query()
    inspector = query.inspector()
    assert query.ComputePointPairPenetration() == []
    close = [(inspector.GetName(pair.id_A), inspector.GetName(pair.id_B), pair.distance)
             for pair in query.ComputeSignedDistancePairwiseClosestPoints(max_distance=0.005)]
    assert close == [], f"collision geometries closer than 5 mm at home: {close}"
    # Home holds the gripper over the floor in front of the base, pointing down.
    X_WG = robot.plant.CalcRelativeTransform(
        robot.plant_context, robot.frame("base_footprint"), robot.frame("grasp_frame"))
    assert X_WG.translation()[0] > 0.3
    assert X_WG.rotation().matrix()[:, 2] @ [0.0, 0.0, -1.0] > math.cos(math.radians(1.0))


def _finger_inner_faces_y(robot):
    """The y coordinate, in the gripper body frame B, of each finger box's gripping face."""
    query = robot.query()
    inspector = query.inspector()
    X_WB = robot.plant.EvalBodyPoseInWorld(
        robot.plant_context, robot.plant.GetBodyByName("gripper_body", robot.model))
    faces = {}
    for name in ["right_finger", "left_finger"]:
        body = robot.plant.GetBodyByName(name, robot.model)
        (geometry,) = robot.plant.GetCollisionGeometriesForBody(body)
        center_y = (X_WB.inverse() @ query.GetPoseInWorld(geometry)).translation()[1]
        half_depth = inspector.GetShape(geometry).depth() / 2  # box extent along y
        faces[name] = center_y - half_depth if center_y > 0 else center_y + half_depth
    return faces


def test_fingers_open_to_the_data_sheet_stroke_and_close_to_touching(robot):
    robot.set_positions({name: 0.0 for name in ARM_JOINTS})
    robot.set_positions({name: WSG_STROKE_M / 2 for name in FINGER_JOINTS})
    faces = _finger_inner_faces_y(robot)
    assert faces["right_finger"] - faces["left_finger"] == pytest.approx(WSG_STROKE_M, abs=1e-6)
    robot.set_positions({name: 0.0 for name in FINGER_JOINTS})
    faces = _finger_inner_faces_y(robot)
    assert faces["right_finger"] - faces["left_finger"] == pytest.approx(0.0, abs=1e-6)
    # The grasp frame lies between the finger pads.
    X_BG = robot.plant.CalcRelativeTransform(
        robot.plant_context, robot.frame("gripper_body"), robot.frame("grasp_frame"))
    assert X_BG.translation()[1] == pytest.approx(0.0)
    assert 0.07 < X_BG.translation()[2] < 0.16


def _solve_top_down_grasp_ik(robot, p_target_in_footprint):
    """IK for a top-down grasp at a point given in the base footprint frame, the base held at
    home (only the lift and the arm move), 5 mm clearance between all robot geometries."""
    plant = robot.plant
    robot.set_positions(home_positions())
    q_home = plant.GetPositions(robot.plant_context)
    ik = InverseKinematics(plant, robot.plant_context, with_joint_limits=True)
    q = ik.q()
    target = np.asarray(p_target_in_footprint)
    ik.AddPositionConstraint(
        frameB=robot.frame("grasp_frame"), p_BQ=np.zeros(3),
        frameA=robot.frame("base_footprint"),
        p_AQ_lower=target - 1e-3, p_AQ_upper=target + 1e-3)
    ik.AddAngleBetweenVectorsConstraint(
        frameA=plant.world_frame(), na_A=[0.0, 0.0, -1.0],
        frameB=robot.frame("grasp_frame"), nb_B=[0.0, 0.0, 1.0],
        angle_lower=0.0, angle_upper=math.radians(1.0))
    ik.AddMinimumDistanceLowerBoundConstraint(0.005)
    prog = ik.get_mutable_prog()
    for name in BASE_JOINTS:
        i = robot.joint(name).position_start()
        prog.AddBoundingBoxConstraint(q_home[i], q_home[i], q[i])
    prog.SetInitialGuess(q, q_home)
    result = Solve(prog)
    return result, result.GetSolution(q)


def test_top_down_grasp_in_front_of_the_base_is_reachable_by_ik(robot):
    """0.6 m in front of the base centre at 0.8 m height, gripper pointing down."""
    target = [0.6, 0.0, 0.8]
    result, q_sol = _solve_top_down_grasp_ik(robot, target)
    assert result.is_success(), f"IK failed ({result.get_solver_id().name()})"
    plant = robot.plant
    lower, upper = plant.GetPositionLowerLimits(), plant.GetPositionUpperLimits()
    assert np.all(q_sol >= lower - 1e-6) and np.all(q_sol <= upper + 1e-6)
    plant.SetPositions(robot.plant_context, q_sol)
    X_AG = plant.CalcRelativeTransform(
        robot.plant_context, robot.frame("base_footprint"), robot.frame("grasp_frame"))
    np.testing.assert_allclose(X_AG.translation(), target, atol=2e-3)


def test_ik_does_not_reach_past_the_arm_with_the_base_held(robot):
    """1.6 m ahead is beyond the arm (1.306 m from its base to the flange): IK must fail, which
    shows the base joints really are held in the check above."""
    result, _ = _solve_top_down_grasp_ik(robot, [1.6, 0.0, 0.8])
    assert not result.is_success()


@pytest.fixture
def fixture_scene(tmp_path):
    """A scene directory named `scene` (so its package is `scene`, as generated scenes name
    theirs after their directory) holding one welded floor slab."""
    scene_dir = tmp_path / "scene"
    scene_dir.mkdir()
    write_scene(scene_dir, [("floor", (0.0, 0.0, -0.05), (8.0, 8.0, 0.1), True)],
                package="scene")
    return scene_dir


def test_scenario_loads_and_holds_the_robot_at_home_for_one_second(fixture_scene):
    scenario = load_scenario("""
        simulation_duration: 1.0
        simulator_config: {target_realtime_rate: 0.0}
        visualization:
          enable_meshcat_creation: false
          publish_illustration: false
          publish_proximity: false
          publish_contacts: false
          publish_inertia: false
    """)
    assert scenario.plant_config.time_step > 0
    assert isinstance(scenario.model_drivers[ROBOT], ZeroForceDriver)
    builder = DiagramBuilder()
    plant, _ = AddMultibodyPlant(scenario.plant_config, builder)
    parser = Parser(plant)
    parser.SetStrictParsing()
    parser.package_map().AddPackageXml(PACKAGE_XML)
    parser.package_map().AddPackageXml(str(fixture_scene / "package.xml"))
    added = ProcessModelDirectives(ModelDirectives(directives=scenario.directives), parser)
    plant.Finalize()
    assert {info.model_name for info in added} == {"floor", ROBOT}
    lcm_buses = ApplyLcmBusConfig(scenario.lcm_buses, builder)
    ApplyDriverConfigs(driver_configs=scenario.model_drivers, sim_plant=plant,
                       models_from_directives=added, lcm_buses=lcm_buses, builder=builder)
    ApplyVisualizationConfig(scenario.visualization, builder, lcm_buses)
    diagram = builder.Build()
    simulator = Simulator(diagram)
    ApplySimulatorConfig(scenario.simulator_config, simulator)
    context = simulator.get_mutable_context()
    plant_context = plant.GetMyMutableContextFromRoot(context)

    robot = plant.GetModelInstanceByName(ROBOT)
    home = home_positions()

    def position(name):
        joint = plant.GetJointByName(name, robot)
        return plant.GetPositions(plant_context)[joint.position_start()]

    # The directive's default_joint_positions put the robot at home.
    for name, value in home.items():
        assert position(name) == pytest.approx(value), name
    # The command a controller would send: hold home, at rest ([q_d, v_d], actuator order).
    q_desired = [home[plant.get_joint_actuator(index).joint().name()]
                 for index in plant.GetJointActuatorIndices(robot)]
    plant.get_desired_state_input_port(robot).FixValue(
        plant_context, np.concatenate([q_desired, np.zeros(len(q_desired))]))

    simulator.AdvanceTo(scenario.simulation_duration)

    for name, value in home.items():
        q = position(name)
        if plant.GetJointByName(name, robot).type_name() == "revolute":
            assert abs(q - value) < math.radians(1.0), f"{name}: {q} rad, home {value} rad"
        else:
            assert abs(q - value) < 0.01, f"{name}: {q} m, home {value} m"
