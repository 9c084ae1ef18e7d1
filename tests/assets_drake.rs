//! Every category of the asset library in real Drake, through the bridge, batched so the whole
//! library costs three requests: every model loads (bodies, mass, joints and collision pieces
//! as written); every furniture piece and small object dropped alone on a floor for 2 s
//! (2 ms steps) stays upright; every
//! articulated model, welded in place with its self-collision turned on, opens each joint to
//! its limit under a constant force without exceeding it and without its links penetrating.

use std::path::Path;

use scenesmith::assets::Asset;
use scenesmith::assets::procedural::{self, AssetRequest, Kind, SupportClass};
use scenesmith::formats::sdf::asset_files;
use scenesmith::physics::Bridge;
use scenesmith::physics::protocol::{
    AssetModel, AssetsDrop, AssetsDropArgs, AssetsLoad, AssetsLoadArgs, AssetsPush, AssetsPushArgs,
};

fn write(dir: &Path, asset: &Asset) -> std::path::PathBuf {
    let d = dir.join(&asset.id);
    std::fs::create_dir_all(&d).unwrap();
    for f in asset_files(asset) {
        std::fs::write(d.join(&f.name), &f.bytes).unwrap();
    }
    d.join("model.sdf")
}

fn library() -> Vec<(String, Asset)> {
    procedural::categories()
        .into_iter()
        .map(|c| {
            let p = procedural::prior(c).unwrap();
            let mut r = AssetRequest::new(c, 0);
            r.size = Some(p.typical);
            (c.to_string(), procedural::build(&r).unwrap())
        })
        .collect()
}

fn model(name: &str, sdf: std::path::PathBuf, footprint: Option<f64>) -> AssetModel {
    AssetModel {
        name: name.to_string(),
        sdf,
        footprint,
        efforts: None,
    }
}

fn footprint(a: &Asset) -> f64 {
    let [lo, hi] = a.bounds();
    (hi[0] - lo[0]).max(hi[1] - lo[1])
}

#[test]
fn every_category_loads_stands_and_opens_in_drake() {
    let dir = tempfile::tempdir().unwrap();
    let assets = library();
    let mut bridge = Bridge::from_env().unwrap();
    let t0 = std::time::Instant::now();

    // 1. Everything loads, strictly (Drake warnings are errors), as written.
    let models: Vec<AssetModel> = assets
        .iter()
        .map(|(c, a)| model(c, write(dir.path(), a), None))
        .collect();
    let loaded = bridge
        .call::<AssetsLoad>(&AssetsLoadArgs { models })
        .unwrap();
    let mut failures = Vec::new();
    for (c, a) in &assets {
        let m = &loaded.models[c];
        if !m.ok {
            failures.push(format!("{c}: {:?}", m.error));
            continue;
        }
        if m.bodies != Some(a.links.len())
            || m.collision_geometries != Some(a.collision_pieces())
            || m.mass
                .is_none_or(|got| (got - a.mass()).abs() > 1e-6 * a.mass())
            || m.joints.as_ref().map(Vec::len) != Some(a.joints.len())
        {
            failures.push(format!("{c}: Drake sees {m:?}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    eprintln!("load: {:.1} s", t0.elapsed().as_secs_f64());

    // 2. Furniture and small objects dropped alone on a floor stay upright (rugs and mats are
    // thin coverings, welded in scenes, so they are not dropped).
    let floor: Vec<&(String, Asset)> = assets
        .iter()
        .filter(|(c, _)| {
            let p = procedural::prior(c).unwrap();
            matches!(p.support, SupportClass::Floor | SupportClass::Surface)
                && p.kind != Kind::ThinCovering
        })
        .collect();
    let models: Vec<AssetModel> = floor
        .iter()
        .map(|(c, a)| {
            model(
                c,
                dir.path().join(&a.id).join("model.sdf"),
                Some(footprint(a)),
            )
        })
        .collect();
    let dropped = bridge
        .call::<AssetsDrop>(&AssetsDropArgs {
            models,
            duration: 2.0,
            time_step: 2e-3,
        })
        .unwrap();
    // Furniture stays exactly upright; a small object may roll or rock a little on a rigid
    // floor under point contact (round fruit, a pen on its side) but never topples or wanders.
    let fallen: Vec<String> = floor
        .iter()
        .filter_map(|(c, _)| {
            let m = &dropped.models[c];
            let small = procedural::prior(c).unwrap().support == SupportClass::Surface;
            let upright = if small {
                m.tilt_rad < 0.5 && m.horizontal_m < 0.03
            } else {
                m.rotation_rad < 0.1
            };
            (!upright || m.vertical_m < -0.05).then(|| format!("{c}: {m:?}"))
        })
        .collect();
    eprintln!("drop: {:.1} s", t0.elapsed().as_secs_f64());
    assert!(
        fallen.is_empty(),
        "did not stay upright:\n{}",
        fallen.join("\n")
    );
    assert!(floor.len() >= 150);

    // 3. Articulated models open every joint to its limit, never past it, never into themselves.
    let articulated: Vec<&(String, Asset)> = assets
        .iter()
        .filter(|(_, a)| !a.joints.is_empty())
        .collect();
    assert!(articulated.len() >= 20);
    for (c, _) in &articulated {
        assert_eq!(
            procedural::prior(c).unwrap().kind,
            Kind::Articulated,
            "{c} has joints but is not marked articulated"
        );
    }
    let models: Vec<AssetModel> = articulated
        .iter()
        .map(|(c, a)| {
            model(
                c,
                dir.path().join(&a.id).join("model.sdf"),
                Some(footprint(a)),
            )
        })
        .collect();
    let pushed = bridge
        .call::<AssetsPush>(&AssetsPushArgs {
            models,
            duration: 1.0,
            time_step: 1e-3,
            force_scale: 2.0,
        })
        .unwrap();
    eprintln!("push: {:.1} s", t0.elapsed().as_secs_f64());
    let mut problems = Vec::new();
    for (c, a) in &articulated {
        let m = &pushed.models[c];
        assert_eq!(m.joints.len(), a.joints.len(), "{c}");
        for (name, j) in &m.joints {
            let (q, lo, hi) = (j.position, j.lower, j.upper);
            let tol = 0.02 * (hi - lo) + 0.005;
            if q > hi + tol || q < lo - tol {
                problems.push(format!("{c}/{name}: {q:.3} outside [{lo:.3}, {hi:.3}]"));
            } else if q < hi - 0.05 * (hi - lo) - 0.005 {
                problems.push(format!("{c}/{name}: stopped at {q:.3} of {hi:.3}"));
            }
        }
        let depth = m.self_penetration_m;
        if depth > 1e-3 {
            problems.push(format!(
                "{c}: links penetrate {depth:.4} m ({:?})",
                m.self_penetration_pair
            ));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
