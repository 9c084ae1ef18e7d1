//! Runs the placement stages of every room through the agent loop: furniture, wall, ceiling,
//! then the manipuland stage once per supporting entity, with the built-in backend or an LLM.

use std::collections::BTreeMap;
use std::sync::Arc;

use super::checkpoint::{CheckpointStore, NoCheckpoints};
use super::{StageKind, StageState, ceiling, furniture, manipuland, wall};
use crate::agents::llm::{LlmCritic, LlmDesigner, LlmOrchestrator};
use crate::agents::{
    AgentError, Backend, BuiltinOrchestrator, CategorySpec, Critic, Designer, Orchestrator,
    PlacementStyle, RunLog, StageConfig, StageSpec, StageSummary, Toolbox, run_stage,
};
use crate::plan::{Arrangement, RoomPlan, SurfaceWant, Want};
use crate::scene::{ObjectKind, SceneObject, Support};
use crate::state::SceneState;

fn stage_config(kind: StageKind) -> StageConfig {
    match kind {
        StageKind::Manipuland => StageConfig {
            max_rounds: 2,
            early_finish_min_score: 9,
            ..StageConfig::default()
        },
        _ => StageConfig {
            max_rounds: 3,
            early_finish_min_score: 9,
            ..StageConfig::default()
        },
    }
}

/// Placement style from the prompt: showrooms, stores and galleries look perfect.
fn style_for(room_type: &str, prompt: &str) -> PlacementStyle {
    let p = prompt.to_lowercase();
    let perfect = [
        "showroom",
        "store",
        "shop",
        "gallery",
        "museum",
        "lobby",
        "conference",
        "pristine",
        "minimalist",
    ];
    if perfect
        .iter()
        .any(|w| p.contains(w) || room_type.contains(w))
    {
        PlacementStyle::Perfect
    } else {
        PlacementStyle::Natural
    }
}

fn brief(state: &StageState) -> String {
    let room = state.scene.scene.room(&state.room);
    let (ty, prompt, size) = room
        .map(|r| {
            let (lo, hi) = crate::geometry::polygon::bounds(&r.floor_polygon);
            (
                r.room_type.clone(),
                r.prompt.clone(),
                [hi[0] - lo[0], hi[1] - lo[1]],
            )
        })
        .unwrap_or_default();
    let wants: Vec<&Want> = match state.kind {
        StageKind::Furniture => state.plan.furniture.iter().collect(),
        StageKind::Wall => state.plan.wall.iter().collect(),
        StageKind::Ceiling => state.plan.ceiling.iter().collect(),
        _ => state.plan.surfaces.iter().flat_map(|s| &s.items).collect(),
    };
    let list = wants
        .iter()
        .map(|w| {
            format!(
                "{} x{}{}",
                w.description,
                w.count,
                if w.explicit { " (requested)" } else { "" }
            )
        })
        .collect::<Vec<_>>()
        .join(", ");
    let focus = state
        .entity
        .as_ref()
        .map(|e| format!(" Supporting entity: {e}."))
        .unwrap_or_default();
    format!(
        "Room {} ({ty}, {:.1} x {:.1} m).{focus} Room prompt: \"{prompt}\". Planned for this stage: {}. Excluded: {}.",
        state.room,
        size[0],
        size[1],
        if list.is_empty() {
            "nothing in particular".to_string()
        } else {
            list
        },
        if state.plan.excluded.is_empty() {
            "nothing".to_string()
        } else {
            state.plan.excluded.join(", ")
        }
    )
}

type Agents = (
    Box<dyn Designer<StageState>>,
    Box<dyn Critic<StageState>>,
    Box<dyn Orchestrator>,
);

fn agents(backend: &Backend, kind: StageKind, style: PlacementStyle, brief_text: &str) -> Agents {
    match backend {
        Backend::Builtin => {
            let orch = Box::new(BuiltinOrchestrator::with_style(style));
            match kind {
                StageKind::Furniture => (
                    Box::new(furniture::BuiltinFurnitureDesigner),
                    Box::new(furniture::BuiltinFurnitureCritic),
                    orch,
                ),
                StageKind::Wall => (
                    Box::new(wall::BuiltinWallDesigner),
                    Box::new(wall::BuiltinWallCritic),
                    orch,
                ),
                StageKind::Ceiling => (
                    Box::new(ceiling::BuiltinCeilingDesigner),
                    Box::new(ceiling::BuiltinCeilingCritic),
                    orch,
                ),
                _ => (
                    Box::new(manipuland::BuiltinManipulandDesigner),
                    Box::new(manipuland::BuiltinManipulandCritic),
                    orch,
                ),
            }
        }
        Backend::Llm { transport, config } => {
            let mut orch = LlmOrchestrator::new(transport.clone(), config.clone());
            orch.set_stage(kind.as_str(), brief_text);
            (
                Box::new(LlmDesigner::new(transport.clone(), config.clone())),
                Box::new(LlmCritic::new(transport.clone(), config.clone())),
                Box::new(orch),
            )
        }
    }
}

fn tools_and_categories(kind: StageKind) -> (Toolbox<StageState>, Vec<CategorySpec>) {
    match kind {
        StageKind::Furniture => (furniture::toolbox(), furniture::categories()),
        StageKind::Wall => (wall::toolbox(), wall::categories()),
        StageKind::Ceiling => (ceiling::toolbox(), ceiling::categories()),
        _ => (manipuland::toolbox(), manipuland::categories()),
    }
}

/// Where a stage run writes what happened.
struct Recorder<'a> {
    log: &'a mut RunLog,
    summaries: Vec<StageSummary>,
}

/// Runs one stage for a room (or one entity of it) and returns the kept scene.
fn run_one(
    scene: SceneState,
    kind: StageKind,
    room: &str,
    entity: Option<String>,
    plan: Arc<RoomPlan>,
    backend: &Backend,
    rec: &mut Recorder<'_>,
) -> Result<SceneState, AgentError> {
    let state = StageState {
        scene,
        kind,
        room: room.to_string(),
        entity: entity.clone(),
        plan,
        requests: 0,
    };
    let text = brief(&state);
    let style = state
        .scene
        .scene
        .room(room)
        .map(|r| style_for(&r.room_type, &state.scene.scene.provenance.prompt))
        .unwrap_or_default();
    let (tools, categories) = tools_and_categories(kind);
    let (mut designer, mut critic, mut orchestrator) = agents(backend, kind, style, &text);
    let spec = StageSpec {
        name: kind.as_str(),
        categories: &categories,
        toolbox: &tools,
        brief: &text,
    };
    let t0 = std::time::Instant::now();
    let outcome = run_stage(
        &spec,
        state,
        designer.as_mut(),
        critic.as_mut(),
        orchestrator.as_mut(),
        &stage_config(kind),
        rec.log,
    )?;
    rec.summaries.push(StageSummary {
        stage: kind.as_str().into(),
        room: room.into(),
        entity,
        critique: outcome.critique.clone(),
        rounds: outcome.history.len(),
        seconds: t0.elapsed().as_secs_f64(),
    });
    Ok(outcome.state.scene)
}

/// The room's furniture whose asset has a support surface.
fn surface_furniture<'a>(
    scene: &'a SceneState,
    room: &'a str,
) -> impl Iterator<Item = &'a crate::scene::SceneObject> {
    scene
        .scene
        .objects
        .iter()
        .filter(move |o| {
            o.room == room && matches!(o.kind, ObjectKind::Furniture | ObjectKind::Wall)
        })
        .filter(|o| {
            scene
                .scene
                .assets
                .get(&o.asset)
                .is_some_and(|a| !a.surfaces.is_empty())
        })
}

/// Splits the room's small objects over the supporting entities present: per entity a plan
/// holding only that entity's share.
///
/// Each piece's defaults grow to its surfaces (`clutter::sized_to`), and the room's defaults
/// together stay near `clutter::room_budget`: past it, every piece's growth shrinks by the
/// same share. Below `clutter::room_floor` (a room of few pieces) every piece's growth
/// grows by the same share instead, at most `clutter::MAX_FLOOR_GROWTH` times.
fn entity_plans(scene: &SceneState, room: &str, plan: &RoomPlan) -> Vec<(String, RoomPlan)> {
    let full = split_plans(scene, room, plan, 1.0);
    let defaults: u32 = full
        .iter()
        .flat_map(|(_, p)| p.surfaces.iter().flat_map(|g| &g.items))
        .filter(|w| !w.explicit)
        .map(|w| w.count)
        .sum();
    let budget = super::clutter::room_budget(plan.density);
    let floor = super::clutter::room_floor(plan.density);
    if defaults > budget {
        return split_plans(scene, room, plan, f64::from(budget) / f64::from(defaults));
    }
    if defaults == 0 || defaults >= floor {
        return full;
    }
    let growth = (f64::from(floor) / f64::from(defaults)).min(super::clutter::MAX_FLOOR_GROWTH);
    split_plans(scene, room, plan, growth)
}

/// `entity_plans` with each piece's growth scaled by `share`.
fn split_plans(
    scene: &SceneState,
    room: &str,
    plan: &RoomPlan,
    share: f64,
) -> Vec<(String, RoomPlan)> {
    let furniture: Vec<(String, String)> = surface_furniture(scene, room)
        .map(|o| (o.id.clone(), scene.scene.built_as(o).to_string()))
        .collect();
    let mut per: BTreeMap<String, RoomPlan> = BTreeMap::new();
    // Default small objects each piece may still take (`clutter::piece_budget`).
    let mut budget: BTreeMap<String, u32> = BTreeMap::new();
    for group in &contents_with_their_containers(&plan.surfaces) {
        let mut hosts: Vec<&(String, String)> = furniture
            .iter()
            .filter(|(_, cat)| {
                group.parent == "any" || crate::assets::router::naming::names(&group.parent, cat)
            })
            .collect();
        if hosts.is_empty() {
            // A narrower kind of the wanted piece ("pillows on the bed": a king bed).
            hosts = furniture
                .iter()
                .filter(|(_, cat)| crate::assets::router::naming::kind_of(&group.parent, cat))
                .collect();
        }
        let own_kind = !hosts.is_empty();
        if hosts.is_empty() {
            // Nothing of the wanted kind: any furniture with a surface, tables first.
            hosts = furniture.iter().filter(|(_, c)| c != "chair").collect();
            hosts.sort_by_key(|(_, c)| !matches!(c.as_str(), "table" | "desk" | "counter"));
        }
        if hosts.is_empty() {
            continue;
        }
        for ((id, cat), items) in hosts.iter().zip(shares_per_host(&group.items, hosts.len())) {
            let items = match scene
                .scene
                .object(id)
                .and_then(|o| scene.scene.assets.get(&o.asset))
            {
                Some(rec) if own_kind && !group.place_settings => {
                    let left = budget
                        .entry(id.clone())
                        .or_insert_with(|| super::clutter::piece_budget(plan.density));
                    super::clutter::sized_to(rec, items, plan.density, share, left)
                }
                _ => items,
            };
            if items.is_empty() {
                continue;
            }
            let entry = per.entry(id.clone()).or_insert_with(|| RoomPlan {
                excluded: plan.excluded.clone(),
                ..RoomPlan::default()
            });
            entry.surfaces.push(SurfaceWant {
                parent: cat.clone(),
                items,
                place_settings: group.place_settings,
            });
        }
    }
    per.into_iter().collect()
}

/// `items` split over `n` hosts: evenly, the remainders going round the hosts (one lamp, one
/// book and one clock on two nightstands: two on one, one on the other); an item that goes
/// inside a container of the same group follows the containers (the fruit goes to the table
/// that got the fruit bowl), shared among their hosts in proportion.
fn shares_per_host(items: &[Want], n: usize) -> Vec<Vec<Want>> {
    let n32 = n as u32;
    let mut turn = 0u32;
    let mut counts: Vec<Vec<u32>> = vec![Vec::with_capacity(items.len()); n];
    for w in items {
        for (i, host) in counts.iter_mut().enumerate() {
            let extra = (i as u32 + n32 - turn % n32) % n32 < w.count % n32;
            host.push(w.count / n32 + u32::from(extra));
        }
        turn += w.count % n32;
    }
    for (k, w) in items.iter().enumerate() {
        let Arrangement::Inside { parent } = &w.arrangement else {
            continue;
        };
        let Some(c) = items.iter().position(|x| &x.noun == parent) else {
            continue;
        };
        let containers: Vec<u32> = counts.iter().map(|host| host[c]).collect();
        let total: u32 = containers.iter().sum();
        if total == 0 {
            continue;
        }
        // Largest remainders: each host's share of the containers, in whole items.
        let mut given = 0u32;
        for (host, held) in counts.iter_mut().zip(&containers) {
            host[k] = w.count * held / total;
            given += host[k];
        }
        for (host, _) in counts
            .iter_mut()
            .zip(&containers)
            .filter(|(_, held)| **held > 0)
        {
            if given == w.count {
                break;
            }
            host[k] += 1;
            given += 1;
        }
    }
    counts
        .into_iter()
        .map(|host| {
            items
                .iter()
                .zip(host)
                .filter(|(_, count)| *count > 0)
                .map(|(w, count)| Want { count, ..w.clone() })
                .collect()
        })
        .collect()
}

/// `groups` with each "anywhere" item that goes inside a container ("a fruit bowl with a
/// fruit in it") moved to the group of the furniture that holds the container, so that both
/// go to the same piece.
fn contents_with_their_containers(groups: &[SurfaceWant]) -> Vec<SurfaceWant> {
    let mut out = groups.to_vec();
    let holder = |out: &[SurfaceWant], container: &str, not: usize| {
        out.iter()
            .enumerate()
            .position(|(k, g)| k != not && g.items.iter().any(|w| w.noun == container))
    };
    for i in 0..out.len() {
        if out[i].parent != "any" {
            continue;
        }
        let items = std::mem::take(&mut out[i].items);
        for want in items {
            let to = match &want.arrangement {
                Arrangement::Inside { parent } => holder(&out, parent, i),
                _ => None,
            };
            out[to.unwrap_or(i)].items.push(want);
        }
    }
    out
}

/// Most extra hosts tried for small objects their own furniture could not hold.
const LEFTOVER_HOSTS: usize = 3;

/// Furniture with a surface that may take leftovers: tables, desks and counters first.
fn leftover_hosts(scene: &SceneState, room: &str) -> Vec<String> {
    let mut hosts: Vec<(String, bool)> = surface_furniture(scene, room)
        .map(|o| {
            let cat = scene.scene.built_as(o);
            let tableish = ["table", "desk", "counter", "sideboard", "console"]
                .iter()
                .any(|t| cat.contains(t));
            (o.id.clone(), tableish)
        })
        .filter(|(_, tableish)| *tableish)
        .collect();
    hosts.sort_by_key(|(id, _)| id.clone());
    hosts
        .into_iter()
        .take(LEFTOVER_HOSTS)
        .map(|(id, _)| id)
        .collect()
}

/// The prompt's small objects still missing from the room, as a plan for `host` (`None`
/// when nothing is missing).
fn leftover_plan(scene: &SceneState, room: &str, plan: &RoomPlan, host: &str) -> Option<RoomPlan> {
    let present = |w: &Want| {
        scene
            .scene
            .objects
            .iter()
            .filter(|o| o.room == room && o.kind == ObjectKind::Manipuland)
            .filter(|o| super::StageState::is_wanted(&scene.scene, w, o))
            .count() as u32
    };
    let items: Vec<Want> = plan
        .surfaces
        .iter()
        .flat_map(|g| g.items.iter())
        .filter(|w| w.explicit && !matches!(w.arrangement, Arrangement::Inside { .. }))
        .filter_map(|w| {
            let missing = w.count.saturating_sub(present(w));
            (missing > 0).then(|| Want {
                count: missing,
                arrangement: Arrangement::Free,
                ..w.clone()
            })
        })
        .collect();
    if items.is_empty() {
        return None;
    }
    let parent = scene
        .scene
        .object(host)
        .map(|o| scene.scene.built_as(o).to_string())
        .unwrap_or_default();
    Some(RoomPlan {
        excluded: plan.excluded.clone(),
        surfaces: vec![SurfaceWant {
            parent,
            items,
            place_settings: false,
        }],
        ..RoomPlan::default()
    })
}

/// Placement tools tried in turn for a thing the prompt asked for that nothing else could
/// hold: along a wall, in a corner, in the open middle of the room.
const FLOOR_TOOLS: [&str; 3] = ["place_against_wall", "place_in_corner", "place_in_center"];

/// The prompt's things missing from the room once every stage and the leftover hosts had
/// their turn, each with the number missing.
///
/// Pieces of furniture are counted: "three music stands" of which the furniture stage placed
/// two (a corner too tight for the third) miss one. A piece is told by the plan noun it was
/// placed for, so the count is that of the plan.
///
/// Small things ("a dozen rolled yoga mats" on a rack the room has no space for) miss only
/// when none is there, by its plan noun or by the name its description gives (tablecloths
/// laid over their tables, one cable of a tangle): topping up a count on the floor would
/// more often add what is already there under another name than what is missing.
fn still_missing(scene: &SceneState, room: &str, plan: &RoomPlan) -> Vec<Want> {
    let objects: Vec<&SceneObject> = scene
        .scene
        .objects
        .iter()
        .filter(|o| o.room == room && o.kind != ObjectKind::Architecture)
        .collect();
    let present = |w: &Want| {
        let name = crate::assets::router::parse::object_name(&w.description)
            .map(|n| crate::scene::sanitize_name(&n));
        objects.iter().any(|o| {
            super::StageState::is_wanted(&scene.scene, w, o)
                || name.as_deref().is_some_and(|n| {
                    o.category == n
                        || o.name
                            .as_deref()
                            .map(crate::scene::sanitize_name)
                            .as_deref()
                            == Some(n)
                })
        })
    };
    let on_floor = |w: &Want, count: u32| Want {
        arrangement: Arrangement::AgainstWall,
        count,
        ..w.clone()
    };
    let mut missing: Vec<Want> = Vec::new();
    let mut counted: Vec<&str> = Vec::new();
    for w in plan.furniture.iter().filter(|w| w.explicit) {
        if counted.contains(&w.noun.as_str()) {
            continue;
        }
        counted.push(&w.noun);
        let wanted: u32 = plan
            .furniture
            .iter()
            .filter(|o| o.explicit && o.noun == w.noun)
            .map(|o| o.count)
            .sum();
        let placed = objects
            .iter()
            .filter(|o| super::StageState::is_wanted(&scene.scene, w, o))
            .count() as u32;
        if placed == 0 && present(w) {
            continue;
        }
        if placed < wanted {
            missing.push(on_floor(w, wanted - placed));
        }
    }
    missing.extend(
        plan.surfaces
            .iter()
            .flat_map(|g| g.items.iter())
            .filter(|w| w.explicit && !present(w))
            .map(|w| on_floor(w, w.count)),
    );
    missing
}

/// Stands what the prompt asked for and no stage could place on the floor, with the
/// furniture stage's tools (a stated count is not lost while the floor has room); returns
/// the scene and how many were placed.
fn place_missing_on_floor(scene: SceneState, room: &str, plan: &RoomPlan) -> (SceneState, u32) {
    let missing = still_missing(&scene, room, plan);
    if missing.is_empty() {
        return (scene, 0);
    }
    let mut state = StageState {
        scene,
        kind: StageKind::Furniture,
        room: room.to_string(),
        entity: None,
        plan: Arc::new(RoomPlan {
            furniture: missing.clone(),
            excluded: plan.excluded.clone(),
            ..RoomPlan::default()
        }),
        requests: 0,
    };
    let (tools, _) = tools_and_categories(StageKind::Furniture);
    let stand = |state: &mut StageState, want: &Want| {
        FLOOR_TOOLS.iter().any(|tool| {
            tools
                .call(
                    state,
                    crate::agents::Role::Designer,
                    tool,
                    serde_json::json!({"description": want.description}),
                )
                .is_ok()
        })
    };
    let mut placed = 0;
    for want in &missing {
        for _ in 0..want.count {
            if !stand(&mut state, want) && !make_room_for(&mut state, plan, want, &stand) {
                tracing::info!("{room}: no floor space for {:?}", want.description);
                break;
            }
            placed += 1;
        }
    }
    (state.scene, placed)
}

/// Pieces of room default furniture tried in turn to make room for a thing the prompt asked
/// for (each try rebuilds the room's floor map).
const MAKE_ROOM_TRIES: usize = 6;

/// Makes floor room for `want` by taking out one piece of furniture the prompt did not ask
/// for (a pantry's default cabinet gives way to "a flour sack beside the butter churn"),
/// the one nearest it in size first, never one that carries something asked for; whether
/// `want` now stands.
/// The piece leaves no trace in the removals: it was a default the room no longer plans.
fn make_room_for(
    state: &mut StageState,
    plan: &RoomPlan,
    want: &Want,
    stand: &dyn Fn(&mut StageState, &Want) -> bool,
) -> bool {
    let scene = &state.scene.scene;
    let explicit: Vec<&Want> = plan
        .furniture
        .iter()
        .chain(plan.surfaces.iter().flat_map(|g| g.items.iter()))
        .filter(|w| w.explicit)
        .collect();
    let asked = |o: &crate::scene::SceneObject| {
        explicit
            .iter()
            .any(|w| super::StageState::is_wanted(scene, w, o))
    };
    let carries_asked = |id: &str| {
        let mut stack = vec![id.to_string()];
        while let Some(p) = stack.pop() {
            for o in &scene.objects {
                if matches!(&o.support, Support::Object { parent, .. } if *parent == p) {
                    if asked(o) {
                        return true;
                    }
                    stack.push(o.id.clone());
                }
            }
        }
        false
    };
    let mut defaults: Vec<(String, f64)> = scene
        .objects
        .iter()
        .filter(|o| o.room == state.room && o.kind == ObjectKind::Furniture)
        .filter(|o| !asked(o) && !carries_asked(&o.id))
        .map(|o| {
            let [lo, hi] = scene
                .assets
                .get(&o.asset)
                .map_or([[0.0; 3]; 2], |a| a.bounds);
            (o.id.clone(), (hi[0] - lo[0]) * (hi[1] - lo[1]))
        })
        .collect();
    // The piece nearest the thing in size first: likely to free its place, and no more.
    let needed = crate::assets::router::naming::footprint(&want.noun);
    let off = |area: f64| (area - needed).abs();
    defaults.sort_by(|a, b| off(a.1).total_cmp(&off(b.1)).then_with(|| a.0.cmp(&b.0)));
    for (id, _) in defaults.into_iter().take(MAKE_ROOM_TRIES) {
        let before = state.scene.clone();
        state
            .scene
            .remove_object(&id, StageKind::Furniture.as_str(), "made room");
        state.scene.scene.removed = before.scene.removed.clone();
        if stand(state, want) {
            tracing::info!(
                "{}: {id} gave way to {:?}, asked for and with no floor space",
                state.room,
                want.description
            );
            return true;
        }
        state.scene = before;
    }
    false
}

/// Runs every placement stage of one room.
pub fn furnish_room(
    scene: SceneState,
    room: &str,
    plan: RoomPlan,
    backend: &Backend,
    log: &mut RunLog,
) -> Result<(SceneState, Vec<StageSummary>), AgentError> {
    furnish_room_resumable(scene, room, plan, backend, log, &mut NoCheckpoints)
}

/// Runs every placement stage of one room, skipping stages `store` has from an earlier run
/// and saving each stage that finishes.
pub fn furnish_room_resumable(
    scene: SceneState,
    room: &str,
    plan: RoomPlan,
    backend: &Backend,
    log: &mut RunLog,
    store: &mut dyn CheckpointStore,
) -> Result<(SceneState, Vec<StageSummary>), AgentError> {
    let plan = Arc::new(plan);
    let mut rec = Recorder {
        log,
        summaries: Vec::new(),
    };
    let mut scene = scene;
    let mut step = |scene: SceneState,
                    kind: StageKind,
                    entity: Option<String>,
                    plan: Arc<RoomPlan>,
                    pass: &str,
                    rec: &mut Recorder<'_>|
     -> Result<SceneState, AgentError> {
        let key = match &entity {
            Some(e) => format!("{room}/{}/{e}{pass}", kind.as_str()),
            None => format!("{room}/{}", kind.as_str()),
        };
        if let Some((saved, saved_log)) = store.load(&key) {
            *rec.log = saved_log;
            return Ok(saved);
        }
        let out = run_one(scene, kind, room, entity, plan, backend, rec)?;
        store.save(&key, &out, rec.log);
        Ok(out)
    };
    for kind in [StageKind::Furniture, StageKind::Wall, StageKind::Ceiling] {
        scene = step(scene, kind, None, plan.clone(), "", &mut rec)?;
    }
    for (entity, eplan) in entity_plans(&scene, room, &plan) {
        scene = step(
            scene,
            StageKind::Manipuland,
            Some(entity),
            Arc::new(eplan),
            "",
            &mut rec,
        )?;
    }
    // What the prompt asked for and its furniture could not hold ("a printer on a small side
    // table" that does not fit): the room's other surfaces, tables first, take it.
    for host in leftover_hosts(&scene, room) {
        let Some(left) = leftover_plan(&scene, room, &plan, &host) else {
            break;
        };
        scene = step(
            scene,
            StageKind::Manipuland,
            Some(host),
            Arc::new(left),
            "/leftover",
            &mut rec,
        )?;
    }
    // What still has no place stands on the floor (the built-in designers' plan; an LLM
    // designer's choices stand as it made them).
    let (mut scene, on_floor) = if matches!(backend, Backend::Builtin) {
        place_missing_on_floor(scene, room, &plan)
    } else {
        (scene, 0)
    };
    if on_floor > 0 {
        tracing::info!(
            "{room}: {on_floor} asked-for objects no surface could hold stand on the floor"
        );
    }
    scene.prune_assets();
    Ok((scene, rec.summaries))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn want(noun: &str, arrangement: Arrangement) -> Want {
        Want {
            noun: noun.to_string(),
            description: noun.to_string(),
            count: 1,
            explicit: true,
            at_least: false,
            arrangement,
            height_m: None,
            parent_instance: None,
        }
    }

    fn group(parent: &str, items: Vec<Want>) -> SurfaceWant {
        SurfaceWant {
            parent: parent.to_string(),
            items,
            place_settings: false,
        }
    }

    #[test]
    fn an_item_for_a_container_goes_with_the_furniture_that_holds_the_container() {
        let inside = Arrangement::Inside {
            parent: "fruit bowl".to_string(),
        };
        let groups = vec![
            group(
                "any",
                vec![
                    want("fruit", inside.clone()),
                    want("vase", Arrangement::Free),
                ],
            ),
            group("dining table", vec![want("fruit bowl", Arrangement::Free)]),
            group("counter", vec![want("kettle", Arrangement::Free)]),
        ];
        let out = contents_with_their_containers(&groups);
        let nouns = |g: &SurfaceWant| g.items.iter().map(|w| w.noun.clone()).collect::<Vec<_>>();
        assert_eq!(nouns(&out[0]), ["vase"]);
        assert_eq!(nouns(&out[1]), ["fruit bowl", "fruit"]);
        assert_eq!(nouns(&out[2]), ["kettle"]);
        // A container nobody plans: the item stays where it was.
        let lone = contents_with_their_containers(&[group("any", vec![want("fruit", inside)])]);
        assert_eq!(nouns(&lone[0]), ["fruit"]);
    }

    #[test]
    fn split_over_two_tables_the_fruit_goes_to_the_table_that_gets_the_bowl() {
        let inside = Arrangement::Inside {
            parent: "fruit bowl".to_string(),
        };
        let mut fruit = want("fruit", inside);
        fruit.count = 3;
        let items = vec![
            want("plate", Arrangement::Free),
            want("fruit bowl", Arrangement::Free),
            fruit,
        ];
        let shares = shares_per_host(&items, 2);
        let held =
            |host: &[Want], noun: &str| host.iter().find(|w| w.noun == noun).map_or(0, |w| w.count);
        // One plate and one bowl go round the two tables; the fruit follows the bowl.
        assert_eq!(held(&shares[0], "plate") + held(&shares[1], "plate"), 1);
        let bowl_host = usize::from(held(&shares[1], "fruit bowl") == 1);
        assert_eq!(held(&shares[bowl_host], "fruit bowl"), 1);
        assert_eq!(held(&shares[bowl_host], "fruit"), 3);
        assert_eq!(held(&shares[1 - bowl_host], "fruit"), 0);
        // Two bowls on two tables: the fruit is shared, every one placed.
        let mut two = items.clone();
        two[1].count = 2;
        let shares = shares_per_host(&two, 2);
        assert_eq!(held(&shares[0], "fruit") + held(&shares[1], "fruit"), 3);
        assert!(held(&shares[0], "fruit") >= 1 && held(&shares[1], "fruit") >= 1);
    }

    #[test]
    fn a_room_default_gives_way_to_an_asked_for_thing_with_no_floor_space() {
        let prompt = "A small pantry.";
        let mut log = RunLog::default();
        let layout =
            crate::layout::stage::run_layout(prompt, 1, &Backend::Builtin, &mut log).unwrap();
        let mut scene = SceneState::new(crate::scene::Scene::new(prompt, 1, "layout"));
        crate::state::install_rooms(&mut scene, &layout.rooms).unwrap();
        let room = layout.rooms[0].id.clone();
        // The room's defaults take every free stretch of floor.
        let mut state = StageState {
            scene,
            kind: StageKind::Furniture,
            room: room.clone(),
            entity: None,
            plan: Arc::new(RoomPlan::default()),
            requests: 0,
        };
        let (tools, _) = tools_and_categories(StageKind::Furniture);
        let mut defaults = 0;
        while defaults < 40
            && FLOOR_TOOLS.iter().any(|tool| {
                tools
                    .call(
                        &mut state,
                        crate::agents::Role::Designer,
                        tool,
                        serde_json::json!({"description": "cabinet"}),
                    )
                    .is_ok()
            })
        {
            defaults += 1;
        }
        assert!(defaults > 0 && defaults < 40, "{defaults} cabinets");
        let plan = RoomPlan {
            furniture: vec![want("side table", Arrangement::Free)],
            ..RoomPlan::default()
        };
        let (scene, placed) = place_missing_on_floor(state.scene, &room, &plan);
        assert_eq!(placed, 1);
        let count = |c: &str| {
            scene
                .scene
                .objects
                .iter()
                .filter(|o| o.category == c)
                .count()
        };
        assert_eq!(count("side_table"), 1);
        assert_eq!(count("cabinet"), defaults - 1);
        // A default that gave way is no removal to report.
        assert!(scene.scene.removed.is_empty(), "{:?}", scene.scene.removed);
    }

    #[test]
    fn a_piece_of_furniture_short_of_its_count_is_topped_up_on_the_floor() {
        let prompt = "A music room.";
        let mut log = RunLog::default();
        let layout =
            crate::layout::stage::run_layout(prompt, 1, &Backend::Builtin, &mut log).unwrap();
        let mut scene = SceneState::new(crate::scene::Scene::new(prompt, 1, "layout"));
        crate::state::install_rooms(&mut scene, &layout.rooms).unwrap();
        let room = layout.rooms[0].id.clone();
        // "a music stand beside the piano ... two more music stands in the corner": three
        // asked for in two wants, two placed.
        let mut beside = want("music stand", Arrangement::Free);
        let mut corner = beside.clone();
        corner.count = 2;
        corner.arrangement = Arrangement::AgainstWall;
        beside.count = 1;
        let plan = RoomPlan {
            furniture: vec![beside, corner],
            ..RoomPlan::default()
        };
        let mut state = StageState {
            scene,
            kind: StageKind::Furniture,
            room: room.clone(),
            entity: None,
            plan: Arc::new(plan.clone()),
            requests: 0,
        };
        let (tools, _) = tools_and_categories(StageKind::Furniture);
        for _ in 0..2 {
            let args = serde_json::json!({"description": "music stand"});
            let placed = tools.call(
                &mut state,
                crate::agents::Role::Designer,
                "place_against_wall",
                args,
            );
            assert!(placed.is_ok(), "{placed:?}");
        }
        let stands = |scene: &SceneState| {
            scene
                .scene
                .objects
                .iter()
                .filter(|o| o.category == "music_stand")
                .count()
        };
        assert_eq!(stands(&state.scene), 2);
        let (scene, placed) = place_missing_on_floor(state.scene, &room, &plan);
        assert_eq!(placed, 1);
        assert_eq!(stands(&scene), 3);
        // Nothing is missing once the count is met.
        let (scene, placed) = place_missing_on_floor(scene, &room, &plan);
        assert_eq!((placed, stands(&scene)), (0, 3));
    }
}
