#!/usr/bin/env python3
"""The robot-policy benchmark of issue 14: the paper's four pick-and-place tasks, N scenes each,
the standard and the degraded policy, success rates with 95 % Wilson intervals.

For each task it runs `scenesmith robot-eval "<task>" --scenes N --policy standard,degraded
--out OUT/<task id>` and reads that run's `results.json`: per policy the episodes, successes and
the Wilson interval, the outcomes that were not a success (`placed_wrong` or the policy's
failure reason: no_base_pose, no_grasp, ik, planning, dropped, timeout; `error` for a bridge
error), the episodes whose carried object hit something, and the mean wall seconds of an
episode. Every judged state (each bound scene's initial state, each executed episode's final
state) is also checked by `robot_state_check.py`, a geometric check written apart from the
built-in evaluator: the summary says in how many states the two agree and in how many initial
states the check finds the goal already holding (cached in OUT/<task id>/independent.json).
A task the binary refuses (exit status and its
last stderr line) is a row of its own, not a crash. Resumable: robot-eval keeps the checked
scenes it already generated under OUT/<task id>/scenes, and a task whose results.json exists is
read, not rerun, unless --rerun.

    .venv/bin/python scripts/bench_robot_eval.py --out out/bench_robot [--scenes 10]
        [--bin target/release/scenesmith] [--tasks fruit,can] [--no-frames] [--rerun] [--json]

The binary is --bin, else $SCENESMITH_BIN, else <repo>/target/release/scenesmith.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "scripts"))

#: The paper's four tasks (id -> text), in the paper's order.
TASKS = {
    "fruit": "pick a fruit from the fruit bowl and place it on a plate on the dining table",
    "can": "pick a coke can from the shelf and place it on the table",
    "cup": "pick a cup from the floor and place it in the sink",
    "bottle": "bring the water bottle from the kitchen to the coffee table in the living room",
}
POLICIES = ("standard", "degraded")


def wilson95(k, n):
    """The 95 % Wilson score interval of k successes in n trials (robot_eval.rs's formula)."""
    if n == 0:
        return (0.0, 1.0)
    z = 1.959963984540054
    p = k / n
    denom = 1.0 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / denom
    return (max(0.0, centre - half), min(1.0, centre + half))


def binary_path(arg):
    return arg or os.environ.get("SCENESMITH_BIN") or os.path.join(
        REPO, "target", "release", "scenesmith")


def run_task(binary, text, out_dir, scenes, frames, log):
    """Runs robot-eval for one task; returns (exit status, last stderr line)."""
    cmd = [binary, "robot-eval", text, "--scenes", str(scenes), "--policy",
           ",".join(POLICIES), "--out", out_dir]
    if not frames:
        cmd.append("--no-frames")
    os.makedirs(out_dir, exist_ok=True)
    with open(os.path.join(out_dir, "bench.log"), "a") as f:
        proc = subprocess.Popen(cmd, stdout=f, stderr=subprocess.PIPE, text=True)
        last = ""
        for line in proc.stderr:
            f.write(line)
            f.flush()
            if line.strip():
                last = line.strip()
                log(f"  {line.rstrip()}")
        return proc.wait(), last


def independent_states(results, cache_path):
    """Each judged state with the built-in verdict and the independent check's:
    [{"state": "initial"|"final", "scene", "policy", "builtin", "independent", "evidence"}];
    read from `cache_path` when it was written for the same states by the same version of
    the check."""
    predicate = results["task"]["predicate"]
    dirs = {s["id"]: s["dir"] for s in results.get("scenes", [])}
    todo = []
    for b in results.get("bindings", []):
        if b.get("target"):
            todo.append(("initial", b["scene"], None, b["target"], b["reference"],
                         "scene.dmd.yaml", False))
    for e in results.get("episodes", []):
        if e.get("outcome") in ("success", "placed_wrong"):
            builtin = e.get("builtin_holds")
            if builtin is None:
                builtin = e["outcome"] == "success"
            todo.append(("final", e["scene"], e["policy"], e["target"], e["reference"],
                         os.path.join(e["dir"], f"after_{e['policy']}.dmd.yaml"), builtin))
    from robot_state_check import VERSION, check
    keys = [list(t[:3]) for t in todo]
    if os.path.exists(cache_path):
        with open(cache_path) as f:
            cached = json.load(f)
        if isinstance(cached, dict) and cached.get("version") == VERSION and [
                [c["state"], c["scene"], c["policy"]] for c in cached["states"]] == keys:
            return cached["states"]
    out = []
    for state, scene, policy, target, reference, directives, builtin in todo:
        try:
            holds, evidence = check(dirs[scene], directives, predicate, target, reference)
        except Exception as e:  # a state that does not load is a disagreement, with why
            holds, evidence = None, {"error": str(e)}
        out.append({"state": state, "scene": scene, "policy": policy, "builtin": builtin,
                    "independent": holds, "evidence": evidence})
    with open(cache_path, "w") as f:
        json.dump({"version": VERSION, "states": out}, f, indent=1)
    return out


def summarise(results, checked=None):
    """Per policy: episodes, successes, interval, failure counts, mean seconds; from a parsed
    results.json (RobotEvalResults in src/task/robot_eval.rs)."""
    usable = sum(1 for b in results.get("bindings", []) if b.get("target"))
    out = {"scenes": len(results.get("scenes", [])), "bound": usable, "policies": {}}
    if checked is not None:
        out["states_checked"] = len(checked)
        out["states_agreeing"] = sum(1 for c in checked if c["independent"] == c["builtin"])
        out["initial_holding"] = sum(1 for c in checked
                                     if c["state"] == "initial" and c["independent"])
        out["disagreements"] = [c for c in checked if c["independent"] != c["builtin"]]
    for policy in POLICIES:
        rows = [e for e in results.get("episodes", []) if e.get("policy") == policy]
        k = sum(1 for e in rows if e.get("outcome") == "success")
        failures = {}
        for e in rows:
            if e.get("outcome") != "success":
                failures[e.get("outcome", "?")] = failures.get(e.get("outcome", "?"), 0) + 1
        seconds = [float(e.get("seconds", 0.0)) for e in rows]
        out["policies"][policy] = {
            "episodes": len(rows), "successes": k, "ci95": wilson95(k, len(rows)),
            "failures": failures,
            "hits": sum(1 for e in rows if e.get("hit")),
            "mean_seconds": sum(seconds) / len(seconds) if seconds else None,
            "max_seconds": max(seconds) if seconds else None,
        }
    return out


def cell(p):
    if p is None or p["episodes"] == 0:
        return "-"
    k, n = p["successes"], p["episodes"]
    lo, hi = p["ci95"]
    return f"{k}/{n} {100 * k / n:.0f}% [{100 * lo:.0f}-{100 * hi:.0f}]"


def table(rows):
    head = ["task", "scenes", "bound", "standard k/n % [95% CI]", "degraded k/n % [95% CI]",
            "standard failures", "degraded failures", "hit something (std/deg)",
            "mean s (std/deg)"]
    lines = [head]
    total = {p: [0, 0] for p in POLICIES}
    for task_id, s in rows:
        if "error" in s:
            lines.append([task_id, "-", "-", "-", "-", s["error"][:120], "", "", ""])
            continue
        ps = s["policies"]
        for p in POLICIES:
            total[p][0] += ps[p]["successes"]
            total[p][1] += ps[p]["episodes"]
        fails = [", ".join(f"{k} {v}" for k, v in sorted(ps[p]["failures"].items())) or "-"
                 for p in POLICIES]
        secs = "/".join("-" if ps[p]["mean_seconds"] is None else f"{ps[p]['mean_seconds']:.0f}"
                        for p in POLICIES)
        hits = "/".join(str(ps[p]["hits"]) for p in POLICIES)
        lines.append([task_id, str(s["scenes"]), str(s["bound"]), cell(ps["standard"]),
                      cell(ps["degraded"]), fails[0], fails[1], hits, secs])
    all_cells = []
    for p in POLICIES:
        k, n = total[p]
        all_cells.append(cell({"episodes": n, "successes": k, "ci95": wilson95(k, n)}))
    lines.append(["all", "", "", all_cells[0], all_cells[1], "", "", "", ""])
    widths = [max(len(r[i]) for r in lines) for i in range(len(head))]
    return "\n".join("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in lines)


def agreement(rows):
    """Lines: the built-in evaluator against the independent check, per task and in all."""
    lines, n, k, held = [], 0, 0, 0
    for task_id, s in rows:
        if "states_checked" not in s:
            continue
        n, k, held = n + s["states_checked"], k + s["states_agreeing"], held + s[
            "initial_holding"]
        for c in s["disagreements"]:
            lines.append(f"  {task_id} {c['scene']} {c['state']} {c['policy'] or ''}: built-in "
                         f"{c['builtin']}, independent {c['independent']} {c['evidence']}")
    head = (f"built-in evaluator vs independent geometric check: {k}/{n} states agree"
            + (f" ({100 * k / n:.1f} %)" if n else "")
            + f"; initial states whose goal already holds (independent check): {held}")
    return "\n".join([head] + lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, help="output directory (one subdirectory a task)")
    ap.add_argument("--scenes", type=int, default=10)
    ap.add_argument("--bin", default=None)
    ap.add_argument("--tasks", default=",".join(TASKS), help="comma-separated task ids: "
                    + ", ".join(f"{k} ({v})" for k, v in TASKS.items()))
    ap.add_argument("--no-frames", action="store_true")
    ap.add_argument("--rerun", action="store_true", help="rerun tasks with a results.json")
    ap.add_argument("--json", action="store_true", help="print the summary as JSON")
    args = ap.parse_args(argv)
    binary = binary_path(args.bin)
    if not os.access(binary, os.X_OK):
        sys.exit(f"no scenesmith binary at {binary} (build it, or set --bin / SCENESMITH_BIN)")
    rows = []
    for task_id in args.tasks.split(","):
        if task_id not in TASKS:
            sys.exit(f"unknown task id {task_id!r}; expected one of {', '.join(TASKS)}")
        out_dir = os.path.join(args.out, task_id)
        results_path = os.path.join(out_dir, "results.json")
        if args.rerun or not os.path.exists(results_path):
            print(f"{task_id}: robot-eval {TASKS[task_id]!r}", file=sys.stderr, flush=True)
            start = time.monotonic()
            status, last = run_task(binary, TASKS[task_id], out_dir, args.scenes,
                                    not args.no_frames,
                                    lambda line: print(line, file=sys.stderr, flush=True))
            print(f"{task_id}: exit {status} after {time.monotonic() - start:.0f} s",
                  file=sys.stderr, flush=True)
            if not os.path.exists(results_path):
                rows.append((task_id, {"error": f"exit {status}: {last}"}))
                continue
        with open(results_path) as f:
            results = json.load(f)
        checked = independent_states(results, os.path.join(out_dir, "independent.json"))
        rows.append((task_id, summarise(results, checked)))
    if args.json:
        print(json.dumps({k: v for k, v in rows}, indent=1))
    else:
        print(table(rows))
        print()
        print(agreement(rows))


if __name__ == "__main__":
    main()
