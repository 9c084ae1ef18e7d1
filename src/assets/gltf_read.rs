//! glTF 2.0 reader into an asset's visual parts (`.gltf` with external or `data:` buffers, and
//! `.glb`): triangle meshes with node transforms baked in, converted from glTF's +Y up to the project's +Z up, with
//! base colours and PNG base-colour textures.
//!
//! Reads what this project writes and the common output of other tools; anything outside
//! that (sparse accessors, non-triangle modes, JPEG textures) is reported or skipped, never a
//! panic.

use std::path::Path;

use nalgebra::{Matrix4, Quaternion, UnitQuaternion, Vector3, Vector4};
use serde_json::Value;

use crate::assets::{Texture, VisualPart};
use crate::geometry::TriMesh;

type R<T> = Result<T, String>;

/// Reads a `.gltf` or `.glb` file.
pub fn read_file(path: &Path) -> R<Vec<VisualPart>> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let base = path.parent().unwrap_or(Path::new("."));
    parse(&bytes, Some(base)).map_err(|e| format!("{}: {e}", path.display()))
}

/// Parses glTF JSON or GLB bytes; external URIs resolve against `base`.
pub fn parse(bytes: &[u8], base: Option<&Path>) -> R<Vec<VisualPart>> {
    let (doc, glb_bin) = if bytes.starts_with(b"glTF") {
        split_glb(bytes)?
    } else {
        let doc: Value =
            serde_json::from_slice(bytes).map_err(|e| format!("not glTF JSON: {e}"))?;
        (doc, None)
    };
    let buffers = load_buffers(&doc, glb_bin, base)?;
    let reader = Reader {
        doc: &doc,
        buffers,
        base,
    };
    let mut parts = Vec::new();
    let scene_nodes: Vec<usize> =
        match doc["scenes"].get(doc["scene"].as_u64().unwrap_or(0) as usize) {
            Some(s) => s["nodes"]
                .as_array()
                .map(|a| {
                    a.iter()
                        .filter_map(|v| v.as_u64().map(|u| u as usize))
                        .collect()
                })
                .unwrap_or_default(),
            // No scene: every root-less node is a root.
            None => (0..doc["nodes"].as_array().map_or(0, |a| a.len())).collect(),
        };
    if scene_nodes.is_empty() && doc["meshes"].as_array().is_some_and(|m| !m.is_empty()) {
        for m in 0..doc["meshes"].as_array().map_or(0, |a| a.len()) {
            reader.mesh(m, &Matrix4::identity(), &mut parts)?;
        }
    }
    for n in scene_nodes {
        reader.node(n, &Matrix4::identity(), &mut parts, 0)?;
    }
    if parts.is_empty() {
        return Err("no triangle meshes".into());
    }
    Ok(parts)
}

fn split_glb(bytes: &[u8]) -> R<(Value, Option<Vec<u8>>)> {
    let u32_at = |i: usize| -> R<u32> {
        bytes
            .get(i..i + 4)
            .and_then(|b| b.try_into().ok())
            .map(u32::from_le_bytes)
            .ok_or_else(|| "truncated GLB".to_string())
    };
    let total = u32_at(8)? as usize;
    if total > bytes.len() {
        return Err("GLB length field exceeds the file".into());
    }
    let mut at = 12;
    let mut json = None;
    let mut bin = None;
    while at + 8 <= total {
        let len = u32_at(at)? as usize;
        let kind = u32_at(at + 4)?;
        let chunk = bytes
            .get(at + 8..at + 8 + len)
            .ok_or("GLB chunk exceeds the file")?;
        match kind {
            0x4E4F_534A => {
                json = Some(serde_json::from_slice(chunk).map_err(|e| format!("GLB JSON: {e}"))?)
            }
            0x004E_4942 => bin = Some(chunk.to_vec()),
            _ => {}
        }
        at += 8 + len;
    }
    Ok((json.ok_or("GLB without JSON chunk")?, bin))
}

fn load_uri(uri: &str, base: Option<&Path>) -> R<Vec<u8>> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, data) = rest
            .split_once(";base64,")
            .ok_or("data URI is not base64")?;
        return crate::util::base64::decode(data);
    }
    if uri.contains("..") || uri.starts_with('/') || uri.contains("://") {
        return Err(format!("refusing URI {uri:?} outside the model's folder"));
    }
    let base = base.ok_or("external URI without a base folder")?;
    std::fs::read(base.join(uri)).map_err(|e| format!("{uri}: {e}"))
}

fn load_buffers(doc: &Value, glb_bin: Option<Vec<u8>>, base: Option<&Path>) -> R<Vec<Vec<u8>>> {
    let mut out = Vec::new();
    let mut glb_bin = glb_bin;
    for b in doc["buffers"].as_array().cloned().unwrap_or_default() {
        let data = match b["uri"].as_str() {
            Some(uri) => load_uri(uri, base)?,
            None => glb_bin
                .take()
                .ok_or("buffer without URI and no GLB binary chunk")?,
        };
        out.push(data);
    }
    Ok(out)
}

/// `Some(())` when `count` elements of `elem` bytes, `stride` apart from `off`, lie within
/// `len` bytes (overflow-checked).
fn fits(count: usize, off: usize, stride: usize, elem: usize, len: usize) -> Option<()> {
    if count == 0 {
        return Some(());
    }
    let end = (count - 1)
        .checked_mul(stride)?
        .checked_add(off)?
        .checked_add(elem)?;
    (end <= len).then_some(())
}

struct Reader<'a> {
    doc: &'a Value,
    buffers: Vec<Vec<u8>>,
    base: Option<&'a Path>,
}

impl Reader<'_> {
    fn view_bytes(&self, view: usize) -> R<(&[u8], usize)> {
        let v = &self.doc["bufferViews"][view];
        let buf = self
            .buffers
            .get(v["buffer"].as_u64().ok_or("bufferView without buffer")? as usize)
            .ok_or("bufferView names a missing buffer")?;
        let off = v["byteOffset"].as_u64().unwrap_or(0) as usize;
        let len = v["byteLength"]
            .as_u64()
            .ok_or("bufferView without length")? as usize;
        let bytes = buf
            .get(off..off + len)
            .ok_or("bufferView exceeds its buffer")?;
        Ok((bytes, v["byteStride"].as_u64().unwrap_or(0) as usize))
    }

    /// Accessor as rows of f64 (`n` components each).
    fn floats(&self, acc: usize, n: usize) -> R<Vec<Vec<f64>>> {
        let a = &self.doc["accessors"][acc];
        let count = a["count"].as_u64().ok_or("accessor without count")? as usize;
        let view = a["bufferView"]
            .as_u64()
            .ok_or("accessor without bufferView (sparse?)")?;
        let (bytes, stride) = self.view_bytes(view as usize)?;
        let off = a["byteOffset"].as_u64().unwrap_or(0) as usize;
        let ctype = a["componentType"].as_u64().unwrap_or(0);
        let size = match ctype {
            5126 => 4,
            5121 => 1,
            5123 => 2,
            _ => return Err(format!("unsupported float component type {ctype}")),
        };
        let stride = if stride == 0 { size * n } else { stride };
        let norm = a["normalized"].as_bool().unwrap_or(false);
        // The count comes from the file: check it against the bytes there before allocating.
        fits(count, off, stride, size * n, bytes.len()).ok_or("accessor exceeds its view")?;
        let mut rows = Vec::with_capacity(count);
        for i in 0..count {
            let mut row = Vec::with_capacity(n);
            for k in 0..n {
                let at = off + i * stride + k * size;
                let b = bytes
                    .get(at..at + size)
                    .ok_or("accessor exceeds its view")?;
                let v = match ctype {
                    5126 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
                    5121 => f64::from(b[0]) / if norm { 255.0 } else { 1.0 },
                    _ => {
                        f64::from(u16::from_le_bytes([b[0], b[1]]))
                            / if norm { 65535.0 } else { 1.0 }
                    }
                };
                if !v.is_finite() {
                    return Err("non-finite vertex data".into());
                }
                row.push(v);
            }
            rows.push(row);
        }
        Ok(rows)
    }

    fn indices(&self, acc: usize, vertices: usize) -> R<Vec<u32>> {
        let a = &self.doc["accessors"][acc];
        let count = a["count"].as_u64().ok_or("accessor without count")? as usize;
        let view = a["bufferView"]
            .as_u64()
            .ok_or("index accessor without bufferView")?;
        let (bytes, _) = self.view_bytes(view as usize)?;
        let off = a["byteOffset"].as_u64().unwrap_or(0) as usize;
        let size = match a["componentType"].as_u64() {
            Some(5121) => 1,
            Some(5123) => 2,
            Some(5125) => 4,
            other => return Err(format!("unsupported index type {other:?}")),
        };
        fits(count, off, size, size, bytes.len()).ok_or("index accessor exceeds its view")?;
        let mut out = Vec::with_capacity(count);
        for i in 0..count {
            let at = off + i * size;
            let b = bytes
                .get(at..at + size)
                .ok_or("index accessor exceeds its view")?;
            let v = match size {
                1 => u32::from(b[0]),
                2 => u32::from(u16::from_le_bytes([b[0], b[1]])),
                _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            };
            if v as usize >= vertices {
                return Err(format!("index {v} out of range ({vertices} vertices)"));
            }
            out.push(v);
        }
        Ok(out)
    }

    fn node(
        &self,
        n: usize,
        parent: &Matrix4<f64>,
        parts: &mut Vec<VisualPart>,
        depth: usize,
    ) -> R<()> {
        if depth > 64 {
            return Err("node hierarchy deeper than 64 (a cycle?)".into());
        }
        let node = &self.doc["nodes"][n];
        let local = node_matrix(node)?;
        let world = parent * local;
        if let Some(m) = node["mesh"].as_u64() {
            self.mesh(m as usize, &world, parts)?;
        }
        for c in node["children"].as_array().cloned().unwrap_or_default() {
            if let Some(c) = c.as_u64() {
                self.node(c as usize, &world, parts, depth + 1)?;
            }
        }
        Ok(())
    }

    fn mesh(&self, m: usize, world_yup: &Matrix4<f64>, parts: &mut Vec<VisualPart>) -> R<()> {
        let mesh = &self.doc["meshes"][m];
        let name = mesh["name"].as_str().unwrap_or("mesh").to_string();
        // Y-up glTF world to Z-up: (x, y, z) -> (x, -z, y).
        let zup_from_yup = Matrix4::new(
            1.0, 0.0, 0.0, 0.0, //
            0.0, 0.0, -1.0, 0.0, //
            0.0, 1.0, 0.0, 0.0, //
            0.0, 0.0, 0.0, 1.0,
        );
        let xf = zup_from_yup * world_yup;
        let normal_xf = xf
            .fixed_view::<3, 3>(0, 0)
            .try_inverse()
            .map(|m| m.transpose())
            .unwrap_or_else(nalgebra::Matrix3::identity);
        for (pi, prim) in mesh["primitives"]
            .as_array()
            .cloned()
            .unwrap_or_default()
            .iter()
            .enumerate()
        {
            if prim["mode"].as_u64().unwrap_or(4) != 4 {
                continue;
            }
            let attrs = &prim["attributes"];
            let pos_acc = attrs["POSITION"]
                .as_u64()
                .ok_or("primitive without POSITION")? as usize;
            let pos = self.floats(pos_acc, 3)?;
            let mut tm = TriMesh::new();
            for p in &pos {
                let q = xf * Vector4::new(p[0], p[1], p[2], 1.0);
                tm.positions.push([q.x, q.y, q.z]);
            }
            let idx = match prim["indices"].as_u64() {
                Some(a) => self.indices(a as usize, pos.len())?,
                None => (0..pos.len() as u32).collect(),
            };
            let flip = xf.fixed_view::<3, 3>(0, 0).determinant() < 0.0;
            for t in idx.chunks_exact(3) {
                tm.triangles.push(if flip {
                    [t[0], t[2], t[1]]
                } else {
                    [t[0], t[1], t[2]]
                });
            }
            match attrs["NORMAL"].as_u64() {
                Some(a) => {
                    for n in self.floats(a as usize, 3)? {
                        let v = (normal_xf * Vector3::new(n[0], n[1], n[2]))
                            .try_normalize(1e-20)
                            .unwrap_or(Vector3::z());
                        tm.normals.push([v.x, v.y, v.z]);
                    }
                }
                None => crate::geometry::mesh::recompute_normals(&mut tm),
            }
            if let Some(a) = attrs["TEXCOORD_0"].as_u64() {
                tm.uvs = self
                    .floats(a as usize, 2)?
                    .into_iter()
                    .map(|r| [r[0], r[1]])
                    .collect();
            }
            let (color, texture) = self.material(prim["material"].as_u64());
            let tm_has_uvs = tm.uvs.len() == tm.positions.len();
            parts.push(VisualPart {
                name: format!("{name}_{pi}"),
                mesh: tm,
                color,
                // A texture is only usable with texture coordinates.
                texture: texture.filter(|_| tm_has_uvs),
            });
        }
        Ok(())
    }

    fn material(&self, m: Option<u64>) -> ([f64; 4], Option<Texture>) {
        let Some(m) = m else {
            return ([0.8, 0.8, 0.8, 1.0], None);
        };
        let pbr = &self.doc["materials"][m as usize]["pbrMetallicRoughness"];
        let mut color = [1.0; 4];
        if let Some(f) = pbr["baseColorFactor"].as_array() {
            for (i, v) in f.iter().take(4).enumerate() {
                color[i] = v.as_f64().unwrap_or(1.0).clamp(0.0, 1.0);
            }
        }
        let texture = pbr["baseColorTexture"]["index"]
            .as_u64()
            .and_then(|t| self.texture(t as usize).ok());
        (color, texture)
    }

    fn texture(&self, t: usize) -> R<Texture> {
        let src = self.doc["textures"][t]["source"]
            .as_u64()
            .ok_or("texture without source")? as usize;
        let image = &self.doc["images"][src];
        let bytes = match (image["uri"].as_str(), image["bufferView"].as_u64()) {
            (Some(uri), _) => load_uri(uri, self.base)?,
            (None, Some(v)) => self.view_bytes(v as usize)?.0.to_vec(),
            _ => return Err("image without data".into()),
        };
        let (width, height, rgba) = crate::util::png::decode_rgba(&bytes)?;
        Ok(Texture {
            name: image["name"]
                .as_str()
                .map(crate::scene::sanitize_name)
                .unwrap_or_else(|| format!("texture_{src}")),
            width,
            height,
            rgba: std::sync::Arc::new(rgba),
        })
    }
}

fn node_matrix(node: &Value) -> R<Matrix4<f64>> {
    if let Some(m) = node["matrix"].as_array() {
        let v: Vec<f64> = m.iter().filter_map(Value::as_f64).collect();
        if v.len() != 16 {
            return Err("node matrix must have 16 numbers".into());
        }
        // glTF matrices are column-major.
        return Ok(Matrix4::from_column_slice(&v));
    }
    let get = |key: &str, n: usize, default: &[f64]| -> Vec<f64> {
        node[key]
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_f64).collect::<Vec<_>>())
            .filter(|v| v.len() == n)
            .unwrap_or_else(|| default.to_vec())
    };
    let t = get("translation", 3, &[0.0, 0.0, 0.0]);
    let r = get("rotation", 4, &[0.0, 0.0, 0.0, 1.0]);
    let s = get("scale", 3, &[1.0, 1.0, 1.0]);
    let q = UnitQuaternion::from_quaternion(Quaternion::new(r[3], r[0], r[1], r[2]));
    let mut m = q.to_homogeneous();
    for c in 0..3 {
        for row in 0..3 {
            m[(row, c)] *= s[c];
        }
    }
    m[(0, 3)] = t[0];
    m[(1, 3)] = t[1];
    m[(2, 3)] = t[2];
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn garbage_is_an_error() {
        assert!(parse(b"glTF\x02\x00\x00\x00\xff\xff\xff\xff", None).is_err());
        assert!(parse(b"{\"asset\":{}}", None).is_err());
        assert!(parse(b"not json", None).is_err());
    }
}
