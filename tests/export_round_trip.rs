//! Round-trip facts on a generated dev scene: each format's total mass equals the scene's, the
//! collider count equals the number of convex pieces, every object is there; exports are
//! deterministic and a scene directory read back from disk exports the same facts.

mod common;
mod export_common;

use export_common::{drake, mujoco, usd, write_all};
use scenesmith::export::{ExportFormat, SceneView, render};
use scenesmith::formats::scene_dir::load_state;
use scenesmith::physics::Bridge;
use scenesmith::pipeline::build_scene;
use scenesmith::scene::ObjectKind;

fn sum(values: impl Iterator<Item = f64>) -> f64 {
    values.sum()
}

#[test]
fn masses_colliders_and_objects_match_in_every_format() {
    let prompt = common::dev_prompt("object_density_03");
    let (state, _) = build_scene(
        &prompt,
        7,
        "round_trip_exports",
        &scenesmith::agents::Backend::Builtin,
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    write_all(dir.path(), &state);

    let scene = &state.scene;
    let asset = |o: &scenesmith::scene::SceneObject| &state.assets[&o.asset];
    let movable = || {
        scene
            .objects
            .iter()
            .filter(|o| o.kind != ObjectKind::Architecture)
    };
    let mass = sum(movable().map(|o| asset(o).mass()));
    let pieces: usize = scene
        .objects
        .iter()
        .map(|o| asset(o).collision_pieces())
        .sum();
    let links: usize = scene.objects.iter().map(|o| asset(o).links.len()).sum();
    assert!(movable().count() >= 10, "a dense scene");

    let mut bridge = Bridge::from_env().unwrap();
    let m = mujoco(&mut bridge, dir.path(), 0.0, &[]);
    let bodies = &m.bodies;
    assert_eq!(bodies.len(), links, "one MuJoCo body per link");
    let mj_mass = sum(bodies.iter().map(|b| b.mass));
    assert!((mj_mass - mass).abs() < 1e-9 * mass, "{mj_mass} vs {mass}");
    let mj_coll: usize = bodies.iter().map(|b| b.collision_geoms).sum();
    assert_eq!(mj_coll, pieces);

    let u = usd(&mut bridge, dir.path());
    let ub = &u.bodies;
    let usd_mass = sum(ub.values().map(|b| b.mass.unwrap()));
    assert!(
        (usd_mass - mass).abs() < 1e-6 * mass,
        "{usd_mass} vs {mass}"
    );
    let usd_coll: usize = ub
        .values()
        .map(|b| b.colliders)
        .chain(u.static_groups.values().map(|s| s.colliders))
        .sum();
    assert_eq!(usd_coll, pieces);
    assert_eq!(u.counts["MeshShape"], pieces);
    let top_level: std::collections::BTreeSet<&str> =
        ub.keys().map(|k| k.split('/').nth(2).unwrap()).collect();
    assert_eq!(top_level.len(), movable().count());

    let d = drake(&mut bridge, dir.path());
    let instances = &d.model_instances;
    assert_eq!(instances.len(), scene.objects.len());
    let drake_mass = sum(instances
        .iter()
        .filter(|i| !i.name.ends_with("_architecture"))
        .map(|i| i.mass));
    assert!((drake_mass - mass).abs() < 1e-9 * mass);
    assert_eq!(d.num_collision_geometries, pieces);

    // The GLB holds every visual triangle once per object.
    let view = SceneView::new(&state).unwrap();
    let tris: usize = view
        .objects
        .iter()
        .map(|o| {
            view.asset_of(o)
                .visuals
                .iter()
                .flatten()
                .map(|g| g.mesh.triangles.len())
                .sum::<usize>()
        })
        .sum();
    let glb = std::fs::read(dir.path().join("export/scene.glb")).unwrap();
    let parts = scenesmith::assets::gltf_read::parse(&glb, None).unwrap();
    assert_eq!(
        parts.iter().map(|p| p.mesh.triangles.len()).sum::<usize>(),
        tris
    );

    // Same state, same bytes.
    for f in ExportFormat::ALL {
        assert_eq!(
            render(&state, f).unwrap(),
            render(&state, f).unwrap(),
            "{f:?}"
        );
    }

    // A scene directory read back from disk exports the same facts.
    let back = load_state(dir.path()).unwrap();
    for f in ExportFormat::ALL {
        let a = render(&state, f).unwrap();
        let b = render(&back, f).unwrap();
        let names = |v: &[scenesmith::export::ExportFile]| -> Vec<String> {
            v.iter().map(|x| x.path.clone()).collect()
        };
        assert_eq!(names(&a), names(&b), "{f:?}");
    }
    let mjcf_back =
        String::from_utf8(render(&back, ExportFormat::Mjcf).unwrap()[0].bytes.clone()).unwrap();
    let mjcf = std::fs::read_to_string(dir.path().join("export/mujoco/scene.xml")).unwrap();
    let masses = |xml: &str| -> Vec<String> {
        xml.split("mass=\"")
            .skip(1)
            .map(|s| s[..s.find('"').unwrap()].to_string())
            .collect()
    };
    assert_eq!(masses(&mjcf_back), masses(&mjcf));
}
