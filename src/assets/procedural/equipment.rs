//! Equipment: gym machines and racks (treadmill, exercise bike, dumbbell rack, squat rack),
//! music (upright piano, music stand) and care (IV stand).

use super::parts::{BLACK, METAL, WHITE, body, shade, single, surface};
use super::{GenContext, Generated, GeneratorFn};
use crate::geometry::GeometryError;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("treadmill", treadmill),
    ("exercise_bike", exercise_bike),
    ("weight_rack", weight_rack),
    ("squat_rack", squat_rack),
    ("piano", piano),
    ("music_stand", music_stand),
    ("iv_stand", iv_stand),
];

/// Treadmill: a deck with a belt running along y, uprights at the front (+Y) and a console.
fn treadmill(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let deck_h = 0.2;
    b.shell(Some(0.004));
    b.add_rounded_box(
        [0.0, -0.05, deck_h / 2.0],
        [w, d - 0.1, deck_h],
        0.03,
        ctx.color,
    )?;
    b.shell(None);
    b.add_detail(
        [0.0, -0.1, deck_h + 0.002],
        [w * 0.7, d * 0.75, 0.004],
        [0.05, 0.05, 0.05],
    );
    b.add_rounded_box(
        [0.0, d / 2.0 - 0.15, deck_h + 0.05],
        [w, 0.3, 0.1],
        0.03,
        shade(ctx.color, 0.8),
    )?;
    let uy = d / 2.0 - 0.15;
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - 0.04);
        b.add_rod([x, uy, deck_h + 0.1], [x, uy - 0.1, h - 0.12], 0.025, METAL)?;
        b.add_rod(
            [x, uy - 0.1, h - 0.3],
            [x, uy - 0.45, h - 0.3],
            0.018,
            BLACK,
        )?;
    }
    b.add_rounded_box(
        [0.0, uy - 0.12, h - 0.08],
        [w * 0.85, 0.18, 0.16],
        0.03,
        BLACK,
    )?;
    b.add_detail(
        [0.0, uy - 0.2, h - 0.06],
        [w * 0.4, 0.02, 0.08],
        [0.05, 0.25, 0.5],
    );
    single(b.finish()?, vec![])
}

/// Upright exercise bike: a base, a frame, a flywheel at the front, a saddle and handlebars.
fn exercise_bike(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let frame = ctx.color;
    for y in [-d / 2.0 + 0.05, d / 2.0 - 0.05] {
        b.add_rounded_box([0.0, y, 0.03], [w, 0.08, 0.06], 0.02, BLACK)?;
    }
    b.add_rod(
        [0.0, -d / 2.0 + 0.05, 0.06],
        [0.0, d / 2.0 - 0.05, 0.06],
        0.03,
        frame,
    )?;
    // Flywheel near the front.
    let fr = (h * 0.2).min(0.24);
    let fy = d / 2.0 - 0.05 - fr;
    b.add_part(
        super::shapes::frustum_mesh([-0.03, fy, 0.1 + fr], [0.03, fy, 0.1 + fr], fr, fr, 32),
        super::shapes::frustum_piece([-0.03, fy, 0.1 + fr], [0.03, fy, 0.1 + fr], fr, fr, 16)?,
        shade(frame, 0.7),
    );
    let seat_y = -d / 2.0 + 0.25;
    let seat_z = h * 0.7;
    b.add_rod(
        [0.0, -d / 2.0 + 0.1, 0.06],
        [0.0, seat_y, seat_z - 0.06],
        0.03,
        frame,
    )?;
    b.add_rod([0.0, seat_y, 0.06], [0.0, fy, 0.1 + fr], 0.03, frame)?;
    b.add_ellipsoid(
        [0.0, seat_y - 0.02, seat_z - 0.03],
        [0.1, 0.14, 0.04],
        BLACK,
    )?;
    let bar_y = d / 2.0 - 0.18;
    b.add_rod([0.0, fy, 0.1 + fr], [0.0, bar_y, h - 0.06], 0.03, frame)?;
    b.add_rod(
        [-w / 2.0 + 0.03, bar_y + 0.05, h - 0.03],
        [w / 2.0 - 0.03, bar_y + 0.05, h - 0.03],
        0.02,
        BLACK,
    )?;
    b.add_rod(
        [0.0, bar_y, h - 0.06],
        [0.0, bar_y + 0.05, h - 0.03],
        0.02,
        frame,
    )?;
    // Pedal cranks.
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * 0.08, fy - fr * 0.8, 0.1 + fr * 0.8],
            [0.1, 0.05, 0.02],
            BLACK,
        )?;
    }
    single(b.finish()?, vec![])
}

/// Dumbbell rack: an A-frame with two tilted tiers of trays.
fn weight_rack(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let frame = ctx.color;
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - 0.03);
        b.add_box([x, 0.0, 0.02], [0.06, d, 0.04], frame)?;
        b.add_rod(
            [x, -d / 2.0 + 0.05, 0.04],
            [x, -0.05, h - 0.02],
            0.025,
            frame,
        )?;
        b.add_rod(
            [x, d / 2.0 - 0.05, 0.04],
            [x, -0.05, h - 0.02],
            0.025,
            frame,
        )?;
    }
    let mut surfaces = Vec::new();
    for (i, z) in [h * 0.35, h * 0.8].iter().enumerate() {
        let td = if i == 0 { d * 0.7 } else { d * 0.4 };
        let y = if i == 0 { 0.02 } else { -0.02 };
        b.add_box([0.0, y, *z - 0.015], [w, td, 0.03], shade(frame, 0.8))?;
        surfaces.push(surface(
            &format!("shelf_{i}"),
            "body",
            [0.0, y, *z],
            [w - 0.1, td],
            if i == 0 { h * 0.4 } else { 0.3 },
        ));
    }
    single(b.finish()?, surfaces)
}

/// Squat rack: four posts, top cross bars, J-hooks and a barbell resting on them.
fn squat_rack(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let post = 0.06;
    let frame = ctx.color;
    let px = w / 2.0 - 0.25;
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            b.add_box(
                [sx * px, sy * (d / 2.0 - post / 2.0), h / 2.0],
                [post, post, h],
                frame,
            )?;
        }
        b.add_box([sx * px, 0.0, 0.03], [post, d, 0.06], frame)?;
        b.add_box([sx * px, 0.0, h - 0.03], [post, d, 0.06], frame)?;
    }
    b.add_box(
        [0.0, -d / 2.0 + post / 2.0, h - 0.03],
        [2.0 * px, post, 0.06],
        frame,
    )?;
    let bar_z = 1.35_f64.min(h * 0.6);
    // Safety arms along y carry the bar in the middle of the rack.
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * px, 0.0, bar_z - 0.05],
            [0.05, d - 2.0 * post, 0.05],
            BLACK,
        )?;
    }
    let by = 0.0;
    b.add_rod([-w / 2.0, by, bar_z], [w / 2.0, by, bar_z], 0.014, METAL)?;
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - 0.12);
        b.add_rod(
            [x - 0.03, by, bar_z],
            [x + 0.03, by, bar_z],
            0.2_f64.min(bar_z - 0.02),
            BLACK,
        )?;
    }
    single(b.finish()?, vec![])
}

/// Upright piano: a tall case, a keyboard shelf with white and black keys, legs, a bench-free
/// front (+Y is the player's side).
fn piano(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let case_d = d * 0.45;
    let y_back = -d / 2.0;
    let key_z = 0.72_f64.min(h * 0.6);
    // Upper case.
    b.add_box(
        [0.0, y_back + case_d / 2.0, (key_z + h) / 2.0],
        [w, case_d, h - key_z],
        ctx.color,
    )?;
    // Lower case (narrower front, recessed for knees).
    b.add_box(
        [0.0, y_back + case_d * 0.4, key_z / 2.0],
        [w, case_d * 0.8, key_z],
        shade(ctx.color, 0.9),
    )?;
    // Cheeks on both sides reaching forward to carry the keyboard.
    let kb_d = d - case_d;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [
                sx * (w / 2.0 - 0.03),
                y_back + case_d + kb_d / 2.0,
                key_z + 0.03,
            ],
            [0.06, kb_d, 0.12],
            ctx.color,
        )?;
        b.add_box(
            [sx * (w / 2.0 - 0.06), d / 2.0 - 0.04, key_z / 2.0],
            [0.05, 0.05, key_z],
            ctx.color,
        )?;
    }
    // Key bed and keys.
    let kw = w - 0.12;
    b.add_box(
        [0.0, y_back + case_d + kb_d / 2.0, key_z - 0.03],
        [kw, kb_d, 0.04],
        shade(ctx.color, 0.8),
    )?;
    let key_len = kb_d * 0.8;
    let ky = d / 2.0 - key_len / 2.0 - 0.01;
    b.add_box([0.0, ky, key_z + 0.005], [kw - 0.01, key_len, 0.03], WHITE)?;
    let n = 52;
    for i in 0..n {
        let x = -kw / 2.0 + (i as f64 + 0.5) * kw / n as f64;
        // Key gaps.
        b.add_detail(
            [x + kw / n as f64 / 2.0, ky, key_z + 0.0205],
            [0.0015, key_len, 0.002],
            [0.5, 0.5, 0.5],
        );
        let pattern = i % 7;
        if pattern != 2 && pattern != 6 && i + 1 < n {
            b.add_detail(
                [x + kw / n as f64 / 2.0, ky - key_len * 0.2, key_z + 0.028],
                [kw / n as f64 * 0.55, key_len * 0.6, 0.014],
                BLACK,
            );
        }
    }
    // Music desk.
    b.add_detail(
        [0.0, y_back + case_d + 0.01, key_z + 0.25],
        [w * 0.5, 0.02, 0.2],
        shade(ctx.color, 1.1),
    );
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, y_back + case_d / 2.0, h],
            [w, case_d],
            0.5,
        )],
    )
}

/// Music stand: a tripod, a telescopic pole and a tilted desk.
fn music_stand(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    for foot in [
        [0.0, -d / 2.0 + 0.008],
        [-w / 2.0 + 0.008, d / 2.0 - 0.008],
        [w / 2.0 - 0.008, d / 2.0 - 0.008],
    ] {
        b.add_rod(
            [0.0, 0.0, 0.25],
            [foot[0], foot[1], 0.008],
            0.008,
            ctx.color,
        )?;
    }
    let desk_h = 0.3;
    b.add_rod(
        [0.0, 0.0, 0.0],
        [0.0, 0.0, h - desk_h * 0.8],
        0.01,
        ctx.color,
    )?;
    let tilt: f64 = 0.3;
    let pose = crate::scene::Pose(nalgebra::Isometry3::from_parts(
        nalgebra::Translation3::new(0.0, 0.0, h - desk_h / 2.0 * tilt.cos()),
        nalgebra::UnitQuaternion::from_axis_angle(&nalgebra::Vector3::x_axis(), -tilt),
    ));
    let size = [w * 0.95, 0.006, desk_h];
    b.add_part(
        crate::geometry::mesh::box_mesh([0.0; 3], size).transformed(&pose),
        crate::geometry::ConvexPiece::cuboid([0.0; 3], size)?.transformed(&pose),
        ctx.color,
    );
    single(b.finish()?, vec![])
}

/// IV stand: a five-leg base on casters, a pole, a hook crossbar and a fluid bag.
fn iv_stand(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0 - 0.02;
    for i in 0..4 {
        let a = std::f64::consts::TAU * i as f64 / 4.0;
        b.add_rod(
            [0.0, 0.0, 0.06],
            [r * a.cos(), r * a.sin(), 0.04],
            0.012,
            METAL,
        )?;
        b.add_ellipsoid([r * a.cos(), r * a.sin(), 0.02], [0.02, 0.02, 0.02], BLACK)?;
    }
    b.add_rod([0.0, 0.0, 0.04], [0.0, 0.0, h - 0.01], 0.012, METAL)?;
    b.add_rod([-0.12, 0.0, h - 0.05], [0.12, 0.0, h - 0.05], 0.006, METAL)?;
    b.density(1000.0);
    b.add_rounded_box(
        [0.1, 0.0, h - 0.2],
        [0.1, 0.03, 0.18],
        0.01,
        [0.85, 0.9, 0.95],
    )?;
    b.material_density();
    b.add_rod([-0.1, 0.0, h - 0.05], [-0.1, 0.0, h - 0.12], 0.004, METAL)?;
    single(b.finish()?, vec![])
}
