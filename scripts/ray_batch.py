#!/usr/bin/env python3
"""Runs a `scenesmith batch` prompts file on a Ray cluster: one Ray task per scene.

    .venv/bin/python scripts/ray_batch.py prompts.jsonl --out DIR [--workers N]
        [--address ADDR] [-- BATCH OPTIONS...]

The output layout and the resumability are `scenesmith batch`'s own, because every task runs
`scenesmith batch PROMPTS --out DIR --only <id>`: a scene goes to DIR/<id>/, its outcome to
DIR/results/<id>.json, and at the end `--summary-only` writes DIR/summary.jsonl and prints
the table. Scenes already finished are not submitted. Options after `--` go to every scene's
`scenesmith batch` (e.g. `-- --no-stb --export glb`).

Without --address a local Ray instance with N CPUs starts (`ray.init(num_cpus=N)`); with
--address (`ray start --head` on one machine, `ray start --address HEAD:6379` on the others)
the tasks spread over the cluster, which then needs this repository (with its built binary and
.venv) at the same path on every node and DIR on a shared file system.
"""

import argparse
import json
import os
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def binary():
    """The scenesmith binary: $SCENESMITH_BIN, else the release build (built when missing)."""
    if os.environ.get("SCENESMITH_BIN"):
        return os.environ["SCENESMITH_BIN"]
    path = REPO / "target" / "release" / "scenesmith"
    subprocess.run(["cargo", "build", "--release", "--quiet", "--bin", "scenesmith",
                    "--manifest-path", str(REPO / "Cargo.toml")], check=True)
    return str(path)


def scene_env():
    """Environment of a scene's process: one bridge worker, as a task holds one CPU."""
    env = dict(os.environ)
    env.setdefault("SCENESMITH_HOME", str(REPO))
    env["SCENESMITH_BRIDGE_WORKERS"] = "1"
    return env


def report(bin_path, prompts, out):
    """`scenesmith batch --summary-only --json`: every scene of the file with its status."""
    r = subprocess.run([bin_path, "--json", "batch", str(prompts), "--out", str(out),
                        "--summary-only"], capture_output=True, text=True, env=scene_env())
    if r.returncode not in (0, 1):
        sys.exit(f"ray_batch: scenesmith refused the batch:\n{r.stderr.strip()}")
    return json.loads(r.stdout)


def run_scene(bin_path, prompts, out, scene_id, extra):
    """One scene through `scenesmith batch --only`: (id, exit status, seconds, last stderr)."""
    start = time.time()
    r = subprocess.run([bin_path, "batch", str(prompts), "--out", str(out), "--only", scene_id,
                        *extra], capture_output=True, text=True, env=scene_env())
    tail = "\n".join(r.stderr.strip().splitlines()[-3:])
    return scene_id, r.returncode, time.time() - start, tail


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("prompts", type=Path)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--workers", type=int, default=2,
                    help="CPUs of the local Ray instance (ignored with --address)")
    ap.add_argument("--address", help="a running Ray cluster, e.g. HEAD:6379 or auto")
    argv = sys.argv[1:]
    cut = argv.index("--") if "--" in argv else len(argv)
    args = ap.parse_args(argv[:cut])
    args.batch_args = argv[cut + 1:]
    prompts, out = args.prompts.resolve(), args.out.resolve()
    bin_path = binary()
    todo = [s["id"] for s in report(bin_path, prompts, out)["scenes"] if s["status"] != "ok"]
    print(f"ray_batch: {len(todo)} scene(s) to run", file=sys.stderr)

    wall = time.time()
    if todo:
        os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")
        import ray

        if args.address:
            ray.init(address=args.address, include_dashboard=False, log_to_driver=False)
        else:
            ray.init(num_cpus=args.workers, include_dashboard=False, log_to_driver=False)
        task = ray.remote(num_cpus=1, max_retries=0)(run_scene)
        pending = [task.remote(bin_path, prompts, out, i, args.batch_args) for i in todo]
        done = 0
        while pending:
            ready, pending = ray.wait(pending, num_returns=1)
            scene_id, code, seconds, tail = ray.get(ready[0])
            done += 1
            outcome = "ok" if code == 0 else f"FAILED (exit {code}): {tail}"
            print(f"[{done}/{len(todo)}] {scene_id} {outcome} ({seconds:.0f} s, "
                  f"elapsed {time.time() - wall:.0f} s)", file=sys.stderr, flush=True)
        ray.shutdown()
    wall = time.time() - wall

    final = subprocess.run([bin_path, "batch", str(prompts), "--out", str(out),
                            "--summary-only"], env=scene_env())
    if todo:
        status = {s["id"]: s["status"] for s in report(bin_path, prompts, out)["scenes"]}
        ok = sum(1 for i in todo if status.get(i) == "ok")
        print(f"ray_batch: {ok} of {len(todo)} scene(s) ok in {wall:.0f} s wall: "
              f"{3600.0 * ok / wall:.1f} scenes/hour", file=sys.stderr)
    return final.returncode


if __name__ == "__main__":
    sys.exit(main())
