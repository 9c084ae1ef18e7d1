//! The layout stage's state: the prompt's brief, the room specifications, their placement, the
//! door and window requests, and the operations the tools perform on them (generate, re-layout
//! with stability, build rooms, validate).

use serde::Serialize;

use super::brief::{self, HouseBrief};
use super::connect::{self, DoorSpec, WindowSpec};
use super::search::{self, Placement, SearchConfig, SearchStats};
use super::spec::{self, HouseSpec};
use super::validate::{self, Validation};
use super::walls::{self, BuildNotes};
use crate::scene::Room;

/// Everything the layout tools work on.
#[derive(Debug, Clone)]
pub struct LayoutState {
    /// The user's prompt.
    pub prompt: String,
    /// Seed of every random choice (door positions).
    pub seed: u64,
    /// Search settings.
    pub config: SearchConfig,
    /// What the prompt asks for.
    pub brief: HouseBrief,
    /// Room specifications (`None` until generated).
    pub spec: Option<HouseSpec>,
    /// Cells of the rooms.
    pub placement: Placement,
    /// Door requests.
    pub doors: Vec<DoorSpec>,
    /// Window requests.
    pub windows: Vec<WindowSpec>,
    /// How the last search went.
    pub stats: SearchStats,
    /// Counter for ids of doors and windows added by edits.
    pub edits: u32,
}

/// A short account of the layout after an edit.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct LayoutSummary {
    /// Room ids with type and clear size.
    pub rooms: Vec<String>,
    /// Rooms that moved in the last re-layout, with the distance, metres.
    pub moved: Vec<(String, f64)>,
    /// Search statistics.
    pub search: SearchStats,
    /// Validation errors (empty: valid).
    pub errors: Vec<String>,
}

impl LayoutState {
    /// A state for `prompt` with nothing generated yet.
    pub fn new(prompt: &str, seed: u64) -> LayoutState {
        LayoutState {
            prompt: prompt.to_string(),
            seed,
            config: SearchConfig::default(),
            brief: brief::read(prompt),
            spec: None,
            placement: Placement::default(),
            doors: Vec::new(),
            windows: Vec::new(),
            stats: SearchStats::default(),
            edits: 0,
        }
    }

    /// A state with the prompt's rooms generated and placed.
    pub fn from_prompt(prompt: &str, seed: u64) -> LayoutState {
        let mut s = LayoutState::new(prompt, seed);
        let spec = spec::house_spec(&s.brief);
        s.install(spec, false);
        s
    }

    /// The spec, or an error an agent can act on.
    pub fn spec(&self) -> Result<&HouseSpec, String> {
        self.spec
            .as_ref()
            .ok_or_else(|| "no rooms yet: call generate_room_specs first".to_string())
    }

    /// Sets the spec and places it: from scratch, or keeping rooms near where they were.
    pub fn install(&mut self, spec: HouseSpec, keep_positions: bool) -> Vec<(String, f64)> {
        let previous =
            (keep_positions && !self.placement.cells.is_empty()).then(|| self.placement.clone());
        let (placement, stats) = search::place(&spec, previous.as_ref(), &self.config);
        let moved = previous
            .as_ref()
            .map(|prev| {
                placement
                    .cells
                    .iter()
                    .filter_map(|(k, r)| {
                        prev.cells.get(k).map(|p| {
                            let (a, b) = (r.center(), p.center());
                            (
                                k.clone(),
                                ((a[0] - b[0]).hypot(a[1] - b[1]) * 1000.0).round() / 1000.0,
                            )
                        })
                    })
                    .filter(|(_, d)| *d > 1e-3)
                    .collect()
            })
            .unwrap_or_default();
        self.placement = placement;
        self.stats = stats;
        self.spec = Some(spec);
        self.replan_openings();
        moved
    }

    /// Re-plans automatic doors and windows for the current placement; edits that still fit
    /// are kept.
    pub fn replan_openings(&mut self) {
        let Some(spec) = &self.spec else { return };
        let manual_doors: Vec<DoorSpec> = self
            .doors
            .iter()
            .filter(|d| !d.auto)
            .filter(|d| match &d.b {
                Some(b) => self.placement.shared(&d.a, b) >= search::MIN_SHARED - 1e-6,
                None => true,
            })
            .cloned()
            .collect();
        let mut doors = connect::auto_doors(spec, &self.placement, self.seed);
        // A manual door between the same rooms replaces the automatic one.
        doors.retain(|d| !manual_doors.iter().any(|m| m.joins(&d.a, d.b.as_deref())));
        doors.extend(manual_doors);
        let manual_windows: Vec<WindowSpec> =
            self.windows.iter().filter(|w| !w.auto).cloned().collect();
        let mut windows = connect::auto_windows(spec, &self.placement, &doors);
        windows.extend(manual_windows);
        self.doors = doors;
        self.windows = windows;
    }

    /// Places the current spec again, keeping rooms where they were as far as possible.
    pub fn relayout(&mut self) -> Result<Vec<(String, f64)>, String> {
        let spec = self.spec()?.clone();
        Ok(self.install(spec, true))
    }

    /// The scene rooms of the current layout.
    pub fn rooms(&self) -> (Vec<Room>, BuildNotes) {
        match &self.spec {
            Some(spec) => walls::build_rooms(
                spec,
                &self.placement,
                &self.doors,
                &self.windows,
                self.config.wall_thickness,
            ),
            None => (Vec::new(), BuildNotes::default()),
        }
    }

    /// Validation of the current layout.
    pub fn validation(&self) -> Validation {
        let Some(spec) = &self.spec else {
            return Validation {
                ok: false,
                errors: vec!["no rooms yet: call generate_room_specs".into()],
                ..Validation::default()
            };
        };
        let (rooms, notes) = self.rooms();
        let mut v = validate::validate(spec, &self.placement, &rooms, &notes.notes);
        if self.brief.left_out > 0 {
            v.warnings.push(format!(
                "the prompt asks for {} more rooms than the layout makes (at most {} rooms, {} per phrase); they were left out",
                self.brief.left_out,
                brief::MAX_ROOMS,
                brief::MAX_PER_MENTION
            ));
        }
        v
    }

    /// A short account of the layout.
    pub fn summary(&self, moved: Vec<(String, f64)>) -> LayoutSummary {
        let rooms = self
            .spec
            .as_ref()
            .map(|s| {
                s.rooms
                    .iter()
                    .map(|r| {
                        let c = self.placement.cells.get(&r.id);
                        let t = self.config.wall_thickness;
                        let size = c.map(|c| [c.w() - t, c.d() - t]).unwrap_or(r.size);
                        format!(
                            "{} ({}) {:.1} x {:.1} m",
                            r.id, r.room_type, size[0], size[1]
                        )
                    })
                    .collect()
            })
            .unwrap_or_default();
        LayoutSummary {
            rooms,
            moved,
            search: self.stats.clone(),
            errors: self.validation().errors,
        }
    }

    /// A fresh id for an edit-made door or window.
    pub fn next_id(&mut self, kind: &str) -> String {
        let id = format!("{kind}_added_{}", self.edits);
        self.edits += 1;
        id
    }
}
