//! Reading SDFormat and URDF model files into assets: links with poses, box / cylinder /
//! sphere / mesh visuals and collisions (mesh collisions become their convex hull, as Drake
//! treats them), colours, inertials; revolute, prismatic, continuous and fixed joints (fixed
//! children are merged into their parents). SDFormat joint poses are taken in the child frame;
//! the child link frame is moved onto the joint frame, the asset convention.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use nalgebra::{Matrix3, Point3, Rotation3, Vector3};

use crate::assets::procedural::shapes;
use crate::assets::{Asset, Contact, Joint, JointKind, Link, VisualPart};
use crate::geometry::{ConvexPiece, MassProps, TriMesh, mesh};
use crate::scene::Pose;
use crate::util::xml::{self, El};

/// A link while reading.
struct RawLink {
    name: String,
    model_from_link: Pose,
    visuals: Vec<VisualPart>,
    collisions: Vec<ConvexPiece>,
    inertial: Option<MassProps>,
    contact: Option<Contact>,
}

#[derive(PartialEq)]
enum RawKind {
    Revolute,
    Prismatic,
    Fixed,
}

struct RawJoint {
    name: String,
    kind: RawKind,
    parent: String,
    child: String,
    axis: [f64; 3],
    lower: f64,
    upper: f64,
    damping: f64,
    effort: f64,
}

pub(super) struct RawModel {
    links: Vec<RawLink>,
    joints: Vec<RawJoint>,
}

fn nums_attr(el: &El, key: &str, n: usize) -> Result<Option<Vec<f64>>, String> {
    match el.get_attr(key) {
        None => Ok(None),
        Some(t) => {
            let v = xml::parse_nums(t)
                .ok_or_else(|| format!("<{}> {key}={t:?} is not numbers", el.name()))?;
            if v.len() != n {
                return Err(format!(
                    "<{}> {key} needs {n} numbers, got {}",
                    el.name(),
                    v.len()
                ));
            }
            Ok(Some(v))
        }
    }
}

fn urdf_origin(el: &El) -> Result<Pose, String> {
    let Some(o) = el.find("origin") else {
        return Ok(Pose::IDENTITY);
    };
    let xyz = nums_attr(o, "xyz", 3)?.unwrap_or(vec![0.0; 3]);
    let rpy = nums_attr(o, "rpy", 3)?.unwrap_or(vec![0.0; 3]);
    Ok(Pose::from_xyz_rpy(
        [xyz[0], xyz[1], xyz[2]],
        [rpy[0], rpy[1], rpy[2]],
    ))
}

fn sdf_pose(el: &El) -> Result<Pose, String> {
    let Some(p) = el.find("pose") else {
        return Ok(Pose::IDENTITY);
    };
    if let Some(rel) = p.get_attr("relative_to")
        && !rel.is_empty()
        && rel != "__model__"
    {
        return Err(format!(
            "<pose relative_to=\"{rel}\"> in <{}> is not supported; express poses in the model frame",
            el.name()
        ));
    }
    let v = xml::parse_nums(p.text_content()).ok_or("<pose> is not numbers")?;
    match v.len() {
        0 => Ok(Pose::IDENTITY),
        6 => Ok(Pose::from_xyz_rpy([v[0], v[1], v[2]], [v[3], v[4], v[5]])),
        n => Err(format!("<pose> needs 6 numbers, got {n}")),
    }
}

/// Resolves a mesh URI: relative to the model file, `file://` absolute, `package://` or
/// `model://` relative to the library folder (first component dropped if not found).
fn resolve_uri(uri: &str, model_dir: &Path, lib_dir: &Path) -> Result<PathBuf, String> {
    if let Some(abs) = uri.strip_prefix("file://") {
        return Ok(PathBuf::from(abs));
    }
    for scheme in ["package://", "model://"] {
        if let Some(rest) = uri.strip_prefix(scheme) {
            let direct = crate::assets::external::folder::inside(lib_dir, rest)
                .map_err(|e| e.to_string())?;
            if direct.exists() {
                return Ok(direct);
            }
            let tail = rest.split_once('/').map(|x| x.1).unwrap_or(rest);
            return crate::assets::external::folder::inside(lib_dir, tail)
                .map_err(|e| e.to_string());
        }
    }
    crate::assets::external::folder::inside(model_dir, uri).map_err(|e| e.to_string())
}

/// Geometry of a `<geometry>` element: a visual mesh and the convex collision pieces.
fn geometry(
    g: &El,
    urdf: bool,
    model_dir: &Path,
    lib_dir: &Path,
) -> Result<(Vec<VisualPart>, Vec<ConvexPiece>), String> {
    let num = |el: &El, key: &str| -> Option<f64> {
        if urdf {
            el.get_attr(key).and_then(|t| t.trim().parse::<f64>().ok())
        } else {
            el.child_text(key).and_then(|t| t.parse::<f64>().ok())
        }
    };
    let part = |m: TriMesh| VisualPart {
        name: String::new(),
        mesh: m,
        color: [0.7, 0.7, 0.7, 1.0],
        texture: None,
    };
    if let Some(b) = g.find("box") {
        let s = if urdf {
            nums_attr(b, "size", 3)?
        } else {
            b.child_nums("size").filter(|v| v.len() == 3)
        }
        .ok_or("<box> without a 3-number size")?;
        let size = [s[0], s[1], s[2]];
        return Ok((
            vec![part(mesh::box_mesh([0.0; 3], size))],
            vec![ConvexPiece::cuboid([0.0; 3], size).map_err(|e| e.to_string())?],
        ));
    }
    if let Some(c) = g.find("cylinder") {
        let r = num(c, "radius").ok_or("<cylinder> without radius")?;
        let l = num(c, "length").ok_or("<cylinder> without length")?;
        return Ok((
            vec![part(mesh::cylinder_mesh(
                0.0,
                0.0,
                r,
                -l / 2.0,
                l / 2.0,
                24,
            ))],
            vec![
                ConvexPiece::cylinder(0.0, 0.0, r, -l / 2.0, l / 2.0, 16)
                    .map_err(|e| e.to_string())?,
            ],
        ));
    }
    if let Some(s) = g.find("sphere") {
        let r = num(s, "radius").ok_or("<sphere> without radius")?;
        return Ok((
            vec![part(shapes::ellipsoid_mesh([0.0; 3], [r; 3], 20))],
            vec![shapes::ellipsoid_piece([0.0; 3], [r; 3]).map_err(|e| e.to_string())?],
        ));
    }
    if let Some(m) = g.find("mesh") {
        let uri = if urdf {
            m.get_attr("filename").map(str::to_string)
        } else {
            m.child_text("uri").map(str::to_string)
        }
        .ok_or("<mesh> without a file")?;
        let scale = if urdf {
            nums_attr(m, "scale", 3)?
        } else {
            m.child_nums("scale").filter(|v| v.len() == 3)
        }
        .unwrap_or(vec![1.0; 3]);
        let path = resolve_uri(&uri, model_dir, lib_dir)?;
        let (parts, _) =
            crate::assets::external::folder::read_mesh_file(&path).map_err(|e| e.to_string())?;
        let s = [scale[0], scale[1], scale[2]];
        let parts: Vec<VisualPart> = parts
            .into_iter()
            .map(|p| VisualPart {
                mesh: p.mesh.scaled(s),
                ..p
            })
            .collect();
        let pts: Vec<[f64; 3]> = parts
            .iter()
            .flat_map(|p| p.mesh.positions.iter().copied())
            .collect();
        let hull = ConvexPiece::from_points(&pts).map_err(|e| format!("{uri}: {e}"))?;
        return Ok((parts, vec![hull]));
    }
    Err("geometry is not a box, cylinder, sphere or mesh".into())
}

fn color_of(v: &El, urdf: bool, named: &BTreeMap<String, [f64; 4]>) -> Option<[f64; 4]> {
    let m = v.find("material")?;
    let parse4 = |t: &str| {
        xml::parse_nums(t)
            .filter(|c| c.len() >= 3)
            .map(|c| [c[0], c[1], c[2], c.get(3).copied().unwrap_or(1.0)])
    };
    if urdf {
        m.find("color")
            .and_then(|c| c.get_attr("rgba"))
            .and_then(parse4)
            .or_else(|| m.get_attr("name").and_then(|n| named.get(n).copied()))
    } else {
        m.child_text("diffuse").and_then(parse4)
    }
}

fn urdf_inertial(l: &El) -> Result<Option<MassProps>, String> {
    let Some(i) = l.find("inertial") else {
        return Ok(None);
    };
    let origin = urdf_origin(i)?;
    let mass = i
        .find("mass")
        .and_then(|m| m.get_attr("value"))
        .and_then(|t| t.trim().parse::<f64>().ok());
    let inertia = i.find("inertia");
    let (Some(mass), Some(inertia)) = (mass, inertia) else {
        return Ok(None);
    };
    let g = |k: &str| {
        inertia
            .get_attr(k)
            .and_then(|t| t.trim().parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    Ok(Some(rotated_inertia(
        mass,
        origin,
        [g("ixx"), g("ixy"), g("ixz"), g("iyy"), g("iyz"), g("izz")],
    )))
}

fn sdf_inertial(l: &El) -> Result<Option<MassProps>, String> {
    let Some(i) = l.find("inertial") else {
        return Ok(None);
    };
    let pose = sdf_pose(i)?;
    let Some(mass) = i.child_text("mass").and_then(|t| t.parse::<f64>().ok()) else {
        return Ok(None);
    };
    let Some(inertia) = i.find("inertia") else {
        return Ok(None);
    };
    let g = |k: &str| {
        inertia
            .child_text(k)
            .and_then(|t| t.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    Ok(Some(rotated_inertia(
        mass,
        pose,
        [g("ixx"), g("ixy"), g("ixz"), g("iyy"), g("iyz"), g("izz")],
    )))
}

/// Mass properties in the link frame from an inertia given in a frame posed at `link_from_inertial`.
fn rotated_inertia(mass: f64, link_from_inertial: Pose, i: [f64; 6]) -> MassProps {
    let m = Matrix3::new(i[0], i[1], i[2], i[1], i[3], i[4], i[2], i[4], i[5]);
    let r = link_from_inertial.rotation().to_rotation_matrix();
    let rot = r.matrix() * m * r.matrix().transpose();
    let t = link_from_inertial.translation();
    MassProps {
        mass,
        com: [t.x, t.y, t.z],
        inertia: [
            [rot[(0, 0)], rot[(0, 1)], rot[(0, 2)]],
            [rot[(1, 0)], rot[(1, 1)], rot[(1, 2)]],
            [rot[(2, 0)], rot[(2, 1)], rot[(2, 2)]],
        ],
    }
}

fn read_parts(
    l: &El,
    urdf: bool,
    model_dir: &Path,
    lib_dir: &Path,
    named: &BTreeMap<String, [f64; 4]>,
) -> Result<(Vec<VisualPart>, Vec<ConvexPiece>), String> {
    let name = l.get_attr("name").unwrap_or("?");
    let mut visuals = Vec::new();
    let mut collisions = Vec::new();
    for v in l.find_all("visual") {
        let pose = if urdf { urdf_origin(v)? } else { sdf_pose(v)? };
        let g = v
            .find("geometry")
            .ok_or_else(|| format!("visual of link {name} without <geometry>"))?;
        let (parts, _) =
            geometry(g, urdf, model_dir, lib_dir).map_err(|e| format!("link {name}: {e}"))?;
        let color = color_of(v, urdf, named);
        for p in parts {
            let k = visuals.len();
            visuals.push(VisualPart {
                name: format!("part_{k}"),
                mesh: p.mesh.transformed(&pose),
                color: color.unwrap_or(p.color),
                texture: p.texture,
            });
        }
    }
    for c in l.find_all("collision") {
        let pose = if urdf { urdf_origin(c)? } else { sdf_pose(c)? };
        let g = c
            .find("geometry")
            .ok_or_else(|| format!("collision of link {name} without <geometry>"))?;
        let (_, pieces) =
            geometry(g, urdf, model_dir, lib_dir).map_err(|e| format!("link {name}: {e}"))?;
        collisions.extend(pieces.into_iter().map(|p| p.transformed(&pose)));
    }
    Ok((visuals, collisions))
}

fn joint_kind(t: Option<&str>, name: &str) -> Result<(RawKind, Option<(f64, f64)>), String> {
    match t {
        Some("revolute") => Ok((RawKind::Revolute, None)),
        Some("continuous") => Ok((
            RawKind::Revolute,
            Some((-std::f64::consts::TAU, std::f64::consts::TAU)),
        )),
        Some("prismatic") => Ok((RawKind::Prismatic, None)),
        Some("fixed") => Ok((RawKind::Fixed, None)),
        other => Err(format!(
            "joint {name}: type {other:?} is not supported (revolute, continuous, prismatic, fixed)"
        )),
    }
}

pub(super) fn read_urdf(root: &El, model_dir: &Path, lib_dir: &Path) -> Result<RawModel, String> {
    let mut named = BTreeMap::new();
    for m in root.find_all("material") {
        if let (Some(n), Some(c)) = (
            m.get_attr("name"),
            m.find("color")
                .and_then(|c| c.get_attr("rgba"))
                .and_then(xml::parse_nums),
        ) && c.len() >= 3
        {
            named.insert(
                n.to_string(),
                [c[0], c[1], c[2], c.get(3).copied().unwrap_or(1.0)],
            );
        }
    }
    let mut joints = Vec::new();
    let mut parent_from_child: BTreeMap<String, (String, Pose)> = BTreeMap::new();
    for j in root.find_all("joint") {
        let name = j
            .get_attr("name")
            .ok_or("joint without a name")?
            .to_string();
        let (kind, forced) = joint_kind(j.get_attr("type"), &name)?;
        let parent = j
            .find("parent")
            .and_then(|p| p.get_attr("link"))
            .ok_or_else(|| format!("joint {name} without <parent link>"))?
            .to_string();
        let child = j
            .find("child")
            .and_then(|p| p.get_attr("link"))
            .ok_or_else(|| format!("joint {name} without <child link>"))?
            .to_string();
        let axis = j
            .find("axis")
            .map(|a| nums_attr(a, "xyz", 3))
            .transpose()?
            .flatten()
            .unwrap_or(vec![1.0, 0.0, 0.0]);
        let limit = j.find("limit");
        let lim = |k: &str, d: f64| {
            limit
                .and_then(|l| l.get_attr(k))
                .and_then(|t| t.trim().parse::<f64>().ok())
                .unwrap_or(d)
        };
        let (lower, upper) = forced.unwrap_or((lim("lower", 0.0), lim("upper", 0.0)));
        let damping = j
            .find("dynamics")
            .and_then(|d| d.get_attr("damping"))
            .and_then(|t| t.trim().parse::<f64>().ok())
            .unwrap_or(0.1);
        parent_from_child.insert(child.clone(), (parent.clone(), urdf_origin(j)?));
        joints.push(RawJoint {
            name,
            kind,
            parent,
            child,
            axis: [axis[0], axis[1], axis[2]],
            lower,
            upper,
            damping,
            effort: lim("effort", 100.0),
        });
    }
    // Link frames: compose joint origins down from the root (the link no joint has as child).
    let mut links = Vec::new();
    for l in root.find_all("link") {
        let name = l.get_attr("name").ok_or("link without a name")?.to_string();
        let mut pose = Pose::IDENTITY;
        let mut cur = name.clone();
        let mut depth = 0;
        while let Some((parent, origin)) = parent_from_child.get(&cur) {
            pose = origin.compose(&pose);
            cur = parent.clone();
            depth += 1;
            if depth > 256 {
                return Err("the joint tree has a cycle".into());
            }
        }
        let (visuals, collisions) = read_parts(l, true, model_dir, lib_dir, &named)?;
        links.push(RawLink {
            name,
            model_from_link: pose,
            visuals,
            collisions,
            inertial: urdf_inertial(l)?,
            contact: None,
        });
    }
    // The root first.
    links.sort_by_key(|l| parent_from_child.contains_key(&l.name));
    Ok(RawModel { links, joints })
}

pub(super) fn read_sdf(root: &El, model_dir: &Path, lib_dir: &Path) -> Result<RawModel, String> {
    let model = root
        .find("model")
        .ok_or("no <model> in the SDFormat file")?;
    if model.find("model").is_some() {
        return Err("nested <model> elements are not supported".into());
    }
    let named = BTreeMap::new();
    let mut links = Vec::new();
    for l in model.find_all("link") {
        let name = l.get_attr("name").ok_or("link without a name")?.to_string();
        let (visuals, collisions) = read_parts(l, false, model_dir, lib_dir, &named)?;
        let contact = l
            .find_all("collision")
            .find_map(|c| c.find("drake:proximity_properties"))
            .map(|p| {
                let g = |k: &str, d: f64| {
                    p.child_text(k)
                        .and_then(|t| t.parse::<f64>().ok())
                        .unwrap_or(d)
                };
                Contact::new(
                    g("drake:mu_dynamic", 0.5),
                    g("drake:mu_static", 0.6),
                    g("drake:hunt_crossley_dissipation", 1.0),
                )
            });
        links.push(RawLink {
            name,
            model_from_link: sdf_pose(l)?,
            visuals,
            collisions,
            inertial: sdf_inertial(l)?,
            contact,
        });
    }
    let mut joints = Vec::new();
    for j in model.find_all("joint") {
        let name = j
            .get_attr("name")
            .ok_or("joint without a name")?
            .to_string();
        let (kind, forced) = joint_kind(j.get_attr("type"), &name)?;
        let parent = j.child_text("parent").unwrap_or_default().to_string();
        let child = j.child_text("child").unwrap_or_default().to_string();
        let child_from_joint = sdf_pose(j)?;
        let axis_el = j.find("axis");
        let xyz = axis_el
            .and_then(|a| a.child_nums("xyz"))
            .filter(|v| v.len() == 3)
            .unwrap_or(vec![0.0, 0.0, 1.0]);
        let limit = axis_el.and_then(|a| a.find("limit"));
        let lim = |k: &str, d: f64| {
            limit
                .and_then(|l| l.child_text(k))
                .and_then(|t| t.parse::<f64>().ok())
                .unwrap_or(d)
        };
        let (lower, upper) = forced.unwrap_or((lim("lower", 0.0), lim("upper", 0.0)));
        let damping = axis_el
            .and_then(|a| a.find("dynamics"))
            .and_then(|d| d.child_text("damping"))
            .and_then(|t| t.parse::<f64>().ok())
            .unwrap_or(0.1);
        // Move the child's frame onto the joint frame (the asset convention).
        if child_from_joint != Pose::IDENTITY
            && let Some(c) = links.iter_mut().find(|l| l.name == child)
        {
            let joint_from_child = child_from_joint.inverse();
            c.model_from_link = c.model_from_link.compose(&child_from_joint);
            for v in c.visuals.iter_mut() {
                v.mesh = v.mesh.transformed(&joint_from_child);
            }
            c.collisions = c
                .collisions
                .iter()
                .map(|p| p.transformed(&joint_from_child))
                .collect();
            if let Some(m) = c.inertial.as_mut() {
                *m = transform_mass(m, &joint_from_child);
            }
        }
        joints.push(RawJoint {
            name,
            kind,
            parent,
            child,
            axis: [xyz[0], xyz[1], xyz[2]],
            lower,
            upper,
            damping,
            effort: lim("effort", 100.0),
        });
    }
    Ok(RawModel { links, joints })
}

/// Mass properties re-expressed in another frame (`new_from_old`).
fn transform_mass(m: &MassProps, new_from_old: &Pose) -> MassProps {
    let c = new_from_old.transform_point(&Point3::from(m.com));
    let r: Rotation3<f64> = new_from_old.rotation().to_rotation_matrix();
    let i = Matrix3::from_fn(|a, b| m.inertia[a][b]);
    let ri = r.matrix() * i * r.matrix().transpose();
    MassProps {
        mass: m.mass,
        com: [c.x, c.y, c.z],
        inertia: [0, 1, 2].map(|a| [0, 1, 2].map(|b| ri[(a, b)])),
    }
}

/// Sum of two bodies' mass properties, both in the same frame.
fn combine(a: &MassProps, b: &MassProps) -> MassProps {
    let m = a.mass + b.mass;
    let ca = Vector3::from(a.com);
    let cb = Vector3::from(b.com);
    let c = (ca * a.mass + cb * b.mass) / m;
    let shift =
        |mass: f64, d: Vector3<f64>| (Matrix3::identity() * d.dot(&d) - d * d.transpose()) * mass;
    let ia = Matrix3::from_fn(|r, k| a.inertia[r][k]) + shift(a.mass, ca - c);
    let ib = Matrix3::from_fn(|r, k| b.inertia[r][k]) + shift(b.mass, cb - c);
    let i = ia + ib;
    MassProps {
        mass: m,
        com: [c.x, c.y, c.z],
        inertia: [0, 1, 2].map(|r| [0, 1, 2].map(|k| i[(r, k)])),
    }
}

/// Folds children of fixed joints into their parents.
pub(super) fn merge_fixed(model: &mut RawModel) -> Result<(), String> {
    while let Some(k) = model.joints.iter().position(|j| j.kind == RawKind::Fixed) {
        let j = model.joints.remove(k);
        let ci = model
            .links
            .iter()
            .position(|l| l.name == j.child)
            .ok_or_else(|| format!("joint {} names unknown child {}", j.name, j.child))?;
        let child = model.links.remove(ci);
        let parent = model
            .links
            .iter_mut()
            .find(|l| l.name == j.parent)
            .ok_or_else(|| format!("joint {} names unknown parent {}", j.name, j.parent))?;
        let parent_from_child = parent
            .model_from_link
            .inverse()
            .compose(&child.model_from_link);
        parent
            .visuals
            .extend(child.visuals.into_iter().map(|v| VisualPart {
                mesh: v.mesh.transformed(&parent_from_child),
                ..v
            }));
        parent.collisions.extend(
            child
                .collisions
                .iter()
                .map(|p| p.transformed(&parent_from_child)),
        );
        parent.inertial = match (parent.inertial, child.inertial) {
            (Some(a), Some(b)) => Some(combine(&a, &transform_mass(&b, &parent_from_child))),
            (a, b) => a.or(b.map(|b| transform_mass(&b, &parent_from_child))),
        };
        for other in model.joints.iter_mut() {
            if other.parent == j.child {
                other.parent = j.parent.clone();
            }
        }
    }
    Ok(())
}

impl RawModel {
    pub(super) fn into_asset(self, id: String, category: &str) -> Result<Asset, String> {
        if self.links.is_empty() {
            return Err("the model has no links".into());
        }
        let mut links = Vec::new();
        for l in self.links {
            if l.collisions.is_empty() {
                return Err(format!("link {} has no collision geometry", l.name));
            }
            let mass = match l.inertial.filter(|m| m.validate().is_ok()) {
                Some(m) => m,
                // No usable inertial: solid pieces at a wood-like density.
                None => MassProps::from_pieces(&l.collisions, 500.0)
                    .map_err(|e| format!("link {}: {e}", l.name))?,
            };
            let visuals = l
                .visuals
                .into_iter()
                .enumerate()
                .map(|(k, v)| VisualPart {
                    name: format!("part_{k}"),
                    ..v
                })
                .collect();
            links.push(Link {
                name: crate::scene::sanitize_name(&l.name),
                model_from_link: l.model_from_link,
                visuals,
                collisions: l.collisions,
                mass,
                contact: l.contact.unwrap_or(Contact::new(0.5, 0.6, 1.0)),
            });
        }
        let joints = self
            .joints
            .into_iter()
            .map(|j| {
                let n = Vector3::from(j.axis)
                    .try_normalize(1e-12)
                    .ok_or_else(|| format!("joint {} has a zero axis", j.name))?;
                Ok(Joint {
                    name: crate::scene::sanitize_name(&j.name),
                    kind: if j.kind == RawKind::Prismatic {
                        JointKind::Prismatic
                    } else {
                        JointKind::Revolute
                    },
                    parent: crate::scene::sanitize_name(&j.parent),
                    child: crate::scene::sanitize_name(&j.child),
                    axis: [n.x, n.y, n.z],
                    lower: j.lower,
                    upper: j.upper,
                    damping: j.damping.max(0.0),
                    effort: j.effort.max(0.0),
                })
            })
            .collect::<Result<Vec<_>, String>>()?;
        let asset = Asset {
            id,
            category: crate::scene::sanitize_name(category),
            material: "wood".into(),
            links,
            joints,
            surfaces: vec![],
            is_static: false,
            provenance: serde_json::Value::Null,
        };
        asset.validate().map_err(|e| e.to_string())?;
        Ok(asset)
    }
}
