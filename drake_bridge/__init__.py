"""scenesmith's Drake bridge: a long-lived pydrake process speaking JSON lines over stdio.

Protocol (version PROTOCOL):
  bridge -> client, once at start:  {"hello": {"protocol": 1, "bridge": ..., "drake": ..., "python": ...}}
  client -> bridge, one per line:   {"id": 7, "op": "load", "args": {...}}
  bridge -> client, one per line:   {"id": 7, "ok": true, "result": {...}}
                                 or {"id": 7, "ok": false, "error": {"type": ..., "message": ...}}
Only protocol lines go to stdout; everything else (Drake's logging, prints) goes to stderr.
"""

PROTOCOL = 1
BRIDGE_VERSION = "0.1.0"
