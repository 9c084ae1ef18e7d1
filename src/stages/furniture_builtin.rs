//! The built-in (offline) designer and critic of the furniture stage.
//!
//! The designer executes the room plan through the same tools an LLM would call; on a change
//! request it re-measures (missing pieces, collisions, unreachable pieces) and repairs, trying
//! other walls and corners after a rollback. The critic scores from measurements taken with the
//! observe and verify tools.

use serde_json::{Value, json};

use super::StageState;
use crate::agents::{
    AgentCx, AgentError, Critic, Critique, DesignRequest, Designer, Issue, Role, Score,
};
use crate::plan::Arrangement;

/// Whether a piece of this category is a seat that faces a table (`chair`, `dining_chair`,
/// `bar_stool`).
fn is_seat(category: &str) -> bool {
    let head = category.rsplit('_').next().unwrap_or(category);
    matches!(head, "chair" | "stool")
}

/// Whether chairs sit around a piece of this category: any table, desk, counter or island
/// (categories are snake_case nouns: `dining_table`, `bar_counter`, `kitchen_island`).
fn is_seat_parent(category: &str) -> bool {
    let head = category.rsplit('_').next().unwrap_or(category);
    matches!(head, "table" | "desk" | "counter" | "island" | "bar")
}

/// The built-in furniture designer.
#[derive(Debug, Default)]
pub struct BuiltinFurnitureDesigner;

fn ok(v: &Result<Value, crate::agents::ToolError>) -> bool {
    v.is_ok()
}

/// Ids of the objects a placement result reports.
fn placed_ids(v: &Value) -> Vec<String> {
    v["placed"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|o| o["id"].as_str().map(str::to_string))
                .collect()
        })
        .unwrap_or_default()
}

impl BuiltinFurnitureDesigner {
    /// Places one piece with fallbacks: the preferred arrangement, then walls, corners, centre.
    fn place_one(
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
        desc: &str,
        arrangement: &Arrangement,
        reverse: bool,
    ) -> bool {
        let mut attempts: Vec<(&str, Value)> = Vec::new();
        match arrangement {
            Arrangement::Center => attempts.push((
                "place_in_center",
                json!({"description": desc, "clearance_m": 0.6}),
            )),
            Arrangement::Corner => attempts.push(("place_in_corner", json!({"description": desc}))),
            Arrangement::NearWindow | Arrangement::NearEntrance => {
                let side = state.room().ok().and_then(|r| {
                    r.walls
                        .iter()
                        .find(|w| {
                            w.openings.iter().any(|o| {
                                let window = o.kind == crate::scene::OpeningKind::Window;
                                window == matches!(arrangement, Arrangement::NearWindow)
                            })
                        })
                        .map(|w| w.id.clone())
                });
                if let Some(w) = side {
                    attempts.push((
                        "place_against_wall",
                        json!({"description": desc, "wall": w}),
                    ));
                }
            }
            _ => {}
        }
        let sides = if reverse {
            ["west", "north", "east", "south"]
        } else {
            ["north", "east", "south", "west"]
        };
        for s in sides {
            attempts.push((
                "place_against_wall",
                json!({"description": desc, "wall": s}),
            ));
        }
        attempts.push(("place_in_corner", json!({"description": desc})));
        attempts.push(("place_in_center", json!({"description": desc})));
        for (tool, args) in attempts {
            if ok(&cx.call(state, Role::Designer, tool, args)) {
                return true;
            }
        }
        false
    }

    fn present(state: &StageState, noun: &str) -> Vec<String> {
        state
            .room_objects()
            .filter(|o| crate::assets::router::naming::object_is(&state.scene.scene, noun, o))
            .map(|o| o.id.clone())
            .collect()
    }

    fn build_plan(state: &mut StageState, cx: &mut AgentCx<'_, StageState>, reverse: bool) {
        let wants = state.plan.furniture.clone();
        for want in &wants {
            let have = Self::present(state, &want.noun).len() as u32;
            let mut need = want.count.saturating_sub(have);
            if need == 0 {
                continue;
            }
            if let Arrangement::Around { parent } = &want.arrangement {
                let parents = Self::present(state, parent);
                if !parents.is_empty() {
                    let per = need.div_ceil(parents.len() as u32);
                    for p in parents {
                        if need == 0 {
                            break;
                        }
                        let n = per.min(need);
                        if let Ok(v) = cx.call(
                            state,
                            Role::Designer,
                            "place_around",
                            json!({"parent": p, "description": want.description, "count": n}),
                        ) {
                            need = need.saturating_sub(placed_ids(&v).len() as u32);
                        }
                    }
                }
            }
            if let Arrangement::Facing { target } = &want.arrangement
                && let Some(t) = Self::present(state, target).first().cloned()
                && need > 0
                && cx
                    .call(
                        state,
                        Role::Designer,
                        "place_facing",
                        json!({"description": want.description, "target": t}),
                    )
                    .is_ok()
            {
                need -= 1;
            }
            for _ in 0..need {
                if !Self::place_one(state, cx, &want.description, &want.arrangement, reverse) {
                    break;
                }
            }
        }
    }

    /// Moves or removes pieces that collide or cannot be reached.
    fn repair(state: &mut StageState, cx: &mut AgentCx<'_, StageState>, reverse: bool) {
        let explicit: Vec<String> = state
            .plan
            .furniture
            .iter()
            .filter(|w| w.explicit)
            .map(|w| w.noun.clone())
            .collect();
        let mut troubled: Vec<String> = Vec::new();
        if let Ok(v) = cx.call(state, Role::Designer, "check_collisions", json!({})) {
            for c in v["collisions"].as_array().into_iter().flatten() {
                for key in ["b", "a"] {
                    if let Some(id) = c[key].as_str()
                        && state.scene.scene.object(id).is_some_and(|o| {
                            o.kind == crate::scene::ObjectKind::Furniture && o.room == state.room
                        })
                    {
                        troubled.push(id.to_string());
                        break;
                    }
                }
            }
        }
        if let Ok(v) = cx.call(state, Role::Designer, "check_reachability", json!({})) {
            for id in v["unreachable"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|x| x.as_str())
            {
                troubled.push(id.to_string());
            }
        }
        troubled.dedup();
        for id in troubled {
            let Some(obj) = state.scene.scene.object(&id).cloned() else {
                continue;
            };
            let is_explicit = explicit
                .iter()
                .any(|n| crate::assets::router::naming::object_is(&state.scene.scene, n, &obj));
            let _ = cx.call(state, Role::Designer, "remove_object", json!({"id": id}));
            if is_explicit {
                // Re-place a requested piece somewhere else; drop a default one.
                let arrangement = Arrangement::AgainstWall;
                Self::place_one(state, cx, &obj.category, &arrangement, !reverse);
            }
        }
    }
}

impl Designer<StageState> for BuiltinFurnitureDesigner {
    fn design(
        &mut self,
        state: &mut StageState,
        request: &DesignRequest,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<String, AgentError> {
        let _ = cx.call(state, Role::Designer, "observe_room", json!({}));
        let reverse = matches!(request, DesignRequest::AfterRollback { .. }) && cx.attempt % 2 == 1;
        match request {
            DesignRequest::Initial => Self::build_plan(state, cx, false),
            DesignRequest::Change { .. } | DesignRequest::AfterRollback { .. } => {
                Self::repair(state, cx, reverse);
                Self::build_plan(state, cx, reverse);
            }
        }
        let n = state
            .room_objects()
            .filter(|o| o.kind == crate::scene::ObjectKind::Furniture)
            .count();
        Ok(format!("{n} pieces of furniture in {}", state.room))
    }
}

/// The built-in furniture critic: scores from measurements.
#[derive(Debug, Default)]
pub struct BuiltinFurnitureCritic;

fn score(category: &str, value: f64, reason: String) -> Score {
    Score {
        category: category.to_string(),
        score: value.round().clamp(0.0, 10.0) as u8,
        reason,
    }
}

impl Critic<StageState> for BuiltinFurnitureCritic {
    fn critique(
        &mut self,
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<Critique, AgentError> {
        let unusable = |m: String| AgentError::Unusable {
            role: "critic",
            stage: "furniture".into(),
            message: m,
        };
        let obs = cx
            .call(state, Role::Critic, "observe_room", json!({}))
            .map_err(|e| unusable(e.message))?;
        let collisions = cx
            .call(state, Role::Critic, "check_collisions", json!({}))
            .map_err(|e| unusable(e.message))?;
        let reach = cx
            .call(state, Role::Critic, "check_reachability", json!({}))
            .map_err(|e| unusable(e.message))?;
        let mut issues = Vec::new();
        let furniture: Vec<&Value> = obs["objects"]
            .as_array()
            .map(|a| a.iter().filter(|o| o["kind"] == "furniture").collect())
            .unwrap_or_default();

        // Prompt following: requested furniture counts present, excluded absent.
        let mut wanted = 0u32;
        let mut got = 0u32;
        for r in obs["requested"].as_array().into_iter().flatten() {
            let noun = r["noun"].as_str().unwrap_or_default();
            let is_furniture = state.plan.furniture.iter().any(|w| w.noun == noun);
            if !is_furniture {
                continue;
            }
            let (w, p) = (
                r["wanted"].as_u64().unwrap_or(0) as u32,
                r["present"].as_u64().unwrap_or(0) as u32,
            );
            wanted += w;
            got += p.min(w);
            if p < w {
                issues.push(Issue {
                    objects: vec![],
                    description: format!("add {} more {noun} (asked for {w}, have {p})", w - p),
                });
            }
        }
        let mut excluded_present = 0;
        for e in obs["excluded"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|v| v.as_str())
        {
            for o in &furniture {
                if o["category"] == e {
                    excluded_present += 1;
                    issues.push(Issue {
                        objects: vec![o["id"].as_str().unwrap_or_default().into()],
                        description: format!("the prompt says no {e}; remove it"),
                    });
                }
            }
        }
        let coverage = if wanted == 0 {
            1.0
        } else {
            got as f64 / wanted as f64
        };
        let prompt_score = 10.0 * coverage - 3.0 * excluded_present as f64;

        // Functionality: seats face a table-like piece nearby.
        let parents: Vec<&Value> = furniture
            .iter()
            .copied()
            .filter(|o| is_seat_parent(o["category"].as_str().unwrap_or_default()))
            .collect();
        let mut seats = 0;
        let mut facing = 0;
        for chair in furniture
            .iter()
            .filter(|o| is_seat(o["category"].as_str().unwrap_or_default()))
        {
            let (x, y, yaw) = (
                chair["x"].as_f64().unwrap_or(0.0),
                chair["y"].as_f64().unwrap_or(0.0),
                chair["yaw_deg"].as_f64().unwrap_or(0.0).to_radians(),
            );
            let nearest = parents.iter().min_by(|a, b| {
                let da =
                    (a["x"].as_f64().unwrap_or(0.0) - x).hypot(a["y"].as_f64().unwrap_or(0.0) - y);
                let db =
                    (b["x"].as_f64().unwrap_or(0.0) - x).hypot(b["y"].as_f64().unwrap_or(0.0) - y);
                da.total_cmp(&db)
            });
            let Some(p) = nearest else { continue };
            let (px, py) = (
                p["x"].as_f64().unwrap_or(0.0),
                p["y"].as_f64().unwrap_or(0.0),
            );
            let reach = p["size_m"][0]
                .as_f64()
                .unwrap_or(1.0)
                .max(p["size_m"][1].as_f64().unwrap_or(1.0))
                / 2.0
                + 1.0;
            if (px - x).hypot(py - y) > reach {
                continue;
            }
            seats += 1;
            let front = [-yaw.sin(), yaw.cos()];
            let to = [px - x, py - y];
            let n = to[0].hypot(to[1]).max(1e-9);
            if (front[0] * to[0] + front[1] * to[1]) / n > 0.8 {
                facing += 1;
            } else {
                issues.push(Issue {
                    objects: vec![chair["id"].as_str().unwrap_or_default().into()],
                    description: format!(
                        "turn it to face {}",
                        p["id"].as_str().unwrap_or_default()
                    ),
                });
            }
        }
        let function_score = if seats == 0 {
            10.0
        } else {
            10.0 * facing as f64 / seats as f64
        };

        // Spatial layout: how much floor the furniture takes.
        let floor =
            obs["size_m"][0].as_f64().unwrap_or(1.0) * obs["size_m"][1].as_f64().unwrap_or(1.0);
        let used: f64 = furniture
            .iter()
            .map(|o| {
                o["size_m"][0].as_f64().unwrap_or(0.0) * o["size_m"][1].as_f64().unwrap_or(0.0)
            })
            .sum();
        let frac = used / floor.max(1e-9);
        let layout_score = if furniture.is_empty() {
            3.0
        } else if frac > 0.6 {
            issues.push(Issue {
                objects: vec![],
                description: format!(
                    "the floor is crammed ({:.0}% covered); remove or shrink pieces",
                    frac * 100.0
                ),
            });
            10.0 - (frac - 0.6) * 25.0
        } else {
            10.0
        };

        // Reachability.
        let nav = reach["nav"].as_f64().unwrap_or(0.0);
        let unreachable: Vec<String> = reach["unreachable"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|v| v.as_str().map(str::to_string))
            .collect();
        for id in &unreachable {
            issues.push(Issue {
                objects: vec![id.clone()],
                description: format!(
                    "{id} cannot be reached from the door; move it or clear a path"
                ),
            });
        }
        let reach_score = 10.0
            - 2.0 * unreachable.len() as f64
            - if nav < 0.95 { 10.0 * (0.95 - nav) } else { 0.0 };

        // Physical feasibility.
        let pairs: Vec<&Value> = collisions["collisions"]
            .as_array()
            .map(|a| a.iter().collect())
            .unwrap_or_default();
        for p in &pairs {
            issues.push(Issue {
                objects: vec![
                    p["a"].as_str().unwrap_or_default().into(),
                    p["b"].as_str().unwrap_or_default().into(),
                ],
                description: format!(
                    "{} and {} overlap by {} mm; move one",
                    p["a"].as_str().unwrap_or_default(),
                    p["b"].as_str().unwrap_or_default(),
                    p["depth_mm"]
                ),
            });
        }
        let physics_score = 10.0 - 3.0 * pairs.len() as f64;

        Ok(Critique {
            scores: vec![
                score(
                    "prompt_following",
                    prompt_score,
                    format!(
                        "{got} of {wanted} requested pieces present{}",
                        if excluded_present > 0 {
                            format!(", {excluded_present} excluded pieces present")
                        } else {
                            String::new()
                        }
                    ),
                ),
                score(
                    "functionality",
                    function_score,
                    format!("{facing} of {seats} seats face their table"),
                ),
                score(
                    "spatial_layout",
                    layout_score,
                    format!("furniture covers {:.0}% of the floor", frac * 100.0),
                ),
                score(
                    "reachability",
                    reach_score,
                    format!("NAV {nav:.2}, {} unreachable", unreachable.len()),
                ),
                score(
                    "physical_feasibility",
                    physics_score,
                    format!("{} penetrating pairs", pairs.len()),
                ),
            ],
            issues,
        })
    }
}
