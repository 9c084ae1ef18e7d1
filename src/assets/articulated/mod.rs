//! Articulated assets: the moving parts procedural generators use (drawers that are real open
//! boxes, hinged doors and flaps, lids; [`parts`]) and articulated models loaded from a user
//! folder of SDFormat/URDF files with a JSON index, searchable by text and size
//! ([`library`]).
//!
//! Joint frames coincide with child link frames (the convention of [`crate::assets::Joint`]),
//! so a door's link frame sits on its hinge line and a drawer's at its closed position.

pub mod library;
pub mod parts;
mod reader;

use std::collections::BTreeMap;

use super::{Asset, link_poses};

/// Pairs of links of `asset` whose collision pieces overlap deeper than `tolerance` metres
/// at `joint_positions` (missing joints at 0): `(link_a, link_b, depth)`. Every pair of links
/// is checked, including a joint's parent and child, which Drake would filter.
pub fn self_collisions(
    asset: &Asset,
    joint_positions: &BTreeMap<String, f64>,
    tolerance: f64,
) -> Vec<(String, String, f64)> {
    use crate::geometry::penetration::{PosedPiece, sat_penetration};
    let poses = link_poses(asset, joint_positions);
    // Pose every piece once, then test pairs (the bounds test inside prunes most of them).
    let posed: Vec<Vec<PosedPiece>> = asset
        .links
        .iter()
        .zip(&poses)
        .map(|(l, pose)| {
            l.collisions
                .iter()
                .map(|p| PosedPiece::new(p, pose))
                .collect()
        })
        .collect();
    let mut out = Vec::new();
    for i in 0..posed.len() {
        for j in i + 1..posed.len() {
            let mut deepest = 0.0_f64;
            for a in &posed[i] {
                for b in &posed[j] {
                    if let Some((d, _)) = sat_penetration(a, b) {
                        deepest = deepest.max(d);
                    }
                }
            }
            if deepest > tolerance {
                out.push((
                    asset.links[i].name.clone(),
                    asset.links[j].name.clone(),
                    deepest,
                ));
            }
        }
    }
    out
}

/// Joint configurations an articulated asset is checked at: all closed, each joint alone at
/// half and full travel, and everything fully open.
pub fn check_configurations(asset: &Asset) -> Vec<BTreeMap<String, f64>> {
    let mut out = vec![BTreeMap::new()];
    for j in &asset.joints {
        for f in [0.5, 1.0] {
            out.push(BTreeMap::from([(
                j.name.clone(),
                j.lower + f * (j.upper - j.lower),
            )]));
        }
    }
    if asset.joints.len() > 1 {
        out.push(
            asset
                .joints
                .iter()
                .map(|j| (j.name.clone(), j.upper))
                .collect(),
        );
    }
    out
}
