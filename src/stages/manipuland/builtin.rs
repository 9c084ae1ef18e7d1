//! The built-in designer and critic of the manipuland stage (one supporting entity at a time).

use serde_json::{Value, json};

use super::surface::{items_on, surfaces};
use crate::agents::{
    AgentCx, AgentError, Critic, Critique, DesignRequest, Designer, Issue, Role, Score,
};
use crate::plan::{Arrangement, Want};
use crate::scene::ObjectKind;
use crate::stages::StageState;

/// The built-in manipuland designer.
#[derive(Debug, Default)]
pub struct BuiltinManipulandDesigner;

/// How many of the plan item `want` rest (transitively) on `entity`
/// (`StageState::is_wanted`).
fn count_on(state: &StageState, entity: &str, want: &Want) -> u32 {
    let scene = &state.scene.scene;
    items_on(state, entity)
        .iter()
        .filter(|id| {
            scene
                .object(id)
                .is_some_and(|o| StageState::is_wanted(scene, want, o))
        })
        .count() as u32
}

/// Height above the entity's base at which asked-for items are put first (m): counter height.
const HANDY_HEIGHT_M: f64 = 0.9;
/// Added to a basin's height in the usual clutter's order, so that it comes after every other
/// open surface of its entity (m).
const BASIN_LAST_M: f64 = 100.0;

/// The entity's surface keys in two tiers: the open ones (tops, open shelves), then the
/// enclosed ones (behind doors, in drawers), which get what the open ones cannot hold: a
/// kitchen counter's appliances stand on its top, not in its cupboards. The usual clutter
/// (`asked` false) fills each tier bottom-up, a wet basin last (shampoo stands on a bathtub's
/// rim, not in the tub) and never a sink's: a sink stays free to put things in. What the prompt asks for goes to the surface
/// nearest HANDY_HEIGHT_M first ("a shelf with a can on it": the can at hand height, not on
/// the bottom board).
fn surface_tiers(state: &StageState, entity: &str, asked: bool) -> [Vec<String>; 2] {
    let mut list: Vec<(bool, f64, String)> = surfaces(state, Some(entity))
        .iter()
        .filter_map(|s| {
            // What the prompt put in a sink goes into its basin first; the usual clutter
            // keeps to the counter.
            let z = s.surface.center[2];
            let order = match (asked, s.surface.id == "basin") {
                (true, true) => f64::NEG_INFINITY,
                (true, false) => (z - HANDY_HEIGHT_M).abs(),
                (false, true) if s.parent.category == "sink" => return None,
                // A tub's basin comes last, after its rim.
                (false, true) => z + BASIN_LAST_M,
                (false, false) => z,
            };
            Some((s.enclosed(state), order, s.key()))
        })
        .collect();
    list.sort_by(|a, b| a.1.total_cmp(&b.1));
    let tier = |enclosed: bool| {
        list.iter()
            .filter(|(e, _, _)| *e == enclosed)
            .map(|(_, _, k)| k.clone())
            .collect()
    };
    [tier(false), tier(true)]
}

/// Whether an object stands like a slab (a book: thin, tall) and so may also be laid flat;
/// a microwave or a pan on its side is no arrangement anyone makes.
fn may_lie_flat(noun: &str) -> bool {
    crate::assets::router::naming::category_of(noun)
        .and_then(crate::assets::procedural::prior)
        .is_some_and(|p| p.typical[0].min(p.typical[1]) < 0.5 * p.typical[2])
}

/// Whether the room's plan asks for a `container` that no stage has placed yet.
fn container_to_come(state: &StageState, container: &str) -> bool {
    state
        .plan
        .surfaces
        .iter()
        .flat_map(|g| &g.items)
        .any(|w| w.noun == container && w.count > 0)
}

/// Whether `noun` is a plate and `entity` a table: a plate goes in front of a seat.
fn lays_at_a_seat(state: &StageState, entity: &str, noun: &str) -> bool {
    let scene = &state.scene.scene;
    super::settings::is_setting_plate(noun)
        && scene
            .object(entity)
            .is_some_and(|o| scene.built_as(o).ends_with("table"))
}

/// Most copies of a flat thing in one stack when it is put away (folded clothes in a drawer).
const STORED_STACK: u32 = 3;

/// Whether a thing put away goes in low stacks: flat things (folded clothes, towels, plates).
fn stacks_when_stored(noun: &str) -> bool {
    crate::assets::router::naming::category_of(noun)
        .and_then(crate::assets::procedural::prior)
        .is_some_and(|p| p.typical[2] < 0.3 * p.typical[0].min(p.typical[1]))
}

/// The `lay_flat` values to try, in order.
fn lay_flat_options(noun: &str, lay_flat_first: bool) -> Vec<bool> {
    if !may_lie_flat(noun) {
        vec![false]
    } else if lay_flat_first {
        vec![true, false]
    } else {
        vec![false, true]
    }
}

impl BuiltinManipulandDesigner {
    fn fill_want(
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
        entity: &str,
        want: &Want,
        lay_flat_first: bool,
    ) {
        let mut need = want.count.saturating_sub(count_on(state, entity, want));
        if need == 0 {
            return;
        }
        if want.arrangement == Arrangement::Free && lays_at_a_seat(state, entity, &want.noun) {
            // A plate on a table is laid where someone sits: at the edge in front of a seat,
            // not in the middle of the table.
            if let Ok(v) = cx.call(
                state,
                Role::Designer,
                "place_settings",
                json!({"surface": format!("{entity}/top"), "items": [want.description], "settings": need}),
            ) {
                need = need.saturating_sub(v["placed"].as_array().map_or(0, |a| a.len() as u32));
            }
            if need == 0 {
                return;
            }
        }
        let tiers = surface_tiers(state, entity, want.explicit);
        let order: Vec<String> = tiers.concat();
        match &want.arrangement {
            Arrangement::Stack | Arrangement::Pile => {
                let tool = if want.arrangement == Arrangement::Stack {
                    "place_stack"
                } else {
                    "place_pile"
                };
                for key in &order {
                    if need == 0 {
                        break;
                    }
                    if let Ok(v) = cx.call(
                        state,
                        Role::Designer,
                        tool,
                        json!({"description": want.description, "count": need, "surface": key}),
                    ) {
                        need = need
                            .saturating_sub(v["placed"].as_array().map_or(0, |a| a.len() as u32));
                    }
                }
            }
            Arrangement::Inside { parent } => {
                // The stage's own entity first when it is such a container: its share goes
                // into it, not into the first container of the room.
                let mut containers: Vec<String> = state
                    .room_objects()
                    .filter(|o| {
                        crate::assets::router::naming::object_is(&state.scene.scene, parent, o)
                    })
                    .map(|o| o.id.clone())
                    .collect();
                containers.sort_by_key(|c| c != entity);
                if containers.is_empty() && container_to_come(state, parent) {
                    // "a fruit bowl with a fruit in it": the fruit waits for its bowl, which a
                    // later piece of furniture holds; not loose on the first counter.
                    return;
                }
                for c in containers {
                    if need == 0 {
                        break;
                    }
                    if let Ok(v) = cx.call(
                        state,
                        Role::Designer,
                        "place_inside",
                        json!({"container": c, "description": want.description, "count": need}),
                    ) {
                        need = need
                            .saturating_sub(v["placed"].as_array().map_or(0, |a| a.len() as u32));
                    }
                }
            }
            Arrangement::Stored => {
                Self::put_away(state, cx, &tiers[1], want, need);
                return;
            }
            _ => {}
        }
        // One item per surface in turn, so the levels of a shelf share the items (a bookcase
        // is not stacked on its bottom shelf only); a surface leaves the turn once full.
        for tier in tiers {
            let mut live = tier;
            while need > 0 && !live.is_empty() {
                let mut still = Vec::new();
                for key in live {
                    if need == 0 {
                        still.push(key);
                        continue;
                    }
                    let placed = Self::place_one(state, cx, want, &key, lay_flat_first);
                    if placed {
                        need -= 1;
                        still.push(key);
                    }
                }
                live = still;
            }
        }
    }

    /// One `want` on surface `key`, standing or lying flat (in the order `lay_flat_first`
    /// asks) where the object may lie flat; whether it was placed.
    fn place_one(
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
        want: &Want,
        key: &str,
        lay_flat_first: bool,
    ) -> bool {
        lay_flat_options(&want.noun, lay_flat_first)
            .into_iter()
            .any(|flat| {
                cx.call(
                    state,
                    Role::Designer,
                    "place_on_surface",
                    json!({"description": want.description, "surface": key, "lay_flat": flat}),
                )
                .is_ok()
            })
    }

    /// Puts `need` of `want` away on the enclosed surfaces `keys` (drawers, shelves behind
    /// doors), one surface after another in turn: flat things (folded clothes, plates) in
    /// low stacks, the rest side by side.
    fn put_away(
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
        keys: &[String],
        want: &Want,
        mut need: u32,
    ) {
        let per_stack = if stacks_when_stored(&want.noun) {
            STORED_STACK
        } else {
            1
        };
        let mut live: Vec<String> = keys.to_vec();
        while need > 0 && !live.is_empty() {
            let mut still = Vec::new();
            for key in live {
                if need == 0 {
                    break;
                }
                let placed = if per_stack > 1 {
                    cx.call(
                        state,
                        Role::Designer,
                        "place_stack",
                        json!({"description": want.description, "count": need.min(per_stack), "surface": key}),
                    )
                    .map_or(0, |v| v["placed"].as_array().map_or(0, |a| a.len() as u32))
                } else {
                    let fits = Self::place_one(state, cx, want, &key, false);
                    u32::from(fits)
                };
                if placed > 0 {
                    need = need.saturating_sub(placed);
                    still.push(key);
                }
            }
            live = still;
        }
    }

    fn build(state: &mut StageState, cx: &mut AgentCx<'_, StageState>, alternate: bool) {
        let Some(entity) = state.entity.clone() else {
            return;
        };
        let groups = state.plan.surfaces.clone();
        for group in &groups {
            if group.place_settings {
                let seats = group.items.iter().map(|w| w.count).min().unwrap_or(0);
                let present = group
                    .items
                    .iter()
                    .map(|w| count_on(state, &entity, w))
                    .min()
                    .unwrap_or(0);
                if seats > present {
                    let items: Vec<String> =
                        group.items.iter().map(|w| w.description.clone()).collect();
                    let surface = format!("{entity}/top");
                    let _ = cx.call(
                        state,
                        Role::Designer,
                        "place_settings",
                        json!({"surface": surface, "items": items, "settings": seats - present}),
                    );
                }
            }
            // Containers before what goes inside them.
            let mut items: Vec<&Want> = group.items.iter().collect();
            items.sort_by_key(|w| matches!(w.arrangement, Arrangement::Inside { .. }));
            for want in items {
                Self::fill_want(state, cx, &entity, want, alternate);
            }
        }
    }

    fn repair(state: &mut StageState, cx: &mut AgentCx<'_, StageState>) {
        if let Ok(v) = cx.call(state, Role::Designer, "check_collisions", json!({})) {
            let mut doomed = Vec::new();
            for c in v["collisions"].as_array().into_iter().flatten() {
                for key in ["b", "a"] {
                    if let Some(id) = c[key].as_str()
                        && state
                            .scene
                            .scene
                            .object(id)
                            .is_some_and(|o| o.kind == ObjectKind::Manipuland)
                    {
                        doomed.push(id.to_string());
                        break;
                    }
                }
            }
            doomed.dedup();
            for id in doomed {
                let _ = cx.call(state, Role::Designer, "remove_object", json!({"id": id}));
            }
        }
    }
}

impl Designer<StageState> for BuiltinManipulandDesigner {
    fn design(
        &mut self,
        state: &mut StageState,
        request: &DesignRequest,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<String, AgentError> {
        let _ = cx.call(state, Role::Designer, "observe_surfaces", json!({}));
        match request {
            DesignRequest::Initial => Self::build(state, cx, false),
            _ => {
                Self::repair(state, cx);
                Self::build(state, cx, cx.attempt % 2 == 1);
            }
        }
        let n = state
            .entity
            .as_deref()
            .map_or(0, |e| items_on(state, e).len());
        Ok(format!(
            "{n} objects on {}",
            state.entity.as_deref().unwrap_or("?")
        ))
    }
}

/// The built-in manipuland critic.
#[derive(Debug, Default)]
pub struct BuiltinManipulandCritic;

impl Critic<StageState> for BuiltinManipulandCritic {
    fn critique(
        &mut self,
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<Critique, AgentError> {
        let unusable = |m: String| AgentError::Unusable {
            role: "critic",
            stage: "manipuland".into(),
            message: m,
        };
        let surfaces_v = cx
            .call(state, Role::Critic, "observe_surfaces", json!({}))
            .map_err(|e| unusable(e.message))?;
        let collisions = cx
            .call(state, Role::Critic, "check_collisions", json!({}))
            .map_err(|e| unusable(e.message))?;
        let entity = state.entity.clone().unwrap_or_default();
        let mine = items_on(state, &entity);
        let mut issues = Vec::new();

        // What the prompt asked for; the room's usual clutter fills what room is left and
        // is not a request.
        let (mut wanted, mut got) = (0u32, 0u32);
        for group in &state.plan.surfaces {
            for w in group.items.iter().filter(|w| w.explicit) {
                let have = count_on(state, &entity, w);
                wanted += w.count;
                got += have.min(w.count);
                if have < w.count {
                    issues.push(Issue {
                        objects: vec![entity.clone()],
                        description: format!(
                            "put {} more {} on {entity} (asked {}, have {have})",
                            w.count - have,
                            w.noun,
                            w.count
                        ),
                    });
                }
            }
        }
        let coverage = if wanted == 0 {
            1.0
        } else {
            f64::from(got) / f64::from(wanted)
        };

        // Realism: objects upright unless they lie flat on purpose (books, cutlery).
        let mut tilted = 0;
        for id in &mine {
            if let Some(o) = state.scene.scene.object(id) {
                let up = o
                    .world_from_object
                    .transform_vector(&nalgebra::Vector3::z());
                let lies = matches!(
                    state.scene.scene.built_as(o),
                    "book" | "fork" | "knife" | "spoon"
                );
                if up.z < 0.9 && !lies {
                    tilted += 1;
                    issues.push(Issue {
                        objects: vec![id.clone()],
                        description: format!("{id} is tipped over; stand it upright"),
                    });
                }
            }
        }
        let realism = if mine.is_empty() {
            10.0
        } else {
            10.0 - 10.0 * tilted as f64 / mine.len() as f64
        };

        // Arrangement: no surface crammed beyond 85 % (objects need room to be grasped).
        let mut crammed = 0;
        for s in surfaces_v.as_array().into_iter().flatten() {
            let occ = s["occupancy"].as_f64().unwrap_or(0.0);
            if occ > 0.85 {
                crammed += 1;
                issues.push(Issue {
                    objects: vec![],
                    description: format!(
                        "{} is {:.0}% covered; spread items to other surfaces",
                        s["surface"].as_str().unwrap_or_default(),
                        occ * 100.0
                    ),
                });
            }
        }
        let arrangement = 10.0 - 2.0 * f64::from(crammed);

        let pairs: Vec<&Value> = collisions["collisions"]
            .as_array()
            .map(|a| {
                a.iter()
                    .filter(|p| {
                        mine.iter()
                            .any(|m| p["a"] == m.as_str() || p["b"] == m.as_str())
                    })
                    .collect()
            })
            .unwrap_or_default();
        for p in &pairs {
            issues.push(Issue {
                objects: vec![
                    p["a"].as_str().unwrap_or_default().into(),
                    p["b"].as_str().unwrap_or_default().into(),
                ],
                description: format!(
                    "{} and {} overlap; move or remove one",
                    p["a"].as_str().unwrap_or_default(),
                    p["b"].as_str().unwrap_or_default()
                ),
            });
        }
        let physics = 10.0 - 3.0 * pairs.len() as f64;
        let s = |c: &str, v: f64, r: String| Score {
            category: c.into(),
            score: v.round().clamp(0.0, 10.0) as u8,
            reason: r,
        };
        Ok(Critique {
            scores: vec![
                s(
                    "prompt_following",
                    10.0 * coverage,
                    format!("{got} of {wanted} requested objects on {entity}"),
                ),
                s(
                    "realism",
                    realism,
                    format!("{tilted} of {} objects tipped over", mine.len()),
                ),
                s(
                    "arrangement",
                    arrangement,
                    format!("{crammed} crammed surfaces"),
                ),
                s(
                    "physical_feasibility",
                    physics,
                    format!("{} penetrating pairs", pairs.len()),
                ),
            ],
            issues,
        })
    }
}
