//! Turning a foreign mesh into an asset: canonical frame (Z up, +Y front; floor objects and
//! manipulands bottom at z = 0 and centred, wall objects back at y = 0, ceiling objects top
//! at z = 0), scaled to the requested size, decomposed into convex pieces (V-HACD, capped by
//! the support class's budget), and given mass, inertia and friction from a material.

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

use super::ExternalError;
use super::vhacd::{self, VhacdOptions};
use crate::assets::physical::{self, Fill};
use crate::assets::procedural::SupportClass;
use crate::assets::{Asset, Contact, Link, VisualPart, content_id, material};
use crate::geometry::{ConvexPiece, TriMesh, mesh};
use crate::scene::Pose;

/// A signed coordinate axis, `+x`, `-z`, ...
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Axis {
    /// +X
    #[serde(rename = "+x")]
    PosX,
    /// -X
    #[serde(rename = "-x")]
    NegX,
    /// +Y
    #[serde(rename = "+y")]
    PosY,
    /// -Y
    #[serde(rename = "-y")]
    NegY,
    /// +Z
    #[serde(rename = "+z")]
    PosZ,
    /// -Z
    #[serde(rename = "-z")]
    NegZ,
}

impl Axis {
    /// The unit vector.
    pub fn vector(self) -> Vector3<f64> {
        match self {
            Axis::PosX => Vector3::x(),
            Axis::NegX => -Vector3::x(),
            Axis::PosY => Vector3::y(),
            Axis::NegY => -Vector3::y(),
            Axis::PosZ => Vector3::z(),
            Axis::NegZ => -Vector3::z(),
        }
    }

    /// The same direction after glTF's +Y-up file coordinates were converted to +Z-up on
    /// loading (`(x, y, z) -> (x, -z, y)`).
    pub fn after_gltf_load(self) -> Axis {
        match self {
            Axis::PosY => Axis::PosZ,
            Axis::NegY => Axis::NegZ,
            Axis::PosZ => Axis::NegY,
            Axis::NegZ => Axis::PosY,
            a => a,
        }
    }
}

/// How to bring a mesh into the canonical frame and what it is made of.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportOptions {
    /// The mesh's up direction, in its loaded coordinates.
    pub up: Axis,
    /// The mesh's front direction, in its loaded coordinates.
    pub front: Axis,
    /// Metres per mesh unit (0.01 for centimetres).
    pub unit_scale: f64,
    /// Where it is supported.
    pub support: SupportClass,
    /// Target size (x, y, z) in metres after canonicalisation, if any.
    pub size: Option<[f64; 3]>,
    /// Material name (friction, density).
    pub material: String,
    /// Wall thickness when the object is hollow (mass from the shell), metres.
    pub hollow: Option<f64>,
    /// Category noun of the asset.
    pub category: String,
    /// Provenance of the source (file, URL, licence, description).
    pub source: serde_json::Value,
    /// Hash of the source bytes (part of the content id).
    pub source_hash: String,
}

/// The rotation taking `up` to +Z and `front` to +Y, or an error when they are parallel.
pub fn canonical_rotation(up: Axis, front: Axis) -> Result<Matrix3<f64>, ExternalError> {
    let u = up.vector();
    let f = front.vector();
    if u.dot(&f).abs() > 0.5 {
        return Err(ExternalError::Mesh(format!(
            "up {up:?} and front {front:?} must be different axes"
        )));
    }
    let r = f.cross(&u);
    Ok(Matrix3::from_rows(&[
        r.transpose(),
        f.transpose(),
        u.transpose(),
    ]))
}

fn map_mesh(
    m: &TriMesh,
    f: impl Fn(Vector3<f64>) -> Vector3<f64>,
    n: impl Fn(Vector3<f64>) -> Vector3<f64>,
) -> TriMesh {
    let mut out = m.clone();
    out.positions = m
        .positions
        .iter()
        .map(|p| {
            let q = f(Vector3::from(*p));
            [q.x, q.y, q.z]
        })
        .collect();
    out.normals = m
        .normals
        .iter()
        .map(|v| {
            let q = n(Vector3::from(*v))
                .try_normalize(1e-12)
                .unwrap_or(Vector3::z());
            [q.x, q.y, q.z]
        })
        .collect();
    out
}

/// Canonicalises, scales, decomposes and weighs `parts`; returns the asset and notes.
pub fn import_parts(
    parts: Vec<VisualPart>,
    opts: &ImportOptions,
) -> Result<(Asset, Vec<String>), ExternalError> {
    if parts.iter().all(|p| p.mesh.triangles.is_empty()) {
        return Err(ExternalError::Mesh("the mesh has no triangles".into()));
    }
    if !(opts.unit_scale.is_finite() && opts.unit_scale > 0.0) {
        return Err(ExternalError::Mesh(format!(
            "unit scale {} is not positive",
            opts.unit_scale
        )));
    }
    let rot = canonical_rotation(opts.up, opts.front)?;
    let s0 = opts.unit_scale;
    let mut parts: Vec<VisualPart> = parts
        .into_iter()
        .filter(|p| !p.mesh.triangles.is_empty())
        .map(|p| VisualPart {
            mesh: map_mesh(&p.mesh, |v| rot * v * s0, |n| rot * n),
            ..p
        })
        .collect();
    let all: Vec<[f64; 3]> = parts
        .iter()
        .flat_map(|p| p.mesh.positions.iter().copied())
        .collect();
    let (lo, hi) = mesh::bounds_of(&all).ok_or_else(|| ExternalError::Mesh("empty mesh".into()))?;
    if all.iter().flatten().any(|v| !v.is_finite()) {
        return Err(ExternalError::Mesh(
            "the mesh has non-finite coordinates".into(),
        ));
    }
    let ext = [0, 1, 2].map(|i| hi[i] - lo[i]);
    if ext.iter().any(|e| *e <= 1e-9) {
        return Err(ExternalError::Mesh(format!(
            "the mesh is flat (extent {ext:?})"
        )));
    }
    let mut notes = Vec::new();
    // Uniform scale to the requested size (geometric mean of the axis ratios), then a
    // bounded per-axis stretch so every axis lands within the 10 % tolerance when it can.
    let scale = match opts.size {
        Some(want) => {
            let ratios = [0, 1, 2].map(|i| want[i] / ext[i]);
            let s = (ratios[0] * ratios[1] * ratios[2]).cbrt();
            let per_axis = ratios.map(|r| (r / s).clamp(0.8, 1.25) * s);
            if ratios
                .iter()
                .zip(&per_axis)
                .any(|(r, p)| ((r - p) / r).abs() > 1e-9)
                || ratios.iter().any(|r| (r / s - 1.0).abs() > 0.01)
            {
                notes.push(format!(
                    "imported mesh proportions {:.2} x {:.2} x {:.2} differ from the request; stretched by {:.2} / {:.2} / {:.2}",
                    ext[0], ext[1], ext[2], per_axis[0] / s, per_axis[1] / s, per_axis[2] / s
                ));
            }
            per_axis
        }
        None => [1.0; 3],
    };
    let c = [0, 1, 2].map(|i| 0.5 * (lo[i] + hi[i]) * scale[i]);
    let offset = match opts.support {
        SupportClass::Floor | SupportClass::Surface => [-c[0], -c[1], -lo[2] * scale[2]],
        SupportClass::Wall => [-c[0], -lo[1] * scale[1], -lo[2] * scale[2]],
        SupportClass::Ceiling => [-c[0], -c[1], -hi[2] * scale[2]],
    };
    let place = |v: Vector3<f64>| {
        Vector3::new(
            v.x * scale[0] + offset[0],
            v.y * scale[1] + offset[1],
            v.z * scale[2] + offset[2],
        )
    };
    let inv = Vector3::new(1.0 / scale[0], 1.0 / scale[1], 1.0 / scale[2]);
    for p in parts.iter_mut() {
        p.mesh = map_mesh(&p.mesh, place, |n| n.component_mul(&inv));
    }
    let mut merged = TriMesh::new();
    for p in &parts {
        let mut m = p.mesh.clone();
        m.uvs.clear();
        merged.append(&m);
    }
    // Collision: V-HACD within the hull budget; one hull if the mesh encloses no volume.
    let cap = physical::hull_cap(opts.support) as u32;
    let mut pieces = vhacd::decompose(
        &merged,
        VhacdOptions {
            max_hulls: cap,
            ..VhacdOptions::default()
        },
    );
    if pieces.is_empty() {
        let hull = ConvexPiece::from_points(&merged.positions)
            .map_err(|e| ExternalError::Mesh(e.to_string()))?;
        notes.push("the mesh encloses no volume for V-HACD; collision is its convex hull".into());
        pieces.push(hull);
    }
    // Mass: material density x enclosed volume when the mesh is closed (or x shell volume
    // when hollow), otherwise x the volume of the convex pieces.
    let mat = material::material_or_default(&opts.material);
    let watertight = parts
        .iter()
        .all(|p| physical::check_watertight(&p.mesh).is_ok());
    let hull_volume: f64 = pieces.iter().map(|p| p.volume()).sum();
    let fills: Vec<Fill> = pieces
        .iter()
        .map(|_| Fill {
            density: mat.density,
            shell: opts.hollow,
        })
        .collect();
    let mut mass =
        physical::mass_props(&pieces, &fills).map_err(|e| ExternalError::Mesh(e.to_string()))?;
    let mut provenance_extra = serde_json::Map::new();
    if watertight && opts.hollow.is_none() {
        let v = mesh::enclosed_volume(&merged);
        if v > 1e-9 && hull_volume > 0.0 {
            mass = mass.scaled(v / hull_volume);
        }
    } else if !watertight {
        provenance_extra.insert(
            "open_visual_reason".into(),
            serde_json::json!("imported mesh is not a closed surface; collision and mass come from its convex decomposition"),
        );
    }
    mass.validate()
        .map_err(|e| ExternalError::Mesh(e.to_string()))?;
    let key = serde_json::json!({
        "source": opts.source_hash,
        "support": opts.support.as_str(),
        "size": opts.size,
        "material": opts.material,
        "up": opts.up, "front": opts.front, "unit_scale": opts.unit_scale,
        "hollow": opts.hollow,
        "importer": 1,
    });
    let id = content_id(&opts.category, &key);
    let link = Link {
        name: "body".into(),
        model_from_link: Pose::IDENTITY,
        visuals: parts
            .into_iter()
            .enumerate()
            .map(|(k, p)| VisualPart {
                name: format!("part_{k}"),
                ..p
            })
            .collect(),
        collisions: pieces,
        mass,
        contact: Contact::from(&mat),
    };
    let mut provenance = serde_json::json!({
        "strategy": "external",
        "source": opts.source,
        "support": opts.support.as_str(),
        "parameters": {"scale": scale, "up": opts.up, "front": opts.front, "unit_scale": opts.unit_scale},
    });
    for (k, v) in provenance_extra {
        provenance[k] = v;
    }
    let mut asset = Asset {
        id,
        category: crate::scene::sanitize_name(&opts.category),
        material: opts.material.clone(),
        links: vec![link],
        joints: vec![],
        surfaces: vec![],
        is_static: false,
        provenance,
    };
    // A flat top becomes a support surface (tables, shelves from a mesh folder).
    let [lo, hi] = asset.bounds();
    if opts.support != SupportClass::Ceiling {
        asset.surfaces.push(crate::scene::SurfaceRecord {
            id: "top".into(),
            link: "body".into(),
            center: [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0, hi[2]],
            size: [(hi[0] - lo[0]) * 0.8, (hi[1] - lo[1]) * 0.8],
            clearance: 0.5,
        });
    }
    physical::check(&asset, opts.support)?;
    asset.provenance["physics"] =
        serde_json::to_value(physical::summarize(&asset, opts.support)).unwrap_or_default();
    Ok((asset, notes))
}

/// A shared helper for tests and callers: the mass of an imported asset as density times
/// its enclosed volume.
pub fn expected_mass(asset: &Asset) -> f64 {
    let m = material::material_or_default(&asset.material);
    let v: f64 = asset
        .links
        .iter()
        .flat_map(|l| l.visuals.iter())
        .map(|v| mesh::enclosed_volume(&v.mesh))
        .sum();
    m.density * v
}
