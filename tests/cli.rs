//! The command line as a user meets it: a scene from a prompt that Drake loads collision-free,
//! determinism, and bad input that gives a clear error and loses nothing.

mod common;

use std::path::Path;

use common::{dev_prompt, scenesmith, text};

fn read(p: &Path) -> Vec<u8> {
    std::fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn generate_then_check_passes_for_dev_prompts() {
    let root = tempfile::tempdir().unwrap();
    // The first scene runs as the README runs it; the two dense ones leave the stability
    // simulations out of their metrics (minutes of CI; STB has its own tests).
    for (id, stb) in [
        ("type_diversity_15", true),
        ("object_density_07", false),
        ("house_03", false),
    ] {
        let out = root.path().join(id);
        let prompt = dev_prompt(id);
        let out_arg = out.to_str().unwrap();
        let mut args = vec!["generate", &prompt, "--out", out_arg, "--json"];
        if !stb {
            args.push("--no-stb");
        }
        let g = scenesmith(&args, &[]);
        assert!(g.status.success(), "{id}: {}", text(&g));
        let summary: serde_json::Value = serde_json::from_slice(&g.stdout).unwrap();
        assert_eq!(summary["check"]["col_percent"].as_f64(), Some(0.0), "{id}");
        assert!(summary["check"]["problems"].as_array().unwrap().is_empty());
        let metrics: serde_json::Value =
            serde_json::from_slice(&read(&out.join("metrics.json"))).unwrap();
        for key in ["stb", "stb_point"] {
            let simulated = metrics[key]["free_objects"].as_u64().is_some_and(|n| n > 0);
            assert_eq!(simulated, stb, "{id}: {key} in metrics.json");
        }
        for f in [
            "scene.dmd.yaml",
            "scene_furniture_welded.dmd.yaml",
            "scene.json",
            "package.xml",
        ] {
            assert!(out.join(f).is_file(), "{id}: missing {f}");
        }
        let c = scenesmith(&["check", out.to_str().unwrap(), "--json"], &[]);
        assert!(c.status.success(), "{id}: {}", text(&c));
        let report: serde_json::Value = serde_json::from_slice(&c.stdout).unwrap();
        assert_eq!(report["passed"], true);
        assert!(
            report["free_bodies"].as_u64().unwrap() >= 1,
            "{id}: nothing free"
        );
    }
}

#[test]
fn same_seed_same_bytes_other_seed_other_scene() {
    let root = tempfile::tempdir().unwrap();
    let prompt = dev_prompt("object_density_12");
    // Same directory name under different parents, so the package names match too.
    let run = |parent: &str, seed: &str| {
        let out = root.path().join(parent).join("scene");
        let g = scenesmith(
            &[
                "generate",
                &prompt,
                "--out",
                out.to_str().unwrap(),
                "--seed",
                seed,
                "--no-check",
            ],
            &[],
        );
        assert!(g.status.success(), "{}", text(&g));
        out
    };
    let a = run("a", "7");
    let b = run("b", "7");
    let c = run("c", "8");
    for f in [
        "scene.json",
        "scene.dmd.yaml",
        "scene_furniture_welded.dmd.yaml",
        "package.xml",
    ] {
        assert_eq!(
            read(&a.join(f)),
            read(&b.join(f)),
            "{f} differs between identical runs"
        );
    }
    assert_ne!(read(&a.join("scene.json")), read(&c.join("scene.json")));
}

#[test]
fn empty_prompt_exits_2_with_a_message() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("never");
    for prompt in ["", "   ", "12345 !!!"] {
        let g = scenesmith(&["generate", prompt, "--out", out.to_str().unwrap()], &[]);
        assert_eq!(g.status.code(), Some(2), "{}", text(&g));
        let err = String::from_utf8_lossy(&g.stderr);
        assert!(err.contains("prompt"), "{err}");
        assert!(!out.exists());
    }
    assert_eq!(std::fs::read_dir(root.path()).unwrap().count(), 0);
}

/// A prompt the built-in reader understands nothing of (another language, gibberish) exits 2
/// with what it read and the way out, and writes nothing; `--lenient` builds a default room.
#[test]
fn unreadable_prompts_are_refused_unless_lenient() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("never");
    for prompt in [
        "Ein Schlafzimmer mit einem Bett und einem Kleiderschrank.",
        "Une cuisine lumineuse avec une grande table en bois et six chaises.",
        "寝室にはベッドと机があります。",
        "asdkjh qwpeoiru zxmcnv",
    ] {
        let g = scenesmith(&["generate", prompt, "--out", out.to_str().unwrap()], &[]);
        assert_eq!(g.status.code(), Some(2), "{prompt}: {}", text(&g));
        let err = String::from_utf8_lossy(&g.stderr);
        assert!(
            err.contains("understood no room and no object")
                && err.contains("--llm-base-url")
                && err.contains("--lenient"),
            "{err}"
        );
        assert!(!out.exists());
    }
    let lenient = root.path().join("lenient");
    let g = scenesmith(
        &[
            "generate",
            "asdkjh qwpeoiru zxmcnv",
            "--out",
            lenient.to_str().unwrap(),
            "--lenient",
            "--no-render",
            "--export",
            "none",
            "--json",
        ],
        &[],
    );
    assert!(g.status.success(), "{}", text(&g));
    let summary: serde_json::Value = serde_json::from_slice(&g.stdout).unwrap();
    assert_eq!(summary["rooms"].as_array().map(Vec::len), Some(1));
    assert!(lenient.join("scene.json").is_file());
}

#[test]
fn unwritable_output_is_a_clear_error() {
    let root = tempfile::tempdir().unwrap();
    // A path below a regular file can never be created.
    let file = root.path().join("file.txt");
    std::fs::write(&file, "x").unwrap();
    let out = file.join("scene");
    let g = scenesmith(
        &[
            "generate",
            "a kitchen with a table",
            "--out",
            out.to_str().unwrap(),
            "--no-stb",
        ],
        &[],
    );
    assert_eq!(g.status.code(), Some(1), "{}", text(&g));
    assert!(
        String::from_utf8_lossy(&g.stderr).contains("file.txt"),
        "{}",
        text(&g)
    );
    // The cause is printed once, not once per layer that wraps it.
    assert_eq!(
        String::from_utf8_lossy(&g.stderr)
            .matches("os error")
            .count(),
        1,
        "{}",
        text(&g)
    );
    assert_eq!(read(&file), b"x");

    // A directory holding something that is not a scene is never replaced.
    let precious = root.path().join("precious");
    std::fs::create_dir(&precious).unwrap();
    std::fs::write(precious.join("notes.txt"), "keep me").unwrap();
    let g = scenesmith(
        &[
            "generate",
            "a kitchen with a table",
            "--out",
            precious.to_str().unwrap(),
        ],
        &[],
    );
    assert_eq!(g.status.code(), Some(1), "{}", text(&g));
    assert!(
        String::from_utf8_lossy(&g.stderr).contains("not a scene directory written by scenesmith")
    );
    assert_eq!(read(&precious.join("notes.txt")), b"keep me");

    // Nor is one whose scene.json some other program wrote.
    std::fs::write(precious.join("scene.json"), r#"{"camera": [0, 0, 1]}"#).unwrap();
    let g = scenesmith(
        &[
            "generate",
            "a kitchen with a table",
            "--out",
            precious.to_str().unwrap(),
        ],
        &[],
    );
    assert_eq!(g.status.code(), Some(1), "{}", text(&g));
    assert_eq!(read(&precious.join("notes.txt")), b"keep me");
    assert_eq!(
        read(&precious.join("scene.json")),
        br#"{"camera": [0, 0, 1]}"#
    );
}

/// Replacing a scene deletes only what scenesmith wrote: a user's file in it moves, with the
/// old scene, to `DIR.previous`; views are replaced whole, refusing a folder with other files.
#[test]
fn replacing_a_scene_keeps_the_users_files() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("scene");
    let out_arg = out.to_str().unwrap();
    let generate = || {
        let g = scenesmith(
            &[
                "generate",
                "a bedroom with a bed",
                "--out",
                out_arg,
                "--no-check",
                "--no-render",
                "--export",
                "glb",
            ],
            &[],
        );
        assert!(g.status.success(), "{}", text(&g));
        String::from_utf8_lossy(&g.stderr).into_owned()
    };
    generate();
    let stderr = generate();
    assert!(!stderr.contains("kept as"), "{stderr}");
    assert_eq!(listing(root.path()), vec!["scene"]);
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let stderr = generate();
    let previous = root.path().join("scene.previous");
    assert!(stderr.contains(previous.to_str().unwrap()), "{stderr}");
    assert_eq!(read(&previous.join("notes.txt")), b"mine");
    assert!(previous.join("scene.json").is_file());
    assert!(!out.join("notes.txt").exists());

    // Views: a folder of views is replaced whole; one holding a user's file is refused.
    let views = root.path().join("views");
    std::fs::create_dir(&views).unwrap();
    std::fs::write(views.join("bedroom_0_view_9.png"), "stale").unwrap();
    let r = scenesmith(&["render", out_arg, "--out", views.to_str().unwrap()], &[]);
    assert!(r.status.success(), "{}", text(&r));
    assert!(views.join("top.png").is_file());
    assert!(
        !views.join("bedroom_0_view_9.png").exists(),
        "a stale view stayed"
    );
    std::fs::write(views.join("sketch.txt"), "mine").unwrap();
    let r = scenesmith(&["render", out_arg, "--out", views.to_str().unwrap()], &[]);
    assert_eq!(r.status.code(), Some(1), "{}", text(&r));
    assert!(
        String::from_utf8_lossy(&r.stderr).contains("sketch.txt"),
        "{}",
        text(&r)
    );
    assert_eq!(read(&views.join("sketch.txt")), b"mine");
}

/// Every entry of `dir` (names only), to prove nothing half-written was left behind.
fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn missing_bridge_is_a_clear_error_and_writes_nothing() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("scene");
    let g = scenesmith(
        &[
            "generate",
            "a kitchen with a table",
            "--out",
            out.to_str().unwrap(),
            "--no-stb",
        ],
        &[("SCENESMITH_PYTHON", "/nonexistent/python")],
    );
    assert_eq!(g.status.code(), Some(1), "{}", text(&g));
    let err = String::from_utf8_lossy(&g.stderr);
    assert!(err.contains("scripts/setup.sh"), "{err}");
    assert!(
        listing(root.path()).is_empty(),
        "{:?}",
        listing(root.path())
    );
}

#[test]
fn bridge_killed_mid_request_keeps_previous_scene() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("scene");
    let first = scenesmith(
        &[
            "generate",
            "a minimal kitchen with a table",
            "--out",
            out.to_str().unwrap(),
            "--no-stb",
        ],
        &[],
    );
    assert!(first.status.success(), "{}", text(&first));
    let before = read(&out.join("scene.json"));
    // --no-stb: metrics without the stability simulations, everything else as usual.
    let metrics: serde_json::Value =
        serde_json::from_slice(&read(&out.join("metrics.json"))).unwrap();
    assert!(
        metrics["stb"].is_null() && metrics["stb_point"].is_null(),
        "{metrics}"
    );
    assert_eq!(metrics["col"]["percent"].as_f64(), Some(0.0));

    // The bridge is SIGKILLed on every collision_report: one restart, one retry, then a clear
    // error; the previous scene is untouched and no staging directory is left behind.
    let g = scenesmith(
        &[
            "generate",
            "an office with a shelf and books",
            "--out",
            out.to_str().unwrap(),
            "--no-stb",
        ],
        &[("SCENESMITH_BRIDGE_CRASH_ON", "collision_report")],
    );
    assert_eq!(g.status.code(), Some(1), "{}", text(&g));
    let err = String::from_utf8_lossy(&g.stderr);
    assert!(err.contains("died during `collision_report`"), "{err}");
    assert_eq!(read(&out.join("scene.json")), before);
    // The finished stages are kept for `--resume`, and the error says so; nothing else.
    assert!(err.contains("--resume"), "{err}");
    assert_eq!(
        listing(root.path()),
        vec![".scene.checkpoints".to_string(), "scene".to_string()]
    );

    // Killed once: the request is retried on a fresh bridge and the run succeeds.
    let marker = root.path().join("crashed-once");
    let g = scenesmith(
        &[
            "generate",
            "an office with a shelf and books",
            "--out",
            out.to_str().unwrap(),
            "--no-stb",
        ],
        &[
            ("SCENESMITH_BRIDGE_CRASH_ON", "collision_report"),
            ("SCENESMITH_BRIDGE_CRASH_ONCE", marker.to_str().unwrap()),
        ],
    );
    assert!(g.status.success(), "{}", text(&g));
    assert!(marker.exists(), "the bridge did crash once");
    assert_ne!(read(&out.join("scene.json")), before);
}

#[test]
fn check_fails_on_a_scene_with_penetration() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("scene");
    let g = scenesmith(
        &[
            "generate",
            "a minimal kitchen with a table and four chairs",
            "--out",
            out.to_str().unwrap(),
            "--no-stb",
        ],
        &[],
    );
    assert!(g.status.success(), "{}", text(&g));
    // Move the first chair into the table in the directives, as a user's edit might.
    let scene: serde_json::Value = serde_json::from_slice(&read(&out.join("scene.json"))).unwrap();
    let table = scene["objects"]
        .as_array()
        .unwrap()
        .iter()
        .find(|o| o["category"] == "table")
        .unwrap();
    let t = &table["world_from_object"]["xyz"];
    let yaml = String::from_utf8(read(&out.join("scene.dmd.yaml"))).unwrap();
    let start = yaml.find("name: chair_0").unwrap();
    let tr = yaml[start..].find("translation: [").unwrap() + start + "translation: [".len();
    let end = yaml[tr..].find(']').unwrap() + tr;
    let edited = format!("{}{}, {}, 0.0{}", &yaml[..tr], t[0], t[1], &yaml[end..]);
    std::fs::write(out.join("scene.dmd.yaml"), edited).unwrap();
    let c = scenesmith(&["check", out.to_str().unwrap(), "--json"], &[]);
    assert_eq!(c.status.code(), Some(1), "{}", text(&c));
    let report: serde_json::Value = serde_json::from_slice(&c.stdout).unwrap();
    assert!(report["col_percent"].as_f64().unwrap() > 0.0);
    assert!(
        !report["problems"].as_array().unwrap().is_empty(),
        "pose mismatch reported"
    );
}

/// The `scene.json` of a scene an earlier run wrote, as small as the check accepts.
const OLD_SCENE: &str = r#"{"schema_version": 1, "provenance": {"tool_version": "0.1.0"}}"#;

/// A full disk: the run fails with a clear error, the previous scene stays, nothing
/// half-written is left. The disk is a 48 KiB tmpfs in a private mount namespace.
#[test]
fn full_disk_is_a_clear_error_and_loses_nothing() {
    let root = tempfile::tempdir().unwrap();
    let disk = root.path().join("disk");
    std::fs::create_dir(&disk).unwrap();
    let bin = env!("CARGO_BIN_EXE_scenesmith");
    let script = format!(
        "set -e; mount -t tmpfs -o size=48k tmpfs {disk}; mkdir {disk}/scene; echo '{old}' > {disk}/scene/scene.json; \
         set +e; SCENESMITH_HOME={home} {bin} generate 'A library with four shelves full of books and a table' --out {disk}/scene --no-check; \
         echo \"exit=$?\"; ls -a {disk}; cat {disk}/scene/scene.json",
        disk = disk.display(),
        home = common::home().display(),
        old = OLD_SCENE,
    );
    let out = std::process::Command::new("unshare")
        .args(["--user", "--map-root-user", "--mount", "sh", "-c", &script])
        .output()
        .expect("unshare runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stdout.contains("exit=1"),
        "stdout:\n{stdout}\nstderr:\n{stderr}"
    );
    assert!(stderr.contains("No space left on device"), "{stderr}");
    assert!(stderr.contains("left as it was"), "{stderr}");
    // Only the previous scene remains, with its content (and the checkpoints of finished
    // stages when they fitted on the disk: then the error points at `--resume`).
    let entries: Vec<&str> = stdout.lines().filter(|l| !l.starts_with("exit=")).collect();
    let kept_checkpoints = entries.contains(&".scene.checkpoints");
    let entries: Vec<&str> = entries
        .into_iter()
        .filter(|l| *l != ".scene.checkpoints")
        .collect();
    assert_eq!(entries, vec![".", "..", "scene", OLD_SCENE], "{stdout}");
    if kept_checkpoints {
        assert!(stderr.contains("--resume"), "{stderr}");
    }
}

/// A run that fails after its stages (here: the Drake bridge dies on every check) keeps
/// checkpoints; `--resume` continues from them and gives the scene an uninterrupted run gives.
#[test]
fn failed_run_resumes_from_its_checkpoints() {
    let root = tempfile::tempdir().unwrap();
    // A minimal room: resuming is about checkpoints, not clutter (and CI time).
    let prompt = "A minimal kitchen with a table, two chairs, two plates and a mug";
    let out = root.path().join("a/scene");
    let g = scenesmith(
        &[
            "generate",
            prompt,
            "--out",
            out.to_str().unwrap(),
            "--no-stb",
        ],
        &[("SCENESMITH_BRIDGE_CRASH_ON", "collision_report")],
    );
    assert_eq!(g.status.code(), Some(1), "{}", text(&g));
    let err = String::from_utf8_lossy(&g.stderr);
    assert!(err.contains("--resume"), "{err}");
    assert!(!out.exists());
    let checkpoints = root.path().join("a/.scene.checkpoints");
    assert!(checkpoints.join("progress.json").is_file());

    let r = scenesmith(
        &[
            "generate",
            prompt,
            "--out",
            out.to_str().unwrap(),
            "--resume",
            "--no-stb",
        ],
        &[("SCENESMITH_LOG", "info")],
    );
    assert!(r.status.success(), "{}", text(&r));
    let log = String::from_utf8_lossy(&r.stderr);
    assert!(log.contains("resumed stage kitchen_0/furniture"), "{log}");
    assert!(
        !checkpoints.exists(),
        "checkpoints are removed after success"
    );

    let fresh = root.path().join("b/scene");
    let f = scenesmith(
        &[
            "generate",
            prompt,
            "--out",
            fresh.to_str().unwrap(),
            "--no-stb",
        ],
        &[],
    );
    assert!(f.status.success(), "{}", text(&f));
    assert_eq!(
        read(&out.join("scene.json")),
        read(&fresh.join("scene.json"))
    );
    assert_eq!(
        read(&out.join("agent_log.jsonl")),
        read(&fresh.join("agent_log.jsonl"))
    );
}
