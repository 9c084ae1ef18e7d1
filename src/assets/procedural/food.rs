//! Food (manipulands, bottom at z = 0): round fruit and vegetables (apples, oranges, lemons,
//! limes, pears, peaches, tomatoes, onions, potatoes), bananas, bunches of grapes, carrots,
//! bread loaves and baguettes, cheese wedges, eggs, cakes.

use super::parts::{LEAF, body, shade, single, surface};
use super::{GenContext, Generated, GeneratorFn};
use crate::geometry::GeometryError;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("fruit", fruit),
    ("banana", banana),
    ("grapes", grapes),
    ("carrot", carrot),
    ("bread", bread),
    ("cheese", cheese),
    ("cake", cake),
];

/// Round fruit and vegetables by variant: `apple` (dimpled with a stem), `orange`, `lemon`
/// and `lime` (pointed ends along x), `pear` (two lobes), `peach`, `tomato` (green calyx),
/// `onion` (pointed top), `potato` (lumpy, brown).
fn fruit(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let c = ctx.color;
    let (rx, ry, rz) = (w / 2.0, d / 2.0, h / 2.0);
    match ctx.variant {
        "pear" => {
            // The lower lobe sits on a small flat base, so a pear stands.
            let low = h * 0.62;
            b.add_frustum(
                [0.0, 0.0, 0.0],
                [0.0, 0.0, low * 0.3],
                rx * 0.55,
                rx * 0.93,
                c,
            )?;
            b.add_ellipsoid([0.0, 0.0, low * 0.08 + low * 0.46], [rx, ry, low * 0.46], c)?;
            let top_r = rx * 0.6;
            b.add_ellipsoid(
                [0.0, 0.0, low * 0.8 + (h - low * 0.8 - 0.012) / 2.0],
                [top_r, top_r, (h - low * 0.8 - 0.012) / 2.0],
                c,
            )?;
            b.add_rod(
                [0.0, 0.0, h - 0.014],
                [0.003, 0.0, h],
                0.002,
                [0.3, 0.2, 0.1],
            )?;
        }
        "lemon" | "lime" => {
            b.add_ellipsoid([0.0, 0.0, rz], [rx * 0.9, ry, rz], c)?;
            for sx in [-1.0, 1.0] {
                b.add_frustum(
                    [sx * rx * 0.85, 0.0, rz],
                    [sx * rx, 0.0, rz],
                    rz * 0.3,
                    rz * 0.08,
                    c,
                )?;
            }
        }
        "onion" => {
            b.add_ellipsoid([0.0, 0.0, rz * 0.8], [rx, ry, rz * 0.8], c)?;
            b.add_frustum(
                [0.0, 0.0, rz * 1.4],
                [0.0, 0.0, h],
                rx * 0.35,
                0.002,
                shade(c, 0.8),
            )?;
        }
        "potato" => {
            let tint = ctx.uniform(0.92, 1.0);
            b.add_ellipsoid([rx * 0.15, 0.0, rz], [rx * 0.85, ry, rz], shade(c, tint))?;
            b.add_ellipsoid(
                [-rx * 0.4, 0.0, rz * 0.9],
                [rx * 0.6, ry * 0.85, rz * 0.9],
                shade(c, 0.95),
            )?;
        }
        _ => {
            b.add_ellipsoid([0.0, 0.0, rz], [rx, ry, rz], c)?;
            match ctx.variant {
                "apple" => {
                    b.add_rod(
                        [0.0, 0.0, h * 0.85],
                        [0.004, 0.0, h],
                        0.0025,
                        [0.3, 0.2, 0.1],
                    )?;
                    b.add_visual(
                        super::shapes::ellipsoid_mesh(
                            [0.012, 0.0, h * 0.93],
                            [0.012, 0.005, 0.003],
                            8,
                        ),
                        LEAF,
                    );
                }
                "tomato" => {
                    b.add_visual(
                        super::shapes::ellipsoid_mesh(
                            [0.0, 0.0, h * 0.985],
                            [rx * 0.4, ry * 0.4, h * 0.02],
                            10,
                        ),
                        LEAF,
                    );
                }
                "orange" | "peach" => {
                    b.add_visual(
                        super::shapes::ellipsoid_mesh(
                            [0.0, 0.0, h * 0.99],
                            [0.004, 0.004, 0.0015],
                            8,
                        ),
                        shade(LEAF, 0.7),
                    );
                }
                _ => {}
            }
        }
    }
    single(b.finish()?, vec![])
}

/// Banana: a curved chain of tapering segments along x, lying on its side (the curve in the
/// horizontal plane, ends towards +y), as a banana rests on a table.
fn banana(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = h / 2.0;
    let n = 6;
    let pts: Vec<[f64; 3]> = (0..=n)
        .map(|i| {
            let t = i as f64 / n as f64 * 2.0 - 1.0;
            [
                t * (w / 2.0 - r * 0.45),
                -d / 2.0 + r + (d - 1.45 * r) * t * t,
                r,
            ]
        })
        .collect();
    for i in 0..n {
        let t0 = (i as f64 / n as f64 * 2.0 - 1.0).abs();
        let t1 = ((i + 1) as f64 / n as f64 * 2.0 - 1.0).abs();
        let rad = |t: f64| r * (1.0 - 0.55 * t * t);
        b.add_frustum(pts[i], pts[i + 1], rad(t0), rad(t1), ctx.color)?;
    }
    b.add_visual(
        super::shapes::ellipsoid_mesh(pts[n], [0.004, 0.004, 0.004], 8),
        [0.25, 0.2, 0.1],
    );
    single(b.finish()?, vec![])
}

/// Bunch of grapes: berries in a cone below a stem.
fn grapes(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = (w.min(d) / 2.0) * 0.32;
    let mut placed = 0;
    let layers = ((h - 0.02) / (1.6 * r)).floor().max(2.0) as usize;
    for layer in 0..layers {
        let z = r + layer as f64 * 1.55 * r;
        // The bunch widens upward; the top rings reach the full width.
        let t = (layer as f64 / (layers as f64 - 1.0).max(1.0)).min(1.0);
        let ring = (w.min(d) / 2.0 - r) * (0.2 + 0.8 * t);
        let fit = ((std::f64::consts::TAU * ring) / (2.05 * r)).floor() as usize;
        // Multiples of four put berries on both axes, so the bunch is as wide as asked.
        let n = if fit < 4 { 1 } else { fit / 4 * 4 };
        for k in 0..n {
            if placed >= 44 {
                break;
            }
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            let (x, y) = if n == 1 {
                (0.0, 0.0)
            } else {
                (ring * a.cos(), ring * a.sin())
            };
            b.add_ellipsoid(
                [x, y, z],
                [r, r, r],
                shade(ctx.color, 0.9 + 0.1 * (k % 2) as f64),
            )?;
            placed += 1;
        }
    }
    b.add_rod(
        [0.0, 0.0, h - 0.025],
        [0.0, 0.0, h],
        0.002,
        [0.35, 0.3, 0.15],
    )?;
    single(b.finish()?, vec![])
}

/// Carrot lying along x: a tapering root and a green top.
fn carrot(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, _h] = ctx.size;
    let mut b = body(ctx);
    let r = d / 2.0;
    let top = w * 0.2;
    b.add_frustum(
        [-w / 2.0 + top, 0.0, r],
        [w / 2.0, 0.0, r],
        r,
        0.002,
        ctx.color,
    )?;
    for k in 0..3 {
        let y = (k as f64 - 1.0) * r * 0.5;
        b.add_frustum(
            [-w / 2.0 + top, y * 0.3, r],
            [-w / 2.0, y, r],
            0.003,
            0.002,
            LEAF,
        )?;
    }
    single(b.finish()?, vec![])
}

/// Bread: a loaf with a domed top (`baguette` is long and thin, scored).
fn bread(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let crust = ctx.color;
    if ctx.variant == "baguette" {
        b.add_ellipsoid([0.0, 0.0, h / 2.0], [w / 2.0, d / 2.0, h / 2.0], crust)?;
    } else {
        b.add_rounded_box([0.0, 0.0, h * 0.3], [w, d, h * 0.6], 0.02, crust)?;
        b.add_ellipsoid(
            [0.0, 0.0, h * 0.6],
            [w / 2.0 * 0.97, d / 2.0 * 0.95, h * 0.4],
            shade(crust, 1.1),
        )?;
    }
    for k in 0..3 {
        let x = (k as f64 - 1.0) * w * 0.25;
        b.add_detail(
            [x, 0.0, h - 0.002],
            [w * 0.08, d * 0.5, 0.004],
            shade(crust, 1.4),
        );
    }
    single(b.finish()?, vec![])
}

/// Cheese wedge: a triangular prism with a rind.
fn cheese(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let tri = [[-w / 2.0, -d / 2.0], [w / 2.0, 0.0], [-w / 2.0, d / 2.0]];
    b.add_part(
        crate::geometry::mesh::prism_mesh(&tri, 0.0, h),
        crate::geometry::ConvexPiece::prism(&tri, 0.0, h)?,
        ctx.color,
    );
    b.add_detail(
        [-w / 2.0 - 0.0005, 0.0, h / 2.0],
        [0.002, d, h],
        shade(ctx.color, 0.8),
    );
    single(b.finish()?, vec![])
}

/// Round cake: two layers of sponge with cream, on a board.
fn cake(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0;
    b.add_cylinder([0.0, 0.0], r, 0.0, 0.006, [0.85, 0.85, 0.85])?;
    b.add_cylinder([0.0, 0.0], r * 0.92, 0.006, h, ctx.color)?;
    b.add_visual(
        crate::geometry::mesh::cylinder_mesh(0.0, 0.0, r * 0.925, h * 0.45, h * 0.52, 24),
        [0.98, 0.96, 0.9],
    );
    for k in 0..8 {
        let a = std::f64::consts::TAU * k as f64 / 8.0;
        b.add_visual(
            super::shapes::ellipsoid_mesh(
                [r * 0.75 * a.cos(), r * 0.75 * a.sin(), h - 0.004],
                [0.008, 0.008, 0.008],
                8,
            ),
            [0.8, 0.1, 0.15],
        );
    }
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [r, r], 0.1)],
    )
}
