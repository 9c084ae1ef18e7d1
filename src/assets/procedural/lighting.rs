//! Lights: floor lamps, table and desk lamps (surface), wall sconces (back at y = 0), and
//! ceiling fixtures (top at z = 0): pendants, chandeliers, ceiling fans, flush lights, track
//! lights. Ceiling fixtures stay within the 16-piece collision budget.

use super::parts::{BLACK, METAL, body, shade, single};
use super::shapes;
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::LinkBuilder;
use crate::geometry::GeometryError;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("floor_lamp", floor_lamp),
    ("table_lamp", table_lamp),
    ("sconce", sconce),
    ("pendant_light", pendant_light),
    ("chandelier", chandelier),
    ("ceiling_fan", ceiling_fan),
    ("flush_light", flush_light),
    ("track_light", track_light),
    ("mobile", mobile),
];

/// Warm light-bulb glass.
const BULB: [f64; 3] = [1.0, 0.95, 0.75];

/// A lamp shade: a frustum from radius `r0` at `z0` to `r1` at `z1` (hollow visually, solid
/// collision: nothing rests inside a shade).
fn shade_part(
    b: &mut LinkBuilder,
    xy: [f64; 2],
    z0: f64,
    z1: f64,
    r0: f64,
    r1: f64,
    color: [f64; 3],
) -> Result<(), GeometryError> {
    b.shell(Some(0.003));
    b.add_frustum([xy[0], xy[1], z0], [xy[0], xy[1], z1], r0, r1, color)?;
    b.shell(None);
    Ok(())
}

/// Floor lamp: a weighted disc base, a pole and a drum shade; the `arc` variant bends over.
fn floor_lamp(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0;
    let base_r = (r * 0.6).clamp(0.12, 0.2);
    let metal = ctx.accent_color;
    b.density(7800.0);
    b.add_frustum(
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.03],
        base_r,
        base_r * 0.9,
        metal,
    )?;
    b.material_density();
    let shade_h = (h * 0.2).clamp(0.2, 0.35);
    b.add_rod(
        [0.0, 0.0, 0.03],
        [0.0, 0.0, h - shade_h * 0.6],
        0.013,
        metal,
    )?;
    b.add_ellipsoid([0.0, 0.0, h - shade_h * 0.6], [0.035, 0.035, 0.05], BULB)?;
    let shade_color = match ctx.style_name() {
        "" => [0.93, 0.88, 0.76],
        _ => ctx.palette(1),
    };
    shade_part(&mut b, [0.0, 0.0], h - shade_h, h, r, r * 0.78, shade_color)?;
    single(b.finish()?, vec![])
}

/// Table lamp: a turned base, a stem and a shade; the `desk` variant is an angled arm with a
/// small cone head.
fn table_lamp(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0;
    if ctx.variant == "desk" {
        // A desk lamp stays up because its weighted base outweighs the head it holds out
        // over the edge: a cast-iron base, and a thin sheet-metal shade (its solid hull at the
        // density of a 1 mm shell) instead of solid steel.
        let base_r = w / 2.0;
        b.density(7800.0);
        b.add_frustum(
            [0.0, -d / 2.0 + base_r, 0.0],
            [0.0, -d / 2.0 + base_r, 0.02],
            base_r,
            base_r * 0.9,
            ctx.color,
        )?;
        b.material_density();
        let elbow = [0.0, -d * 0.25, h * 0.62];
        b.add_rod([0.0, -d / 2.0 + base_r, 0.02], elbow, 0.008, ctx.color)?;
        let head = [0.0, d * 0.25, h - 0.03];
        b.add_rod(elbow, head, 0.008, ctx.color)?;
        b.density(400.0);
        b.add_frustum(
            head,
            [0.0, d / 2.0 - 0.06, h * 0.72],
            0.03,
            r * 0.5,
            ctx.color,
        )?;
        return single(b.finish()?, vec![]);
    }
    let shade_h = h * 0.42;
    let body_h = h - shade_h * 0.75;
    let br = r * 0.45;
    b.density(2000.0);
    b.add_solid_lathe(
        &[
            (br * 0.7, 0.0),
            (br, body_h * 0.35),
            (br * 0.8, body_h * 0.7),
            (br * 0.25, body_h * 0.85),
        ],
        ctx.color,
    )?;
    b.material_density();
    b.add_rod([0.0, 0.0, body_h * 0.85], [0.0, 0.0, body_h], 0.008, METAL)?;
    let shade_color = match ctx.style_name() {
        "" => [0.95, 0.92, 0.84],
        _ => ctx.palette(2),
    };
    shade_part(&mut b, [0.0, 0.0], h - shade_h, h, r, r * 0.7, shade_color)?;
    single(b.finish()?, vec![])
}

/// Wall sconce: a back plate at y = 0, an arm and an upturned shade.
fn sconce(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let metal = ctx.accent_color;
    b.add_box(
        [0.0, 0.006, h * 0.3],
        [0.08_f64.min(w), 0.012, h * 0.6],
        metal,
    )?;
    let r = (w / 2.0).min(d / 2.0);
    b.add_tube(
        &[
            [0.0, 0.012, h * 0.3],
            [0.0, d - r, h * 0.3],
            [0.0, d - r, h * 0.45],
        ],
        0.008,
        metal,
    )?;
    shade_part(
        &mut b,
        [0.0, d - r],
        h * 0.45,
        h,
        r * 0.55,
        r,
        [0.95, 0.9, 0.8],
    )?;
    single(b.finish()?, vec![])
}

/// Pendant light: a canopy at the ceiling, a cord and a dome shade with a bulb.
fn pendant_light(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0;
    b.add_frustum(
        [0.0, 0.0, -0.03],
        [0.0, 0.0, 0.0],
        0.05,
        0.06,
        ctx.accent_color,
    )?;
    let shade_h = (r * 0.9).min(h * 0.5);
    b.add_rod([0.0, 0.0, -h + shade_h], [0.0, 0.0, -0.03], 0.004, BLACK)?;
    b.shell(Some(0.002));
    b.add_solid_lathe(
        &[
            (r, -h),
            (r * 0.8, -h + shade_h * 0.5),
            (r * 0.2, -h + shade_h),
        ],
        ctx.color,
    )?;
    b.shell(None);
    b.add_visual(
        shapes::ellipsoid_mesh([0.0, 0.0, -h + 0.02], [0.035, 0.035, 0.03], 12),
        BULB,
    );
    single(b.finish()?, vec![])
}

/// Chandelier: a chain, a central column, curved arms carrying candle bulbs.
fn chandelier(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0 - 0.03;
    let metal = ctx.color;
    b.add_frustum([0.0, 0.0, -0.04], [0.0, 0.0, 0.0], 0.06, 0.07, metal)?;
    let body_top = -h * 0.35;
    b.add_rod([0.0, 0.0, body_top], [0.0, 0.0, -0.04], 0.008, metal)?;
    b.add_solid_lathe(
        &[
            (0.02, -h),
            (0.07, -h + 0.1),
            (0.04, -h + 0.2),
            (0.03, body_top),
        ],
        metal,
    )?;
    let arms = 8;
    let arm_z = -h + 0.15;
    for i in 0..arms {
        let a = std::f64::consts::TAU * i as f64 / arms as f64;
        let (c, s) = (a.cos(), a.sin());
        b.add_rod(
            [0.05 * c, 0.05 * s, arm_z],
            [r * c, r * s, arm_z + 0.05],
            0.008,
            metal,
        )?;
        // Candle and flame bulb (visual only: the budget is 16 pieces).
        b.add_visual(
            shapes::frustum_mesh(
                [r * c, r * s, arm_z + 0.05],
                [r * c, r * s, arm_z + 0.13],
                0.012,
                0.012,
                12,
            ),
            [0.95, 0.93, 0.88],
        );
        b.add_visual(
            shapes::ellipsoid_mesh([r * c, r * s, arm_z + 0.155], [0.012, 0.012, 0.025], 10),
            BULB,
        );
        b.add_visual(
            shapes::frustum_mesh(
                [r * c, r * s, arm_z + 0.045],
                [r * c, r * s, arm_z + 0.055],
                0.03,
                0.035,
                12,
            ),
            metal,
        );
    }
    single(b.finish()?, vec![])
}

/// Ceiling fan: a canopy, a downrod, a motor housing, four blades and a light bowl.
fn ceiling_fan(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0;
    let metal = ctx.accent_color;
    b.add_frustum([0.0, 0.0, -0.06], [0.0, 0.0, 0.0], 0.05, 0.07, metal)?;
    let motor_z = -h + 0.1;
    b.add_rod([0.0, 0.0, motor_z + 0.05], [0.0, 0.0, -0.06], 0.012, metal)?;
    b.add_solid_lathe(
        &[
            (0.06, motor_z - 0.04),
            (0.11, motor_z),
            (0.09, motor_z + 0.05),
        ],
        metal,
    )?;
    for i in 0..4 {
        let a = std::f64::consts::TAU * i as f64 / 4.0;
        let pose = crate::scene::Pose::from_xyz_yaw(0.0, 0.0, motor_z - 0.01, a);
        let len = r - 0.1;
        let size = [len, 0.12, 0.008];
        let c = [0.1 + len / 2.0, 0.0, 0.0];
        b.add_part(
            crate::geometry::mesh::box_mesh(c, size).transformed(&pose),
            crate::geometry::ConvexPiece::cuboid(c, size)?.transformed(&pose),
            ctx.color,
        );
    }
    b.add_ellipsoid(
        [0.0, 0.0, -h + 0.04],
        [0.08, 0.08, 0.04],
        [0.95, 0.93, 0.85],
    )?;
    single(b.finish()?, vec![])
}

/// Flush ceiling light: a shallow frosted dome against the ceiling with a metal rim.
fn flush_light(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0;
    b.add_frustum([0.0, 0.0, -0.015], [0.0, 0.0, 0.0], r, r, ctx.accent_color)?;
    b.add_solid_lathe(
        &[(r * 0.95, -0.015), (r * 0.8, -h * 0.7), (r * 0.4, -h)],
        ctx.color,
    )?;
    single(b.finish()?, vec![])
}

/// Track light: a rail on two canopies with three adjustable spot cans.
fn track_light(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let c = ctx.color;
    b.add_box([0.0, 0.0, -0.015], [w, 0.03, 0.03], c)?;
    let n = 3;
    for i in 0..n {
        let x = -w / 2.0 + (i as f64 + 0.5) * w / n as f64;
        let side: f64 = if i % 2 == 0 { 1.0 } else { -1.0 };
        let cy = (d / 2.0 - 0.035) * side;
        b.add_rod([x, 0.0, -0.03], [x, 0.0, -0.07], 0.006, c)?;
        b.add_rod([x, 0.0, -0.07], [x, cy, -0.07], 0.006, c)?;
        b.add_frustum([x, cy, -0.07], [x, cy, -h], 0.03, 0.035, shade(c, 0.9))?;
    }
    single(b.finish()?, vec![])
}

/// Baby mobile: a hanger under the ceiling, two crossed arms and shapes dangling on threads
/// (the shapes are visual; the collision is the hanger and the arms).
fn mobile(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0 - 0.04;
    let arm_z = -h * 0.35;
    b.add_rod([0.0, 0.0, arm_z], [0.0, 0.0, 0.0], 0.005, ctx.color)?;
    b.add_rod([-r, 0.0, arm_z], [r, 0.0, arm_z], 0.005, ctx.color)?;
    b.add_rod([0.0, -r, arm_z], [0.0, r, arm_z], 0.005, ctx.color)?;
    for (k, (x, y)) in [(r, 0.0), (-r, 0.0), (0.0, r), (0.0, -r)]
        .into_iter()
        .enumerate()
    {
        let z = -h + 0.04 + 0.06 * (k % 2) as f64;
        b.add_visual(
            shapes::frustum_mesh([x, y, z], [x, y, arm_z], 0.001, 0.001, 4),
            [0.9, 0.9, 0.9],
        );
        let c = ctx.palette(k + 1);
        let radii = if k % 2 == 0 {
            [0.04, 0.04, 0.04]
        } else {
            [0.04, 0.04, 0.025]
        };
        b.add_visual(shapes::ellipsoid_mesh([x, y, z], radii, 12), c);
    }
    single(b.finish()?, vec![])
}
