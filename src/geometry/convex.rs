//! Convex collision pieces: the only collision geometry the project writes.
//!
//! Every collider in every format (SDFormat `drake:declare_convex`, MJCF mesh geoms, USD
//! `convexHull` colliders) is one of these, so a piece must really be convex: it is always built
//! as the convex hull of its points.

use nalgebra::Point3;
use parry3d_f64::math::Vector as PVec;
use parry3d_f64::shape::ConvexPolyhedron;

use super::GeometryError;
use super::mesh::{bounds_of, circle_ring};
use crate::scene::Pose;

/// A closed convex polyhedron: hull vertices and outward-wound triangles.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvexPiece {
    /// Hull vertices, metres, in the link frame.
    pub vertices: Vec<[f64; 3]>,
    /// Hull triangles (counter-clockwise seen from outside).
    pub triangles: Vec<[u32; 3]>,
}

impl ConvexPiece {
    /// Convex hull of `points`; fails when the points span no volume.
    pub fn from_points(points: &[[f64; 3]]) -> Result<ConvexPiece, GeometryError> {
        if points.len() < 4 {
            return Err(GeometryError::DegenerateHull {
                points: points.len(),
            });
        }
        if points.iter().flatten().any(|v| !v.is_finite()) {
            return Err(GeometryError::NonFinite);
        }
        let pts: Vec<PVec> = points.iter().map(|p| PVec::new(p[0], p[1], p[2])).collect();
        let (verts, tris) = parry3d_f64::transformation::try_convex_hull(&pts).map_err(|_| {
            GeometryError::DegenerateHull {
                points: points.len(),
            }
        })?;
        let piece = ConvexPiece {
            vertices: verts.iter().map(|v| [v.x, v.y, v.z]).collect(),
            triangles: tris,
        };
        if piece.triangles.len() < 4 || piece.volume() <= 1e-15 {
            return Err(GeometryError::DegenerateHull {
                points: points.len(),
            });
        }
        Ok(piece)
    }

    /// An axis-aligned box of full extents `size` centred at `center`.
    pub fn cuboid(center: [f64; 3], size: [f64; 3]) -> Result<ConvexPiece, GeometryError> {
        let h = [size[0] / 2.0, size[1] / 2.0, size[2] / 2.0];
        let mut pts = Vec::with_capacity(8);
        for sx in [-1.0, 1.0] {
            for sy in [-1.0, 1.0] {
                for sz in [-1.0, 1.0] {
                    pts.push([
                        center[0] + sx * h[0],
                        center[1] + sy * h[1],
                        center[2] + sz * h[2],
                    ]);
                }
            }
        }
        Self::from_points(&pts)
    }

    /// A vertical prism over the convex hull of `ring_xy`, from `z0` to `z1`.
    pub fn prism(ring_xy: &[[f64; 2]], z0: f64, z1: f64) -> Result<ConvexPiece, GeometryError> {
        let pts: Vec<[f64; 3]> = ring_xy
            .iter()
            .flat_map(|p| [[p[0], p[1], z0], [p[0], p[1], z1]])
            .collect();
        Self::from_points(&pts)
    }

    /// A vertical cylinder approximated by a `segments`-sided prism whose faces touch the circle
    /// (circumscribed, so resting contact matches the visual's silhouette from outside).
    pub fn cylinder(
        cx: f64,
        cy: f64,
        radius: f64,
        z0: f64,
        z1: f64,
        segments: usize,
    ) -> Result<ConvexPiece, GeometryError> {
        Self::prism(&circle_ring(cx, cy, radius, segments), z0, z1)
    }

    /// The piece with every vertex mapped by `a_from_b`.
    pub fn transformed(&self, a_from_b: &Pose) -> ConvexPiece {
        ConvexPiece {
            vertices: self
                .vertices
                .iter()
                .map(|v| {
                    let q = a_from_b.transform_point(&Point3::new(v[0], v[1], v[2]));
                    [q.x, q.y, q.z]
                })
                .collect(),
            triangles: self.triangles.clone(),
        }
    }

    /// Enclosed volume, m^3.
    pub fn volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let a = nalgebra::Vector3::from(self.vertices[t[0] as usize]);
                let b = nalgebra::Vector3::from(self.vertices[t[1] as usize]);
                let c = nalgebra::Vector3::from(self.vertices[t[2] as usize]);
                a.dot(&b.cross(&c)) / 6.0
            })
            .sum()
    }

    /// Axis-aligned bounds in the piece's frame.
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        bounds_of(&self.vertices).unwrap_or(([0.0; 3], [0.0; 3]))
    }

    /// The parry3d shape for queries (collision, distance, mass properties).
    pub fn to_parry(&self) -> Result<ConvexPolyhedron, GeometryError> {
        let pts: Vec<PVec> = self
            .vertices
            .iter()
            .map(|p| PVec::new(p[0], p[1], p[2]))
            .collect();
        ConvexPolyhedron::from_convex_mesh(pts, &self.triangles)
            .or_else(|| {
                // A hull whose coplanar faces parry cannot merge still has a valid hull.
                let pts: Vec<PVec> = self
                    .vertices
                    .iter()
                    .map(|p| PVec::new(p[0], p[1], p[2]))
                    .collect();
                ConvexPolyhedron::from_convex_hull(&pts)
            })
            .ok_or(GeometryError::DegenerateHull {
                points: self.vertices.len(),
            })
    }
}

/// Convex pieces approximating a solid of revolution about +Z: the closed `(radius, z)` profile
/// polygon is swept between consecutive angles and each sweep becomes one hull. Used for the
/// walls of cups, bowls, plates and pots, so their cavities stay open.
pub fn revolved_pieces(
    profile: &[(f64, f64)],
    segments: usize,
) -> Result<Vec<ConvexPiece>, GeometryError> {
    let segments = segments.max(3);
    (0..segments)
        .map(|i| {
            let a0 = std::f64::consts::TAU * i as f64 / segments as f64;
            let a1 = std::f64::consts::TAU * (i + 1) as f64 / segments as f64;
            let pts: Vec<[f64; 3]> = profile
                .iter()
                .flat_map(|&(r, z)| {
                    [
                        [r * a0.cos(), r * a0.sin(), z],
                        [r * a1.cos(), r * a1.sin(), z],
                    ]
                })
                .collect();
            ConvexPiece::from_points(&pts)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cuboid_volume() {
        let c = ConvexPiece::cuboid([1.0, 2.0, 3.0], [0.5, 0.4, 0.2]).unwrap();
        assert!((c.volume() - 0.04).abs() < 1e-12);
        assert_eq!(c.vertices.len(), 8);
    }

    #[test]
    fn flat_points_are_rejected() {
        let flat = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        assert!(ConvexPiece::from_points(&flat).is_err());
    }

    #[test]
    fn hull_drops_interior_points() {
        let mut pts = vec![];
        for x in [0.0, 1.0] {
            for y in [0.0, 1.0] {
                for z in [0.0, 1.0] {
                    pts.push([x, y, z]);
                }
            }
        }
        pts.push([0.5, 0.5, 0.5]);
        let c = ConvexPiece::from_points(&pts).unwrap();
        assert_eq!(c.vertices.len(), 8);
        assert!(c.to_parry().is_ok());
    }
}
