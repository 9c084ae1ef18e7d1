//! The annotated top-down plan: geometry seen from above (walls dark, ceiling and ceiling
//! fixtures left out, the latter outlined dashed), doors with their swing, windows, room names
//! and sizes, every object labelled with its id, a scale bar and the world axes.

use super::RenderError;
use super::camera::Camera;
use super::draw::{Canvas, arc_points};
use super::image::Image;
use super::labels::{self, Label};
use super::raster::{self, DrawItem, RasterOptions};
use super::scene::{RenderScene, Role};
use super::shadow::FloorShadow;
use super::text::{draw_text, measure};
use crate::geometry::polygon;
use crate::scene::{ObjectKind, OpeningKind};

/// Plan options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanOptions {
    /// Longest image side, pixels.
    pub max_side_px: u32,
    /// Upper limit of the scale, pixels per metre (small rooms are not blown up).
    pub max_px_per_m: f64,
    /// Free border around the rooms, metres (room for labels and the scale bar).
    pub margin_m: f64,
    /// Label objects with their ids.
    pub object_labels: bool,
    /// Samples per pixel along each axis.
    pub supersample: u32,
}

impl Default for PlanOptions {
    fn default() -> Self {
        PlanOptions {
            max_side_px: 1600,
            max_px_per_m: 200.0,
            margin_m: 0.7,
            object_labels: true,
            supersample: 2,
        }
    }
}

/// Plan wall colour (linear).
const WALL: [f32; 3] = [0.035, 0.037, 0.045];

/// Plan floor colour: 25 % of the material over a light neutral.
fn pale(c: [f32; 3]) -> [f32; 3] {
    let base = [0.80, 0.80, 0.78];
    [
        0.25 * c[0] + 0.75 * base[0],
        0.25 * c[1] + 0.75 * base[1],
        0.25 * c[2] + 0.75 * base[2],
    ]
}

/// XY bounds of the plan: rooms (walls included) or, without rooms, all geometry.
/// The mean linear colour of a mesh: its colour times its texture's mean (textured floors
/// are drawn flat in the plan).
fn mean_color(m: &super::scene::RenderMesh) -> [f32; 3] {
    let Some(t) = &m.texture else {
        return m.color;
    };
    let mut sum = [0.0f64; 3];
    let texels = t.rgba.chunks_exact(4);
    let n = texels.len().max(1) as f64;
    for px in texels {
        for k in 0..3 {
            sum[k] += (f64::from(px[k]) / 255.0).powf(2.2);
        }
    }
    [0, 1, 2].map(|k| m.color[k] * (sum[k] / n) as f32)
}

fn plan_bounds(rs: &RenderScene) -> Option<([f64; 2], [f64; 2])> {
    let mut pts: Vec<[f64; 2]> = Vec::new();
    for r in &rs.rooms {
        pts.extend(&r.floor_polygon);
        for w in &r.walls {
            let h = w.thickness / 2.0;
            pts.extend([
                [w.start[0] - h, w.start[1] - h],
                [w.end[0] + h, w.end[1] + h],
                [w.start[0] + h, w.start[1] + h],
                [w.end[0] - h, w.end[1] - h],
            ]);
        }
    }
    if pts.is_empty() {
        let (lo, hi) = rs.bounds_where(|m| m.role != Role::Ceiling)?;
        return Some(([lo[0], lo[1]], [hi[0], hi[1]]));
    }
    let (lo, hi) = polygon::bounds(&pts);
    Some((lo, hi))
}

/// Renders the annotated plan of `rs`.
pub fn plan_view(rs: &RenderScene, opts: &PlanOptions) -> Result<Image, RenderError> {
    let (lo, hi) = plan_bounds(rs)
        .ok_or_else(|| RenderError::Empty("the scene has no rooms or geometry".into()))?;
    let m = opts.margin_m.max(0.0);
    let (lo, hi) = ([lo[0] - m, lo[1] - m], [hi[0] + m, hi[1] + m]);
    let (wm, hm) = (hi[0] - lo[0], hi[1] - lo[1]);
    let ppm = (f64::from(opts.max_side_px) / wm.max(hm)).min(opts.max_px_per_m);
    let width = ((wm * ppm).round() as u32).clamp(1, raster::MAX_SIDE);
    let height = ((hm * ppm).round() as u32).clamp(1, raster::MAX_SIDE);
    let top_z = rs.bounds_where(|_| true).map(|(_, h)| h[2]).unwrap_or(3.0) + 1.0;
    let camera = Camera::top_down(lo, hi, top_z)?;

    let hidden = |m: &super::scene::RenderMesh| {
        m.role == Role::Ceiling
            || m.object
                .and_then(|o| rs.objects.get(o))
                .is_some_and(|o| o.kind == ObjectKind::Ceiling)
    };
    let items: Vec<DrawItem<'_>> = rs
        .meshes
        .iter()
        .filter(|m| !hidden(m))
        .map(|m| match m.role {
            Role::Wall { .. } => DrawItem {
                mesh: m,
                color: Some(WALL),
                unlit: true,
                receives_shadow: false,
            },
            // A pale, flat version of the floor material, so furniture of the same material
            // (a wooden table on a wooden floor) still stands out.
            Role::Floor => DrawItem {
                mesh: m,
                color: Some(pale(mean_color(m))),
                unlit: true,
                receives_shadow: true,
            },
            _ => DrawItem::new(m),
        })
        .collect();
    let mut ropts = RasterOptions::new(width, height);
    ropts.supersample = opts.supersample;
    ropts.background = [0.93, 0.93, 0.92];
    ropts.edge_strength = 0.6;
    // From above, the key light mostly from the zenith keeps tops evenly lit.
    ropts.lighting.key_dir = [0.3, -0.4, 1.0];
    let casters: Vec<DrawItem<'_>> = items
        .iter()
        .filter(|i| i.mesh.role == Role::Object)
        .copied()
        .collect();
    let shadow = FloorShadow::build(&casters, lo, hi, 0.0, 0.02, 0.1, 0.55)?;
    let out = raster::render_with_shadow(&items, &camera, &ropts, rs.objects.len(), Some(&shadow))?;

    let to_px = |p: [f64; 2]| -> [f64; 2] {
        camera
            .project([p[0], p[1], 0.0], width, height)
            .map(|q| [q[0], q[1]])
            .unwrap_or([0.0, 0.0])
    };
    let mut canvas = Canvas::new(out.image);
    draw_openings(&mut canvas, rs, &to_px, ppm);
    for o in rs.objects.iter().filter(|o| o.kind == ObjectKind::Ceiling) {
        let [a, b] = o.bounds;
        let ring = [[a[0], a[1]], [b[0], a[1]], [b[0], b[1]], [a[0], b[1]]].map(to_px);
        canvas.polyline(&ring, true, [60, 60, 140, 220], 1.5, Some([6.0, 4.0]));
    }
    let mut img = canvas.finish();

    let mut ls = Vec::new();
    for o in &rs.objects {
        if o.kind == ObjectKind::Architecture {
            continue;
        }
        let c = o.center();
        let [a, b] = o.bounds;
        let footprint = (b[0] - a[0]) * (b[1] - a[1]);
        let kind_rank = match o.kind {
            ObjectKind::Furniture => 4.0,
            ObjectKind::Wall => 3.0,
            ObjectKind::ThinCovering => 1.0,
            ObjectKind::Ceiling => 2.0,
            _ => 0.0,
        };
        let (p0, p1) = (to_px([a[0], b[1]]), to_px([b[0], a[1]]));
        ls.push(Label {
            text: o.id.clone(),
            anchor: to_px([c[0], c[1]]),
            priority: kind_rank * 100.0 + footprint.min(99.0),
            size_px: 12.0,
            target: Some([p0[0], p0[1], p1[0], p1[1]]),
        });
    }
    let mut obstacles = Vec::new();
    obstacles.push(draw_scale_bar(&mut img, ppm)?);
    obstacles.push(draw_axes(&mut img)?);
    let footprints: Vec<[f64; 4]> = ls.iter().filter_map(|l| l.target).collect();
    for r in &rs.rooms {
        let taken: Vec<[f64; 4]> = footprints.iter().chain(&obstacles).copied().collect();
        obstacles.push(draw_room_label(&mut img, r, &to_px, &taken)?);
    }
    if opts.object_labels {
        let placed = labels::place(&ls, img.width, img.height, &obstacles)?;
        labels::draw(&mut img, &ls, &placed)?;
    }
    Ok(img)
}

/// Windows (light blue glazing across the wall), doors (leaf and swing arc into the owning
/// room) and open connections (dashed).
fn draw_openings(
    canvas: &mut Canvas,
    rs: &RenderScene,
    to_px: &dyn Fn([f64; 2]) -> [f64; 2],
    ppm: f64,
) {
    for room in &rs.rooms {
        for wall in &room.walls {
            let len = wall.length();
            if len < 1e-9 {
                continue;
            }
            let ux = [
                (wall.end[0] - wall.start[0]) / len,
                (wall.end[1] - wall.start[1]) / len,
            ];
            // Wall frame +Y (into the owning room) is +X rotated by +90 degrees.
            let uy = [-ux[1], ux[0]];
            let at = |x: f64, y: f64| -> [f64; 2] {
                to_px([
                    wall.start[0] + ux[0] * x + uy[0] * y,
                    wall.start[1] + ux[1] * x + uy[1] * y,
                ])
            };
            let h = wall.thickness / 2.0;
            for o in &wall.openings {
                let (x0, x1) = (
                    (o.center - o.width / 2.0).max(0.0),
                    (o.center + o.width / 2.0).min(len),
                );
                match o.kind {
                    OpeningKind::Window => {
                        let ring = [at(x0, -h), at(x1, -h), at(x1, h), at(x0, h)];
                        canvas.fill(&ring, [175, 215, 240, 255]);
                        canvas.polyline(&ring, true, [30, 60, 90, 255], 1.2, None);
                        canvas.line(at(x0, 0.0), at(x1, 0.0), [30, 60, 90, 255], 1.2);
                    }
                    OpeningKind::Door => {
                        // Hinge at the jamb nearer a wall end, so the door folds back onto the
                        // shorter stretch of wall.
                        let hinge_at_start = x0 <= len - x1;
                        let (hx, fx) = if hinge_at_start { (x0, x1) } else { (x1, x0) };
                        let w = (x1 - x0).max(0.0);
                        let hinge = [hx, h];
                        let leaf_tip = [hx, h + w];
                        let color = [140, 50, 30, 255];
                        canvas.line(
                            at(hinge[0], hinge[1]),
                            at(leaf_tip[0], leaf_tip[1]),
                            color,
                            2.5,
                        );
                        // Swing arc from the open leaf tip down to the far jamb.
                        let (a0, a1) = if hinge_at_start {
                            (std::f64::consts::FRAC_PI_2, 0.0)
                        } else {
                            (std::f64::consts::FRAC_PI_2, std::f64::consts::PI)
                        };
                        let pts: Vec<[f64; 2]> = arc_points(hinge, w, a0, a1, 24)
                            .into_iter()
                            .map(|p| at(p[0], p[1]))
                            .collect();
                        canvas.polyline(&pts, false, color, 1.3, Some([5.0, 3.0]));
                        // Threshold line across the doorway.
                        canvas.line(at(fx, -h), at(fx, h), color, 1.0);
                        canvas.line(at(hx, -h), at(hx, h), color, 1.0);
                    }
                    OpeningKind::Open => {
                        canvas.polyline(
                            &[at(x0, 0.0), at(x1, 0.0)],
                            false,
                            [90, 90, 90, 255],
                            1.2,
                            Some([(0.1 * ppm) as f32, (0.06 * ppm) as f32]),
                        );
                    }
                }
            }
        }
    }
}

/// Draws a boxed two-line room label (type, id, size, area) in the inside corner where it
/// covers least of `taken`; returns its box.
fn draw_room_label(
    img: &mut Image,
    room: &crate::scene::Room,
    to_px: &dyn Fn([f64; 2]) -> [f64; 2],
    taken: &[[f64; 4]],
) -> Result<[f64; 4], RenderError> {
    let (lo, hi) = polygon::bounds(&room.floor_polygon);
    let area = polygon::signed_area(&room.floor_polygon).abs();
    let title = format!("{} ({})", room.room_type, room.id);
    let sub = format!(
        "{:.1} x {:.1} m, {:.1} m\u{b2}; {} floor, {} walls",
        hi[0] - lo[0],
        hi[1] - lo[1],
        area,
        room.floor_material,
        room.wall_material
    );
    let (t_px, s_px) = (16.0, 12.0);
    let mt = measure(&title, t_px)?;
    let ms = measure(&sub, s_px)?;
    let w = f64::from(mt.width.max(ms.width)) + 10.0;
    let h = f64::from(mt.height() + ms.height()) + 8.0;
    // The inside corner where the label covers least furniture (top-left on ties).
    let (tl, br) = (to_px([lo[0], hi[1]]), to_px([hi[0], lo[1]]));
    let candidates = [
        [tl[0] + 6.0, tl[1] + 6.0],
        [br[0] - 6.0 - w, tl[1] + 6.0],
        [tl[0] + 6.0, br[1] - 6.0 - h],
        [br[0] - 6.0 - w, br[1] - 6.0 - h],
    ];
    let overlap = |r: [f64; 4], t: &[f64; 4]| {
        (r[2].min(t[2]) - r[0].max(t[0])).max(0.0) * (r[3].min(t[3]) - r[1].max(t[1])).max(0.0)
    };
    let mut best = (f64::INFINITY, candidates[0]);
    for c in candidates {
        let r = [c[0], c[1], c[0] + w, c[1] + h];
        let cost: f64 = taken.iter().map(|t| overlap(r, t)).sum();
        if cost < best.0 {
            best = (cost, c);
        }
    }
    let [x0, y0] = best.1;
    let rect = [x0, y0, x0 + w, y0 + h];
    img.fill_rect(
        x0 as i64,
        y0 as i64,
        (x0 + w) as i64,
        (y0 + h) as i64,
        [250, 250, 245],
        0.85,
    );
    draw_text(
        img,
        (x0 + 5.0) as f32,
        y0 as f32 + 3.0 + mt.ascent,
        &title,
        t_px,
        [15, 15, 20],
    )?;
    draw_text(
        img,
        (x0 + 5.0) as f32,
        y0 as f32 + 4.0 + mt.height() + ms.ascent,
        &sub,
        s_px,
        [60, 60, 70],
    )?;
    Ok(rect)
}

/// A scale bar in the bottom-left corner, its length a round number of metres; returns its
/// box.
fn draw_scale_bar(img: &mut Image, ppm: f64) -> Result<[f64; 4], RenderError> {
    let target_px = (f64::from(img.width) * 0.18).clamp(60.0, 260.0);
    let len_m = [0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0]
        .into_iter()
        .rev()
        .find(|l| l * ppm <= target_px)
        .unwrap_or(0.25);
    let len_px = len_m * ppm;
    let (x0, y1) = (12.0f64, f64::from(img.height) - 12.0);
    let bar_h = 7.0;
    let y0 = y1 - bar_h;
    let segments = 4;
    for i in 0..segments {
        let a = x0 + len_px * f64::from(i) / f64::from(segments);
        let b = x0 + len_px * f64::from(i + 1) / f64::from(segments);
        let c = if i % 2 == 0 {
            [20, 20, 25]
        } else {
            [250, 250, 250]
        };
        img.fill_rect(
            a.round() as i64,
            y0 as i64,
            b.round() as i64,
            y1 as i64,
            c,
            1.0,
        );
    }
    let k = [20, 20, 25];
    img.fill_rect(
        x0 as i64,
        y0 as i64 - 1,
        (x0 + len_px).round() as i64 + 1,
        y0 as i64,
        k,
        1.0,
    );
    img.fill_rect(
        x0 as i64,
        y1 as i64,
        (x0 + len_px).round() as i64 + 1,
        y1 as i64 + 1,
        k,
        1.0,
    );
    img.fill_rect(
        (x0 + len_px).round() as i64,
        y0 as i64 - 1,
        (x0 + len_px).round() as i64 + 1,
        y1 as i64 + 1,
        k,
        1.0,
    );
    let text = if len_m < 1.0 {
        format!("{} cm", (len_m * 100.0).round())
    } else {
        format!("{len_m} m")
    };
    let m = measure(&text, 12.0)?;
    let ty = (y0 - 4.0) as f32;
    draw_text(img, x0 as f32, ty, "0", 12.0, k)?;
    draw_text(
        img,
        (x0 + len_px) as f32 - m.width / 2.0,
        ty,
        &text,
        12.0,
        k,
    )?;
    Ok([
        x0 - 2.0,
        y0 - 4.0 - f64::from(m.height()),
        x0 + len_px + f64::from(m.width),
        y1 + 2.0,
    ])
}

/// World axes (+x right, +y up) in the bottom-right corner; returns their box.
fn draw_axes(img: &mut Image) -> Result<[f64; 4], RenderError> {
    let (w, h) = (f64::from(img.width), f64::from(img.height));
    let o = [w - 52.0, h - 16.0];
    let len = 30.0;
    let color = [30, 30, 36, 255];
    let mut c = Canvas::new(std::mem::replace(img, Image::new(1, 1, [0; 4])));
    c.line(o, [o[0] + len, o[1]], color, 1.6);
    c.arrow_head([o[0] + len + 4.0, o[1]], [1.0, 0.0], 7.0, color);
    c.line(o, [o[0], o[1] - len], color, 1.6);
    c.arrow_head([o[0], o[1] - len - 4.0], [0.0, -1.0], 7.0, color);
    *img = c.finish();
    draw_text(
        img,
        (o[0] + len + 6.0) as f32,
        (o[1] + 4.0) as f32,
        "x",
        12.0,
        [30, 30, 36],
    )?;
    draw_text(
        img,
        (o[0] + 5.0) as f32,
        (o[1] - len) as f32,
        "y",
        12.0,
        [30, 30, 36],
    )?;
    Ok([o[0] - 4.0, o[1] - len - 12.0, w, h])
}
