#!/usr/bin/env python3
"""Scenes per hour on this machine: `scenesmith batch` and `scripts/ray_batch.py`, each with 1
and 2 workers, on the same prompts (the first N of the dev set by default), with the generate
defaults unless options follow `--`. Prints a table; every run starts from an empty directory.

    .venv/bin/python scripts/bench_batch.py [--scenes 6] [--prompts FILE] [--runs batch1,batch2,ray1,ray2] [-- BATCH OPTIONS]
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from ray_batch import REPO, binary  # the same binary lookup (and first build) as Ray's

DEV = REPO / "tests" / "fixtures" / "dev_prompts.jsonl"


def main():
    argv = sys.argv[1:]
    cut = argv.index("--") if "--" in argv else len(argv)
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", type=int, default=6)
    ap.add_argument("--prompts", type=Path, default=DEV)
    ap.add_argument("--runs", default="batch1,batch2,ray1,ray2")
    args = ap.parse_args(argv[:cut])
    extra = argv[cut + 1:]
    bin_path = binary()
    env = dict(os.environ, SCENESMITH_HOME=str(REPO), SCENESMITH_BIN=bin_path)
    lines = [json.loads(l) for l in args.prompts.read_text().splitlines() if l.strip()]
    lines = lines[:args.scenes]
    rows = []
    with tempfile.TemporaryDirectory(prefix="bench_batch_") as tmp:
        prompts = Path(tmp) / "prompts.jsonl"
        prompts.write_text("".join(json.dumps({"id": l.get("id", f"p{k}"),
                                               "prompt": l["prompt"]}) + "\n"
                                   for k, l in enumerate(lines)))
        for run in args.runs.split(","):
            kind, workers = run[:-1], run[-1]
            out = Path(tmp) / run
            if kind == "batch":
                cmd = [bin_path, "batch", str(prompts), "--out", str(out), "--workers", workers,
                       *extra]
            elif kind == "ray":
                cmd = [sys.executable, str(REPO / "scripts" / "ray_batch.py"), str(prompts),
                       "--out", str(out), "--workers", workers, "--", *extra]
            else:
                sys.exit(f"bench_batch: unknown run {run!r} (batch1, batch2, ray1, ray2)")
            print(f"bench_batch: {run} ...", file=sys.stderr, flush=True)
            start = time.time()
            subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            wall = time.time() - start
            summary = [json.loads(l) for l in (out / "summary.jsonl").read_text().splitlines()]
            ok = [s for s in summary if s["status"] == "ok"]
            mean = sum(s["seconds"] for s in ok) / max(len(ok), 1)
            rows.append((run, len(ok), len(summary), wall, 3600.0 * len(ok) / wall, mean))
    print(f"{'run':<8} {'ok':>6} {'wall s':>8} {'scenes/h':>9} {'s/scene (each)':>15}")
    for run, ok, n, wall, rate, mean in rows:
        print(f"{run:<8} {f'{ok}/{n}':>6} {wall:>8.0f} {rate:>9.1f} {mean:>15.1f}")
    print(f"({len(lines)} prompts from {args.prompts.name}; options: {' '.join(extra) or 'generate defaults'};"
          f" {os.cpu_count()} cores)")


if __name__ == "__main__":
    main()
