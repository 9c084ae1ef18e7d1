//! The bridge pool: jobs run on several workers and come back in job order; a start-up
//! failure is a clear error.

mod physics_util;

use physics_util::*;
use scenesmith::formats::scene_dir::write_scene_dir;
use scenesmith::physics::protocol::{Load, NoArgs, Ping, SceneFiles};
use scenesmith::physics::{BridgeConfig, BridgeError, BridgePool};
use scenesmith::scene::{ObjectKind, Pose};

#[test]
fn run_all_keeps_job_order_and_uses_every_worker() {
    let root = tempfile::tempdir().unwrap();
    let mut jobs = Vec::new();
    for i in 0..4 {
        let mut state = room(2.0 + i as f64 * 0.1, 2.0);
        let cube = block("cube", Shape::Box([0.1, 0.1, 0.1]), "wood");
        for k in 0..=i {
            place(
                &mut state,
                &cube,
                ObjectKind::Manipuland,
                Pose::from_xyz(0.5 + 0.2 * k as f64, 1.0, 0.0),
                floor(),
            );
        }
        let dir = root.path().join(format!("s{i}"));
        write_scene_dir(&dir, &state).unwrap();
        jobs.push(SceneFiles::new(
            dir.join("scene.dmd.yaml"),
            dir.join("package.xml"),
        ));
    }
    let pool = pool(2);
    let results = pool.call_all::<Load>(&jobs);
    assert_eq!(results.len(), 4);
    for (i, r) in results.into_iter().enumerate() {
        let r = r.unwrap();
        assert_eq!(std::path::Path::new(&r.directives), jobs[i].directives);
        // The architecture plus i + 1 cubes.
        assert_eq!(r.num_model_instances, i + 2);
    }
    let pids: Vec<u32> = pool.pids().into_iter().flatten().collect();
    assert_eq!(pids.len(), 2, "both workers started");
    assert_ne!(pids[0], pids[1]);
    // The same directives again go to the worker that has the plant: a cache hit.
    let again = pool.call::<Load>(&jobs[3]).unwrap();
    assert!(again.cache.hits >= 1, "{:?}", again.cache);
}

#[test]
fn a_pool_without_python_fails_clearly() {
    let mut config = BridgeConfig::from_env();
    config.python = "/nonexistent/python".into();
    let pool = BridgePool::new(config, 2);
    let err = pool.call::<Ping>(&NoArgs {}).unwrap_err();
    assert!(matches!(err, BridgeError::PythonMissing { .. }), "{err}");
    assert!(err.to_string().contains("scripts/setup.sh"));
    let all = pool.call_all::<Ping>(&[NoArgs {}, NoArgs {}, NoArgs {}]);
    assert!(
        all.iter()
            .all(|r| matches!(r, Err(BridgeError::PythonMissing { .. })))
    );
}
