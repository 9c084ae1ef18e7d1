//! Tableware and kitchenware (manipulands, bottom at z = 0): plates, saucers, bowls, cups,
//! mugs, glasses, wine glasses, bottles, cans, jars, pots, pans, cutting boards, trays,
//! teapots and kettles, cutlery, holders, food containers, toasters, coffee makers, tubes.
//!
//! Open vessels (bowls, cups, mugs, pots, holders) have real cavities: a base disc plus wall
//! sectors, so things put inside stay inside. Closed vessels (bottles, jars, cans) collide as
//! their solid outline but weigh as thin shells.

use super::parts::{BLACK, METAL, WHITE, body, shade, single, surface};
use super::shapes;
use super::{GenContext, Generated, GeneratorFn};
use crate::geometry::{ConvexPiece, GeometryError, mesh};

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("plate", plate),
    ("bowl", bowl),
    ("mug", mug),
    ("glass", glass),
    ("wine_glass", wine_glass),
    ("bottle", bottle),
    ("can", can),
    ("jar", jar),
    ("pot", pot),
    ("cutting_board", cutting_board),
    ("tray", tray),
    ("teapot", teapot),
    ("cutlery", cutlery),
    ("holder", holder),
    ("food_container", food_container),
    ("toaster", toaster),
    ("coffee_maker", coffee_maker),
    ("tube", tube),
];

/// Height of a plate rim's lowest edge above the plate's bottom, metres.
const RIM_LIFT: f64 = 0.0015;

/// Plate: a flat base disc and a sloped rim; plates nest when stacked. `saucer` is the same
/// smaller.
fn plate(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r_out = w / 2.0;
    let r_base = r_out * 0.68;
    let base_t = (h * 0.25).clamp(0.003, 0.007);
    // The rim is thinner than the base, so a plate nested on another rests base on base
    // with its rim clear of the rim below (a flat contact, not a ring of wedged rim pieces,
    // which costs Drake's contact solver several times as much per step).
    let rim_t = (h * 0.2).clamp(0.003, 0.006).min(base_t * 0.8);
    let mut b = body(ctx);
    let visual_profile = [
        (0.0, 0.0),
        (r_base, 0.0),
        (r_out, h - rim_t),
        (r_out, h),
        (r_base - 0.002, base_t),
        (0.0, base_t),
    ];
    b.add_visual(mesh::lathe_mesh(&visual_profile, 40), ctx.color);
    b.add_collision(ConvexPiece::cylinder(0.0, 0.0, r_base, 0.0, base_t, 16)?);
    // The rim starts just above the ground (only the base touches a shelf) and its top
    // starts just outside the base, so the base of a plate above lands on this base.
    let rim_profile = [
        (r_base - 0.002, RIM_LIFT),
        (r_out, h - rim_t),
        (r_out, h),
        (r_base + 0.0005, base_t),
    ];
    for piece in crate::geometry::convex::revolved_pieces(&rim_profile, 16)? {
        b.add_collision(piece);
    }
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, 0.0, base_t],
            [r_base * 1.4, r_base * 1.4],
            0.3,
        )],
    )
}

/// Bowl: a curved open vessel on a foot ring (`large` variants are serving / fruit bowls).
fn bowl(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r = w / 2.0;
    let mut b = body(ctx);
    let outer = [
        (r * 0.45, 0.0),
        (r * 0.7, h * 0.3),
        (r * 0.9, h * 0.65),
        (r, h),
    ];
    let wall = (r * 0.06).clamp(0.003, 0.008);
    b.add_vessel([0.0; 3], &outer, wall, wall * 1.2, 12, ctx.color)?;
    single(
        b.finish()?,
        vec![surface(
            "inside",
            "body",
            [0.0, 0.0, wall * 1.2],
            [r * 0.9, r * 0.9],
            h - wall,
        )],
    )
}

/// Mug (or a tea `cup` with a saucer-friendly foot): an open cylinder with a thick base and
/// a handle on +X.
fn mug(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    // Round body of diameter d; the handle takes the rest of the width, centred overall.
    let r = d / 2.0;
    let cx = -(w - d) / 2.0;
    let wall = (r * 0.1).clamp(0.003, 0.006);
    let base = 0.008;
    let mut b = body(ctx);
    let outer: Vec<(f64, f64)> = if ctx.variant == "cup" {
        vec![(r * 0.6, 0.0), (r * 0.85, h * 0.5), (r, h)]
    } else {
        vec![(r, 0.0), (r, h)]
    };
    b.add_vessel([cx, 0.0, 0.0], &outer, wall, base, 16, ctx.color)?;
    // Handle: two arms and a grip on +X, inside the width budget.
    let t = 0.009;
    let grip_x = w / 2.0 - t / 2.0;
    for z in [h * 0.78, h * 0.3] {
        let x_in =
            cx + if ctx.variant == "cup" {
                r * (0.6 + 0.4 * z / h)
            } else {
                r
            } - 0.002;
        b.add_box(
            [(x_in + grip_x) / 2.0, 0.0, z],
            [grip_x - x_in + t, t, t],
            ctx.color,
        )?;
    }
    let grip_h = h * 0.48 - t;
    b.add_box(
        [grip_x, 0.0, (h * 0.78 + h * 0.3) / 2.0],
        [t, t, grip_h],
        ctx.color,
    )?;
    single(
        b.finish()?,
        vec![surface("inside", "body", [cx, 0.0, base], [r, r], h - base)],
    )
}

/// Drinking glass (tumbler): a clear open cylinder, slightly flared.
fn glass(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r = w / 2.0;
    let mut b = body(ctx);
    let (visual, pieces) = shapes::vessel(&[(r * 0.85, 0.0), (r, h)], 0.0025, 0.008, 12)?;
    for p in pieces {
        b.add_collision(p);
    }
    b.add_visual_rgba(visual, [0.82, 0.9, 0.95, 0.4]);
    single(
        b.finish()?,
        vec![surface(
            "inside",
            "body",
            [0.0, 0.0, 0.008],
            [r, r],
            h - 0.008,
        )],
    )
}

/// Wine glass: a foot, a stem and a bowl.
fn wine_glass(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r = w / 2.0;
    let mut b = body(ctx);
    let clear = [0.82, 0.9, 0.95, 0.45];
    let foot = [0.0, 0.0, 0.0];
    b.add_part_rgba(
        shapes::frustum_mesh(foot, [0.0, 0.0, 0.004], r * 0.85, r * 0.8, 32),
        shapes::frustum_piece(foot, [0.0, 0.0, 0.004], r * 0.85, r * 0.8, 16)?,
        clear,
    );
    let stem_top = h * 0.42;
    b.add_part_rgba(
        shapes::frustum_mesh([0.0, 0.0, 0.004], [0.0, 0.0, stem_top], 0.004, 0.004, 12),
        shapes::frustum_piece([0.0, 0.0, 0.004], [0.0, 0.0, stem_top], 0.004, 0.004, 8)?,
        clear,
    );
    let bh = h - stem_top;
    let (visual, pieces) = shapes::vessel(
        &[
            (r * 0.3, 0.0),
            (r * 0.95, bh * 0.45),
            (r, bh * 0.7),
            (r * 0.85, bh),
        ],
        0.002,
        0.006,
        10,
    )?;
    let at = crate::scene::Pose::from_xyz(0.0, 0.0, stem_top);
    for p in pieces {
        b.add_collision(p.transformed(&at));
    }
    b.add_visual_rgba(visual.transformed(&at), clear);
    single(
        b.finish()?,
        vec![surface(
            "inside",
            "body",
            [0.0, 0.0, stem_top + 0.006],
            [r, r],
            bh,
        )],
    )
}

/// Bottles: `wine` (dark glass, long neck), `water` (clear blue plastic), `beer` (brown),
/// `pill` (small plastic with a cap), `pump` (soap dispenser). Collide as the solid outline,
/// weigh as a shell plus some contents.
fn bottle(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r = w / 2.0;
    let mut b = body(ctx);
    let (profile, rgba, cap): (Vec<(f64, f64)>, [f64; 4], [f64; 3]) = match ctx.variant {
        "wine" => (
            vec![
                (r * 0.95, 0.0),
                (r, 0.01),
                (r, h * 0.62),
                (r * 0.85, h * 0.7),
                (r * 0.3, h * 0.8),
                (r * 0.28, h * 0.97),
                (r * 0.32, h),
            ],
            [0.05, 0.18, 0.06, 0.9],
            [0.45, 0.05, 0.08],
        ),
        "beer" => (
            vec![
                (r, 0.0),
                (r, h * 0.6),
                (r * 0.35, h * 0.8),
                (r * 0.3, h * 0.97),
                (r * 0.33, h),
            ],
            [0.28, 0.12, 0.03, 0.85],
            [0.8, 0.7, 0.2],
        ),
        "pill" => (
            vec![(r, 0.0), (r, h * 0.8), (r * 0.92, h * 0.82)],
            [0.8, 0.45, 0.1, 0.9],
            WHITE,
        ),
        "pump" => (
            vec![(r, 0.0), (r, h * 0.65), (r * 0.5, h * 0.72)],
            [ctx.color[0], ctx.color[1], ctx.color[2], 1.0],
            WHITE,
        ),
        _ => (
            vec![
                (r * 0.92, 0.0),
                (r, 0.01),
                (r, h * 0.68),
                (r * 0.4, h * 0.88),
                (r * 0.35, h * 0.95),
            ],
            [0.6, 0.8, 0.95, 0.55],
            [0.1, 0.3, 0.8],
        ),
    };
    let body_top = profile.last().map_or(h, |p| p.1);
    b.shell(Some(0.002));
    for p in shapes::solid_lathe_pieces(&profile, 16)? {
        b.add_collision(p);
    }
    b.shell(None);
    b.add_visual_rgba(shapes::solid_lathe_mesh(&profile, 32), rgba);
    // Cap, or a pump head.
    let cap_r = profile.last().map_or(r * 0.3, |p| p.0) * 1.05;
    if ctx.variant == "pump" {
        b.add_rod(
            [0.0, 0.0, body_top],
            [0.0, 0.0, h - 0.02],
            cap_r * 0.4,
            WHITE,
        )?;
        b.add_box([r * 0.3, 0.0, h - 0.01], [r * 1.2, 0.015, 0.02], WHITE)?;
    } else if body_top < h - 0.002 {
        b.add_rod([0.0, 0.0, body_top], [0.0, 0.0, h], cap_r, cap)?;
    }
    // Label band.
    if matches!(ctx.variant, "wine" | "beer" | "" | "water") {
        b.add_visual(
            shapes::solid_lathe_mesh(&[(r + 0.0008, h * 0.2), (r + 0.0008, h * 0.45)], 32),
            [0.92, 0.88, 0.78],
        );
    }
    single(b.finish()?, vec![])
}

/// Drink can: an aluminium cylinder with rims and a coloured body.
fn can(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r = w / 2.0;
    let mut b = body(ctx);
    let profile = [(r * 0.8, 0.0), (r, h * 0.06), (r, h * 0.92), (r * 0.85, h)];
    b.shell(Some(0.0005));
    for p in shapes::solid_lathe_pieces(&profile, 16)? {
        b.add_collision(p);
    }
    b.shell(None);
    b.add_visual(shapes::solid_lathe_mesh(&profile, 32), METAL);
    b.add_visual(
        shapes::solid_lathe_mesh(&[(r + 0.0006, h * 0.12), (r + 0.0006, h * 0.88)], 32),
        ctx.color,
    );
    single(b.finish()?, vec![])
}

/// Jar with a lid: glass body (weighs as a shell) and a metal screw lid; `spice` jars are
/// small with a coloured content band.
fn jar(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r = w / 2.0;
    let mut b = body(ctx);
    let lid_h = (h * 0.15).max(0.01);
    let profile = [
        (r * 0.95, 0.0),
        (r, 0.01),
        (r, h - lid_h - 0.01),
        (r * 0.9, h - lid_h),
    ];
    b.shell(Some(0.003));
    for p in shapes::solid_lathe_pieces(&profile, 16)? {
        b.add_collision(p);
    }
    b.shell(None);
    b.add_visual_rgba(
        shapes::solid_lathe_mesh(&profile, 32),
        [0.85, 0.9, 0.92, 0.5],
    );
    let k = ctx.uniform(0.0, 6.0) as usize;
    let fill = ctx.palette(k);
    b.add_visual(
        shapes::solid_lathe_mesh(&[(r * 0.92, 0.004), (r * 0.92, (h - lid_h) * 0.7)], 24),
        if ctx.variant == "spice" {
            [0.6, 0.3, 0.1]
        } else {
            fill
        },
    );
    b.add_rod(
        [0.0, 0.0, h - lid_h],
        [0.0, 0.0, h],
        r * 0.95,
        ctx.accent_color,
    )?;
    single(b.finish()?, vec![])
}

/// Cooking pot (two side handles, a lid knob band) or, with `pan`, a frying pan with a long
/// handle on +X.
fn pot(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    if ctx.variant == "pan" {
        let r = d / 2.0;
        let cx = -w / 2.0 + r;
        b.add_vessel(
            [cx, 0.0, 0.0],
            &[(r * 0.85, 0.0), (r, h)],
            0.003,
            0.004,
            12,
            ctx.color,
        )?;
        b.add_rod(
            [cx + r, 0.0, h * 0.8],
            [w / 2.0 - 0.01, 0.0, h + 0.0 - 0.012],
            0.011,
            BLACK,
        )?;
        return single(
            b.finish()?,
            vec![surface("inside", "body", [cx, 0.0, 0.004], [r, r], h)],
        );
    }
    let r = d / 2.0;
    b.add_vessel([0.0; 3], &[(r, 0.0), (r, h)], 0.003, 0.005, 16, ctx.color)?;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - (w / 2.0 - r) / 2.0), 0.0, h * 0.8],
            [w / 2.0 - r + 0.004, 0.05, 0.015],
            BLACK,
        )?;
    }
    single(
        b.finish()?,
        vec![surface(
            "inside",
            "body",
            [0.0, 0.0, 0.005],
            [r * 1.3, r * 1.3],
            h,
        )],
    )
}

/// Cutting board: a rounded slab with a handle hole shown at one end.
fn cutting_board(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.add_rounded_box([0.0, 0.0, h / 2.0], [w, d, h], h * 0.4, ctx.color)?;
    b.add_detail(
        [w / 2.0 - 0.04, 0.0, h - 0.0005],
        [0.04, 0.015, 0.002],
        shade(ctx.color, 0.5),
    );
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [w, d], 0.2)],
    )
}

/// Serving tray: a flat base with a low rim and two handles.
fn tray(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let t = 0.006;
    b.add_box([0.0, 0.0, t / 2.0], [w, d, t], ctx.color)?;
    let rim = 0.008;
    for sy in [-1.0, 1.0] {
        b.add_box(
            [0.0, sy * (d / 2.0 - rim / 2.0), h / 2.0],
            [w, rim, h],
            ctx.color,
        )?;
    }
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - rim / 2.0), 0.0, h / 2.0],
            [rim, d - 2.0 * rim, h],
            shade(ctx.color, 0.9),
        )?;
    }
    single(
        b.finish()?,
        vec![surface(
            "top",
            "body",
            [0.0, 0.0, t],
            [w - 2.0 * rim, d - 2.0 * rim],
            0.3,
        )],
    )
}

/// Teapot (or `kettle`): a round body, a spout on +X, a handle on -X and a lid knob.
fn teapot(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = d / 2.0;
    let body_h = h * 0.8;
    // The body sits toward the handle side so spout and handle fit the width.
    let cx = if ctx.variant == "kettle" {
        -w / 2.0 + r
    } else {
        0.0
    };
    let profile: Vec<(f64, f64)> = if ctx.variant == "kettle" {
        vec![
            (r * 0.95, 0.0),
            (r, body_h * 0.2),
            (r * 0.9, body_h * 0.8),
            (r * 0.55, body_h),
        ]
    } else {
        vec![
            (r * 0.6, 0.0),
            (r * 0.95, body_h * 0.35),
            (r, body_h * 0.55),
            (r * 0.7, body_h * 0.9),
            (r * 0.45, body_h),
        ]
    };
    b.shell(Some(0.003));
    b.add_solid_lathe_at([cx, 0.0], &profile, ctx.color)?;
    b.shell(None);
    b.add_ellipsoid(
        [cx, 0.0, body_h + (h - body_h) * 0.4],
        [r * 0.12, r * 0.12, (h - body_h) * 0.4],
        ctx.accent_color,
    )?;
    // Spout toward +X.
    let sx = w / 2.0 - 0.008;
    b.add_frustum(
        [cx + r * 0.8, 0.0, body_h * 0.3],
        [sx, 0.0, body_h * 0.85],
        0.016,
        0.008,
        ctx.color,
    )?;
    // Handle toward -X (or over the top for a kettle).
    if ctx.variant == "kettle" {
        b.add_tube(
            &[
                [cx - r * 0.4, 0.0, body_h],
                [cx - r * 0.3, 0.0, h - 0.01],
                [cx + r * 0.3, 0.0, h - 0.01],
                [cx + r * 0.4, 0.0, body_h],
            ],
            0.01,
            BLACK,
        )?;
    } else {
        b.add_tube(
            &[
                [-r * 0.9, 0.0, body_h * 0.75],
                [-w / 2.0 + 0.01, 0.0, body_h * 0.65],
                [-w / 2.0 + 0.01, 0.0, body_h * 0.3],
                [-r * 0.9, 0.0, body_h * 0.25],
            ],
            0.008,
            ctx.color,
        )?;
    }
    single(b.finish()?, vec![])
}

/// Cutlery lying flat along x: `fork`, `knife`, `spoon`, `chopsticks`.
fn cutlery(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let steel = ctx.color;
    let handle_len = w * 0.55;
    let head_len = w - handle_len;
    let x_split = -w / 2.0 + handle_len;
    let t = h.min(0.004);
    if ctx.variant == "chopsticks" {
        for sy in [-1.0, 1.0] {
            b.add_frustum(
                [-w / 2.0, sy * d / 4.0, d / 4.0],
                [w / 2.0, sy * d / 4.0 * 0.6, d / 4.0],
                d / 4.0,
                d / 8.0,
                steel,
            )?;
        }
        return single(b.finish()?, vec![]);
    }
    // Handle: a slightly raised slab.
    b.add_rounded_box(
        [-w / 2.0 + handle_len / 2.0, 0.0, h / 2.0],
        [handle_len, d * 0.45, h],
        0.002,
        steel,
    )?;
    match ctx.variant {
        "knife" => {
            let blade = [
                [x_split, -d * 0.5],
                [w / 2.0, -d * 0.1],
                [w / 2.0 - 0.02, d * 0.5],
                [x_split, d * 0.5],
            ];
            b.add_part(
                mesh::prism_mesh(&blade, 0.0, t),
                ConvexPiece::prism(&blade, 0.0, t)?,
                shade(steel, 1.1),
            );
        }
        "spoon" => {
            b.add_ellipsoid(
                [x_split + head_len / 2.0, 0.0, h * 0.4],
                [head_len / 2.0, d / 2.0, h * 0.4],
                steel,
            )?;
        }
        _ => {
            b.add_box(
                [x_split + head_len * 0.15, 0.0, t / 2.0],
                [head_len * 0.3, d * 0.9, t],
                steel,
            )?;
            for k in 0..4 {
                let y = -d * 0.4 + k as f64 * d * 0.8 / 3.0;
                b.add_box(
                    [x_split + head_len * 0.65, y, t / 2.0],
                    [head_len * 0.7, d * 0.12, t],
                    steel,
                )?;
            }
        }
    }
    single(b.finish()?, vec![])
}

/// Open cylindrical holders: utensil holders, pencil cups, toothbrush cups.
fn holder(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r = w / 2.0;
    let mut b = body(ctx);
    b.add_vessel(
        [0.0; 3],
        &[(r * 0.95, 0.0), (r, h)],
        0.003,
        0.006,
        12,
        ctx.color,
    )?;
    single(
        b.finish()?,
        vec![surface("inside", "body", [0.0, 0.0, 0.006], [r, r], h)],
    )
}

/// Food container / lunch box: a rounded box with a coloured lid.
fn food_container(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.density(1000.0);
    b.shell(Some(0.002));
    b.add_rounded_box(
        [0.0, 0.0, (h - 0.015) / 2.0],
        [w, d, h - 0.015],
        0.01,
        [0.9, 0.92, 0.93],
    )?;
    b.shell(None);
    b.material_density();
    b.add_rounded_box([0.0, 0.0, h - 0.0075], [w, d, 0.015], 0.005, ctx.color)?;
    b.add_detail(
        [0.0, 0.0, (h - 0.015) * 0.45],
        [w * 0.9, d * 0.9, (h - 0.015) * 0.7],
        ctx.palette(2),
    );
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, 0.0, h], [w, d], 0.3)],
    )
}

/// Toaster: a rounded body with two bread slots and a lever.
fn toaster(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.shell(Some(0.002));
    b.add_rounded_box([0.0, 0.0, h / 2.0], [w, d, h], 0.03, ctx.color)?;
    b.shell(None);
    for sx in [-1.0, 1.0] {
        b.add_detail(
            [sx * w * 0.18, 0.0, h + 0.0005],
            [0.03, d * 0.7, 0.001],
            BLACK,
        );
    }
    b.add_detail([w / 2.0 + 0.0005, 0.0, h * 0.7], [0.001, 0.02, 0.04], BLACK);
    single(b.finish()?, vec![])
}

/// Drip coffee maker: a base with a hot plate, a tower at the back, a glass carafe.
fn coffee_maker(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.shell(Some(0.003));
    b.add_box([0.0, 0.0, 0.02], [w, d, 0.04], ctx.color)?;
    b.add_box(
        [0.0, -d / 2.0 + d * 0.2, h / 2.0],
        [w, d * 0.4, h],
        ctx.color,
    )?;
    b.add_box([0.0, 0.0, h - 0.04], [w, d, 0.08], ctx.color)?;
    b.shell(None);
    let cr = (w.min(d * 0.6) / 2.0) * 0.85;
    let at = crate::scene::Pose::from_xyz(0.0, d * 0.15, 0.0);
    b.add_part_rgba(
        shapes::solid_lathe_mesh(
            &[
                (cr * 0.9, 0.04),
                (cr, 0.08),
                (cr * 0.8, h * 0.5),
                (cr * 0.6, h * 0.55),
            ],
            24,
        )
        .transformed(&at),
        shapes::frustum_piece(
            [0.0, d * 0.15, 0.04],
            [0.0, d * 0.15, h * 0.55],
            cr,
            cr * 0.6,
            12,
        )?,
        [0.3, 0.2, 0.12, 0.7],
    );
    single(b.finish()?, vec![])
}

/// Squeeze tube (toothpaste, cream): a flattened body with a round cap.
fn tube(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let cap = w * 0.15;
    b.add_ellipsoid(
        [cap / 2.0, 0.0, h / 2.0],
        [(w - cap) / 2.0, d / 2.0, h / 2.0],
        ctx.color,
    )?;
    b.add_rod(
        [-w / 2.0, 0.0, h / 2.0],
        [-w / 2.0 + cap, 0.0, h / 2.0],
        h * 0.4,
        WHITE,
    )?;
    single(b.finish()?, vec![])
}
