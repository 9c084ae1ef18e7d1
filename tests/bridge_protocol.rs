//! Issue 13: a bridge reply that does not match its operation's reply type is an error naming
//! the operation, never a value with defaults filled in (before the typed protocol, a missing
//! key read as 0). The bridge here is a stand-in Python package that speaks the protocol's
//! framing but answers `ping` without its `drake` field, so the check runs without Drake.

use std::time::Duration;

use scenesmith::physics::protocol::{NoArgs, Ping};
use scenesmith::physics::{Bridge, BridgeConfig, BridgeError};

const STAND_IN: &str = r#"
import json, sys
print(json.dumps({"hello": {"protocol": 1, "bridge": "stand-in", "drake": "none",
                            "python": "3"}}), flush=True)
for line in sys.stdin:
    request = json.loads(line)
    result = {"pong": True, "protocol": 1, "bridge": "stand-in"}
    if request["op"] == "complete":
        result["drake"] = "none"
    print(json.dumps({"id": request["id"], "ok": True, "result": result}), flush=True)
"#;

fn stand_in_bridge() -> (tempfile::TempDir, Bridge) {
    let home = tempfile::tempdir().unwrap();
    let package = home.path().join("drake_bridge");
    std::fs::create_dir_all(&package).unwrap();
    std::fs::write(package.join("__init__.py"), "").unwrap();
    std::fs::write(package.join("__main__.py"), STAND_IN).unwrap();
    let config = BridgeConfig {
        python: which_python(),
        home: home.path().to_path_buf(),
        startup_timeout: Duration::from_secs(30),
        request_timeout: Duration::from_secs(30),
        env: Vec::new(),
    };
    let bridge = Bridge::start(config).unwrap();
    (home, bridge)
}

fn which_python() -> std::path::PathBuf {
    ["/usr/bin/python3", "/usr/local/bin/python3"]
        .iter()
        .map(std::path::PathBuf::from)
        .find(|p| p.exists())
        .expect("a python3 interpreter")
}

#[test]
fn a_reply_missing_a_field_is_an_error_naming_the_op() {
    let (_home, mut bridge) = stand_in_bridge();
    let err = bridge.call::<Ping>(&NoArgs {}).unwrap_err();
    match &err {
        BridgeError::BadReply { op, cause } => {
            assert_eq!(op, "ping");
            assert!(cause.contains("drake"), "{cause}");
        }
        other => panic!("expected BadReply, got {other}"),
    }
    assert!(err.to_string().contains("`ping`"), "{err}");
    // The same framing with every field present parses: the failure above is the missing key.
    let complete = bridge.request("complete", serde_json::json!({})).unwrap();
    let reply: scenesmith::physics::protocol::PingReply = serde_json::from_value(complete).unwrap();
    assert_eq!(reply.drake, "none");
}
