"""The robot operations: one pick-and-place episode (`policy_episode`, drake_bridge/policy/),
the built-in evaluator's verdicts on bound objects (`judge_task`, drake_bridge/evaluator/), and
one tool call of the LLM evaluator (`evaluator_tool`, drake_bridge/evaluator/llm_tools.py).

Both are thin: they translate the protocol dataclasses to the packages' own types and back.
An input the policy cannot run at all (an unknown instance, a target that is not a free body)
is a BadRequest; a policy that fails is a normal reply with its failure reason.
"""

import base64
import collections
import json
import math
import os

from drake_bridge.errors import BadRequest
from drake_bridge.evaluator import THRESHOLDS, load_state, run_tool
from drake_bridge.evaluator.builtin import judge_inside, judge_near, judge_on
from drake_bridge.policy import BadTask, PickPlaceTask, run_episode
from drake_bridge.protocol import EpisodeReply, EvalToolReply, JudgeReply, PairVerdict, ToolImage

_JUDGES = {"on": judge_on, "inside": judge_inside, "near": judge_near}


def op_policy_episode(args):
    """protocol.EpisodeArgs -> EpisodeReply."""
    task = PickPlaceTask(args.predicate, args.target, args.reference)
    try:
        r = run_episode(args.scene_dir, task, args.policy, args.out_dir, seed=args.seed,
                        frames=args.frames, animation=args.frames)
    except BadTask as e:
        raise BadRequest(str(e)) from e
    files = sorted(str(p) for p in r.files.values())
    after = r.files.get("after_directives")
    return EpisodeReply(
        success=bool(r.success),
        failure_reason=r.failure_reason,
        message=r.message,
        timings_s={k: float(v) for k, v in r.timings_s.items()},
        simulated_s=float(r.simulated_s),
        max_gripper_speed=float(r.trajectory.max_gripper_speed_m_s) if r.trajectory else 0.0,
        welded=len(r.welded_instances),
        carry_hits=list(r.carry_hits),
        after=str(after) if after else None,
        files=files,
    )


def _numbers(evidence):
    """The finite numeric entries of an evidence dict (nested dicts flattened with dots)."""
    out = {}
    for key, value in (evidence or {}).items():
        if isinstance(value, dict):
            out.update({f"{key}.{k}": v for k, v in _numbers(value).items()})
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            if math.isfinite(value):
                out[key] = float(value)
    return out


def _directives_path(scene_dir, directives):
    return directives if os.path.isabs(directives) else os.path.join(scene_dir, directives)


def op_judge_task(args):
    """protocol.JudgeArgs -> JudgeReply: one verdict per (target, reference) pair."""
    state = load_state(args.scene_dir, dmd=_directives_path(args.scene_dir, args.directives))
    judge = _JUDGES[args.predicate]
    pairs = []
    for t in args.targets:
        for r in args.references:
            if t == r:
                continue
            state.instance(t)  # an unknown id is a BadRequest naming it
            state.instance(r)
            holds, evidence, reason = judge(state, t, r)
            pairs.append(PairVerdict(target=t, reference=r, holds=bool(holds), reason=reason,
                                     evidence=_numbers(evidence)))
    return JudgeReply(pairs=pairs, thresholds={k: float(v) for k, v in THRESHOLDS.items()})


#: States the LLM evaluator's tools read, most recently used last: a conversation calls many
#: tools on one state (and its renderer, built on the first vision call, stays with it).
_TOOL_STATES = collections.OrderedDict()
#: At most this many states are kept (a judged scene and a policy's after-state).
TOOL_STATES_KEPT = 2


def _tool_state(scene_dir, directives):
    """load_state, cached by (scene dir, directives path, the file's mtime)."""
    if not os.path.isdir(scene_dir):
        raise BadRequest(f"scene directory not found: {scene_dir}")
    path = os.path.abspath(_directives_path(scene_dir, directives))
    try:
        mtime = os.stat(path).st_mtime_ns
    except OSError:
        mtime = None  # load_state names the missing file
    key = (os.path.abspath(scene_dir), path, mtime)
    state = _TOOL_STATES.pop(key, None)
    if state is None:
        state = load_state(scene_dir, dmd=path)
    _TOOL_STATES[key] = state
    while len(_TOOL_STATES) > TOOL_STATES_KEPT:
        _TOOL_STATES.popitem(last=False)
    return state


def op_evaluator_tool(args):
    """protocol.EvalToolArgs -> EvalToolReply: one state or vision tool (llm_tools.run_tool);
    a bad tool argument is a result {"error": ...} for the model to read."""
    state = _tool_state(args.scene_dir, args.directives)
    result, images = run_tool(state, args)
    return EvalToolReply(
        result_json=json.dumps(result, allow_nan=False),
        images=[ToolImage(name=name, png_base64=base64.b64encode(png).decode("ascii"))
                for name, png in images])


OPS = {
    "policy_episode": op_policy_episode,
    "judge_task": op_judge_task,
    "evaluator_tool": op_evaluator_tool,
}
