"""The built-in evaluator: geometric predicates with stated thresholds, judged for every
candidate pair (each object the target noun names x each object the reference noun names).

Predicates (thresholds are the module constants):

- **on(t, r)**: directly, when all of
  - part of r lies under t's footprint, and t's lowest point is at most ON_MAX_GAP_M (1 cm)
    above the top of r under it (and at most SURFACE_PENETRATION_M, 5 mm, below it);
  - t is in contact with r: signed distance <= ON_CONTACT_M (5 mm);
  - at least ON_MIN_FOOTPRINT (50 %) of t's footprint lies over that surface of r.
  Or with one level of indirection: t is directly on some object o that is directly on r, and
  at least ON_MIN_FOOTPRINT of t's footprint lies over r's surface under t (a mug on a plate on
  the table is on the table; the plate's thickness does not count against the height rule).
  No tilt rule: a fallen bottle or a book lying on its side still rests on the table, and the
  asset frames of flat things (books, plates, rugs) do not agree on which axis is "up"; the
  tilt is reported as evidence (`tilt_deg`) for a caller that wants "upright".
- **inside(t, r)**: at least INSIDE_MIN_VOLUME (80 %) of t's oriented box (the bounds of its
  collision vertices in its own frame) lies inside r's oriented box (the bounds of r's
  collision vertices, every link at its current position, in r's frame). For a cabinet or a
  chest of drawers that box covers the carcass and every drawer and door, open or shut.
- **near(t, r)**: signed distance between their collision geometry <= NEAR_MAX_M (0.15 m),
  whether or not t is also on or inside r.

The overall verdict holds when any candidate pair holds. A noun that names no object gives a
verdict that does not hold, with the reason, never an exception.
"""

import json
import os

from drake_bridge.errors import BadRequest, FileMissing
from drake_bridge.evaluator.geometry import box_inside_fraction
from drake_bridge.evaluator.state import load_state, matching_ids
from drake_bridge.evaluator.tools import (
    SURFACE_PENETRATION_M,
    contacts,
    signed_distance,
    surface_under,
    tilt_deg,
)

#: "on": largest height of the target's lowest point above the reference's surface under it, m.
ON_MAX_GAP_M = 0.01
#: "on": largest signed distance between the target and what it rests on, m.
ON_CONTACT_M = 0.005
#: "on": smallest fraction of the target's footprint over the reference's surface.
ON_MIN_FOOTPRINT = 0.5
#: "inside": smallest fraction of the target's oriented-box volume inside the reference's box.
INSIDE_MIN_VOLUME = 0.8
#: "near": largest signed distance between target and reference, m.
NEAR_MAX_M = 0.15

PREDICATES = ("on", "inside", "near")

THRESHOLDS = {
    "on_max_gap_m": ON_MAX_GAP_M,
    "on_max_penetration_m": SURFACE_PENETRATION_M,
    "on_contact_m": ON_CONTACT_M,
    "on_min_footprint_fraction": ON_MIN_FOOTPRINT,
    "inside_min_volume_fraction": INSIDE_MIN_VOLUME,
    "near_max_m": NEAR_MAX_M,
}


def _mm(metres):
    return f"{round(metres * 1000.0, 1) + 0.0:.1f} mm"   # + 0.0: no "-0.0 mm"


def _on_direct(state, t, r):
    """(holds, evidence, reason) of t resting directly on r."""
    nearest = signed_distance(state, t, r)
    surface = surface_under(state, t, r)
    evidence = {
        "signed_distance_m": None if nearest is None else nearest[0],
        "bottom_gap_m": None if surface is None else surface["gap_m"],
        "surface_z_m": None if surface is None else surface["surface_z_m"],
        "footprint_fraction": None if surface is None else surface["footprint_fraction"],
        "tilt_deg": tilt_deg(state, t),
    }
    if surface is None:
        return False, evidence, f"no part of {r} lies under {t}"
    if surface["gap_m"] > ON_MAX_GAP_M:
        return False, evidence, (f"{t}'s lowest point is {_mm(surface['gap_m'])} above {r}'s "
                                 f"surface under it (at most {_mm(ON_MAX_GAP_M)})")
    if nearest is None:
        return False, evidence, f"{t} or {r} has no collision geometry"
    if nearest[0] > ON_CONTACT_M:
        return False, evidence, (f"{t} does not touch {r} (signed distance {_mm(nearest[0])}, "
                                 f"at most {_mm(ON_CONTACT_M)})")
    if surface["footprint_fraction"] < ON_MIN_FOOTPRINT:
        return False, evidence, (f"only {surface['footprint_fraction']:.0%} of {t}'s footprint "
                                 f"lies over {r} (at least {ON_MIN_FOOTPRINT:.0%})")
    return True, evidence, (f"{t} rests on {r}: its lowest point {_mm(surface['gap_m'])} from "
                            f"the surface at z = {surface['surface_z_m']:.3f} m, "
                            f"{surface['footprint_fraction']:.0%} of its footprint over it, "
                            f"signed distance {_mm(nearest[0])}")


def judge_on(state, t, r):
    """(holds, evidence, reason) of on(t, r), directly or through one object (module doc)."""
    holds, evidence, reason = _on_direct(state, t, r)
    evidence["via"] = None
    if holds:
        return True, evidence, reason
    for other in contacts(state, t, ON_CONTACT_M):
        if other == r:
            continue
        upper, upper_evidence, _ = _on_direct(state, t, other)
        lower, lower_evidence, _ = (False, None, None) if not upper else _on_direct(state, other, r)
        if not lower:
            continue
        surface = surface_under(state, t, r)
        over = 0.0 if surface is None else surface["footprint_fraction"]
        evidence["via"] = {"id": other, "target_on_via": upper_evidence,
                           "via_on_reference": lower_evidence,
                           "footprint_fraction_over_reference": over}
        if over >= ON_MIN_FOOTPRINT:
            return True, evidence, (f"{t} rests on {other}, which rests on {r}; {over:.0%} of "
                                    f"{t}'s footprint lies over {r}")
        reason = (f"{t} rests on {other}, which rests on {r}, but only {over:.0%} of {t}'s "
                  f"footprint lies over {r} (at least {ON_MIN_FOOTPRINT:.0%})")
    return False, evidence, reason


def judge_inside(state, t, r):
    """(holds, evidence, reason) of inside(t, r) (module doc)."""
    t_lo, t_hi = state.box_in_own_frame(t)
    r_lo, r_hi = state.box_in_own_frame(r)
    X_RT = state.X_WO(r).inverse().multiply(state.X_WO(t))
    fraction = box_inside_fraction(X_RT.rotation().matrix(), X_RT.translation(),
                                   t_lo, t_hi, r_lo, r_hi)
    evidence = {"volume_inside_fraction": fraction,
                "target_box_size_m": [float(v) for v in t_hi - t_lo],
                "reference_box_size_m": [float(v) for v in r_hi - r_lo],
                "reference_links": len(state.bodies(r))}
    if fraction >= INSIDE_MIN_VOLUME:
        return True, evidence, f"{fraction:.0%} of {t}'s box lies inside {r}'s box"
    return False, evidence, (f"only {fraction:.0%} of {t}'s box lies inside {r}'s box "
                             f"(at least {INSIDE_MIN_VOLUME:.0%})")


def judge_near(state, t, r):
    """(holds, evidence, reason) of near(t, r) (module doc)."""
    nearest = signed_distance(state, t, r)
    if nearest is None:
        return False, {"signed_distance_m": None}, f"{t} or {r} has no collision geometry"
    d = nearest[0]
    evidence = {"signed_distance_m": d}
    if d <= NEAR_MAX_M:
        return True, evidence, f"{t} is {d:.3f} m from {r} (at most {NEAR_MAX_M} m)"
    return False, evidence, f"{t} is {d:.3f} m from {r} (more than {NEAR_MAX_M} m)"


_JUDGES = {"on": judge_on, "inside": judge_inside, "near": judge_near}


def evaluate(state, predicate, target_category, reference_category):
    """Judges `predicate` (on / inside / near) for every pair of an object the noun
    `target_category` names and another the noun `reference_category` names.

    Returns {"predicate", "target", "reference", "holds" (any pair holds), "reason",
    "targets", "references" (the matching ids), "pairs": [{"target", "reference", "holds",
    "evidence", "reason"}], "thresholds", "directives" (the file judged)}. BadRequest for an
    unknown predicate."""
    judge_pair = _JUDGES.get(predicate)
    if judge_pair is None:
        raise BadRequest(f"unknown predicate {predicate!r}; expected one of {list(PREDICATES)}")
    targets = matching_ids(state, target_category)
    references = matching_ids(state, reference_category)
    pairs = []
    for t in targets:
        for r in references:
            if t == r:
                continue
            holds, evidence, reason = judge_pair(state, t, r)
            pairs.append({"target": t, "reference": r, "holds": holds, "evidence": evidence,
                          "reason": reason})
    held = [p for p in pairs if p["holds"]]
    if not targets:
        reason = f"no object in the scene is a {target_category!r}"
    elif not references:
        reason = f"no object in the scene is a {reference_category!r}"
    elif not pairs:
        reason = f"the only {target_category!r} is also the only {reference_category!r}"
    elif held:
        reason = "; ".join(p["reason"] for p in held)
    else:
        reason = "no pair holds: " + "; ".join(p["reason"] for p in pairs)
    return {"predicate": predicate, "target": target_category, "reference": reference_category,
            "holds": bool(held), "reason": reason, "targets": targets, "references": references,
            "pairs": pairs, "thresholds": dict(THRESHOLDS),
            "directives": state.directives_path}


def judge(scene_dir, task, dmd="scene.dmd.yaml"):
    """Loads `dmd` of the scene in `scene_dir` (see state.load_state) and evaluates `task`: a
    dict with "predicate", "target", "reference" (task.json's fields) or the path of a
    task.json. Returns `evaluate`'s dict."""
    if isinstance(task, (str, os.PathLike)):
        try:
            with open(task) as f:
                task = json.load(f)
        except FileNotFoundError as e:
            raise FileMissing(f"task file not found: {task}") from e
        except ValueError as e:
            raise BadRequest(f"{task} is not JSON: {e}") from e
    missing = [k for k in ("predicate", "target", "reference") if not task.get(k)]
    if missing:
        raise BadRequest(f"task lacks {', '.join(missing)}")
    state = load_state(scene_dir, dmd)
    return evaluate(state, task["predicate"], task["target"], task["reference"])
