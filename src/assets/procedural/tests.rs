//! Tests over every category: valid assets within their priors, canonical frames, collision
//! budgets, articulated parts that never touch their bodies.

use super::*;
use crate::assets::articulated::{check_configurations, self_collisions};
use crate::assets::physical::hull_cap;
use crate::geometry::convex::{MAX_BASE_VERTICES, MAX_FACE_VERTICES, MAX_PIECE_VERTICES};

fn extents(asset: &Asset) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let [lo, hi] = asset.bounds();
    (lo, hi, [0, 1, 2].map(|i| hi[i] - lo[i]))
}

/// Frame conventions per support class, and the size the generator was asked for.
fn check_frame(cat: &str, asset: &Asset, want: [f64; 3]) -> Result<(), String> {
    let p = prior(cat).ok_or("no prior")?;
    let (lo, hi, ext) = extents(asset);
    for i in 0..3 {
        if (ext[i] - want[i]).abs() > 0.1 * want[i] + 0.004 {
            return Err(format!(
                "axis {i} extent {:.4} vs requested {:.4}",
                ext[i], want[i]
            ));
        }
    }
    if (lo[0] + hi[0]).abs() > 0.02 + 0.05 * want[0] {
        return Err(format!("not centred in x ({:.3}, {:.3})", lo[0], hi[0]));
    }
    let bad = |what: &str, v: f64| Err(format!("{what} at {v:.4}"));
    match p.support {
        SupportClass::Floor | SupportClass::Surface => {
            if lo[2].abs() > 2e-3 {
                return bad("bottom", lo[2]);
            }
            if (lo[1] + hi[1]).abs() > 0.02 + 0.05 * want[1] {
                return Err(format!("not centred in y ({:.3}, {:.3})", lo[1], hi[1]));
            }
        }
        SupportClass::Wall => {
            if lo[1].abs() > 2e-3 {
                return bad("back", lo[1]);
            }
            if lo[2].abs() > 2e-3 {
                return bad("bottom", lo[2]);
            }
        }
        SupportClass::Ceiling => {
            if hi[2].abs() > 2e-3 {
                return bad("top", hi[2]);
            }
        }
    }
    Ok(())
}

#[test]
fn there_are_enough_categories_in_every_class() {
    let cats = categories();
    assert!(cats.len() >= 120, "{} categories", cats.len());
    let count = |s: SupportClass| {
        cats.iter()
            .filter(|c| prior(c).unwrap().support == s)
            .count()
    };
    assert!(count(SupportClass::Floor) >= 50);
    assert!(count(SupportClass::Wall) >= 13);
    assert!(count(SupportClass::Ceiling) >= 5);
    assert!(count(SupportClass::Surface) >= 50);
    for c in &cats {
        let p = prior(c).unwrap();
        for i in 0..3 {
            assert!(
                p.min[i] > 0.0 && p.min[i] <= p.typical[i] && p.typical[i] <= p.max[i],
                "{c}: prior axis {i}"
            );
        }
        assert!(
            material::material(&p.material).is_some(),
            "{c}: material {}",
            p.material
        );
        if let Some(a) = &p.accent {
            assert!(material::material(a).is_some(), "{c}: accent {a}");
        }
        assert!(
            generator(&p.generator).is_some(),
            "{c}: generator {}",
            p.generator
        );
    }
}

fn check_category(cat: &str) -> Result<(), String> {
    let p = prior(cat).ok_or("no prior")?;
    for (k, size) in [p.typical, p.min, p.max].into_iter().enumerate() {
        let mut r = AssetRequest::new(cat, 11 + k as u64);
        r.size = Some(size);
        let asset = build(&r).map_err(|e| format!("at {size:?}: {e}"))?;
        asset.validate().map_err(|e| e.to_string())?;
        check_frame(cat, &asset, size).map_err(|e| format!("size #{k}: {e}"))?;
        let n = asset.collision_pieces();
        if n == 0 || n > hull_cap(p.support) {
            return Err(format!("{n} collision pieces"));
        }
        for link in &asset.links {
            link.mass
                .validate()
                .map_err(|e| format!("{}: {e}", link.name))?;
            if link.collisions.iter().any(|c| c.volume() <= 0.0) {
                return Err("empty piece".into());
            }
            // Simplified for contact: few vertices, few on a flat base or top (a rounded piece
            // is left as it is).
            for c in &link.collisions {
                let (lo, hi) = c.bounds();
                let on = |z: f64| {
                    c.vertices
                        .iter()
                        .filter(|v| (v[2] - z).abs() <= 1e-4)
                        .count()
                };
                let (base, top) = (on(lo[2]), on(hi[2]));
                let flat = base >= 3 && top >= 3;
                if flat
                    && (c.vertices.len() > MAX_PIECE_VERTICES
                        || base > MAX_BASE_VERTICES + 4
                        || top > MAX_FACE_VERTICES + 4)
                {
                    return Err(format!(
                        "{}: a piece of {} vertices, {base} on its base, {top} on its top",
                        link.name,
                        c.vertices.len()
                    ));
                }
            }
        }
        let range = &asset.provenance["physics"]["mass_range_kg"];
        let (lo, hi) = (
            range[0].as_f64().unwrap_or(0.0),
            range[1].as_f64().unwrap_or(0.0),
        );
        if !(lo < asset.mass() && asset.mass() < hi) {
            return Err("mass outside its range".into());
        }
    }
    Ok(())
}

#[test]
fn every_category_builds_a_valid_asset_at_typical_min_and_max_size() {
    let failures: Vec<String> = categories()
        .into_iter()
        .filter_map(|c| check_category(c).err().map(|e| format!("{c}: {e}")))
        .collect();
    assert!(
        failures.is_empty(),
        "{} failing categories:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn masses_are_plausible() {
    // Loose real-world bounds, kg: catches a solid-steel fridge or a weightless sofa.
    let mut failures = Vec::new();
    for (cat, lo, hi) in [
        ("refrigerator", 30.0, 200.0),
        ("sofa", 20.0, 150.0),
        ("bed", 20.0, 200.0),
        ("mug", 0.15, 0.8),
        ("apple", 0.08, 0.4),
        ("laptop", 0.8, 4.0),
        ("wine_bottle", 0.2, 1.5),
        ("book", 0.2, 1.5),
        ("chair", 2.0, 15.0),
        ("wardrobe", 30.0, 250.0),
        ("plate", 0.2, 1.5),
        ("potted_plant", 5.0, 60.0),
    ] {
        let m = build(&AssetRequest::new(cat, 1)).unwrap().mass();
        if !(m > lo && m < hi) {
            failures.push(format!("{cat}: {m:.2} kg not in [{lo}, {hi}]"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn articulated_parts_never_touch_their_bodies() {
    let mut articulated = 0;
    let mut failures = Vec::new();
    for cat in categories() {
        let p = prior(cat).unwrap();
        let asset = build(&AssetRequest::new(cat, 3)).unwrap();
        if p.kind == Kind::Articulated {
            assert!(
                !asset.joints.is_empty(),
                "{cat} is articulated but has no joints"
            );
        }
        if asset.joints.is_empty() {
            continue;
        }
        articulated += 1;
        assert_eq!(asset.provenance["strategy"], "articulated", "{cat}");
        for j in &asset.joints {
            assert!(
                j.lower < j.upper && j.damping > 0.0 && j.effort > 0.0,
                "{cat}: {}",
                j.name
            );
        }
        for q in check_configurations(&asset) {
            let hits = self_collisions(&asset, &q, 5e-4);
            if !hits.is_empty() {
                failures.push(format!("{cat} at {q:?}: {hits:?}"));
                break;
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(articulated >= 20, "{articulated} articulated categories");
}

#[test]
fn drawers_are_open_boxes_with_a_surface_inside() {
    let asset = build(&AssetRequest::new("dresser", 4)).unwrap();
    let drawers: Vec<_> = asset
        .links
        .iter()
        .filter(|l| l.name.starts_with("drawer_"))
        .collect();
    assert!(drawers.len() >= 3);
    for d in drawers {
        // Front, bottom, two sides, back: five boxes (plus the handle).
        assert!(d.collisions.len() >= 5, "{}", d.name);
        let s = asset
            .surfaces
            .iter()
            .find(|s| s.id == d.name)
            .expect("drawer surface");
        assert!(
            s.clearance > 0.05 && s.size[0] > 0.2 && s.size[1] > 0.2,
            "{s:?}"
        );
    }
    let j = asset
        .joints
        .iter()
        .find(|j| j.kind == crate::assets::JointKind::Prismatic)
        .unwrap();
    // Out of the front, climbing a little so a closed drawer stays shut.
    assert!(
        j.axis[1] > 0.99 && j.axis[2] > 0.0 && j.axis[0] == 0.0,
        "{:?}",
        j.axis
    );
    assert!(j.upper > 0.2);
}

#[test]
fn vessels_have_cavities() {
    for cat in [
        "mug",
        "bowl",
        "cup",
        "glass",
        "pot",
        "basket",
        "storage_bin",
        "trash_can",
        "vase",
        "bathtub",
        "serving_bowl",
    ] {
        let a = build(&AssetRequest::new(cat, 3)).unwrap();
        let inside = a
            .surfaces
            .iter()
            .find(|s| s.id == "inside" || s.id == "basin");
        let s = inside.unwrap_or_else(|| panic!("{cat}: no inside surface"));
        assert!(
            prior(cat).unwrap().container,
            "{cat} is not marked container"
        );
        // A point just above the inside floor is outside every collision piece.
        let p = nalgebra::Point3::new(s.center[0], s.center[1], s.center[2] + 0.3 * s.clearance);
        for piece in &a.links[0].collisions {
            let shape = piece.to_parry().unwrap();
            use parry3d_f64::query::PointQuery;
            let inside_piece = shape.contains_point(
                &parry3d_f64::math::Pose::identity(),
                parry3d_f64::math::Vector::new(p.x, p.y, p.z),
            );
            assert!(!inside_piece, "{cat}: cavity is filled");
        }
    }
}

#[test]
fn shelves_keep_clearance_between_levels() {
    for cat in [
        "bookshelf",
        "shelf",
        "shelving_unit",
        "display_case",
        "cabinet",
        "refrigerator",
    ] {
        let a = build(&AssetRequest::new(cat, 2)).unwrap();
        let shelves: Vec<_> = a
            .surfaces
            .iter()
            .filter(|s| s.id.starts_with("shelf_"))
            .collect();
        assert!(shelves.len() >= 2, "{cat}");
        for s in shelves {
            assert!(
                s.clearance > 0.15,
                "{cat}/{}: clearance {}",
                s.id,
                s.clearance
            );
        }
    }
}

#[test]
fn same_request_same_asset() {
    let r = AssetRequest::new("chair", 5);
    let a = build(&r).unwrap();
    let b = build(&r).unwrap();
    assert_eq!(a, b);
    let c = build(&AssetRequest::new("chair", 6)).unwrap();
    assert_ne!(a.id, c.id);
}

#[test]
fn aliases_and_unknown_nouns() {
    assert_eq!(resolve_category("Bookshelf"), Some("bookshelf"));
    assert_eq!(resolve_category("coffee mug"), Some("mug"));
    assert_eq!(resolve_category("L-shaped sofa"), Some("l_shaped_sofa"));
    assert_eq!(resolve_category("fridge"), Some("refrigerator"));
    assert!(candidate_categories("clock").contains(&"wall_clock"));
    assert!(candidate_categories("clock").contains(&"table_clock"));
    assert!(matches!(
        build(&AssetRequest::new("spaceship", 1)),
        Err(AssetError::UnknownCategory(_))
    ));
}

#[test]
fn requested_size_is_clamped_to_prior() {
    let mut r = AssetRequest::new("table", 1);
    r.size = Some([50.0, 0.9, 0.75]);
    let a = build(&r).unwrap();
    let [lo, hi] = a.bounds();
    assert!(hi[0] - lo[0] <= 3.2 + 1e-9);
}

#[test]
fn cabinet_door_is_articulated() {
    let a = build(&AssetRequest::new("cabinet", 2)).unwrap();
    assert_eq!(a.links.len(), 2);
    assert_eq!(a.joints.len(), 1);
    let j = &a.joints[0];
    assert_eq!(j.name, "door_hinge");
    assert!(j.lower == 0.0 && (j.upper - 100f64.to_radians()).abs() < 1e-12);
}

#[test]
fn styles_change_materials_and_look() {
    let plain = build(&AssetRequest::new("desk", 1)).unwrap();
    let steam = build_styled(
        &AssetRequest::new("desk", 1),
        crate::assets::attributes::style("steampunk").as_ref(),
    )
    .unwrap();
    assert_ne!(plain.id, steam.id);
    assert_eq!(steam.material, "walnut");
    assert_eq!(steam.provenance["parameters"]["style"], "steampunk");
}

#[test]
fn generic_shapes_are_marked() {
    for s in [
        SupportClass::Floor,
        SupportClass::Surface,
        SupportClass::Wall,
        SupportClass::Ceiling,
    ] {
        let a = build_generic("flux capacitor", s, None, 1, None, None).unwrap();
        assert_eq!(a.provenance["generic"], true);
        assert_eq!(a.category, "flux_capacitor");
        a.validate().unwrap();
    }
}

#[test]
fn what_stands_on_one_piece_gets_contact_pads_and_legs_do_not() {
    let feet = |cat: &str| {
        let asset = build(&AssetRequest::new(cat, 3)).expect("builds");
        super::feet(&asset.links[0]).len()
    };
    // A plinth: the piece and its four pads.
    assert!(feet("bar_counter") >= 4, "{}", feet("bar_counter"));
    // Small objects get none (each pad is a compliant piece Drake's contact carries).
    assert_eq!(feet("printer"), 1);
    // Four legs stay four.
    assert_eq!(feet("dining_table"), 4);
}
