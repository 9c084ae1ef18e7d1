//! Penetration of two posed convex pieces (the same pieces Drake uses), and the direction
//! that separates them.
//!
//! Penetration depth between two convex polyhedra is computed exactly with the separating axis
//! theorem (face normals of both pieces and cross products of their edge directions): the
//! minimum overlap over those axes is the minimum translation distance. parry3d's EPA was
//! measured to return wrong depths or no contact at all for deep overlaps of identical boxes
//! (see `tests::deep_overlaps_are_exact`), so it is not used for depths.

use std::collections::BTreeMap;

use nalgebra::{Point3, Vector3};

use super::ConvexPiece;
use crate::scene::Pose;

/// A convex piece posed in the world with the axes the separating-axis test needs.
#[derive(Debug, Clone)]
pub struct PosedPiece {
    /// Hull vertices, world frame.
    pub vertices: Vec<Vector3<f64>>,
    /// Distinct face normal directions, world frame (unit).
    pub normals: Vec<Vector3<f64>>,
    /// Edges between faces that are not coplanar: the two face normals (unit, world frame),
    /// which give the edge's arc on the Gauss map.
    pub edges: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// World bounds.
    pub lo: Vector3<f64>,
    /// World bounds.
    pub hi: Vector3<f64>,
}

fn push_direction(list: &mut Vec<Vector3<f64>>, d: Vector3<f64>) {
    let Some(u) = d.try_normalize(1e-12) else {
        return;
    };
    if !list.iter().any(|v| v.cross(&u).norm() < 1e-9) {
        list.push(u);
    }
}

impl PosedPiece {
    /// Poses `piece` by `world_from_piece`.
    pub fn new(piece: &ConvexPiece, world_from_piece: &Pose) -> PosedPiece {
        let vertices: Vec<Vector3<f64>> = piece
            .vertices
            .iter()
            .map(|v| {
                world_from_piece
                    .transform_point(&Point3::new(v[0], v[1], v[2]))
                    .coords
            })
            .collect();
        let mut normals = Vec::new();
        // Only true edges (between faces that are not coplanar) give separating axes; the
        // diagonals that triangulate a flat face do not, and they would square the work.
        let mut faces_of_edge: BTreeMap<(u32, u32), Vec<Vector3<f64>>> = BTreeMap::new();
        for t in &piece.triangles {
            let [a, b, c] = t.map(|i| vertices[i as usize]);
            let n = (b - a).cross(&(c - a));
            push_direction(&mut normals, n);
            for (p, q) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                faces_of_edge
                    .entry((p.min(q), p.max(q)))
                    .or_default()
                    .push(n);
            }
        }
        let mut edges = Vec::new();
        for faces in faces_of_edge.values() {
            let [Some(n0), Some(n1)] = [0, 1].map(|k| faces.get(k)?.try_normalize(1e-15)) else {
                continue;
            };
            if faces.len() == 2 && n0.cross(&n1).norm() > 1e-9 {
                edges.push((n0, n1));
            }
        }
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = Vector3::repeat(f64::NEG_INFINITY);
        for v in &vertices {
            lo = lo.inf(v);
            hi = hi.sup(v);
        }
        PosedPiece {
            vertices,
            normals,
            edges,
            lo,
            hi,
        }
    }

    fn project(&self, axis: &Vector3<f64>) -> (f64, f64) {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for v in &self.vertices {
            let p = v.dot(axis);
            lo = lo.min(p);
            hi = hi.max(p);
        }
        (lo, hi)
    }
}

/// Penetration depth (m) and direction (unit, pushing `b` out of `a`) of two posed convex
/// pieces, or `None` when they are separated or just touching.
pub fn sat_penetration(a: &PosedPiece, b: &PosedPiece) -> Option<(f64, Vector3<f64>)> {
    sat_penetration_shifted(a, &Vector3::zeros(), b, &Vector3::zeros())
}

/// [`sat_penetration`] of the pieces translated by `offset_a` and `offset_b` (the projection
/// loop moves pieces without re-posing them).
pub fn sat_penetration_shifted(
    a: &PosedPiece,
    offset_a: &Vector3<f64>,
    b: &PosedPiece,
    offset_b: &Vector3<f64>,
) -> Option<(f64, Vector3<f64>)> {
    let (alo, ahi) = (a.lo + offset_a, a.hi + offset_a);
    let (blo, bhi) = (b.lo + offset_b, b.hi + offset_b);
    if (0..3).any(|k| ahi[k] < blo[k] || bhi[k] < alo[k]) {
        return None;
    }
    let mut best = f64::INFINITY;
    let mut best_axis = Vector3::z();
    let mut test = |axis: Vector3<f64>| -> bool {
        let (sa, sb) = (offset_a.dot(&axis), offset_b.dot(&axis));
        let (a0, a1) = a.project(&axis);
        let (b0, b1) = b.project(&axis);
        let (a0, a1, b0, b1) = (a0 + sa, a1 + sa, b0 + sb, b1 + sb);
        let push_pos = a1 - b0; // move b along +axis by this much
        let push_neg = b1 - a0; // move b along -axis by this much
        let overlap = push_pos.min(push_neg);
        if overlap <= 0.0 {
            return false;
        }
        if overlap < best {
            best = overlap;
            best_axis = if push_pos <= push_neg { axis } else { -axis };
        }
        true
    };
    for n in a.normals.iter().chain(&b.normals) {
        if !test(*n) {
            return None;
        }
    }
    // Edge pairs: only those whose arcs cross on the Gauss map (a face of the Minkowski
    // difference) can separate the pieces; the rest are never the minimum.
    for (na0, na1) in &a.edges {
        let ea = na1.cross(na0);
        for (nb0, nb1) in &b.edges {
            let (c, d) = (-nb0, -nb1);
            let dc = d.cross(&c);
            let (cba, dba) = (c.dot(&ea), d.dot(&ea));
            let (adc, bdc) = (na0.dot(&dc), na1.dot(&dc));
            if !(cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0) {
                continue;
            }
            if let Some(axis) = ea.cross(&dc).try_normalize(1e-9)
                && !test(axis)
            {
                return None;
            }
        }
    }
    Some((best, best_axis))
}

/// How two penetrating pieces come apart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exit {
    /// Penetration depth (the minimum translation distance), metres.
    pub depth: f64,
    /// The minimum translation's direction (unit, moving `b`).
    pub minimum_axis: Vector3<f64>,
    /// How far `b` moves along `axis` to come free, metres (at least `depth`).
    pub exit_depth: f64,
    /// Unit direction `b` leaves along.
    pub axis: Vector3<f64>,
}

/// Overlaps shallower than this are grazes (see [`exit_direction`]), metres.
const GRAZE: f64 = 1e-3;

/// A way out for two penetrating pieces (the projection's linearisation), or `None` when they
/// are apart: among the face planes of the thinner piece that the other piece's centre lies
/// beyond, the one needing the least motion; the minimum-translation axis of the
/// separating-axis test when the centre lies beyond none (deep overlaps), or for a graze
/// (under 1 mm) when every face exit costs more than crossing the thinner piece.
///
/// The minimum translation can point through the wrong side of a thin part: a book pushed
/// through a bookcase's 8 mm back panel overlaps it least sideways, along the panel, into the
/// side panel, and the two rows then fight. The book's centre lies in front of the panel, so
/// the way out is forwards.
pub fn exit_direction(
    a: &PosedPiece,
    offset_a: &Vector3<f64>,
    b: &PosedPiece,
    offset_b: &Vector3<f64>,
) -> Option<Exit> {
    let (depth, minimum_axis) = sat_penetration_shifted(a, offset_a, b, offset_b)?;
    let centre = |p: &PosedPiece, o: &Vector3<f64>| (p.lo + p.hi) / 2.0 + o;
    let (ca, cb) = (centre(a, offset_a), centre(b, offset_b));
    let extent = |p: &PosedPiece, o: &Vector3<f64>, axis: &Vector3<f64>| {
        let (lo, hi) = p.project(axis);
        (lo + o.dot(axis), hi + o.dot(axis))
    };
    let mut best: Option<(f64, Vector3<f64>)> = None;
    let mut consider = |depth: f64, push_b: Vector3<f64>| {
        if depth > 0.0 && best.is_none_or(|(d, _)| depth < d) {
            best = Some((depth, push_b));
        }
    };
    // The thinner piece's faces decide (both when they are about as thick): a thin panel's
    // centre says nothing about where a book pushed through it should go, the book's centre
    // does.
    let thickness = |p: &PosedPiece| {
        p.normals
            .iter()
            .map(|n| {
                let (lo, hi) = p.project(n);
                hi - lo
            })
            .fold(f64::INFINITY, f64::min)
    };
    let (ta, tb) = (thickness(a), thickness(b));
    if ta <= tb * 1.5 {
        for n in &a.normals {
            for s in [*n, -n] {
                let (_, a1) = extent(a, offset_a, &s);
                let (b0, _) = extent(b, offset_b, &s);
                // b's centre beyond a's face along s: b leaves along s.
                if cb.dot(&s) > a1 {
                    consider(a1 - b0, s);
                }
            }
        }
    }
    if tb <= ta * 1.5 {
        for n in &b.normals {
            for s in [*n, -n] {
                // a's centre beyond b's face along s: b leaves along -s.
                if ca.dot(&s) > extent(b, offset_b, &s).1 {
                    let (_, a1) = extent(a, offset_a, &(-s));
                    let (b0, _) = extent(b, offset_b, &(-s));
                    consider(a1 - b0, -s);
                }
            }
        }
    }
    // A graze (under 1 mm) leaves along the minimum translation unless a face exit costs
    // about as little: faces far from the contact mislead (a plate's slanted rim touching a
    // shelf by 0.1 mm would otherwise leave through the shelf, 4 cm down).
    let (exit_depth, axis) = best
        .filter(|(d, _)| depth >= GRAZE || *d <= depth + 1.5 * ta.min(tb) + GRAZE)
        .unwrap_or((depth, minimum_axis));
    Some(Exit {
        depth,
        minimum_axis,
        exit_depth,
        axis,
    })
}

/// Penetration depth of two convex pieces at the given poses (`None` when apart).
pub fn penetration(
    a: &ConvexPiece,
    world_from_a: &Pose,
    b: &ConvexPiece,
    world_from_b: &Pose,
) -> Option<f64> {
    sat_penetration(
        &PosedPiece::new(a, world_from_a),
        &PosedPiece::new(b, world_from_b),
    )
    .map(|(d, _)| d)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> ConvexPiece {
        ConvexPiece::cuboid([0.0; 3], [1.0; 3]).unwrap()
    }

    #[test]
    fn overlapping_boxes_report_depth() {
        let d = penetration(
            &cube(),
            &Pose::IDENTITY,
            &cube(),
            &Pose::from_xyz(0.97, 0.0, 0.0),
        )
        .unwrap();
        assert!((d - 0.03).abs() < 1e-9, "{d}");
        assert!(
            penetration(
                &cube(),
                &Pose::IDENTITY,
                &cube(),
                &Pose::from_xyz(1.01, 0.0, 0.0)
            )
            .is_none()
        );
        let rotated = Pose::from_xyz_yaw(0.0, 0.0, 1.6, 0.7);
        assert!(penetration(&cube(), &Pose::IDENTITY, &cube(), &rotated).is_none());
    }

    /// The separating-axis minimum over every face normal and every edge pair (no Gauss-map
    /// pruning), for comparison.
    fn brute_force_depth(a: &PosedPiece, b: &PosedPiece) -> Option<f64> {
        let mut axes: Vec<Vector3<f64>> = a.normals.iter().chain(&b.normals).copied().collect();
        for (a0, a1) in &a.edges {
            for (b0, b1) in &b.edges {
                if let Some(axis) = a1.cross(a0).cross(&b1.cross(b0)).try_normalize(1e-9) {
                    axes.push(axis);
                }
            }
        }
        let mut best = f64::INFINITY;
        for axis in axes {
            let (a0, a1) = a.project(&axis);
            let (b0, b1) = b.project(&axis);
            let overlap = (a1 - b0).min(b1 - a0);
            if overlap <= 0.0 {
                return None;
            }
            best = best.min(overlap);
        }
        Some(best)
    }

    proptest::proptest! {
        /// Gauss-map pruning of edge pairs never changes the depth: boxes and cylinders in
        /// random orientations give the brute-force minimum.
        #[test]
        fn pruned_sat_equals_brute_force(
            rpy_a in proptest::array::uniform3(-3.2f64..3.2),
            rpy_b in proptest::array::uniform3(-3.2f64..3.2),
            offset in proptest::array::uniform3(-0.6f64..0.6),
            shapes in (0usize..3, 0usize..3),
        ) {
            let shape = |k: usize| match k {
                0 => ConvexPiece::cuboid([0.0; 3], [0.8, 0.5, 0.3]).unwrap(),
                1 => ConvexPiece::cylinder(0.0, 0.0, 0.3, -0.25, 0.25, 12).unwrap(),
                _ => ConvexPiece::from_points(&[
                    [0.0, 0.0, 0.0], [0.6, 0.1, 0.0], [0.2, 0.5, 0.1], [0.1, 0.2, 0.5],
                    [0.4, 0.4, 0.4],
                ]).unwrap(),
            };
            let a = PosedPiece::new(&shape(shapes.0), &Pose::from_xyz_rpy([0.0; 3], rpy_a));
            let b = PosedPiece::new(&shape(shapes.1), &Pose::from_xyz_rpy(offset, rpy_b));
            let pruned = sat_penetration(&a, &b).map(|(d, _)| d);
            let brute = brute_force_depth(&a, &b);
            match (pruned, brute) {
                (Some(p), Some(q)) => proptest::prop_assert!((p - q).abs() < 1e-9, "{p} vs {q}"),
                (None, None) => {}
                (p, q) => proptest::prop_assert!(false, "pruned {p:?}, brute force {q:?}"),
            }
        }
    }

    /// Regression: parry3d's EPA returned no contact at dz = 0.05 and depths of 0.017 and
    /// 0.004 m (instead of 0.03) for these two identical thin boxes.
    #[test]
    fn deep_overlaps_are_exact() {
        let book = ConvexPiece::cuboid([0.0, 0.0, 0.115], [0.03, 0.16, 0.23]).unwrap();
        for dz in [0.0, 0.05, 0.1, 0.2] {
            let d =
                penetration(&book, &Pose::IDENTITY, &book, &Pose::from_xyz(0.0, 0.0, dz)).unwrap();
            assert!((d - 0.03).abs() < 1e-9, "dz {dz}: {d}");
        }
        assert!(
            penetration(
                &book,
                &Pose::IDENTITY,
                &book,
                &Pose::from_xyz(0.0, 0.0, 0.231)
            )
            .is_none()
        );
    }

    /// A plate's slanted rim piece grazing a shelf panel by 0.1 mm leaves upwards by about
    /// 0.1 mm, not through the panel along a face far from the contact.
    #[test]
    fn a_graze_leaves_along_the_minimum_translation() {
        let panel = ConvexPiece::cuboid([0.0, 0.0, 0.089], [0.8, 0.45, 0.018]).unwrap();
        // Parallelogram in x-z (lowest along the edge at x = 0), extruded 5 cm along y.
        let mut pts = Vec::new();
        for y in [0.0, 0.05] {
            for (x, z) in [(0.0, 0.0), (0.04, 0.02), (0.04, 0.028), (0.0, 0.008)] {
                pts.push([x, y, z]);
            }
        }
        let rim = ConvexPiece::from_points(&pts).unwrap();
        let a = PosedPiece::new(&panel, &Pose::IDENTITY);
        for (x, y) in [(0.25, -0.2), (-0.3, 0.1), (0.1, 0.15), (0.33, -0.05)] {
            let b = PosedPiece::new(&rim, &Pose::from_xyz(x, y, 0.098 - 1e-4));
            let zero = Vector3::zeros();
            let exit = exit_direction(&a, &zero, &b, &zero).unwrap();
            assert!(exit.depth < 2e-4, "{x},{y}: depth {}", exit.depth);
            assert!(
                exit.exit_depth < 1e-3 && exit.axis.z > 0.9,
                "{x},{y}: leaves {:.4} m along {:?}",
                exit.exit_depth,
                exit.axis
            );
        }
    }

    #[test]
    fn edge_edge_contact_depth() {
        // Two cubes crossed at 45 degrees about different axes meet edge to edge.
        let a = Pose::from_xyz_rpy([0.0, 0.0, 0.0], [std::f64::consts::FRAC_PI_4, 0.0, 0.0]);
        let b = Pose::from_xyz_rpy([0.0, 0.0, 1.4], [0.0, std::f64::consts::FRAC_PI_4, 0.0]);
        let d = penetration(&cube(), &a, &cube(), &b).unwrap();
        // Edges at z = +-0.7071 each: overlap 2 * 0.7071 - 1.4.
        assert!((d - (2.0 * 0.5f64.sqrt() - 1.4)).abs() < 1e-9, "{d}");
        let (_, n) =
            sat_penetration(&PosedPiece::new(&cube(), &a), &PosedPiece::new(&cube(), &b)).unwrap();
        assert!(n.z > 0.99, "pushes b up: {n:?}");
    }
}
