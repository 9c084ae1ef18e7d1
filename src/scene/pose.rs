//! Rigid transforms with named frames.
//!
//! A [`Pose`] is always read as `a_from_b`: it maps coordinates expressed in frame `b` into frame
//! `a` (Drake's `X_AB`). Field and variable names say which frames they relate
//! (`world_from_object`, `object_from_link`), never a bare `pose`.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// A rigid transform `a_from_b`, metres and radians.
///
/// Serialised as `{"xyz": [x, y, z], "wxyz": [w, x, y, z]}` (Drake's quaternion order), which
/// round-trips exactly through JSON.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose(pub Isometry3<f64>);

impl Default for Pose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Pose {
    /// The identity transform.
    pub const IDENTITY: Pose = Pose(Isometry3 {
        rotation: UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(1.0, 0.0, 0.0, 0.0)),
        translation: Translation3 {
            vector: Vector3::new(0.0, 0.0, 0.0),
        },
    });

    /// A pure translation.
    pub fn from_xyz(x: f64, y: f64, z: f64) -> Self {
        Pose(Isometry3::translation(x, y, z))
    }

    /// Translation plus a rotation about +Z by `yaw` radians (the common case indoors).
    pub fn from_xyz_yaw(x: f64, y: f64, z: f64, yaw: f64) -> Self {
        Pose(Isometry3::from_parts(
            Translation3::new(x, y, z),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
        ))
    }

    /// Translation plus roll-pitch-yaw (extrinsic X-Y-Z, Drake's `RollPitchYaw`), radians.
    pub fn from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> Self {
        Pose(Isometry3::from_parts(
            Translation3::new(xyz[0], xyz[1], xyz[2]),
            UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
        ))
    }

    /// The translation part.
    pub fn translation(&self) -> Vector3<f64> {
        self.0.translation.vector
    }

    /// Same pose with a new translation.
    pub fn with_translation(mut self, p: Vector3<f64>) -> Self {
        self.0.translation.vector = p;
        self
    }

    /// The rotation part.
    pub fn rotation(&self) -> UnitQuaternion<f64> {
        self.0.rotation
    }

    /// Roll-pitch-yaw in radians (extrinsic X-Y-Z, as Drake's `RollPitchYaw`).
    pub fn rpy(&self) -> [f64; 3] {
        let (r, p, y) = self.0.rotation.euler_angles();
        [r, p, y]
    }

    /// Rotation about +Z in radians, assuming the pose is (close to) upright.
    pub fn yaw(&self) -> f64 {
        self.rpy()[2]
    }

    /// `self * other`: if `self` is `a_from_b` and `other` is `b_from_c`, the result is `a_from_c`.
    pub fn compose(&self, other: &Pose) -> Pose {
        Pose(self.0 * other.0)
    }

    /// The inverse transform (`b_from_a`).
    pub fn inverse(&self) -> Pose {
        Pose(self.0.inverse())
    }

    /// Maps a point expressed in `b` to `a`.
    pub fn transform_point(&self, p: &Point3<f64>) -> Point3<f64> {
        self.0.transform_point(p)
    }

    /// Maps a free vector expressed in `b` to `a`.
    pub fn transform_vector(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.0.transform_vector(v)
    }

    /// Angle of the rotation from `self` to `other`, radians.
    pub fn angle_to(&self, other: &Pose) -> f64 {
        self.0.rotation.angle_to(&other.0.rotation)
    }

    /// True when every component is finite.
    pub fn is_finite(&self) -> bool {
        let t = self.0.translation.vector;
        let q = self.0.rotation.coords;
        t.iter().chain(q.iter()).all(|v| v.is_finite())
    }
}

/// A pose on the wire: translation in metres, unit quaternion in Drake's order.
#[derive(Serialize, Deserialize, schemars::JsonSchema)]
#[schemars(rename = "Pose")]
struct PoseRepr {
    /// Translation, metres.
    xyz: [f64; 3],
    /// Unit quaternion `[w, x, y, z]`.
    wxyz: [f64; 4],
}

impl schemars::JsonSchema for Pose {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Pose".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        PoseRepr::json_schema(generator)
    }
}

impl Serialize for Pose {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let t = self.0.translation.vector;
        let q = self.0.rotation.quaternion();
        PoseRepr {
            xyz: [t.x, t.y, t.z],
            wxyz: [q.w, q.i, q.j, q.k],
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Pose {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let r = PoseRepr::deserialize(d)?;
        let q = nalgebra::Quaternion::new(r.wxyz[0], r.wxyz[1], r.wxyz[2], r.wxyz[3]);
        let norm = q.norm();
        if !norm.is_finite() || (norm - 1.0).abs() > 1e-6 {
            return Err(serde::de::Error::custom(format!(
                "pose quaternion {:?} is not unit length (norm {norm})",
                r.wxyz
            )));
        }
        if r.xyz.iter().any(|v| !v.is_finite()) {
            return Err(serde::de::Error::custom("pose translation is not finite"));
        }
        // Keep our own (already unit) quaternions bit-exact; renormalise anything else.
        let rotation = if (norm - 1.0).abs() < 1e-12 {
            UnitQuaternion::new_unchecked(q)
        } else {
            UnitQuaternion::from_quaternion(q)
        };
        Ok(Pose(Isometry3::from_parts(
            Translation3::new(r.xyz[0], r.xyz[1], r.xyz[2]),
            rotation,
        )))
    }
}

/// Degrees from radians, for the boundaries that want degrees (Drake's `!Rpy {deg: ...}`, USD).
pub fn to_deg(rad: f64) -> f64 {
    rad.to_degrees()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_round_trip_is_exact() {
        let world_from_object = Pose::from_xyz_rpy([1.25, -0.5, 0.75], [0.1, -0.2, 2.9]);
        let text = serde_json::to_string(&world_from_object).unwrap();
        let back: Pose = serde_json::from_str(&text).unwrap();
        assert_eq!(back, world_from_object);
    }

    #[test]
    fn rpy_matches_constructor() {
        let rpy = [0.3, -0.4, 1.2];
        let p = Pose::from_xyz_rpy([0.0; 3], rpy);
        let got = p.rpy();
        for i in 0..3 {
            assert!((got[i] - rpy[i]).abs() < 1e-12, "{got:?} vs {rpy:?}");
        }
    }

    #[test]
    fn compose_then_inverse_is_identity() {
        let a = Pose::from_xyz_yaw(1.0, 2.0, 0.0, 0.7);
        let b = Pose::from_xyz_rpy([0.1, 0.2, 0.3], [0.2, 0.1, -0.4]);
        let c = a.compose(&b).compose(&b.inverse()).compose(&a.inverse());
        assert!(c.translation().norm() < 1e-12);
        assert!(c.rotation().angle() < 1e-12);
    }

    #[test]
    fn rejects_non_unit_quaternion() {
        let bad = r#"{"xyz":[0,0,0],"wxyz":[2,0,0,0]}"#;
        assert!(serde_json::from_str::<Pose>(bad).is_err());
    }
}
