//! Reads back the SDFormat models this project writes (one model per file, links with
//! glTF visuals, OBJ convex collisions, inertials, revolute/prismatic joints), so a scene
//! directory can be rendered, exported, measured or resumed without regenerating its assets.

use std::path::Path;

use crate::assets::gltf_read;
use crate::assets::{Asset, Contact, Joint, JointKind, Link};
use crate::geometry::MassProps;
use crate::geometry::obj;
use crate::scene::{AssetRecord, Pose};
use crate::util::xml::{self, El};

fn pose_of(el: &El) -> Result<Pose, String> {
    match el.child_nums("pose") {
        None => Ok(Pose::IDENTITY),
        Some(v) if v.len() == 6 => Ok(Pose::from_xyz_rpy([v[0], v[1], v[2]], [v[3], v[4], v[5]])),
        Some(v) => Err(format!("<pose> needs 6 numbers, got {}", v.len())),
    }
}

fn mesh_uri(el: &El) -> Option<&str> {
    el.find("geometry")?.find("mesh")?.child_text("uri")
}

/// Resolves a URI written in a model file: relative paths only, never outside the folder.
fn local_file(dir: &Path, uri: &str) -> Result<std::path::PathBuf, String> {
    if uri.contains("..") || uri.starts_with('/') || uri.contains("://") {
        return Err(format!("URI {uri:?} points outside the asset folder"));
    }
    Ok(dir.join(uri))
}

fn inertial(link: &El) -> Result<MassProps, String> {
    let Some(inertial) = link.find("inertial") else {
        return Ok(MassProps {
            mass: 1.0,
            com: [0.0; 3],
            inertia: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        });
    };
    let p = pose_of(inertial)?;
    let mass = inertial
        .child_text("mass")
        .and_then(|t| t.parse::<f64>().ok())
        .ok_or("inertial without a valid <mass>")?;
    let i = inertial
        .find("inertia")
        .ok_or("inertial without <inertia>")?;
    let g = |k: &str| -> Result<f64, String> {
        i.child_text(k)
            .and_then(|t| t.parse::<f64>().ok())
            .ok_or_else(|| format!("inertia without <{k}>"))
    };
    let (ixx, ixy, ixz, iyy, iyz, izz) = (
        g("ixx")?,
        g("ixy")?,
        g("ixz")?,
        g("iyy")?,
        g("iyz")?,
        g("izz")?,
    );
    let t = p.translation();
    Ok(MassProps {
        mass,
        com: [t.x, t.y, t.z],
        inertia: [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]],
    })
}

fn contact(collision: &El) -> Contact {
    let props = collision.find("drake:proximity_properties");
    let get = |k: &str, d: f64| {
        props
            .and_then(|p| p.child_text(k))
            .and_then(|t| t.parse::<f64>().ok())
            .unwrap_or(d)
    };
    Contact::new(
        get("drake:mu_dynamic", 0.5),
        get("drake:mu_static", 0.6),
        get("drake:hunt_crossley_dissipation", 1.0),
    )
}

/// Reads `model.sdf` in `dir` (plus its meshes) into an asset; `record` supplies what SDFormat
/// does not carry (category, material, surfaces, provenance).
pub fn read_asset(dir: &Path, record: &AssetRecord) -> Result<Asset, String> {
    let sdf_path = dir.join("model.sdf");
    let text =
        std::fs::read_to_string(&sdf_path).map_err(|e| format!("{}: {e}", sdf_path.display()))?;
    let root = xml::parse(&text).map_err(|e| format!("{}: {e}", sdf_path.display()))?;
    let model = root
        .find("model")
        .ok_or("no <model> in the SDFormat file")?;
    let is_static = model.child_text("static") == Some("true");
    let mut links = Vec::new();
    for l in model.find_all("link") {
        let name = l.get_attr("name").ok_or("link without a name")?.to_string();
        let mut visuals = Vec::new();
        for v in l.find_all("visual") {
            if let Some(uri) = mesh_uri(v) {
                visuals.extend(gltf_read::read_file(&local_file(dir, uri)?)?);
            }
        }
        let mut collisions = Vec::new();
        let mut link_contact = None;
        for c in l.find_all("collision") {
            let uri =
                mesh_uri(c).ok_or_else(|| format!("collision in link {name} is not a mesh"))?;
            let path = local_file(dir, uri)?;
            let text =
                std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            collisions.push(
                obj::parse_convex_obj(&text).map_err(|e| format!("{}: {e}", path.display()))?,
            );
            link_contact.get_or_insert_with(|| contact(c));
        }
        links.push(Link {
            name,
            model_from_link: pose_of(l)?,
            visuals,
            collisions,
            mass: inertial(l)?,
            contact: link_contact.unwrap_or(Contact::new(0.5, 0.6, 1.0)),
        });
    }
    let mut joints = Vec::new();
    for j in model.find_all("joint") {
        let name = j
            .get_attr("name")
            .ok_or("joint without a name")?
            .to_string();
        let kind = match j.get_attr("type") {
            Some("revolute") => JointKind::Revolute,
            Some("prismatic") => JointKind::Prismatic,
            other => return Err(format!("joint {name}: unsupported type {other:?}")),
        };
        let axis = j
            .find("axis")
            .ok_or_else(|| format!("joint {name} without <axis>"))?;
        let xyz = axis
            .child_nums("xyz")
            .filter(|v| v.len() == 3)
            .unwrap_or(vec![0.0, 0.0, 1.0]);
        let limit = axis.find("limit");
        let lim = |k: &str, d: f64| {
            limit
                .and_then(|l| l.child_text(k))
                .and_then(|t| t.parse::<f64>().ok())
                .unwrap_or(d)
        };
        joints.push(Joint {
            name,
            kind,
            parent: j.child_text("parent").unwrap_or_default().to_string(),
            child: j.child_text("child").unwrap_or_default().to_string(),
            axis: [xyz[0], xyz[1], xyz[2]],
            lower: lim("lower", 0.0),
            upper: lim("upper", 0.0),
            effort: lim("effort", 0.0),
            damping: axis
                .find("dynamics")
                .and_then(|d| d.child_text("damping"))
                .and_then(|t| t.parse::<f64>().ok())
                .unwrap_or(0.0),
        });
    }
    let asset = Asset {
        id: record.id.clone(),
        category: record.category.clone(),
        material: record.material.clone(),
        links,
        joints,
        surfaces: record.surfaces.clone(),
        is_static,
        provenance: record.provenance.clone(),
    };
    asset.validate().map_err(|e| e.to_string())?;
    Ok(asset)
}
