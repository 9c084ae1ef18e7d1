//! Names with spaces, quotes, unicode, control characters and `..` in the prompt and in asset,
//! link, joint, part, material and texture names give valid, escaped files (MuJoCo loads the
//! MJCF, usd-core opens the USD with no validator error and reads the prompt back verbatim, the
//! GLB parses) and nothing is written outside the output directory.

mod export_common;

use std::path::Path;

use export_common::{drawer_and_door_asset, mujoco, usd};
use scenesmith::assets::Texture;
use scenesmith::export::{ExportSet, write_exports};
use scenesmith::physics::Bridge;
use scenesmith::pipeline::build_scene;
use scenesmith::scene::{ObjectKind, Pose, SceneObject, Support};
use serde_json::Value;

const PROMPT: &str = "A \"quoted\" kitchen's <b>table</b> & ]]> -- @../../etc/passwd@ \
                      tür 漢字 🙂 back\\slash\nnew line\ttab \u{1} bell, with a cabinet";

fn walk(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            walk(&p, out);
        }
        out.push(p);
    }
}

#[test]
fn hostile_names_give_valid_escaped_contained_files() {
    let (mut state, _) = build_scene(
        PROMPT,
        1,
        "names_test",
        &scenesmith::agents::Backend::Builtin,
    )
    .unwrap();
    let room = state.scene.rooms[0].id.clone();

    // An asset whose every name is hostile, with a texture.
    let mut asset = drawer_and_door_asset();
    asset.id = "../../evil \"asset\" tür/..".into();
    asset.category = "drawer \"box\" ../".into();
    asset.material = "oak \"x\" ..".into();
    asset.links[0].name = "bo dy/../".into();
    asset.links[1].name = "Bo Dy".into();
    asset.links[2].name = "../../door \"r\"".into();
    asset.joints[0].parent = asset.links[0].name.clone();
    asset.joints[0].child = asset.links[1].name.clone();
    asset.joints[0].name = "slide \"1\" ..".into();
    asset.joints[1].parent = asset.links[0].name.clone();
    asset.joints[1].child = asset.links[2].name.clone();
    asset.joints[1].name = "../hinge <&>".into();
    let part = &mut asset.links[0].visuals[0];
    part.name = "../../part \u{1} ü".into();
    part.mesh = part.mesh.with_box_uvs(0.1);
    let rgba: Vec<u8> = (0..16)
        .flat_map(|i| [i * 16, 255 - i * 16, 90, 255])
        .collect();
    part.texture = Some(Texture {
        name: "../../tex \"ü\" ..".into(),
        width: 4,
        height: 4,
        rgba: std::sync::Arc::new(rgba),
    });
    asset.validate().unwrap();
    let asset_id = state.insert_asset(asset);
    state.scene.objects.push(SceneObject {
        id: "weird \"obj\" ../tür".into(),
        category: "drawer \"box\" ../".into(),
        name: None,
        planned: None,
        kind: ObjectKind::Furniture,
        room,
        asset: asset_id,
        world_from_object: Pose::from_xyz_yaw(-3.0, 0.0, 0.0, 0.3),
        support: Support::World,
        welded: true,
        joint_positions: Default::default(),
    });
    state.scene.validate().unwrap();

    let outer = tempfile::tempdir().unwrap();
    let dir = outer.path().join("nested").join("scene");
    std::fs::create_dir_all(&dir).unwrap();
    let written = write_exports(&dir, &state, &ExportSet::all()).unwrap();
    assert_eq!(written.len(), 3);

    // Nothing outside the scene directory, every path component plain.
    let mut files = Vec::new();
    walk(outer.path(), &mut files);
    for f in files.iter().filter(|f| !dir.starts_with(f)) {
        let rel = f.strip_prefix(outer.path()).unwrap();
        assert!(rel.starts_with("nested/scene"), "{} escaped", f.display());
        for c in f
            .strip_prefix(&dir)
            .into_iter()
            .flat_map(|r| r.components())
        {
            let c = c.as_os_str().to_str().unwrap();
            assert!(
                !c.starts_with('.')
                    && c.chars()
                        .all(|ch| ch.is_ascii_alphanumeric() || ch == '_' || ch == '.'),
                "unsafe file name {c:?} in {}",
                f.display()
            );
        }
    }
    assert!(
        files
            .iter()
            .any(|f| f.to_string_lossy().ends_with(".png") && f.starts_with(dir.join("export/usd"))),
        "the texture is exported for USD"
    );

    let mut bridge = Bridge::from_env().unwrap();
    // MuJoCo loads it (XML escaping held) and the prompt comes back as written, minus the
    // control characters XML cannot carry.
    let m = mujoco(&mut bridge, &dir, 0.2, &[]);
    assert!(m.finite);
    let xml = std::fs::read_to_string(dir.join("export/mujoco/scene.xml")).unwrap();
    let root = scenesmith::util::xml::parse(&xml).unwrap();
    let data = root
        .find("custom")
        .unwrap()
        .find_all("text")
        .find(|t| t.get_attr("name") == Some("scenesmith/prompt"))
        .and_then(|t| t.get_attr("data").map(str::to_string))
        .unwrap();
    let plain: String = PROMPT
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    assert_eq!(data, plain);
    assert!(m.joints.len() >= 3);

    // usd-core opens it, no validator error, and the prompt round-trips exactly.
    let u = usd(&mut bridge, &dir);
    assert_eq!(u.metadata.custom_layer_data["prompt"], PROMPT);
    let errors: Vec<_> = u
        .findings
        .iter()
        .filter(|f| f.severity == "Error")
        .collect();
    assert!(errors.is_empty(), "{errors:?}");
    assert!(u.composition_errors.is_empty());
    let joints = &u.joints;
    assert!(joints.iter().all(|j| j.body0_ok && j.body1_ok));
    assert!(
        joints
            .iter()
            .any(|j| j.path.starts_with("/World/weird_obj_t_r/Joints/")),
        "{joints:?}"
    );

    // The GLB parses and carries the prompt and the raw ids as JSON strings.
    let glb = std::fs::read(dir.join("export/scene.glb")).unwrap();
    let len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let doc: Value = serde_json::from_slice(&glb[20..20 + len]).unwrap();
    assert_eq!(doc["asset"]["extras"]["prompt"], PROMPT);
    assert!(
        doc["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .any(|n| n["extras"]["id"] == "weird \"obj\" ../tür")
    );
    assert!(scenesmith::assets::gltf_read::parse(&glb, None).is_ok());
}
