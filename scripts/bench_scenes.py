#!/usr/bin/env python3
"""What users get per scene: objects per room and per house, COL, STB both ways, removals, time.

Generates one scene per prompt with the built-in backend (a JSON Lines file with `id` and
`prompt`, optionally `kind`; prompts of kind "refuse" are skipped; a scene already generated
into OUT/<id> is reused, so a run resumes) and prints a table from each scene's metrics.json,
the file as shipped: objects, rooms, objects per room, COL, STB under Drake's default plant on the
files as written (`stb`) and under point contact (`stb_point`, SceneEval's protocol), objects
removed by post-processing (count and percent of those placed), asked-for objects lost, and the
generate time. Totals: mean objects per room over single-room scenes, per house over scenes of
three or more rooms, the sparsest room, and pooled COL / STB / removed.

    .venv/bin/python scripts/bench_scenes.py ../shared/eval/dev_prompts.jsonl --out out/bench \\
        [--bin target/release/scenesmith] [--ids a,b] [--limit N]
"""

import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_requirements import bench_args, generate  # noqa: E402 - the sibling script's runner


def pct(a, b):
    return 100.0 * a / b if b else 100.0


def share(a, b):
    """A percent cell, or "-" when nothing was simulated."""
    return f"{pct(a, b):.1f}" if b else "-"


def row_of(entry_id, metrics, secs):
    c = metrics["counts"]
    rooms = max(1, len(c.get("per_room") or {}))
    stb = metrics.get("stb") or {}
    point = metrics.get("stb_point") or {}
    removed = metrics.get("removed") or {}
    return {
        "id": entry_id,
        "rooms": rooms,
        "objects": c["total"],
        "per_room_counts": list((c.get("per_room") or {}).values()),
        "col_n": len(metrics["col"].get("colliding") or []),
        "col_pct": metrics["col"]["percent"],
        "free": stb.get("free_objects", 0),
        "stable": stb.get("stable", 0),
        "free_pt": point.get("free_objects", 0),
        "stable_pt": point.get("stable", 0),
        "removed": removed.get("removed", 0),
        "placed": removed.get("placed", c["total"]),
        "lost": removed.get("lost") or {},
        "secs": secs,
    }


def main():
    args, want = bench_args(
        __doc__, lambda ap: ap.add_argument("--limit", type=int, default=0))
    with open(args.prompts) as f:
        entries = [json.loads(line) for line in f if line.strip()]
    entries = [e for e in entries if e.get("kind") != "refuse" and (not want or e["id"] in want)]
    if args.limit:
        entries = entries[: args.limit]
    rows, failed = [], []
    for e in entries:
        out = os.path.join(args.out, e["id"])
        rc, secs = generate(args.bin, e["prompt"], out, os.path.join(args.out, e["id"] + ".log"))
        path = os.path.join(out, "metrics.json")
        if rc != 0 or not os.path.exists(path):
            failed.append((e["id"], rc))
            continue
        with open(path) as f:
            rows.append(row_of(e["id"], json.load(f), secs))
    print("| id | rooms | objects | per room | COL % | STB % (Drake defaults) | STB % (point) "
          "| removed | lost | generate s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        lost = ", ".join(f"{k} {v}" for k, v in sorted(r["lost"].items()))
        print(f"| {r['id']} | {r['rooms']} | {r['objects']} | {r['objects'] / r['rooms']:.1f} "
              f"| {r['col_pct']:.2f} | {share(r['stable'], r['free'])} "
              f"| {share(r['stable_pt'], r['free_pt'])} "
              f"| {r['removed']} ({pct(r['removed'], r['placed']):.1f} %) | {lost} "
              f"| {r['secs']:.0f} |")
    for i, rc in failed:
        print(f"| {i} | generate exit {rc} | | | | | | | | |")
    print()
    single = [r for r in rows if r["rooms"] == 1]
    houses = [r for r in rows if r["rooms"] >= 3]
    room_counts = [n for r in rows for n in r["per_room_counts"]]
    if single:
        print(f"objects per room (single-room scenes, {len(single)}): "
              f"mean {sum(r['objects'] for r in single) / len(single):.1f}, "
              f"min {min(r['objects'] for r in single)}, "
              f"time mean {sum(r['secs'] for r in single) / len(single):.0f} s")
    if houses:
        print(f"objects per house (3+ rooms, {len(houses)}): "
              f"mean {sum(r['objects'] for r in houses) / len(houses):.1f}, "
              f"min {min(r['objects'] for r in houses)}, "
              f"time mean {sum(r['secs'] for r in houses) / len(houses):.0f} s")
    if room_counts:
        print(f"sparsest room (any scene): {min(room_counts)} objects")
    objects = sum(r["objects"] for r in rows)
    print(f"COL: {sum(r['col_n'] for r in rows)} of {objects} objects "
          f"({pct(sum(r['col_n'] for r in rows), objects):.2f} %) deeper than 1 mm")
    for key, free, stable in (("Drake defaults, files as written", "free", "stable"),
                              ("point contact (SceneEval)", "free_pt", "stable_pt")):
        f_, s_ = sum(r[free] for r in rows), sum(r[stable] for r in rows)
        print(f"STB {key}: {s_}/{f_} free objects stable ({share(s_, f_)} %)")
    removed, placed = sum(r["removed"] for r in rows), sum(r["placed"] for r in rows)
    lost = sum(sum(r["lost"].values()) for r in rows)
    print(f"removed by post-processing: {removed} of {placed} placed ({pct(removed, placed):.2f} %); "
          f"asked for and lost: {lost}")
    if failed:
        print(f"failed: {len(failed)} of {len(entries)}")


if __name__ == "__main__":
    sys.exit(main())
