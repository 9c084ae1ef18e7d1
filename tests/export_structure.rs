//! The MJCF, USD and GLB writers against scenes the pipeline builds: one MuJoCo body per link
//! and one collision geom per convex piece, USD asset layers with their bodies, colliders and
//! joints (and a welded, posed articulated cabinet), every scene object a named GLB root node.
//!
//! These were unit tests of `export` until issue 13 item 2: they build their scenes with
//! `pipeline::build_scene`, and `export` sits below `pipeline`, so they live here and use the
//! writers' public API.

use scenesmith::agents::Backend;
use scenesmith::export::view::Hold;
use scenesmith::export::{ExportFile, SceneView, glb, mjcf, usd};
use scenesmith::pipeline::build_scene;
use scenesmith::state::SceneState;
use serde_json::Value;

fn kitchen() -> SceneState {
    build_scene(
        "a kitchen with a table, two chairs, a cabinet, plates and mugs",
        2,
        "mjcf_unit",
        &Backend::Builtin,
    )
    .unwrap()
    .0
}

#[test]
fn one_collision_geom_per_piece_and_one_body_per_link() {
    let state = kitchen();
    let view = SceneView::new(&state).unwrap();
    let files = mjcf::files(&view).unwrap();
    let xml = String::from_utf8(files[0].bytes.clone()).unwrap();
    let pieces: usize = view
        .objects
        .iter()
        .map(|o| view.asset_of(o).asset.collision_pieces())
        .sum();
    assert_eq!(xml.matches("class=\"collision\"").count(), pieces + 1);
    let links: usize = view
        .objects
        .iter()
        .map(|o| view.asset_of(o).asset.links.len())
        .sum();
    assert_eq!(xml.matches("<body ").count(), links);
    let free = view.objects.iter().filter(|o| o.hold == Hold::Free).count();
    assert_eq!(xml.matches("<freejoint ").count(), free);
    assert!(xml.contains("type=\"hinge\""));
    assert!(xml.contains("<exclude body1="));
    assert!(xml.contains("angle=\"radian\""));
    // Every referenced mesh file is written.
    for f in xml.split("file=\"").skip(1) {
        let name = &f[..f.find('"').unwrap()];
        let path = if name.ends_with(".png") {
            format!("textures/{name}")
        } else {
            format!("meshes/{name}")
        };
        assert!(files.iter().any(|x| x.path == path), "{path}");
    }
}

fn text<'a>(files: &'a [ExportFile], path: &str) -> &'a str {
    let f = files.iter().find(|f| f.path == path).unwrap();
    std::str::from_utf8(&f.bytes).unwrap()
}

fn bedroom() -> SceneState {
    let (mut state, _) = build_scene(
        "a bedroom with a cabinet and books",
        4,
        "usd_unit",
        &Backend::Builtin,
    )
    .unwrap();
    // Weld the cabinet with its door half open.
    let cab = state
        .scene
        .objects
        .iter_mut()
        .find(|o| o.category == "cabinet")
        .unwrap();
    cab.welded = true;
    cab.joint_positions.insert("door_hinge".into(), 0.5);
    state
}

#[test]
fn asset_layers_carry_bodies_colliders_and_joints() {
    let state = bedroom();
    let view = SceneView::new(&state).unwrap();
    let files = usd::files(&view).unwrap();
    for av in &view.assets {
        let layer = text(&files, &format!("assets/{}.usda", av.name));
        assert!(layer.starts_with("#usda 1.0\n"));
        assert!(layer.contains(&format!("defaultPrim = \"{}\"", av.name)));
        assert_eq!(
            layer
                .matches("physics:approximation = \"convexHull\"")
                .count(),
            av.asset.collision_pieces(),
            "{}",
            av.name
        );
        let bodies = layer.matches("\"PhysicsRigidBodyAPI\"").count();
        let want = if av.asset.is_static {
            0
        } else {
            av.asset.links.len()
        };
        assert_eq!(bodies, want, "{}", av.name);
        if av.asset.category == "cabinet" {
            assert!(layer.contains("def PhysicsRevoluteJoint \"door_hinge\""));
            assert!(layer.contains("float physics:upperLimit = 100"));
            assert!(layer.contains("rel physics:filteredPairs = [</"));
        }
    }
    let scene = text(&files, "scene.usda");
    assert!(scene.contains("metersPerUnit = 1") && scene.contains("upAxis = \"Z\""));
    assert!(scene.contains("def PhysicsScene \"PhysicsScene\""));
    // The welded cabinet: articulation root on the object prim, a weld to the world, and
    // its door posed at 0.5 rad.
    let cab = view
        .objects
        .iter()
        .find(|o| o.object.category == "cabinet")
        .unwrap();
    let start = scene.find(&format!("def Xform \"{}\"", cab.name)).unwrap();
    let block = &scene[start..];
    let block = &block[..block.find("\n    }\n").unwrap()];
    assert!(block.contains("PhysicsArticulationRootAPI"), "{block}");
    assert!(block.contains("def PhysicsFixedJoint \"world_weld\""));
    assert!(block.contains("over \"door\""));
    // Books are free single-link bodies: no kinematic flag.
    let book = view
        .objects
        .iter()
        .find(|o| o.object.category == "book")
        .unwrap();
    let start = scene.find(&format!("def Xform \"{}\"", book.name)).unwrap();
    let block = &scene[start..];
    let block = &block[..block.find("\n    }\n").unwrap()];
    assert!(!block.contains("kinematicEnabled"), "{block}");
}

#[test]
fn every_object_is_a_named_root_node() {
    let (state, _) = build_scene(
        "a bedroom with a cabinet and a shelf with books",
        5,
        "glb_unit",
        &Backend::Builtin,
    )
    .unwrap();
    let view = SceneView::new(&state).unwrap();
    let glb = glb::scene_glb(&view);
    let total = u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize;
    assert_eq!(total, glb.len());
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let doc: Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    let roots = doc["scenes"][0]["nodes"].as_array().unwrap();
    assert_eq!(roots.len(), state.scene.objects.len());
    for (r, o) in roots.iter().zip(&state.scene.objects) {
        let node = &doc["nodes"][r.as_u64().unwrap() as usize];
        assert_eq!(node["name"], o.id.as_str());
        assert_eq!(node["extras"]["category"], o.category.as_str());
    }
    assert_eq!(
        doc["asset"]["extras"]["prompt"],
        state.scene.provenance.prompt.as_str()
    );
    // The binary chunk survived the re-pack: every buffer view fits.
    let bin_len = doc["buffers"][0]["byteLength"].as_u64().unwrap() as usize;
    let chunk = u32::from_le_bytes(glb[20 + json_len..24 + json_len].try_into().unwrap()) as usize;
    assert!(chunk >= bin_len);
}
