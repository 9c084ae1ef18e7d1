//! Triangle meshes for visuals: positions, per-vertex normals, triangles.
//!
//! Builders produce closed, outward-wound meshes in a local frame (metres, Z up). Flat-shaded
//! shapes (boxes, prisms) duplicate vertices per face so normals stay sharp; lathe shapes share
//! vertices around the axis so curved walls look smooth.

use nalgebra::{Point3, Vector3};

use crate::scene::Pose;

/// An indexed triangle mesh with one normal per vertex; triangles wind counter-clockwise seen
/// from outside.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions, metres.
    pub positions: Vec<[f64; 3]>,
    /// Unit normals, one per vertex.
    pub normals: Vec<[f64; 3]>,
    /// Triangles as indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// Texture coordinates, one per vertex, or empty when the mesh is untextured. `(0, 0)` is
    /// the top-left of the image (glTF's convention).
    pub uvs: Vec<[f64; 2]>,
}

impl TriMesh {
    /// An empty mesh.
    pub fn new() -> Self {
        Self::default()
    }

    /// True when the mesh has no triangles.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Appends `other` to `self`.
    pub fn append(&mut self, other: &TriMesh) {
        let offset = self.positions.len() as u32;
        // Keep uvs aligned with positions when only one side has them.
        if !other.uvs.is_empty() || !self.uvs.is_empty() {
            self.uvs.resize(self.positions.len(), [0.0, 0.0]);
            if other.uvs.is_empty() {
                self.uvs
                    .extend(std::iter::repeat_n([0.0, 0.0], other.positions.len()));
            } else {
                self.uvs.extend_from_slice(&other.uvs);
            }
        }
        self.positions.extend_from_slice(&other.positions);
        self.normals.extend_from_slice(&other.normals);
        self.triangles.extend(
            other
                .triangles
                .iter()
                .map(|t| [t[0] + offset, t[1] + offset, t[2] + offset]),
        );
    }

    /// The mesh with every vertex mapped by `a_from_b` (the mesh is read as expressed in `b`).
    pub fn transformed(&self, a_from_b: &Pose) -> TriMesh {
        let positions = self
            .positions
            .iter()
            .map(|p| {
                let q = a_from_b.transform_point(&Point3::new(p[0], p[1], p[2]));
                [q.x, q.y, q.z]
            })
            .collect();
        let normals = self
            .normals
            .iter()
            .map(|n| {
                let m = a_from_b.transform_vector(&Vector3::new(n[0], n[1], n[2]));
                [m.x, m.y, m.z]
            })
            .collect();
        TriMesh {
            positions,
            normals,
            triangles: self.triangles.clone(),
            uvs: self.uvs.clone(),
        }
    }

    /// The mesh scaled per axis about the local origin (normals re-normalised).
    pub fn scaled(&self, s: [f64; 3]) -> TriMesh {
        let positions = self
            .positions
            .iter()
            .map(|p| [p[0] * s[0], p[1] * s[1], p[2] * s[2]])
            .collect();
        let normals = self
            .normals
            .iter()
            .map(|n| {
                let m = Vector3::new(n[0] / s[0], n[1] / s[1], n[2] / s[2]);
                let m = m.try_normalize(1e-12).unwrap_or(Vector3::z());
                [m.x, m.y, m.z]
            })
            .collect();
        TriMesh {
            positions,
            normals,
            triangles: self.triangles.clone(),
            uvs: self.uvs.clone(),
        }
    }

    /// The mesh with texture coordinates from box mapping: each triangle is projected onto the
    /// plane most facing its normal, one texture repeat per `tile_m` metres. Suits tileable
    /// textures (floors, walls, fabric, wood grain).
    pub fn with_box_uvs(&self, tile_m: f64) -> TriMesh {
        let mut out = TriMesh::new();
        let tile = if tile_m > 1e-9 { tile_m } else { 1.0 };
        for t in &self.triangles {
            let p = t.map(|i| Vector3::from(self.positions[i as usize]));
            let n = (p[1] - p[0]).cross(&(p[2] - p[0]));
            let (a, b) = if n.z.abs() >= n.x.abs() && n.z.abs() >= n.y.abs() {
                (0, 1)
            } else if n.x.abs() >= n.y.abs() {
                (1, 2)
            } else {
                (0, 2)
            };
            let base = out.positions.len() as u32;
            for (k, &i) in t.iter().enumerate() {
                out.positions.push(self.positions[i as usize]);
                out.normals.push(self.normals[i as usize]);
                out.uvs.push([p[k][a] / tile, 1.0 - p[k][b] / tile]);
            }
            out.triangles.push([base, base + 1, base + 2]);
        }
        out
    }

    /// Axis-aligned bounds `(min, max)`; `None` for an empty mesh.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        bounds_of(&self.positions)
    }

    /// Adds one flat quad (`a b c d` counter-clockwise seen from outside).
    fn push_quad(&mut self, corners: [Vector3<f64>; 4]) {
        let normal = (corners[1] - corners[0])
            .cross(&(corners[2] - corners[0]))
            .try_normalize(1e-15)
            .unwrap_or(Vector3::z());
        let base = self.positions.len() as u32;
        for c in corners {
            self.positions.push([c.x, c.y, c.z]);
            self.normals.push([normal.x, normal.y, normal.z]);
        }
        self.triangles.push([base, base + 1, base + 2]);
        self.triangles.push([base, base + 2, base + 3]);
    }

    /// Adds a flat polygon fan (convex, counter-clockwise seen from outside).
    fn push_fan(&mut self, ring: &[Vector3<f64>]) {
        if ring.len() < 3 {
            return;
        }
        let normal = (ring[1] - ring[0])
            .cross(&(ring[2] - ring[0]))
            .try_normalize(1e-15)
            .unwrap_or(Vector3::z());
        let base = self.positions.len() as u32;
        for c in ring {
            self.positions.push([c.x, c.y, c.z]);
            self.normals.push([normal.x, normal.y, normal.z]);
        }
        for i in 1..ring.len() as u32 - 1 {
            self.triangles.push([base, base + i, base + i + 1]);
        }
    }
}

/// Axis-aligned bounds of a point set.
pub fn bounds_of(points: &[[f64; 3]]) -> Option<([f64; 3], [f64; 3])> {
    let first = points.first()?;
    let mut lo = *first;
    let mut hi = *first;
    for p in points {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    Some((lo, hi))
}

/// A box of full extents `size` centred at `center`.
pub fn box_mesh(center: [f64; 3], size: [f64; 3]) -> TriMesh {
    let c = Vector3::from(center);
    let h = Vector3::from(size) * 0.5;
    let v = |sx: f64, sy: f64, sz: f64| c + Vector3::new(sx * h.x, sy * h.y, sz * h.z);
    let mut m = TriMesh::new();
    // +X, -X, +Y, -Y, +Z, -Z faces, each counter-clockwise seen from outside.
    m.push_quad([
        v(1., -1., -1.),
        v(1., 1., -1.),
        v(1., 1., 1.),
        v(1., -1., 1.),
    ]);
    m.push_quad([
        v(-1., 1., -1.),
        v(-1., -1., -1.),
        v(-1., -1., 1.),
        v(-1., 1., 1.),
    ]);
    m.push_quad([
        v(1., 1., -1.),
        v(-1., 1., -1.),
        v(-1., 1., 1.),
        v(1., 1., 1.),
    ]);
    m.push_quad([
        v(-1., -1., -1.),
        v(1., -1., -1.),
        v(1., -1., 1.),
        v(-1., -1., 1.),
    ]);
    m.push_quad([
        v(-1., -1., 1.),
        v(1., -1., 1.),
        v(1., 1., 1.),
        v(-1., 1., 1.),
    ]);
    m.push_quad([
        v(-1., 1., -1.),
        v(1., 1., -1.),
        v(1., -1., -1.),
        v(-1., -1., -1.),
    ]);
    m
}

/// A vertical prism over a convex counter-clockwise polygon `ring_xy`, from `z0` to `z1`.
pub fn prism_mesh(ring_xy: &[[f64; 2]], z0: f64, z1: f64) -> TriMesh {
    let mut m = TriMesh::new();
    let n = ring_xy.len();
    if n < 3 {
        return m;
    }
    let at = |i: usize, z: f64| Vector3::new(ring_xy[i % n][0], ring_xy[i % n][1], z);
    for i in 0..n {
        m.push_quad([at(i, z0), at(i + 1, z0), at(i + 1, z1), at(i, z1)]);
    }
    let top: Vec<_> = (0..n).map(|i| at(i, z1)).collect();
    let bottom: Vec<_> = (0..n).rev().map(|i| at(i, z0)).collect();
    m.push_fan(&top);
    m.push_fan(&bottom);
    m
}

/// Vertices of a regular polygon of `segments` sides with circumradius `radius`, centred at
/// `(cx, cy)`, counter-clockwise, first vertex on +X.
pub fn circle_ring(cx: f64, cy: f64, radius: f64, segments: usize) -> Vec<[f64; 2]> {
    let segments = segments.max(3);
    (0..segments)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / segments as f64;
            [cx + radius * a.cos(), cy + radius * a.sin()]
        })
        .collect()
}

/// A vertical cylinder of `radius` from `z0` to `z1` centred on `(cx, cy)` (flat-shaded sides).
pub fn cylinder_mesh(cx: f64, cy: f64, radius: f64, z0: f64, z1: f64, segments: usize) -> TriMesh {
    prism_mesh(&circle_ring(cx, cy, radius, segments), z0, z1)
}

/// A surface of revolution about +Z through the profile `(radius, z)` points, smooth-shaded.
///
/// The profile runs from the outer bottom around to wherever it ends; a closed solid such as a
/// mug is described by walking outside-bottom -> outside-top -> rim -> inside-top ->
/// inside-bottom -> axis. Profile points on the axis (radius 0) close the surface.
pub fn lathe_mesh(profile: &[(f64, f64)], segments: usize) -> TriMesh {
    let segments = segments.max(3);
    let mut m = TriMesh::new();
    if profile.len() < 2 {
        return m;
    }
    // Each profile edge becomes its own band so creases (rim, base) stay sharp.
    for w in profile.windows(2) {
        let (r0, z0) = w[0];
        let (r1, z1) = w[1];
        // Outward normal in the (r, z) half-plane for a profile walked counter-clockwise.
        let (dr, dz) = (r1 - r0, z1 - z0);
        let len = (dr * dr + dz * dz).sqrt();
        if len < 1e-12 {
            continue;
        }
        let (nr, nz) = (dz / len, -dr / len);
        let base = m.positions.len() as u32;
        for i in 0..=segments {
            let a = std::f64::consts::TAU * (i % segments) as f64 / segments as f64;
            let (c, s) = (a.cos(), a.sin());
            m.positions.push([r0 * c, r0 * s, z0]);
            m.normals.push([nr * c, nr * s, nz]);
            m.positions.push([r1 * c, r1 * s, z1]);
            m.normals.push([nr * c, nr * s, nz]);
        }
        for i in 0..segments as u32 {
            let a0 = base + 2 * i;
            let a1 = a0 + 1;
            let b0 = a0 + 2;
            let b1 = a0 + 3;
            // Skip degenerate triangles at the axis.
            if r0 > 1e-12 {
                m.triangles.push([a0, b0, b1]);
            }
            if r1 > 1e-12 {
                m.triangles.push([a0, b1, a1]);
            }
        }
    }
    m
}

/// Signed volume enclosed by a closed, outward-wound mesh (divergence theorem).
pub fn enclosed_volume(mesh: &TriMesh) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let a = Vector3::from(mesh.positions[t[0] as usize]);
            let b = Vector3::from(mesh.positions[t[1] as usize]);
            let c = Vector3::from(mesh.positions[t[2] as usize]);
            a.dot(&b.cross(&c)) / 6.0
        })
        .sum()
}

/// Recomputes smooth per-vertex normals as area-weighted face normals.
pub fn recompute_normals(mesh: &mut TriMesh) {
    let mut acc = vec![Vector3::zeros(); mesh.positions.len()];
    for t in &mesh.triangles {
        let p = t.map(|i| Vector3::from(mesh.positions[i as usize]));
        let n = (p[1] - p[0]).cross(&(p[2] - p[0]));
        for &i in t {
            acc[i as usize] += n;
        }
    }
    mesh.normals = acc
        .into_iter()
        .map(|n| {
            let n = n.try_normalize(1e-20).unwrap_or(Vector3::z());
            [n.x, n.y, n.z]
        })
        .collect();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_volume_and_bounds() {
        let m = box_mesh([0.0, 0.0, 0.5], [2.0, 3.0, 1.0]);
        assert!((enclosed_volume(&m) - 6.0).abs() < 1e-12);
        let (lo, hi) = m.bounds().unwrap();
        assert_eq!(lo, [-1.0, -1.5, 0.0]);
        assert_eq!(hi, [1.0, 1.5, 1.0]);
    }

    #[test]
    fn prism_is_outward_wound() {
        let m = cylinder_mesh(0.0, 0.0, 1.0, 0.0, 2.0, 64);
        let v = enclosed_volume(&m);
        let exact = std::f64::consts::PI * 2.0;
        assert!(v > 0.0 && (v - exact).abs() / exact < 0.01, "{v}");
    }

    #[test]
    fn lathe_cup_encloses_its_shell() {
        // Cup: outer radius 1, inner 0.9, height 1, base 0.1 thick.
        let profile = [
            (0.0, 0.0),
            (1.0, 0.0),
            (1.0, 1.0),
            (0.9, 1.0),
            (0.9, 0.1),
            (0.0, 0.1),
        ];
        let m = lathe_mesh(&profile, 128);
        let v = enclosed_volume(&m);
        let pi = std::f64::consts::PI;
        let exact = pi * 1.0 * 1.0 - pi * 0.81 * 0.9;
        assert!((v - exact).abs() / exact < 0.01, "{v} vs {exact}");
    }
}
