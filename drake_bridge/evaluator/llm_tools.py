"""The evaluator's tools as an LLM calls them: one entry point, `run_tool(state, args)`, over the
state tools (tools.py) and the vision tools (vision.py).

    result, images = run_tool(state, EvalToolArgs(scene_dir, dmd, "get_distance",
                                                  object_id="mug_0", other_id="table_0"))

The model reads the result, so a bad argument (a missing or unknown id, the same id twice) is
a result `{"error": "..."}` naming the argument and a few valid ids, never an exception. Results
are plain JSON: floats rounded to ROUND_DIGITS, NaN and infinities as null. Images are
(name, PNG bytes).
"""

import difflib
import math

import numpy as np

from drake_bridge.errors import BadRequest
from drake_bridge.evaluator import tools, vision
from drake_bridge.policy.output import png_bytes

#: Decimals kept in results (0.1 mm, 1e-4 of a fraction).
ROUND_DIGITS = 4
#: Valid ids an error message lists.
SUGGESTED_IDS = 6


def run_tool(state, args):
    """Runs `args.tool` (protocol.EvalToolArgs or any object with its fields) on `state`:
    (JSON-ready result dict, [(image name, PNG bytes)])."""
    handler = _TOOLS.get(args.tool)
    if handler is None:
        return {"error": f"unknown tool {args.tool!r}; tools: {', '.join(sorted(_TOOLS))}"}, []
    try:
        result, images = handler(state, args)
    except _ArgumentError as e:
        return {"error": str(e)}, []
    except BadRequest as e:
        # What the tool itself refuses (an object without collision geometry) is the model's
        # to read too.
        return {"error": e.message}, []
    return clean(result), [(name, png_bytes(rgba)) for name, rgba in images]


def clean(value):
    """`value` as plain JSON data: numpy scalars and arrays unwrapped, floats rounded to
    ROUND_DIGITS, NaN and infinities as None."""
    if isinstance(value, dict):
        return {str(k): clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [clean(v) for v in value]
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        value = float(value)
        if not math.isfinite(value):
            return None
        return round(value, ROUND_DIGITS) + 0.0  # + 0.0: no "-0.0"
    return value


class _ArgumentError(Exception):
    """A bad tool argument; its message is the error the model reads."""


# -- arguments ------------------------------------------------------------------------------

def _suggestions(state, wrong):
    """A few valid ids: those that look like `wrong` first, then the scene's movable objects."""
    close = difflib.get_close_matches(wrong or "", state.ids, n=SUGGESTED_IDS, cutoff=0.4)
    rest = [i for i in state.ids if i not in close and state.kind(i) != "architecture"]
    rest += [i for i in state.ids if i not in close and i not in rest]
    return (close + rest)[:SUGGESTED_IDS]


def _object(state, args, field, tool):
    """The id in args.<field>, checked."""
    object_id = getattr(args, field)
    if not object_id:
        raise _ArgumentError(f"{tool} needs {field} (an object id, e.g. "
                             f"{', '.join(_suggestions(state, ''))})")
    _check_known(state, object_id, field)
    return object_id


def _check_known(state, object_id, field):
    if object_id not in state.ids:
        raise _ArgumentError(
            f"{field} {object_id!r} is no object of this scene; valid ids include "
            f"{', '.join(_suggestions(state, object_id))} ({len(state.ids)} objects: "
            "list_objects names them all)")


def _pair(state, args, tool):
    a = _object(state, args, "object_id", tool)
    b = _object(state, args, "other_id", tool)
    if a == b:
        raise _ArgumentError(f"{tool} needs two different objects; object_id and other_id are "
                             f"both {a!r}")
    return a, b


# -- the tools ------------------------------------------------------------------------------

def _list_objects(state, args):
    result = tools.list_objects(state, category=args.category or None)
    if args.category and not result["objects"]:
        categories = sorted({state.category(i) for i in state.ids} - {None})
        result["note"] = (f"no object's category matches {args.category!r}; the scene's "
                          f"categories: {', '.join(categories)}")
    return result, []


def _get_object_info(state, args):
    return tools.get_object_info(state, _object(state, args, "object_id", "get_object_info")), []


def _get_distance(state, args):
    return tools.get_distance(state, *_pair(state, args, "get_distance")), []


def _get_spatial_relation(state, args):
    return tools.get_spatial_relation(state, *_pair(state, args, "get_spatial_relation")), []


def _get_support(state, args):
    return tools.get_support(state, _object(state, args, "object_id", "get_support")), []


def _observe_scene(state, args):
    return vision.observe_scene(state)


def _observe_objects(state, args):
    asked = list(args.object_ids or []) or [i for i in (args.object_id, args.other_id) if i]
    if not asked:
        raise _ArgumentError("observe_objects needs object_ids (one or more object ids, e.g. "
                             f"{', '.join(_suggestions(state, '')[:2])})")
    ids = list(dict.fromkeys(asked))
    if len(ids) > len(vision.HIGHLIGHTS):
        raise _ArgumentError(f"observe_objects shows at most {len(vision.HIGHLIGHTS)} objects "
                             f"at once; got {len(ids)}")
    for object_id in ids:
        _check_known(state, object_id, "object_ids entry")
    return vision.observe_objects(state, ids)


_TOOLS = {
    "list_objects": _list_objects,
    "get_object_info": _get_object_info,
    "get_distance": _get_distance,
    "get_spatial_relation": _get_spatial_relation,
    "get_support": _get_support,
    "observe_scene": _observe_scene,
    "observe_objects": _observe_objects,
}
