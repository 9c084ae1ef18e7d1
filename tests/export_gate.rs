//! The conformance gate and the CLI around it: `generate` writes the exports (and `--export`
//! chooses), `export DIR --check` passes on a good scene, and the gate fails on exactly the
//! export bugs users of other generators report: joints not set up in USD, prims without
//! collision, joint-limit signs flipped, collision offset from visuals on articulated parts.

mod common;
mod export_common;

use std::path::Path;

use export_common::{articulated_state, write_all};
use scenesmith::export::conformance::{GateOptions, run_gate, table};
use scenesmith::export::{ExportSet, write_exports};
use scenesmith::physics::Bridge;
use scenesmith::state::SceneState;

fn asset_layer(dir: &Path, starts_with: &str) -> std::path::PathBuf {
    std::fs::read_dir(dir.join("export/usd/assets"))
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .find(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with(starts_with)
        })
        .unwrap()
}

fn edit(path: &Path, f: impl FnOnce(String) -> String) {
    let text = std::fs::read_to_string(path).unwrap();
    let new = f(text.clone());
    assert_ne!(new, text, "the edit of {} changed nothing", path.display());
    std::fs::write(path, new).unwrap();
}

/// Runs the gate on `formats` and returns the failed rows as `format: check`.
fn failed_rows(bridge: &mut Bridge, dir: &Path, state: &SceneState, formats: &str) -> Vec<String> {
    let opts = GateOptions {
        seconds: 0.2,
        formats: ExportSet::parse(formats).unwrap(),
    };
    let report = run_gate(bridge, dir, state, &opts).unwrap();
    let failed: Vec<String> = report
        .rows
        .iter()
        .filter(|r| !r.pass)
        .map(|r| format!("{}: {}", r.format, r.check))
        .collect();
    assert_eq!(report.passed, failed.is_empty(), "{}", table(&report));
    failed
}

#[test]
fn gate_catches_the_classic_export_bugs() {
    let state = articulated_state();
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    write_all(dir, &state);
    let mut bridge = Bridge::from_env().unwrap();
    assert!(failed_rows(&mut bridge, dir, &state, "all").is_empty());
    let rewrite = |fmt: &str| write_exports(dir, &state, &ExportSet::parse(fmt).unwrap()).unwrap();

    // Joints not set up in USD: the hinge prim is a plain Xform.
    edit(&asset_layer(dir, "cabinet_"), |t| {
        t.replace("def PhysicsRevoluteJoint", "def Xform")
    });
    let failed = failed_rows(&mut bridge, dir, &state, "usd");
    assert!(
        failed.iter().any(|f| f.starts_with("usd: joints")),
        "{failed:?}"
    );
    assert!(
        failed
            .iter()
            .any(|f| f.starts_with("all: objects / mass / joints"))
    );
    rewrite("usd");

    // Prims without collision: a rigid body whose colliders lost PhysicsCollisionAPI.
    edit(&asset_layer(dir, "drawer_box"), |t| {
        t.replace("\"PhysicsCollisionAPI\", ", "")
    });
    let failed = failed_rows(&mut bridge, dir, &state, "usd");
    assert!(
        failed
            .iter()
            .any(|f| f.starts_with("usd: rigid bodies with mass and colliders")),
        "{failed:?}"
    );
    assert!(
        failed
            .iter()
            .any(|f| f.starts_with("usd: convexHull collider per piece"))
    );
    rewrite("usd");

    // Joint-limit signs flipped, in USD (limits) and in MJCF (axis).
    edit(&asset_layer(dir, "cabinet_"), |t| {
        t.replace("physics:lowerLimit = 0", "physics:lowerLimit = -100")
            .replace("physics:upperLimit = 100", "physics:upperLimit = 0")
    });
    let failed = failed_rows(&mut bridge, dir, &state, "usd");
    assert_eq!(
        failed,
        vec!["usd: joints: targets resolve, limits (deg / m), axis sign, initial position"]
    );
    rewrite("usd");
    edit(&dir.join("export/mujoco/scene.xml"), |t| {
        t.replace(
            "type=\"hinge\" axis=\"0 0 1\"",
            "type=\"hinge\" axis=\"0 0 -1\"",
        )
    });
    let failed = failed_rows(&mut bridge, dir, &state, "mjcf");
    assert!(
        failed
            .iter()
            .any(|f| f.starts_with("mujoco: hinge/slide joints")),
        "{failed:?}"
    );
    rewrite("mjcf");

    // Collision offset from the visuals on an articulated part (MJCF and USD).
    edit(&dir.join("export/mujoco/scene.xml"), |t| {
        t.replace(
            "/door/c000\" class=\"collision\"",
            "/door/c000\" pos=\"0.05 0 0\" class=\"collision\"",
        )
    });
    let failed = failed_rows(&mut bridge, dir, &state, "mjcf");
    assert_eq!(failed, vec!["mujoco: collision/visual placement"]);
    rewrite("mjcf");
    edit(&asset_layer(dir, "cabinet_"), |t| {
        let door = t.find("def Xform \"door\"").unwrap();
        let coll = door + t[door..].find("def Xform \"collisions\"").unwrap();
        let brace = coll + t[coll..].find('{').unwrap() + 1;
        format!(
            "{}\n double3 xformOp:translate = (0.05, 0, 0)\n uniform token[] xformOpOrder = [\"xformOp:translate\"]{}",
            &t[..brace],
            &t[brace..]
        )
    });
    let failed = failed_rows(&mut bridge, dir, &state, "usd");
    assert_eq!(failed, vec!["usd: collision/visual placement"]);
    rewrite("usd");

    // A missing export is a failure, not a crash.
    std::fs::remove_file(dir.join("export/scene.glb")).unwrap();
    let failed = failed_rows(&mut bridge, dir, &state, "glb");
    assert_eq!(failed, vec!["glb: loads"]);
}

#[test]
fn generate_writes_exports_and_the_cli_gate_passes() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("scene");
    let out_s = out.to_str().unwrap();
    let prompt = "A bedroom with a cabinet and a shelf with books";
    let r = common::scenesmith(&["generate", prompt, "--out", out_s, "--no-check"], &[]);
    assert!(r.status.success(), "{}", common::text(&r));
    for f in [
        "export/mujoco/scene.xml",
        "export/usd/scene.usda",
        "export/scene.glb",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }

    let r = common::scenesmith(&["--json", "export", out_s, "--check", "--no-write"], &[]);
    assert!(r.status.success(), "{}", common::text(&r));
    let v: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    assert_eq!(v["passed"], true);
    assert!(v["check"]["rows"].as_array().unwrap().len() >= 15);
    assert_eq!(v["check"]["mujoco_stability"]["finite"], true);

    // Only MJCF, then none; a bad list is a usage error that writes nothing.
    let only = root.path().join("only_mjcf");
    let only_s = only.to_str().unwrap();
    let r = common::scenesmith(
        &[
            "generate",
            prompt,
            "--out",
            only_s,
            "--no-check",
            "--export",
            "mjcf",
        ],
        &[],
    );
    assert!(r.status.success(), "{}", common::text(&r));
    assert!(only.join("export/mujoco/scene.xml").is_file());
    assert!(!only.join("export/usd").exists() && !only.join("export/scene.glb").exists());
    let none = root.path().join("none");
    let r = common::scenesmith(
        &[
            "generate",
            prompt,
            "--out",
            none.to_str().unwrap(),
            "--no-check",
            "--export",
            "none",
        ],
        &[],
    );
    assert!(r.status.success(), "{}", common::text(&r));
    assert!(!none.join("export").exists());
    let bad = root.path().join("bad");
    let r = common::scenesmith(
        &[
            "generate",
            prompt,
            "--out",
            bad.to_str().unwrap(),
            "--export",
            "fbx",
        ],
        &[],
    );
    assert_eq!(r.status.code(), Some(2), "{}", common::text(&r));
    assert!(!bad.exists());

    // `export` on a scene without exports writes them; a broken export fails the gate (exit 1).
    let r = common::scenesmith(&["export", none.to_str().unwrap(), "--formats", "usd"], &[]);
    assert!(r.status.success(), "{}", common::text(&r));
    assert!(none.join("export/usd/scene.usda").is_file());
    std::fs::write(
        none.join("export/usd/scene.usda"),
        "#usda 1.0\ndef \"World\" {\n",
    )
    .unwrap();
    let r = common::scenesmith(
        &[
            "export",
            none.to_str().unwrap(),
            "--formats",
            "usd",
            "--check",
            "--no-write",
        ],
        &[],
    );
    assert_eq!(r.status.code(), Some(1), "{}", common::text(&r));
    assert!(String::from_utf8_lossy(&r.stderr).contains("FAIL"));
}
