//! Physical properties of assets: mass from solid or shell pieces, the mass range written for
//! domain randomisation, collision hull budgets, and the checks an asset passes before it is
//! written (inertia validity, hull budget, watertight visuals).
//!
//! Mass is density x volume of the convex collision pieces. Pieces that stand for hollow
//! bodies (a fridge cabinet, a bottle, a monitor housing) are marked as shells: their mass is
//! the outer piece minus the piece shrunk inward by the wall thickness, so the centre of mass
//! and inertia are those of the shell, not of a solid block.

use nalgebra::{Matrix3, Vector3};
use parry3d_f64::shape::Shape;
use serde::{Deserialize, Serialize};

use super::procedural::SupportClass;
use super::{Asset, AssetError};
use crate::geometry::{ConvexPiece, GeometryError, MassProps, TriMesh};

/// What a collision piece is made of, for its mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fill {
    /// Density, kg/m^3.
    pub density: f64,
    /// `Some(t)`: a closed shell with walls `t` metres thick; `None`: solid.
    pub shell: Option<f64>,
}

/// Largest number of convex collision pieces an asset of a support class may have.
pub fn hull_cap(support: SupportClass) -> usize {
    match support {
        SupportClass::Floor => 128,
        SupportClass::Wall | SupportClass::Surface => 64,
        SupportClass::Ceiling => 16,
    }
}

/// Mass, first moment and second moment about the link origin, accumulated over pieces.
#[derive(Default)]
struct Moments {
    mass: f64,
    first: Vector3<f64>,
    /// Inertia about the origin.
    inertia_o: Matrix3<f64>,
}

impl Moments {
    fn add(&mut self, sign: f64, mass: f64, com: Vector3<f64>, inertia_c: Matrix3<f64>) {
        let shift = Matrix3::identity() * com.dot(&com) - com * com.transpose();
        self.mass += sign * mass;
        self.first += sign * mass * com;
        self.inertia_o += sign * (inertia_c + shift * mass);
    }
}

fn piece_moments(
    piece: &ConvexPiece,
    density: f64,
) -> Result<(f64, Vector3<f64>, Matrix3<f64>), GeometryError> {
    let mp = piece.to_parry()?.mass_properties(density);
    let c = mp.local_com;
    let i = mp.reconstruct_inertia_matrix();
    let inertia = Matrix3::new(
        i.x_axis.x, i.y_axis.x, i.z_axis.x, //
        i.x_axis.y, i.y_axis.y, i.z_axis.y, //
        i.x_axis.z, i.y_axis.z, i.z_axis.z,
    );
    Ok((mp.mass(), Vector3::new(c.x, c.y, c.z), inertia))
}

/// The piece shrunk inward by `t` on every side (scaled about its centroid per axis), or
/// `None` when the walls would meet (the piece is then effectively solid).
pub fn shrunk(piece: &ConvexPiece, t: f64) -> Option<ConvexPiece> {
    let (lo, hi) = piece.bounds();
    let mut s = [0.0; 3];
    let mut c = [0.0; 3];
    for i in 0..3 {
        let ext = hi[i] - lo[i];
        if ext <= 2.0 * t * 1.05 {
            return None;
        }
        s[i] = (ext - 2.0 * t) / ext;
        c[i] = 0.5 * (lo[i] + hi[i]);
    }
    let pts: Vec<[f64; 3]> = piece
        .vertices
        .iter()
        .map(|v| [0, 1, 2].map(|i| c[i] + (v[i] - c[i]) * s[i]))
        .collect();
    ConvexPiece::from_points(&pts).ok()
}

/// Mass properties (link frame) of pieces with individual fills.
pub fn mass_props(pieces: &[ConvexPiece], fills: &[Fill]) -> Result<MassProps, GeometryError> {
    let mut m = Moments::default();
    for (k, piece) in pieces.iter().enumerate() {
        let fill = fills
            .get(k)
            .copied()
            .ok_or_else(|| GeometryError::InvalidInertia(format!("piece {k} has no fill")))?;
        if !(fill.density.is_finite() && fill.density > 0.0) {
            return Err(GeometryError::InvalidDensity(fill.density));
        }
        let (mass, com, inertia) = piece_moments(piece, fill.density)?;
        m.add(1.0, mass, com, inertia);
        if let Some(inner) = fill.shell.and_then(|t| shrunk(piece, t)) {
            let (mi, ci, ii) = piece_moments(&inner, fill.density)?;
            m.add(-1.0, mi, ci, ii);
        }
    }
    if !(m.mass.is_finite() && m.mass > 0.0) {
        return Err(GeometryError::InvalidInertia(format!(
            "mass {} kg from {} pieces",
            m.mass,
            pieces.len()
        )));
    }
    let com = m.first / m.mass;
    let shift = Matrix3::identity() * com.dot(&com) - com * com.transpose();
    let ic = m.inertia_o - shift * m.mass;
    let ic = (ic + ic.transpose()) * 0.5;
    let props = MassProps {
        mass: m.mass,
        com: [com.x, com.y, com.z],
        inertia: [
            [ic[(0, 0)], ic[(0, 1)], ic[(0, 2)]],
            [ic[(1, 0)], ic[(1, 1)], ic[(1, 2)]],
            [ic[(2, 0)], ic[(2, 1)], ic[(2, 2)]],
        ],
    };
    props.validate()?;
    Ok(props)
}

/// Relative spread of the mass range written for domain randomisation: how much the real
/// object's density may differ from the table value (wood varies more than steel).
pub fn density_spread(material: &str) -> f64 {
    super::material::spread(material)
}

/// Why a mesh is not a closed surface, or `Ok` when every edge has exactly two faces of
/// opposite winding (vertices are welded by position first, so flat-shaded meshes with
/// duplicated corners count as closed).
pub fn check_watertight(mesh: &TriMesh) -> Result<(), String> {
    use std::collections::HashMap;
    if mesh.triangles.is_empty() {
        return Err("empty mesh".into());
    }
    let key = |p: &[f64; 3]| p.map(|v| (v * 1e6).round() as i64);
    let mut ids: HashMap<[i64; 3], u32> = HashMap::new();
    let weld: Vec<u32> = mesh
        .positions
        .iter()
        .map(|p| {
            let n = ids.len() as u32;
            *ids.entry(key(p)).or_insert(n)
        })
        .collect();
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    for t in &mesh.triangles {
        let v = t.map(|i| weld.get(i as usize).copied().unwrap_or(u32::MAX));
        if v[0] == v[1] || v[1] == v[2] || v[0] == v[2] {
            continue; // degenerate after welding (poles of a sphere, axis of a lathe)
        }
        for k in 0..3 {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            let (lo, hi, s) = if a < b { (a, b, 1) } else { (b, a, -1) };
            *edges.entry((lo, hi)).or_insert(0) += s;
        }
    }
    let open = edges.values().filter(|&&s| s != 0).count();
    if open > 0 {
        return Err(format!("{open} boundary or inconsistently wound edges"));
    }
    Ok(())
}

/// Summary of an asset's physics, stored in its provenance (`physics`) and checked before
/// the asset is written.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PhysicsSummary {
    /// Total mass, kg.
    pub mass_kg: f64,
    /// `[min, max]` mass for domain randomisation, kg (density spread of the material).
    pub mass_range_kg: [f64; 2],
    /// Per-link `[min, max]` masses, kg, in link order.
    pub link_mass_range_kg: Vec<(String, [f64; 2])>,
    /// Convex collision pieces over all links.
    pub hull_count: usize,
    /// Budget for the support class.
    pub hull_cap: usize,
    /// Whether every visual part is a closed surface.
    pub watertight: bool,
    /// Visual parts that are open, with why that is acceptable (empty when watertight).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub open_visuals: Vec<String>,
}

/// Computes the physics summary of an asset.
pub fn summarize(asset: &Asset, support: SupportClass) -> PhysicsSummary {
    let spread = density_spread(&asset.material);
    let range = |m: f64| [m * (1.0 - spread), m * (1.0 + spread)];
    let mut open = Vec::new();
    for link in &asset.links {
        for v in &link.visuals {
            if let Err(why) = check_watertight(&v.mesh) {
                open.push(format!("{}/{}: {why}", link.name, v.name));
            }
        }
    }
    PhysicsSummary {
        mass_kg: asset.mass(),
        mass_range_kg: range(asset.mass()),
        link_mass_range_kg: asset
            .links
            .iter()
            .map(|l| (l.name.clone(), range(l.mass.mass)))
            .collect(),
        hull_count: asset.collision_pieces(),
        hull_cap: hull_cap(support),
        watertight: open.is_empty(),
        open_visuals: open,
    }
}

/// The checks every asset passes before it is written: structure and inertia
/// ([`Asset::validate`]) and the hull budget of its support class.
pub fn check(asset: &Asset, support: SupportClass) -> Result<(), AssetError> {
    asset.validate()?;
    let cap = hull_cap(support);
    if asset.collision_pieces() > cap {
        return Err(AssetError::Malformed {
            asset: asset.id.clone(),
            reason: format!(
                "{} collision pieces exceed the budget of {cap} for {support:?} objects",
                asset.collision_pieces()
            ),
        });
    }
    for link in &asset.links {
        if !link.mass.com.iter().all(|v| v.is_finite()) {
            return Err(AssetError::Malformed {
                asset: asset.id.clone(),
                reason: format!("link {:?} has a non-finite centre of mass", link.name),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::mesh;

    #[test]
    fn shell_box_matches_closed_form() {
        let (a, b, c, t) = (0.6, 0.5, 1.8, 0.03);
        let piece = ConvexPiece::cuboid([0.0, 0.0, c / 2.0], [a, b, c]).unwrap();
        let p = mass_props(
            &[piece],
            &[Fill {
                density: 1000.0,
                shell: Some(t),
            }],
        )
        .unwrap();
        let outer = a * b * c;
        let inner = (a - 2.0 * t) * (b - 2.0 * t) * (c - 2.0 * t);
        assert!((p.mass - 1000.0 * (outer - inner)).abs() < 1e-6);
        assert!((p.com[2] - c / 2.0).abs() < 1e-9);
        // A shell has more inertia per kilogram than the solid block.
        let solid = MassProps::from_pieces(
            &[ConvexPiece::cuboid([0.0, 0.0, c / 2.0], [a, b, c]).unwrap()],
            1000.0,
        )
        .unwrap();
        assert!(p.inertia[0][0] / p.mass > solid.inertia[0][0] / solid.mass);
    }

    #[test]
    fn mixed_densities_sum() {
        let a = ConvexPiece::cuboid([-1.0, 0.0, 0.0], [1.0, 1.0, 1.0]).unwrap();
        let b = ConvexPiece::cuboid([1.0, 0.0, 0.0], [1.0, 1.0, 1.0]).unwrap();
        let p = mass_props(
            &[a, b],
            &[
                Fill {
                    density: 100.0,
                    shell: None,
                },
                Fill {
                    density: 300.0,
                    shell: None,
                },
            ],
        )
        .unwrap();
        assert!((p.mass - 400.0).abs() < 1e-9);
        assert!((p.com[0] - 0.5).abs() < 1e-9);
    }

    #[test]
    fn watertight_detects_open_meshes() {
        let closed = mesh::box_mesh([0.0; 3], [1.0; 3]);
        assert!(check_watertight(&closed).is_ok());
        let mut open = closed.clone();
        open.triangles.truncate(10);
        assert!(check_watertight(&open).is_err());
        let cup = mesh::lathe_mesh(
            &[
                (0.0, 0.0),
                (1.0, 0.0),
                (1.0, 1.0),
                (0.9, 1.0),
                (0.9, 0.1),
                (0.0, 0.1),
            ],
            24,
        );
        assert!(check_watertight(&cup).is_ok());
    }
}
