//! Wavefront OBJ for convex collision pieces (read by Drake with `drake:declare_convex`, by
//! MuJoCo as mesh geoms, and by most tools).

use std::fmt::Write;

use crate::geometry::{ConvexPiece, TriMesh};

/// OBJ text of a convex piece (positions at micrometre precision, 1-based faces).
pub fn convex_to_obj(piece: &ConvexPiece) -> String {
    mesh_to_obj(&piece.vertices, &piece.triangles, None)
}

/// A convex piece from the OBJ text [`convex_to_obj`] writes, keeping its vertex order and
/// triangles, so a piece read back writes the same bytes (and Drake, which hulls the file,
/// sees the same file). Other OBJ text (no faces, polygons, `v/vt/vn` corners) is re-hulled.
pub fn parse_convex_obj(text: &str) -> Result<ConvexPiece, String> {
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    let mut exact = true;
    for line in text.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let xyz: Vec<f64> = it.filter_map(|t| t.parse().ok()).collect();
                let [x, y, z] = xyz[..] else {
                    return Err(format!("bad vertex line {line:?}"));
                };
                vertices.push([x, y, z]);
            }
            Some("f") => {
                let idx: Vec<Option<u32>> = it
                    .map(|t| t.parse::<u32>().ok().and_then(|i| i.checked_sub(1)))
                    .collect();
                match idx[..] {
                    [Some(a), Some(b), Some(c)] => triangles.push([a, b, c]),
                    _ => exact = false,
                }
            }
            _ => {}
        }
    }
    let n = vertices.len() as u32;
    if exact && !triangles.is_empty() && triangles.iter().flatten().all(|i| *i < n) {
        let piece = ConvexPiece {
            vertices,
            triangles,
        };
        if piece.volume() > 0.0 {
            return Ok(piece);
        }
        return ConvexPiece::from_points(&piece.vertices).map_err(|e| e.to_string());
    }
    ConvexPiece::from_points(&vertices).map_err(|e| e.to_string())
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

/// A mesh read from OBJ text: positions, triangles and (when every face corner has them)
/// normals and texture coordinates, un-indexed per corner into a [`TriMesh`].
pub fn parse_obj(text: &str) -> Result<TriMesh, String> {
    let mut v: Vec<[f64; 3]> = Vec::new();
    let mut vn: Vec<[f64; 3]> = Vec::new();
    let mut vt: Vec<[f64; 2]> = Vec::new();
    // Corner keys (v, vt, vn) -> output vertex, so shared corners stay shared.
    let mut corners: std::collections::HashMap<(usize, Option<usize>, Option<usize>), u32> =
        std::collections::HashMap::new();
    let mut mesh = TriMesh::new();
    let mut all_normals = true;
    let mut all_uvs = true;
    let resolve = |idx: &str, len: usize, line: usize| -> Result<usize, String> {
        let i: i64 = idx
            .parse()
            .map_err(|_| format!("line {line}: bad index {idx:?}"))?;
        let k = if i < 0 { len as i64 + i } else { i - 1 };
        if k < 0 || k as usize >= len {
            return Err(format!("line {line}: index {i} out of range (have {len})"));
        }
        Ok(k as usize)
    };
    let nums = |parts: &[&str], n: usize, line: usize| -> Result<Vec<f64>, String> {
        let vals: Vec<f64> = parts
            .iter()
            .take(n)
            .map(|p| p.parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect::<Option<_>>()
            .ok_or_else(|| format!("line {line}: bad number"))?;
        if vals.len() < n {
            return Err(format!("line {line}: expected {n} numbers"));
        }
        Ok(vals)
    };
    for (ln, raw) in text.lines().enumerate() {
        let line = ln + 1;
        let parts: Vec<&str> = raw.split_whitespace().collect();
        match parts.first().copied() {
            Some("v") => {
                let p = nums(&parts[1..], 3, line)?;
                v.push([p[0], p[1], p[2]]);
            }
            Some("vn") => {
                let p = nums(&parts[1..], 3, line)?;
                vn.push([p[0], p[1], p[2]]);
            }
            Some("vt") => {
                let p = nums(&parts[1..], 2, line)?;
                // OBJ's v runs upward; glTF's (ours) runs downward.
                vt.push([p[0], 1.0 - p[1]]);
            }
            Some("f") => {
                let mut face: Vec<u32> = Vec::new();
                for c in &parts[1..] {
                    let mut it = c.split('/');
                    let vi = resolve(it.next().unwrap_or(""), v.len(), line)?;
                    let ti = match it.next() {
                        Some(s) if !s.is_empty() => Some(resolve(s, vt.len(), line)?),
                        _ => None,
                    };
                    let ni = match it.next() {
                        Some(s) if !s.is_empty() => Some(resolve(s, vn.len(), line)?),
                        _ => None,
                    };
                    all_uvs &= ti.is_some();
                    all_normals &= ni.is_some();
                    let key = (vi, ti, ni);
                    let id = *corners.entry(key).or_insert_with(|| {
                        mesh.positions.push(v[vi]);
                        mesh.normals
                            .push(ni.map(|n| vn[n]).unwrap_or([0.0, 0.0, 0.0]));
                        mesh.uvs.push(ti.map(|t| vt[t]).unwrap_or([0.0, 0.0]));
                        (mesh.positions.len() - 1) as u32
                    });
                    face.push(id);
                }
                if face.len() < 3 {
                    return Err(format!("line {line}: face with fewer than 3 corners"));
                }
                for k in 1..face.len() - 1 {
                    mesh.triangles.push([face[0], face[k], face[k + 1]]);
                }
            }
            _ => {}
        }
    }
    if mesh.triangles.is_empty() {
        // A file with vertices only (a point cloud for a hull) keeps its points.
        if !v.is_empty() {
            mesh.positions = v;
            mesh.normals = vec![[0.0, 0.0, 1.0]; mesh.positions.len()];
            mesh.uvs.clear();
            return Ok(mesh);
        }
        return Err("no vertices or faces".into());
    }
    if !all_uvs {
        mesh.uvs.clear();
    }
    if !all_normals {
        crate::geometry::mesh::recompute_normals(&mut mesh);
    }
    Ok(mesh)
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

#[cfg(test)]
mod parse_tests {
    use super::*;

    #[test]
    fn convex_piece_round_trips() {
        let c = ConvexPiece::cuboid([0.1, 0.2, 0.3], [0.4, 0.5, 0.6]).unwrap();
        let m = parse_obj(&convex_to_obj(&c)).unwrap();
        let back = ConvexPiece::from_points(&m.positions).unwrap();
        assert!((back.volume() - c.volume()).abs() < 1e-9);
    }

    #[test]
    fn quads_negative_indices_and_uvs() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf -4/1 -3/2 -2/3 -1/4\n";
        let m = parse_obj(text).unwrap();
        assert_eq!(m.triangles.len(), 2);
        assert_eq!(m.uvs.len(), 4);
        assert_eq!(m.uvs[0], [0.0, 1.0]);
        // Normals recomputed facing +Z for a counter-clockwise quad.
        assert!((m.normals[0][2] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn broken_obj_is_an_error_not_a_panic() {
        assert!(parse_obj("f 1 2 3\n").is_err());
        assert!(parse_obj("v 0 0 nan\n").is_err());
        assert!(parse_obj("").is_err());
        assert!(parse_obj("v 0 0 0\nv 1 0 0\nf 1 2\n").is_err());
    }
}
