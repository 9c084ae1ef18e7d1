//! The built-in (offline) designer and critic of the furniture stage.
//!
//! The designer executes the room plan through the same tools an LLM would call; on a change
//! request it re-measures (missing pieces, collisions, unreachable pieces) and repairs, trying
//! other walls and corners after a rollback. The critic scores from measurements taken with the
//! observe and verify tools.

use serde_json::{Value, json};

use crate::agents::{
    AgentCx, AgentError, Critic, Critique, DesignRequest, Designer, Issue, Role, Score,
};
use crate::plan::{Arrangement, RoomPlan, Want};
use crate::stages::StageState;

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
        guard: bool,
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
            if Self::call_guarded(state, cx, tool, args, guard) {
                return true;
            }
        }
        false
    }

    /// How many pieces the robot cannot reach from the door.
    fn unreachable_count(state: &mut StageState, cx: &mut AgentCx<'_, StageState>) -> usize {
        cx.call(state, Role::Designer, "check_reachability", json!({}))
            .map(|v| v["unreachable"].as_array().map_or(0, Vec::len))
            .unwrap_or(0)
    }

    /// Calls a placement tool; with `guard` (a room default, not a piece the prompt asked for)
    /// a piece that cuts anything off from the door is taken back (a floor lamp and a plant
    /// that box a nightstand in), and the call counts as failed.
    fn call_guarded(
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
        tool: &str,
        args: Value,
        guard: bool,
    ) -> bool {
        let before = if guard {
            Self::unreachable_count(state, cx)
        } else {
            0
        };
        let Ok(v) = cx.call(state, Role::Designer, tool, args) else {
            return false;
        };
        if guard && Self::unreachable_count(state, cx) > before {
            for id in placed_ids(&v) {
                let _ = cx.call(state, Role::Designer, "remove_object", json!({"id": id}));
            }
            return false;
        }
        true
    }

    /// The plan's furniture in the order it is placed: the plan's order, except that a piece
    /// placed relative to another piece of the plan comes right after that piece (the
    /// nightstands after the bed, before the dresser can take the bed's sides), what the
    /// prompt asked for before the room's defaults.
    fn in_placing_order(wants: &[Want]) -> Vec<Want> {
        let anchor = |w: &Want| {
            w.arrangement.target().and_then(|t| {
                (!Self::of_own_kind(w, t))
                    .then(|| wants.iter().position(|o| o.noun == t))
                    .flatten()
            })
        };
        let mut order: Vec<usize> = Vec::new();
        fn visit(i: usize, wants: &[Want], anchors: &[Option<usize>], order: &mut Vec<usize>) {
            if order.contains(&i) {
                return;
            }
            order.push(i);
            let mut followers: Vec<usize> = (0..wants.len())
                .filter(|&j| anchors[j] == Some(i))
                .collect();
            followers.sort_by_key(|&j| !wants[j].explicit);
            for j in followers {
                visit(j, wants, anchors, order);
            }
        }
        let anchors: Vec<Option<usize>> = wants.iter().map(anchor).collect();
        for i in 0..wants.len() {
            if anchors[i].is_none() {
                visit(i, wants, &anchors, &mut order);
            }
        }
        for i in 0..wants.len() {
            visit(i, wants, &anchors, &mut order); // left over: a cycle of relations
        }
        order.into_iter().map(|i| wants[i].clone()).collect()
    }

    /// Whether the plan puts pieces beside or flanking `want` (nightstands by a bed).
    fn has_side_followers(want: &Want, wants: &[Want]) -> bool {
        wants.iter().any(|w| match &w.arrangement {
            Arrangement::Beside { target } | Arrangement::Flanking { target } => {
                *target == want.noun
            }
            _ => false,
        })
    }

    /// Places up to `need` pieces of `want` against a wall, as near its middle as is free,
    /// leaving room at both sides for what goes beside them; returns how many it placed.
    fn place_centred_on_a_wall(
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
        want: &Want,
        need: u32,
    ) -> u32 {
        let walls: Vec<(String, f64)> = state
            .room()
            .map(|r| {
                r.walls
                    .iter()
                    .map(|w| (w.id.clone(), w.length() / 2.0))
                    .collect()
            })
            .unwrap_or_default();
        let mut placed = 0;
        'pieces: while placed < need {
            for (wall, middle) in &walls {
                let args =
                    json!({"description": want.description, "wall": wall, "along_m": middle});
                if Self::call_guarded(state, cx, "place_against_wall", args, !want.explicit) {
                    placed += 1;
                    continue 'pieces;
                }
            }
            break;
        }
        placed
    }

    /// Whether `target` names the want's own kind ("two sofas facing each other").
    fn of_own_kind(want: &Want, target: &str) -> bool {
        want.noun == target || want.noun.ends_with(&format!(" {target}"))
    }

    /// Places up to `need` pieces of `want` where its arrangement relates them to other
    /// pieces in the room (beside, flanking, in front of, behind, between, across from,
    /// facing each other) with `place_relative` / `place_facing`; returns how many it placed.
    /// What it cannot place that way is left to the caller's fallbacks.
    fn place_related(
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
        want: &Want,
        wants: &[Want],
        need: u32,
    ) -> u32 {
        let desc = want.description.as_str();
        // A room default must not cut anything off from the door (armchairs beside a coffee
        // table that two sofas already face).
        let call = |state: &mut StageState, cx: &mut AgentCx<'_, StageState>, tool, args| {
            Self::call_guarded(state, cx, tool, args, !want.explicit)
        };
        let relative = |target: &str, relation: &str| json!({"description": desc, "target": target, "relation": relation});
        let mut placed = 0;
        match &want.arrangement {
            Arrangement::Beside { target }
            | Arrangement::Flanking { target }
            | Arrangement::InFront { target }
            | Arrangement::Behind { target } => {
                let relation = match &want.arrangement {
                    Arrangement::InFront { .. } => "in_front",
                    Arrangement::Behind { .. } => "behind",
                    _ => "beside",
                };
                let targets = Self::present(state, target);
                'pieces: while placed < need {
                    for t in &targets {
                        if call(state, cx, "place_relative", relative(t, relation)) {
                            placed += 1;
                            continue 'pieces;
                        }
                    }
                    break;
                }
            }
            Arrangement::Between { targets } => {
                let mut ends: Vec<String> = Vec::new();
                for t in targets {
                    let present = Self::present(state, t);
                    let take = if targets.len() == 1 { 2 } else { 1 };
                    let fresh: Vec<String> = present
                        .into_iter()
                        .filter(|id| !ends.contains(id))
                        .take(take)
                        .collect();
                    ends.extend(fresh);
                }
                if let [a, b, ..] = ends.as_slice() {
                    let mut args = relative(a, "between");
                    args["second"] = json!(b);
                    if call(state, cx, "place_relative", args) {
                        placed += 1;
                    }
                }
            }
            Arrangement::AcrossFrom { target } if target != "entrance" => {
                if let Some(t) = Self::present(state, target).first() {
                    let args = json!({"description": desc, "target": t, "distance_m": 1.2});
                    if call(state, cx, "place_facing", args) {
                        placed += 1;
                    }
                }
            }
            Arrangement::Facing { target } if Self::of_own_kind(want, target) => {
                // The first where it fits, each other one facing the first across a gap that
                // leaves room for what the plan puts between them.
                // The first goes against each wall in turn until the other fits facing it.
                let gap = Self::gap_for_between(want, wants);
                let facing =
                    |first: &str| json!({"description": desc, "target": first, "distance_m": gap});
                let mine = Self::present_for(state, want, wants);
                if let Some(first) = mine.first().cloned() {
                    while placed < need && call(state, cx, "place_facing", facing(&first)) {
                        placed += 1;
                    }
                    return placed;
                }
                for wall in ["north", "east", "south", "west"] {
                    let args = json!({"description": desc, "wall": wall});
                    let Ok(v) = cx.call(state, Role::Designer, "place_against_wall", args) else {
                        continue;
                    };
                    let Some(first) = placed_ids(&v).into_iter().next() else {
                        continue;
                    };
                    if call(state, cx, "place_facing", facing(&first)) {
                        placed = 2;
                        while placed < need && call(state, cx, "place_facing", facing(&first)) {
                            placed += 1;
                        }
                        return placed.min(need);
                    }
                    let _ = cx.call(state, Role::Designer, "remove_object", json!({"id": first}));
                }
            }
            _ => {}
        }
        placed
    }

    /// The gap (m) between two pieces of `want` that face each other: the depth of a piece
    /// the plan puts between them plus a 0.45 m passage on each side, else 0.9 m.
    fn gap_for_between(want: &Want, wants: &[Want]) -> f64 {
        wants
            .iter()
            .filter(|w| match &w.arrangement {
                Arrangement::Between { targets } => {
                    targets.iter().any(|t| Self::of_own_kind(want, t))
                }
                _ => false,
            })
            .filter_map(|w| {
                let category = crate::assets::router::parse::main_categories(&w.noun)
                    .into_iter()
                    .next()?;
                crate::assets::procedural::prior(category).map(|p| p.typical[1])
            })
            .map(|depth| depth + 0.9)
            .fold(0.9, f64::max)
    }

    fn present(state: &StageState, noun: &str) -> Vec<String> {
        state
            .room_objects()
            .filter(|o| crate::assets::router::naming::object_is(&state.scene.scene, noun, o))
            .map(|o| o.id.clone())
            .collect()
    }

    /// The pieces present that count for `want`: what was placed for it, and what its noun
    /// names except a piece named after another item of the plan (a guest chair is no dental
    /// chair, though both are built as chairs).
    fn present_for(state: &StageState, want: &Want, wants: &[Want]) -> Vec<String> {
        let own = crate::scene::sanitize_name(&want.noun);
        let others: Vec<String> = wants
            .iter()
            .map(|w| crate::scene::sanitize_name(&w.noun))
            .filter(|n| *n != own)
            .collect();
        // Pieces of the same noun the prompt describes apart ("three wicker chairs, a hammock
        // chair"): each description counts its own.
        let own_description = crate::scene::sanitize_name(&want.description);
        let described_apart: Vec<String> = wants
            .iter()
            .filter(|w| w.noun == want.noun)
            .map(|w| crate::scene::sanitize_name(&w.description))
            .filter(|d| *d != own_description)
            .collect();
        Self::present(state, &want.noun)
            .into_iter()
            .filter(|id| {
                state.scene.scene.object(id).is_none_or(|o| {
                    // Placed for this want ("a cast-iron wood stove", a fireplace built as a
                    // stove): it counts whatever it is built as.
                    if o.planned.as_deref() == Some(want.noun.as_str()) {
                        return true;
                    }
                    let named = o.name.as_deref().map(crate::scene::sanitize_name);
                    if named.as_ref().is_some_and(|n| described_apart.contains(n)) {
                        return false;
                    }
                    !others.contains(&o.category)
                        && named.is_none_or(|n| n == own || !others.contains(&n))
                })
            })
            .collect()
    }

    fn build_plan(state: &mut StageState, cx: &mut AgentCx<'_, StageState>, reverse: bool) {
        let wants = Self::in_placing_order(&state.plan.furniture);
        for want in &wants {
            let have = Self::present_for(state, want, &wants).len() as u32;
            let mut need = want.count.saturating_sub(have);
            if need == 0 {
                continue;
            }
            need -= Self::place_related(state, cx, want, &wants, need);
            if need > 0 && Self::has_side_followers(want, &wants) {
                need -= Self::place_centred_on_a_wall(state, cx, want, need);
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
                && !Self::of_own_kind(want, target)
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
                if !Self::place_one(
                    state,
                    cx,
                    &want.description,
                    &want.arrangement,
                    reverse,
                    !want.explicit,
                ) {
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
                Self::place_one(state, cx, &obj.category, &arrangement, !reverse, false);
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

/// A number of an observation, `default` when it is missing or not a number (the tools write
/// every field, but a critic never fails on a reply it can still read).
fn num(v: &Value, default: f64) -> f64 {
    v.as_f64().unwrap_or(default)
}

/// A string of an observation, empty when it is missing.
fn text(v: &Value) -> &str {
    v.as_str().unwrap_or_default()
}

/// The furniture of an `observe_room` reply (wall and ceiling objects are other stages').
fn furniture_of(obs: &Value) -> Vec<&Value> {
    obs["objects"]
        .as_array()
        .map(|a| a.iter().filter(|o| o["kind"] == "furniture").collect())
        .unwrap_or_default()
}

/// Prompt following: requested furniture counts present, excluded absent.
fn prompt_following(
    obs: &Value,
    furniture: &[&Value],
    plan: &RoomPlan,
    issues: &mut Vec<Issue>,
) -> Score {
    let (got, wanted) = requested_present(obs, plan, issues);
    let excluded_present = excluded_present(obs, furniture, issues);
    let coverage = if wanted == 0 {
        1.0
    } else {
        got as f64 / wanted as f64
    };
    score(
        "prompt_following",
        10.0 * coverage - 3.0 * excluded_present as f64,
        format!(
            "{got} of {wanted} requested pieces present{}",
            if excluded_present > 0 {
                format!(", {excluded_present} excluded pieces present")
            } else {
                String::new()
            }
        ),
    )
}

/// How many of the requested furniture pieces are present and how many were asked for
/// (other stages' nouns are not counted: a missing lamp on the wall is not the furniture's).
fn requested_present(obs: &Value, plan: &RoomPlan, issues: &mut Vec<Issue>) -> (u32, u32) {
    let mut wanted = 0u32;
    let mut got = 0u32;
    for r in obs["requested"].as_array().into_iter().flatten() {
        let noun = text(&r["noun"]);
        if !plan.furniture.iter().any(|w| w.noun == noun) {
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
    (got, wanted)
}

/// How many placed pieces the prompt excluded.
fn excluded_present(obs: &Value, furniture: &[&Value], issues: &mut Vec<Issue>) -> u32 {
    let mut present = 0;
    for e in obs["excluded"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|v| v.as_str())
    {
        for o in furniture {
            if o["category"] == e {
                present += 1;
                issues.push(Issue {
                    objects: vec![text(&o["id"]).into()],
                    description: format!("the prompt says no {e}; remove it"),
                });
            }
        }
    }
    present
}

/// Functionality: seats face a table-like piece nearby.
fn functionality(furniture: &[&Value], issues: &mut Vec<Issue>) -> Score {
    let parents: Vec<&Value> = furniture
        .iter()
        .copied()
        .filter(|o| is_seat_parent(text(&o["category"])))
        .collect();
    let mut seats = 0;
    let mut facing = 0;
    for chair in furniture.iter().filter(|o| is_seat(text(&o["category"]))) {
        let Some(table) = seat_table(chair, &parents) else {
            continue;
        };
        seats += 1;
        if faces(chair, table) {
            facing += 1;
        } else {
            issues.push(Issue {
                objects: vec![text(&chair["id"]).into()],
                description: format!("turn it to face {}", text(&table["id"])),
            });
        }
    }
    let value = if seats == 0 {
        10.0
    } else {
        10.0 * facing as f64 / seats as f64
    };
    score(
        "functionality",
        value,
        format!("{facing} of {seats} seats face their table"),
    )
}

/// The table-like piece a seat belongs to: the nearest one, when the seat is within a metre of
/// its edge (half its larger side plus a metre from its centre).
fn seat_table<'v>(chair: &Value, parents: &[&'v Value]) -> Option<&'v Value> {
    let (x, y) = (num(&chair["x"], 0.0), num(&chair["y"], 0.0));
    let distance = |p: &Value| (num(&p["x"], 0.0) - x).hypot(num(&p["y"], 0.0) - y);
    let nearest = parents
        .iter()
        .min_by(|a, b| distance(a).total_cmp(&distance(b)))?;
    let reach = num(&nearest["size_m"][0], 1.0).max(num(&nearest["size_m"][1], 1.0)) / 2.0 + 1.0;
    (distance(nearest) <= reach).then_some(*nearest)
}

/// Whether the seat's front (its -sin/cos yaw direction) points at the table's centre within
/// about 37 degrees.
fn faces(chair: &Value, table: &Value) -> bool {
    let (x, y) = (num(&chair["x"], 0.0), num(&chair["y"], 0.0));
    let yaw = num(&chair["yaw_deg"], 0.0).to_radians();
    let front = [-yaw.sin(), yaw.cos()];
    let to = [num(&table["x"], 0.0) - x, num(&table["y"], 0.0) - y];
    let n = to[0].hypot(to[1]).max(1e-9);
    (front[0] * to[0] + front[1] * to[1]) / n > 0.8
}

/// Spatial layout: how much floor the furniture takes.
fn spatial_layout(obs: &Value, furniture: &[&Value], issues: &mut Vec<Issue>) -> Score {
    let floor = num(&obs["size_m"][0], 1.0) * num(&obs["size_m"][1], 1.0);
    let used: f64 = furniture
        .iter()
        .map(|o| num(&o["size_m"][0], 0.0) * num(&o["size_m"][1], 0.0))
        .sum();
    let frac = used / floor.max(1e-9);
    let value = if furniture.is_empty() {
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
    score(
        "spatial_layout",
        value,
        format!("furniture covers {:.0}% of the floor", frac * 100.0),
    )
}

/// Reachability: every piece reachable from the door, and the free floor connected (NAV).
fn reachability(reach: &Value, issues: &mut Vec<Issue>) -> Score {
    let nav = num(&reach["nav"], 0.0);
    let unreachable: Vec<String> = reach["unreachable"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|v| v.as_str().map(str::to_string))
        .collect();
    for id in &unreachable {
        issues.push(Issue {
            objects: vec![id.clone()],
            description: format!("{id} cannot be reached from the door; move it or clear a path"),
        });
    }
    let value =
        10.0 - 2.0 * unreachable.len() as f64 - if nav < 0.95 { 10.0 * (0.95 - nav) } else { 0.0 };
    score(
        "reachability",
        value,
        format!("NAV {nav:.2}, {} unreachable", unreachable.len()),
    )
}

/// Physical feasibility: penetrating pairs.
fn physical_feasibility(collisions: &Value, issues: &mut Vec<Issue>) -> Score {
    let pairs: Vec<&Value> = collisions["collisions"]
        .as_array()
        .map(|a| a.iter().collect())
        .unwrap_or_default();
    for p in &pairs {
        let (a, b) = (text(&p["a"]), text(&p["b"]));
        issues.push(Issue {
            objects: vec![a.into(), b.into()],
            description: format!("{a} and {b} overlap by {} mm; move one", p["depth_mm"]),
        });
    }
    score(
        "physical_feasibility",
        10.0 - 3.0 * pairs.len() as f64,
        format!("{} penetrating pairs", pairs.len()),
    )
}

impl Critic<StageState> for BuiltinFurnitureCritic {
    fn critique(
        &mut self,
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<Critique, AgentError> {
        let mut measure = |tool: &str| {
            cx.call(state, Role::Critic, tool, json!({}))
                .map_err(|e| AgentError::Unusable {
                    role: "critic",
                    stage: "furniture".into(),
                    message: e.message,
                })
        };
        let obs = measure("observe_room")?;
        let collisions = measure("check_collisions")?;
        let reach = measure("check_reachability")?;
        let furniture = furniture_of(&obs);
        // Issues in category order: the designer reads them in the order they are listed.
        let mut issues = Vec::new();
        let scores = vec![
            prompt_following(&obs, &furniture, &state.plan, &mut issues),
            functionality(&furniture, &mut issues),
            spatial_layout(&obs, &furniture, &mut issues),
            reachability(&reach, &mut issues),
            physical_feasibility(&collisions, &mut issues),
        ];
        Ok(Critique { scores, issues })
    }
}
