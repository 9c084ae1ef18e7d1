//! Beds and padded tables: beds of every size, bunk and loft beds, cribs, hospital beds, exam
//! tables, changing tables. The head end is at -Y (against the wall), the foot at +Y.

use super::parts::{LINEN, LegShape, METAL, WHITE, body, four_legs, mix, shade, single, surface};
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::LinkBuilder;
use crate::geometry::GeometryError;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("bed", bed),
    ("bunk_bed", bunk_bed),
    ("crib", crib),
    ("hospital_bed", hospital_bed),
    ("exam_table", exam_table),
    ("changing_table", changing_table),
];

/// Mattresses, duvets and pillows: foam and fabric, kg/m^3.
const BEDDING: f64 = 70.0;

/// Mattress, duvet and pillows on a platform whose top is at `z` spanning `w` x `len` centred
/// at (0, `cy`); returns the mattress top height.
fn bedding(
    b: &mut LinkBuilder,
    ctx: &mut GenContext,
    w: f64,
    len: f64,
    cy: f64,
    z: f64,
    thick: f64,
) -> Result<f64, GeometryError> {
    let cover = match &ctx.style {
        Some(_) => ctx.palette(1),
        None => mix(ctx.color, LINEN, 0.55 + 0.3 * ctx.uniform(0.0, 1.0)),
    };
    b.density(BEDDING);
    b.add_rounded_box([0.0, cy, z + thick / 2.0], [w, len, thick], 0.04, LINEN)?;
    let top = z + thick;
    // Duvet over the foot two thirds.
    let dl = len * 0.68;
    b.add_rounded_box(
        [0.0, cy + len / 2.0 - dl / 2.0, top + 0.03],
        [w + 0.0, dl, 0.06],
        0.03,
        cover,
    )?;
    // Pillows at the head.
    let n = if w > 1.2 { 2 } else { 1 };
    let pw = (w - 0.1) / n as f64 - 0.04;
    for i in 0..n {
        let x = -w / 2.0 + 0.05 + (i as f64 + 0.5) * (w - 0.1) / n as f64;
        b.add_rounded_box(
            [x, cy - len / 2.0 + 0.22, top + 0.06],
            [pw, 0.36, 0.12],
            0.05,
            WHITE,
        )?;
    }
    b.material_density();
    Ok(top)
}

/// Bed: frame with side rails, a headboard, a low footboard, legs, and bedding.
fn bed(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let head_t = 0.045;
    let rail_h = 0.2;
    let rail_top = (h * 0.33).clamp(0.28, 0.4);
    let frame = ctx.color;
    // Headboard.
    b.add_box(
        [0.0, -d / 2.0 + head_t / 2.0, h / 2.0],
        [w, head_t, h],
        frame,
    )?;
    // Footboard.
    let foot_h = rail_top + 0.1;
    b.add_box(
        [0.0, d / 2.0 - 0.03, foot_h / 2.0],
        [w, 0.06, foot_h],
        frame,
    )?;
    // Side rails and legs.
    let inner_len = d - head_t - 0.06;
    let cy = (-d / 2.0 + head_t + d / 2.0 - 0.06) / 2.0;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - 0.025), cy, rail_top - rail_h / 2.0],
            [0.05, inner_len, rail_h],
            shade(frame, 0.9),
        )?;
        b.add_box(
            [sx * (w / 2.0 - 0.04), cy, (rail_top - rail_h) / 2.0],
            [0.06, 0.06, rail_top - rail_h],
            shade(frame, 0.8),
        )?;
    }
    // Slat deck.
    b.add_box(
        [0.0, cy, rail_top - 0.04],
        [w - 0.1, inner_len, 0.015],
        shade(frame, 0.7),
    )?;
    let top = bedding(
        &mut b,
        ctx,
        w - 0.1,
        inner_len - 0.02,
        cy,
        rail_top - 0.03,
        0.2,
    )?;
    let len = inner_len - 0.02;
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, cy + len * 0.1, top + 0.06],
            [w - 0.2, len * 0.6],
            1.0,
        )],
    )
}

/// Bunk bed (two sleeping levels) or, with the `loft` variant, a loft bed with a desk top
/// below. Ladder on the right end of the front (+Y).
fn bunk_bed(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let loft = ctx.variant == "loft";
    let mut b = body(ctx);
    let post = 0.07;
    let frame = ctx.color;
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            b.add_box(
                [
                    sx * (w / 2.0 - post / 2.0),
                    sy * (d / 2.0 - post / 2.0),
                    h / 2.0,
                ],
                [post, post, h],
                frame,
            )?;
        }
    }
    let upper_z = if loft { h - 0.55 } else { h * 0.62 };
    let levels: Vec<f64> = if loft {
        vec![upper_z]
    } else {
        vec![0.3, upper_z]
    };
    let iw = w - 2.0 * post;
    let mut surfaces = Vec::new();
    for (k, &z) in levels.iter().enumerate() {
        for sx in [-1.0, 1.0] {
            b.add_box(
                [sx * (w / 2.0 - post / 2.0), 0.0, z - 0.06],
                [0.03, d - 2.0 * post, 0.12],
                shade(frame, 0.9),
            )?;
        }
        for sy in [-1.0, 1.0] {
            b.add_box(
                [0.0, sy * (d / 2.0 - post / 2.0), z - 0.06],
                [iw, 0.03, 0.12],
                shade(frame, 0.9),
            )?;
        }
        b.add_box(
            [0.0, 0.0, z - 0.1],
            [iw, d - 2.0 * post, 0.02],
            shade(frame, 0.7),
        )?;
        let top = bedding(
            &mut b,
            ctx,
            iw - 0.02,
            d - 2.0 * post - 0.02,
            0.0,
            z - 0.09,
            0.15,
        )?;
        surfaces.push(surface(
            if k == 0 && !loft { "top" } else { "upper" },
            "body",
            [0.0, 0.0, top + 0.06],
            [iw * 0.6, (d - 2.0 * post) * 0.5],
            if k + 1 < levels.len() {
                upper_z - top - 0.2
            } else {
                0.6
            },
        ));
    }
    // Guard rails around the top level, open where the ladder is.
    let gz = upper_z + 0.25;
    let ladder_w = 0.4;
    b.add_box(
        [-ladder_w / 2.0, d / 2.0 - post / 2.0, gz],
        [iw - ladder_w, 0.03, 0.08],
        frame,
    )?;
    b.add_box([0.0, -d / 2.0 + post / 2.0, gz], [iw, 0.03, 0.08], frame)?;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - post / 2.0), 0.0, gz],
            [0.03, d - 2.0 * post, 0.08],
            frame,
        )?;
    }
    // Ladder: two rails and rungs in front of the right end.
    let lx0 = w / 2.0 - post - ladder_w;
    let ly = d / 2.0 - 0.02;
    for x in [lx0, w / 2.0 - post] {
        b.add_box(
            [x, ly, upper_z / 2.0 + 0.1],
            [0.04, 0.04, upper_z + 0.2],
            frame,
        )?;
    }
    let rungs = (upper_z / 0.3) as usize;
    for i in 1..=rungs {
        let z = i as f64 * upper_z / (rungs as f64 + 0.5);
        b.add_rod(
            [lx0 + 0.02, ly, z],
            [w / 2.0 - post - 0.02, ly, z],
            0.014,
            frame,
        )?;
    }
    if loft {
        // Desk top under the bed along the back.
        let dz = 0.75;
        b.add_box(
            [-0.1, -d / 2.0 + post + 0.3, dz],
            [iw - 0.3, 0.6, 0.03],
            shade(frame, 1.1),
        )?;
        surfaces.push(surface(
            "top",
            "body",
            [-0.1, -d / 2.0 + post + 0.3, dz + 0.015],
            [iw - 0.3, 0.6],
            upper_z - 0.15 - dz,
        ));
    }
    single(b.finish()?, surfaces)
}

/// Crib: slatted sides around a raised mattress.
fn crib(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let post = 0.05;
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            b.add_box(
                [
                    sx * (w / 2.0 - post / 2.0),
                    sy * (d / 2.0 - post / 2.0),
                    h / 2.0,
                ],
                [post, post, h],
                ctx.color,
            )?;
        }
    }
    let base_z = 0.3;
    let top_z = h - 0.04;
    // Rails and slats on the long sides (y) and ends (x).
    for sy in [-1.0, 1.0] {
        let y = sy * (d / 2.0 - post / 2.0);
        for z in [base_z, top_z] {
            b.add_box([0.0, y, z], [w - 2.0 * post, 0.03, 0.04], ctx.color)?;
        }
        let n = ((w - 2.0 * post) / 0.08) as usize;
        for i in 1..n {
            let x = -w / 2.0 + post + i as f64 * (w - 2.0 * post) / n as f64;
            b.add_rod(
                [x, y, base_z + 0.02],
                [x, y, top_z - 0.02],
                0.009,
                ctx.color,
            )?;
        }
    }
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - post / 2.0), 0.0, (base_z + top_z) / 2.0],
            [0.03, d - 2.0 * post, top_z - base_z + 0.04],
            shade(ctx.color, 0.95),
        )?;
    }
    b.add_box(
        [0.0, 0.0, base_z - 0.02],
        [w - 2.0 * post, d - 2.0 * post, 0.02],
        shade(ctx.color, 0.8),
    )?;
    b.density(BEDDING);
    b.add_rounded_box(
        [0.0, 0.0, base_z + 0.05],
        [w - 2.0 * post - 0.01, d - 2.0 * post - 0.06, 0.1],
        0.03,
        LINEN,
    )?;
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, 0.0, base_z + 0.1],
            [w - 2.0 * post - 0.05, d - 2.0 * post - 0.1],
            top_z - base_z - 0.1,
        )],
    )
}

/// Hospital bed: a frame on casters, a mattress with the head section raised, side rails and
/// plastic head and foot boards.
fn hospital_bed(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let deck = 0.55_f64.min(h * 0.55);
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            let (x, y) = (sx * (w / 2.0 - 0.08), sy * (d / 2.0 - 0.12));
            b.add_ellipsoid([x, y, 0.05], [0.04, 0.05, 0.05], super::parts::BLACK)?;
            b.add_rod([x, y, 0.1], [x, y, deck - 0.1], 0.025, METAL)?;
        }
    }
    b.add_box([0.0, 0.0, deck - 0.06], [w - 0.12, d - 0.2, 0.1], METAL)?;
    b.density(BEDDING);
    let ml = d - 0.24;
    let flat = ml * 0.62;
    b.add_rounded_box(
        [0.0, d / 2.0 - 0.12 - flat / 2.0, deck + 0.07],
        [w - 0.16, flat, 0.14],
        0.04,
        LINEN,
    )?;
    // Raised head section, tilted.
    let head_l = ml - flat;
    let y_hinge = d / 2.0 - 0.12 - flat;
    // Raise the head section as far as the height allows (up to about 30 degrees).
    let tilt: f64 = ((h - deck - 0.07 - 0.1) / head_l).clamp(0.0, 0.5).asin();
    let c = [
        0.0,
        y_hinge - head_l / 2.0 * tilt.cos(),
        deck + 0.07 + head_l / 2.0 * tilt.sin(),
    ];
    let head = crate::geometry::mesh::box_mesh([0.0; 3], [w - 0.16, head_l, 0.14]);
    let pose = crate::scene::Pose(nalgebra::Isometry3::from_parts(
        nalgebra::Translation3::new(c[0], c[1], c[2]),
        nalgebra::UnitQuaternion::from_axis_angle(&nalgebra::Vector3::x_axis(), -tilt),
    ));
    let piece = crate::geometry::ConvexPiece::cuboid([0.0; 3], [w - 0.16, head_l, 0.14])?
        .transformed(&pose);
    b.add_part(head.transformed(&pose), piece, LINEN);
    b.material_density();
    let board = ctx.color;
    b.add_rounded_box(
        [0.0, -d / 2.0 + 0.03, (deck + h) / 2.0],
        [w - 0.04, 0.06, h - deck],
        0.03,
        board,
    )?;
    let foot_h = 0.4_f64.min(h - deck);
    b.add_rounded_box(
        [0.0, d / 2.0 - 0.03, deck + foot_h / 2.0],
        [w - 0.04, 0.06, foot_h],
        0.03,
        board,
    )?;
    for sx in [-1.0, 1.0] {
        b.add_rounded_box(
            [sx * (w / 2.0 - 0.03), -0.1, deck + 0.25],
            [0.03, d * 0.45, 0.22],
            0.01,
            board,
        )?;
    }
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, d / 2.0 - 0.12 - flat / 2.0, deck + 0.14],
            [w - 0.3, flat * 0.8],
            1.0,
        )],
    )
}

/// Exam table: a padded top with a raised head section on a cabinet base, paper roll at the head.
fn exam_table(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let top_z = h - 0.2;
    b.add_box(
        [0.0, 0.0, (top_z - 0.08) / 2.0],
        [w * 0.8, d * 0.85, top_z - 0.08],
        WHITE,
    )?;
    b.add_box(
        [0.0, 0.0, 0.04],
        [w * 0.85, d * 0.9, 0.08],
        shade(WHITE, 0.6),
    )?;
    b.density(BEDDING);
    let pad = ctx.color;
    let flat = d * 0.7;
    b.add_rounded_box(
        [0.0, d / 2.0 - flat / 2.0, top_z - 0.04],
        [w, flat, 0.08],
        0.025,
        pad,
    )?;
    b.add_rounded_box(
        [0.0, -d / 2.0 + (d - flat) / 2.0, top_z + 0.06],
        [w, d - flat, 0.28],
        0.025,
        pad,
    )?;
    b.material_density();
    b.add_rod(
        [-w / 2.0 + 0.02, -d / 2.0 + 0.05, h - 0.04],
        [w / 2.0 - 0.02, -d / 2.0 + 0.05, h - 0.04],
        0.04,
        LINEN,
    )?;
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, d / 2.0 - flat / 2.0, top_z],
            [w - 0.1, flat - 0.1],
            1.0,
        )],
    )
}

/// Changing table: an open cabinet with two shelves and a pad with raised edges on top.
fn changing_table(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let t = 0.02;
    let top_z = h - 0.12;
    four_legs(
        &mut b,
        w,
        d,
        0.0,
        0.0,
        top_z,
        0.045,
        0.0,
        LegShape::Square,
        ctx.color,
    )?;
    let mut surfaces = Vec::new();
    for (i, z) in [0.1, top_z * 0.5].iter().enumerate() {
        b.add_box(
            [0.0, 0.0, *z],
            [w - 0.09, d - 0.01, t],
            shade(ctx.color, 0.95),
        )?;
        surfaces.push(surface(
            &format!("shelf_{i}"),
            "body",
            [0.0, 0.0, z + t / 2.0],
            [w - 0.09, d - 0.01],
            top_z * 0.5 - 0.1 - t - 0.02,
        ));
    }
    b.add_box([0.0, 0.0, top_z - t / 2.0], [w, d, t], ctx.color)?;
    // Guard rails on three sides.
    b.add_box(
        [0.0, -d / 2.0 + 0.01, top_z + 0.06],
        [w, 0.02, 0.12],
        ctx.color,
    )?;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - 0.01), 0.01, top_z + 0.06],
            [0.02, d - 0.02, 0.12],
            ctx.color,
        )?;
    }
    b.density(BEDDING);
    b.add_rounded_box(
        [0.0, 0.02, top_z + 0.04],
        [w - 0.06, d - 0.08, 0.08],
        0.03,
        ctx.palette(4),
    )?;
    b.material_density();
    surfaces.push(surface(
        "top",
        "body",
        [0.0, 0.02, top_z + 0.08],
        [w - 0.15, d - 0.15],
        0.5,
    ));
    single(b.finish()?, surfaces)
}
