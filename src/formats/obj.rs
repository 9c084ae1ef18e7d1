//! Wavefront OBJ for convex collision pieces (read by Drake with `drake:declare_convex`, by
//! MuJoCo as mesh geoms, and by most tools).

use std::fmt::Write;

use crate::geometry::{ConvexPiece, TriMesh};

/// OBJ text of a convex piece (positions at micrometre precision, 1-based faces).
pub fn convex_to_obj(piece: &ConvexPiece) -> String {
    mesh_to_obj(&piece.vertices, &piece.triangles, None)
}

/// OBJ text of a triangle mesh with normals.
pub fn trimesh_to_obj(mesh: &TriMesh) -> String {
    mesh_to_obj(&mesh.positions, &mesh.triangles, Some(&mesh.normals))
}

fn mesh_to_obj(
    positions: &[[f64; 3]],
    triangles: &[[u32; 3]],
    normals: Option<&[[f64; 3]]>,
) -> String {
    let mut out = String::with_capacity(positions.len() * 40 + triangles.len() * 24);
    out.push_str("# scenesmith\n");
    for v in positions {
        let _ = writeln!(out, "v {:.6} {:.6} {:.6}", v[0], v[1], v[2]);
    }
    if let Some(ns) = normals {
        for n in ns {
            let _ = writeln!(out, "vn {:.6} {:.6} {:.6}", n[0], n[1], n[2]);
        }
        for t in triangles {
            let (a, b, c) = (t[0] + 1, t[1] + 1, t[2] + 1);
            let _ = writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}");
        }
    } else {
        for t in triangles {
            let _ = writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_obj_has_8_vertices_and_12_faces() {
        let c = ConvexPiece::cuboid([0.0; 3], [1.0; 3]).unwrap();
        let text = convex_to_obj(&c);
        assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 8);
        assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 12);
        assert!(
            !text.contains(" 0 ")
                || !text
                    .lines()
                    .any(|l| l.starts_with("f ") && l.contains(" 0"))
        );
    }
}
