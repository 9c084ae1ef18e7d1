//! The physical material table (friction, density, contact dissipation, default colour),
//! compiled in from `src/data/materials.json`.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

/// Physical and visual defaults of one material.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq)]
pub struct Material {
    /// Coulomb dynamic friction coefficient.
    pub mu_dynamic: f64,
    /// Coulomb static friction coefficient (>= `mu_dynamic`).
    pub mu_static: f64,
    /// Density, kg/m^3.
    pub density: f64,
    /// Hunt-Crossley dissipation, s/m.
    pub hunt_crossley_dissipation: f64,
    /// Default base colour, linear RGB in [0, 1].
    pub color: [f64; 3],
}

#[derive(Deserialize)]
struct Table {
    materials: BTreeMap<String, Material>,
}

fn table() -> &'static BTreeMap<String, Material> {
    static TABLE: OnceLock<BTreeMap<String, Material>> = OnceLock::new();
    TABLE.get_or_init(|| {
        // The file is part of the binary and checked by a unit test; an error here is a bug in
        // the shipped data, not bad user input.
        serde_json::from_str::<Table>(include_str!("../data/materials.json"))
            .map(|t| t.materials)
            .unwrap_or_default()
    })
}

/// The material called `name`, if the table has it.
pub fn material(name: &str) -> Option<Material> {
    table().get(name).copied()
}

/// The material called `name`, or plain wood when the table has no such entry.
pub fn material_or_default(name: &str) -> Material {
    material(name)
        .or_else(|| material("wood"))
        .unwrap_or(Material {
            mu_dynamic: 0.4,
            mu_static: 0.5,
            density: 600.0,
            hunt_crossley_dissipation: 1.0,
            color: [0.55, 0.38, 0.22],
        })
}

/// All material names, sorted.
pub fn names() -> Vec<&'static str> {
    table().keys().map(String::as_str).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_complete_and_physical() {
        let names = names();
        assert!(names.len() >= 19, "only {} materials", names.len());
        for n in names {
            let m = material(n).unwrap();
            assert!(m.mu_static >= m.mu_dynamic, "{n}: static < dynamic");
            assert!(m.mu_dynamic > 0.0 && m.density > 0.0, "{n}");
            assert!(m.color.iter().all(|c| (0.0..=1.0).contains(c)), "{n}");
        }
        let wood = material("wood").unwrap();
        assert_eq!((wood.mu_dynamic, wood.density), (0.40, 600.0));
        assert_eq!(material("steel").unwrap().density, 7800.0);
    }
}
