"""The JSON-lines protocol, spoken by a real bridge subprocess."""

import json
import subprocess
import sys

from drake_bridge import PROTOCOL


def start(env):
    return subprocess.Popen([sys.executable, "-m", "drake_bridge"], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)


def ask(proc, request):
    proc.stdin.write(json.dumps(request) + "\n")
    proc.stdin.flush()
    return json.loads(proc.stdout.readline())


def test_handshake_ping_and_structured_errors(bridge_env, overlapping_scene):
    proc = start(bridge_env)
    try:
        hello = json.loads(proc.stdout.readline())["hello"]
        assert hello["protocol"] == PROTOCOL
        assert ask(proc, {"id": 1, "op": "ping"}) == {
            "id": 1, "ok": True,
            "result": {"pong": True, "protocol": PROTOCOL, "bridge": hello["bridge"],
                       "drake": hello["drake"]}}
        bad = ask(proc, {"id": 2, "op": "fly"})
        assert bad["ok"] is False and bad["error"]["type"] == "bad_request"
        assert "unknown op" in bad["error"]["message"]
        proc.stdin.write("this is not json\n")
        proc.stdin.flush()
        garbled = json.loads(proc.stdout.readline())
        assert garbled["ok"] is False and garbled["error"]["type"] == "bad_request"
        loaded = ask(proc, {"id": 3, "op": "load", "args": overlapping_scene})
        assert loaded["ok"] is True and loaded["result"]["num_model_instances"] == 4
        missing = ask(proc, {"id": 4, "op": "load", "args": {"directives": "/no/such.yaml"}})
        assert missing["error"]["type"] == "file_missing"
    finally:
        proc.stdin.close()
        proc.wait(timeout=30)
    assert proc.returncode == 0


def test_crash_hook_kills_like_a_signal(bridge_env, tmp_path):
    env = dict(bridge_env, SCENESMITH_BRIDGE_CRASH_ON="ping",
               SCENESMITH_BRIDGE_CRASH_ONCE=str(tmp_path / "once"))
    proc = start(env)
    json.loads(proc.stdout.readline())
    proc.stdin.write(json.dumps({"id": 1, "op": "ping"}) + "\n")
    proc.stdin.flush()
    assert proc.stdout.readline() == ""
    assert proc.wait(timeout=30) == -9
    # The marker file makes a restarted bridge survive the same request.
    proc = start(env)
    json.loads(proc.stdout.readline())
    assert ask(proc, {"id": 1, "op": "ping"})["ok"] is True
    proc.stdin.close()
    proc.wait(timeout=30)
