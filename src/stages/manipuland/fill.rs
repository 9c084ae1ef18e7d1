//! Fills: copies of one item inside a container (a fruit bowl, a bin, a refrigerator), cavity
//! first, then its shelves, at a smaller plausible size when that holds more.

use schemars::JsonSchema;
use serde::Deserialize;

use super::pile::place_layers;
use super::surface::SurfaceRef;
use super::tools::{PlaceResult, result_for};
use crate::agents::ToolError;
use crate::stages::{RoutedAsset, StageState};

/// Fill a container.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct FillArgs {
    /// Id of the container object (bowl, bin, basket, box, refrigerator...).
    pub container: String,
    /// What to put in it, e.g. "apple".
    pub description: String,
    /// How many.
    pub count: u32,
}

pub(super) fn place_inside(state: &mut StageState, a: FillArgs) -> Result<PlaceResult, ToolError> {
    if a.count == 0 || a.count > 60 {
        return Err(ToolError::bad_args("count must be between 1 and 60"));
    }
    let container = state
        .scene
        .scene
        .object(&a.container)
        .cloned()
        .ok_or_else(|| ToolError::failed(format!("no object {:?}", a.container)))?;
    let rec = state.scene.scene.assets[&container.asset].clone();
    if rec.surfaces.is_empty() {
        return Err(ToolError::failed(format!(
            "{} has no inside or top surface to fill",
            a.container
        )));
    }
    // Cavities first (surface ids starting with "inside"), then shelves, then the rest.
    let mut surfaces = rec.surfaces.clone();
    surfaces.sort_by_key(|s| {
        (
            !s.id.starts_with("inside"),
            !s.id.starts_with("shelf"),
            s.id.clone(),
        )
    });
    let fill = |state: &mut StageState,
                size: Option<[f64; 3]>|
     -> Result<(RoutedAsset, Vec<String>), ToolError> {
        let routed = state.route_asset(&a.description, size)?;
        let mut ids = Vec::new();
        for surface in &surfaces {
            if ids.len() as u32 >= a.count {
                break;
            }
            let s = SurfaceRef {
                parent: container.clone(),
                surface: surface.clone(),
            };
            let more = place_layers(state, &s, &routed, a.count - ids.len() as u32)?;
            ids.extend(more);
        }
        Ok((routed, ids))
    };
    // At their typical size first; when fewer fit than asked for ("a bin with at least five
    // stuffed animals"), the smallest plausible size of the same object, if that holds more.
    let mut trial = state.clone();
    let (mut routed, mut ids) = fill(&mut trial, None)?;
    let smallest = crate::assets::router::naming::category_of(&a.description)
        .and_then(crate::assets::procedural::prior)
        .map(|p| p.min);
    if (ids.len() as u32) < a.count
        && let Some(min) = smallest
    {
        let mut small = state.clone();
        if let Ok((r, more)) = fill(&mut small, Some(min))
            && more.len() > ids.len()
        {
            (trial, routed, ids) = (small, r, more);
        }
    }
    *state = trial;
    if ids.is_empty() {
        return Err(ToolError::failed(format!(
            "nothing fits inside {}",
            a.container
        )));
    }
    let notes = if (ids.len() as u32) < a.count {
        vec![format!(
            "only {} of {} fit in {}",
            ids.len(),
            a.count,
            a.container
        )]
    } else {
        vec![]
    };
    result_for(state, &ids, [routed.notes.clone(), notes].concat())
}
