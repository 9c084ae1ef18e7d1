"""The Python side of the protocol against the schema the Rust types generate.

protocol.schema.json is written from src/physics/protocol (a Rust unit test keeps it current).
Here every op's argument and reply dataclass must match it field by field: the same names, the
same required fields and defaults for arguments, and compatible types all the way down. A field
added on one side only fails here, before a reply with a missing key could reach the client.
"""

import dataclasses
import json
import os
import types
import typing
from typing import Literal, Union

import pytest

from drake_bridge import ops, protocol
from drake_bridge.protocol import SIGNATURES

SCHEMA_PATH = os.path.join(os.path.dirname(protocol.__file__), "protocol.schema.json")


@pytest.fixture(scope="module")
def schema():
    with open(SCHEMA_PATH, encoding="utf-8") as f:
        return json.load(f)


def _split_null(s):
    """(nullable, schema without the null alternative)."""
    t = s.get("type")
    if isinstance(t, list) and "null" in t:
        rest = [x for x in t if x != "null"]
        inner = dict(s, type=rest[0] if len(rest) == 1 else rest)
        return True, inner
    for key in ("anyOf", "oneOf"):
        alts = s.get(key)
        if alts and any(a.get("type") == "null" for a in alts):
            others = [a for a in alts if a.get("type") != "null"]
            if len(others) == 1:
                return True, others[0]
    return False, s


def _consts(s):
    if "enum" in s:
        return set(s["enum"])
    if "const" in s:
        return {s["const"]}
    alts = s.get("oneOf") or s.get("anyOf") or []
    out = set()
    for a in alts:
        c = _consts(a)
        if not c:
            return set()
        out |= c
    return out


def compare(tp, s, where, problems):
    """Records in `problems` every way annotation `tp` and JSON schema `s` disagree."""
    origin = typing.get_origin(tp)
    nullable, inner = _split_null(s)
    if origin in (Union, types.UnionType):
        args = [a for a in typing.get_args(tp) if a is not type(None)]
        if not nullable:
            problems.append(f"{where}: Optional in Python, not nullable in the schema")
        compare(args[0], inner, where, problems)
        return
    if nullable:
        problems.append(f"{where}: nullable in the schema, not Optional in Python")
    s = inner
    if origin is Literal:
        want = set(typing.get_args(tp))
        got = _consts(s)
        if want != got:
            problems.append(f"{where}: values {sorted(want)} in Python, {sorted(got)} in the schema")
        return
    simple = {bool: "boolean", int: "integer", float: "number", str: "string"}
    if tp in simple:
        if s.get("type") != simple[tp]:
            problems.append(f"{where}: {tp.__name__} in Python, {s.get('type')} in the schema")
        return
    if origin is list:
        if s.get("type") != "array" or "maxItems" in s:
            problems.append(f"{where}: list in Python, {s.get('type')} in the schema")
            return
        compare(typing.get_args(tp)[0], s.get("items", {}), f"{where}[]", problems)
        return
    if origin is tuple:
        items = typing.get_args(tp)
        if s.get("type") != "array" or s.get("minItems") != len(items) or s.get("maxItems") != len(items):
            problems.append(f"{where}: {len(items)}-tuple in Python, not a fixed array in the schema")
            return
        for i, t in enumerate(items):
            compare(t, s.get("items", {}), f"{where}[{i}]", problems)
        return
    if origin is dict:
        if s.get("type") != "object" or "additionalProperties" not in s:
            problems.append(f"{where}: dict in Python, not a map in the schema")
            return
        compare(typing.get_args(tp)[1], s["additionalProperties"], f"{where}{{}}", problems)
        return
    if dataclasses.is_dataclass(tp):
        compare_dataclass(tp, s, where, problems, check_required=False)
        return
    problems.append(f"{where}: no rule for {tp!r}")


def _default(f):
    if f.default is not dataclasses.MISSING:
        return protocol._to_json(f.default)
    if f.default_factory is not dataclasses.MISSING:
        return protocol._to_json(f.default_factory())
    return dataclasses.MISSING


def compare_dataclass(cls, s, where, problems, check_required):
    if s.get("type") != "object":
        problems.append(f"{where}: {cls.__name__} is not an object in the schema")
        return
    props = s.get("properties", {})
    fields = {f.name: f for f in dataclasses.fields(cls)}
    for name in sorted(set(props) - set(fields)):
        problems.append(f"{where}.{name}: in the schema, not in {cls.__name__}")
    for name in sorted(set(fields) - set(props)):
        problems.append(f"{where}.{name}: in {cls.__name__}, not in the schema")
    hints = typing.get_type_hints(cls)
    required = set(s.get("required", []))
    for name in sorted(set(fields) & set(props)):
        compare(hints[name], props[name], f"{where}.{name}", problems)
        if not check_required:
            continue
        default = _default(fields[name])
        if (default is dataclasses.MISSING) != (name in required):
            problems.append(f"{where}.{name}: required in one side only")
        if default is not dataclasses.MISSING and "default" in props[name] \
                and props[name]["default"] != default:
            problems.append(f"{where}.{name}: default {default!r} in Python, "
                            f"{props[name]['default']!r} in the schema")


def test_the_schema_and_the_python_side_name_the_same_ops(schema):
    assert schema["protocol"] == protocol_version()
    assert set(schema["ops"]) == set(SIGNATURES) == set(ops.OPS)


def protocol_version():
    from drake_bridge import PROTOCOL
    return PROTOCOL


@pytest.mark.parametrize("op", sorted(SIGNATURES))
def test_every_dataclass_matches_the_schema(schema, op):
    args_type, reply_type = SIGNATURES[op]
    problems = []
    compare_dataclass(args_type, schema["ops"][op]["args"], f"{op}.args", problems,
                      check_required=True)
    compare_dataclass(reply_type, schema["ops"][op]["reply"], f"{op}.reply", problems,
                      check_required=False)
    assert problems == []


def test_the_comparison_catches_a_drifted_field(schema):
    @dataclasses.dataclass(kw_only=True)
    class Drifted:
        pong: bool
        protocol: str  # an integer in the schema
        bridge: str
        extra: int  # not in the schema
    problems = []
    compare_dataclass(Drifted, schema["ops"]["ping"]["reply"], "ping.reply", problems, False)
    assert any("protocol" in p for p in problems)
    assert any("extra" in p for p in problems)
    assert any("drake" in p for p in problems)
