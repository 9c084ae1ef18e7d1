//! Floor-standing miscellany: potted plants (and small, cactus and hanging variants), coat
//! racks, step ladders, barrels, aquariums on stands, trash cans, rocking horses, easels.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::parts::{BLACK, LEAF, METAL, SOIL, body, shade, single, surface};
use super::shapes;
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::LinkBuilder;
use crate::geometry::{ConvexPiece, GeometryError};
use crate::scene::Pose;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("potted_plant", potted_plant),
    ("coat_rack", coat_rack),
    ("ladder", ladder),
    ("barrel", barrel),
    ("aquarium", aquarium),
    ("trash_can", trash_can),
    ("rocking_horse", rocking_horse),
    ("easel", easel),
];

/// An ellipsoid leaf from `base` along `dir` of length `len`, width `wid`.
pub(super) fn leaf(
    b: &mut LinkBuilder,
    base: [f64; 3],
    dir: Vector3<f64>,
    len: f64,
    wid: f64,
    color: [f64; 3],
) -> Result<(), GeometryError> {
    let dir = dir.normalize();
    let rot = UnitQuaternion::rotation_between(&Vector3::z(), &dir)
        .unwrap_or_else(UnitQuaternion::identity);
    let c = Vector3::from(base) + dir * (len / 2.0);
    let pose = Pose(Isometry3::from_parts(Translation3::from(c), rot));
    let radii = [wid / 2.0, (wid * 0.18).max(0.003), len / 2.0];
    b.add_part(
        shapes::ellipsoid_mesh([0.0; 3], radii, 12).transformed(&pose),
        shapes::ellipsoid_piece([0.0; 3], radii)?.transformed(&pose),
        color,
    );
    Ok(())
}

/// Pot with soil, a stem and a crown of leaves filling the size; `small` is a table plant,
/// `cactus` a columnar cactus, `hanging` hangs from the ceiling on cords (top at z = 0).
fn potted_plant(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let hanging = ctx.variant == "hanging";
    let mut b = body(ctx);
    let r_top = w.min(d) / 2.0
        * match ctx.variant {
            "hanging" => 0.6,
            "cactus" => 0.9,
            _ => 0.55,
        };
    let pot_h = (h * if ctx.variant == "small" { 0.4 } else { 0.3 }).min(r_top * 2.4);
    // A hanging pot hangs at mid height so its vines can trail below it.
    let z0 = if hanging { -0.45 * h - pot_h } else { 0.0 };
    let pot_color = ctx.color;
    // Pot and soil as one solid (a filled pot weighs what wet soil does).
    b.density(1100.0);
    b.add_solid_lathe(
        &[
            (r_top * 0.72, z0),
            (r_top * 0.96, z0 + pot_h * 0.92),
            (r_top, z0 + pot_h),
        ],
        pot_color,
    )?;
    b.material_density();
    b.add_visual(
        shapes::solid_lathe_mesh(
            &[
                (r_top * 0.97, z0 + pot_h - 0.001),
                (r_top * 0.97, z0 + pot_h + 0.004),
            ],
            24,
        ),
        SOIL,
    );
    b.density(150.0);
    let top = if hanging { 0.0 } else { h };
    let crown_base = z0 + pot_h;
    if ctx.variant == "cactus" {
        let r = r_top * 0.3;
        b.add_solid_lathe(
            &[
                (r * 0.9, crown_base),
                (r, crown_base + 0.05),
                (r, top - r),
                (r * 0.6, top - r * 0.3),
                (0.01, top),
            ],
            [0.15, 0.4, 0.15],
        )?;
        let arm_z = crown_base + (top - crown_base) * 0.5;
        for sx in [-1.0, 1.0] {
            let ax = sx * (w / 2.0 - r * 0.8);
            b.add_rod(
                [0.0, 0.0, arm_z],
                [ax, 0.0, arm_z],
                r * 0.55,
                [0.15, 0.4, 0.15],
            )?;
            b.add_rod(
                [ax, 0.0, arm_z],
                [ax, 0.0, arm_z + (top - arm_z) * 0.6],
                r * 0.55,
                [0.15, 0.4, 0.15],
            )?;
        }
        return single(b.finish()?, vec![]);
    }
    if hanging {
        b.add_frustum(
            [0.0, 0.0, -0.012],
            [0.0, 0.0, 0.0],
            0.03,
            0.035,
            shade(pot_color, 0.6),
        )?;
        for i in 0..3 {
            let a = std::f64::consts::TAU * i as f64 / 3.0;
            b.add_rod(
                [r_top * 0.9 * a.cos(), r_top * 0.9 * a.sin(), crown_base],
                [0.0, 0.0, -0.005],
                0.003,
                shade(pot_color, 0.6),
            )?;
        }
        // Trailing vines over the rim, down to the bottom of the size box.
        let n = 8;
        let out = w.min(d) / 2.0 * 0.92 - r_top;
        let drop = crown_base + h - 0.02;
        for i in 0..n {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let dir = Vector3::new(out * a.cos(), out * a.sin(), -drop);
            let len = (out * out + drop * drop).sqrt() * if i % 2 == 0 { 1.0 } else { 0.7 };
            leaf(
                &mut b,
                [r_top * a.cos(), r_top * a.sin(), crown_base],
                dir,
                len,
                0.045,
                LEAF,
            )?;
        }
        return single(b.finish()?, vec![]);
    }
    // Stem and leaves.
    let stem_top = crown_base + (top - crown_base) * 0.45;
    b.add_rod(
        [0.0, 0.0, crown_base - 0.02],
        [0.0, 0.0, stem_top],
        (r_top * 0.08).clamp(0.004, 0.025),
        [0.35, 0.25, 0.12],
    )?;
    let n = if ctx.variant == "small" { 7 } else { 11 };
    let reach = w.min(d) / 2.0;
    let mut rng_angle = ctx.uniform(0.0, 1.0);
    for i in 0..n {
        rng_angle += 0.618_034;
        let a = std::f64::consts::TAU * rng_angle;
        let up = 0.6 + 0.9 * (i as f64 / n as f64);
        let base_z = crown_base + (stem_top - crown_base) * (0.3 + 0.7 * i as f64 / n as f64);
        let len = ((top - base_z) / (up / (1.0 + up * up).sqrt()))
            .min(reach * 1.6)
            .max(0.03);
        let dir = Vector3::new(a.cos(), a.sin(), up);
        // Keep the leaf tip inside the size box.
        let tip = Vector3::new(0.0, 0.0, base_z) + dir.normalize() * len;
        let scale = (reach * 0.95 / tip.x.abs().max(1e-9))
            .min(reach * 0.95 / tip.y.abs().max(1e-9))
            .min((top - base_z) / (tip.z - base_z).max(1e-9))
            .min(1.0);
        let shade_k = 0.8 + 0.4 * ctx.uniform(0.0, 1.0);
        leaf(
            &mut b,
            [0.0, 0.0, base_z],
            dir,
            len * scale,
            (len * scale * 0.28).max(0.01),
            shade(LEAF, shade_k),
        )?;
    }
    // A central shoot up to the full height, and two leaves reaching the full width.
    leaf(
        &mut b,
        [0.0, 0.0, stem_top],
        Vector3::z(),
        top - stem_top,
        ((top - stem_top) * 0.2).max(0.01),
        LEAF,
    )?;
    for sx in [-1.0, 1.0] {
        let dir = Vector3::new(sx * (reach - 0.01), 0.0, (top - stem_top) * 0.4);
        let len = dir.norm();
        leaf(
            &mut b,
            [0.0, 0.0, stem_top],
            dir,
            len,
            (len * 0.25).max(0.01),
            shade(LEAF, 0.9),
        )?;
    }
    single(b.finish()?, vec![])
}

/// Coat rack: a weighted base, a pole and hooks at the top.
fn coat_rack(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = w.min(d) / 2.0;
    for i in 0..4 {
        let a = std::f64::consts::TAU * i as f64 / 4.0;
        b.add_rod(
            [0.0, 0.0, 0.12],
            [(r - 0.02) * a.cos(), (r - 0.02) * a.sin(), 0.02],
            0.018,
            ctx.color,
        )?;
    }
    b.add_rod([0.0, 0.0, 0.0], [0.0, 0.0, h - 0.04], 0.022, ctx.color)?;
    b.add_ellipsoid([0.0, 0.0, h - 0.03], [0.03, 0.03, 0.03], ctx.color)?;
    for i in 0..6 {
        let a = std::f64::consts::TAU * i as f64 / 6.0;
        let z = h - 0.12 - 0.12 * (i % 2) as f64;
        b.add_tube(
            &[
                [0.0, 0.0, z - 0.06],
                [0.16 * a.cos(), 0.16 * a.sin(), z],
                [0.19 * a.cos(), 0.19 * a.sin(), z + 0.04],
            ],
            0.009,
            ctx.accent_color,
        )?;
    }
    single(b.finish()?, vec![])
}

/// Step ladder: an A-frame with steps at the front (+Y) and a top platform.
fn ladder(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let c = ctx.color;
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - 0.02);
        b.add_box([x, 0.0, h - 0.02], [0.04, 0.12, 0.04], c)?;
        b.add_leg([x, 0.03, h - 0.04], [x, d / 2.0 - 0.02], 0.02, c)?;
        b.add_leg([x, -0.03, h - 0.04], [x, -d / 2.0 + 0.02], 0.018, c)?;
    }
    let steps = ((h / 0.28).floor() as usize).max(2);
    let mut surfaces = Vec::new();
    for i in 1..steps {
        let t = i as f64 / steps as f64;
        let z = t * (h - 0.04);
        let y = d / 2.0 - 0.03 - t * (d / 2.0 - 0.06);
        b.add_box([0.0, y, z], [w - 0.06, 0.09, 0.025], shade(c, 0.9))?;
        surfaces.push(surface(
            &format!("step_{i}"),
            "body",
            [0.0, y, z + 0.0125],
            [w - 0.08, 0.08],
            0.3,
        ));
    }
    b.add_box([0.0, 0.0, h - 0.02], [w - 0.04, 0.2, 0.02], shade(c, 0.8))?;
    surfaces.push(surface("top", "body", [0.0, 0.0, h], [w - 0.06, 0.18], 0.5));
    single(b.finish()?, surfaces)
}

/// Barrel: bulging staves with metal hoops.
fn barrel(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let r = w.min(d) / 2.0;
    let mut b = body(ctx);
    b.shell(Some(0.025));
    let profile: Vec<(f64, f64)> = (0..=6)
        .map(|i| {
            let t = i as f64 / 6.0;
            (r * (0.86 + 0.14 * (std::f64::consts::PI * t).sin()), h * t)
        })
        .collect();
    b.add_solid_lathe(&profile, ctx.color)?;
    b.shell(None);
    for t in [0.08, 0.3, 0.7, 0.92] {
        let rr = r * (0.86 + 0.14 * (std::f64::consts::PI * t).sin()) + 0.002;
        b.add_visual(
            shapes::solid_lathe_mesh(&[(rr, h * t - 0.02), (rr, h * t + 0.02)], 32),
            ctx.accent_color,
        );
    }
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, 0.0, h],
            [r * 1.4, r * 1.4],
            0.5,
        )],
    )
}

/// Aquarium: a cabinet stand with a glass tank of water on top.
fn aquarium(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let stand_h = h * 0.55;
    b.shell(Some(0.018));
    b.add_box([0.0, 0.0, stand_h / 2.0], [w, d, stand_h], ctx.color)?;
    b.shell(None);
    let tank_h = h - stand_h - 0.03;
    let z0 = stand_h;
    let g = 0.008;
    b.density(2500.0);
    let glass = [0.75, 0.88, 0.92, 0.3];
    let panes: [([f64; 3], [f64; 3]); 5] = [
        ([0.0, 0.0, z0 + g / 2.0], [w, d, g]),
        ([0.0, d / 2.0 - g / 2.0, z0 + tank_h / 2.0], [w, g, tank_h]),
        ([0.0, -d / 2.0 + g / 2.0, z0 + tank_h / 2.0], [w, g, tank_h]),
        (
            [w / 2.0 - g / 2.0, 0.0, z0 + tank_h / 2.0],
            [g, d - 2.0 * g, tank_h],
        ),
        (
            [-w / 2.0 + g / 2.0, 0.0, z0 + tank_h / 2.0],
            [g, d - 2.0 * g, tank_h],
        ),
    ];
    for (c, s) in panes {
        b.add_part_rgba(
            crate::geometry::mesh::box_mesh(c, s),
            ConvexPiece::cuboid(c, s)?,
            glass,
        );
    }
    // Water fills the tank (collision included: it weighs).
    b.density(1000.0);
    let wc = [0.0, 0.0, z0 + g + (tank_h * 0.85) / 2.0];
    let ws = [w - 2.0 * g - 0.002, d - 2.0 * g - 0.002, tank_h * 0.85];
    b.add_part_rgba(
        crate::geometry::mesh::box_mesh(wc, ws),
        ConvexPiece::cuboid(wc, ws)?,
        [0.25, 0.5, 0.7, 0.45],
    );
    b.material_density();
    b.add_box([0.0, 0.0, h - 0.015], [w, d, 0.03], BLACK)?;
    // Gravel, a plant.
    b.add_detail(
        [0.0, 0.0, z0 + g + 0.01],
        [w - 0.03, d - 0.03, 0.02],
        [0.6, 0.55, 0.45],
    );
    leaf(
        &mut b,
        [w * 0.25, 0.0, z0 + g + 0.02],
        Vector3::new(0.1, 0.0, 1.0),
        tank_h * 0.6,
        0.04,
        LEAF,
    )?;
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [w, d], 0.3)],
    )
}

/// Trash can: an open tapered bin, a pedal bin lid ring; `laundry` is a basket-like hamper.
fn trash_can(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let r = w.min(d) / 2.0;
    let mut b = body(ctx);
    let outer = [(r * 0.85, 0.0), (r * 0.97, h * 0.9), (r, h)];
    b.add_vessel([0.0, 0.0, 0.0], &outer, 0.004, 0.01, 12, ctx.color)?;
    if ctx.variant != "laundry" {
        b.add_visual(
            shapes::solid_lathe_mesh(&[(r * 0.99, h - 0.02), (r * 1.0, h - 0.0)], 32),
            shade(ctx.color, 0.7),
        );
    }
    single(
        b.finish()?,
        vec![surface(
            "inside",
            "body",
            [0.0, 0.0, 0.01],
            [r * 1.2, r * 1.2],
            h - 0.01,
        )],
    )
}

/// Rocking horse: a horse body on legs standing on curved rockers.
fn rocking_horse(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let c = ctx.color;
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - 0.03);
        let n = 8;
        let pts: Vec<[f64; 3]> = (0..=n)
            .map(|i| {
                let t = i as f64 / n as f64 * 2.0 - 1.0;
                let u = ((t.abs() - 0.4).max(0.0) / 0.6).powi(2);
                [x, t * (d / 2.0 - 0.03), 0.025 + 0.08 * u]
            })
            .collect();
        b.add_tube(&pts, 0.025, shade(c, 0.7))?;
    }
    let body_z = h * 0.55;
    b.add_ellipsoid([0.0, 0.0, body_z], [w * 0.25, d * 0.3, h * 0.12], c)?;
    for sy in [-1.0, 1.0] {
        for sx in [-1.0, 1.0] {
            b.add_rod(
                [sx * w * 0.1, sy * d * 0.2, body_z - h * 0.05],
                [sx * (w / 2.0 - 0.03), sy * d * 0.25, 0.05],
                0.02,
                c,
            )?;
        }
    }
    // Neck and head toward +Y.
    b.add_rod(
        [0.0, d * 0.22, body_z + h * 0.05],
        [0.0, d * 0.3, h - 0.12],
        0.05,
        c,
    )?;
    b.add_ellipsoid([0.0, d * 0.36, h - 0.09], [0.06, d * 0.12, 0.07], c)?;
    b.add_ellipsoid([0.0, d * 0.26, h - 0.1], [0.02, 0.06, 0.09], BLACK)?;
    b.add_rod(
        [0.0, -d * 0.25, body_z],
        [0.0, -d / 2.0 + 0.05, body_z - 0.1],
        0.025,
        BLACK,
    )?;
    b.add_detail(
        [0.0, -d * 0.02, body_z + h * 0.12],
        [w * 0.35, d * 0.2, 0.03],
        [0.6, 0.1, 0.1],
    );
    single(b.finish()?, vec![])
}

/// Easel: a tripod frame leaning back, a ledge and a canvas.
fn easel(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let c = ctx.color;
    for sx in [-1.0, 1.0] {
        b.add_leg(
            [sx * 0.05, 0.0, h - 0.016],
            [sx * (w / 2.0 - 0.016), d / 2.0 - 0.05],
            0.015,
            c,
        )?;
    }
    b.add_leg([0.0, -0.02, h * 0.7], [0.0, -d / 2.0 + 0.016], 0.015, c)?;
    let ledge_z = h * 0.4;
    let ly = d / 2.0 - 0.05 - (d / 2.0 - 0.05) * ledge_z / h;
    b.add_box([0.0, ly + 0.02, ledge_z], [w - 0.05, 0.06, 0.02], c)?;
    let canvas_h = h * 0.45;
    b.add_box(
        [0.0, ly + 0.01, ledge_z + 0.01 + canvas_h / 2.0],
        [w * 0.8, 0.02, canvas_h],
        [0.95, 0.94, 0.9],
    )?;
    b.add_detail(
        [0.0, ly + 0.0205, ledge_z + 0.01 + canvas_h / 2.0],
        [w * 0.6, 0.001, canvas_h * 0.7],
        [0.3, 0.5, 0.7],
    );
    let _ = METAL;
    single(
        b.finish()?,
        // The strip of ledge in front of the canvas (brushes, a paint tube).
        vec![surface(
            "ledge",
            "body",
            [0.0, ly + 0.035, ledge_z + 0.01],
            [w - 0.05, 0.03],
            0.1,
        )],
    )
}
