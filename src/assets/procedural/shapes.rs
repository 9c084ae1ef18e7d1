//! Shape kernels the generators are made of: closed visual meshes and the exact convex pieces
//! that go with them (rods between two points, frusta, ellipsoids, rounded boxes, solids and
//! shells of revolution, slabs with a textured face).
//!
//! Every visual mesh here is closed and outward-wound, and every collision piece is convex by
//! construction, so an asset's collision is exact where the generator knows its parts.

use nalgebra::{Point3, Unit, UnitQuaternion, Vector3};

use crate::geometry::{ConvexPiece, GeometryError, TriMesh, mesh};
use crate::scene::Pose;

/// Rotation taking +Z onto `dir` (any unit vector).
fn z_to(dir: Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::rotation_between(&Vector3::z(), &dir).unwrap_or_else(|| {
        UnitQuaternion::from_axis_angle(&Unit::new_normalize(Vector3::x()), std::f64::consts::PI)
    })
}

/// Pose whose +Z runs from `p0` towards `p1`, origin at `p0`; and the length.
fn axis_pose(p0: [f64; 3], p1: [f64; 3]) -> (Pose, f64) {
    let a = Vector3::from(p0);
    let d = Vector3::from(p1) - a;
    let len = d.norm();
    let rot = if len > 1e-12 {
        z_to(d / len)
    } else {
        UnitQuaternion::identity()
    };
    (
        Pose(nalgebra::Isometry3::from_parts(
            nalgebra::Translation3::from(a),
            rot,
        )),
        len,
    )
}

/// A closed frustum (cone section) from `p0` (radius `r0`) to `p1` (radius `r1`).
pub fn frustum_mesh(p0: [f64; 3], p1: [f64; 3], r0: f64, r1: f64, segments: usize) -> TriMesh {
    let (pose, len) = axis_pose(p0, p1);
    let profile = [(0.0, 0.0), (r0, 0.0), (r1, len), (0.0, len)];
    mesh::lathe_mesh(&profile, segments).transformed(&pose)
}

/// The convex hull of a frustum from `p0` (radius `r0`) to `p1` (radius `r1`).
pub fn frustum_piece(
    p0: [f64; 3],
    p1: [f64; 3],
    r0: f64,
    r1: f64,
    segments: usize,
) -> Result<ConvexPiece, GeometryError> {
    let (pose, len) = axis_pose(p0, p1);
    let mut pts = Vec::new();
    for (r, z) in [(r0, 0.0), (r1, len)] {
        let r = r.max(1e-5);
        for q in mesh::circle_ring(0.0, 0.0, r, segments) {
            let p = pose.transform_point(&Point3::new(q[0], q[1], z));
            pts.push([p.x, p.y, p.z]);
        }
    }
    ConvexPiece::from_points(&pts)
}

/// Unit-sphere directions on a UV grid (poles included once).
fn sphere_dirs(segments: usize, rings: usize) -> Vec<Vector3<f64>> {
    let mut out = vec![Vector3::new(0.0, 0.0, -1.0)];
    for j in 1..rings {
        let phi = std::f64::consts::PI * j as f64 / rings as f64 - std::f64::consts::FRAC_PI_2;
        for i in 0..segments {
            let th = std::f64::consts::TAU * i as f64 / segments as f64;
            out.push(Vector3::new(
                phi.cos() * th.cos(),
                phi.cos() * th.sin(),
                phi.sin(),
            ));
        }
    }
    out.push(Vector3::new(0.0, 0.0, 1.0));
    out
}

/// A closed mesh over `dirs` laid out by [`sphere_dirs`], each direction mapped by `place`
/// to a position and a normal.
fn sphere_like(
    segments: usize,
    rings: usize,
    place: impl Fn(Vector3<f64>) -> (Vector3<f64>, Vector3<f64>),
) -> TriMesh {
    let dirs = sphere_dirs(segments, rings);
    let mut m = TriMesh::new();
    for d in &dirs {
        let (p, n) = place(*d);
        m.positions.push([p.x, p.y, p.z]);
        let n = n.try_normalize(1e-12).unwrap_or(*d);
        m.normals.push([n.x, n.y, n.z]);
    }
    let s = segments as u32;
    let ring = |j: u32, i: u32| 1 + (j - 1) * s + (i % s);
    let top = dirs.len() as u32 - 1;
    for i in 0..s {
        m.triangles.push([0, ring(1, i + 1), ring(1, i)]);
    }
    for j in 1..rings as u32 - 1 {
        for i in 0..s {
            let (a, b) = (ring(j, i), ring(j, i + 1));
            let (c, d) = (ring(j + 1, i + 1), ring(j + 1, i));
            m.triangles.push([a, b, c]);
            m.triangles.push([a, c, d]);
        }
    }
    let last = rings as u32 - 1;
    for i in 0..s {
        m.triangles.push([top, ring(last, i), ring(last, i + 1)]);
    }
    m
}

/// A closed ellipsoid mesh with semi-axes `radii`, smooth-shaded.
pub fn ellipsoid_mesh(center: [f64; 3], radii: [f64; 3], segments: usize) -> TriMesh {
    let c = Vector3::from(center);
    let r = Vector3::from(radii);
    let rings = (segments / 2).max(3);
    sphere_like(segments.max(4), rings, |d| {
        let p = c + d.component_mul(&r);
        let n = Vector3::new(d.x / r.x, d.y / r.y, d.z / r.z);
        (p, n)
    })
}

/// The convex hull of an ellipsoid sampled on a coarse grid, standing on a small flat facet
/// instead of its bottom pole: a hull balanced on a vertex is at rest only in theory (a ball
/// or an orange settles on it, then tips 15 degrees onto a facet in the next simulation).
pub fn ellipsoid_piece(center: [f64; 3], radii: [f64; 3]) -> Result<ConvexPiece, GeometryError> {
    let c = Vector3::from(center);
    let r = Vector3::from(radii);
    const FOOT_Z: f64 = -0.97;
    let foot = (1.0 - FOOT_Z * FOOT_Z).sqrt();
    let dirs = sphere_dirs(12, 6)
        .into_iter()
        .skip(1)
        .chain((0..12).map(|i| {
            let th = std::f64::consts::TAU * (f64::from(i) + 0.5) / 12.0;
            Vector3::new(foot * th.cos(), foot * th.sin(), FOOT_Z)
        }));
    let pts: Vec<[f64; 3]> = dirs
        .map(|d| {
            let p = c + d.component_mul(&r);
            [p.x, p.y, p.z]
        })
        .collect();
    ConvexPiece::from_points(&pts)
}

/// A closed box of full extents `size` whose edges are rounded with `radius` (clamped to half
/// the smallest extent), smooth-shaded: cushions, mattresses, appliance bodies.
pub fn rounded_box_mesh(center: [f64; 3], size: [f64; 3], radius: f64) -> TriMesh {
    let r = radius
        .min(size[0] / 2.0)
        .min(size[1] / 2.0)
        .min(size[2] / 2.0)
        .max(1e-5);
    let c = Vector3::from(center);
    let inner = Vector3::new(size[0] / 2.0 - r, size[1] / 2.0 - r, size[2] / 2.0 - r);
    // Each direction goes to the corner sphere of its octant; directions on an axis plane
    // (the equator, the seams) snap to the face between corners, so extents are exact.
    sphere_like(16, 8, |d| {
        let corner = Vector3::new(
            inner.x.copysign(if d.x.abs() < 1e-9 { 1.0 } else { d.x }),
            inner.y.copysign(if d.y.abs() < 1e-9 { 1.0 } else { d.y }),
            inner.z.copysign(if d.z.abs() < 1e-9 { 1.0 } else { d.z }),
        );
        // Directions exactly on an axis plane would pick one corner; snap them to the face.
        let snap = |v: f64, h: f64| if v.abs() < 1e-9 { 0.0 } else { h };
        let corner = Vector3::new(
            snap(d.x, corner.x),
            snap(d.y, corner.y),
            snap(d.z, corner.z),
        );
        (c + corner + d * r, d)
    })
}

/// Corner points of a rounded box, for its convex hull.
pub fn rounded_box_piece(
    center: [f64; 3],
    size: [f64; 3],
    radius: f64,
) -> Result<ConvexPiece, GeometryError> {
    let m = rounded_box_mesh(center, size, radius);
    ConvexPiece::from_points(&m.positions).or_else(|_| ConvexPiece::cuboid(center, size))
}

/// Frustum pieces of a solid of revolution: one hull per consecutive pair of profile points
/// `(radius, z)` with z increasing. Convex when the profile between the two points is (it is a
/// straight segment), so the union is exact.
pub fn solid_lathe_pieces(
    profile: &[(f64, f64)],
    segments: usize,
) -> Result<Vec<ConvexPiece>, GeometryError> {
    let mut out = Vec::new();
    for w in profile.windows(2) {
        let ((r0, z0), (r1, z1)) = (w[0], w[1]);
        if (z1 - z0).abs() < 1e-6 || (r0 <= 1e-9 && r1 <= 1e-9) {
            continue;
        }
        out.push(frustum_piece(
            [0.0, 0.0, z0],
            [0.0, 0.0, z1],
            r0,
            r1,
            segments,
        )?);
    }
    Ok(out)
}

/// The closed lathe mesh of a solid whose side is the profile `(radius, z)` from bottom to
/// top; the axis closes it.
pub fn solid_lathe_mesh(profile: &[(f64, f64)], segments: usize) -> TriMesh {
    let mut p: Vec<(f64, f64)> = Vec::with_capacity(profile.len() + 2);
    if let Some(&(_, z0)) = profile.first() {
        p.push((0.0, z0));
    }
    p.extend_from_slice(profile);
    if let Some(&(_, z1)) = profile.last() {
        p.push((0.0, z1));
    }
    mesh::lathe_mesh(&p, segments)
}

/// A hollow vessel (cup, bowl, pot, bin, vase): `outer` is the outside wall from the base rim
/// up to the lip, `(radius, z)` with z increasing and starting at z = 0; walls `wall` thick,
/// base `base` thick. Returns the closed visual and the convex pieces: a base disc plus
/// `sectors` hulls per wall band, so the cavity stays open for things put inside.
pub fn vessel(
    outer: &[(f64, f64)],
    wall: f64,
    base: f64,
    sectors: usize,
) -> Result<(TriMesh, Vec<ConvexPiece>), GeometryError> {
    if outer.len() < 2 {
        return Err(GeometryError::DegenerateHull {
            points: outer.len(),
        });
    }
    let inner: Vec<(f64, f64)> = outer
        .iter()
        .map(|&(r, z)| ((r - wall).max(0.002), z.max(base)))
        .collect();
    let mut profile = vec![(0.0, 0.0)];
    profile.extend_from_slice(outer);
    profile.extend(inner.iter().rev().copied());
    profile.push((0.0, base));
    // Drop repeated points (inner bottom can coincide after clamping).
    profile.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9);
    let visual = mesh::lathe_mesh(&profile, 40);
    let mut pieces = Vec::new();
    let r_base = outer[0].0.max(inner[0].0);
    pieces.push(frustum_piece(
        [0.0, 0.0, 0.0],
        [0.0, 0.0, base],
        outer[0].0,
        r_base.min(
            outer[0].0 + (outer[1].0 - outer[0].0) * base / (outer[1].1 - outer[0].1).max(1e-9),
        ),
        24,
    )?);
    for k in 0..outer.len() - 1 {
        let (o0, o1) = (outer[k], outer[k + 1]);
        let (i0, i1) = (inner[k], inner[k + 1]);
        if o1.1 <= base + 1e-6 {
            continue;
        }
        // Band from max(z, base) so the wall pieces sit on the base disc.
        let lift = |(r, z): (f64, f64), (r2, z2): (f64, f64)| -> (f64, f64) {
            if z >= base || (z2 - z).abs() < 1e-12 {
                (r, z.max(base))
            } else {
                let t = (base - z) / (z2 - z);
                (r + (r2 - r) * t, base)
            }
        };
        let band = [lift(o0, o1), o1, i1, lift(i0, i1)];
        pieces.extend(crate::geometry::convex::revolved_pieces(&band, sectors)?);
    }
    Ok((visual, pieces))
}

/// Which face of a slab carries the texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TexFace {
    /// +Z (rugs, placemats, tablecloths): image u along +x, v along -y.
    Top,
    /// +Y (posters, paintings, screens): image u along +x, v down along -z.
    Front,
}

/// A closed box whose `face` carries texture coordinates 0..1 (`repeat` times across); the
/// other faces sample the texture's top-left texel.
pub fn textured_slab(center: [f64; 3], size: [f64; 3], face: TexFace, repeat: [f64; 2]) -> TriMesh {
    let mut m = mesh::box_mesh(center, size);
    let lo = [
        center[0] - size[0] / 2.0,
        center[1] - size[1] / 2.0,
        center[2] - size[2] / 2.0,
    ];
    m.uvs = m
        .positions
        .iter()
        .zip(&m.normals)
        .map(|(p, n)| {
            let u = (p[0] - lo[0]) / size[0];
            match face {
                TexFace::Top if n[2] > 0.9 => {
                    [u * repeat[0], (1.0 - (p[1] - lo[1]) / size[1]) * repeat[1]]
                }
                TexFace::Front if n[1] > 0.9 => {
                    [u * repeat[0], (1.0 - (p[2] - lo[2]) / size[2]) * repeat[1]]
                }
                _ => [0.001, 0.001],
            }
        })
        .collect();
    m
}

/// A closed prism over an arbitrary convex polygon in a vertical plane: the polygon is given in
/// (x, z) and extruded along y from `y0` to `y1` (chair backs, gable shapes, piano lids).
pub fn xz_prism_mesh(ring_xz: &[[f64; 2]], y0: f64, y1: f64) -> TriMesh {
    // Build in (x, y=z) then rotate +90 degrees about X so that y -> z and z -> -y.
    let m = mesh::prism_mesh(ring_xz, -y1, -y0);
    let rot = Pose(nalgebra::Isometry3::from_parts(
        nalgebra::Translation3::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2),
    ));
    m.transformed(&rot)
}

/// Convex piece matching [`xz_prism_mesh`].
pub fn xz_prism_piece(
    ring_xz: &[[f64; 2]],
    y0: f64,
    y1: f64,
) -> Result<ConvexPiece, GeometryError> {
    let pts: Vec<[f64; 3]> = ring_xz
        .iter()
        .flat_map(|p| [[p[0], y0, p[1]], [p[0], y1, p[1]]])
        .collect();
    ConvexPiece::from_points(&pts)
}

/// A closed prism over a convex polygon in a plane perpendicular to X, extruded along x
/// (side profiles: chaise seats, ramps, treadmill decks).
pub fn yz_prism_mesh(ring_yz: &[[f64; 2]], x0: f64, x1: f64) -> TriMesh {
    let m = mesh::prism_mesh(ring_yz, x0, x1);
    // prism is built along z with the ring in (x, y); map (x, y, z) -> (z, x, y).
    let mut out = m.clone();
    out.positions = m.positions.iter().map(|p| [p[2], p[0], p[1]]).collect();
    out.normals = m.normals.iter().map(|n| [n[2], n[0], n[1]]).collect();
    out
}

/// Convex piece matching [`yz_prism_mesh`].
pub fn yz_prism_piece(
    ring_yz: &[[f64; 2]],
    x0: f64,
    x1: f64,
) -> Result<ConvexPiece, GeometryError> {
    let pts: Vec<[f64; 3]> = ring_yz
        .iter()
        .flat_map(|p| [[x0, p[0], p[1]], [x1, p[0], p[1]]])
        .collect();
    ConvexPiece::from_points(&pts)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An ellipsoid stands on a flat facet (12 hull vertices at its lowest height), not on a
    /// pole vertex it would tip off.
    #[test]
    fn ellipsoids_stand_on_a_facet() {
        let piece = ellipsoid_piece([0.0, 0.0, 0.1], [0.1, 0.1, 0.1]).unwrap();
        let low = piece
            .vertices
            .iter()
            .map(|v| v[2])
            .fold(f64::INFINITY, f64::min);
        let feet = piece.vertices.iter().filter(|v| v[2] < low + 1e-9).count();
        assert_eq!(feet, 12);
        assert!((low - 0.003).abs() < 1e-9, "{low}");
    }
    use crate::assets::physical::check_watertight;
    use crate::geometry::mesh::enclosed_volume;

    #[test]
    fn meshes_are_closed_and_outward() {
        let meshes = [
            frustum_mesh([0.1, 0.2, 0.0], [0.4, 0.1, 0.5], 0.05, 0.02, 16),
            ellipsoid_mesh([0.0, 0.0, 1.0], [0.1, 0.2, 0.3], 16),
            rounded_box_mesh([0.0; 3], [1.0, 0.5, 0.3], 0.05),
            solid_lathe_mesh(&[(0.1, 0.0), (0.2, 0.3), (0.05, 0.5)], 24),
            textured_slab([0.0; 3], [1.0, 2.0, 0.01], TexFace::Top, [1.0, 1.0]),
            xz_prism_mesh(&[[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]], 0.0, 0.2),
            yz_prism_mesh(&[[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]], 0.0, 0.2),
        ];
        for (k, m) in meshes.iter().enumerate() {
            check_watertight(m).unwrap_or_else(|e| panic!("mesh {k}: {e}"));
            assert!(enclosed_volume(m) > 0.0, "mesh {k} is inside out");
        }
    }

    #[test]
    fn rounded_box_keeps_its_extents() {
        let m = rounded_box_mesh([0.0, 0.0, 0.15], [1.0, 0.5, 0.3], 0.05);
        let (lo, hi) = m.bounds().unwrap();
        for i in 0..3 {
            assert!((hi[i] - lo[i] - [1.0, 0.5, 0.3][i]).abs() < 1e-9);
        }
        let piece = rounded_box_piece([0.0, 0.0, 0.15], [1.0, 0.5, 0.3], 0.05).unwrap();
        let v = piece.volume();
        assert!(v < 0.15 && v > 0.14, "{v}");
    }

    #[test]
    fn vessel_is_open_and_closed() {
        let (visual, pieces) =
            vessel(&[(0.04, 0.0), (0.06, 0.05), (0.07, 0.08)], 0.004, 0.006, 12).unwrap();
        check_watertight(&visual).unwrap();
        assert!(enclosed_volume(&visual) > 0.0);
        assert_eq!(pieces.len(), 1 + 2 * 12);
        // Nothing of the collision reaches into the middle above the base.
        for p in &pieces[1..] {
            let (lo, _) = p.bounds();
            assert!(lo[2] >= 0.006 - 1e-9);
        }
    }

    #[test]
    fn frustum_piece_has_the_right_volume() {
        let p = frustum_piece([0.0; 3], [0.0, 0.0, 1.0], 0.1, 0.1, 32).unwrap();
        let exact = std::f64::consts::PI * 0.01;
        assert!((p.volume() - exact).abs() / exact < 0.02);
        let slanted = frustum_piece([0.0; 3], [1.0, 1.0, 1.0], 0.1, 0.1, 32).unwrap();
        assert!((slanted.volume() - exact * 3f64.sqrt()).abs() / exact < 0.05);
    }
}
