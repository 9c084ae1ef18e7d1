//! `scenesmith render` and the renders `generate` writes, as a user runs them.

mod common;

use std::path::Path;

use common::{dev_prompt, scenesmith, text};

/// Width and height of a PNG file (decoding the whole image, so a truncated file fails).
fn png_size(path: &Path) -> (u32, u32) {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    (info.width, info.height)
}

fn pngs(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".png"))
        .collect();
    names.sort();
    names
}

#[test]
fn generate_writes_renders_and_render_rewrites_them_from_the_directory() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("office");
    let prompt = dev_prompt("type_diversity_15");
    let g = scenesmith(
        &[
            "generate",
            &prompt,
            "--out",
            out.to_str().unwrap(),
            "--no-check",
        ],
        &[],
    );
    assert!(g.status.success(), "{}", text(&g));
    let renders = out.join("renders");
    let names = pngs(&renders);
    assert!(names.contains(&"top.png".to_string()), "{names:?}");
    let views: Vec<_> = names.iter().filter(|n| n.contains("_view_")).collect();
    assert_eq!(views.len(), 4, "{names:?}");
    for n in &names {
        let (w, h) = png_size(&renders.join(n));
        if n.contains("_view_") {
            assert_eq!((w, h), (1280, 960), "{n}");
        } else {
            assert!(w > 400 && h > 400 && w <= 1600 && h <= 1600, "{n}: {w}x{h}");
        }
    }

    // Re-render the written directory elsewhere: same files.
    let again = root.path().join("again");
    let r = scenesmith(
        &[
            "render",
            out.to_str().unwrap(),
            "--out",
            again.to_str().unwrap(),
            "--json",
        ],
        &[],
    );
    assert!(r.status.success(), "{}", text(&r));
    let summary: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
    let files = summary["files"].as_array().unwrap();
    assert_eq!(files.len(), names.len());
    assert_eq!(pngs(&again), names);
    for n in &names {
        assert_eq!(png_size(&again.join(n)), png_size(&renders.join(n)), "{n}");
    }

    // Default output: DIR/renders. Three threads give the bytes one thread gave.
    std::fs::remove_dir_all(&renders).unwrap();
    let r = scenesmith(
        &["render", out.to_str().unwrap()],
        &[("RAYON_NUM_THREADS", "3")],
    );
    assert!(r.status.success(), "{}", text(&r));
    assert_eq!(pngs(&renders), names);
    for n in &names {
        assert!(
            std::fs::read(renders.join(n)).unwrap() == std::fs::read(again.join(n)).unwrap(),
            "{n} depends on the thread count"
        );
    }
}

#[test]
fn generate_no_render_writes_no_renders() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("plain");
    let g = scenesmith(
        &[
            "generate",
            "a small bedroom with a bed",
            "--out",
            out.to_str().unwrap(),
            "--no-check",
            "--no-render",
        ],
        &[],
    );
    assert!(g.status.success(), "{}", text(&g));
    assert!(out.join("scene.json").is_file());
    assert!(!out.join("renders").exists());
}

#[test]
fn render_of_a_missing_directory_is_a_clear_error() {
    let root = tempfile::tempdir().unwrap();
    let missing = root.path().join("nope");
    let r = scenesmith(&["render", missing.to_str().unwrap()], &[]);
    assert_eq!(r.status.code(), Some(1), "{}", text(&r));
    let err = String::from_utf8_lossy(&r.stderr);
    assert!(err.contains("nope") && err.contains("scene.json"), "{err}");
    assert!(
        !missing.exists(),
        "a failed render must not create the directory"
    );
}

#[test]
fn asset_writes_a_preview_and_gallery_writes_contact_sheets() {
    let root = tempfile::tempdir().unwrap();
    let asset = root.path().join("chair");
    let a = scenesmith(
        &["asset", "a red armchair", "--out", asset.to_str().unwrap()],
        &[("SCENESMITH_ASSET_CACHE", "off")],
    );
    assert!(a.status.success(), "{}", text(&a));
    assert_eq!(png_size(&asset.join("preview.png")), (480, 360));

    let gallery = root.path().join("gallery");
    let g = scenesmith(
        &[
            "gallery",
            "--out",
            gallery.to_str().unwrap(),
            "--only",
            "lamp",
            "--json",
        ],
        &[],
    );
    assert!(g.status.success(), "{}", text(&g));
    let report: serde_json::Value = serde_json::from_slice(&g.stdout).unwrap();
    let entries = report["entries"].as_array().unwrap();
    // Floor lamps stand on the floor, table and desk lamps on surfaces, sconces on walls.
    let sheets = pngs(&gallery);
    assert!(
        sheets.contains(&"gallery_floor.png".to_string()),
        "{sheets:?}"
    );
    assert!(
        sheets.contains(&"gallery_surface.png".to_string()),
        "{sheets:?}"
    );
    assert!(entries.iter().any(|e| e["category"] == "floor_lamp"));
    assert!(
        entries
            .iter()
            .all(|e| e["category"].as_str().unwrap().contains("lamp"))
    );
    for s in &sheets {
        let (w, h) = png_size(&gallery.join(s));
        assert!(w >= 240 && h >= 180, "{s}: {w}x{h}");
    }
    let none = scenesmith(
        &[
            "gallery",
            "--out",
            gallery.to_str().unwrap(),
            "--only",
            "zeppelin",
        ],
        &[],
    );
    assert_eq!(none.status.code(), Some(2), "{}", text(&none));
}
