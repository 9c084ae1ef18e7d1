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

    /// The hull of at most about `max_vertices` of the piece's vertices, with its bounds kept.
    ///
    /// Drake's compliant hydroelastic contact builds a tetrahedron per hull triangle, and every
    /// polygon where two such meshes meet is a contact point its solver carries: a glass base
    /// of 16 sides on a shelf is about 58 of them, of 6 sides about 22. The bottom face (what
    /// the piece rests on) keeps at most [`MAX_BASE_VERTICES`] vertices spread around it and
    /// the top face (what carries other things) at most [`MAX_FACE_VERTICES`]; each side face
    /// keeps at least one, taken off the bottom face where it can be. Every bound, the resting
    /// height and the height of a top surface are unchanged; farthest-point sampling over the
    /// other vertices fills the rest. The result lies inside the piece: a round top at most
    /// `r (1 - cos(pi / 12))` (3.4 % of the radius) inside its silhouette, a round base at most
    /// `r (1 - cos(pi / 6))` (13 %), a chamfer along the bottom edge. A piece whose kept points
    /// span no volume, or whose bottom or top is rounded, stays as it was.
    pub fn simplified(&self, max_vertices: usize) -> ConvexPiece {
        let (lo, hi) = self.bounds();
        let bottom = self.on_plane(2, lo[2]);
        let top = self.on_plane(2, hi[2]);
        // A rounded bottom or top (a pole, an edge) rests on the rings just above it: a toilet
        // pedestal simplified there stood on a cone and tipped 8 degrees. It stays as it is.
        let rounded = bottom.len() < 3 || top.len() < 3;
        if rounded || (self.vertices.len() <= max_vertices && bottom.len() <= MAX_BASE_VERTICES) {
            return self.clone();
        }
        // The base and the top first: they carry what rests on them and what the piece rests
        // on.
        let mut keep = farthest_points(&self.vertices, &bottom, &[], MAX_BASE_VERTICES);
        for i in farthest_points(&self.vertices, &top, &[], MAX_FACE_VERTICES) {
            if !keep.contains(&i) {
                keep.push(i);
            }
        }
        // A side face needs one vertex to keep its bound; one off the base if it has one.
        for axis in [0, 1] {
            for plane in [lo[axis], hi[axis]] {
                let on = self.on_plane(axis, plane);
                if on.iter().any(|i| keep.contains(i)) {
                    continue;
                }
                let off_base: Vec<usize> =
                    on.iter().copied().filter(|i| !bottom.contains(i)).collect();
                let from = if off_base.is_empty() { &on } else { &off_base };
                keep.extend(from.first().copied());
            }
        }
        // The fill leaves the bottom and top faces at what they kept.
        let off_caps: Vec<usize> = (0..self.vertices.len())
            .filter(|i| !bottom.contains(i) && !top.contains(i))
            .collect();
        let keep = farthest_points(&self.vertices, &off_caps, &keep, max_vertices);
        let points: Vec<[f64; 3]> = keep.iter().map(|&i| self.vertices[i]).collect();
        ConvexPiece::from_points(&points).unwrap_or_else(|_| self.clone())
    }

    /// Small pieces inside this one at the corners of its bottom face, for point contact.
    ///
    /// Point contact (Drake's `point` model, SceneEval's protocol) gives one contact point per
    /// pair of pieces: a 3 m counter whose plinth is one box rests on a single point and rocks
    /// and walks. Each pad is a small wedge (about 2 cm) on the bottom face at one of its four
    /// most spread corners: a triangle of the face (the corner, a point towards the face's
    /// centre, a point towards the nearest other corner) and the same triangle raised towards
    /// the piece's centre. Every pad point is a convex combination of the piece's own points,
    /// so a pad lies inside the piece whatever its shape (a tapering pedestal too): the shape,
    /// the bounds and every other contact stay as they were, and the piece rests on four
    /// points or more. A bottom face narrower than `min_extent` (metres) gets none.
    pub fn corner_pads(&self, min_extent: f64) -> Vec<ConvexPiece> {
        let bottom = self.on_plane(2, self.bounds().0[2]);
        let corners = farthest_points(&self.vertices, &bottom, &[], 4);
        let extent = |axis: usize| {
            let vals = bottom.iter().map(|&i| self.vertices[i][axis]);
            vals.clone().fold(f64::NEG_INFINITY, f64::max) - vals.fold(f64::INFINITY, f64::min)
        };
        if corners.len() < 3 || extent(0).max(extent(1)) < min_extent {
            return Vec::new();
        }
        let mean = |ids: &mut dyn Iterator<Item = usize>| {
            let (mut sum, mut n) = ([0.0; 3], 0.0);
            for i in ids {
                (0..3).for_each(|k| sum[k] += self.vertices[i][k]);
                n += 1.0;
            }
            sum.map(|v| v / n)
        };
        let face_centre = mean(&mut bottom.iter().copied());
        let centre = mean(&mut (0..self.vertices.len()));
        // `q` moved towards `target` by `reach` metres, at most half way: a convex combination
        // of the piece's points, so inside it.
        let toward = |q: [f64; 3], target: [f64; 3], reach: f64| {
            let d = (0..3)
                .map(|k| (target[k] - q[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            let t = (reach / d.max(1e-12)).min(0.5);
            [0, 1, 2].map(|k| q[k] + t * (target[k] - q[k]))
        };
        corners
            .iter()
            .filter_map(|&i| {
                let p = self.vertices[i];
                // The nearest other corner: along an edge of the face, not across it.
                let next = corners
                    .iter()
                    .filter(|&&j| j != i)
                    .map(|&j| self.vertices[j])
                    .min_by(|a, b| {
                        let d = |q: &[f64; 3]| (0..3).map(|k| (q[k] - p[k]).powi(2)).sum::<f64>();
                        d(a).total_cmp(&d(b))
                    })?;
                // A small triangle of the bottom face at the corner, and the same raised
                // towards the piece's centre by about half its size.
                let base = [p, toward(p, face_centre, PAD_M), toward(p, next, PAD_M)];
                let rise = (centre[2] - p[2]).max(1e-9);
                let raised = base.map(|q| {
                    let t = (PAD_M / 2.0 / rise).min(0.5);
                    [0, 1, 2].map(|k| q[k] + t * (centre[k] - q[k]))
                });
                ConvexPiece::from_points(&[base, raised].concat()).ok()
            })
            .collect()
    }

    /// The vertices within [`FACE_TOLERANCE_M`] of the plane `coordinate[axis] == value`.
    fn on_plane(&self, axis: usize, value: f64) -> Vec<usize> {
        (0..self.vertices.len())
            .filter(|&i| (self.vertices[i][axis] - value).abs() <= FACE_TOLERANCE_M)
            .collect()
    }

    /// Whether `point` lies inside the piece or on its boundary (1e-9 m).
    pub fn contains(&self, point: [f64; 3]) -> bool {
        self.triangles.iter().all(|t| {
            let [a, b, c] = t.map(|i| nalgebra::Vector3::from(self.vertices[i as usize]));
            let n = (b - a).cross(&(c - a));
            let len = n.norm();
            len <= 0.0 || n.dot(&(nalgebra::Vector3::from(point) - a)) / len <= 1e-9
        })
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

/// Vertices a simplified collision piece keeps ([`ConvexPiece::simplified`]): enough for a
/// 12-sided base and top and a round body, few enough that Drake's hydroelastic contact stays
/// cheap.
pub const MAX_PIECE_VERTICES: usize = 32;

/// Most vertices [`ConvexPiece::simplified`] keeps on a piece's top face.
pub const MAX_FACE_VERTICES: usize = 12;

/// Most vertices [`ConvexPiece::simplified`] keeps on a piece's bottom face: a hexagon rests
/// as steadily as a circle and makes a third of the contact polygons of a 16-sided base.
pub const MAX_BASE_VERTICES: usize = 6;

/// How far a contact pad reaches from its corner, metres.
const PAD_M: f64 = 0.02;

/// A vertex this close to an extreme plane lies on that face, metres.
const FACE_TOLERANCE_M: f64 = 1e-4;

/// Greedy farthest-point sampling: `seeds`, then the candidate farthest from everything chosen,
/// until `total` are chosen or every candidate coincides with a chosen one. Without seeds it
/// starts from the candidate farthest from the candidates' centroid. Indices into `points`.
fn farthest_points(
    points: &[[f64; 3]],
    candidates: &[usize],
    seeds: &[usize],
    total: usize,
) -> Vec<usize> {
    let dist = |a: [f64; 3], b: [f64; 3]| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
    let mut chosen: Vec<usize> = seeds.to_vec();
    if chosen.is_empty() {
        let n = candidates.len().max(1) as f64;
        let mut c = [0.0; 3];
        for &i in candidates {
            for k in 0..3 {
                c[k] += points[i][k] / n;
            }
        }
        let first = candidates
            .iter()
            .copied()
            .max_by(|&a, &b| dist(points[a], c).total_cmp(&dist(points[b], c)));
        chosen.extend(first);
    }
    let mut gap: Vec<f64> = candidates
        .iter()
        .map(|&i| {
            chosen
                .iter()
                .map(|&j| dist(points[i], points[j]))
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    while chosen.len() < total {
        let Some((at, &far)) = gap.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)) else {
            break;
        };
        if far <= 1e-9 {
            break;
        }
        let next = candidates[at];
        chosen.push(next);
        for (g, &i) in gap.iter_mut().zip(candidates) {
            *g = g.min(dist(points[i], points[next]));
        }
    }
    chosen
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

    #[test]
    fn a_simplified_cylinder_keeps_its_bounds_a_six_sided_base_and_a_twelve_sided_top() {
        let glass = ConvexPiece::cylinder(0.0, 0.0, 0.04, 0.0, 0.1, 32).unwrap();
        assert_eq!(glass.vertices.len(), 64);
        let s = glass.simplified(MAX_PIECE_VERTICES);
        // A prism has no vertex off its two rings: the base keeps six, the top twelve and the
        // side bounds take one each, off the base.
        assert!(
            s.vertices.len() <= MAX_BASE_VERTICES + MAX_FACE_VERTICES + 4,
            "{}",
            s.vertices.len()
        );
        assert_eq!(s.bounds(), glass.bounds());
        let at = |z: f64| {
            s.vertices
                .iter()
                .filter(|v| (v[2] - z).abs() < 1e-9)
                .count()
        };
        assert_eq!(at(0.0), MAX_BASE_VERTICES);
        assert!(
            (MAX_FACE_VERTICES..=MAX_FACE_VERTICES + 4).contains(&at(0.1)),
            "{}",
            at(0.1)
        );
        // Inside the original, and losing little of it.
        assert!(s.volume() <= glass.volume() + 1e-12);
        assert!(
            s.volume() > 0.85 * glass.volume(),
            "{} of {}",
            s.volume(),
            glass.volume()
        );
        let bottom_triangles = s
            .triangles
            .iter()
            .filter(|t| t.iter().all(|&i| s.vertices[i as usize][2].abs() < 1e-9))
            .count();
        assert_eq!(bottom_triangles, MAX_BASE_VERTICES - 2);
    }

    #[test]
    fn a_small_piece_with_a_many_sided_base_gets_a_six_sided_one() {
        let jar = ConvexPiece::cylinder(0.0, 0.0, 0.03, 0.0, 0.08, 10).unwrap();
        assert!(jar.vertices.len() <= MAX_PIECE_VERTICES);
        let s = jar.simplified(MAX_PIECE_VERTICES);
        assert_eq!(s.bounds(), jar.bounds());
        let at = |z: f64| {
            s.vertices
                .iter()
                .filter(|v| (v[2] - z).abs() < 1e-9)
                .count()
        };
        assert_eq!((at(0.0), at(0.08)), (MAX_BASE_VERTICES, 10));
    }

    #[test]
    fn a_small_piece_is_not_simplified() {
        let b = ConvexPiece::cuboid([0.0; 3], [0.3, 0.2, 0.1]).unwrap();
        assert_eq!(b.simplified(MAX_PIECE_VERTICES), b);
    }

    #[test]
    fn a_rounded_piece_is_left_as_it_is() {
        let mut pts = Vec::new();
        for i in 0..12 {
            for j in 1..12 {
                let (a, b) = (
                    std::f64::consts::TAU * i as f64 / 12.0,
                    std::f64::consts::PI * j as f64 / 12.0,
                );
                pts.push([
                    0.05 * b.sin() * a.cos(),
                    0.05 * b.sin() * a.sin(),
                    0.05 * b.cos(),
                ]);
            }
        }
        pts.push([0.0, 0.0, 0.05]);
        pts.push([0.0, 0.0, -0.05]);
        let ball = ConvexPiece::from_points(&pts).unwrap();
        assert!(ball.vertices.len() > MAX_PIECE_VERTICES);
        assert_eq!(ball.simplified(MAX_PIECE_VERTICES), ball);
    }

    #[test]
    fn a_wide_base_gets_four_pads_inside_it_touching_the_floor() {
        let plinth = ConvexPiece::cuboid([0.0, 0.0, 0.05], [3.0, 0.5, 0.1]).unwrap();
        let pads = plinth.corner_pads(0.05);
        assert_eq!(pads.len(), 4);
        let (lo, hi) = plinth.bounds();
        let mut corners_seen = Vec::new();
        for pad in &pads {
            let (plo, phi) = pad.bounds();
            assert!((plo[2] - lo[2]).abs() < 1e-12, "a pad rests on the floor");
            assert!((0..3).all(|k| plo[k] >= lo[k] - 1e-12 && phi[k] <= hi[k] + 1e-12));
            assert!(pad.volume() > 0.0);
            corners_seen.push([plo[0] < 0.0, plo[1] < 0.0]);
        }
        corners_seen.sort();
        corners_seen.dedup();
        assert_eq!(corners_seen.len(), 4, "one pad per corner");
        // A round base gets its pads where they fit inside it.
        let tin = ConvexPiece::cylinder(0.0, 0.0, 0.05, 0.0, 0.1, 12).unwrap();
        let pads = tin.corner_pads(0.05);
        assert!(pads.len() >= 3, "{}", pads.len());
        for pad in &pads {
            assert!(pad.vertices.iter().all(|v| tin.contains(*v)));
        }
        // A small base gets none.
        let die = ConvexPiece::cuboid([0.0, 0.0, 0.01], [0.02, 0.02, 0.02]).unwrap();
        assert!(die.corner_pads(0.05).is_empty());
    }
}
