"""The standard pick-and-place policy of issue 14 (part 3): a mobile KUKA iiwa (sdf_templates/)
moves one free object of a generated scene so that a predicate (on / inside / near a
reference) can hold, planned and then simulated closed loop in Drake.

    from drake_bridge.policy import PickPlaceTask, run_episode
    result = run_episode("scene_dir", PickPlaceTask("on", "mug_0", "table_0"), "standard",
                         "out_dir", seed=0)
    dataclasses.asdict(result)  # JSON-ready; also written to out_dir/episode_standard.json

What it does not do: judge success (a separate evaluator reads `after_<policy>.dmd.yaml`),
bind task words to instances (the caller names the instances). Between rooms of a house it
drives the base along a lattice path (navigation.py) with the object held and the arm tucked.

| Module | One concept |
|---|---|
| `types.py` | the typed boundary: task, policy settings, result, failure reasons |
| `scene.py` | scene + robot loading, welding, planning models and checkers, timing plants |
| `surfaces.py` | point clouds sampled on collision geometry |
| `grasp.py` | antipodal grasp sampling, the open-gripper collision filter |
| `placement.py` | place locations per predicate, base pose candidates |
| `ik.py` | grasp-frame IK with minimum-distance constraints |
| `rrt.py` | RRT-Connect and randomized shortcutting |
| `navigation.py` | the base's drive between rooms: lazy A* on a navigability lattice |
| `timing.py` | TOPPRA with joint, torque and gripper limits |
| `rollout.py` | the closed-loop simulation, drop detection |
| `frames.py` | rendering recorded states (VTK), the flipbook animation |
| `output.py` | the files: after-directives, PNG, JSON |
| `episode.py` | one episode end to end: `run_episode` |
"""

from drake_bridge.policy.episode import Episode, run_episode
from drake_bridge.policy.types import (
    FAILURE_REASONS,
    POLICIES,
    PREDICATES,
    BadTask,
    EpisodeResult,
    GraspInfo,
    PickPlaceTask,
    PolicyConfig,
    PoseError,
    TrajectoryInfo,
)

__all__ = [
    "FAILURE_REASONS",
    "POLICIES",
    "PREDICATES",
    "BadTask",
    "Episode",
    "EpisodeResult",
    "GraspInfo",
    "PickPlaceTask",
    "PolicyConfig",
    "PoseError",
    "TrajectoryInfo",
    "run_episode",
]
