//! The built-in (offline) designer and critic of the layout stage.
//!
//! The designer generates the rooms from the prompt (when there are none yet) and repairs what
//! validation and the critic report, through the same tools an LLM would call: doors for cut-off
//! rooms, no passage through bathrooms, squarer rooms, windows, water-resistant floors in wet
//! rooms. The critic scores from measurements only (observe_scene and validate).

use serde_json::{Value, json};

use super::search::MIN_SHARED;
use super::state::LayoutState;
use crate::agents::{
    AgentCx, AgentError, Critic, Critique, DesignRequest, Designer, Issue, Role, Score,
};

/// Longest side over shortest side above which a room (not a corridor) looks wrong.
pub const MAX_ASPECT: f64 = 2.2;

/// The built-in layout designer.
#[derive(Debug, Default)]
pub struct BuiltinLayoutDesigner;

fn strs(v: &Value) -> Vec<String> {
    v.as_array()
        .map(|a| {
            a.iter()
                .filter_map(|x| x.as_str().map(str::to_string))
                .collect()
        })
        .unwrap_or_default()
}

fn room<'a>(obs: &'a Value, id: &str) -> Option<&'a Value> {
    obs["rooms"].as_array()?.iter().find(|r| r["id"] == id)
}

impl BuiltinLayoutDesigner {
    /// Gives every unreachable room a door to a reachable neighbour that is not a bathroom,
    /// or moves it next to one of its parents.
    fn connect(state: &mut LayoutState, cx: &mut AgentCx<'_, LayoutState>, v: &Value) {
        let Ok(obs) = cx.call(state, Role::Designer, "observe_scene", json!({})) else {
            return;
        };
        let lost = strs(&v["unreachable"]);
        let through_bath = strs(&v["only_through_bathroom"]);
        for id in lost.iter().chain(&through_bath) {
            let Some(r) = room(&obs, id) else { continue };
            // Drop doors that lead in through a bathroom.
            for d in strs(&r["doors"]) {
                let (door, to) = d.split_once(" -> ").unwrap_or((d.as_str(), ""));
                let via_bath = room(&obs, to).is_some_and(|n| n["role"] == "wet");
                if via_bath && r["role"] != "wet" {
                    let _ = cx.call(state, Role::Designer, "remove_door", json!({"id": door}));
                }
            }
            let reachable =
                |n: &str| !lost.contains(&n.to_string()) && !through_bath.contains(&n.to_string());
            let mut options: Vec<(String, f64, i32)> = r["neighbors"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|n| {
                    let nid = n[0].as_str()?.to_string();
                    let len = n[1].as_f64()?;
                    let info = room(&obs, &nid)?;
                    let rank = match info["role"].as_str()? {
                        "hub" => 0,
                        "entry" => 1,
                        "public" => 2,
                        "private" => 3,
                        "service" => 4,
                        _ => return None,
                    };
                    (len >= MIN_SHARED && reachable(&nid)).then_some((nid, len, rank))
                })
                .collect();
            options.sort_by(|a, b| a.2.cmp(&b.2).then(b.1.total_cmp(&a.1)));
            let done = options.iter().any(|(nid, _, _)| {
                cx.call(
                    state,
                    Role::Designer,
                    "add_door",
                    json!({"room_a": id, "room_b": nid, "position": "center"}),
                )
                .is_ok()
            });
            if !done {
                let target = strs(&r["parents"])
                    .into_iter()
                    .next()
                    .unwrap_or_else(|| obs["entrance"].as_str().unwrap_or_default().to_string());
                if !target.is_empty() && target != *id {
                    let _ = cx.call(
                        state,
                        Role::Designer,
                        "add_adjacency",
                        json!({"room_a": id, "room_b": target}),
                    );
                }
            }
        }
        if v["exterior_doors"].as_u64() == Some(0) {
            let entrance = obs["entrance"].as_str().unwrap_or_default();
            let _ = cx.call(
                state,
                Role::Designer,
                "add_door",
                json!({"room_a": entrance, "room_b": "outside"}),
            );
        }
    }

    /// Squarer rooms, windows where wanted, water-resistant floors in wet rooms.
    fn improve(state: &mut LayoutState, cx: &mut AgentCx<'_, LayoutState>) {
        let Ok(obs) = cx.call(state, Role::Designer, "observe_scene", json!({})) else {
            return;
        };
        for r in obs["rooms"].as_array().into_iter().flatten() {
            let id = r["id"].as_str().unwrap_or_default();
            let (w, d) = (
                r["size_m"][0].as_f64().unwrap_or(1.0),
                r["size_m"][1].as_f64().unwrap_or(1.0),
            );
            let aspect = w.max(d) / w.min(d).max(0.1);
            if r["role"] != "hub" && aspect > MAX_ASPECT {
                let area = w * d;
                let short = (area / 1.5).sqrt();
                let _ = cx.call(
                    state,
                    Role::Designer,
                    "resize_room",
                    json!({"room": id, "width_m": (short * 1.5 * 10.0).round() / 10.0, "depth_m": (short * 10.0).round() / 10.0}),
                );
            }
            if r["wants_windows"] == true && r["windows"] == 0 {
                let _ = cx.call(state, Role::Designer, "add_window", json!({"room": id}));
            }
            let floor = r["floor"].as_str().unwrap_or_default();
            let wet_ok = super::knowledge::knowledge()
                .house()
                .wet_floor_materials
                .iter()
                .any(|m| m == floor);
            let asked = obs["requested_materials"]
                .as_array()
                .into_iter()
                .flatten()
                .any(|m| m[0] == id && !m[1].is_null());
            if r["role"] == "wet" && !wet_ok && !asked {
                let _ = cx.call(
                    state,
                    Role::Designer,
                    "set_room_materials",
                    json!({"room": id, "floor": "tile"}),
                );
            }
        }
    }
}

impl Designer<LayoutState> for BuiltinLayoutDesigner {
    fn design(
        &mut self,
        state: &mut LayoutState,
        request: &DesignRequest,
        cx: &mut AgentCx<'_, LayoutState>,
    ) -> Result<String, AgentError> {
        if state.spec.is_none() {
            let _ = cx.call(state, Role::Designer, "generate_room_specs", json!({}));
        }
        if !matches!(request, DesignRequest::Initial) {
            Self::improve(state, cx);
        }
        for _ in 0..3 {
            let Ok(v) = cx.call(state, Role::Designer, "validate", json!({})) else {
                break;
            };
            if v["ok"] == true {
                break;
            }
            Self::connect(state, cx, &v);
        }
        let _ = cx.call(state, Role::Designer, "render_ascii", json!({}));
        let n = state.spec.as_ref().map(|s| s.rooms.len()).unwrap_or(0);
        Ok(format!("{n} rooms laid out"))
    }
}

/// The built-in layout critic: scores from measurements.
#[derive(Debug, Default)]
pub struct BuiltinLayoutCritic;

fn score(category: &str, value: f64, reason: String) -> Score {
    Score {
        category: category.to_string(),
        score: value.round().clamp(0.0, 10.0) as u8,
        reason,
    }
}

impl Critic<LayoutState> for BuiltinLayoutCritic {
    fn critique(
        &mut self,
        state: &mut LayoutState,
        cx: &mut AgentCx<'_, LayoutState>,
    ) -> Result<Critique, AgentError> {
        let unusable = |m: String| AgentError::Unusable {
            role: "critic",
            stage: "layout".into(),
            message: m,
        };
        let obs = cx
            .call(state, Role::Critic, "observe_scene", json!({}))
            .map_err(|e| unusable(e.message))?;
        let v = cx
            .call(state, Role::Critic, "validate", json!({}))
            .map_err(|e| unusable(e.message))?;
        let rooms: Vec<&Value> = obs["rooms"]
            .as_array()
            .map(|a| a.iter().collect())
            .unwrap_or_default();
        let mut issues = Vec::new();
        let issue = |ids: Vec<String>, d: String| Issue {
            objects: ids,
            description: d,
        };

        // Proportions: usable shapes for everything but corridors.
        let mut proportions = 10.0;
        for r in rooms.iter().filter(|r| r["role"] != "hub") {
            let (w, d) = (
                r["size_m"][0].as_f64().unwrap_or(1.0),
                r["size_m"][1].as_f64().unwrap_or(1.0),
            );
            let aspect = w.max(d) / w.min(d).max(0.1);
            let id = r["id"].as_str().unwrap_or_default().to_string();
            if aspect > MAX_ASPECT {
                proportions -= 2.0 * (aspect - MAX_ASPECT).min(2.0) + 1.0;
                issues.push(issue(
                    vec![id.clone()],
                    format!("{id} is {w:.1} x {d:.1} m (ratio {aspect:.1}); resize it to a squarer shape"),
                ));
            }
            if w.min(d) < 1.5 {
                proportions -= 2.0;
                issues.push(issue(
                    vec![id.clone()],
                    format!("{id} is only {:.1} m wide", w.min(d)),
                ));
            }
        }

        // Flow: reachability, bathrooms, en-suites, hubs, required neighbours.
        let unreachable = strs(&v["unreachable"]);
        let via_bath = strs(&v["only_through_bathroom"]);
        let via_room = strs(&v["only_through_room"]);
        let mut flow = 10.0
            - 3.0 * unreachable.len() as f64
            - 3.0 * via_bath.len() as f64
            - 0.5 * via_room.len() as f64;
        for e in strs(&v["errors"]) {
            if e.contains("en-suite") || e.contains("must share a wall") {
                flow -= 2.0;
            }
            if e.contains("no exterior door") {
                flow -= 5.0;
            }
            issues.push(issue(vec![], e));
        }
        for id in &via_room {
            issues.push(issue(
                vec![id.clone()],
                format!("{id} is reached only through another room; connect it to a corridor or hallway if possible"),
            ));
        }

        // Daylight.
        let want: Vec<&&Value> = rooms
            .iter()
            .filter(|r| r["wants_windows"] == true)
            .collect();
        let lit = want
            .iter()
            .filter(|r| r["windows"].as_u64().unwrap_or(0) > 0)
            .count();
        for r in want.iter().filter(|r| r["windows"] == 0) {
            let id = r["id"].as_str().unwrap_or_default().to_string();
            issues.push(issue(
                vec![id.clone()],
                format!(
                    "{id} has no window; add one on an outside wall (or move it to the outside)"
                ),
            ));
        }
        let lighting = if want.is_empty() {
            10.0
        } else {
            10.0 * lit as f64 / want.len() as f64
        };

        // Materials: wet rooms on water-resistant floors, the prompt's materials used, one
        // floor per room type.
        let wet_ok = &super::knowledge::knowledge().house().wet_floor_materials;
        let mut materials = 10.0;
        for r in rooms.iter().filter(|r| r["role"] == "wet") {
            let floor = r["floor"].as_str().unwrap_or_default();
            if !wet_ok.iter().any(|m| m == floor) {
                materials -= 3.0;
                issues.push(issue(
                    vec![r["id"].as_str().unwrap_or_default().into()],
                    format!("a {floor} floor in a wet room; use tile or stone"),
                ));
            }
        }
        for m in obs["requested_materials"].as_array().into_iter().flatten() {
            let Some(r) = m[0]
                .as_str()
                .and_then(|id| rooms.iter().find(|r| r["id"] == id))
            else {
                continue;
            };
            for (k, key) in [(1, "floor"), (2, "wall")] {
                if let Some(want) = m[k].as_str()
                    && r[key] != want
                {
                    materials -= 3.0;
                    issues.push(issue(
                        vec![r["id"].as_str().unwrap_or_default().into()],
                        format!("the prompt asks for a {want} {key}; it is {}", r[key]),
                    ));
                }
            }
        }
        for r in &rooms {
            if super::knowledge::material_word(r["floor"].as_str().unwrap_or_default()).is_none() {
                materials -= 2.0;
            }
        }

        // Prompt following: rooms with their counts, height.
        let (mut wanted, mut present) = (0usize, 0usize);
        for q in obs["requested"].as_array().into_iter().flatten() {
            let (w, p) = (
                q["wanted"].as_u64().unwrap_or(0) as usize,
                q["present"].as_u64().unwrap_or(0) as usize,
            );
            wanted += w;
            present += p.min(w);
            if p < w {
                issues.push(issue(
                    vec![],
                    format!("the prompt asks for {w} {}, there are {p}", q["room_type"]),
                ));
            }
        }
        let mut following = if wanted == 0 {
            10.0
        } else {
            10.0 * present as f64 / wanted as f64
        };
        if let Some(h) = obs["requested_wall_height_m"].as_f64()
            && (obs["wall_height_m"].as_f64().unwrap_or(0.0) - h).abs() > 0.05
        {
            following -= 2.0;
            issues.push(issue(
                vec![],
                format!("the prompt asks for {h:.2} m ceilings"),
            ));
        }

        Ok(Critique {
            scores: vec![
                score(
                    "room_proportions",
                    proportions,
                    "aspect ratios and widths of the rooms".into(),
                ),
                score(
                    "spatial_flow",
                    flow,
                    format!(
                        "{} unreachable, {} only through a bathroom, {} only through another room",
                        unreachable.len(),
                        via_bath.len(),
                        via_room.len()
                    ),
                ),
                score(
                    "natural_lighting",
                    lighting,
                    format!(
                        "{lit} of {} rooms that want daylight have windows",
                        want.len()
                    ),
                ),
                score(
                    "material_consistency",
                    materials,
                    "floor and wall materials per room".into(),
                ),
                score(
                    "prompt_following",
                    following,
                    format!("{present} of {wanted} requested rooms present"),
                ),
            ],
            issues,
        })
    }
}
