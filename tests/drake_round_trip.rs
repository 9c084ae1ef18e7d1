//! Rust writes a scene, the Drake bridge loads it, and what Drake sees matches what Rust wrote:
//! model instances, bodies, free bodies and their poses, welds, joints and limits.

mod common;

use std::collections::BTreeMap;

use scenesmith::agents::Backend;
use scenesmith::formats::scene_dir::write_scene_dir;
use scenesmith::physics::Bridge;
use scenesmith::physics::protocol::{Load, LoadedInstance, SceneFiles};
use scenesmith::pipeline::build_scene;
use scenesmith::scene::ObjectKind;

#[test]
fn drake_loads_what_rust_wrote() {
    let prompt =
        "A kitchen with a table, four chairs, a cabinet, a shelf with books, plates and mugs.";
    let (state, _) = build_scene(prompt, 4, "round_trip", &Backend::Builtin).unwrap();
    let dir = tempfile::tempdir().unwrap();
    write_scene_dir(dir.path(), &state).unwrap();

    let mut bridge = Bridge::from_env().unwrap();
    let loaded = bridge
        .call::<Load>(&SceneFiles::new(
            dir.path().join("scene.dmd.yaml"),
            dir.path().join("package.xml"),
        ))
        .unwrap();

    let scene = &state.scene;
    let instances: BTreeMap<&str, &LoadedInstance> = loaded
        .model_instances
        .iter()
        .map(|m| (m.name.as_str(), m))
        .collect();
    assert_eq!(
        instances.len(),
        scene.objects.len(),
        "one model instance per object"
    );

    let expected_bodies: usize = scene
        .objects
        .iter()
        .map(|o| state.assets[&o.asset].links.len())
        .sum();
    assert_eq!(loaded.num_bodies, expected_bodies);

    let mut free = 0;
    for obj in &scene.objects {
        let m = instances[obj.id.as_str()];
        let free_bodies = &m.free_bodies;
        if obj.welded {
            assert!(free_bodies.is_empty(), "{} should be welded", obj.id);
            continue;
        }
        free += 1;
        assert_eq!(free_bodies.len(), 1, "{}: one free root body", obj.id);
        let pose = &free_bodies["body"];
        let t = obj.world_from_object.translation();
        let q = obj.world_from_object.rotation();
        let p = pose.translation();
        let xyz = [p.x, p.y, p.z];
        let r = pose.rotation();
        let wxyz = [r.w, r.i, r.j, r.k];
        for (a, b) in xyz.iter().zip([t.x, t.y, t.z]) {
            assert!(
                (a - b).abs() < 1e-8,
                "{}: translation {xyz:?} vs {t:?}",
                obj.id
            );
        }
        // q and -q are the same rotation.
        let dot = wxyz[0] * q.w + wxyz[1] * q.i + wxyz[2] * q.j + wxyz[3] * q.k;
        assert!(
            dot.abs() > 1.0 - 1e-9,
            "{}: rotation {wxyz:?} vs {q:?}",
            obj.id
        );
        let asset = &state.assets[&obj.asset];
        assert!(
            (m.mass - asset.mass()).abs() < 1e-6 * asset.mass(),
            "{}: mass",
            obj.id
        );
    }
    assert!(
        free > 10,
        "expected furniture and manipulands to be free, got {free}"
    );

    // The articulated cabinet's hinge arrives with its limits.
    let cabinet = scene
        .objects
        .iter()
        .find(|o| o.category == "cabinet")
        .expect("a cabinet was placed");
    let joints = &instances[cabinet.id.as_str()].joints;
    assert_eq!(joints.len(), 1);
    assert_eq!(joints[0].kind, "revolute");
    let upper = joints[0].upper[0];
    assert!((upper - 100f64.to_radians()).abs() < 1e-9);

    // Architecture is welded (static) and there is exactly one per room.
    let arch: Vec<_> = scene.objects_of_kind(ObjectKind::Architecture).collect();
    assert_eq!(arch.len(), scene.rooms.len());
}

#[test]
fn furniture_welded_variant_loads_with_only_manipulands_free() {
    let (state, _) = build_scene(
        "An office with a table, a chair and a shelf with books.",
        2,
        "welded_variant",
        &Backend::Builtin,
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    write_scene_dir(dir.path(), &state).unwrap();
    let mut bridge = Bridge::from_env().unwrap();
    let loaded = bridge
        .call::<Load>(&SceneFiles::new(
            dir.path().join("scene_furniture_welded.dmd.yaml"),
            dir.path().join("package.xml"),
        ))
        .unwrap();
    for m in &loaded.model_instances {
        let name = &m.name;
        let obj = state.scene.object(name).unwrap();
        let is_free = !m.free_bodies.is_empty();
        assert_eq!(is_free, obj.kind == ObjectKind::Manipuland, "{name}");
    }
}
