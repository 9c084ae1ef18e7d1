//! Tables, desks and counters: dining / coffee / side / round / bar / conference / console
//! tables, workbenches and display pedestals, desks with a drawer pedestal, reception desks
//! and shop or bar counters.

use super::parts::{BLACK, LegShape, METAL, apron, body, four_legs, shade, single, surface};
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::articulated::parts::{Look, Opening, drawer};
use crate::geometry::GeometryError;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] =
    &[("table", table), ("desk", desk), ("counter", counter)];

/// Four-legged and pedestal tables, by variant.
fn table(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    match ctx.variant {
        "round" | "bar" => return round_table(ctx),
        "conference" => return conference_table(ctx),
        "pedestal" => return pedestal(ctx),
        _ => {}
    }
    let [w, d, h] = ctx.size;
    let thick_top = ctx.variant == "workbench";
    let top_t = if thick_top {
        0.05
    } else {
        (0.028 + 0.012 * ctx.uniform(0.0, 1.0)).min(h * 0.1)
    };
    let leg = (0.035 + 0.02 * (w.max(d) / 2.0).min(1.0)).min(w.min(d) * 0.15);
    let inset = if ctx.variant == "console" { 0.01 } else { 0.03 };
    let shape = LegShape::for_style(ctx, LegShape::Square);
    let mut b = body(ctx);
    b.add_box([0.0, 0.0, h - top_t / 2.0], [w, d, top_t], ctx.color)?;
    let leg_color = if thick_top {
        ctx.accent_color
    } else {
        shade(ctx.color, 0.85)
    };
    b.density(ctx.accent.density);
    four_legs(
        &mut b,
        w,
        d,
        0.0,
        0.0,
        h - top_t,
        leg,
        inset,
        shape,
        leg_color,
    )?;
    b.material_density();
    let apron_h = (h * 0.1).clamp(0.04, 0.09);
    if shape == LegShape::Square && h > 0.6 {
        let inner = 2.0 * (inset + leg);
        apron(
            &mut b,
            w - inner + 0.02,
            d - inner + 0.02,
            h - top_t,
            apron_h,
            0.02,
            shade(ctx.color, 0.9),
        )?;
    }
    let mut surfaces = vec![surface("top", "body", [0.0, 0.0, h], [w, d], 1.0)];
    // Coffee, side, console tables and workbenches have a lower shelf.
    if matches!(ctx.variant, "coffee" | "side" | "console" | "workbench") {
        let z = (h * 0.2).max(0.06);
        let sw = w - 2.0 * inset - 2.0 * leg - 0.004;
        let sd = d - 2.0 * inset - 0.004;
        let st = 0.018;
        b.add_box([0.0, 0.0, z], [sw, sd, st], shade(ctx.color, 0.95))?;
        surfaces.push(surface(
            "shelf_0",
            "body",
            [0.0, 0.0, z + st / 2.0],
            [sw, sd],
            h - top_t
                - z
                - st / 2.0
                - (if shape == LegShape::Square {
                    apron_h
                } else {
                    0.0
                }),
        ));
    }
    single(b.finish()?, surfaces)
}

/// Round top on a central column and a weighted base (round and bar tables).
fn round_table(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let r = w.min(d) / 2.0;
    let top_t = 0.03;
    let mut b = body(ctx);
    b.add_cylinder([0.0, 0.0], r, h - top_t, h, ctx.color)?;
    let col_r = (r * 0.09).clamp(0.03, 0.06);
    let base_r = (r * 0.6).clamp(0.2, 0.4).min(r);
    let dark = ctx.accent_color;
    b.add_frustum(
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.04],
        base_r,
        base_r * 0.9,
        dark,
    )?;
    b.add_rod([0.0, 0.0, 0.04], [0.0, 0.0, h - top_t], col_r, dark)?;
    b.add_frustum(
        [0.0, 0.0, h - top_t - 0.08],
        [0.0, 0.0, h - top_t],
        col_r,
        r * 0.35,
        dark,
    )?;
    if ctx.variant == "bar" {
        // Foot ring.
        let fr = base_r * 0.9;
        let z = 0.28;
        let n = 8;
        let pts: Vec<[f64; 3]> = (0..=n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                [fr * a.cos(), fr * a.sin(), z]
            })
            .collect();
        b.add_tube(&pts, 0.01, METAL)?;
        for i in 0..4 {
            let a = std::f64::consts::TAU * i as f64 / 4.0;
            b.add_rod([0.0, 0.0, z], [fr * a.cos(), fr * a.sin(), z], 0.008, METAL)?;
        }
    }
    let side = r * std::f64::consts::SQRT_2;
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [side, side], 1.0)],
    )
}

/// Long table on two panel legs joined by a modesty panel.
fn conference_table(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let top_t = 0.04;
    let mut b = body(ctx);
    // Top with rounded ends: a central box and two half-discs.
    let r = d / 2.0;
    b.add_box([0.0, 0.0, h - top_t / 2.0], [w - d, d, top_t], ctx.color)?;
    for sx in [-1.0, 1.0] {
        b.add_cylinder([sx * (w / 2.0 - r), 0.0], r, h - top_t, h, ctx.color)?;
    }
    let leg_t = 0.05;
    let leg_d = d * 0.6;
    let dark = ctx.accent_color;
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - d * 0.7);
        b.add_box(
            [x, 0.0, (h - top_t) / 2.0 + 0.02],
            [leg_t, leg_d, h - top_t - 0.04],
            dark,
        )?;
        b.add_box([x, 0.0, 0.01], [leg_t * 2.0, leg_d * 1.2, 0.02], dark)?;
    }
    b.add_box(
        [0.0, 0.0, h - top_t - 0.15],
        [w - d * 1.4 - leg_t, 0.02, 0.25],
        dark,
    )?;
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, 0.0, h],
            [w - d * 0.3, d * 0.9],
            1.0,
        )],
    )
}

/// A display pedestal: a plinth, a column and a cap with a flat top.
fn pedestal(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.add_box([0.0, 0.0, 0.04], [w, d, 0.08], shade(ctx.color, 0.9))?;
    b.add_box([0.0, 0.0, h / 2.0], [w * 0.8, d * 0.8, h - 0.16], ctx.color)?;
    b.add_box([0.0, 0.0, h - 0.04], [w, d, 0.08], shade(ctx.color, 0.9))?;
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [w, d], 1.0)],
    )
}

/// Desks: an office desk with a drawer pedestal (articulated), a student desk on a metal
/// frame, or a reception desk with a raised front counter.
fn desk(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    match ctx.variant {
        "reception" => return reception_desk(ctx),
        "student" => return student_desk(ctx),
        _ => {}
    }
    let [w, d, h] = ctx.size;
    let top_t = 0.03;
    let panel = 0.02;
    let mut b = body(ctx);
    b.add_box([0.0, 0.0, h - top_t / 2.0], [w, d, top_t], ctx.color)?;
    // Left panel leg.
    b.add_box(
        [-w / 2.0 + panel / 2.0, 0.0, (h - top_t) / 2.0],
        [panel, d, h - top_t],
        shade(ctx.color, 0.9),
    )?;
    // Modesty panel at the back.
    b.add_box(
        [0.0, -d / 2.0 + 0.03, h - top_t - 0.2],
        [w - 2.0 * panel, 0.015, 0.36],
        shade(ctx.color, 0.85),
    )?;
    // Right pedestal carcass: sides, bottom, back, dividers; three drawer openings.
    let pw = (w * 0.3).clamp(0.35, 0.45);
    let x_r = w / 2.0;
    let x_l = x_r - pw;
    // Drawer fronts and handles stay under the top.
    let y_front = d / 2.0 - 0.04 - 0.018 - 0.002;
    let y_back = -d / 2.0 + 0.05;
    let cd = y_front - y_back;
    let cy = (y_front + y_back) / 2.0;
    let z_bottom = 0.06;
    let z_top = h - top_t;
    let carcass = shade(ctx.color, 0.9);
    for x in [x_l + panel / 2.0, x_r - panel / 2.0] {
        b.add_box([x, cy, z_top / 2.0], [panel, cd, z_top], carcass)?;
    }
    let inner_x0 = x_l + panel;
    let inner_x1 = x_r - panel;
    let iw = inner_x1 - inner_x0;
    let ix = (inner_x0 + inner_x1) / 2.0;
    b.add_box([ix, cy, z_bottom - panel / 2.0], [iw, cd, panel], carcass)?;
    b.add_box(
        [ix, y_front - 0.03, z_bottom / 2.0 - panel / 2.0],
        [iw, panel, z_bottom - panel],
        shade(carcass, 0.8),
    )?;
    b.add_box(
        [ix, y_back + 0.005, (z_bottom + z_top) / 2.0],
        [iw, 0.01, z_top - z_bottom],
        carcass,
    )?;
    let n = 3;
    let div = 0.016;
    // The top drawer's front stays clear of the desk top above it.
    let z_open = z_top - 0.012;
    b.add_box([ix, cy, z_top - 0.006], [iw, cd, 0.012], carcass)?;
    let avail = z_open - z_bottom - (n as f64 - 1.0) * div;
    let heights = [avail * 0.28, avail * 0.32, avail * 0.40];
    let mut openings = Vec::new();
    let mut z = z_open;
    for (i, hh) in heights.iter().enumerate() {
        let o = Opening {
            x0: inner_x0,
            x1: inner_x1,
            z0: z - hh,
            z1: z,
        };
        openings.push(o);
        z -= hh;
        if i + 1 < n {
            b.add_box([ix, cy, z - div / 2.0], [iw, cd, div], carcass)?;
            z -= div;
        }
    }
    let look = Look {
        material: ctx.material,
        front: ctx.color,
        inner: shade(ctx.color, 0.75),
        handle: ctx.accent_color,
    };
    let mut links = vec![];
    let mut joints = vec![];
    let mut surfaces = vec![surface("top", "body", [0.0, 0.0, h], [w, d], 1.0)];
    let drawer_depth = cd - 0.04;
    let mut drawer_links = Vec::new();
    for (i, o) in openings.iter().enumerate() {
        let (l, j, s) = drawer(
            &format!("drawer_{i}"),
            "body",
            *o,
            y_front,
            drawer_depth,
            div / 2.0 - 0.0015,
            look,
        )?;
        drawer_links.push(l);
        joints.push(j);
        surfaces.push(s);
    }
    links.push(b.finish()?);
    links.extend(drawer_links);
    Ok(Generated {
        links,
        joints,
        surfaces,
    })
}

/// Student desk: a top on a tubular metal frame with a book shelf under the top.
fn student_desk(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let top_t = 0.025;
    let mut b = body(ctx);
    b.add_box([0.0, 0.0, h - top_t / 2.0], [w, d, top_t], ctx.color)?;
    four_legs(
        &mut b,
        w,
        d,
        0.0,
        0.0,
        h - top_t,
        0.03,
        0.02,
        LegShape::Round,
        ctx.accent_color,
    )?;
    for sx in [-1.0, 1.0] {
        b.add_rod(
            [sx * (w / 2.0 - 0.035), -d / 2.0 + 0.035, 0.12],
            [sx * (w / 2.0 - 0.035), d / 2.0 - 0.035, 0.12],
            0.01,
            ctx.accent_color,
        )?;
    }
    let sz = h - top_t - 0.12;
    b.add_box([0.0, -0.03, sz], [w - 0.1, d - 0.12, 0.012], BLACK)?;
    single(
        b.finish()?,
        vec![
            surface("top", "body", [0.0, 0.0, h], [w, d], 1.0),
            surface(
                "shelf_0",
                "body",
                [0.0, -0.03, sz + 0.006],
                [w - 0.1, d - 0.12],
                0.1,
            ),
        ],
    )
}

/// Reception desk: a work top behind a raised front panel with a transaction ledge; +Y is
/// the visitors' side.
fn reception_desk(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let work_h = 0.75;
    let t = 0.03;
    let mut b = body(ctx);
    let front_y = d / 2.0 - 0.25;
    // Front panel and ledge.
    b.add_box(
        [0.0, front_y + 0.02, (h - t) / 2.0],
        [w, 0.04, h - t],
        ctx.color,
    )?;
    b.add_box(
        [0.0, d / 2.0 - 0.14, h - t / 2.0],
        [w, 0.28, t],
        ctx.accent_color,
    )?;
    // Side panels.
    for sx in [-1.0, 1.0] {
        b.add_box(
            [
                sx * (w / 2.0 - 0.02),
                (front_y - d / 2.0) / 2.0,
                work_h / 2.0,
            ],
            [0.04, front_y + d / 2.0, work_h],
            shade(ctx.color, 0.9),
        )?;
    }
    // Work top behind the panel.
    let wd = front_y + d / 2.0;
    b.add_box(
        [0.0, -d / 2.0 + wd / 2.0, work_h - t / 2.0],
        [w - 0.08, wd, t],
        shade(ctx.color, 1.1),
    )?;
    // Kick plate along the bottom of the front panel.
    b.add_box(
        [0.0, front_y + 0.05, 0.05],
        [w - 0.02, 0.02, 0.1],
        shade(ctx.color, 0.6),
    )?;
    single(
        b.finish()?,
        vec![
            surface(
                "top",
                "body",
                [0.0, -d / 2.0 + wd / 2.0, work_h],
                [w - 0.08, wd],
                h - work_h - 0.02,
            ),
            surface("ledge", "body", [0.0, d / 2.0 - 0.14, h], [w, 0.28], 1.0),
        ],
    )
}

/// Shop, bar and checkout counters: a closed body with a top overhanging the front; the bar
/// variant adds a foot rail.
fn counter(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let t = 0.04;
    let overhang = if ctx.variant == "bar" { 0.2 } else { 0.05 };
    let mut b = body(ctx);
    b.shell(Some(0.02));
    let bd = d - overhang;
    b.add_box(
        [0.0, -d / 2.0 + bd / 2.0, (h - t) / 2.0 + 0.05],
        [w - 0.02, bd, h - t - 0.1],
        ctx.color,
    )?;
    b.shell(None);
    b.add_box(
        [0.0, -d / 2.0 + bd / 2.0 - 0.03, 0.05],
        [w - 0.06, bd - 0.06, 0.1],
        shade(ctx.color, 0.5),
    )?;
    b.add_box([0.0, 0.0, h - t / 2.0], [w, d, t], ctx.accent_color)?;
    // Panels on the front face.
    let n = ((w / 0.6).round() as usize).max(1);
    for i in 0..n {
        let x = -w / 2.0 + (i as f64 + 0.5) * w / n as f64;
        b.add_detail(
            [x, -d / 2.0 + bd + 0.003, h / 2.0],
            [w / n as f64 - 0.06, 0.006, h - t - 0.3],
            shade(ctx.color, 0.85),
        );
    }
    if ctx.variant == "bar" {
        let y = d / 2.0 - 0.03;
        b.add_rod(
            [-w / 2.0 + 0.05, y, 0.2],
            [w / 2.0 - 0.05, y, 0.2],
            0.02,
            ctx.accent_color,
        )?;
        let n = ((w / 1.0).ceil() as usize).max(2);
        for i in 0..=n {
            let x = -w / 2.0 + 0.05 + (w - 0.1) * i as f64 / n as f64;
            b.add_box(
                [x, (y + (-d / 2.0 + bd)) / 2.0, 0.2],
                [0.02, y - (-d / 2.0 + bd), 0.02],
                ctx.accent_color,
            )?;
        }
    }
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [w, d], 1.0)],
    )
}
