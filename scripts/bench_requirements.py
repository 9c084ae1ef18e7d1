#!/usr/bin/env python3
"""Label-based scores of generated scenes against requirements written independently.

Reads a JSON Lines file of prompts with requirements (the format of
tests/fixtures/heldout_long.jsonl: id, kind, prompt, requirements), generates one scene per
prompt with the built-in backend (skipped when OUT/<id>.rc records an earlier run, so a run resumes),
scores each with `scenesmith eval DIR --requirements FILE --json`, and prints a table: objects,
absents and rooms met per prompt and in total, and for prompts of kind "refuse" whether
`generate` refused them (exit code 2).

    .venv/bin/python scripts/bench_requirements.py tests/fixtures/heldout_long.jsonl \\
        --out out/heldout [--bin target/release/scenesmith] [--ids long_01,long_02]

Nothing here reads the prompt the way the tool does: the requirements are the file's.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def generate(bin_path, prompt, out, log, extra=()):
    """Runs `generate` once; its exit code and time are kept in OUT/<id>.rc ("rc seconds")."""
    rc_file = out + ".rc"
    if os.path.exists(rc_file):
        rc, secs = open(rc_file).read().split()
        return int(rc), float(secs)
    start = time.time()
    with open(log, "w") as f:
        rc = subprocess.call(
            [bin_path, "generate", prompt, "--out", out, "--no-render", "--export", "none", *extra],
            stdout=f,
            stderr=subprocess.STDOUT,
            env={**os.environ, "SCENESMITH_HOME": ROOT},
        )
    secs = time.time() - start
    with open(rc_file, "w") as f:
        f.write(f"{rc} {secs}\n")
    return rc, secs


def score(bin_path, out, requirements):
    with tempfile.NamedTemporaryFile("w", suffix=".jsonl", delete=False) as f:
        for r in requirements:
            f.write(json.dumps(r) + "\n")
        path = f.name
    try:
        res = subprocess.run(
            [bin_path, "--json", "eval", out, "--requirements", path],
            capture_output=True,
            text=True,
            env={**os.environ, "SCENESMITH_HOME": ROOT},
        )
    finally:
        os.unlink(path)
    if res.returncode != 0:
        raise RuntimeError(f"eval failed on {out}: {res.stderr.strip()}")
    return json.loads(res.stdout)


def tally(summary, key):
    t = summary.get(key) or {}
    return t.get("met", 0), t.get("total", 0)


def bench_args(doc, extra=lambda ap: None):
    """The arguments the scene benchmarks share (prompts, --out, --bin, --ids), plus `extra`'s;
    returns them with the set of wanted ids, after creating --out."""
    ap = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    ap.add_argument("prompts")
    ap.add_argument("--out", required=True)
    ap.add_argument("--bin", default=os.path.join(ROOT, "target", "release", "scenesmith"))
    ap.add_argument("--ids", default="")
    extra(ap)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    return args, {i for i in args.ids.split(",") if i}


def main():
    def options(ap):
        ap.add_argument(
            "--no-stb",
            action="store_true",
            help="pass --no-stb to generate: the scene is the same, only metrics.json lacks STB",
        )
        ap.add_argument(
            "--no-check",
            action="store_true",
            help="pass --no-check to generate: no Drake (no settling, no removals), for a quick look",
        )

    args, want = bench_args(__doc__, options)
    extra = (["--no-stb"] if args.no_stb else []) + (["--no-check"] if args.no_check else [])
    rows = []
    totals = {"objects": [0, 0], "absent": [0, 0], "rooms": [0, 0], "refused": [0, 0]}
    with open(args.prompts) as f:
        entries = [json.loads(line) for line in f if line.strip()]
    for e in entries:
        if want and e["id"] not in want:
            continue
        out = os.path.join(args.out, e["id"])
        log = os.path.join(args.out, e["id"] + ".log")
        secs = None
        if e["kind"] == "refuse":
            rc, secs = generate(args.bin, e["prompt"], out, log, extra)
            totals["refused"][1] += 1
            totals["refused"][0] += int(rc == 2)
            rows.append((e["id"], "refuse", f"exit {rc}", "", "", secs))
            continue
        rc, secs = generate(args.bin, e["prompt"], out, log, extra)
        if not os.path.exists(os.path.join(out, "scene.json")):
            # A failed run meets nothing: its requirements count, unmet.
            rows.append((e["id"], e["kind"], f"generate exit {rc}", "", "", secs))
            for key, name in (("object", "objects"), ("absent", "absent"), ("room", "rooms")):
                totals[name][1] += sum(
                    1 for r in e["requirements"] if key in r and (key != "room" or "object" not in r)
                )
            continue
        report = score(args.bin, out, e["requirements"])
        summary = report["summary"]
        cells = []
        for key, name in (("objects", "objects"), ("absents", "absent"), ("rooms", "rooms")):
            met, total = tally(summary, key)
            totals[name][0] += met
            totals[name][1] += total
            cells.append(f"{met}/{total}")
        rows.append((e["id"], e["kind"], *cells, secs))
    print("| id | kind | objects | absent | rooms | generate s |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        secs = "" if r[5] is None else f"{r[5]:.0f}"
        print(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]} | {r[4]} | {secs} |")
    print()
    for key, (met, total) in totals.items():
        pct = 100.0 * met / total if total else 100.0
        print(f"{key:8} {met:4}/{total:4}  {pct:5.1f} %")


if __name__ == "__main__":
    sys.exit(main())
