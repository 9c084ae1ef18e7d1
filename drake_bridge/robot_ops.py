"""The robot operations: one pick-and-place episode (`policy_episode`, drake_bridge/policy/)
and the built-in evaluator's verdicts on bound objects (`judge_task`, drake_bridge/evaluator/).

Both are thin: they translate the protocol dataclasses to the packages' own types and back.
An input the policy cannot run at all (an unknown instance, a target that is not a free body)
is a BadRequest; a policy that fails is a normal reply with its failure reason.
"""

import math
import os

from drake_bridge.errors import BadRequest
from drake_bridge.evaluator import THRESHOLDS, load_state
from drake_bridge.evaluator.builtin import judge_inside, judge_near, judge_on
from drake_bridge.policy import BadTask, PickPlaceTask, run_episode
from drake_bridge.protocol import EpisodeReply, JudgeReply, PairVerdict

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


def op_judge_task(args):
    """protocol.JudgeArgs -> JudgeReply: one verdict per (target, reference) pair."""
    directives = args.directives
    if not os.path.isabs(directives):
        directives = os.path.join(args.scene_dir, directives)
    state = load_state(args.scene_dir, dmd=directives)
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


OPS = {
    "policy_episode": op_policy_episode,
    "judge_task": op_judge_task,
}
