//! The built-in (offline) designer and critic of the wall stage.

use serde_json::json;

use crate::agents::{
    AgentCx, AgentError, Critic, Critique, DesignRequest, Designer, Issue, Role, Score,
};
use crate::plan::Arrangement;
use crate::scene::ObjectKind;
use crate::stages::StageState;
use crate::stages::common;
use crate::stages::placement::Footprint;

/// Targets of an `Above` want present in the room.
fn targets(state: &StageState, noun: &str) -> Vec<String> {
    state
        .room_objects()
        .filter(|o| {
            crate::assets::router::naming::object_is(&state.scene.scene, noun, o)
                && o.kind == ObjectKind::Furniture
        })
        .map(|o| o.id.clone())
        .collect()
}

/// The built-in wall designer.
#[derive(Debug, Default)]
pub struct BuiltinWallDesigner;

impl Designer<StageState> for BuiltinWallDesigner {
    fn design(
        &mut self,
        state: &mut StageState,
        _request: &DesignRequest,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<String, AgentError> {
        let _ = cx.call(state, Role::Designer, "observe_room", json!({}));
        for want in state.plan.wall.clone() {
            let have = common::present_count(state, &want.noun);
            let mut need = want.count.saturating_sub(have);
            if let Arrangement::Above { target } = &want.arrangement {
                for t in targets(state, target) {
                    if need == 0 {
                        break;
                    }
                    if cx
                        .call(
                            state,
                            Role::Designer,
                            "mount_above",
                            json!({"description": want.description, "target": t}),
                        )
                        .is_ok()
                    {
                        need -= 1;
                    }
                }
            }
            for _ in 0..need {
                if cx
                    .call(
                        state,
                        Role::Designer,
                        "mount_on_wall",
                        json!({"description": want.description}),
                    )
                    .is_err()
                {
                    break;
                }
            }
        }
        let n = state
            .room_objects()
            .filter(|o| o.kind == ObjectKind::Wall)
            .count();
        Ok(format!("{n} wall objects"))
    }
}

/// The built-in wall critic.
#[derive(Debug, Default)]
pub struct BuiltinWallCritic;

fn requested_score(
    state: &StageState,
    wants: &[crate::plan::Want],
    issues: &mut Vec<Issue>,
) -> (f64, String) {
    let (mut wanted, mut got) = (0u32, 0u32);
    for w in wants.iter().filter(|w| w.explicit) {
        let have = common::present_count(state, &w.noun);
        wanted += w.count;
        got += have.min(w.count);
        if have < w.count {
            issues.push(Issue {
                objects: vec![],
                description: format!("add {} more {}", w.count - have, w.noun),
            });
        }
    }
    let cov = if wanted == 0 {
        1.0
    } else {
        f64::from(got) / f64::from(wanted)
    };
    (10.0 * cov, format!("{got} of {wanted} requested present"))
}

/// Penetrating pairs involving an object of `kind`, each an issue. A collision check that
/// fails makes the critique unusable: it is never counted as no collisions.
fn collisions_of(
    state: &mut StageState,
    cx: &mut AgentCx<'_, StageState>,
    kind: ObjectKind,
    issues: &mut Vec<Issue>,
) -> Result<usize, AgentError> {
    let v = cx
        .call(state, Role::Critic, "check_collisions", json!({}))
        .map_err(|e| AgentError::Unusable {
            role: "critic",
            stage: kind.as_str().into(),
            message: format!("the collision check failed: {}", e.message),
        })?;
    let mut n = 0;
    for p in v["collisions"].as_array().into_iter().flatten() {
        let ids: Vec<String> = ["a", "b"]
            .iter()
            .filter_map(|k| p[*k].as_str().map(str::to_string))
            .collect();
        if ids
            .iter()
            .any(|id| state.scene.scene.object(id).is_some_and(|o| o.kind == kind))
        {
            n += 1;
            issues.push(Issue {
                objects: ids.clone(),
                description: format!("{} overlap; move one", ids.join(" and ")),
            });
        }
    }
    Ok(n)
}

/// Closest edge-to-edge gap at which two wall objects at overlapping heights still read as
/// separate pieces, metres.
const WALL_GAP_M: f64 = 0.08;

/// Pairs of the room's wall objects closer than [`WALL_GAP_M`], each an issue.
fn crowded_wall_pairs(state: &StageState, issues: &mut Vec<Issue>) -> usize {
    let mounted: Vec<(String, Footprint)> = state
        .room_objects()
        .filter(|o| o.kind == ObjectKind::Wall)
        .filter_map(|o| {
            let rec = state.scene.scene.assets.get(&o.asset)?;
            Some((o.id.clone(), Footprint::of(rec, &o.world_from_object)))
        })
        .collect();
    let mut n = 0;
    for (i, (a, fa)) in mounted.iter().enumerate() {
        for (b, fb) in &mounted[i + 1..] {
            if fa.overlaps(fb, WALL_GAP_M) {
                n += 1;
                issues.push(Issue {
                    objects: vec![a.clone(), b.clone()],
                    description: format!(
                        "{a} and {b} are closer than {:.0} cm; space them",
                        WALL_GAP_M * 100.0
                    ),
                });
            }
        }
    }
    n
}

fn clamp_score(c: &str, v: f64, r: String) -> Score {
    Score {
        category: c.into(),
        score: v.round().clamp(0.0, 10.0) as u8,
        reason: r,
    }
}

impl Critic<StageState> for BuiltinWallCritic {
    fn critique(
        &mut self,
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<Critique, AgentError> {
        let _ = cx.call(state, Role::Critic, "observe_room", json!({}));
        let mut issues = Vec::new();
        let wants = state.plan.wall.clone();
        let (pf, pf_reason) = requested_score(state, &wants, &mut issues);
        let mounted: Vec<(String, f64, f64)> = state
            .room_objects()
            .filter(|o| o.kind == ObjectKind::Wall)
            .filter_map(|o| {
                let rec = state.scene.scene.assets.get(&o.asset)?;
                let c = o.world_from_object.translation().z
                    + (rec.bounds[0][2] + rec.bounds[1][2]) / 2.0;
                Some((o.id.clone(), c, rec.bounds[1][2] - rec.bounds[0][2]))
            })
            .collect();
        let mut odd = 0;
        for (id, c, _) in &mounted {
            if !(0.9..=2.3).contains(c) {
                odd += 1;
                issues.push(Issue {
                    objects: vec![id.clone()],
                    description: format!(
                        "{id} hangs with its centre at {c:.2} m; 1.3-1.7 m reads best"
                    ),
                });
            }
        }
        let logic = if mounted.is_empty() {
            10.0
        } else {
            10.0 - 10.0 * odd as f64 / mounted.len() as f64
        };
        // Aesthetics, measured: crowding (pieces closer than a hand's width) and a wall left
        // bare when wall objects were planned.
        let crowded = crowded_wall_pairs(state, &mut issues);
        let bare = mounted.is_empty() && !wants.is_empty();
        let aesthetics = 10.0 - 3.0 * crowded as f64 - if bare { 6.0 } else { 0.0 };
        let n = collisions_of(state, cx, ObjectKind::Wall, &mut issues)?;
        Ok(Critique {
            scores: vec![
                clamp_score("prompt_following", pf, pf_reason),
                clamp_score(
                    "placement_logic",
                    logic,
                    format!("{odd} of {} at unusual heights", mounted.len()),
                ),
                clamp_score(
                    "aesthetics",
                    aesthetics,
                    format!(
                        "{} wall objects, {crowded} pairs closer than {:.0} cm{}",
                        mounted.len(),
                        WALL_GAP_M * 100.0,
                        if bare {
                            ", none of the planned ones hung"
                        } else {
                            ""
                        }
                    ),
                ),
                clamp_score(
                    "physical_feasibility",
                    10.0 - 3.0 * n as f64,
                    format!("{n} penetrating pairs"),
                ),
            ],
            issues,
        })
    }
}

/// Shared by the ceiling critic.
pub(crate) fn requested_and_collisions(
    state: &mut StageState,
    cx: &mut AgentCx<'_, StageState>,
    wants: &[crate::plan::Want],
    kind: ObjectKind,
    issues: &mut Vec<Issue>,
) -> Result<(Score, Score), AgentError> {
    let (pf, r) = requested_score(state, wants, issues);
    let n = collisions_of(state, cx, kind, issues)?;
    Ok((
        clamp_score("prompt_following", pf, r),
        clamp_score(
            "physical_feasibility",
            10.0 - 3.0 * n as f64,
            format!("{n} penetrating pairs"),
        ),
    ))
}
