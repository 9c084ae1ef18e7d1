//! Mass properties from convex pieces, and the physical-validity check every inertia passes
//! before anything is written.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};
use parry3d_f64::mass_properties::MassProperties;
use parry3d_f64::shape::Shape;
use serde::{Deserialize, Serialize};

use super::GeometryError;
use super::convex::ConvexPiece;

/// Mass, centre of mass and rotational inertia of one rigid link, all in the link frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MassProps {
    /// Mass, kg.
    pub mass: f64,
    /// Centre of mass in the link frame, m.
    pub com: [f64; 3],
    /// Rotational inertia about the centre of mass, axes of the link frame, kg m^2.
    pub inertia: [[f64; 3]; 3],
}

impl MassProps {
    /// Solid mass properties of the union of `pieces` at uniform `density` (kg/m^3).
    ///
    /// Pieces are treated as disjoint; overlapping pieces count their shared volume twice, which
    /// generators avoid by construction.
    pub fn from_pieces(pieces: &[ConvexPiece], density: f64) -> Result<MassProps, GeometryError> {
        if !(density.is_finite() && density > 0.0) {
            return Err(GeometryError::InvalidDensity(density));
        }
        let mut total = MassProperties::default();
        for piece in pieces {
            let shape = piece.to_parry()?;
            total += shape.mass_properties(density);
        }
        let mass = total.mass();
        if !(mass.is_finite() && mass > 0.0) {
            return Err(GeometryError::InvalidInertia(format!(
                "mass {mass} kg from {} pieces",
                pieces.len()
            )));
        }
        let com = total.local_com;
        let i = total.reconstruct_inertia_matrix();
        let inertia = [
            [i.x_axis.x, i.y_axis.x, i.z_axis.x],
            [i.x_axis.y, i.y_axis.y, i.z_axis.y],
            [i.x_axis.z, i.y_axis.z, i.z_axis.z],
        ];
        let props = MassProps {
            mass,
            com: [com.x, com.y, com.z],
            inertia: symmetrize(inertia),
        };
        props.validate()?;
        Ok(props)
    }

    /// Scales mass and inertia by `factor` (same geometry, different density).
    pub fn scaled(&self, factor: f64) -> MassProps {
        let mut out = *self;
        out.mass *= factor;
        for row in out.inertia.iter_mut() {
            for v in row.iter_mut() {
                *v *= factor;
            }
        }
        out
    }

    /// Checks that the properties describe a real rigid body: positive finite mass, a
    /// symmetric positive-definite inertia whose principal moments satisfy the triangle
    /// inequality (each moment at most the sum of the other two).
    pub fn validate(&self) -> Result<(), GeometryError> {
        validate_inertia(self.mass, &self.inertia)
    }

    /// Principal moments, ascending.
    pub fn principal_moments(&self) -> [f64; 3] {
        let m = Matrix3::from_fn(|r, c| self.inertia[r][c]);
        let mut e: Vec<f64> = SymmetricEigen::new(m).eigenvalues.iter().copied().collect();
        e.sort_by(f64::total_cmp);
        [e[0], e[1], e[2]]
    }

    /// Principal moments (ascending) and the rotation whose columns are the principal axes,
    /// expressed in the link frame (as USD's `principalAxes` wants).
    pub fn principal_frame(&self) -> ([f64; 3], nalgebra::UnitQuaternion<f64>) {
        let m = Matrix3::from_fn(|r, c| self.inertia[r][c]);
        let eig = SymmetricEigen::new(m);
        let mut order = [0usize, 1, 2];
        order.sort_by(|a, b| eig.eigenvalues[*a].total_cmp(&eig.eigenvalues[*b]));
        let mut axes = Matrix3::zeros();
        for (col, &k) in order.iter().enumerate() {
            axes.set_column(col, &eig.eigenvectors.column(k));
        }
        if axes.determinant() < 0.0 {
            let flipped = -axes.column(2);
            axes.set_column(2, &flipped);
        }
        let rot = nalgebra::Rotation3::from_matrix_unchecked(axes);
        let moments = [
            eig.eigenvalues[order[0]],
            eig.eigenvalues[order[1]],
            eig.eigenvalues[order[2]],
        ];
        (
            moments,
            nalgebra::UnitQuaternion::from_rotation_matrix(&rot),
        )
    }
}

fn symmetrize(m: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut out = m;
    for r in 0..3 {
        for c in 0..3 {
            out[r][c] = 0.5 * (m[r][c] + m[c][r]);
        }
    }
    out
}

/// The physical-validity check on a mass and a 3x3 inertia about the centre of mass.
pub fn validate_inertia(mass: f64, inertia: &[[f64; 3]; 3]) -> Result<(), GeometryError> {
    if !(mass.is_finite() && mass > 0.0) {
        return Err(GeometryError::InvalidInertia(format!(
            "mass must be positive and finite, got {mass}"
        )));
    }
    if inertia.iter().flatten().any(|v| !v.is_finite()) {
        return Err(GeometryError::InvalidInertia(
            "inertia has a non-finite entry".into(),
        ));
    }
    let scale = inertia[0][0].abs() + inertia[1][1].abs() + inertia[2][2].abs();
    for r in 0..3 {
        for c in 0..3 {
            if (inertia[r][c] - inertia[c][r]).abs() > 1e-9 * scale.max(1e-300) {
                return Err(GeometryError::InvalidInertia(format!(
                    "inertia is not symmetric at ({r},{c})"
                )));
            }
        }
    }
    let m = Matrix3::from_fn(|r, c| inertia[r][c]);
    let eig: Vector3<f64> = SymmetricEigen::new(m).eigenvalues;
    let mut e = [eig[0], eig[1], eig[2]];
    e.sort_by(f64::total_cmp);
    if e[0] <= 1e-12 * scale || e[0] <= 0.0 {
        return Err(GeometryError::InvalidInertia(format!(
            "inertia is not positive definite (principal moments {e:?})"
        )));
    }
    // Triangle inequality: the largest moment cannot exceed the sum of the other two.
    if e[2] > (e[0] + e[1]) * (1.0 + 1e-9) {
        return Err(GeometryError::InvalidInertia(format!(
            "principal moments {e:?} violate the triangle inequality"
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn box_matches_closed_form() {
        let (a, b, c) = (0.4, 0.3, 0.2);
        let piece = ConvexPiece::cuboid([0.1, 0.0, 0.1], [a, b, c]).unwrap();
        let p = MassProps::from_pieces(&[piece], 1000.0).unwrap();
        let m = 1000.0 * a * b * c;
        assert!((p.mass - m).abs() < 1e-9);
        assert!((p.com[0] - 0.1).abs() < 1e-12 && (p.com[2] - 0.1).abs() < 1e-12);
        let ixx = m / 12.0 * (b * b + c * c);
        let izz = m / 12.0 * (a * a + b * b);
        assert!((p.inertia[0][0] - ixx).abs() < 1e-9);
        assert!((p.inertia[2][2] - izz).abs() < 1e-9);
        assert!(p.inertia[0][1].abs() < 1e-12);
    }

    #[test]
    fn two_pieces_use_parallel_axis() {
        let left = ConvexPiece::cuboid([-0.5, 0.0, 0.0], [0.2, 0.2, 0.2]).unwrap();
        let right = ConvexPiece::cuboid([0.5, 0.0, 0.0], [0.2, 0.2, 0.2]).unwrap();
        let p = MassProps::from_pieces(&[left, right], 1000.0).unwrap();
        let m1 = 8.0;
        let i_own = m1 / 12.0 * (0.04 + 0.04);
        let expected_izz = 2.0 * (i_own + m1 * 0.25);
        assert!(
            (p.inertia[2][2] - expected_izz).abs() < 1e-9,
            "{:?}",
            p.inertia
        );
        assert!(p.com[0].abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_density() {
        let piece = ConvexPiece::cuboid([0.0; 3], [1.0; 3]).unwrap();
        assert!(MassProps::from_pieces(&[piece], 0.0).is_err());
    }

    #[test]
    fn principal_frame_diagonalises() {
        let piece = ConvexPiece::from_points(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.2, 0.0],
            [0.1, 0.6, 0.1],
            [0.3, 0.2, 0.9],
            [0.8, 0.7, 0.4],
        ])
        .unwrap();
        let p = MassProps::from_pieces(&[piece], 700.0).unwrap();
        let (moments, rot) = p.principal_frame();
        let r = rot.to_rotation_matrix();
        let i = Matrix3::from_fn(|a, b| p.inertia[a][b]);
        let d = r.matrix().transpose() * i * r.matrix();
        for k in 0..3 {
            assert!((d[(k, k)] - moments[k]).abs() < 1e-9 * moments[2]);
        }
        assert!(d[(0, 1)].abs() < 1e-9 * moments[2]);
    }

    proptest! {
        /// Any diagonal tensor whose largest moment exceeds the sum of the others is rejected,
        /// any with a non-positive moment is rejected, and every real box is accepted.
        #[test]
        fn triangle_inequality_and_definiteness(a in 0.01f64..10.0, b in 0.01f64..10.0, extra in 0.001f64..10.0) {
            let bad = [[a, 0.0, 0.0], [0.0, b, 0.0], [0.0, 0.0, a + b + extra]];
            prop_assert!(validate_inertia(1.0, &bad).is_err());
            let neg = [[a, 0.0, 0.0], [0.0, -b, 0.0], [0.0, 0.0, a]];
            prop_assert!(validate_inertia(1.0, &neg).is_err());
            let (x, y, z) = (a, b, extra);
            let boxy = [[(y*y+z*z)/12.0, 0.0, 0.0], [0.0, (x*x+z*z)/12.0, 0.0], [0.0, 0.0, (x*x+y*y)/12.0]];
            prop_assert!(validate_inertia(1.0, &boxy).is_ok());
        }

        /// Rotating a valid tensor keeps it valid; an asymmetric perturbation is rejected.
        #[test]
        fn rotation_invariance(yaw in -3.0f64..3.0, pitch in -1.5f64..1.5, skew in 0.01f64..1.0) {
            let r = nalgebra::Rotation3::from_euler_angles(0.2, pitch, yaw);
            let d = Matrix3::from_diagonal(&Vector3::new(1.0, 1.5, 2.0));
            let i = r.matrix() * d * r.matrix().transpose();
            let arr = [[i[(0,0)], i[(0,1)], i[(0,2)]], [i[(1,0)], i[(1,1)], i[(1,2)]], [i[(2,0)], i[(2,1)], i[(2,2)]]];
            prop_assert!(validate_inertia(2.0, &arr).is_ok());
            let mut asym = arr;
            asym[0][1] += skew;
            prop_assert!(validate_inertia(2.0, &asym).is_err());
        }
    }
}
