//! Which objects fell during settling, and the reason recorded for each.
//!
//! Rules (defaults in [`RemovalRules`]):
//! - furniture whose up axis tilted more than 45 degrees from vertical fell over;
//! - a small object that started on a surface and ended with its lowest point near the floor
//!   after dropping more than 0.3 m fell off its surface;
//! - anything whose lowest point ended below the floor top passed through the floor.
//!
//! This module only judges; removing is `SceneState::remove_object` (which also removes what
//! rested on the removed object).

use nalgebra::{Point3, Vector3};
use serde::Serialize;

use crate::assets::{Asset, link_poses};
use crate::scene::{Pose, SceneObject, Support};

/// Thresholds of the fallen-object rules.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RemovalRules {
    /// Furniture tilted more than this from upright is removed, radians.
    pub max_furniture_tilt_rad: f64,
    /// A small object that dropped more than this ...
    pub fall_drop_m: f64,
    /// ... and ended with its lowest point within this of the floor fell off its surface, m.
    pub near_floor_m: f64,
    /// Lowest point this far below the floor top: passed through the floor, m.
    pub below_floor_m: f64,
    /// Height of the floor top, m.
    pub floor_z: f64,
}

impl Default for RemovalRules {
    fn default() -> Self {
        RemovalRules {
            max_furniture_tilt_rad: 45f64.to_radians(),
            fall_drop_m: 0.3,
            near_floor_m: 0.15,
            below_floor_m: 0.02,
            floor_z: 0.0,
        }
    }
}

/// Lowest z of an object's collision geometry at `world_from_object`, metres.
pub fn lowest_z(asset: &Asset, obj: &SceneObject, world_from_object: &Pose) -> f64 {
    let mut lo = f64::INFINITY;
    for (link, model_from_link) in asset
        .links
        .iter()
        .zip(link_poses(asset, &obj.joint_positions))
    {
        let world_from_link = world_from_object.compose(&model_from_link);
        for piece in &link.collisions {
            for v in &piece.vertices {
                lo = lo.min(
                    world_from_link
                        .transform_point(&Point3::new(v[0], v[1], v[2]))
                        .z,
                );
            }
        }
    }
    lo
}

/// Angle between the object's up axis and the world's, radians.
pub fn tilt(world_from_object: &Pose) -> f64 {
    let up = world_from_object.transform_vector(&Vector3::z());
    up.z.clamp(-1.0, 1.0).acos()
}

/// Why a piece of furniture must go after settling, if it must.
pub fn furniture_verdict(
    asset: &Asset,
    obj: &SceneObject,
    after: &Pose,
    rules: &RemovalRules,
) -> Option<String> {
    let t = tilt(after);
    if t > rules.max_furniture_tilt_rad {
        return Some(format!(
            "fell over while settling: tilted {:.0} degrees (limit {:.0})",
            t.to_degrees(),
            rules.max_furniture_tilt_rad.to_degrees()
        ));
    }
    let low = lowest_z(asset, obj, after);
    if low < rules.floor_z - rules.below_floor_m {
        return Some(format!(
            "passed through the floor while settling (lowest point {:.3} m)",
            low
        ));
    }
    None
}

/// Why a small object must go after settling from `before` to `after`, if it must.
pub fn manipuland_verdict(
    asset: &Asset,
    obj: &SceneObject,
    before: &Pose,
    after: &Pose,
    rules: &RemovalRules,
) -> Option<String> {
    let low = lowest_z(asset, obj, after);
    if low < rules.floor_z - rules.below_floor_m {
        return Some(format!(
            "passed through the floor while settling (lowest point {:.3} m)",
            low
        ));
    }
    let drop = before.translation().z - after.translation().z;
    if let Support::Object { parent, surface } = &obj.support
        && drop > rules.fall_drop_m
        && low <= rules.floor_z + rules.near_floor_m
    {
        return Some(format!(
            "fell off {parent} ({surface}) to the floor while settling: dropped {drop:.2} m"
        ));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tilt_of_upright_and_toppled() {
        assert!(tilt(&Pose::from_xyz_yaw(1.0, 2.0, 0.0, 2.0)).abs() < 1e-12);
        let toppled = Pose::from_xyz_rpy([0.0; 3], [std::f64::consts::FRAC_PI_2, 0.0, 0.3]);
        assert!((tilt(&toppled) - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
        let leaning = Pose::from_xyz_rpy([0.0; 3], [0.0, 0.5, 0.0]);
        assert!((tilt(&leaning) - 0.5).abs() < 1e-9);
    }
}
