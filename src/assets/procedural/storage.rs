//! Case furniture: cabinets, wardrobes, dressers, nightstands, filing cabinets, sideboards,
//! TV stands, lockers, display cases, chests. Open shelving is in [`super::shelving`].
//!
//! Doors and drawers are separate links on joints ([`crate::assets::articulated::parts`]);
//! shelves keep real clearance between levels and every level is a surface (`shelf_N`).

use super::parts::{METAL, body, shade, surface};
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::articulated::parts::{Hinge, Look, Opening, door, door_pair, drawer, lid};
use crate::assets::{Joint, Link, LinkBuilder};
use crate::geometry::GeometryError;
use crate::scene::SurfaceRecord;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("cabinet", cabinet),
    ("wardrobe", wardrobe),
    ("dresser", dresser),
    ("sideboard", sideboard),
    ("locker", locker),
    ("display_case", display_case),
    ("chest", chest),
];

/// Panel thickness of case furniture, metres.
pub(super) const PANEL: f64 = 0.018;
/// Thickness of doors and drawer fronts, metres.
pub(super) const FRONT: f64 = 0.018;
/// Depth kept in front of doors and drawer fronts for their handles, metres.
pub(super) const HANDLE: f64 = 0.031;

/// The box of a case piece: its inside in model coordinates.
#[derive(Debug, Clone, Copy)]
pub(super) struct Carcass {
    /// Inside left / right x.
    pub x0: f64,
    pub x1: f64,
    /// Inside bottom / top z.
    pub z0: f64,
    pub z1: f64,
    /// Back panel's front face / carcass front face y.
    pub y_back: f64,
    pub y_front: f64,
}

impl Carcass {
    pub fn inner_w(&self) -> f64 {
        self.x1 - self.x0
    }
    pub fn inner_d(&self) -> f64 {
        self.y_front - self.y_back
    }
    pub fn cy(&self) -> f64 {
        (self.y_front + self.y_back) / 2.0
    }
    /// The `top` surface of a case `d` deep and `h` high, over the carcass (not the fronts).
    pub fn top_surface(&self, w: f64, d: f64, h: f64, clearance: f64) -> SurfaceRecord {
        surface(
            "top",
            "body",
            [0.0, (-d / 2.0 + self.y_front) / 2.0, h],
            [w, self.y_front + d / 2.0],
            clearance,
        )
    }
}

/// Sides, top, bottom, back and a recessed plinth of a `w` x `d` x `h` case whose front face
/// leaves `front_t` metres for doors or drawer fronts and [`HANDLE`] for their handles (the
/// carcass sits at the back). With
/// `on_legs` the sides start at the plinth height and there is no plinth board (the caller
/// adds legs).
#[allow(clippy::too_many_arguments)]
pub(super) fn carcass(
    b: &mut LinkBuilder,
    w: f64,
    d: f64,
    h: f64,
    plinth: f64,
    front_t: f64,
    color: [f64; 3],
    on_legs: bool,
) -> Result<Carcass, GeometryError> {
    carcass_opts(b, w, d, h, plinth, front_t, color, on_legs, true)
}

/// [`carcass`] with or without the top panel (counters and vanities carry a worktop with a
/// basin instead).
#[allow(clippy::too_many_arguments)]
pub(super) fn carcass_opts(
    b: &mut LinkBuilder,
    w: f64,
    d: f64,
    h: f64,
    plinth: f64,
    front_t: f64,
    color: [f64; 3],
    on_legs: bool,
    top: bool,
) -> Result<Carcass, GeometryError> {
    let cd = d - front_t - 0.002 - HANDLE;
    let y_back_out = -d / 2.0;
    let y_front = y_back_out + cd;
    let cy = (y_back_out + y_front) / 2.0;
    let z_side = if on_legs { plinth } else { 0.0 };
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - PANEL / 2.0), cy, (z_side + h) / 2.0],
            [PANEL, cd, h - z_side],
            color,
        )?;
    }
    let iw = w - 2.0 * PANEL;
    b.add_box([0.0, cy, plinth + PANEL / 2.0], [iw, cd, PANEL], color)?;
    if top {
        b.add_box([0.0, cy, h - PANEL / 2.0], [iw, cd, PANEL], color)?;
    }
    let back = 0.008;
    b.add_box(
        [0.0, y_back_out + back / 2.0, (plinth + h) / 2.0],
        [iw, back, h - plinth - 2.0 * PANEL],
        shade(color, 0.9),
    )?;
    if plinth > 0.0 && !on_legs {
        b.add_box(
            [0.0, y_front - 0.03, plinth / 2.0],
            [iw, PANEL, plinth],
            shade(color, 0.7),
        )?;
    }
    Ok(Carcass {
        x0: -w / 2.0 + PANEL,
        x1: w / 2.0 - PANEL,
        z0: plinth + PANEL,
        z1: h - PANEL,
        y_back: y_back_out + back,
        y_front,
    })
}

/// Horizontal shelves inside a carcass between `z_lo` and `z_hi` (`n` levels of equal
/// clearance); returns the shelf surfaces numbered from `first`.
fn inner_shelves(
    b: &mut LinkBuilder,
    c: &Carcass,
    z_lo: f64,
    z_hi: f64,
    n: usize,
    first: usize,
    color: [f64; 3],
) -> Result<Vec<SurfaceRecord>, GeometryError> {
    let pitch = (z_hi - z_lo) / n as f64;
    let sd = c.inner_d() - 0.01;
    let sy = c.y_back + sd / 2.0;
    let mut out = Vec::new();
    for i in 0..n {
        let z = z_lo + pitch * i as f64;
        if i > 0 {
            b.add_box(
                [(c.x0 + c.x1) / 2.0, sy, z],
                [c.inner_w() - 0.002, sd, PANEL],
                color,
            )?;
        }
        let base = if i > 0 { z + PANEL / 2.0 } else { z };
        let top = z_lo + pitch * (i + 1) as f64 - if i + 1 < n { PANEL / 2.0 } else { 0.0 };
        out.push(surface(
            &format!("shelf_{}", first + i),
            "body",
            [(c.x0 + c.x1) / 2.0, sy, base],
            [c.inner_w() - 0.004, sd],
            top - base,
        ));
    }
    Ok(out)
}

fn look(ctx: &GenContext) -> Look {
    Look {
        material: ctx.material,
        front: shade(ctx.color, 0.97),
        inner: shade(ctx.color, 0.8),
        handle: ctx.accent_color,
    }
}

/// Assembles the body and its moving parts.
pub(super) fn assemble(
    b: LinkBuilder,
    parts: Vec<(Link, Joint)>,
    surfaces: Vec<SurfaceRecord>,
) -> Result<Generated, GeometryError> {
    let mut links = vec![b.finish()?];
    let mut joints = Vec::new();
    for (l, j) in parts {
        links.push(l);
        joints.push(j);
    }
    Ok(Generated {
        links,
        joints,
        surfaces,
    })
}

/// A column of drawers filling `opening` from top to bottom; heights grow downward.
#[allow(clippy::too_many_arguments)]
fn drawer_column(
    b: &mut LinkBuilder,
    c: &Carcass,
    x: [f64; 2],
    z: [f64; 2],
    n: usize,
    first: usize,
    look: Look,
    parts: &mut Vec<(Link, Joint)>,
    surfaces: &mut Vec<SurfaceRecord>,
) -> Result<(), GeometryError> {
    let div = PANEL;
    let weights: Vec<f64> = (0..n).map(|i| 1.0 + 0.15 * i as f64).collect();
    let total: f64 = weights.iter().sum();
    let avail = z[1] - z[0] - div * (n as f64 - 1.0);
    let mut top = z[1];
    let depth = c.inner_d() - 0.02;
    for (i, wgt) in weights.iter().enumerate() {
        let hh = avail * wgt / total;
        let o = Opening {
            x0: x[0],
            x1: x[1],
            z0: top - hh,
            z1: top,
        };
        let (l, j, s) = drawer(
            &format!("drawer_{}", first + i),
            "body",
            o,
            c.y_front,
            depth,
            div / 2.0 - 0.0015,
            look,
        )?;
        parts.push((l, j));
        surfaces.push(s);
        top -= hh;
        if i + 1 < n {
            b.add_box(
                [(x[0] + x[1]) / 2.0, c.cy(), top - div / 2.0],
                [x[1] - x[0], c.inner_d(), div],
                look.inner,
            )?;
            top -= div;
        }
    }
    Ok(())
}

/// Box cabinet with one hinged door on the front (+Y), an inner shelf and a plinth.
///
/// The door link's frame sits on the hinge line (front-left vertical edge); the door opens
/// outward for positive joint angles, up to 100 degrees.
fn cabinet(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let plinth = 0.06_f64.min(h * 0.1);
    let c = carcass(&mut b, w, d, h, plinth, FRONT, ctx.color, false)?;
    let mut surfaces = vec![c.top_surface(w, d, h, 1.0)];
    surfaces.extend(inner_shelves(&mut b, &c, c.z0, c.z1, 2, 0, ctx.color)?);
    let opening = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: c.z0,
        z1: c.z1,
    };
    let double = ctx.variant == "double" || (w > 0.9 && ctx.variant != "single");
    let mut parts = Vec::new();
    let ov = PANEL / 2.0 - 0.002;
    if double {
        parts.extend(door_pair(
            "body",
            opening,
            c.y_front,
            ov,
            FRONT,
            100f64.to_radians(),
            false,
            look(ctx),
        )?);
    } else {
        parts.push(door(
            "door",
            "body",
            opening,
            c.y_front,
            ov,
            FRONT,
            Hinge::Left,
            100f64.to_radians(),
            false,
            look(ctx),
        )?);
    }
    assemble(b, parts, surfaces)
}

/// Wardrobe: two tall hinged doors, a hanging rail and a hat shelf; drawers at the bottom in
/// the `drawers` variant.
fn wardrobe(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let c = carcass(&mut b, w, d, h, 0.08, FRONT, ctx.color, false)?;
    let shelf_z = c.z1 - 0.3;
    let mut surfaces = vec![c.top_surface(w, d, h, 0.5)];
    let sd = c.inner_d() - 0.01;
    b.add_box(
        [0.0, c.y_back + sd / 2.0, shelf_z],
        [c.inner_w() - 0.002, sd, PANEL],
        ctx.color,
    )?;
    surfaces.push(surface(
        "shelf_1",
        "body",
        [0.0, c.y_back + sd / 2.0, shelf_z + PANEL / 2.0],
        [c.inner_w() - 0.004, sd],
        c.z1 - shelf_z - PANEL / 2.0,
    ));
    b.add_rod(
        [c.x0, c.cy(), shelf_z - 0.08],
        [c.x1, c.cy(), shelf_z - 0.08],
        0.012,
        METAL,
    )?;
    surfaces.push(surface(
        "shelf_0",
        "body",
        [0.0, c.y_back + sd / 2.0, c.z0],
        [c.inner_w() - 0.004, sd],
        shelf_z - c.z0 - 0.2,
    ));
    let ov = PANEL / 2.0 - 0.002;
    let full = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: c.z0,
        z1: c.z1,
    };
    let parts = door_pair("body", full, c.y_front, ov, FRONT, 1.75, false, look(ctx))?.into();
    // Cornice detail across the top.
    b.add_detail(
        [0.0, c.y_front - 0.01, h - 0.01],
        [w, 0.02, 0.02],
        shade(ctx.color, 0.85),
    );
    assemble(b, parts, surfaces)
}

/// Chests of drawers: `dresser` (two columns of drawers, or three rows of full-width drawers
/// when narrow), `nightstand` (a drawer over an open shelf) and `filing` (a single column of
/// deep drawers).
fn dresser(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let plinth = if ctx.variant == "filing" {
        0.03
    } else {
        0.06_f64.min(h * 0.1)
    };
    let c = carcass(&mut b, w, d, h, plinth, FRONT, ctx.color, false)?;
    let mut parts = Vec::new();
    let mut surfaces = vec![c.top_surface(w, d, h, 1.0)];
    let lk = look(ctx);
    // Keep the top drawer front clear of the top panel's front edge.
    let z_hi = c.z1 - 0.006;
    match ctx.variant {
        "nightstand" => {
            let split = c.z1 - (c.z1 - c.z0) * 0.4;
            b.add_box(
                [0.0, c.cy(), split - PANEL / 2.0],
                [c.inner_w(), c.inner_d(), PANEL],
                ctx.color,
            )?;
            drawer_column(
                &mut b,
                &c,
                [c.x0, c.x1],
                [split, z_hi],
                1,
                0,
                lk,
                &mut parts,
                &mut surfaces,
            )?;
            surfaces.push(surface(
                "shelf_0",
                "body",
                [0.0, c.cy(), c.z0],
                [c.inner_w() - 0.004, c.inner_d() - 0.01],
                split - PANEL - c.z0,
            ));
        }
        "filing" => {
            let n = ((h / 0.33).round() as usize).clamp(2, 5);
            drawer_column(
                &mut b,
                &c,
                [c.x0, c.x1],
                [c.z0, z_hi],
                n,
                0,
                lk,
                &mut parts,
                &mut surfaces,
            )?;
        }
        _ => {
            let rows = ((h / 0.22).round() as usize).clamp(2, 6);
            if w > 1.0 {
                let mid = (c.x0 + c.x1) / 2.0;
                b.add_box(
                    [mid, c.cy(), (c.z0 + c.z1) / 2.0],
                    [PANEL, c.inner_d(), c.z1 - c.z0],
                    ctx.color,
                )?;
                drawer_column(
                    &mut b,
                    &c,
                    [c.x0, mid - PANEL / 2.0],
                    [c.z0, z_hi],
                    rows,
                    0,
                    lk,
                    &mut parts,
                    &mut surfaces,
                )?;
                drawer_column(
                    &mut b,
                    &c,
                    [mid + PANEL / 2.0, c.x1],
                    [c.z0, z_hi],
                    rows,
                    rows,
                    lk,
                    &mut parts,
                    &mut surfaces,
                )?;
            } else {
                drawer_column(
                    &mut b,
                    &c,
                    [c.x0, c.x1],
                    [c.z0, z_hi],
                    rows,
                    0,
                    lk,
                    &mut parts,
                    &mut surfaces,
                )?;
            }
        }
    }
    assemble(b, parts, surfaces)
}

/// Low wide cabinets: `sideboard` (doors across the front) and `tv_stand` (two doors around
/// an open media shelf).
fn sideboard(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let legs = 0.1_f64.min(h * 0.25);
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            let y = sy * (d / 2.0 - 0.05) - (FRONT + HANDLE) / 2.0;
            b.add_frustum(
                [sx * (w / 2.0 - 0.05), y, 0.0],
                [sx * (w / 2.0 - 0.05), y, legs],
                0.012,
                0.02,
                ctx.accent_color,
            )?;
        }
    }
    // Carcass floats on the legs: shift by building a box from `legs` up.
    let c = carcass(&mut b, w, d, h, legs, FRONT, ctx.color, true)?;
    let mut surfaces = vec![c.top_surface(w, d, h, 1.0)];
    let ov = PANEL / 2.0 - 0.002;
    let full = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: c.z0,
        z1: c.z1,
    };
    let mut parts = Vec::new();
    if ctx.variant == "tv_stand" {
        let third = c.inner_w() / 3.0;
        let xa = c.x0 + third;
        let xb = c.x1 - third;
        for x in [xa, xb] {
            b.add_box(
                [x, c.cy(), (c.z0 + c.z1) / 2.0],
                [PANEL, c.inner_d(), c.z1 - c.z0],
                ctx.color,
            )?;
        }
        parts.push(door(
            "door_left",
            "body",
            Opening {
                x1: xa - PANEL / 2.0,
                ..full
            },
            c.y_front,
            ov,
            FRONT,
            Hinge::Left,
            1.75,
            false,
            look(ctx),
        )?);
        parts.push(door(
            "door_right",
            "body",
            Opening {
                x0: xb + PANEL / 2.0,
                ..full
            },
            c.y_front,
            ov,
            FRONT,
            Hinge::Right,
            1.75,
            false,
            look(ctx),
        )?);
        let mid_shelf = (c.z0 + c.z1) / 2.0;
        let sd = c.inner_d() - 0.01;
        b.add_box(
            [0.0, c.y_back + sd / 2.0, mid_shelf],
            [xb - xa - PANEL, sd, PANEL],
            ctx.color,
        )?;
        surfaces.push(surface(
            "shelf_0",
            "body",
            [0.0, c.y_back + sd / 2.0, c.z0],
            [xb - xa - PANEL - 0.004, sd],
            mid_shelf - PANEL / 2.0 - c.z0,
        ));
        surfaces.push(surface(
            "shelf_1",
            "body",
            [0.0, c.y_back + sd / 2.0, mid_shelf + PANEL / 2.0],
            [xb - xa - PANEL - 0.004, sd],
            c.z1 - mid_shelf - PANEL / 2.0,
        ));
    } else {
        let n = ((w / 0.5).round() as usize).clamp(2, 4);
        let cw = c.inner_w() / n as f64;
        for i in 0..n {
            let x0 = c.x0 + cw * i as f64;
            let x1 = x0 + cw;
            if i > 0 {
                b.add_box(
                    [x0, c.cy(), (c.z0 + c.z1) / 2.0],
                    [PANEL, c.inner_d(), c.z1 - c.z0],
                    ctx.color,
                )?;
            }
            let o = Opening {
                x0: x0 + if i > 0 { PANEL / 2.0 } else { 0.0 },
                x1: x1 - if i + 1 < n { PANEL / 2.0 } else { 0.0 },
                ..full
            };
            let hinge = if i % 2 == 0 {
                Hinge::Left
            } else {
                Hinge::Right
            };
            // Neighbouring doors hinge on the same divider: stop before their handles meet.
            parts.push(door(
                &format!("door_{i}"),
                "body",
                o,
                c.y_front,
                ov,
                FRONT,
                hinge,
                1.45,
                false,
                look(ctx),
            )?);
        }
        surfaces.push(surface(
            "shelf_0",
            "body",
            [0.0, c.cy(), c.z0],
            [c.inner_w() - 0.05, c.inner_d() - 0.01],
            c.z1 - c.z0,
        ));
    }
    assemble(b, parts, surfaces)
}

/// Metal locker: one tall door with vent slots, a hat shelf.
fn locker(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.shell(Some(0.0015));
    let c = carcass(&mut b, w, d, h, 0.05, FRONT, ctx.color, false)?;
    b.shell(None);
    let shelf_z = c.z1 - 0.3;
    let sd = c.inner_d() - 0.01;
    b.add_box(
        [0.0, c.y_back + sd / 2.0, shelf_z],
        [c.inner_w() - 0.002, sd, PANEL],
        ctx.color,
    )?;
    let surfaces = vec![
        surface(
            "shelf_0",
            "body",
            [0.0, c.y_back + sd / 2.0, c.z0],
            [c.inner_w() - 0.004, sd],
            shelf_z - c.z0 - PANEL / 2.0,
        ),
        surface(
            "shelf_1",
            "body",
            [0.0, c.y_back + sd / 2.0, shelf_z + PANEL / 2.0],
            [c.inner_w() - 0.004, sd],
            c.z1 - shelf_z - PANEL / 2.0,
        ),
        c.top_surface(w, d, h, 0.5),
    ];
    let o = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: c.z0,
        z1: c.z1,
    };
    let (mut link, joint) = door(
        "door",
        "body",
        o,
        c.y_front,
        PANEL / 2.0 - 0.002,
        FRONT,
        Hinge::Left,
        1.75,
        false,
        look(ctx),
    )?;
    // Vent slots near the top of the door (visual).
    let dw = o.x1 - o.x0;
    for k in 0..4 {
        let z = o.height() - 0.08 - k as f64 * 0.03;
        link.visuals.push(crate::assets::VisualPart {
            name: format!("vent_{k}"),
            mesh: crate::geometry::mesh::box_mesh(
                [dw / 2.0, FRONT + 0.001, z],
                [dw * 0.6, 0.002, 0.01],
            ),
            color: [0.05, 0.05, 0.05, 1.0],
            texture: None,
        });
    }
    assemble(b, vec![(link, joint)], surfaces)
}

/// Display case: glass doors in a frame, glass shelves, a lit cabinet base.
fn display_case(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let c = carcass(&mut b, w, d, h, 0.1, FRONT, ctx.color, false)?;
    let mut surfaces = vec![c.top_surface(w, d, h, 0.4)];
    let n = ((c.z1 - c.z0) / 0.35).floor().clamp(1.0, 6.0) as usize;
    surfaces.extend(inner_shelves(
        &mut b,
        &c,
        c.z0,
        c.z1,
        n,
        0,
        [0.7, 0.8, 0.85],
    )?);
    let ov = PANEL / 2.0 - 0.002;
    let full = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: c.z0,
        z1: c.z1,
    };
    let mut lk = look(ctx);
    lk.front = ctx.color;
    let parts = if w > 0.7 {
        door_pair("body", full, c.y_front, ov, FRONT, 1.6, true, lk)?.into()
    } else {
        vec![door(
            "door",
            "body",
            full,
            c.y_front,
            ov,
            FRONT,
            Hinge::Left,
            1.6,
            true,
            lk,
        )?]
    };
    assemble(b, parts, surfaces)
}

/// Chest / trunk / toy box: an open box with a lid hinged at the back.
fn chest(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let t = 0.02;
    let lid_t = 0.025;
    let bh = h - lid_t - 0.002;
    b.add_box([0.0, 0.0, t / 2.0], [w, d, t], ctx.color)?;
    for sy in [-1.0, 1.0] {
        b.add_box(
            [0.0, sy * (d / 2.0 - t / 2.0), bh / 2.0 + t / 2.0],
            [w, t, bh - t],
            ctx.color,
        )?;
    }
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - t / 2.0), 0.0, bh / 2.0 + t / 2.0],
            [t, d - 2.0 * t, bh - t],
            shade(ctx.color, 0.95),
        )?;
    }
    // Corner straps.
    for sx in [-1.0, 1.0] {
        b.add_detail(
            [sx * (w / 2.0 - 0.06), d / 2.0 + 0.001, bh / 2.0],
            [0.03, 0.002, bh],
            ctx.accent_color,
        );
    }
    let mut lk = look(ctx);
    lk.front = shade(ctx.color, 0.9);
    let (lid_link, lid_joint) = lid(
        "lid",
        "body",
        [-w / 2.0, w / 2.0],
        [-d / 2.0, d / 2.0],
        bh,
        lid_t,
        1.5,
        lk,
    )?;
    let surfaces = vec![surface(
        "inside",
        "body",
        [0.0, 0.0, t],
        [w - 2.0 * t, d - 2.0 * t],
        bh - t,
    )];
    assemble(b, vec![(lid_link, lid_joint)], surfaces)
}
