"""The evaluator of issue 14 (part 4): state tools over a scene's Drake state and a built-in
evaluator that judges a task's predicate (on / inside / near) for every candidate pair, with the
numbers it used.

    from drake_bridge.evaluator import judge, load_state, get_support
    verdict = judge("scene_dir", {"predicate": "on", "target": "mug", "reference": "table"})
    verdict = judge("scene_dir", "task.json", dmd="/abs/out/after_standard.dmd.yaml")
    state = load_state("scene_dir")            # scene.dmd.yaml; or dmd="after_<policy>.dmd.yaml"
    get_support(state, "mug_0")["supporters"]   # JSON-ready dicts

    result, images = run_tool(state, args)     # one tool call of the LLM evaluator (llm_tools)

What it does not do: the LLM evaluator's conversation (the Rust side holds it and calls
`run_tool` through the bridge op `evaluator_tool`), binding a task's words to a policy's
instances, or changing the state (every tool reads the poses of the directives file it was
loaded from).

| Module | One concept |
|---|---|
| `state.py` | `load_state`, `SceneState`: the plant, scene.json records, collision vertices; noun matching |
| `geometry.py` | numpy geometry: 2-D hulls, footprint fractions, interval gaps, box-in-box volume |
| `tools.py` | the state tools (list_objects, get_object_info, get_distance, get_spatial_relation, get_support) and their shared measurements |
| `builtin.py` | the built-in evaluator: thresholds, `evaluate`, `judge` |
| `vision.py` | the vision tools (observe_scene, observe_objects): RenderEngineVtk views of a state |
| `llm_tools.py` | `run_tool`: every tool as the LLM evaluator calls it, bad arguments as `{"error"}` |
"""

from drake_bridge.evaluator.builtin import (
    INSIDE_MIN_VOLUME,
    NEAR_MAX_M,
    ON_CONTACT_M,
    ON_MAX_GAP_M,
    ON_MIN_FOOTPRINT,
    PREDICATES,
    THRESHOLDS,
    evaluate,
    judge,
)
from drake_bridge.evaluator.llm_tools import run_tool
from drake_bridge.evaluator.state import SceneState, category_matches, load_state, matching_ids
from drake_bridge.evaluator.tools import (
    SUPPORT_CONTACT_M,
    get_distance,
    get_object_info,
    get_spatial_relation,
    get_support,
    list_objects,
)
from drake_bridge.evaluator.vision import observe_objects, observe_scene

__all__ = [
    "INSIDE_MIN_VOLUME",
    "NEAR_MAX_M",
    "ON_CONTACT_M",
    "ON_MAX_GAP_M",
    "ON_MIN_FOOTPRINT",
    "PREDICATES",
    "SUPPORT_CONTACT_M",
    "THRESHOLDS",
    "SceneState",
    "category_matches",
    "evaluate",
    "get_distance",
    "get_object_info",
    "get_spatial_relation",
    "get_support",
    "judge",
    "list_objects",
    "load_state",
    "matching_ids",
    "observe_objects",
    "observe_scene",
    "run_tool",
]
