//! Electronics (manipulands, bottom at z = 0, screens facing +Y): laptops (lid on a hinge),
//! monitors and TVs on stands, keyboards, mice, phones / tablets / remotes, desktop
//! computers, printers, speakers, cash registers, projectors.
//!
//! Housings weigh as thin plastic or metal shells around their electronics, not as solid
//! blocks.

use super::parts::{BLACK, METAL, SCREEN, WHITE, body, shade, single, surface};
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::{Joint, JointKind, LinkBuilder};
use crate::geometry::GeometryError;
use crate::scene::Pose;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("laptop", laptop),
    ("monitor", monitor),
    ("keyboard", keyboard),
    ("computer_mouse", computer_mouse),
    ("phone", phone),
    ("computer", computer),
    ("printer", printer),
    ("speaker", speaker),
    ("cash_register", cash_register),
    ("projector", projector),
];

/// Effective density of electronics in a housing, kg/m^3.
const DEVICE: f64 = 600.0;

/// Laptop, closed at zero joint position: a base with a keyboard and a lid hinged along the
/// back edge that opens up to 130 degrees (typical working position about 110 degrees).
fn laptop(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let base_t = h * 0.55;
    let lid_t = h - base_t - 0.002;
    let mut b = body(ctx);
    b.density(DEVICE * 2.5);
    b.add_rounded_box([0.0, 0.0, base_t / 2.0], [w, d, base_t], 0.004, ctx.color)?;
    b.add_detail(
        [0.0, d * 0.08, base_t + 0.0003],
        [w * 0.85, d * 0.45, 0.0006],
        BLACK,
    );
    b.add_detail(
        [0.0, d * 0.36, base_t + 0.0003],
        [w * 0.3, d * 0.18, 0.0006],
        shade(ctx.color, 0.85),
    );
    let mut lid = LinkBuilder::new(
        "lid",
        Pose::from_xyz(0.0, -d / 2.0, base_t + 0.002 + lid_t),
        ctx.material,
    );
    lid.density(DEVICE * 2.5);
    lid.add_rounded_box(
        [0.0, d / 2.0, -lid_t / 2.0],
        [w, d, lid_t],
        0.003,
        ctx.color,
    )?;
    lid.add_detail(
        [0.0, d / 2.0, -lid_t - 0.0003],
        [w * 0.9, d * 0.85, 0.0006],
        SCREEN,
    );
    let joint = Joint {
        name: "lid_hinge".into(),
        kind: JointKind::Revolute,
        parent: "body".into(),
        child: "lid".into(),
        axis: [1.0, 0.0, 0.0],
        lower: 0.0,
        upper: 130f64.to_radians(),
        damping: 0.05,
        effort: 2.0,
    };
    Ok(Generated {
        links: vec![b.finish()?, lid.finish()?],
        joints: vec![joint],
        surfaces: vec![surface("top", "body", [0.0, 0.0, h], [w, d], 0.3)],
    })
}

/// Monitor (or `tv`): a thin screen panel on a neck and a foot.
fn monitor(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let foot_d = d;
    b.add_rounded_box(
        [0.0, 0.0, 0.01],
        [(w * 0.35).min(0.4), foot_d, 0.02],
        0.008,
        BLACK,
    )?;
    let panel_h = h * if ctx.variant == "tv" { 0.88 } else { 0.72 };
    let panel_t = if ctx.variant == "tv" { 0.05 } else { 0.03 };
    let y_panel = -d / 2.0 + panel_t / 2.0 + 0.01;
    b.add_box(
        [0.0, y_panel - 0.005, (h - panel_h) / 2.0 + 0.01],
        [0.05, 0.025, h - panel_h],
        BLACK,
    )?;
    b.density(DEVICE);
    b.shell(Some(0.002));
    b.add_rounded_box(
        [0.0, y_panel, h - panel_h / 2.0],
        [w, panel_t, panel_h],
        0.005,
        ctx.color,
    )?;
    b.shell(None);
    b.add_detail(
        [0.0, y_panel + panel_t / 2.0 + 0.0005, h - panel_h / 2.0],
        [w - 0.02, 0.001, panel_h - 0.02],
        SCREEN,
    );
    single(b.finish()?, vec![])
}

/// Keyboard: a low slab with rows of keys.
fn keyboard(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.density(DEVICE);
    b.add_rounded_box([0.0, 0.0, h * 0.35], [w, d, h * 0.7], 0.004, ctx.color)?;
    let rows = 5;
    for r in 0..rows {
        let y = -d / 2.0 + d * (r as f64 + 0.7) / (rows as f64 + 0.4);
        let n = if r == 0 { 5 } else { 14 };
        for k in 0..n {
            let kw = if r == 0 && k == 2 {
                w * 0.35
            } else {
                (w - 0.02) / 14.0 * 0.82
            };
            let x = if r == 0 {
                -w * 0.3 + k as f64 * w * 0.15
            } else {
                -w / 2.0 + 0.01 + (k as f64 + 0.5) * (w - 0.02) / 14.0
            };
            b.add_detail(
                [x, y, h * 0.7 + h * 0.12],
                [kw, d / 7.0, h * 0.24],
                shade(ctx.color, 1.25),
            );
        }
    }
    single(b.finish()?, vec![])
}

/// Computer mouse: a rounded shell with a button split.
fn computer_mouse(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.density(DEVICE);
    b.add_ellipsoid([0.0, 0.0, h / 2.0], [w / 2.0, d / 2.0, h / 2.0], ctx.color)?;
    b.add_detail([0.0, d * 0.25, h * 0.95], [0.002, d * 0.35, 0.004], BLACK);
    single(b.finish()?, vec![])
}

/// Handheld slabs: `""` phone and `tablet` (screen up), `remote` (buttons up).
fn phone(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.density(DEVICE * 3.0);
    b.add_rounded_box([0.0, 0.0, h / 2.0], [w, d, h], h * 0.45, ctx.color)?;
    if ctx.variant == "remote" {
        for k in 0..8 {
            let y = -d * 0.35 + k as f64 * d * 0.09;
            for sx in [-1.0, 0.0, 1.0] {
                b.add_detail(
                    [sx * w * 0.25, y, h + 0.001],
                    [w * 0.16, d * 0.04, 0.002],
                    if k == 7 && sx == 0.0 {
                        [0.8, 0.1, 0.1]
                    } else {
                        shade(ctx.color, 1.6)
                    },
                );
            }
        }
    } else {
        b.add_detail([0.0, 0.0, h + 0.0003], [w * 0.9, d * 0.92, 0.0006], SCREEN);
    }
    single(b.finish()?, vec![])
}

/// Desktop computer tower: a tall box with a front panel, vents and a power button.
fn computer(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.density(DEVICE);
    b.shell(Some(0.01));
    b.add_box([0.0, 0.0, h / 2.0], [w, d, h], ctx.color)?;
    b.shell(None);
    b.add_detail(
        [0.0, d / 2.0 + 0.001, h / 2.0],
        [w * 0.85, 0.002, h * 0.95],
        shade(ctx.color, 1.3),
    );
    b.add_detail(
        [0.0, d / 2.0 + 0.0025, h * 0.85],
        [0.015, 0.002, 0.015],
        [0.2, 0.5, 0.9],
    );
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [w, d], 0.2)],
    )
}

/// Office printer: a body with a paper tray in front and an output slot on top.
fn printer(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.density(DEVICE);
    b.shell(Some(0.005));
    b.add_rounded_box([0.0, -0.03, h / 2.0], [w, d - 0.06, h], 0.01, ctx.color)?;
    b.shell(None);
    b.add_box(
        [0.0, d / 2.0 - 0.035, 0.02],
        [w * 0.6, 0.07, 0.015],
        shade(ctx.color, 0.8),
    )?;
    b.add_detail([0.0, 0.0, h + 0.0005], [w * 0.7, d * 0.4, 0.001], BLACK);
    b.add_detail(
        [w * 0.3, d / 2.0 - 0.059, h * 0.8],
        [w * 0.2, 0.002, 0.04],
        [0.1, 0.4, 0.2],
    );
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, -0.03, h], [w, d - 0.06], 0.3)],
    )
}

/// Speaker: a box with two driver cones on the front.
fn speaker(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.shell(Some(0.012));
    b.add_box([0.0, 0.0, h / 2.0], [w, d, h], ctx.color)?;
    b.shell(None);
    let r1 = (w * 0.38).min(h * 0.2);
    let r2 = r1 * 0.45;
    b.add_visual(
        super::shapes::frustum_mesh(
            [0.0, d / 2.0 - 0.004, h * 0.32],
            [0.0, d / 2.0 + 0.001, h * 0.32],
            r1,
            r1 * 0.5,
            32,
        ),
        BLACK,
    );
    b.add_visual(
        super::shapes::frustum_mesh(
            [0.0, d / 2.0 - 0.004, h * 0.75],
            [0.0, d / 2.0 + 0.001, h * 0.75],
            r2,
            r2 * 0.5,
            24,
        ),
        BLACK,
    );
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [w, d], 0.3)],
    )
}

/// Cash register: a base with a cash drawer front, a keypad slope and a display on a post.
fn cash_register(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.density(DEVICE * 1.5);
    let base_h = h * 0.35;
    b.add_box([0.0, 0.0, base_h / 2.0], [w, d, base_h], ctx.color)?;
    b.add_detail(
        [0.0, d / 2.0 + 0.001, base_h / 2.0],
        [w * 0.8, 0.002, base_h * 0.6],
        shade(ctx.color, 0.7),
    );
    let slope = crate::assets::procedural::shapes::yz_prism_piece(
        &[
            [-d / 2.0, base_h],
            [d / 2.0 - 0.02, base_h],
            [-d / 2.0, base_h + h * 0.25],
        ],
        -w / 2.0,
        w / 2.0,
    )?;
    b.add_part(
        crate::assets::procedural::shapes::yz_prism_mesh(
            &[
                [-d / 2.0, base_h],
                [d / 2.0 - 0.02, base_h],
                [-d / 2.0, base_h + h * 0.25],
            ],
            -w / 2.0,
            w / 2.0,
        ),
        slope,
        shade(ctx.color, 1.1),
    );
    b.add_rod(
        [0.0, -d / 2.0 + 0.04, base_h + h * 0.2],
        [0.0, -d / 2.0 + 0.04, h - 0.06],
        0.012,
        BLACK,
    )?;
    b.add_box(
        [0.0, -d / 2.0 + 0.04, h - 0.035],
        [w * 0.4, 0.03, 0.07],
        BLACK,
    )?;
    b.add_detail(
        [0.0, -d / 2.0 + 0.056, h - 0.035],
        [w * 0.35, 0.002, 0.05],
        [0.2, 0.6, 0.3],
    );
    single(b.finish()?, vec![])
}

/// Projector: a box with a lens on the front.
fn projector(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.density(DEVICE);
    b.add_rounded_box([0.0, -0.01, h / 2.0], [w, d - 0.02, h], 0.015, ctx.color)?;
    let r = h * 0.32;
    b.add_rod(
        [w * 0.22, d / 2.0 - 0.025, h / 2.0],
        [w * 0.22, d / 2.0, h / 2.0],
        r,
        BLACK,
    )?;
    b.add_visual(
        super::shapes::frustum_mesh(
            [w * 0.22, d / 2.0 - 0.001, h / 2.0],
            [w * 0.22, d / 2.0 + 0.0005, h / 2.0],
            r * 0.7,
            r * 0.7,
            24,
        ),
        [0.3, 0.35, 0.5],
    );
    let _ = (WHITE, METAL);
    single(b.finish()?, vec![])
}
