//! `scenesmith view DIR` in headless Chromium: the page loads the scene, a click on an object
//! picks and highlights it, hiding a kind changes the picture, focusing a room moves the camera
//! (the checks are in `src/view/web/test/screenshot.mjs`, which compares screenshots pixel by
//! pixel). Needs node, npm and Debian's chromium, which `scripts/test.sh` installs.

mod common;

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};

use common::{generate_quick, home, scenesmith, text};

/// Kills the server when the test ends, passing or not.
struct Server(Child);

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn run(cmd: &mut Command) -> std::process::Output {
    cmd.output()
        .unwrap_or_else(|e| panic!("cannot run {cmd:?}: {e}"))
}

#[test]
fn the_viewer_shows_picks_and_highlights_an_object_in_chromium() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("scene");
    let d = dir.to_str().unwrap();
    // No GLB export: `view` writes it before serving.
    generate_quick(
        "a bedroom with a bed, a nightstand and a lamp on the nightstand",
        &dir,
    );
    assert!(!dir.join("export/scene.glb").exists());

    let build = run(Command::new(home().join("scripts/build_viewer.sh")).arg("--quiet"));
    assert!(build.status.success(), "build_viewer.sh: {}", text(&build));

    let child = Command::new(env!("CARGO_BIN_EXE_scenesmith"))
        .args(["view", d, "--port", "0"])
        .env("SCENESMITH_HOME", home())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("scenesmith view starts");
    let mut server = Server(child);
    let stdout = server.0.stdout.take().expect("piped stdout");
    let mut url = String::new();
    BufReader::new(stdout)
        .read_line(&mut url)
        .expect("the server prints its address");
    let url = url.trim().to_string();
    assert!(
        url.starts_with("http://127.0.0.1:"),
        "address line: {url:?}"
    );
    assert!(dir.join("export/scene.glb").is_file(), "view wrote the GLB");

    let shot = root.path().join("view.png");
    let test = run(Command::new("node")
        .arg(home().join("src/view/web/test/screenshot.mjs"))
        .arg(&url)
        .arg(&shot));
    assert!(test.status.success(), "screenshot test: {}", text(&test));
    let png = std::fs::read(&shot).expect("screenshot written");
    assert!(
        png.starts_with(b"\x89PNG") && png.len() > 20_000,
        "{} bytes",
        png.len()
    );
    drop(server);

    // A directory that is not a scene is refused before anything is served.
    let r = scenesmith(&["view", root.path().to_str().unwrap()], &[]);
    assert_eq!(r.status.code(), Some(2), "{}", text(&r));
    assert!(text(&r).contains("not a scene directory"), "{}", text(&r));
}
