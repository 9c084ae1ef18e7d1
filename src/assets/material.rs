//! The physical material table (friction, density, contact dissipation, default colour),
//! compiled in from `src/data/materials.json`.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

/// The contact model every collision geometry of a scene declares in its SDFormat file, so
/// that Drake's default plant (`MultibodyPlantConfig()`: hydroelastic with point fallback)
/// simulates what settling simulated: compliant hydroelastic at this modulus, Pa ...
pub const HYDROELASTIC_MODULUS_PA: f64 = 1e8;

/// ... with Hunt-Crossley dissipation of at least this, s/m. At the table's 0.5 to 3 s/m a
/// cube dropped 2 cm onto a table top kept rocking (3 mm/s, 0.1 rad/s); from 4 s/m up it
/// rests within 0.3 s, and 10 s/m leaves stacks of boxes where they were.
pub const MIN_HUNT_CROSSLEY_DISSIPATION: f64 = 10.0;

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

#[derive(Deserialize)]
struct SpreadEntry {
    #[serde(default = "default_spread")]
    density_spread: f64,
}

#[derive(Deserialize)]
struct SpreadTable {
    materials: BTreeMap<String, SpreadEntry>,
}

fn default_spread() -> f64 {
    0.15
}

const TABLE_JSON: &str = include_str!("../data/materials.json");

fn table() -> &'static BTreeMap<String, Material> {
    static TABLE: OnceLock<BTreeMap<String, Material>> = OnceLock::new();
    TABLE.get_or_init(|| {
        // The file is part of the binary and checked by a unit test; an error here is a bug in
        // the shipped data, not bad user input.
        serde_json::from_str::<Table>(TABLE_JSON)
            .map(|t| t.materials)
            .unwrap_or_default()
    })
}

/// Relative spread of real densities of a material (`0.15` = +-15 %), used for the mass range
/// written for domain randomisation; 0.15 for unknown names.
pub fn spread(name: &str) -> f64 {
    static SPREAD: OnceLock<BTreeMap<String, f64>> = OnceLock::new();
    SPREAD
        .get_or_init(|| {
            serde_json::from_str::<SpreadTable>(TABLE_JSON)
                .map(|t| {
                    t.materials
                        .into_iter()
                        .map(|(k, v)| (k, v.density_spread))
                        .collect()
                })
                .unwrap_or_default()
        })
        .get(name)
        .copied()
        .unwrap_or_else(default_spread)
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
        for (name, mu, rho) in [
            ("ceramic", 0.35, 2400.0),
            ("glass", 0.9, 2500.0),
            ("fabric", 0.40, 500.0),
            ("rubber", 1.15, 1100.0),
            ("paper", 0.32, 900.0),
        ] {
            let m = material(name).unwrap();
            assert_eq!((m.mu_dynamic, m.density), (mu, rho), "{name}");
        }
        for n in super::names() {
            let s = spread(n);
            assert!(s > 0.0 && s < 0.5, "{n}: spread {s}");
        }
    }

    /// The room registry names materials of this table (room type floors and walls, prompt
    /// material words, wet-room floors) but sits below `assets`, so it cannot check them when
    /// it loads; this test does, where both are visible.
    #[test]
    fn every_material_the_room_registry_names_is_in_the_table() {
        let registry = crate::knowledge::rooms::Registry::compiled().unwrap();
        for (key, t) in registry.types() {
            for m in [&t.floor, &t.wall] {
                assert!(
                    material(m).is_some(),
                    "room type {key}: unknown material {m:?}"
                );
            }
        }
        let h = registry.house();
        for m in h.materials.values().chain(&h.wet_floor_materials) {
            assert!(material(m).is_some(), "_house: unknown material {m:?}");
        }
    }
}
