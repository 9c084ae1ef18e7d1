//! Toys and sports items (manipulands, bottom at z = 0): board games, stuffed animals (teddy
//! bears, dinosaurs), toy blocks and bricks, balls, toy cars and trains, dumbbells, weight
//! plates.

use super::parts::{BLACK, METAL, WHITE, body, shade, single, surface};
use super::shapes;
use super::{GenContext, Generated, GeneratorFn};
use crate::geometry::{ConvexPiece, GeometryError, mesh};

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("board_game", board_game),
    ("stuffed_animal", stuffed_animal),
    ("toy_block", toy_block),
    ("ball", ball),
    ("toy_vehicle", toy_vehicle),
    ("dumbbell", dumbbell),
    ("weight_plate", weight_plate),
];

/// Board game box: a flat box with a printed lid.
fn board_game(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.shell(Some(0.002));
    b.add_box([0.0, 0.0, h / 2.0], [w, d, h], ctx.color)?;
    b.shell(None);
    for k in 0..4 {
        let x = -w * 0.3 + k as f64 * w * 0.2;
        b.add_detail(
            [x, d * 0.1, h + 0.0005],
            [w * 0.15, d * 0.3, 0.001],
            ctx.palette(k + 1),
        );
    }
    b.add_detail(
        [0.0, -d * 0.3, h + 0.0005],
        [w * 0.7, d * 0.15, 0.001],
        WHITE,
    );
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [w, d], 0.3)],
    )
}

/// Stuffed animal: a sitting teddy bear (body, head, ears, snout, arms, legs); the `dinosaur`
/// variant has a long neck and tail.
fn stuffed_animal(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.density(80.0);
    let c = ctx.color;
    if ctx.variant == "dinosaur" {
        b.add_ellipsoid([0.0, 0.0, h * 0.32], [w * 0.45, d * 0.3, h * 0.3], c)?;
        b.add_frustum(
            [0.0, d * 0.1, h * 0.4],
            [0.0, d * 0.3, h * 0.82],
            w * 0.18,
            w * 0.12,
            c,
        )?;
        b.add_ellipsoid([0.0, d * 0.34, h * 0.88], [w * 0.16, d * 0.16, h * 0.12], c)?;
        b.add_frustum(
            [0.0, -d * 0.2, h * 0.25],
            [0.0, -d / 2.0 + 0.012, h * 0.06],
            w * 0.2,
            0.01,
            c,
        )?;
        for (x, y) in [(-1.0, 1.0), (1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
            let lr = w * 0.1;
            b.add_leg(
                [x * (w / 2.0 - lr), y * d * 0.12, h * 0.2],
                [x * (w / 2.0 - lr), y * d * 0.14],
                lr,
                shade(c, 0.9),
            )?;
        }
        return single(b.finish()?, vec![]);
    }
    let body_h = h * 0.55;
    b.add_ellipsoid(
        [0.0, -d * 0.15, body_h * 0.5],
        [w * 0.32, d * 0.35, body_h * 0.5],
        c,
    )?;
    let head_r = h * 0.2;
    let head_z = h - head_r - 0.01;
    b.add_ellipsoid([0.0, 0.0, head_z], [head_r, head_r * 0.9, head_r], c)?;
    b.add_ellipsoid(
        [0.0, head_r * 0.8, head_z - head_r * 0.25],
        [head_r * 0.4, head_r * 0.3, head_r * 0.3],
        shade(c, 1.3),
    )?;
    for sx in [-1.0, 1.0] {
        b.add_ellipsoid(
            [sx * head_r * 0.75, 0.0, head_z + head_r * 0.75],
            [head_r * 0.3, head_r * 0.15, head_r * 0.3],
            c,
        )?;
        b.add_ellipsoid(
            [sx * w * 0.36, d * 0.1, body_h * 0.55],
            [w * 0.12, d * 0.12, body_h * 0.28],
            c,
        )?;
        b.add_ellipsoid(
            [sx * w * 0.18, d * 0.3, body_h * 0.15],
            [w * 0.12, d * 0.2, body_h * 0.15],
            c,
        )?;
        b.add_visual(
            shapes::ellipsoid_mesh(
                [sx * head_r * 0.35, head_r * 0.82, head_z + head_r * 0.2],
                [0.008, 0.006, 0.008],
                8,
            ),
            BLACK,
        );
    }
    b.add_visual(
        shapes::ellipsoid_mesh(
            [0.0, head_r * 1.08, head_z - head_r * 0.2],
            [0.01, 0.006, 0.008],
            8,
        ),
        BLACK,
    );
    single(b.finish()?, vec![])
}

/// Toy building block (a cube with a letter face) or `brick` (with studs on top).
fn toy_block(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let color = match ctx.style {
        Some(_) => {
            let k = ctx.uniform(0.0, 5.0) as usize;
            ctx.palette(k)
        }
        None => [
            [0.8, 0.1, 0.1],
            [0.1, 0.3, 0.8],
            [0.95, 0.8, 0.1],
            [0.1, 0.6, 0.2],
        ][ctx.uniform(0.0, 4.0) as usize % 4],
    };
    let color = if ctx.variant == "wooden" {
        ctx.color
    } else {
        color
    };
    if ctx.variant == "brick" {
        let stud = h * 0.18;
        b.add_box([0.0, 0.0, (h - stud) / 2.0], [w, d, h - stud], color)?;
        let nx = ((w / 0.008).round() as usize).max(1);
        let ny = ((d / 0.008).round() as usize).max(1);
        for i in 0..nx {
            for j in 0..ny {
                let x = -w / 2.0 + (i as f64 + 0.5) * w / nx as f64;
                let y = -d / 2.0 + (j as f64 + 0.5) * d / ny as f64;
                b.add_visual(
                    mesh::cylinder_mesh(x, y, w / nx as f64 * 0.3, h - stud, h, 12),
                    color,
                );
            }
        }
        return single(b.finish()?, vec![]);
    }
    b.add_box([0.0, 0.0, h / 2.0], [w, d, h], color)?;
    b.add_detail(
        [0.0, d / 2.0 + 0.0005, h / 2.0],
        [w * 0.5, 0.001, h * 0.5],
        shade(color, 0.5),
    );
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [w, d], 0.3)],
    )
}

/// Ball: a sphere with seams (`basketball`, `soccer`, `exercise` variants colour it).
fn ball(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d).min(h) / 2.0;
    b.shell(Some((r * 0.05).max(0.002)));
    b.add_ellipsoid([0.0, 0.0, r], [r, r, r], ctx.color)?;
    b.shell(None);
    b.add_visual(
        shapes::frustum_mesh(
            [0.0, 0.0, r - 0.002],
            [0.0, 0.0, r + 0.002],
            r * 1.003,
            r * 1.003,
            32,
        ),
        shade(ctx.color, 0.5),
    );
    single(b.finish()?, vec![])
}

/// Toy vehicles along x: `car` (body, cabin, wheels), `train` (engine with a chimney and cab).
fn toy_vehicle(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let wr = h * 0.22;
    let tw = d * 0.15;
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            let (x, y) = (sx * w * 0.3, sy * (d / 2.0 - tw / 2.0));
            b.add_rod([x, y - tw / 2.0, wr], [x, y + tw / 2.0, wr], wr, BLACK)?;
        }
    }
    let base = wr * 0.8;
    let bd = d * 0.7;
    if ctx.variant == "train" {
        b.add_box(
            [-w * 0.1, 0.0, base + (h * 0.35) / 2.0],
            [w * 0.8, bd, h * 0.35],
            ctx.color,
        )?;
        b.add_rod(
            [w * 0.05, 0.0, base + h * 0.35 / 2.0],
            [w / 2.0 - 0.005, 0.0, base + h * 0.35 / 2.0],
            h * 0.17,
            ctx.color,
        )?;
        b.add_box(
            [-w / 2.0 + w * 0.15, 0.0, (base + h * 0.35 + h) / 2.0],
            [w * 0.3, bd, h - base - h * 0.35],
            shade(ctx.color, 0.8),
        )?;
        b.add_rod(
            [w * 0.3, 0.0, base + h * 0.4],
            [w * 0.3, 0.0, h * 0.85],
            h * 0.06,
            BLACK,
        )?;
    } else {
        b.add_rounded_box(
            [0.0, 0.0, base + h * 0.2],
            [w, bd, h * 0.4],
            0.01_f64.min(h * 0.1),
            ctx.color,
        )?;
        b.add_rounded_box(
            [-w * 0.05, 0.0, base + h * 0.4 + (h - base - h * 0.4) / 2.0],
            [w * 0.5, bd * 0.9, h - base - h * 0.4],
            0.01_f64.min(h * 0.1),
            shade(ctx.color, 0.9),
        )?;
        b.add_detail(
            [-w * 0.05, 0.0, h - 0.001],
            [w * 0.4, bd * 0.8, 0.002],
            [0.6, 0.75, 0.85],
        );
    }
    single(b.finish()?, vec![])
}

/// Dumbbell along x: a handle and two hexagonal heads.
fn dumbbell(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    // Hexagonal heads resting on a flat side: circumradius r, across-flats height 1.73 r.
    let r = (d / 2.0).min(h / 3f64.sqrt());
    let zc = r * 3f64.sqrt() / 2.0;
    let head = w * 0.25;
    for sx in [-1.0, 1.0] {
        let x0 = sx * (w / 2.0 - head);
        let ring: Vec<[f64; 2]> = mesh::circle_ring(0.0, 0.0, r, 6);
        let pts: Vec<[f64; 3]> = ring
            .iter()
            .flat_map(|p| [[x0, p[0], zc + p[1]], [sx * w / 2.0, p[0], zc + p[1]]])
            .collect();
        let piece = ConvexPiece::from_points(&pts)?;
        let m = shapes::yz_prism_mesh(
            &ring.iter().map(|p| [p[0], zc + p[1]]).collect::<Vec<_>>(),
            x0.min(sx * w / 2.0),
            x0.max(sx * w / 2.0),
        );
        b.add_part(m, piece, BLACK);
    }
    b.add_rod(
        [-w / 2.0 + head, 0.0, zc],
        [w / 2.0 - head, 0.0, zc],
        r * 0.3,
        METAL,
    )?;
    single(b.finish()?, vec![])
}

/// Weight plate lying flat: a thick disc with a centre hole (eight sectors around it).
fn weight_plate(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0;
    let hole = 0.026_f64.min(r * 0.3);
    let profile = [(hole, 0.0), (r, 0.0), (r, h), (hole, h)];
    for p in crate::geometry::convex::revolved_pieces(&profile, 12)? {
        b.add_collision(p);
    }
    b.add_visual(
        mesh::lathe_mesh(&[(hole, 0.0), (r, 0.0), (r, h), (hole, h), (hole, 0.0)], 40),
        ctx.color,
    );
    single(b.finish()?, vec![])
}
