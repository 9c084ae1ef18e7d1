//! Articulated objects in every format: hinge and slide joints, limits and their signs are the
//! same in Drake, MJCF (radians) and USD (degrees / metres); the joint axes point the same way
//! in the world; initial joint positions are honoured; the cabinet door opens in MuJoCo under
//! an applied torque and stops at its limits; collision and visual geometry of moving parts sit
//! where the scene puts them; the conformance gate passes.

mod export_common;

use std::collections::BTreeMap;

use export_common::{articulated_state, drake, mujoco, usd, write_all};
use scenesmith::assets::JointKind;
use scenesmith::export::conformance::{GateOptions, run_gate, table};
use scenesmith::export::view::SceneView;
use scenesmith::physics::Bridge;

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[test]
fn joints_limits_and_signs_agree_across_formats() {
    let state = articulated_state();
    let dir = tempfile::tempdir().unwrap();
    write_all(dir.path(), &state);
    let mut bridge = Bridge::from_env().unwrap();

    // The gate runs every check (Drake, MuJoCo, USD, GLB) and passes.
    let report = run_gate(
        &mut bridge,
        dir.path(),
        &state,
        &GateOptions {
            seconds: 1.0,
            ..GateOptions::default()
        },
    )
    .unwrap();
    assert!(report.passed, "{}", table(&report));

    let d = drake(&mut bridge, dir.path());
    let m = mujoco(&mut bridge, dir.path(), 0.0, &[]);
    let u = usd(&mut bridge, dir.path());
    let drake_joints: BTreeMap<(String, String), _> = d
        .model_instances
        .iter()
        .flat_map(|inst| {
            inst.joints
                .iter()
                .map(move |j| ((inst.name.clone(), j.name.clone()), j))
        })
        .collect();
    let mj_joints: BTreeMap<&str, _> = m.joints.iter().map(|j| (j.name.as_str(), j)).collect();
    let usd_joints: BTreeMap<&str, _> = u.joints.iter().map(|j| (j.path.as_str(), j)).collect();

    let view = SceneView::new(&state).unwrap();
    let mut checked = std::collections::BTreeSet::new();
    let mut kinds = std::collections::BTreeSet::new();
    for o in view.objects.iter() {
        let av = view.asset_of(o);
        for (ji, j) in av.asset.joints.iter().enumerate() {
            let child = av
                .asset
                .links
                .iter()
                .position(|l| l.name == j.child)
                .unwrap();
            let axis_world = {
                let a = o.world_from_links[child]
                    .transform_vector(&nalgebra::Vector3::from(j.axis))
                    .normalize();
                [a.x, a.y, a.z]
            };
            let q = o
                .object
                .joint_positions
                .get(&j.name)
                .copied()
                .unwrap_or(0.0);
            kinds.insert((j.kind.as_str(), j.axis.iter().sum::<f64>() < 0.0));

            // Drake: SI limits as written.
            let dj = drake_joints[&(o.object.id.clone(), j.name.clone())];
            assert_eq!(dj.kind, j.kind.as_str());
            assert_eq!(dj.lower[0], j.lower);
            assert_eq!(dj.upper[0], j.upper);

            // MJCF: radians / metres, same sign, same world axis, ref at the initial position.
            let name = format!("{}/{}", o.name, av.joint_names[ji]);
            let mj = mj_joints[name.as_str()];
            let want = if j.kind == JointKind::Revolute {
                "hinge"
            } else {
                "slide"
            };
            assert_eq!(mj.kind, want, "{name}");
            assert_eq!(mj.range[0], j.lower, "{name}");
            assert_eq!(mj.range[1], j.upper, "{name}");
            assert!(dot(mj.axis_world, axis_world) > 1.0 - 1e-9, "{name}");
            assert!((mj.qpos0 - q).abs() < 1e-12, "{name}");

            // USD: degrees for revolute, metres for prismatic, same sign and world axis, bodies
            // posed at the initial position.
            let path = format!("/World/{}/Joints/{}", o.name, av.joint_names[ji]);
            let uj = usd_joints[path.as_str()];
            let (lo, hi, q_usd) = match j.kind {
                JointKind::Revolute => (j.lower.to_degrees(), j.upper.to_degrees(), q.to_degrees()),
                JointKind::Prismatic => (j.lower, j.upper, q),
            };
            assert_eq!(uj.kind, j.kind.as_str(), "{path}");
            assert!((uj.lower.unwrap() - lo).abs() < 1e-4, "{path}: {uj:?}");
            assert!((uj.upper.unwrap() - hi).abs() < 1e-4, "{path}: {uj:?}");
            assert!(
                dot(uj.axis_world.unwrap(), axis_world) > 1.0 - 1e-6,
                "{path}"
            );
            assert!(
                (uj.position_measured.unwrap() - q_usd).abs() < 1e-3,
                "{path}: {uj:?}"
            );
            assert!(uj.body0_ok && uj.body1_ok);
            checked.insert(format!("{}/{}", o.object.id, j.name));
        }
    }
    // Every joint of the scene was compared; among them the hand-placed ones: the welded
    // cabinet's door (opened 0.6 rad) and the drawer box's slide and hinge.
    for want in [
        "cabinet_welded/door_hinge",
        "drawer_box_0/drawer_slide",
        "drawer_box_0/door_hinge",
    ] {
        assert!(checked.contains(want), "{want} not among {checked:?}");
    }
    assert!(checked.len() >= 4, "{checked:?}");
    // Both signs of revolute axis (+Z and -Z) and a prismatic axis along -Y were covered.
    for want in [("revolute", false), ("revolute", true), ("prismatic", true)] {
        assert!(kinds.contains(&want), "{want:?} not among {kinds:?}");
    }

    // Welded articulated objects are fixed to the world; free ones are articulation roots.
    let roots: Vec<&str> = u.articulations.iter().map(|a| a.path.as_str()).collect();
    assert!(roots.contains(&"/World/cabinet_welded"), "{roots:?}");
    assert!(roots.contains(&"/World/drawer_box_0"), "{roots:?}");
    assert!(
        roots
            .iter()
            .any(|r| r.ends_with("/body") && r.contains("cabinet_"))
    );
    assert!(usd_joints.contains_key("/World/cabinet_welded/world_weld"));
}

#[test]
fn cabinet_door_opens_under_torque_and_stops_at_its_limits() {
    let state = articulated_state();
    let dir = tempfile::tempdir().unwrap();
    write_all(dir.path(), &state);
    let mut bridge = Bridge::from_env().unwrap();
    let cabinet = state
        .scene
        .objects
        .iter()
        .find(|o| o.category == "cabinet" && !o.welded)
        .unwrap();
    let hinge = format!("{}/door_hinge", cabinet.id);
    let upper = 100f64.to_radians();

    let opened = mujoco(&mut bridge, dir.path(), 1.5, &[(&hinge, 3.0)]);
    let q = opened.probe[&hinge];
    assert!(
        q > 0.5 && q < upper + 0.05,
        "door at {q} rad after pushing it open"
    );
    assert!(opened.finite);

    let pushed = mujoco(&mut bridge, dir.path(), 1.0, &[(&hinge, -3.0)]);
    let q = pushed.probe[&hinge];
    assert!(
        q > -0.05 && q < 0.01,
        "door at {q} rad after pushing it shut"
    );

    // The drawer slides out along its -Y axis (negative positions) and stops at -0.25 m; the
    // right door turns about -Z.
    let probe = [
        ("drawer_box_0/drawer_slide", 30.0),
        ("drawer_box_0/door_hinge", 2.0),
    ];
    let r = mujoco(&mut bridge, dir.path(), 1.5, &probe);
    let slide = r.probe["drawer_box_0/drawer_slide"];
    let door = r.probe["drawer_box_0/door_hinge"];
    assert!(
        slide > -0.01 && slide < 0.01,
        "pushing +30 N closes the drawer: {slide}"
    );
    assert!(door > 1.0 && door < 1.55, "right door at {door}");
    let r = mujoco(
        &mut bridge,
        dir.path(),
        1.5,
        &[("drawer_box_0/drawer_slide", -30.0)],
    );
    let slide = r.probe["drawer_box_0/drawer_slide"];
    assert!(
        slide < -0.2 && slide > -0.27,
        "drawer pulled out to {slide}"
    );
}
