//! Approximate convex decomposition (V-HACD, parry3d's implementation) of imported meshes,
//! capped at the hull budget of the asset's support class.

use parry3d_f64::math::Vector as PVec;
use parry3d_f64::transformation::vhacd::{VHACD, VHACDParameters};

use crate::geometry::{ConvexPiece, TriMesh};

/// Decomposition settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VhacdOptions {
    /// Voxel resolution along the longest axis (cost grows about 4x per doubling).
    pub resolution: u32,
    /// Largest concavity (relative) a hull may keep.
    pub concavity: f64,
    /// Hull budget.
    pub max_hulls: u32,
}

impl Default for VhacdOptions {
    fn default() -> Self {
        VhacdOptions {
            resolution: 64,
            concavity: 0.01,
            max_hulls: 64,
        }
    }
}

/// Convex pieces approximating the volume enclosed by `mesh` (vertex positions welded first).
/// Hulls are built from the mesh's own vertices clipped to each part (exact hulls), so they
/// hug the surface instead of the voxels. Empty when the mesh encloses no volume.
pub fn decompose(mesh: &TriMesh, opts: VhacdOptions) -> Vec<ConvexPiece> {
    let points: Vec<PVec> = mesh
        .positions
        .iter()
        .map(|p| PVec::new(p[0], p[1], p[2]))
        .collect();
    if points.len() < 4 || mesh.triangles.is_empty() {
        return Vec::new();
    }
    let params = VHACDParameters {
        resolution: opts.resolution.max(8),
        concavity: opts.concavity,
        max_convex_hulls: opts.max_hulls.max(1),
        ..VHACDParameters::default()
    };
    let decomposition = VHACD::decompose(&params, &points, &mesh.triangles, true);
    let hulls: Vec<ConvexPiece> = decomposition
        .compute_exact_convex_hulls(&points, &mesh.triangles)
        .into_iter()
        .filter_map(|(verts, _)| {
            let pts: Vec<[f64; 3]> = verts.iter().map(|v| [v.x, v.y, v.z]).collect();
            ConvexPiece::from_points(&pts).ok()
        })
        .collect();
    let mut merged = merge_convex_neighbours(hulls, 0.01);
    merged.truncate(opts.max_hulls as usize);
    merged
}

/// Relative volume a merge may add: hull(a U b) versus a + b.
fn merge_excess(a: &ConvexPiece, b: &ConvexPiece) -> Option<(f64, ConvexPiece)> {
    let (alo, ahi) = a.bounds();
    let (blo, bhi) = b.bounds();
    let gap = (0..3)
        .map(|i| (blo[i] - ahi[i]).max(alo[i] - bhi[i]))
        .fold(f64::MIN, f64::max);
    let scale = (0..3)
        .map(|i| (ahi[i] - alo[i]).max(bhi[i] - blo[i]))
        .fold(0.0, f64::max);
    if gap > 1e-3 * scale.max(1e-6) {
        return None;
    }
    let pts: Vec<[f64; 3]> = a.vertices.iter().chain(&b.vertices).copied().collect();
    let hull = ConvexPiece::from_points(&pts).ok()?;
    let sum = a.volume() + b.volume();
    Some(((hull.volume() - sum) / sum.max(1e-18), hull))
}

/// Greedily merges touching pieces whose union is (within `tol` of its volume) convex:
/// V-HACD's voxel concavity measure over-splits flat-sided shapes (a box comes back in
/// several slabs); merging restores one hull per convex part and frees hull budget.
pub fn merge_convex_neighbours(mut pieces: Vec<ConvexPiece>, tol: f64) -> Vec<ConvexPiece> {
    loop {
        let mut best: Option<(f64, usize, usize, ConvexPiece)> = None;
        for i in 0..pieces.len() {
            for j in i + 1..pieces.len() {
                if let Some((excess, hull)) = merge_excess(&pieces[i], &pieces[j])
                    && excess <= tol
                    && best.as_ref().is_none_or(|b| excess < b.0)
                {
                    best = Some((excess, i, j, hull));
                }
            }
        }
        let Some((_, i, j, hull)) = best else {
            return pieces;
        };
        pieces.swap_remove(j);
        pieces[i] = hull;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::mesh;

    #[test]
    fn an_l_shape_splits_and_a_box_does_not() {
        let mut l = mesh::box_mesh([0.0, 0.0, 0.5], [2.0, 1.0, 1.0]);
        l.append(&mesh::box_mesh([-0.5, 0.0, 1.5], [1.0, 1.0, 1.0]));
        // Weld the duplicate corners so the union is one closed surface for voxelisation.
        let pieces = decompose(
            &l,
            VhacdOptions {
                resolution: 32,
                ..Default::default()
            },
        );
        assert!(pieces.len() >= 2, "{} pieces", pieces.len());
        let total: f64 = pieces.iter().map(|p| p.volume()).sum();
        assert!(total > 2.5 && total < 3.6, "volume {total}");
        let b = decompose(
            &mesh::box_mesh([0.0; 3], [1.0, 1.0, 1.0]),
            VhacdOptions {
                resolution: 32,
                ..Default::default()
            },
        );
        assert_eq!(b.len(), 1);
        assert!((b[0].volume() - 1.0).abs() < 1e-6);
        let capped = decompose(
            &l,
            VhacdOptions {
                resolution: 32,
                max_hulls: 1,
                ..Default::default()
            },
        );
        assert_eq!(capped.len(), 1);
    }
}
