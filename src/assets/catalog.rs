//! Category metadata for designers (the built-in rule-based designer and LLM tool schemas):
//! for every category its support class and stage, typical and allowed sizes, whether it is
//! a container, its support surfaces (which ones objects may be placed on, with their size and
//! clearance), its joints, how it is made, and the nouns that name it.
//!
//! Surfaces and joints come from building the category once at its typical size (memoised),
//! so they are exactly what the generator makes.

use std::collections::BTreeMap;
use std::sync::{Mutex, OnceLock};

use serde::Serialize;

use super::procedural::{self, AssetRequest, Kind, SupportClass};
use super::router::Stage;

/// What kind of support a surface is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceKind {
    /// An open top (table top, counter, bed, shelf top).
    Top,
    /// A shelf level inside or on a case piece.
    Shelf,
    /// A cavity things go into (bowl, basket, sink, bathtub, bin).
    Inside,
    /// The inside of a drawer (moves with the drawer).
    Drawer,
    /// A seat.
    Seat,
}

/// One support surface of a category.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceInfo {
    /// Surface id on the asset (`top`, `shelf_0`, `inside`, `drawer_1`, ...).
    pub id: String,
    /// What kind it is.
    pub kind: SurfaceKind,
    /// Width and depth, metres (at the typical size).
    pub size: [f64; 2],
    /// Free height above it, metres.
    pub clearance: f64,
    /// Whether the surface is behind a door or in a drawer (open it first).
    pub enclosed: bool,
}

/// One joint of a category.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointInfo {
    /// Joint name on the asset.
    pub name: String,
    /// `revolute` or `prismatic`.
    pub kind: &'static str,
    /// Range (rad or m).
    pub range: [f64; 2],
}

/// Everything a designer needs to know about a category.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CategoryInfo {
    /// Category name.
    pub name: String,
    /// Where it is supported.
    pub support: SupportClass,
    /// The stage that places it.
    pub stage: Stage,
    /// Procedural, articulated or thin covering.
    pub kind: Kind,
    /// Things go inside it.
    pub container: bool,
    /// Smallest, typical and largest size (x, y, z), metres.
    pub min: [f64; 3],
    /// Typical size.
    pub typical: [f64; 3],
    /// Largest size.
    pub max: [f64; 3],
    /// Default material.
    pub material: String,
    /// Other nouns for it.
    pub aliases: Vec<String>,
    /// Support surfaces, at the typical size.
    pub surfaces: Vec<SurfaceInfo>,
    /// Joints.
    pub joints: Vec<JointInfo>,
}

fn surface_kind(id: &str) -> SurfaceKind {
    if id.starts_with("shelf") || id.starts_with("tier") || id == "rack" || id == "freezer" {
        SurfaceKind::Shelf
    } else if id.starts_with("drawer") {
        SurfaceKind::Drawer
    } else if matches!(id, "inside" | "basin" | "floor") {
        SurfaceKind::Inside
    } else if matches!(id, "seat" | "chaise") {
        SurfaceKind::Seat
    } else {
        SurfaceKind::Top
    }
}

fn compute(name: &str) -> Option<CategoryInfo> {
    let p = procedural::prior(name)?;
    let mut r = AssetRequest::new(name, 0);
    r.size = Some(p.typical);
    let asset = procedural::build(&r).ok()?;
    let has_joints = !asset.joints.is_empty();
    Some(CategoryInfo {
        name: name.to_string(),
        support: p.support,
        stage: Stage::for_support(p.support),
        kind: if has_joints {
            Kind::Articulated
        } else {
            p.kind
        },
        container: p.container,
        min: p.min,
        typical: p.typical,
        max: p.max,
        material: p.material.clone(),
        aliases: p.aliases.clone(),
        surfaces: asset
            .surfaces
            .iter()
            .map(|s| {
                let kind = surface_kind(&s.id);
                SurfaceInfo {
                    id: s.id.clone(),
                    kind,
                    size: s.size,
                    clearance: s.clearance,
                    enclosed: kind == SurfaceKind::Drawer
                        || (has_joints && kind != SurfaceKind::Top),
                }
            })
            .collect(),
        joints: asset
            .joints
            .iter()
            .map(|j| JointInfo {
                name: j.name.clone(),
                kind: j.kind.as_str(),
                range: [j.lower, j.upper],
            })
            .collect(),
    })
}

/// Metadata of one category (or alias), built once and remembered.
pub fn info(category: &str) -> Option<CategoryInfo> {
    static MEMO: OnceLock<Mutex<BTreeMap<String, CategoryInfo>>> = OnceLock::new();
    let name = procedural::resolve_category(category)?;
    let memo = MEMO.get_or_init(|| Mutex::new(BTreeMap::new()));
    if let Some(i) = memo.lock().unwrap_or_else(|p| p.into_inner()).get(name) {
        return Some(i.clone());
    }
    let i = compute(name)?;
    memo.lock()
        .unwrap_or_else(|p| p.into_inner())
        .insert(name.to_string(), i.clone());
    Some(i)
}

/// Metadata of every category a stage can place, sorted by name.
pub fn for_stage(stage: Stage) -> Vec<CategoryInfo> {
    procedural::categories()
        .into_iter()
        .filter(|c| procedural::prior(c).is_some_and(|p| p.support == stage.support()))
        .filter_map(info)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn metadata_tells_where_things_go() {
        let t = info("dining table").unwrap();
        assert_eq!(t.name, "table");
        assert_eq!(t.stage, Stage::Furniture);
        assert!(
            t.surfaces
                .iter()
                .any(|s| s.id == "top" && s.kind == SurfaceKind::Top && !s.enclosed)
        );
        let d = info("dresser").unwrap();
        assert_eq!(d.kind, Kind::Articulated);
        assert!(d.joints.iter().all(|j| j.kind == "prismatic"));
        assert!(
            d.surfaces
                .iter()
                .any(|s| s.kind == SurfaceKind::Drawer && s.enclosed)
        );
        let b = info("bowl").unwrap();
        assert!(b.container);
        assert_eq!(b.stage, Stage::Manipuland);
        assert!(b.surfaces.iter().any(|s| s.kind == SurfaceKind::Inside));
        let walls = for_stage(Stage::Wall);
        assert!(walls.iter().any(|c| c.name == "mirror"));
        assert!(walls.iter().all(|c| c.support == SupportClass::Wall));
    }
}
