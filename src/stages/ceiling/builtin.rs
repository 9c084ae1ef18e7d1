//! The built-in (offline) designer and critic of the ceiling stage.

use serde_json::json;

use super::tools::{HEAD_ROOM, OVER_FURNITURE_M};
use crate::agents::{
    AgentCx, AgentError, Critic, Critique, DesignRequest, Designer, Issue, Role, Score,
};
use crate::plan::Arrangement;
use crate::scene::ObjectKind;
use crate::stages::StageState;
use crate::stages::common::{self, floor_footprints};
use crate::stages::placement::Footprint;
use crate::stages::room::RoomFrame;

/// Ceiling objects of the room whose bottom is below the head room, or, over furniture,
/// closer than the clearance to its top; each an issue. Returns `(low, checked)`.
fn low_hanging(state: &StageState, issues: &mut Vec<Issue>) -> (usize, usize) {
    let furniture = floor_footprints(state);
    let mut low = 0;
    let mut checked = 0;
    for o in state
        .room_objects()
        .filter(|o| o.kind == ObjectKind::Ceiling)
    {
        let Some(rec) = state.scene.scene.assets.get(&o.asset) else {
            continue;
        };
        checked += 1;
        let mut fp = Footprint::of(rec, &o.world_from_object);
        let bottom = fp.z[0];
        // Compare in plan only: any furniture below, whatever its height.
        fp.z = [f64::MIN, f64::MAX];
        let below = furniture
            .iter()
            .filter(|(_, f)| fp.overlaps(f, 0.0))
            .map(|(_, f)| f.z[1])
            .fold(None, |m: Option<f64>, z| Some(m.map_or(z, |m| m.max(z))));
        let (needed, what) = match below {
            Some(top) => (top + OVER_FURNITURE_M, "the furniture below"),
            None => (HEAD_ROOM, "the floor"),
        };
        if bottom < needed - 1e-6 {
            low += 1;
            issues.push(Issue {
                objects: vec![o.id.clone()],
                description: format!(
                    "{} hangs {:.2} m low over {what}; raise it",
                    o.id,
                    needed - bottom
                ),
            });
        }
    }
    (low, checked)
}

/// Cells per side of the finer grid of spots the designer tries when its first spots are
/// taken.
const FALLBACK_GRID: usize = 5;

/// The built-in ceiling designer.
#[derive(Debug, Default)]
pub struct BuiltinCeilingDesigner;

impl Designer<StageState> for BuiltinCeilingDesigner {
    fn design(
        &mut self,
        state: &mut StageState,
        _request: &DesignRequest,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<String, AgentError> {
        let _ = cx.call(state, Role::Designer, "observe_room", json!({}));
        let room = state
            .room()
            .map_err(|e| AgentError::Unusable {
                role: "designer",
                stage: "ceiling".into(),
                message: e.message,
            })?
            .clone();
        let frame = RoomFrame::new(&room);
        for want in state.plan.ceiling.clone() {
            let mut need = want
                .count
                .saturating_sub(common::present_count(state, &want.noun));
            if let Arrangement::Above { target } = &want.arrangement {
                let ids: Vec<String> = state
                    .room_objects()
                    .filter(|o| {
                        crate::assets::router::naming::object_is(&state.scene.scene, target, o)
                    })
                    .map(|o| o.id.clone())
                    .collect();
                for t in ids {
                    if need == 0 {
                        break;
                    }
                    if cx
                        .call(
                            state,
                            Role::Designer,
                            "hang_above",
                            json!({"description": want.description, "target": t}),
                        )
                        .is_ok()
                    {
                        need -= 1;
                    }
                }
            }
            // Spread the rest on a grid over the room.
            let n = need as usize;
            if n == 0 {
                continue;
            }
            let cols = (n as f64 * frame.size[0] / frame.size[1].max(0.1))
                .sqrt()
                .ceil()
                .max(1.0) as usize;
            let rows = n.div_ceil(cols);
            let cell = |i: usize, j: usize, cols: usize, rows: usize| {
                [
                    frame.size[0] * (i as f64 + 0.5) / cols as f64,
                    frame.size[1] * (j as f64 + 0.5) / rows as f64,
                ]
            };
            let grid = (0..rows).flat_map(|r| (0..cols).map(move |c| cell(c, r, cols, rows)));
            // A spot of the grid may be taken (a chandelier over the table at the centre):
            // then a finer grid, nearest the centre first.
            let mut finer: Vec<[f64; 2]> = (0..FALLBACK_GRID)
                .flat_map(|i| (0..FALLBACK_GRID).map(move |j| (i, j)))
                .map(|(i, j)| cell(i, j, FALLBACK_GRID, FALLBACK_GRID))
                .collect();
            let centre = [frame.size[0] / 2.0, frame.size[1] / 2.0];
            let dist = |p: &[f64; 2]| (p[0] - centre[0]).hypot(p[1] - centre[1]);
            finer.sort_by(|a, b| dist(a).total_cmp(&dist(b)));
            // A pendant too long for head room over the floor hangs over furniture: the
            // largest pieces first (tables, beds, islands).
            let mut pieces = floor_footprints(state);
            let area = |f: &Footprint| f.half[0] * f.half[1];
            pieces.sort_by(|a, b| area(&b.1).total_cmp(&area(&a.1)));
            let d = &want.description;
            let tries = grid
                .chain(finer)
                .map(|[x, y]| {
                    (
                        "hang_from_ceiling",
                        json!({"description": d, "x": x, "y": y}),
                    )
                })
                .chain(
                    pieces
                        .into_iter()
                        .map(|(t, _)| ("hang_above", json!({"description": d, "target": t}))),
                );
            let mut placed = 0;
            for (tool, args) in tries {
                if placed >= n {
                    break;
                }
                if cx.call(state, Role::Designer, tool, args).is_ok() {
                    placed += 1;
                }
            }
        }
        let n = state
            .room_objects()
            .filter(|o| o.kind == ObjectKind::Ceiling)
            .count();
        Ok(format!("{n} ceiling objects"))
    }
}

/// The built-in ceiling critic.
#[derive(Debug, Default)]
pub struct BuiltinCeilingCritic;

impl Critic<StageState> for BuiltinCeilingCritic {
    fn critique(
        &mut self,
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<Critique, AgentError> {
        let _ = cx.call(state, Role::Critic, "observe_room", json!({}));
        let mut issues = Vec::new();
        let wants = state.plan.ceiling.clone();
        let (pf, phys) = crate::stages::wall::requested_and_collisions(
            state,
            cx,
            &wants,
            ObjectKind::Ceiling,
            &mut issues,
        )?;
        let room = state
            .room()
            .map_err(|e| AgentError::Unusable {
                role: "critic",
                stage: "ceiling".into(),
                message: e.message,
            })?
            .clone();
        let frame = RoomFrame::new(&room);
        let hung: Vec<[f64; 2]> = state
            .room_objects()
            .filter(|o| o.kind == ObjectKind::Ceiling)
            .map(|o| {
                let t = o.world_from_object.translation();
                frame.to_room([t.x, t.y])
            })
            .collect();
        // Coverage: the centroid of the lights near the room centre.
        let coverage = if hung.is_empty() {
            10.0
        } else {
            let cx_ = hung.iter().map(|p| p[0]).sum::<f64>() / hung.len() as f64;
            let cy_ = hung.iter().map(|p| p[1]).sum::<f64>() / hung.len() as f64;
            let off = ((cx_ - frame.size[0] / 2.0) / frame.size[0])
                .hypot((cy_ - frame.size[1] / 2.0) / frame.size[1]);
            if off > 0.25 {
                issues.push(Issue {
                    objects: vec![],
                    description: "ceiling objects bunch on one side; spread them".into(),
                });
            }
            10.0 - 20.0 * (off - 0.15).max(0.0)
        };
        let (low, checked) = low_hanging(state, &mut issues);
        let logic = if checked == 0 {
            10.0
        } else {
            10.0 - 10.0 * low as f64 / checked as f64
        };
        let s = |c: &str, v: f64, r: String| Score {
            category: c.into(),
            score: v.round().clamp(0.0, 10.0) as u8,
            reason: r,
        };
        Ok(Critique {
            scores: vec![
                pf,
                s(
                    "placement_logic",
                    logic,
                    format!(
                        "{low} of {checked} ceiling objects hang lower than {HEAD_ROOM:.1} m \
                         over the floor or {OVER_FURNITURE_M:.1} m over the furniture below"
                    ),
                ),
                s(
                    "coverage",
                    coverage,
                    format!("{} ceiling objects", hung.len()),
                ),
                phys,
            ],
            issues,
        })
    }
}
