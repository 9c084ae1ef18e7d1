//! The standard views: per-room perspective views from the corners (walls between the camera
//! and the room cut away, no ceiling, objects labelled), a three-quarter preview of one asset,
//! contact sheets, and [`write_standard_views`], which writes the plan and the room views of a
//! scene into `renders/`.

use std::path::{Path, PathBuf};

use nalgebra::{Point3, Vector2};

use super::RenderError;
use super::camera::{Camera, fit_perspective};
use super::image::Image;
use super::labels::{self, Label};
use super::plan::{PlanOptions, plan_view};
use super::raster::{self, DrawItem, RasterOptions};
use super::scene::{RenderMesh, RenderScene, Role};
use super::shadow::FloorShadow;
use super::text::{draw_text, measure};
use crate::assets::Asset;
use crate::scene::{ObjectKind, Room};
use crate::state::SceneState;
use crate::util::fsx::{FsError, files_under, replace_folder, swap_folder};

/// Options of the per-room perspective views.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoomViewOptions {
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Vertical field of view, degrees.
    pub fov_y_deg: f64,
    /// Camera height above the floor, metres.
    pub eye_height_m: f64,
    /// Samples per pixel along each axis.
    pub supersample: u32,
    /// Label visible objects with their ids.
    pub labels: bool,
}

impl Default for RoomViewOptions {
    fn default() -> Self {
        RoomViewOptions {
            width: 1280,
            height: 960,
            fov_y_deg: 60.0,
            eye_height_m: 1.6,
            supersample: 2,
            labels: true,
        }
    }
}

/// Corners of a floor polygon that a camera can look in from (convex corners), with the unit
/// bisector pointing into the room.
fn convex_corners(ring: &[[f64; 2]]) -> Vec<([f64; 2], [f64; 2])> {
    let n = ring.len();
    if n < 3 {
        return Vec::new();
    }
    let ccw = crate::geometry::polygon::signed_area(ring) >= 0.0;
    let mut out = Vec::new();
    for k in 0..n {
        let p = Vector2::from(ring[k]);
        let a = Vector2::from(ring[(k + n - 1) % n]);
        let b = Vector2::from(ring[(k + 1) % n]);
        let (ea, eb) = (p - a, b - p);
        let cross = ea.x * eb.y - ea.y * eb.x;
        let convex = if ccw { cross > 1e-9 } else { cross < -1e-9 };
        if !convex {
            continue;
        }
        let (Some(to_a), Some(to_b)) = ((a - p).try_normalize(1e-12), (b - p).try_normalize(1e-12))
        else {
            continue;
        };
        if let Some(d) = (to_a + to_b).try_normalize(1e-12) {
            out.push((ring[k], [d.x, d.y]));
        }
    }
    // More than four corners (an L or U room): keep four spread around the polygon.
    if out.len() > 4 {
        let m = out.len();
        out = (0..4).map(|i| out[i * m / 4]).collect();
    }
    out
}

fn centroid(ring: &[[f64; 2]]) -> [f64; 2] {
    let n = ring.len().max(1) as f64;
    let s = ring
        .iter()
        .fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
    [s[0] / n, s[1] / n]
}

/// True when `wall` (of `rooms[wall_room]`) stands between the camera and the viewed room: its
/// centre line separates the eye from the room's centre, or the eye is (nearly) inside it.
fn wall_is_between(
    rooms: &[Room],
    wall_room: usize,
    wall: usize,
    eye: [f64; 2],
    center: [f64; 2],
) -> bool {
    let Some(w) = rooms.get(wall_room).and_then(|r| r.walls.get(wall)) else {
        return false;
    };
    let wall_from_world = w.world_from_wall().inverse();
    let y = |p: [f64; 2]| {
        wall_from_world
            .transform_point(&Point3::new(p[0], p[1], 0.0))
            .y
    };
    let (ye, yc) = (y(eye), y(center));
    ye.abs() < w.thickness / 2.0 + 0.05 || ye * yc < 0.0
}

/// Perspective views of one room from its corners at eye height, looking in; returns
/// `(name, image)` pairs named `<room>_view_<k>`.
pub fn room_views(
    rs: &RenderScene,
    room_index: usize,
    opts: &RoomViewOptions,
) -> Result<Vec<(String, Image)>, RenderError> {
    let room = rs
        .rooms
        .get(room_index)
        .ok_or_else(|| RenderError::Empty(format!("no room with index {room_index}")))?;
    let center = centroid(&room.floor_polygon);
    let in_room = |m: &RenderMesh| -> bool {
        match m.object.and_then(|o| rs.objects.get(o)) {
            Some(o) if o.kind == ObjectKind::Architecture => true,
            Some(o) => o.room == room.id,
            None => true,
        }
    };
    // Points every view must show: every object of the room.
    let mut object_pts: Vec<[f64; 3]> = Vec::new();
    for o in rs
        .objects
        .iter()
        .filter(|o| o.room == room.id && o.kind != ObjectKind::Architecture)
    {
        let [a, b] = o.bounds;
        for i in 0..8 {
            object_pts.push([
                if i & 1 == 0 { a[0] } else { b[0] },
                if i & 2 == 0 { a[1] } else { b[1] },
                if i & 4 == 0 { a[2] } else { b[2] },
            ]);
        }
    }
    let aspect = f64::from(opts.width) / f64::from(opts.height);
    // Soft contact shadows of the room's objects on the floor, shared by its views.
    let casters: Vec<DrawItem<'_>> = rs
        .meshes
        .iter()
        .filter(|m| m.role == Role::Object && in_room(m))
        .map(DrawItem::new)
        .collect();
    let (flo, fhi) = crate::geometry::polygon::bounds(&room.floor_polygon);
    let shadow = FloorShadow::build(
        &casters,
        [flo[0] - 0.5, flo[1] - 0.5],
        [fhi[0] + 0.5, fhi[1] + 0.5],
        0.0,
        0.02,
        0.15,
        0.45,
    )?;
    let mut out = Vec::new();
    for (k, (corner, inward)) in convex_corners(&room.floor_polygon).into_iter().enumerate() {
        // Plus the floor corners away from the camera; the two beside it may fall out of the
        // frame (showing them would push the camera far back and shrink the room).
        let n = room.floor_polygon.len();
        let ci = room
            .floor_polygon
            .iter()
            .position(|p| *p == corner)
            .unwrap_or(0);
        let mut fit_pts = object_pts.clone();
        for (j, p) in room.floor_polygon.iter().enumerate() {
            if j != ci && j != (ci + 1) % n && j != (ci + n - 1) % n {
                // The far corners floor to ceiling: the view shows the room, not only its
                // furniture.
                fit_pts.push([p[0], p[1], 0.0]);
                fit_pts.push([p[0], p[1], room.wall_height]);
            }
        }
        if fit_pts.is_empty() {
            fit_pts.push([center[0], center[1], 0.0]);
        }
        let camera = corner_camera(corner, inward, center, &fit_pts, opts, aspect)?;
        let eye = [camera.eye.x, camera.eye.y];
        let items: Vec<DrawItem<'_>> = rs
            .meshes
            .iter()
            .filter(|m| in_room(m))
            .filter(|m| match m.role {
                Role::Ceiling => false,
                Role::Wall { room: r, wall } => !wall_is_between(&rs.rooms, r, wall, eye, center),
                _ => true,
            })
            .map(|m| DrawItem {
                receives_shadow: m.role == Role::Floor,
                ..DrawItem::new(m)
            })
            .collect();
        let mut ropts = RasterOptions::new(opts.width, opts.height);
        ropts.supersample = opts.supersample;
        ropts.background = [0.80, 0.81, 0.83];
        let r =
            raster::render_with_shadow(&items, &camera, &ropts, rs.objects.len(), Some(&shadow))?;
        let mut img = r.image;
        let caption = format!(
            "{} ({}), view {k} from corner ({:.1}, {:.1})",
            room.room_type, room.id, corner[0], corner[1]
        );
        let cap_box = draw_caption(&mut img, &caption)?;
        if opts.labels {
            let mut ls = Vec::new();
            for (oi, o) in rs.objects.iter().enumerate() {
                let Some(cov) = r.coverage.get(oi) else {
                    continue;
                };
                if o.kind == ObjectKind::Architecture || o.room != room.id || cov.pixels < 30.0 {
                    continue;
                }
                ls.push(Label {
                    text: o.id.clone(),
                    anchor: cov.centroid,
                    priority: cov.pixels,
                    size_px: 13.0,
                    target: Some(cov.bbox),
                });
            }
            let placed = labels::place(&ls, img.width, img.height, &[cap_box])?;
            labels::draw(&mut img, &ls, &placed)?;
        }
        out.push((format!("{}_view_{k}", room.id), img));
    }
    Ok(out)
}

/// A level camera at eye height at `corner` or behind it (along `-inward`), facing the room
/// centre, with a lens shift that frames `fit_pts`: verticals stay vertical. It stands as
/// close to the corner as the field of view allows (at most 6 m back).
fn corner_camera(
    corner: [f64; 2],
    inward: [f64; 2],
    center: [f64; 2],
    fit_pts: &[[f64; 3]],
    opts: &RoomViewOptions,
    aspect: f64,
) -> Result<Camera, RenderError> {
    let max_tan = (opts.fov_y_deg.to_radians() / 2.0).tan();
    let margin = 0.05;
    // The frame (lens shift, tan of half the vertical field) that shows every point from
    // `back` metres behind the corner; `None` when a point is behind the camera.
    let frame = |back: f64| -> Result<Option<(Camera, f64)>, RenderError> {
        let eye = [
            corner[0] - inward[0] * back,
            corner[1] - inward[1] * back,
            opts.eye_height_m,
        ];
        let look = [center[0], center[1], opts.eye_height_m];
        let look = if (look[0] - eye[0]).hypot(look[1] - eye[1]) > 1e-6 {
            look
        } else {
            [eye[0] + inward[0], eye[1] + inward[1], eye[2]]
        };
        let mut cam = Camera::look_at(eye, look, [0.0, 0.0, 1.0], opts.fov_y_deg)?;
        cam.near = 0.05;
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in fit_pts {
            let c = cam.to_camera(*p);
            if c.z < 0.1 {
                return Ok(None);
            }
            let (x, y) = (c.x / c.z, c.y / c.z);
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        let need = ((y1 - y0) / 2.0).max((x1 - x0) / 2.0 / aspect) / (1.0 - margin);
        cam.lens_shift = [(x0 + x1) / 2.0, (y0 + y1) / 2.0];
        Ok(Some((cam, need)))
    };
    let fits = |back: f64| -> Result<Option<Camera>, RenderError> {
        Ok(match frame(back)? {
            Some((mut cam, need)) if need <= max_tan => {
                // Zoom in when the points need less than the widest field of view, but not to
                // a telephoto view of a single small object.
                let tan = need.max(max_tan * 0.6);
                cam.projection = super::camera::Projection::Perspective {
                    tan_half_fov_y: tan,
                };
                Some(cam)
            }
            _ => None,
        })
    };
    if let Some(cam) = fits(0.0)? {
        return Ok(cam);
    }
    let (mut lo, mut hi) = (0.0f64, 6.0f64);
    let Some(mut best) = fits(hi)? else {
        // Even 6 m back does not show everything: use the widest view from there.
        return frame(hi)?
            .map(|(mut cam, _)| {
                cam.projection = super::camera::Projection::Perspective {
                    tan_half_fov_y: max_tan,
                };
                cam
            })
            .ok_or_else(|| {
                RenderError::InvalidCamera("no view of the room from its corner".into())
            });
    };
    for _ in 0..30 {
        let mid = (lo + hi) / 2.0;
        match fits(mid)? {
            Some(cam) => {
                hi = mid;
                best = cam;
            }
            None => lo = mid,
        }
    }
    Ok(best)
}

/// Draws a caption box in the top-left corner; returns its box.
fn draw_caption(img: &mut Image, text: &str) -> Result<[f64; 4], RenderError> {
    let px = 14.0;
    let m = measure(text, px)?;
    let (x0, y0) = (8.0, 8.0);
    let (x1, y1) = (
        x0 + f64::from(m.width) + 10.0,
        y0 + f64::from(m.height()) + 6.0,
    );
    img.fill_rect(
        x0 as i64,
        y0 as i64,
        x1 as i64,
        y1 as i64,
        [250, 250, 245],
        0.85,
    );
    draw_text(
        img,
        (x0 + 5.0) as f32,
        y0 as f32 + 3.0 + m.ascent,
        text,
        px,
        [15, 15, 20],
    )?;
    Ok([x0, y0, x1, y1])
}

/// A three-quarter view (front-right, from above) of one asset at zero joint positions,
/// fitted to a `width x height` frame on a neutral background.
pub fn asset_preview(asset: &Asset, width: u32, height: u32) -> Result<Image, RenderError> {
    if width == 0 || height == 0 || width > raster::MAX_SIDE || height > raster::MAX_SIDE {
        return Err(RenderError::InvalidSize { width, height });
    }
    let rs = RenderScene::from_asset(asset);
    let mut pts = Vec::new();
    for m in &rs.meshes {
        if let Some((a, b)) = m.bounds() {
            for i in 0..8 {
                pts.push([
                    if i & 1 == 0 { a[0] } else { b[0] },
                    if i & 2 == 0 { a[1] } else { b[1] },
                    if i & 4 == 0 { a[2] } else { b[2] },
                ]);
            }
        }
    }
    if pts.is_empty() {
        return Err(RenderError::Empty(format!(
            "asset {} has no visual geometry",
            asset.id
        )));
    }
    // Asset front is +Y: look from front-right and above, towards -Y.
    let direction = [-0.62, -1.0, -0.62];
    let camera = fit_perspective(
        direction,
        [0.0, 0.0, 1.0],
        30.0,
        f64::from(width) / f64::from(height),
        &pts,
        0.1,
    )?;
    let items: Vec<DrawItem<'_>> = rs.meshes.iter().map(DrawItem::new).collect();
    let mut ropts = RasterOptions::new(width, height);
    ropts.background = [0.78, 0.79, 0.80];
    ropts.supersample = 3;
    Ok(raster::render(&items, &camera, &ropts, 1)?.image)
}

/// A grid of images, `columns` per row, each with its caption underneath, on white.
pub fn contact_sheet(items: &[(String, Image)], columns: usize) -> Result<Image, RenderError> {
    if items.is_empty() {
        return Err(RenderError::Empty(
            "a contact sheet needs at least one image".into(),
        ));
    }
    let cols = columns.clamp(1, items.len());
    let rows = items.len().div_ceil(cols);
    let cell_w = items.iter().map(|(_, i)| i.width).max().unwrap_or(1);
    let cell_h = items.iter().map(|(_, i)| i.height).max().unwrap_or(1);
    let (pad, cap_px) = (8u32, 14.0f32);
    let cap_h = (measure("Ag", cap_px)?.height().ceil() as u32) + 6;
    let width = cols as u32 * (cell_w + pad) + pad;
    let height = rows as u32 * (cell_h + cap_h + pad) + pad;
    if width > raster::MAX_SIDE * 2 || height > raster::MAX_SIDE * 2 {
        return Err(RenderError::InvalidSize { width, height });
    }
    let mut sheet = Image::new(width, height, [255, 255, 255, 255]);
    for (i, (caption, img)) in items.iter().enumerate() {
        let (c, r) = ((i % cols) as u32, (i / cols) as u32);
        let x = pad + c * (cell_w + pad);
        let y = pad + r * (cell_h + cap_h + pad);
        let ox = x + (cell_w - img.width) / 2;
        let oy = y + (cell_h - img.height) / 2;
        sheet.blit(img, i64::from(ox), i64::from(oy));
        let text = fit_text(caption, cap_px, cell_w as f32)?;
        let m = measure(&text, cap_px)?;
        let tx = x as f32 + (cell_w as f32 - m.width) / 2.0;
        let ty = (y + cell_h + 3) as f32 + m.ascent;
        draw_text(&mut sheet, tx, ty, &text, cap_px, [20, 20, 28])?;
    }
    Ok(sheet)
}

/// `text`, shortened with an ellipsis to fit `max_w` pixels.
fn fit_text(text: &str, px: f32, max_w: f32) -> Result<String, RenderError> {
    if measure(text, px)?.width <= max_w {
        return Ok(text.to_string());
    }
    let chars: Vec<char> = text.chars().collect();
    for n in (0..chars.len()).rev() {
        let s: String = chars[..n].iter().collect::<String>() + "\u{2026}";
        if measure(&s, px)?.width <= max_w {
            return Ok(s);
        }
    }
    Ok(String::new())
}

/// `top.png` and every room's corner views (`<room>_view_<k>.png`) of `state`, encoded.
fn encoded_views(state: &SceneState) -> Result<Vec<(PathBuf, Vec<u8>)>, RenderError> {
    let rs = RenderScene::from_state(state)?;
    let top = plan_view(&rs, &PlanOptions::default())?;
    let mut files = vec![(PathBuf::from("top.png"), top.encode_png()?)];
    for ri in 0..rs.rooms.len() {
        for (name, img) in room_views(&rs, ri, &RoomViewOptions::default())? {
            let name = format!("{}.png", crate::scene::sanitize_name(&name));
            files.push((PathBuf::from(name), img.encode_png()?));
        }
    }
    Ok(files)
}

/// Whether `name` is a file [`write_views`] writes.
fn is_view_file(name: &Path) -> bool {
    let n = name.to_string_lossy();
    n == "top.png"
        || n.strip_suffix(".png")
            .and_then(|s| s.rsplit_once("_view_"))
            .is_some_and(|(_, k)| !k.is_empty() && k.chars().all(|c| c.is_ascii_digit()))
}

/// Replaces `out_dir` with `top.png` and every room's corner views of `state` (so views of
/// rooms no longer in the scene go); refuses a folder holding other files. Returns the paths.
pub fn write_views(out_dir: &Path, state: &SceneState) -> Result<Vec<PathBuf>, RenderError> {
    if let Some(file) = files_under(out_dir)?.into_iter().find(|f| !is_view_file(f)) {
        return Err(FsError::ForeignFile {
            folder: out_dir.to_path_buf(),
            file,
        }
        .into());
    }
    let files = encoded_views(state)?;
    swap_folder(out_dir, &files)?;
    Ok(files.into_iter().map(|(p, _)| out_dir.join(p)).collect())
}

/// Replaces the standard views of a scene directory's state in `dir/renders/`, recorded in
/// the scene's manifest.
pub fn write_standard_views(dir: &Path, state: &SceneState) -> Result<Vec<PathBuf>, RenderError> {
    let out_dir = dir.join("renders");
    let files = encoded_views(state)?;
    replace_folder(dir, &out_dir, &files)?;
    Ok(files.into_iter().map(|(p, _)| out_dir.join(p)).collect())
}
