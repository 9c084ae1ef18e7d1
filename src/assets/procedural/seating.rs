//! Seating: dining / office / arm / rocking chairs, stools and bar stools, benches, sofas
//! (straight, loveseat, L-shaped, sectional), bean bags and ottomans. Every seat faces +Y.
//!
//! Upholstered parts weigh what foam and fabric weigh (about 60 kg/m^3 over the cushion
//! volume), not what solid fabric would.

use super::parts::{BLACK, LegShape, METAL, body, four_legs, shade, single, surface};
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::LinkBuilder;
use crate::geometry::GeometryError;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("chair", chair),
    ("office_chair", office_chair),
    ("armchair", armchair),
    ("stool", stool),
    ("bench", bench),
    ("sofa", sofa),
    ("rocking_chair", rocking_chair),
    ("bean_bag", bean_bag),
    ("ottoman", ottoman),
];

/// Effective density of upholstered parts (foam, fabric and a light frame), kg/m^3.
const UPHOLSTERY: f64 = 60.0;

/// Dining chair: legs, a seat at 45-50 % of the height, a backrest at the back (-Y).
fn chair(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let seat_h = (h * 0.5).clamp(0.4, 0.5);
    let seat_t = 0.04;
    let leg = 0.035;
    let back_t = 0.03;
    let shape = LegShape::for_style(ctx, LegShape::Square);
    let mut b = body(ctx);
    let leg_h = seat_h - seat_t;
    let legc = shade(ctx.color, 0.85);
    four_legs(&mut b, w, d, 0.0, 0.0, leg_h, leg, 0.0, shape, legc)?;
    // Stretchers between the legs make the chair read as a chair from any side.
    if shape == LegShape::Square {
        for sx in [-1.0, 1.0] {
            b.add_box(
                [sx * (w / 2.0 - leg / 2.0), 0.0, leg_h * 0.3],
                [0.015, d - 2.0 * leg, 0.02],
                legc,
            )?;
        }
    }
    b.add_box([0.0, 0.0, seat_h - seat_t / 2.0], [w, d, seat_t], ctx.color)?;
    let post_h = h - seat_h;
    let (lx, ly) = (w / 2.0 - leg / 2.0, d / 2.0 - back_t / 2.0);
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * lx, -ly, seat_h + post_h / 2.0],
            [leg, back_t, post_h],
            legc,
        )?;
    }
    let panel_h = post_h * 0.45;
    b.add_box(
        [0.0, -ly, h - panel_h / 2.0],
        [w - 2.0 * leg, back_t * 0.8, panel_h],
        ctx.color,
    )?;
    // A mid rail.
    b.add_box(
        [0.0, -ly, seat_h + post_h * 0.3],
        [w - 2.0 * leg, back_t * 0.6, 0.03],
        ctx.color,
    )?;
    let seat_depth = d - back_t;
    single(
        b.finish()?,
        vec![surface(
            "seat",
            "body",
            [0.0, back_t / 2.0, seat_h],
            [w - 2.0 * leg, seat_depth],
            0.4,
        )],
    )
}

/// Swivel office chair: five-star base on casters, gas column, seat, backrest, armrests.
fn office_chair(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let base_r = w.min(d) / 2.0 - 0.025;
    let caster = 0.025;
    let hub_z = 0.1;
    for i in 0..5 {
        let a = std::f64::consts::TAU * i as f64 / 5.0 + std::f64::consts::FRAC_PI_2;
        let (cx, cy) = (base_r * a.cos(), base_r * a.sin());
        b.add_rod([0.0, 0.0, hub_z], [cx, cy, 0.07], 0.018, BLACK)?;
        b.add_ellipsoid([cx, cy, caster], [caster, caster * 0.8, caster], BLACK)?;
    }
    let seat_z = (h * 0.45).clamp(0.42, 0.52);
    b.add_rod(
        [0.0, 0.0, hub_z - 0.02],
        [0.0, 0.0, seat_z - 0.08],
        0.025,
        METAL,
    )?;
    b.add_box([0.0, 0.0, seat_z - 0.09], [0.2, 0.2, 0.03], BLACK)?;
    let sw = w * 0.75;
    let sd = d * 0.72;
    b.density(UPHOLSTERY);
    b.add_rounded_box([0.0, 0.02, seat_z - 0.04], [sw, sd, 0.08], 0.03, ctx.color)?;
    let back_h = h - seat_z - 0.1;
    b.add_rounded_box(
        [0.0, -d / 2.0 + 0.06, h - back_h / 2.0],
        [sw * 0.95, 0.07, back_h],
        0.03,
        ctx.color,
    )?;
    b.material_density();
    b.add_box(
        [0.0, -d / 2.0 + 0.1, seat_z + 0.03],
        [0.06, 0.14, 0.03],
        BLACK,
    )?;
    b.add_box(
        [0.0, -d / 2.0 + 0.1, seat_z + 0.08],
        [0.06, 0.02, 0.12],
        BLACK,
    )?;
    for sx in [-1.0, 1.0] {
        let x = sx * (sw / 2.0 + 0.02);
        b.add_box([x, 0.02, seat_z + 0.1], [0.025, 0.025, 0.2], BLACK)?;
        b.add_box([x, 0.02, seat_z + 0.21], [0.06, 0.24, 0.025], BLACK)?;
    }
    single(
        b.finish()?,
        vec![surface(
            "seat",
            "body",
            [0.0, 0.02, seat_z],
            [sw * 0.9, sd * 0.9],
            0.35,
        )],
    )
}

/// Upholstered arm chair: base, seat cushion, back cushion, two arms, short legs.
fn armchair(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let leg_h = 0.1;
    four_legs(
        &mut b,
        w,
        d,
        0.0,
        0.0,
        leg_h,
        0.04,
        0.05,
        LegShape::Tapered,
        ctx.accent_color,
    )?;
    let arm_w = (w * 0.16).clamp(0.1, 0.2);
    let back_d = (d * 0.2).clamp(0.14, 0.22);
    b.density(UPHOLSTERY);
    let seat_top = (h * 0.48).clamp(0.4, 0.48);
    b.add_rounded_box(
        [0.0, 0.0, (leg_h + seat_top - 0.12) / 2.0],
        [w, d, seat_top - 0.12 - leg_h],
        0.03,
        shade(ctx.color, 0.9),
    )?;
    let iw = w - 2.0 * arm_w;
    b.add_rounded_box(
        [0.0, back_d / 2.0, seat_top - 0.06],
        [iw - 0.01, d - back_d - 0.01, 0.12],
        0.04,
        ctx.color,
    )?;
    let arm_h = (h * 0.72).min(h - 0.05);
    for sx in [-1.0, 1.0] {
        b.add_rounded_box(
            [
                sx * (w / 2.0 - arm_w / 2.0),
                0.0,
                (seat_top - 0.12 + arm_h) / 2.0,
            ],
            [arm_w, d, arm_h - seat_top + 0.12],
            0.04,
            ctx.color,
        )?;
    }
    b.add_rounded_box(
        [0.0, -d / 2.0 + back_d / 2.0, (seat_top - 0.12 + h) / 2.0],
        [iw - 0.01, back_d, h - seat_top + 0.12],
        0.05,
        ctx.color,
    )?;
    single(
        b.finish()?,
        vec![surface(
            "seat",
            "body",
            [0.0, back_d / 2.0, seat_top],
            [iw - 0.05, d - back_d - 0.05],
            0.5,
        )],
    )
}

/// Stools: a round seat on splayed legs with a foot ring; `bar` variant is taller.
fn stool(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let r = w.min(d) / 2.0;
    let mut b = body(ctx);
    let seat_t = 0.04;
    b.add_cylinder([0.0, 0.0], r * 0.98, h - seat_t, h, ctx.color)?;
    let legc = if ctx.variant == "bar" {
        ctx.accent_color
    } else {
        shade(ctx.color, 0.85)
    };
    let leg_r = 0.014;
    let top_r = r * 0.55;
    let foot_r = r - leg_r;
    for i in 0..4 {
        let a = std::f64::consts::TAU * i as f64 / 4.0;
        b.add_leg(
            [top_r * a.cos(), top_r * a.sin(), h - seat_t],
            [foot_r * a.cos(), foot_r * a.sin()],
            leg_r,
            legc,
        )?;
    }
    let ring_z = h * if ctx.variant == "bar" { 0.35 } else { 0.3 };
    let t = ring_z / (h - seat_t);
    let ring_r = foot_r + (top_r - foot_r) * t;
    let n = 8;
    let pts: Vec<[f64; 3]> = (0..=n)
        .map(|i| {
            let a = std::f64::consts::TAU * (i as f64 + 0.5) / n as f64;
            [ring_r * a.cos(), ring_r * a.sin(), ring_z]
        })
        .collect();
    b.add_tube(&pts, 0.009, legc)?;
    single(
        b.finish()?,
        vec![surface(
            "seat",
            "body",
            [0.0, 0.0, h],
            [r * 1.2, r * 1.2],
            0.4,
        )],
    )
}

/// Bench: a slatted seat on two frames; the `backed` variant adds a backrest.
fn bench(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let backed = ctx.variant == "backed";
    let seat_h = if backed {
        (h * 0.5).clamp(0.4, 0.48)
    } else {
        h
    };
    let seat_d = if backed { d - 0.06 } else { d };
    let seat_y = if backed { 0.03 } else { 0.0 };
    let slats = 4;
    let gap = 0.01;
    let sd = (seat_d - gap * (slats as f64 - 1.0)) / slats as f64;
    for i in 0..slats {
        let y = seat_y - seat_d / 2.0 + sd / 2.0 + i as f64 * (sd + gap);
        b.add_box([0.0, y, seat_h - 0.02], [w, sd, 0.04], ctx.color)?;
    }
    let legc = ctx.accent_color;
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - 0.12);
        for sy in [-1.0, 1.0] {
            b.add_box(
                [
                    x,
                    seat_y + sy * (seat_d / 2.0 - 0.04),
                    (seat_h - 0.04) / 2.0,
                ],
                [0.05, 0.05, seat_h - 0.04],
                legc,
            )?;
        }
        b.add_box(
            [x, seat_y, seat_h - 0.06],
            [0.05, seat_d - 0.04, 0.04],
            legc,
        )?;
        b.add_box([x, seat_y, 0.12], [0.04, seat_d - 0.1, 0.03], legc)?;
    }
    if backed {
        for sx in [-1.0, 1.0] {
            b.add_box(
                [sx * (w / 2.0 - 0.12), -d / 2.0 + 0.02, (seat_h + h) / 2.0],
                [0.05, 0.04, h - seat_h],
                legc,
            )?;
        }
        for k in 0..2 {
            let z = h - 0.06 - k as f64 * 0.14;
            b.add_box([0.0, -d / 2.0 + 0.02, z], [w, 0.03, 0.1], ctx.color)?;
        }
    }
    single(
        b.finish()?,
        vec![surface(
            "seat",
            "body",
            [0.0, seat_y, seat_h],
            [w, seat_d],
            0.4,
        )],
    )
}

/// Upholstered sofa module geometry along x from `x0` to `x1`, depth along -y from `y_back`.
#[allow(clippy::too_many_arguments)]
fn sofa_run(
    b: &mut LinkBuilder,
    ctx: &GenContext,
    x0: f64,
    x1: f64,
    y_back: f64,
    depth: f64,
    seat_top: f64,
    h: f64,
    seats: usize,
) -> Result<(), GeometryError> {
    let back_d = 0.2;
    let base_top = seat_top - 0.14;
    let w = x1 - x0;
    let xc = (x0 + x1) / 2.0;
    b.add_rounded_box(
        [xc, y_back + depth / 2.0, (0.08 + base_top) / 2.0],
        [w, depth, base_top - 0.08],
        0.02,
        shade(ctx.color, 0.9),
    )?;
    b.add_rounded_box(
        [xc, y_back + back_d / 2.0, (base_top + h) / 2.0],
        [w, back_d, h - base_top],
        0.05,
        ctx.color,
    )?;
    let cw = w / seats as f64;
    for i in 0..seats {
        let cx = x0 + cw * (i as f64 + 0.5);
        b.add_rounded_box(
            [
                cx,
                y_back + back_d + (depth - back_d) / 2.0,
                base_top + 0.07,
            ],
            [cw - 0.01, depth - back_d - 0.01, 0.14],
            0.04,
            ctx.color,
        )?;
    }
    Ok(())
}

/// Sofas: straight (3 seats), `loveseat` (2), `l_shaped` (chaise on the right, toward +Y),
/// `sectional` (U: wings on both sides).
fn sofa(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let seat_top = (h * 0.52).clamp(0.4, 0.48);
    let arm_w = 0.18;
    let depth = match ctx.variant {
        "l_shaped" | "sectional" => 0.9_f64.min(d * 0.55),
        _ => d,
    };
    let y_back = -d / 2.0;
    let legs_y = [y_back + 0.06, y_back + depth - 0.06];
    for x in [-w / 2.0 + 0.08, w / 2.0 - 0.08] {
        for y in legs_y {
            b.add_frustum([x, y, 0.0], [x, y, 0.08], 0.015, 0.022, ctx.accent_color)?;
        }
    }
    b.density(UPHOLSTERY);
    let mut surfaces = Vec::new();
    match ctx.variant {
        "l_shaped" => {
            // Main run on the left, chaise on the right reaching to the front.
            let chaise_w = (w * 0.35).clamp(0.7, 1.0);
            let x_split = w / 2.0 - chaise_w;
            sofa_run(
                &mut b,
                ctx,
                -w / 2.0 + arm_w,
                x_split,
                y_back,
                depth,
                seat_top,
                h,
                2,
            )?;
            arm(&mut b, ctx, -w / 2.0 + arm_w / 2.0, y_back, depth, seat_top)?;
            chaise(&mut b, ctx, x_split, w / 2.0, y_back, d, seat_top, h)?;
            for (x, y) in [
                (w / 2.0 - 0.08, d / 2.0 - 0.06),
                (x_split + 0.08, d / 2.0 - 0.06),
            ] {
                b.material_density();
                b.add_frustum([x, y, 0.0], [x, y, 0.08], 0.015, 0.022, ctx.accent_color)?;
                b.density(UPHOLSTERY);
            }
            surfaces.push(surface(
                "seat",
                "body",
                [
                    (-w / 2.0 + arm_w + x_split) / 2.0,
                    y_back + 0.2 + (depth - 0.2) / 2.0,
                    seat_top,
                ],
                [x_split + w / 2.0 - arm_w, depth - 0.2],
                0.4,
            ));
            surfaces.push(surface(
                "chaise",
                "body",
                [
                    x_split + chaise_w / 2.0,
                    (y_back + 0.2 + d / 2.0) / 2.0,
                    seat_top,
                ],
                [chaise_w - 0.05, d - 0.2],
                0.4,
            ));
        }
        "sectional" => {
            let wing_w = 0.85_f64.min(w * 0.3);
            chaise(
                &mut b,
                ctx,
                -w / 2.0,
                -w / 2.0 + wing_w,
                y_back,
                d,
                seat_top,
                h,
            )?;
            chaise(
                &mut b,
                ctx,
                w / 2.0 - wing_w,
                w / 2.0,
                y_back,
                d,
                seat_top,
                h,
            )?;
            sofa_run(
                &mut b,
                ctx,
                -w / 2.0 + wing_w,
                w / 2.0 - wing_w,
                y_back,
                depth,
                seat_top,
                h,
                2,
            )?;
            b.material_density();
            for x in [
                -w / 2.0 + 0.08,
                w / 2.0 - 0.08,
                -w / 2.0 + wing_w - 0.08,
                w / 2.0 - wing_w + 0.08,
            ] {
                b.add_frustum(
                    [x, d / 2.0 - 0.06, 0.0],
                    [x, d / 2.0 - 0.06, 0.08],
                    0.015,
                    0.022,
                    ctx.accent_color,
                )?;
            }
            surfaces.push(surface(
                "seat",
                "body",
                [0.0, y_back + 0.2 + (depth - 0.2) / 2.0, seat_top],
                [w - 2.0 * wing_w, depth - 0.2],
                0.4,
            ));
        }
        _ => {
            let seats = if ctx.variant == "loveseat" || w < 1.6 {
                2
            } else {
                3
            };
            sofa_run(
                &mut b,
                ctx,
                -w / 2.0 + arm_w,
                w / 2.0 - arm_w,
                y_back,
                depth,
                seat_top,
                h,
                seats,
            )?;
            for x in [-w / 2.0 + arm_w / 2.0, w / 2.0 - arm_w / 2.0] {
                arm(&mut b, ctx, x, y_back, depth, seat_top)?;
            }
            surfaces.push(surface(
                "seat",
                "body",
                [0.0, y_back + 0.2 + (depth - 0.2) / 2.0, seat_top],
                [w - 2.0 * arm_w, depth - 0.2],
                0.4,
            ));
        }
    }
    single(b.finish()?, surfaces)
}

/// A sofa arm centred at `x`, from the back to the front of the seat depth.
fn arm(
    b: &mut LinkBuilder,
    ctx: &GenContext,
    x: f64,
    y_back: f64,
    depth: f64,
    seat_top: f64,
) -> Result<(), GeometryError> {
    let top = seat_top + 0.2;
    b.add_rounded_box(
        [x, y_back + depth / 2.0, (0.08 + top) / 2.0],
        [0.18, depth, top - 0.08],
        0.05,
        ctx.color,
    )?;
    Ok(())
}

/// A wing of an L or U sofa: seat reaching from the back to the front (`y_back + d`), with a
/// back along its rear and an outer arm.
#[allow(clippy::too_many_arguments)]
fn chaise(
    b: &mut LinkBuilder,
    ctx: &GenContext,
    x0: f64,
    x1: f64,
    y_back: f64,
    d: f64,
    seat_top: f64,
    h: f64,
) -> Result<(), GeometryError> {
    let w = x1 - x0;
    let xc = (x0 + x1) / 2.0;
    let base_top = seat_top - 0.14;
    b.add_rounded_box(
        [xc, y_back + d / 2.0, (0.08 + base_top) / 2.0],
        [w, d, base_top - 0.08],
        0.02,
        shade(ctx.color, 0.9),
    )?;
    b.add_rounded_box(
        [xc, y_back + 0.1, (base_top + h) / 2.0],
        [w, 0.2, h - base_top],
        0.05,
        ctx.color,
    )?;
    b.add_rounded_box(
        [xc, y_back + 0.2 + (d - 0.2) / 2.0, base_top + 0.07],
        [w - 0.01, d - 0.21, 0.14],
        0.04,
        ctx.color,
    )?;
    Ok(())
}

/// Rocking chair: a slatted chair on two curved rockers.
fn rocking_chair(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let rocker_h = 0.1;
    let legc = shade(ctx.color, 0.85);
    // Rockers: flat in the middle (so the chair rests level), curving up at both ends.
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - 0.025);
        let n = 8;
        let pts: Vec<[f64; 3]> = (0..=n)
            .map(|i| {
                let t = i as f64 / n as f64 * 2.0 - 1.0;
                let y = t * (d / 2.0 - 0.02);
                let u = ((t.abs() - 0.5).max(0.0) / 0.5).powi(2);
                [x, y, 0.02 + 0.06 * u]
            })
            .collect();
        b.add_tube(&pts, 0.02, legc)?;
    }
    let seat_h = (h * 0.42).clamp(0.38, 0.46);
    let seat_d = d * 0.6;
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            let (x, y) = (sx * (w / 2.0 - 0.025), sy * seat_d / 2.0);
            b.add_box(
                [x, y, (rocker_h + seat_h) / 2.0 - 0.01],
                [0.035, 0.035, seat_h - rocker_h + 0.02],
                legc,
            )?;
        }
    }
    b.add_box([0.0, 0.0, seat_h], [w, seat_d + 0.04, 0.04], ctx.color)?;
    // Tall back, leaning slightly.
    let back_y = -seat_d / 2.0;
    for sx in [-1.0, 1.0] {
        b.add_rod(
            [sx * (w / 2.0 - 0.025), back_y, seat_h],
            [sx * (w / 2.0 - 0.025), back_y - 0.08, h - 0.02],
            0.018,
            legc,
        )?;
    }
    for k in 0..5 {
        let x = -w / 2.0 + 0.08 + k as f64 * (w - 0.16) / 4.0;
        b.add_rod(
            [x, back_y - 0.01, seat_h + 0.05],
            [x, back_y - 0.075, h - 0.08],
            0.01,
            ctx.color,
        )?;
    }
    b.add_box(
        [0.0, back_y - 0.075, h - 0.04],
        [w - 0.02, 0.04, 0.07],
        ctx.color,
    )?;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - 0.025), 0.0, seat_h + 0.22],
            [0.05, seat_d, 0.03],
            legc,
        )?;
        b.add_box(
            [sx * (w / 2.0 - 0.025), seat_d / 2.0 - 0.02, seat_h + 0.11],
            [0.03, 0.03, 0.2],
            legc,
        )?;
    }
    single(
        b.finish()?,
        vec![surface(
            "seat",
            "body",
            [0.0, 0.0, seat_h + 0.02],
            [w - 0.1, seat_d],
            0.4,
        )],
    )
}

/// Bean bag: a squashed sack (flat where it sits on the floor) with a raised back.
fn bean_bag(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.density(UPHOLSTERY);
    let low = h * 0.55;
    b.add_rounded_box([0.0, 0.0, low / 2.0], [w, d, low], low * 0.45, ctx.color)?;
    b.add_ellipsoid(
        [0.0, -d * 0.22, h * 0.55],
        [w * 0.42, d * 0.26, h * 0.45],
        shade(ctx.color, 0.95),
    )?;
    single(
        b.finish()?,
        vec![surface(
            "seat",
            "body",
            [0.0, d * 0.12, low],
            [w * 0.5, d * 0.4],
            0.5,
        )],
    )
}

/// Ottoman / pouf: a padded block on short legs, or a round pouf (variant `pouf`).
fn ottoman(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    if ctx.variant == "pouf" {
        b.density(UPHOLSTERY);
        let r = w.min(d) / 2.0;
        b.add_solid_lathe(
            &[(r * 0.9, 0.0), (r, h * 0.3), (r, h * 0.7), (r * 0.9, h)],
            ctx.color,
        )?;
        return single(
            b.finish()?,
            vec![surface("top", "body", [0.0, 0.0, h], [r, r], 0.5)],
        );
    }
    four_legs(
        &mut b,
        w,
        d,
        0.0,
        0.0,
        0.08,
        0.035,
        0.04,
        LegShape::Tapered,
        ctx.accent_color,
    )?;
    b.density(UPHOLSTERY);
    b.add_rounded_box(
        [0.0, 0.0, (0.08 + h) / 2.0],
        [w, d, h - 0.08],
        0.04,
        ctx.color,
    )?;
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, 0.0, h],
            [w * 0.9, d * 0.9],
            0.5,
        )],
    )
}
