#!/usr/bin/env python3
"""Export conformance benchmark: generates dev-prompt scenes and runs the conformance gate
(`scenesmith export DIR --check --no-write`) on each, then prints one row per scene and the
targets of issue 7:

  - share of scenes passing the gate (target 100 %),
  - MuJoCo STB: free objects moving < 1 cm and turning < 0.1 rad in 5 s (target >= 95 %),
  - scenes whose MuJoCo state went non-finite (target 0),
  - object count, mass and joint count equal across Drake, MJCF and USD (target: every scene).

With --drake-stb it also reads each scene's Drake STB (metrics.json: discrete plant, 1 ms, 5 s,
hydroelastic contact) and counts the free objects both engines classify the same way (stable
in both or moving in both).

Usage: scripts/bench_exports.py [--limit N] [--ids id1,id2] [--out DIR] [--seconds 5] [--drake-stb]
Runs the release binary through scripts/scenesmith (which builds it when needed); run it with
the project's .venv/bin/python (--drake-stb needs pydrake).
"""

import argparse
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(args):
    t0 = time.perf_counter()
    p = subprocess.run([os.path.join(ROOT, "scripts", "scenesmith"), "--json", *args],
                       capture_output=True, text=True)
    return p, time.perf_counter() - t0


def drake_moved(scene_dir):
    """Free objects and the ones that moved >= 1 cm or turned >= 0.1 rad in Drake: the STB of
    the scene's metrics.json (`generate` simulates 5 s at 1 ms with hydroelastic contact, per
    island of touching objects; see the README's metrics)."""
    with open(os.path.join(scene_dir, "metrics.json")) as f:
        stb = json.load(f).get("stb") or {}
    return stb.get("free_objects", 0), {u["id"] for u in stb.get("unstable", [])}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--limit", type=int, default=0, help="first N prompts (0 = all)")
    ap.add_argument("--ids", default="", help="comma-separated prompt ids")
    ap.add_argument("--out", default="/tmp/scenesmith_bench_exports")
    ap.add_argument("--seconds", type=float, default=5.0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--drake-stb", action="store_true",
                    help="also compare with the Drake STB of metrics.json")
    a = ap.parse_args()

    prompts = [json.loads(l) for l in open(os.path.join(ROOT, "tests/fixtures/dev_prompts.jsonl"))
               if l.strip()]
    if a.ids:
        want = set(a.ids.split(","))
        prompts = [p for p in prompts if p["id"] in want]
    if a.limit:
        prompts = prompts[:a.limit]
    os.makedirs(a.out, exist_ok=True)

    header = ("scene", "objs", "free", "pieces", "mass kg", "gen s", "gate s", "mj sim s",
              "STB", "max mm", "finite", "equal", "gate")
    print(" | ".join(header))
    print(" | ".join("-" * len(h) for h in header))
    totals = {"scenes": 0, "passed": 0, "free": 0, "stable": 0, "nonfinite": 0, "equal": 0,
              "failed_gen": 0, "drake_free": 0, "drake_stable": 0, "agree": 0}
    failures = []
    for p in prompts:
        out = os.path.join(a.out, p["id"])
        gen, gen_s = run(["generate", p["prompt"], "--out", out, "--seed", str(a.seed)])
        if gen.returncode != 0:
            totals["failed_gen"] += 1
            print(f"{p['id']} | generate failed ({gen.returncode}): {gen.stderr.strip()[-200:]}")
            continue
        chk, chk_s = run(["export", out, "--check", "--no-write", "--seconds", str(a.seconds)])
        try:
            rep = json.loads(chk.stdout)["check"]
        except (ValueError, KeyError):
            print(f"{p['id']} | gate crashed ({chk.returncode}): {chk.stderr.strip()[-300:]}")
            totals["scenes"] += 1
            failures.append(p["id"])
            continue
        totals["scenes"] += 1
        s = rep.get("mujoco_stability") or {}
        facts = rep.get("facts", {})
        scene = rep["scene"]
        equal = all(f["objects"] == scene["objects"] and f["joints"] == scene["joints"]
                    and abs(f["mass_kg"] - scene["mass_kg"]) <= 1e-6 * max(1.0, scene["mass_kg"])
                    for f in facts.values()) and len(facts) == 3
        totals["passed"] += rep["passed"]
        totals["free"] += s.get("free_objects", 0)
        totals["stable"] += s.get("stable", 0)
        totals["nonfinite"] += not s.get("finite", False)
        totals["equal"] += equal
        if not rep["passed"]:
            failures.append(p["id"] + ": " + "; ".join(
                f"{r['format']} {r['check']}: {r['got']}" for r in rep["rows"] if not r["pass"]))
        print(" | ".join(str(v) for v in (
            p["id"], scene["objects"], s.get("free_objects"), scene["colliders"],
            f"{scene['mass_kg']:.1f}", f"{gen_s:.1f}", f"{chk_s:.1f}",
            f"{rep['seconds'].get('mujoco', 0):.1f}",
            f"{s.get('stable')}/{s.get('free_objects')}",
            f"{1e3 * s.get('max_displacement_m', 0):.1f}", s.get("finite"),
            "yes" if equal else "NO", "PASS" if rep["passed"] else "FAIL")))
        for oid, d, r in s.get("moved", []):
            print(f"    moved: {oid} {1e3 * d:.1f} mm {r:.3f} rad")
        if a.drake_stb:
            n_free, d_moved = drake_moved(out)
            mj_moved = {m[0] for m in s.get("moved", [])}
            totals["drake_free"] += n_free
            totals["drake_stable"] += n_free - len(d_moved)
            totals["agree"] += n_free - len(d_moved ^ mj_moved)
            print(f"    drake: {n_free - len(d_moved)}/{n_free} stable; "
                  f"moved only in MuJoCo {sorted(mj_moved - d_moved)}, "
                  f"only in Drake {sorted(d_moved - mj_moved)}")
        sys.stdout.flush()

    n = max(1, totals["scenes"])
    print()
    print(f"scenes: {totals['scenes']} (generate failed: {totals['failed_gen']})")
    print(f"gate passed: {totals['passed']}/{totals['scenes']} = {100 * totals['passed'] / n:.1f} %")
    print(f"MuJoCo STB: {totals['stable']}/{totals['free']} free objects = "
          f"{100 * totals['stable'] / max(1, totals['free']):.2f} %")
    print(f"non-finite scenes: {totals['nonfinite']}")
    if a.drake_stb:
        print(f"Drake STB: {totals['drake_stable']}/{totals['drake_free']} free objects; "
              f"same verdict in MuJoCo and Drake: {totals['agree']}/{totals['drake_free']}")
    print(f"counts/mass/joints equal across Drake, MJCF, USD: {totals['equal']}/{totals['scenes']}")
    for f in failures:
        print("FAIL", f)
    return 0 if totals["passed"] == totals["scenes"] else 1


if __name__ == "__main__":
    sys.exit(main())
