//! The README's pydrake snippet loads a generated scene, exactly as written.

mod common;

use common::{run_python, scenesmith, text};

#[test]
fn readme_pydrake_snippet_loads_a_generated_scene() {
    let readme = std::fs::read_to_string(common::home().join("README.md")).unwrap();
    let marker = readme
        .find("<!-- pydrake-snippet")
        .expect("snippet marker in README");
    let start = readme[marker..].find("```python\n").unwrap() + marker + "```python\n".len();
    let end = readme[start..].find("```").unwrap() + start;
    let snippet = &readme[start..end];
    assert!(
        snippet.lines().count() <= 6,
        "the README promises a short snippet"
    );

    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("out/kitchen");
    let g = scenesmith(
        &[
            "generate",
            "A kitchen with a table, four chairs, plates and mugs",
            "--out",
            out.to_str().unwrap(),
            "--no-check",
        ],
        &[],
    );
    assert!(g.status.success(), "{}", text(&g));
    // The snippet uses the README's relative path; run it from the directory that has out/.
    let code = format!(
        "import os; os.chdir({:?})\n{snippet}",
        root.path().to_str().unwrap()
    );
    let stdout = run_python(&code, &[]);
    let scene: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("scene.json")).unwrap()).unwrap();
    let objects = scene["objects"].as_array().unwrap().len();
    // Drake adds the world and default model instances.
    assert!(
        stdout.starts_with(&format!("{} model instances", objects + 2)),
        "{stdout}"
    );
}
