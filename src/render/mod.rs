//! The renderer: a CPU software rasterizer that turns a scene (or one asset) into annotated PNG
//! images — the plan users and critic agents look at, per-room perspective views, asset
//! previews and contact sheets.
//!
//! Data flow: [`scene::RenderScene`] poses every visual of a [`SceneState`] in the world;
//! a [`camera::Camera`] and [`raster::render`] turn a draw list into an [`Image`] plus
//! per-object coverage (optionally with a [`shadow::FloorShadow`]); [`plan`] and [`views`]
//! choose cameras, cut walls away and draw labels ([`labels`], [`text`]) on top. Output is
//! deterministic: the same input gives the same bytes, whatever the thread count.
//!
//! It does not do cast shadows from lights, reflections, transparency (alpha is ignored) or
//! texture mipmaps, and it reads files only through
//! [`formats::scene_dir::load_state`](crate::formats::scene_dir::load_state).

pub mod camera;
pub mod draw;
pub mod gallery;
pub mod image;
pub mod labels;
pub mod plan;
pub mod raster;
mod resolve;
pub mod scene;
pub mod shadow;
pub mod text;
pub mod views;

pub use camera::Camera;
pub use image::Image;
pub use scene::RenderScene;
pub use views::{asset_preview, contact_sheet, write_standard_views, write_views};

use crate::scene::Room;
use crate::state::SceneState;
use crate::state::install_rooms;

/// What can go wrong rendering.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// PNG encoding failed.
    #[error("PNG encoding failed: {0}")]
    Png(String),
    /// Writing a file failed.
    #[error(transparent)]
    Fs(#[from] crate::util::fsx::FsError),
    /// Reading a scene directory failed.
    #[error(transparent)]
    Format(#[from] crate::formats::FormatError),
    /// The image size is zero or too large.
    #[error("image size {width}x{height} is not between 1 and {max} pixels per side", max = raster::MAX_SIDE)]
    InvalidSize {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
    },
    /// A camera that cannot be built (degenerate direction, bad field of view, empty bounds).
    #[error("invalid camera: {0}")]
    InvalidCamera(String),
    /// The bundled font failed to load.
    #[error("font: {0}")]
    Font(String),
    /// An object names an asset the state does not hold.
    #[error("object {object:?} refers to asset {asset:?}, which is not loaded")]
    MissingAsset {
        /// Object id.
        object: String,
        /// Asset id.
        asset: String,
    },
    /// There is nothing to draw.
    #[error("nothing to render: {0}")]
    Empty(String),
    /// Geometry to draw could not be built (e.g. a room's architecture).
    #[error(transparent)]
    Geometry(#[from] crate::geometry::GeometryError),
}

/// Loads the scene directory `dir` ([`load_state`](crate::formats::scene_dir::load_state))
/// and writes its standard views into `out` (default `dir/renders`); returns the paths.
pub fn render_scene_dir(
    dir: &std::path::Path,
    out: Option<&std::path::Path>,
) -> Result<Vec<std::path::PathBuf>, RenderError> {
    let state = crate::formats::scene_dir::load_state(dir)?;
    match out {
        Some(out) => write_views(out, &state),
        None => write_standard_views(dir, &state),
    }
}

/// Renders the plan of a scene state (`top.png`'s content) at the default size.
pub fn top_view(state: &SceneState) -> Result<Image, RenderError> {
    let rs = RenderScene::from_state(state)?;
    plan::plan_view(&rs, &plan::PlanOptions::default())
}

/// The top-down plan of a layout as PNG bytes: rooms with their names, sizes and materials,
/// textured floors, walls, doors with their swing and windows (what `scenesmith layout --png`
/// writes and an LLM designer or critic of the layout stage can be shown).
pub fn plan_png(prompt: &str, seed: u64, rooms: &[Room]) -> Result<Vec<u8>, RenderError> {
    let mut state = SceneState::new(crate::scene::Scene::new(prompt, seed, "layout"));
    install_rooms(&mut state, rooms)?;
    top_view(&state)?.encode_png()
}

/// Renders the corner views of the room `room_id` of a scene state; `(name, image)` pairs
/// named `<room>_view_<k>`.
pub fn room_views_of(
    state: &SceneState,
    room_id: &str,
    opts: &views::RoomViewOptions,
) -> Result<Vec<(String, Image)>, RenderError> {
    let rs = RenderScene::from_state(state)?;
    let index = rs
        .rooms
        .iter()
        .position(|r| r.id == room_id)
        .ok_or_else(|| RenderError::Empty(format!("the scene has no room {room_id:?}")))?;
    views::room_views(&rs, index, opts)
}
