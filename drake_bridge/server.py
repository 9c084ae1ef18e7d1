"""The JSON-lines server loop: handshake, dispatch, structured errors."""

import json
import os
import signal
import sys
import traceback

from drake_bridge import BRIDGE_VERSION, PROTOCOL
from drake_bridge.errors import BadRequest, BridgeError


def _protocol_stream():
    """Keeps the real stdout for protocol lines and points fd 1 at stderr.

    Drake's C++ code and stray prints then cannot corrupt the protocol stream.
    """
    proto_fd = os.dup(1)
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    return os.fdopen(proto_fd, "w", buffering=1, encoding="utf-8")


def _maybe_crash(op):
    """Test hook: die like a killed process when asked to (see tests/test_protocol.py).

    SCENESMITH_BRIDGE_CRASH_ON=<op> kills the process on every request with that op;
    SCENESMITH_BRIDGE_CRASH_ONCE=<path> kills it on the first such request only (the file
    records that the crash happened, so a restarted bridge succeeds).
    """
    target = os.environ.get("SCENESMITH_BRIDGE_CRASH_ON")
    if not target or target != op:
        return
    once = os.environ.get("SCENESMITH_BRIDGE_CRASH_ONCE")
    if once:
        if os.path.exists(once):
            return
        with open(once, "w", encoding="utf-8") as f:
            f.write("crashed\n")
    os.kill(os.getpid(), signal.SIGKILL)


def handle(line, call):
    """Handles one request line with `call(op, args)`; returns the response dict."""
    try:
        request = json.loads(line)
    except json.JSONDecodeError as e:
        return {"id": None, "ok": False,
                "error": {"type": "bad_request", "message": f"request is not JSON: {e}"}}
    if not isinstance(request, dict):
        return {"id": None, "ok": False,
                "error": {"type": "bad_request", "message": "request must be a JSON object"}}
    rid = request.get("id")
    op = request.get("op")
    args = request.get("args") or {}
    try:
        if not isinstance(args, dict):
            raise BadRequest("args must be a JSON object")
        _maybe_crash(op)
        result = call(op, args)
        return {"id": rid, "ok": True, "result": result}
    except BridgeError as e:
        return {"id": rid, "ok": False, "error": {"type": e.type_name, "message": e.message}}
    except Exception as e:  # noqa: BLE001 - every failure must reach the client as a reply
        traceback.print_exc(file=sys.stderr)
        return {"id": rid, "ok": False,
                "error": {"type": "internal", "message": f"{type(e).__name__}: {e}"}}


def main():
    proto = _protocol_stream()
    # Imported after the stream swap so that anything pydrake prints goes to stderr.
    from drake_bridge import ops as ops_module

    hello = {"hello": {"protocol": PROTOCOL, "bridge": BRIDGE_VERSION,
                       "drake": ops_module.drake_version(),
                       "python": ".".join(map(str, sys.version_info[:3]))}}
    proto.write(json.dumps(hello) + "\n")
    proto.flush()
    for line in sys.stdin:
        line = line.strip()
        if not line:
            continue
        response = handle(line, ops_module.call)
        proto.write(json.dumps(response) + "\n")
        proto.flush()
    return 0
