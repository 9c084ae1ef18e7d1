//! glTF 2.0 writer for visual meshes: per-link `.gltf` + `.bin` files that Drake reads as
//! visual geometry, and whole-scene binary GLB files.
//!
//! glTF is +Y up; the project is +Z up. Vertices are stored in glTF's convention
//! (`(x, y, z)_zup -> (x, z, -y)_yup`), which Drake undoes when it loads a glTF file.

use serde_json::{Value, json};

use crate::assets::VisualPart;
use crate::scene::Pose;

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;

/// Accumulates meshes, materials, textures and nodes, then writes `.gltf` or `.glb`.
#[derive(Debug, Default)]
pub struct GltfBuilder {
    bin: Vec<u8>,
    buffer_views: Vec<Value>,
    accessors: Vec<Value>,
    meshes: Vec<Value>,
    materials: Vec<Value>,
    material_keys: Vec<([u32; 4], Option<String>)>,
    images: Vec<Value>,
    textures: Vec<Value>,
    texture_names: Vec<String>,
    /// PNG files referenced by URI (when not embedding), `(file name, bytes)`.
    image_files: Vec<(String, Vec<u8>)>,
    embed_images: bool,
    samplers_used: bool,
    nodes: Vec<Value>,
    roots: Vec<usize>,
}

/// Z-up point or direction to glTF's Y-up.
fn to_y_up(v: [f64; 3]) -> [f32; 3] {
    [v[0] as f32, v[2] as f32, -v[1] as f32]
}

impl GltfBuilder {
    /// An empty builder whose textures become separate PNG files (for `.gltf`).
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty builder whose textures are embedded in the binary buffer (for `.glb`).
    pub fn new_embedded() -> Self {
        GltfBuilder {
            embed_images: true,
            ..Self::default()
        }
    }

    /// PNG files the `.gltf` refers to, `(file name, bytes)`; empty when embedding.
    pub fn image_files(&self) -> &[(String, Vec<u8>)] {
        &self.image_files
    }

    fn texture(&mut self, tex: &crate::assets::Texture) -> Option<usize> {
        if let Some(i) = self.texture_names.iter().position(|n| *n == tex.name) {
            return Some(i);
        }
        let png = crate::util::png::encode_rgba(tex.width, tex.height, &tex.rgba).ok()?;
        let image = if self.embed_images {
            let view = self.push_view_untargeted(&png);
            json!({"bufferView": view, "mimeType": "image/png", "name": tex.name})
        } else {
            let file = format!("{}.png", crate::scene::sanitize_name(&tex.name));
            self.image_files.push((file.clone(), png));
            json!({"uri": file, "name": tex.name})
        };
        // One repeating, linearly filtered sampler serves every texture.
        self.samplers_used = true;
        self.images.push(image);
        self.textures
            .push(json!({"source": self.images.len() - 1, "sampler": 0}));
        self.texture_names.push(tex.name.clone());
        Some(self.textures.len() - 1)
    }

    fn push_view_untargeted(&mut self, bytes: &[u8]) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.buffer_views
            .push(json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()}));
        self.buffer_views.len() - 1
    }

    fn push_view(&mut self, bytes: &[u8], target: u32) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.buffer_views.push(json!({
            "buffer": 0, "byteOffset": offset, "byteLength": bytes.len(), "target": target
        }));
        self.buffer_views.len() - 1
    }

    fn material(&mut self, color: [f64; 4], texture: Option<usize>) -> usize {
        let key = (
            color.map(|c| (c.clamp(0.0, 1.0) * 1e4).round() as u32),
            texture.map(|t| self.texture_names[t].clone()),
        );
        if let Some(i) = self.material_keys.iter().position(|k| *k == key) {
            return i;
        }
        let c = color.map(|c| ((c.clamp(0.0, 1.0) * 1e4).round() / 1e4) as f32);
        let mut m = json!({
            "name": format!("color_{}", self.materials.len()),
            "pbrMetallicRoughness": {
                "baseColorFactor": c,
                "metallicFactor": 0.0,
                "roughnessFactor": 0.8
            },
            "doubleSided": false
        });
        if c[3] < 1.0 {
            m["alphaMode"] = json!("BLEND");
        }
        if let Some(t) = texture {
            m["pbrMetallicRoughness"]["baseColorTexture"] = json!({"index": t, "texCoord": 0});
        }
        self.materials.push(m);
        self.material_keys.push(key);
        self.materials.len() - 1
    }

    /// Adds one mesh whose primitives are `parts` (one primitive per part, with its colour).
    /// Returns the mesh index.
    pub fn add_mesh(&mut self, name: &str, parts: &[VisualPart]) -> usize {
        let mut primitives = Vec::new();
        for part in parts.iter().filter(|p| !p.mesh.is_empty()) {
            let pos: Vec<[f32; 3]> = part.mesh.positions.iter().map(|p| to_y_up(*p)).collect();
            let nrm: Vec<[f32; 3]> = part.mesh.normals.iter().map(|n| to_y_up(*n)).collect();
            let mut lo = [f32::INFINITY; 3];
            let mut hi = [f32::NEG_INFINITY; 3];
            for p in &pos {
                for i in 0..3 {
                    lo[i] = lo[i].min(p[i]);
                    hi[i] = hi[i].max(p[i]);
                }
            }
            let pos_bytes: Vec<u8> = pos.iter().flatten().flat_map(|v| v.to_le_bytes()).collect();
            let nrm_bytes: Vec<u8> = nrm.iter().flatten().flat_map(|v| v.to_le_bytes()).collect();
            let idx_bytes: Vec<u8> = part
                .mesh
                .triangles
                .iter()
                .flatten()
                .flat_map(|v| v.to_le_bytes())
                .collect();
            let pv = self.push_view(&pos_bytes, ARRAY_BUFFER);
            let nv = self.push_view(&nrm_bytes, ARRAY_BUFFER);
            let iv = self.push_view(&idx_bytes, ELEMENT_ARRAY_BUFFER);
            self.accessors.push(json!({
                "bufferView": pv, "componentType": FLOAT, "count": pos.len(), "type": "VEC3",
                "min": lo, "max": hi
            }));
            let pa = self.accessors.len() - 1;
            self.accessors.push(json!({
                "bufferView": nv, "componentType": FLOAT, "count": nrm.len(), "type": "VEC3"
            }));
            let na = self.accessors.len() - 1;
            self.accessors.push(json!({
                "bufferView": iv, "componentType": UNSIGNED_INT,
                "count": part.mesh.triangles.len() * 3, "type": "SCALAR"
            }));
            let ia = self.accessors.len() - 1;
            let mut attributes = json!({"POSITION": pa, "NORMAL": na});
            let textured = part.mesh.uvs.len() == part.mesh.positions.len();
            let texture = match (&part.texture, textured) {
                (Some(tex), true) => self.texture(tex),
                _ => None,
            };
            if texture.is_some() {
                let uv_bytes: Vec<u8> = part
                    .mesh
                    .uvs
                    .iter()
                    .flat_map(|uv| [uv[0] as f32, uv[1] as f32])
                    .flat_map(|v| v.to_le_bytes())
                    .collect();
                let uv_view = self.push_view(&uv_bytes, ARRAY_BUFFER);
                self.accessors.push(json!({
                    "bufferView": uv_view, "componentType": FLOAT,
                    "count": part.mesh.uvs.len(), "type": "VEC2"
                }));
                attributes["TEXCOORD_0"] = json!(self.accessors.len() - 1);
            }
            let mat = self.material(part.color, texture);
            primitives.push(json!({
                "attributes": attributes,
                "indices": ia,
                "material": mat,
                "mode": 4
            }));
        }
        self.meshes
            .push(json!({"name": name, "primitives": primitives}));
        self.meshes.len() - 1
    }

    /// Adds a node with an optional mesh, an optional pose relative to its parent (Z-up,
    /// converted to glTF's frame) and children. Returns the node index.
    pub fn add_node(
        &mut self,
        name: &str,
        mesh: Option<usize>,
        parent_from_node: Option<&Pose>,
        children: Vec<usize>,
    ) -> usize {
        let mut node = json!({"name": name});
        if let Some(m) = mesh {
            node["mesh"] = json!(m);
        }
        if let Some(p) = parent_from_node {
            let t = to_y_up([p.translation().x, p.translation().y, p.translation().z]);
            let q = p.rotation();
            // Rotations change frame like vectors: the axis maps through the same Y-up swap.
            let axis = to_y_up([q.i, q.j, q.k]);
            node["translation"] = json!(t);
            node["rotation"] = json!([axis[0], axis[1], axis[2], q.w as f32]);
        }
        if !children.is_empty() {
            node["children"] = json!(children);
        }
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    /// Marks a node as a root of the default scene.
    pub fn add_root(&mut self, node: usize) {
        self.roots.push(node);
    }

    fn document(&self, uri: Option<&str>) -> Value {
        let mut buffer = json!({"byteLength": self.bin.len()});
        if let Some(u) = uri {
            buffer["uri"] = json!(u);
        }
        let mut doc = json!({
            "asset": {"version": "2.0", "generator": concat!("scenesmith ", env!("CARGO_PKG_VERSION"))},
            "scene": 0,
            "scenes": [{"nodes": self.roots}],
            "nodes": self.nodes,
            "meshes": self.meshes,
            "materials": self.materials,
            "accessors": self.accessors,
            "bufferViews": self.buffer_views,
            "buffers": [buffer],
        });
        if self.samplers_used {
            // 10497 = REPEAT, 9729 = LINEAR, 9987 = LINEAR_MIPMAP_LINEAR.
            doc["samplers"] =
                json!([{"wrapS": 10497, "wrapT": 10497, "magFilter": 9729, "minFilter": 9987}]);
            doc["images"] = json!(self.images);
            doc["textures"] = json!(self.textures);
        }
        doc
    }

    /// `.gltf` JSON text referring to the binary buffer at `bin_uri`, and the buffer bytes.
    pub fn to_gltf(&self, bin_uri: &str) -> (String, Vec<u8>) {
        let text = serde_json::to_string(&self.document(Some(bin_uri))).unwrap_or_default();
        (text, self.bin.clone())
    }

    /// A self-contained binary glTF (GLB).
    pub fn to_glb(&self) -> Vec<u8> {
        let mut json_bytes = serde_json::to_vec(&self.document(None)).unwrap_or_default();
        while !json_bytes.len().is_multiple_of(4) {
            json_bytes.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let total = 12 + 8 + json_bytes.len() + 8 + bin.len();
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&json_bytes);
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
        out
    }
}

/// One link's visuals as glTF: the `.gltf` text, the `.bin` bytes, and the PNG texture files
/// it refers to.
pub struct LinkGltf {
    /// `.gltf` JSON text.
    pub gltf: String,
    /// Binary buffer.
    pub bin: Vec<u8>,
    /// Texture images `(file name, PNG bytes)`, referenced relative to the `.gltf`.
    pub images: Vec<(String, Vec<u8>)>,
}

/// The glTF of one link's visual parts (a single node, no transform).
pub fn link_visual_gltf(name: &str, parts: &[VisualPart], bin_uri: &str) -> LinkGltf {
    let mut b = GltfBuilder::new();
    let mesh = b.add_mesh(name, parts);
    let node = b.add_node(name, Some(mesh), None, vec![]);
    b.add_root(node);
    let (gltf, bin) = b.to_gltf(bin_uri);
    LinkGltf {
        gltf,
        bin,
        images: b.image_files().to_vec(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::mesh::box_mesh;

    fn part() -> VisualPart {
        VisualPart {
            name: "p".into(),
            mesh: box_mesh([0.0, 0.0, 0.5], [1.0, 2.0, 1.0]),
            color: [0.5, 0.4, 0.3, 1.0],
            texture: None,
        }
    }

    fn textured_part() -> VisualPart {
        let rgba: Vec<u8> = (0..16)
            .flat_map(|i| [i * 16, 255 - i * 16, 128, 255])
            .collect();
        VisualPart {
            name: "t".into(),
            mesh: box_mesh([0.0, 0.0, 0.5], [1.0, 1.0, 1.0]).with_box_uvs(0.5),
            color: [1.0; 4],
            texture: Some(crate::assets::Texture {
                name: "checker".into(),
                width: 4,
                height: 4,
                rgba: std::sync::Arc::new(rgba),
            }),
        }
    }

    #[test]
    fn textures_become_png_files_or_embedded_views() {
        let link = link_visual_gltf("rug", &[textured_part(), part()], "rug.bin");
        assert_eq!(link.images.len(), 1);
        assert_eq!(link.images[0].0, "checker.png");
        let doc: Value = serde_json::from_str(&link.gltf).unwrap();
        assert_eq!(doc["images"][0]["uri"], "checker.png");
        assert_eq!(
            doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"],
            0
        );
        assert!(doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"].is_u64());
        assert!(doc["meshes"][0]["primitives"][1]["attributes"]["TEXCOORD_0"].is_null());

        let mut b = GltfBuilder::new_embedded();
        let m = b.add_mesh("m", &[textured_part()]);
        let n = b.add_node("n", Some(m), None, vec![]);
        b.add_root(n);
        let glb = b.to_glb();
        let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
        let doc: Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
        assert_eq!(doc["images"][0]["mimeType"], "image/png");
        assert!(doc["images"][0]["bufferView"].is_u64());
    }

    #[test]
    fn gltf_bounds_are_y_up() {
        let link = link_visual_gltf("body", &[part()], "body.bin");
        let (text, bin) = (link.gltf, link.bin);
        let doc: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(
            doc["buffers"][0]["byteLength"].as_u64().unwrap() as usize,
            bin.len()
        );
        let acc = &doc["accessors"][0];
        // z-up height 0..1 becomes y-up 0..1; z-up y extent -1..1 becomes -z 1..-1.
        assert_eq!(acc["min"][1].as_f64().unwrap(), 0.0);
        assert_eq!(acc["max"][1].as_f64().unwrap(), 1.0);
        assert_eq!(acc["min"][2].as_f64().unwrap(), -1.0);
        assert_eq!(doc["asset"]["version"], "2.0");
    }

    #[test]
    fn glb_header_is_consistent() {
        let mut b = GltfBuilder::new();
        let m = b.add_mesh("m", &[part(), part()]);
        let n = b.add_node(
            "n",
            Some(m),
            Some(&Pose::from_xyz_yaw(1.0, 2.0, 0.0, 0.5)),
            vec![],
        );
        b.add_root(n);
        let glb = b.to_glb();
        assert_eq!(&glb[0..4], b"glTF");
        let total = u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize;
        assert_eq!(total, glb.len());
        assert_eq!(total % 4, 0);
        // One shared material for two parts of the same colour.
        let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
        let doc: Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
        assert_eq!(doc["materials"].as_array().unwrap().len(), 1);
    }
}

/// The reader ([`crate::assets::gltf_read`]) reads back what this writer wrote.
#[cfg(test)]
mod read_back {
    use serde_json::Value;

    use super::{GltfBuilder, link_visual_gltf};
    use crate::assets::gltf_read::{parse, read_file};
    use crate::assets::{Texture, VisualPart};
    use crate::geometry::mesh::box_mesh;
    use crate::scene::Pose;

    fn part(textured: bool) -> VisualPart {
        let mesh = box_mesh([0.1, 0.2, 0.5], [1.0, 2.0, 1.0]);
        VisualPart {
            name: "p".into(),
            mesh: if textured {
                mesh.with_box_uvs(0.5)
            } else {
                mesh
            },
            color: [0.5, 0.25, 0.125, 1.0],
            texture: textured.then(|| Texture {
                name: "tex".into(),
                width: 2,
                height: 2,
                rgba: std::sync::Arc::new(vec![
                    255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255,
                ]),
            }),
        }
    }

    #[test]
    fn reads_back_what_the_writer_wrote() {
        let dir = tempfile::tempdir().unwrap();
        let link = link_visual_gltf("body", &[part(true), part(false)], "body.bin");
        std::fs::write(dir.path().join("body.gltf"), &link.gltf).unwrap();
        std::fs::write(dir.path().join("body.bin"), &link.bin).unwrap();
        for (name, png) in &link.images {
            std::fs::write(dir.path().join(name), png).unwrap();
        }
        let parts = read_file(&dir.path().join("body.gltf")).unwrap();
        assert_eq!(parts.len(), 2);
        let (lo, hi) = parts[1].mesh.bounds().unwrap();
        for (a, b) in lo.iter().zip([-0.4, -0.8, 0.0]) {
            assert!((a - b).abs() < 1e-6, "{lo:?}");
        }
        for (a, b) in hi.iter().zip([0.6, 1.2, 1.0]) {
            assert!((a - b).abs() < 1e-6, "{hi:?}");
        }
        let tex = parts[0].texture.as_ref().unwrap();
        assert_eq!((tex.width, tex.height), (2, 2));
        assert_eq!(&tex.rgba[0..4], &[255, 0, 0, 255]);
        assert_eq!(parts[1].color, [0.5, 0.25, 0.125, 1.0]);
    }

    #[test]
    fn glb_with_node_transform() {
        let mut b = GltfBuilder::new_embedded();
        let m = b.add_mesh("m", &[part(false)]);
        let n = b.add_node(
            "n",
            Some(m),
            Some(&Pose::from_xyz_yaw(
                2.0,
                0.0,
                0.0,
                std::f64::consts::FRAC_PI_2,
            )),
            vec![],
        );
        b.add_root(n);
        let parts = parse(&b.to_glb(), None).unwrap();
        let (lo, hi) = parts[0].mesh.bounds().unwrap();
        // Rotated 90 degrees about z then moved +2 in x: x extent 2 - 1.2 .. 2 + 0.8.
        assert!(
            (lo[0] - 0.8).abs() < 1e-5 && (hi[0] - 2.8).abs() < 1e-5,
            "{lo:?} {hi:?}"
        );
    }

    #[test]
    fn a_hostile_count_is_an_error_not_an_allocation() {
        let dir = tempfile::tempdir().unwrap();
        let link = link_visual_gltf("body", &[part(false)], "body.bin");
        std::fs::write(dir.path().join("body.bin"), &link.bin).unwrap();
        let doc: Value = serde_json::from_str(&link.gltf).unwrap();
        let accessors = doc["accessors"].as_array().unwrap().len();
        for count in [1u64 << 60, u64::MAX / 2, 1 << 30] {
            for i in 0..accessors {
                let mut hostile = doc.clone();
                hostile["accessors"][i]["count"] = count.into();
                let path = dir.path().join(format!("hostile_{i}.gltf"));
                std::fs::write(&path, serde_json::to_vec(&hostile).unwrap()).unwrap();
                let err = read_file(&path).unwrap_err();
                assert!(
                    err.contains("exceeds"),
                    "accessor {i}, count {count}: {err}"
                );
            }
        }
    }
}
