//! A written scene directory loads back as the scene that was written (moved out of
//! `formats::scene_dir`'s unit tests: building the scene takes the whole pipeline, which sits
//! above `formats`).

use scenesmith::agents::Backend;
use scenesmith::formats::scene_dir::{load_state, write_scene_dir};
use scenesmith::pipeline::build_scene;

#[test]
fn written_scene_loads_back_with_the_same_assets() {
    let (state, _) = build_scene(
        "a kitchen with a table, four chairs, a cabinet, a shelf with books, plates and mugs",
        3,
        "load_back",
        &Backend::Builtin,
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    write_scene_dir(dir.path(), &state).unwrap();
    let back = load_state(dir.path()).unwrap();
    assert_eq!(back.scene, state.scene);
    assert_eq!(back.assets.len(), state.assets.len());
    for (id, a) in &state.assets {
        let b = &back.assets[id];
        assert_eq!(a.links.len(), b.links.len(), "{id}");
        assert_eq!(a.joints, b.joints, "{id}");
        assert_eq!(a.is_static, b.is_static, "{id}");
        for (la, lb) in a.links.iter().zip(&b.links) {
            assert_eq!(la.name, lb.name);
            assert_eq!(la.collisions.len(), lb.collisions.len(), "{id}/{}", la.name);
            assert_eq!(la.contact, lb.contact);
            if !a.is_static {
                assert!((la.mass.mass - lb.mass.mass).abs() <= 1e-12 * la.mass.mass);
            }
            for (pa, pb) in la.collisions.iter().zip(&lb.collisions) {
                // OBJ stores micrometres: thin pieces lose a little volume.
                assert!((pa.volume() - pb.volume()).abs() < 1e-3 * pa.volume());
            }
            let ta: usize = la.visuals.iter().map(|v| v.mesh.triangles.len()).sum();
            let tb: usize = lb.visuals.iter().map(|v| v.mesh.triangles.len()).sum();
            assert_eq!(ta, tb, "{id}/{}", la.name);
            let pa = la.model_from_link.translation();
            let pb = lb.model_from_link.translation();
            assert!((pa - pb).norm() < 1e-12);
        }
    }
}

#[test]
fn a_corrupt_asset_names_the_asset() {
    let (state, _) =
        build_scene("an office with a table", 1, "corrupt", &Backend::Builtin).unwrap();
    let dir = tempfile::tempdir().unwrap();
    write_scene_dir(dir.path(), &state).unwrap();
    let table = state
        .assets
        .values()
        .find(|a| a.category == "table")
        .unwrap();
    std::fs::write(
        dir.path().join(table.scene_dir()).join("collision_000.obj"),
        "v 0 0 0\nf 1 1\n",
    )
    .unwrap();
    let err = load_state(dir.path()).unwrap_err().to_string();
    assert!(err.contains(&table.id), "{err}");
}
