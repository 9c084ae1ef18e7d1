//! Tools for doors and windows.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::{fail, room_exists};
use crate::agents::ToolError;
use crate::layout::connect::{self, DoorPos, DoorSpec, Side, WindowSpec, intervals};
use crate::layout::knowledge::Role;
use crate::layout::state::{LayoutState, LayoutSummary};

/// Arguments of `add_door`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct DoorArgs {
    /// Room id.
    pub room_a: String,
    /// The neighbouring room id, or "outside" for an exterior door.
    pub room_b: String,
    /// `left`, `center` or `right` along the shared wall (default center).
    #[serde(default)]
    pub position: Option<DoorPos>,
    /// For an exterior door: side of room_a (`north`, `east`, `south`, `west`); the longest
    /// outside wall when omitted.
    #[serde(default)]
    pub side: Option<String>,
    /// Width, metres (0.7 - 2.0, default 0.9; 1.0 outside).
    #[serde(default)]
    pub width_m: Option<f64>,
}

/// A door or window that was added.
#[derive(Debug, Serialize, JsonSchema)]
pub struct Added {
    /// Its id.
    pub id: String,
    /// Remarks (empty: it is in place as asked).
    pub notes: Vec<String>,
}

pub(super) fn add_door(s: &mut LayoutState, a: DoorArgs) -> Result<Added, ToolError> {
    room_exists(s, &a.room_a)?;
    let outside = matches!(
        a.room_b.trim().to_lowercase().as_str(),
        "outside" | "exterior" | "none"
    );
    let width = a.width_m.unwrap_or(if outside { 1.0 } else { 0.9 });
    if !(0.7..=2.0).contains(&width) {
        return Err(ToolError::bad_args("width_m must be between 0.7 and 2.0"));
    }
    let side = match &a.side {
        Some(x) => Some(Side::parse(x).ok_or_else(|| {
            ToolError::bad_args(format!(
                "unknown side {x:?}; use north, east, south or west"
            ))
        })?),
        None => None,
    };
    let ivs = intervals(&s.placement, &a.room_a);
    let (b, side) = if outside {
        let fits: Vec<_> = ivs
            .iter()
            .filter(|iv| iv.outside && iv.len() >= width + 0.35)
            .filter(|iv| side.is_none_or(|sd| iv.side == sd))
            .collect();
        let best = fits
            .iter()
            .max_by(|x, y| x.len().total_cmp(&y.len()))
            .ok_or_else(|| {
                fail(format!(
                    "{} has no outside wall{} long enough for a {width:.2} m door",
                    a.room_a,
                    side.map(|s| format!(" on the {} side", s.as_str()))
                        .unwrap_or_default()
                ))
            })?;
        (None, Some(best.side))
    } else {
        room_exists(s, &a.room_b)?;
        let shared = s.placement.shared(&a.room_a, &a.room_b);
        if shared < width + 0.35 {
            return Err(fail(format!(
                "{} and {} share {shared:.2} m of wall; a {width:.2} m door needs {:.2} m \
                 (add_adjacency to move them together)",
                a.room_a,
                a.room_b,
                width + 0.35
            )));
        }
        let spec = s.spec().map_err(fail)?;
        for (x, y) in [(&a.room_a, &a.room_b), (&a.room_b, &a.room_a)] {
            if let Some(owner) = spec.room(x).and_then(|r| r.owner.clone())
                && owner != *y
            {
                return Err(fail(format!(
                    "{x} is the en-suite of {owner}; it is entered only from there"
                )));
            }
        }
        (Some(a.room_b.clone()), None)
    };
    if s.doors
        .iter()
        .any(|d| d.joins(&a.room_a, b.as_deref()) && b.is_some())
    {
        return Err(fail(format!(
            "{} and {} already have a door",
            a.room_a, a.room_b
        )));
    }
    let id = s.next_id("door");
    s.doors.push(DoorSpec {
        id: id.clone(),
        a: a.room_a.clone(),
        b,
        pos: a.position.unwrap_or(DoorPos::Center),
        side,
        width,
        auto: false,
    });
    let (_, notes) = s.rooms();
    if let Some(n) = notes.notes.iter().find(|n| n.starts_with(&id)) {
        let n = n.clone();
        s.doors.retain(|d| d.id != id);
        return Err(fail(n));
    }
    Ok(Added {
        notes: Vec::new(),
        id,
    })
}

/// An id.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct IdArgs {
    /// Door or window id.
    pub id: String,
}

pub(super) fn remove_door(s: &mut LayoutState, a: IdArgs) -> Result<LayoutSummary, ToolError> {
    let before = s.doors.len();
    s.doors.retain(|d| d.id != a.id);
    if s.doors.len() == before {
        return Err(ToolError::bad_args(format!(
            "no door {:?}; doors: {}",
            a.id,
            s.doors
                .iter()
                .map(|d| d.id.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    Ok(s.summary(Vec::new()))
}

/// Arguments of `add_window`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct WindowArgs {
    /// Room id.
    pub room: String,
    /// Side of the room (`north`, `east`, `south`, `west`); its longest outside wall when
    /// omitted.
    #[serde(default)]
    pub side: Option<String>,
    /// Width, metres (0.4 - 4.0, default 1.2).
    #[serde(default)]
    pub width_m: Option<f64>,
    /// Sill height, metres (default from the room type).
    #[serde(default)]
    pub sill_m: Option<f64>,
    /// Height, metres.
    #[serde(default)]
    pub height_m: Option<f64>,
}

pub(super) fn add_window(s: &mut LayoutState, a: WindowArgs) -> Result<Added, ToolError> {
    room_exists(s, &a.room)?;
    let spec = s.spec().map_err(fail)?.clone();
    let Some(r) = spec.room(&a.room) else {
        return Err(ToolError::bad_args("no such room"));
    };
    let [dw, dh] = connect::window_size(r.sill, spec.wall_height, r.role == Role::Wet);
    let width = a.width_m.unwrap_or(dw);
    let sill = a.sill_m.unwrap_or(r.sill);
    let height = a.height_m.unwrap_or(dh);
    if !(0.4..=4.0).contains(&width)
        || !(0.0..=2.0).contains(&sill)
        || !(0.3..=3.0).contains(&height)
    {
        return Err(ToolError::bad_args(
            "width_m 0.4-4.0, sill_m 0-2.0, height_m 0.3-3.0",
        ));
    }
    if sill + height > spec.wall_height - 0.1 {
        return Err(ToolError::bad_args(format!(
            "sill + height must stay 0.1 m under the {:.2} m ceiling",
            spec.wall_height
        )));
    }
    let want = match &a.side {
        Some(x) => Some(Side::parse(x).ok_or_else(|| {
            ToolError::bad_args(format!(
                "unknown side {x:?}; use north, east, south or west"
            ))
        })?),
        None => None,
    };
    let iv = intervals(&s.placement, &a.room)
        .into_iter()
        .filter(|iv| iv.outside && iv.len() >= width + 0.4)
        .filter(|iv| want.is_none_or(|sd| iv.side == sd))
        .max_by(|x, y| x.len().total_cmp(&y.len()))
        .ok_or_else(|| {
            fail(format!(
                "{} has no outside wall{} long enough for a {width:.2} m window",
                a.room,
                want.map(|s| format!(" on the {} side", s.as_str()))
                    .unwrap_or_default()
            ))
        })?;
    let cell = s.placement.cells[&a.room];
    let (lo, len) = connect::side_extent(&cell, iv.side);
    let mid = (iv.lo + iv.hi) / 2.0;
    let along = match iv.side {
        Side::South | Side::East => (mid - lo) / len,
        Side::North | Side::West => 1.0 - (mid - lo) / len,
    };
    let id = s.next_id("window");
    s.windows.push(WindowSpec {
        id: id.clone(),
        room: a.room.clone(),
        side: iv.side,
        along,
        width,
        height,
        sill,
        auto: false,
    });
    let (_, notes) = s.rooms();
    if let Some(n) = notes.notes.iter().find(|n| n.starts_with(&id)) {
        let n = n.clone();
        s.windows.retain(|w| w.id != id);
        return Err(fail(n));
    }
    Ok(Added {
        notes: Vec::new(),
        id,
    })
}

pub(super) fn remove_window(s: &mut LayoutState, a: IdArgs) -> Result<LayoutSummary, ToolError> {
    let before = s.windows.len();
    s.windows.retain(|w| w.id != a.id);
    if s.windows.len() == before {
        return Err(ToolError::bad_args(format!("no window {:?}", a.id)));
    }
    Ok(s.summary(Vec::new()))
}
