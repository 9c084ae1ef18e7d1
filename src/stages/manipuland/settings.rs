//! Place settings: plate, glass and cutlery laid at the table edge in front of every seat
//! that faces the table.

use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::Deserialize;

use super::fit::{add_item, fit, item_rotation};
use super::surface::find_surface;
use super::tools::{PlaceResult, result_for};
use crate::agents::ToolError;
use crate::stages::StageState;

/// Place settings at a table.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct SettingsArgs {
    /// Table top surface (`object_id/surface_id`).
    pub surface: String,
    /// Items of one setting, e.g. ["plate", "glass", "fork", "knife"].
    pub items: Vec<String>,
    /// Number of settings; one per seat facing the table when omitted.
    #[serde(default)]
    pub settings: Option<u32>,
}

/// Categories laid as a place setting's plate.
const SETTING_PLATES: [&str; 3] = ["plate", "dinner plate", "dish"];

/// Whether `noun` is a plate that a place setting lays in front of a seat.
pub(super) fn is_setting_plate(noun: &str) -> bool {
    crate::assets::router::naming::category_of(noun)
        .is_some_and(|c| SETTING_PLATES.contains(&c.replace('_', " ").as_str()))
}

/// Item offsets of a place setting: (u across, v towards the table centre) from the edge
/// point in front of the seat, metres; and a yaw for cutlery.
fn setting_offset(noun: &str) -> (f64, f64, f64) {
    match noun {
        n if SETTING_PLATES.contains(&n) => (0.0, 0.19, 0.0),
        "fork" => (-0.17, 0.19, 0.0),
        "knife" => (0.17, 0.19, 0.0),
        "spoon" => (0.21, 0.19, 0.0),
        "napkin" => (-0.24, 0.17, 0.0),
        "glass" | "wine glass" | "cup" | "mug" | "teacup" => (0.19, 0.36, 0.0),
        _ => (-0.2, 0.36, 0.0),
    }
}

pub(super) fn place_settings(
    state: &mut StageState,
    a: SettingsArgs,
) -> Result<PlaceResult, ToolError> {
    let s = find_surface(state, &a.surface)?;
    // Seats: chairs, stools and benches near the table whose front faces it.
    let table_xy = s.world_from_surface().translation();
    let (hw, hd) = (s.surface.size[0] / 2.0, s.surface.size[1] / 2.0);
    let surface_from_world = s.world_from_surface().inverse();
    let mut seats: Vec<(f64, f64, f64)> = Vec::new(); // edge point (u, v) and inward yaw
    for o in state.room_objects() {
        if !matches!(
            state.scene.scene.built_as(o),
            "chair" | "stool" | "bar_stool" | "bar stool" | "bench" | "armchair"
        ) {
            continue;
        }
        let local = surface_from_world.compose(&o.world_from_object);
        let p = local.translation();
        let front = local.transform_vector(&Vector3::y());
        let dist_out_u = p.x.abs() - hw;
        let dist_out_v = p.y.abs() - hd;
        if dist_out_u > 0.8 || dist_out_v > 0.8 || (dist_out_u < 0.0 && dist_out_v < 0.0) {
            continue;
        }
        let to_center = Vector3::new(-p.x, -p.y, 0.0).normalize();
        if front.dot(&to_center) < 0.5 {
            continue;
        }
        // Edge point: project the seat onto the nearest table edge.
        let (eu, ev, inward) = if dist_out_v >= dist_out_u {
            (
                p.x.clamp(-hw, hw),
                hd * p.y.signum(),
                if p.y > 0.0 { std::f64::consts::PI } else { 0.0 },
            )
        } else {
            (
                hw * p.x.signum(),
                p.y.clamp(-hd, hd),
                if p.x > 0.0 {
                    std::f64::consts::FRAC_PI_2
                } else {
                    -std::f64::consts::FRAC_PI_2
                },
            )
        };
        seats.push((eu, ev, inward));
    }
    let _ = table_xy;
    if seats.is_empty() {
        return Err(ToolError::failed(format!(
            "no seats face {}; place chairs first or use place_on_surface",
            s.parent.id
        )));
    }
    let n = a
        .settings
        .map(|n| n as usize)
        .unwrap_or(seats.len())
        .min(seats.len());
    let mut ids = Vec::new();
    let mut notes = Vec::new();
    for &(eu, ev, inward) in seats.iter().take(n) {
        let (sin, cos) = inward.sin_cos();
        for item in &a.items {
            let routed = match state.route_asset(item, None) {
                Ok(r) => r,
                Err(e) => {
                    notes.push(e.message);
                    continue;
                }
            };
            for n in &routed.notes {
                if !notes.contains(n) {
                    notes.push(n.clone());
                }
            }
            let rec = state.scene.scene.assets[&routed.asset].clone();
            let (du, dv, yaw) = setting_offset(&routed.category);
            // Rotate the (across, inward) offset into the surface frame.
            let u = eu + du * cos - dv * sin;
            let v = ev + du * sin + dv * cos;
            match fit(
                state,
                &s,
                &rec,
                &item_rotation(inward.to_degrees() + yaw, false),
                Some((u, v)),
                &[],
            ) {
                Ok((pose, _)) => {
                    ids.push(add_item(state, &routed, pose, &s.parent.id, &s.surface.id))
                }
                Err(e) => notes.push(format!("{item}: {e}")),
            }
        }
    }
    if ids.is_empty() {
        return Err(ToolError::failed(format!(
            "no place setting fits: {}",
            notes.join("; ")
        )));
    }
    result_for(state, &ids, notes)
}
