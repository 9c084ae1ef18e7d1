//! Decor, containers and textiles (manipulands, bottom at z = 0): vases, flowers, candles,
//! picture frames, table clocks, books, magazines, boxes, baskets, bins, towels, pillows,
//! shoes, globes, trophies, statuettes, pens and pencils. Toys and sports items are in
//! [`super::toys`].

use nalgebra::Vector3;

use super::misc::leaf;
use super::parts::{BLACK, LEAF, METAL, WHITE, body, shade, single, surface};
use super::shapes;
use super::{GenContext, Generated, GeneratorFn};
use crate::geometry::{ConvexPiece, GeometryError, mesh};

/// Silvered glass as a diffuse colour: a light blue-grey.
const MIRROR_GLASS: [f64; 3] = [0.78, 0.83, 0.86];

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("vase", vase),
    ("flowers", flowers),
    ("candle", candle),
    ("paper_roll", paper_roll),
    ("picture_frame", picture_frame),
    ("table_clock", table_clock),
    ("book", book),
    ("box", box_),
    ("basket", basket),
    ("bin", bin),
    ("towel", towel),
    ("pillow", pillow),
    ("shoe", shoe),
    ("globe", globe),
    ("trophy", trophy),
    ("statuette", statuette),
    ("pen", pen),
];

/// Vase: an open bellied vessel with a neck.
fn vase(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r = w / 2.0;
    let mut b = body(ctx);
    let outer = [
        (r * 0.6, 0.0),
        (r, h * 0.35),
        (r * 0.85, h * 0.6),
        (r * 0.45, h * 0.85),
        (r * 0.55, h),
    ];
    b.add_vessel([0.0; 3], &outer, 0.004, 0.01, 10, ctx.color)?;
    single(
        b.finish()?,
        vec![surface(
            "inside",
            "body",
            [0.0, 0.0, 0.01],
            [r * 0.6, r * 0.6],
            h,
        )],
    )
}

/// Flowers in a vase: a short vase, green stems and coloured blossoms.
fn flowers(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let vr = w.min(d) / 2.0 * 0.45;
    let vh = h * 0.4;
    b.add_vessel(
        [0.0; 3],
        &[(vr * 0.8, 0.0), (vr, vh * 0.6), (vr * 0.7, vh)],
        0.003,
        0.008,
        8,
        [0.8, 0.88, 0.92],
    )?;
    // One bloom in the middle and eight around it, the outer ones reaching the full width.
    let n = 9;
    let reach = w.min(d) / 2.0 - 0.03;
    for i in 0..n {
        let a = std::f64::consts::TAU * (i as f64 - 1.0) / 8.0;
        let spread = if i == 0 {
            0.0
        } else {
            reach * if i % 2 == 1 { 1.0 } else { 0.7 }
        };
        let top = [
            spread * a.cos(),
            spread * a.sin(),
            h - 0.025 - 0.06 * ((i % 2) as f64),
        ];
        b.add_visual(
            shapes::frustum_mesh([0.0, 0.0, vh * 0.5], top, 0.003, 0.003, 6),
            LEAF,
        );
        let color = ctx.palette(i);
        b.add_ellipsoid(
            top,
            [0.03, 0.03, 0.025],
            if ctx.style.is_none() {
                [
                    [0.8, 0.1, 0.2],
                    [0.95, 0.8, 0.1],
                    [0.9, 0.5, 0.7],
                    [0.95, 0.95, 0.9],
                ][i % 4]
            } else {
                color
            },
        )?;
        if i % 3 == 1 {
            leaf(
                &mut b,
                [top[0] * 0.5, top[1] * 0.5, vh + (top[2] - vh) * 0.4],
                Vector3::new(a.cos(), a.sin(), 0.6),
                reach * 0.35,
                0.02,
                LEAF,
            )?;
        }
    }
    single(b.finish()?, vec![])
}

/// Candle: a wax cylinder with a wick and flame (`pillar` is wide and short).
fn candle(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r = w / 2.0;
    let mut b = body(ctx);
    let wax_h = h - 0.02;
    b.add_cylinder([0.0, 0.0], r, 0.0, wax_h, ctx.color)?;
    b.add_visual(
        shapes::frustum_mesh(
            [0.0, 0.0, wax_h],
            [0.0, 0.0, wax_h + 0.006],
            0.001,
            0.001,
            6,
        ),
        BLACK,
    );
    b.add_visual(
        shapes::ellipsoid_mesh([0.0, 0.0, wax_h + 0.012], [0.004, 0.004, 0.008], 8),
        [1.0, 0.7, 0.2],
    );
    single(b.finish()?, vec![])
}

/// Roll of toilet paper or paper towel: a soft cylinder around a cardboard core, the core's
/// hole shown on its top (the collision is the solid cylinder: nothing goes in the hole).
fn paper_roll(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r = w / 2.0;
    let core = (r * 0.4).max(0.02);
    let mut b = body(ctx);
    // Loosely wound paper around air: weighed as an 8 mm shell of the cylinder (a toilet
    // roll about 0.12 kg, a kitchen roll about 0.25 kg).
    b.shell(Some(0.008));
    b.add_cylinder([0.0, 0.0], r, 0.0, h, ctx.color)?;
    b.shell(None);
    b.add_visual(
        shapes::frustum_mesh(
            [0.0, 0.0, h - 0.0002],
            [0.0, 0.0, h + 0.0004],
            core,
            core,
            24,
        ),
        [0.55, 0.42, 0.28],
    );
    single(b.finish()?, vec![])
}

/// Picture frame standing on a table: a frame with a photo, leaning back on a strut. Variant
/// `mirror`: a table (hand) mirror, the same frame with a silvered glass face.
fn picture_frame(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let t = 0.015;
    let tilt: f64 = 0.18;
    let pose = crate::scene::Pose(nalgebra::Isometry3::from_parts(
        nalgebra::Translation3::new(0.0, d / 2.0 - t / 2.0, 0.0),
        nalgebra::UnitQuaternion::from_axis_angle(&Vector3::x_axis(), tilt),
    ));
    let fh = h / tilt.cos();
    let frame_size = [w, t, fh];
    b.add_part(
        mesh::box_mesh([0.0, 0.0, fh / 2.0], frame_size).transformed(&pose),
        ConvexPiece::cuboid([0.0, 0.0, fh / 2.0], frame_size)?.transformed(&pose),
        ctx.color,
    );
    let photo = mesh::box_mesh(
        [0.0, t / 2.0 + 0.0005, fh / 2.0],
        [w * 0.75, 0.001, fh * 0.75],
    )
    .transformed(&pose);
    let face = if ctx.variant == "mirror" {
        MIRROR_GLASS
    } else {
        ctx.palette(1)
    };
    b.add_visual(photo, face);
    b.add_rod(
        [0.0, d / 2.0 - t - fh * 0.3 * tilt.sin(), fh * 0.3],
        [0.0, -d / 2.0 + 0.004, 0.004],
        0.004,
        shade(ctx.color, 0.7),
    )?;
    single(b.finish()?, vec![])
}

/// Table (alarm) clock: a round face in a case on two feet.
fn table_clock(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let r = (w.min(h) / 2.0) * 0.92;
    let mut b = body(ctx);
    let zc = h - r;
    b.add_part(
        shapes::frustum_mesh([0.0, -d / 2.0, zc], [0.0, d / 2.0, zc], r, r, 32),
        shapes::frustum_piece([0.0, -d / 2.0, zc], [0.0, d / 2.0, zc], r, r, 16)?,
        ctx.color,
    );
    b.add_visual(
        shapes::frustum_mesh(
            [0.0, d / 2.0 - 0.001, zc],
            [0.0, d / 2.0 + 0.0005, zc],
            r * 0.85,
            r * 0.85,
            32,
        ),
        WHITE,
    );
    b.add_detail(
        [0.0, d / 2.0 + 0.001, zc + r * 0.25],
        [0.004, 0.001, r * 0.5],
        BLACK,
    );
    b.add_detail(
        [r * 0.18, d / 2.0 + 0.0012, zc],
        [r * 0.36, 0.001, 0.004],
        BLACK,
    );
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * r * 0.6, 0.0, (zc - r * 0.8).max(0.004) / 2.0],
            [0.01, d * 0.6, (zc - r * 0.8).max(0.004)],
            BLACK,
        )?;
    }
    single(b.finish()?, vec![])
}

/// Book standing upright: spine towards +Y, thickness along X, height along Z (`magazine`
/// lies flat: thin along z).
fn book(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [t, d, h] = ctx.size;
    const COVERS: [[f64; 3]; 8] = [
        [0.55, 0.10, 0.10],
        [0.10, 0.25, 0.50],
        [0.12, 0.40, 0.20],
        [0.80, 0.60, 0.15],
        [0.30, 0.30, 0.32],
        [0.45, 0.15, 0.40],
        [0.85, 0.85, 0.80],
        [0.10, 0.10, 0.12],
    ];
    let cover = COVERS[ctx.uniform(0.0, COVERS.len() as f64) as usize % COVERS.len()];
    let mut b = body(ctx);
    if ctx.variant == "magazine" {
        b.add_box([0.0, 0.0, h / 2.0], [t, d, h], [0.95, 0.94, 0.9])?;
        b.add_detail([0.0, 0.0, h + 0.0003], [t * 0.98, d * 0.98, 0.0006], cover);
        b.add_detail(
            [0.0, d * 0.3, h + 0.0007],
            [t * 0.8, d * 0.15, 0.0004],
            shade(cover, 0.4),
        );
        return single(b.finish()?, vec![]);
    }
    // One collision box for the whole book; visuals show covers and a page block.
    b.add_collision(ConvexPiece::cuboid([0.0, 0.0, h / 2.0], [t, d, h])?);
    let c = 0.0025_f64.min(t * 0.2);
    b.add_visual(
        mesh::box_mesh([-(t - c) / 2.0, 0.0, h / 2.0], [c, d, h]),
        cover,
    );
    b.add_visual(
        mesh::box_mesh([(t - c) / 2.0, 0.0, h / 2.0], [c, d, h]),
        cover,
    );
    b.add_visual(
        mesh::box_mesh([0.0, d / 2.0 - c / 2.0, h / 2.0], [t - 2.0 * c, c, h]),
        shade(cover, 0.8),
    );
    b.add_visual(
        mesh::box_mesh(
            [0.0, -c / 2.0, h / 2.0],
            [t - 2.0 * c, d - c - 0.004, h - 0.006],
        ),
        [0.95, 0.93, 0.86],
    );
    single(b.finish()?, vec![])
}

/// Closed boxes: `""` cardboard box with tape, `package` (pasta, cereal: printed carton),
/// `gift` (ribbon), `pill` (small pill box). Weigh as shells.
fn box_(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.shell(Some(0.003_f64.min(w.min(d).min(h) / 5.0)));
    b.add_box([0.0, 0.0, h / 2.0], [w, d, h], ctx.color)?;
    b.shell(None);
    match ctx.variant {
        "gift" => {
            b.add_detail(
                [0.0, 0.0, h / 2.0],
                [w * 0.12, d + 0.002, h + 0.002],
                ctx.palette(0),
            );
            b.add_detail(
                [0.0, 0.0, h / 2.0],
                [w + 0.002, d * 0.12, h + 0.002],
                ctx.palette(0),
            );
        }
        "package" => {
            b.add_detail(
                [0.0, d / 2.0 + 0.0005, h * 0.6],
                [w * 0.8, 0.001, h * 0.35],
                ctx.palette(2),
            );
            b.add_detail(
                [0.0, d / 2.0 + 0.0008, h * 0.25],
                [w * 0.5, 0.001, h * 0.12],
                WHITE,
            );
        }
        "pill" => {
            b.add_detail([0.0, 0.0, h + 0.0005], [w * 0.8, d * 0.8, 0.001], WHITE);
        }
        _ => {
            b.add_detail(
                [0.0, 0.0, h + 0.0005],
                [w + 0.001, 0.05_f64.min(d * 0.3), 0.001],
                [0.75, 0.62, 0.4],
            );
        }
    }
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [w, d], 0.3)],
    )
}

/// Baskets: an open woven vessel with a carrying handle (`shopping` is a rectangular plastic
/// basket, `fruit` a low bowl-like basket).
fn basket(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    if ctx.variant == "shopping" {
        return open_box(ctx, b, w, d, h, 0.006, true);
    }
    // Built round, then stretched to an oval w x d.
    let r = d / 2.0;
    let sx = w / d;
    let rim_h = if ctx.variant == "fruit" { h } else { h * 0.6 };
    let outer = [(r * 0.75, 0.0), (r * 0.95, rim_h * 0.6), (r, rim_h)];
    b.add_vessel_scaled([0.0; 3], &outer, 0.008, 0.01, 12, [sx, 1.0], ctx.color)?;
    for k in 1..4 {
        let z = rim_h * k as f64 / 4.0;
        let rr = r * (0.75 + 0.25 * k as f64 / 4.0) + 0.001;
        b.add_visual(
            shapes::solid_lathe_mesh(&[(rr, z - 0.004), (rr, z + 0.004)], 24)
                .scaled([sx, 1.0, 1.0]),
            shade(ctx.color, 0.75),
        );
    }
    if ctx.variant != "fruit" {
        let n = 6;
        let pts: Vec<[f64; 3]> = (0..=n)
            .map(|i| {
                let a = std::f64::consts::PI * i as f64 / n as f64;
                [
                    r * sx * 0.95 * a.cos(),
                    0.0,
                    rim_h + (h - rim_h - 0.007) * a.sin(),
                ]
            })
            .collect();
        b.add_tube(&pts, 0.007, shade(ctx.color, 0.8))?;
    }
    single(
        b.finish()?,
        vec![surface(
            "inside",
            "body",
            [0.0, 0.0, 0.01],
            [r * 1.2 * sx, r * 1.2],
            rim_h,
        )],
    )
}

/// An open rectangular box: floor and four walls `t` thick; with `handles`, two handles.
fn open_box(
    ctx: &GenContext,
    mut b: crate::assets::LinkBuilder,
    w: f64,
    d: f64,
    h: f64,
    t: f64,
    handles: bool,
) -> Result<Generated, GeometryError> {
    let wall_h = if handles { h * 0.75 } else { h };
    b.add_box([0.0, 0.0, t / 2.0], [w, d, t], ctx.color)?;
    for sy in [-1.0, 1.0] {
        b.add_box(
            [0.0, sy * (d / 2.0 - t / 2.0), wall_h / 2.0 + t / 2.0],
            [w, t, wall_h - t],
            ctx.color,
        )?;
    }
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - t / 2.0), 0.0, wall_h / 2.0 + t / 2.0],
            [t, d - 2.0 * t, wall_h - t],
            shade(ctx.color, 0.92),
        )?;
    }
    if handles {
        for sx in [-1.0, 1.0] {
            let x = sx * w * 0.3;
            b.add_tube(
                &[
                    [x, -d / 2.0 + t, wall_h],
                    [x, -d / 4.0, h - 0.01],
                    [x, d / 4.0, h - 0.01],
                    [x, d / 2.0 - t, wall_h],
                ],
                0.005,
                BLACK,
            )?;
        }
    }
    single(
        b.finish()?,
        vec![surface(
            "inside",
            "body",
            [0.0, 0.0, t],
            [w - 2.0 * t, d - 2.0 * t],
            wall_h - t,
        )],
    )
}

/// Storage / toy bin: an open rectangular box (`round` is a round tub).
fn bin(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let b = body(ctx);
    let t = (w.min(d) * 0.02).clamp(0.004, 0.012);
    if ctx.variant == "round" {
        let mut b = b;
        let r = w.min(d) / 2.0;
        b.add_vessel([0.0; 3], &[(r * 0.9, 0.0), (r, h)], t, t, 12, ctx.color)?;
        return single(
            b.finish()?,
            vec![surface(
                "inside",
                "body",
                [0.0, 0.0, t],
                [r * 1.2, r * 1.2],
                h - t,
            )],
        );
    }
    open_box(ctx, b, w, d, h, t, false)
}

/// Folded towel (or blanket): a stack of rounded layers.
fn towel(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let layers = 3;
    let lh = h / layers as f64;
    for i in 0..layers {
        b.add_rounded_box(
            [0.0, 0.0, lh * (i as f64 + 0.5)],
            [w, d, lh],
            lh * 0.45,
            shade(ctx.color, 0.95 + 0.05 * (i % 2) as f64),
        )?;
    }
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, 0.0, h],
            [w * 0.9, d * 0.9],
            0.3,
        )],
    )
}

/// Pillow / cushion: a puffy rounded slab.
fn pillow(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.add_rounded_box([0.0, 0.0, h / 2.0], [w, d, h], h * 0.45, ctx.color)?;
    b.add_ellipsoid(
        [0.0, 0.0, h / 2.0],
        [w * 0.42, d * 0.42, h / 2.0],
        ctx.color,
    )?;
    single(b.finish()?, vec![])
}

/// Shoe along y (toe at +Y): a sole and an upper.
fn shoe(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let sole = 0.02_f64.min(h * 0.25);
    b.add_rounded_box([0.0, 0.0, sole / 2.0], [w, d, sole], sole * 0.45, WHITE)?;
    b.add_ellipsoid(
        [0.0, d * 0.12, sole + (h - sole) * 0.35],
        [w / 2.0 * 0.95, d * 0.38, (h - sole) * 0.35],
        ctx.color,
    )?;
    b.add_rounded_box(
        [0.0, -d * 0.25, sole + (h - sole) / 2.0],
        [w * 0.95, d * 0.45, h - sole],
        0.02,
        ctx.color,
    )?;
    single(b.finish()?, vec![])
}

/// Desk globe: a sphere on a tilted axis over a stand.
fn globe(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = (w.min(d) / 2.0).min((h - 0.06) / 2.0);
    b.add_frustum(
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 0.02],
        r * 0.6,
        r * 0.5,
        ctx.accent_color,
    )?;
    b.add_rod(
        [0.0, 0.0, 0.02],
        [0.0, 0.0, h - 2.0 * r],
        0.008,
        ctx.accent_color,
    )?;
    b.shell(Some(0.003));
    b.add_ellipsoid([0.0, 0.0, h - r], [r, r, r], [0.15, 0.35, 0.7])?;
    b.shell(None);
    for (x, y, z, s) in [
        (0.5, 0.5, 0.2, 0.35),
        (-0.6, 0.3, -0.2, 0.3),
        (0.1, -0.7, 0.4, 0.3),
    ] {
        let v = Vector3::new(x, y, z).normalize() * (r * 0.93);
        b.add_visual(
            shapes::ellipsoid_mesh([v.x, v.y, h - r + v.z], [r * s, r * s, r * s * 0.8], 12),
            [0.25, 0.55, 0.2],
        );
    }
    single(b.finish()?, vec![])
}

/// Trophy cup: a base, a stem and a cup with handles.
fn trophy(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = d / 2.0;
    b.add_box([0.0, 0.0, h * 0.06], [w * 0.7, d, h * 0.12], BLACK)?;
    b.add_solid_lathe(
        &[
            (r * 0.2, h * 0.12),
            (r * 0.12, h * 0.35),
            (r * 0.25, h * 0.45),
        ],
        ctx.color,
    )?;
    b.add_vessel(
        [0.0, 0.0, h * 0.45],
        &[(r * 0.3, 0.0), (r * 0.8, h * 0.3), (r * 0.85, h * 0.55)],
        0.003,
        0.005,
        8,
        ctx.color,
    )?;
    for sx in [-1.0, 1.0] {
        b.add_tube(
            &[
                [sx * r * 0.8, 0.0, h * 0.9],
                [sx * (w / 2.0 - 0.005), 0.0, h * 0.85],
                [sx * r * 0.7, 0.0, h * 0.65],
            ],
            0.005,
            ctx.color,
        )?;
    }
    single(b.finish()?, vec![])
}

/// Statuette / sculpture: a figure on a plinth (head, torso, legs) or an abstract form.
fn statuette(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let plinth = h * 0.1;
    b.add_box(
        [0.0, 0.0, plinth / 2.0],
        [w, d, plinth],
        shade(ctx.color, 0.7),
    )?;
    if ctx.variant == "abstract" {
        b.add_ellipsoid(
            [0.0, 0.0, plinth + (h - plinth) * 0.3],
            [w * 0.4, d * 0.3, (h - plinth) * 0.3],
            ctx.color,
        )?;
        b.add_ellipsoid(
            [w * 0.1, 0.0, plinth + (h - plinth) * 0.75],
            [w * 0.2, d * 0.25, (h - plinth) * 0.25],
            ctx.color,
        )?;
        return single(b.finish()?, vec![]);
    }
    let fh = h - plinth;
    let c = ctx.color;
    for sx in [-1.0, 1.0] {
        b.add_frustum(
            [sx * w * 0.1, 0.0, plinth],
            [sx * w * 0.09, 0.0, plinth + fh * 0.45],
            w * 0.07,
            w * 0.09,
            c,
        )?;
    }
    b.add_frustum(
        [0.0, 0.0, plinth + fh * 0.45],
        [0.0, 0.0, plinth + fh * 0.8],
        w * 0.2,
        w * 0.25,
        c,
    )?;
    b.add_ellipsoid(
        [0.0, 0.0, plinth + fh * 0.89],
        [w * 0.1, d * 0.12, fh * 0.09],
        c,
    )?;
    for sx in [-1.0, 1.0] {
        b.add_frustum(
            [sx * w * 0.27, 0.0, plinth + fh * 0.78],
            [sx * w * 0.33, 0.0, plinth + fh * 0.45],
            w * 0.06,
            w * 0.05,
            c,
        )?;
    }
    single(b.finish()?, vec![])
}

/// Writing tools lying along x: `""` pen (body, clip, cap), `pencil` (hexagonal, sharpened
/// tip), `marker` (fat body, coloured cap).
fn pen(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = d.min(h) / 2.0;
    let tip = w * 0.12;
    match ctx.variant {
        "pencil" => {
            let ring: Vec<[f64; 2]> = mesh::circle_ring(0.0, r, r, 6);
            let x0 = -w / 2.0;
            let x1 = w / 2.0 - tip;
            b.add_part(
                shapes::yz_prism_mesh(&ring, x0, x1),
                shapes::yz_prism_piece(&ring, x0, x1)?,
                ctx.color,
            );
            b.add_frustum(
                [x1, 0.0, r],
                [w / 2.0, 0.0, r],
                r * 0.85,
                r * 0.1,
                [0.85, 0.7, 0.5],
            )?;
            b.add_visual(
                shapes::frustum_mesh(
                    [w / 2.0 - tip * 0.3, 0.0, r],
                    [w / 2.0, 0.0, r],
                    r * 0.3,
                    r * 0.05,
                    8,
                ),
                BLACK,
            );
            b.add_visual(
                shapes::frustum_mesh(
                    [x0 - 0.0005, 0.0, r],
                    [x0 + w * 0.06, 0.0, r],
                    r * 1.01,
                    r * 1.01,
                    12,
                ),
                [0.9, 0.5, 0.55],
            );
        }
        _ => {
            let cap = if ctx.variant == "marker" {
                w * 0.3
            } else {
                w * 0.25
            };
            b.add_rod(
                [-w / 2.0 + cap, 0.0, r],
                [w / 2.0 - tip, 0.0, r],
                r * 0.92,
                if ctx.variant == "marker" {
                    WHITE
                } else {
                    ctx.color
                },
            )?;
            b.add_frustum(
                [w / 2.0 - tip, 0.0, r],
                [w / 2.0, 0.0, r],
                r * 0.8,
                r * 0.25,
                METAL,
            )?;
            b.add_rod([-w / 2.0, 0.0, r], [-w / 2.0 + cap, 0.0, r], r, ctx.color)?;
        }
    }
    single(b.finish()?, vec![])
}
