//! Wall-mounted objects, back at y = 0, facing +Y, bottom at z = 0, centred in x: mirrors,
//! wall shelves, clocks, wall-mounted TVs, boards (white, chalk, bulletin), wall and medicine
//! cabinets (articulated doors), spice and mug racks, coat hooks, towel bars, projector
//! screens, ballet barres, air conditioners.

use super::parts::{BLACK, METAL, MIRROR, SCREEN, WHITE, body, shade, single, surface};
use super::storage::{PANEL, carcass};
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::LinkBuilder;
use crate::assets::articulated::parts::{Hinge, Look, Opening, door, door_pair};
use crate::geometry::GeometryError;
use crate::scene::SurfaceRecord;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("mirror", mirror),
    ("wall_shelf", wall_shelf),
    ("wall_clock", wall_clock),
    ("wall_tv", wall_tv),
    ("board", board),
    ("wall_cabinet", wall_cabinet),
    ("wall_rack", wall_rack),
    ("towel_bar", towel_bar),
    ("projector_screen", projector_screen),
    ("air_conditioner", air_conditioner),
    ("range_hood", range_hood),
];

/// A rectangular frame of bar width `f` around a `w` x `h` panel lying in the wall plane, `t`
/// deep (y from 0 to t).
fn frame(
    b: &mut LinkBuilder,
    w: f64,
    h: f64,
    t: f64,
    f: f64,
    color: [f64; 3],
) -> Result<(), GeometryError> {
    b.add_box([0.0, t / 2.0, f / 2.0], [w, t, f], color)?;
    b.add_box([0.0, t / 2.0, h - f / 2.0], [w, t, f], color)?;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - f / 2.0), t / 2.0, h / 2.0],
            [f, t, h - 2.0 * f],
            color,
        )?;
    }
    Ok(())
}

/// Mirror: a reflective panel in a frame (round in the `round` variant; standing on two
/// feet in the `floor` variant).
fn mirror(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    if ctx.variant == "floor" {
        return floor_mirror(b, ctx, [w, d, h]);
    }
    if ctx.variant == "round" {
        let r = w.min(h) / 2.0;
        b.add_part(
            super::shapes::frustum_mesh([0.0, 0.0, r], [0.0, d, r], r, r, 48),
            super::shapes::frustum_piece([0.0, 0.0, r], [0.0, d, r], r, r, 16)?,
            ctx.accent_color,
        );
        b.add_visual(
            super::shapes::frustum_mesh(
                [0.0, d - 0.002, r],
                [0.0, d + 0.0005, r],
                r * 0.9,
                r * 0.9,
                48,
            ),
            MIRROR,
        );
        return single(b.finish()?, vec![]);
    }
    let f = (w.min(h) * 0.06).clamp(0.02, 0.06);
    frame(&mut b, w, h, d, f, ctx.accent_color)?;
    b.density(2500.0);
    b.add_box(
        [0.0, d * 0.4, h / 2.0],
        [w - 2.0 * f, d * 0.5, h - 2.0 * f],
        MIRROR,
    )?;
    single(b.finish()?, vec![])
}

/// A full-length mirror on the floor (canonical floor frame: centred in x and y, front +Y):
/// the framed panel upright over the middle of two feet that run the whole depth, its lower
/// rail a little above the floor.
fn floor_mirror(
    mut b: LinkBuilder,
    ctx: &GenContext,
    [w, d, h]: [f64; 3],
) -> Result<Generated, GeometryError> {
    let foot = 0.04;
    let lift = 0.06;
    let t = 0.03_f64.min(d * 0.5);
    let f = (w.min(h) * 0.06).clamp(0.025, 0.05);
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - f / 2.0);
        b.add_box([x, 0.0, foot / 2.0], [f, d, foot], ctx.accent_color)?;
        b.add_box(
            [x, 0.0, (foot + h) / 2.0],
            [f, t, h - foot],
            ctx.accent_color,
        )?;
    }
    for z in [lift + f / 2.0, h - f / 2.0] {
        b.add_box([0.0, 0.0, z], [w - 2.0 * f, t, f], ctx.accent_color)?;
    }
    b.density(2500.0);
    b.add_box(
        [0.0, 0.0, (lift + h) / 2.0],
        [w - 2.0 * f, t * 0.5, h - lift - 2.0 * f],
        MIRROR,
    )?;
    single(b.finish()?, vec![])
}

/// Floating wall shelf: a board on two brackets.
fn wall_shelf(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let t = 0.025_f64.min(h * 0.3);
    b.add_box([0.0, d / 2.0, h - t / 2.0], [w, d, t], ctx.color)?;
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - 0.08).max(0.02);
        b.add_box(
            [x, 0.005, (h - t) / 2.0],
            [0.02, 0.01, h - t],
            ctx.accent_color,
        )?;
        b.add_box(
            [x, d * 0.4, h - t - 0.01],
            [0.02, d * 0.8, 0.02],
            ctx.accent_color,
        )?;
    }
    single(
        b.finish()?,
        vec![surface("top", "body", [0.0, d / 2.0, h], [w, d], 0.35)],
    )
}

/// Wall clock: a round case, a face, hour marks and hands.
fn wall_clock(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    if ctx.variant == "floor" {
        return longcase_clock(b, ctx, [w, d, h]);
    }
    let r = w.min(h) / 2.0;
    b.add_part(
        super::shapes::frustum_mesh([0.0, 0.0, r], [0.0, d, r], r, r * 0.96, 48),
        super::shapes::frustum_piece([0.0, 0.0, r], [0.0, d, r], r, r * 0.96, 16)?,
        ctx.color,
    );
    b.add_visual(
        super::shapes::frustum_mesh(
            [0.0, d - 0.003, r],
            [0.0, d + 0.0005, r],
            r * 0.88,
            r * 0.88,
            48,
        ),
        WHITE,
    );
    for k in 0..12 {
        let a = std::f64::consts::TAU * k as f64 / 12.0;
        let len = if k % 3 == 0 { 0.12 } else { 0.06 } * r;
        b.add_detail(
            [0.78 * r * a.sin(), d + 0.001, r + 0.78 * r * a.cos()],
            [0.012 * r / 0.15, 0.001, len],
            BLACK,
        );
    }
    b.add_detail(
        [0.0, d + 0.002, r + 0.25 * r],
        [0.015, 0.001, 0.5 * r],
        BLACK,
    );
    b.add_detail([0.18 * r, d + 0.003, r], [0.36 * r, 0.001, 0.012], BLACK);
    single(b.finish()?, vec![])
}

/// A longcase (grandfather) clock in the floor frame (centred, front +Y): a plinth, a narrow
/// trunk with a glazed pendulum door and a wider hood whose face looks forward.
fn longcase_clock(
    mut b: LinkBuilder,
    ctx: &GenContext,
    [w, d, h]: [f64; 3],
) -> Result<Generated, GeometryError> {
    // A hollow case with a movement and weights: about 80 kg at the typical size.
    b.density(320.0);
    let plinth = h * 0.15;
    let hood = (w * 1.05).min(h * 0.3);
    let trunk = h - plinth - hood;
    b.add_box([0.0, 0.0, plinth / 2.0], [w, d, plinth], ctx.color)?;
    b.add_box(
        [0.0, 0.0, plinth + trunk / 2.0],
        [w * 0.8, d * 0.85, trunk],
        ctx.color,
    )?;
    b.add_box([0.0, 0.0, h - hood / 2.0], [w, d, hood], ctx.color)?;
    let front = d / 2.0 + 0.001;
    let r = (w * 0.38).min(hood * 0.4);
    b.add_detail(
        [0.0, front, h - hood / 2.0],
        [2.0 * r, 0.002, 2.0 * r],
        WHITE,
    );
    b.add_detail(
        [0.0, front, h - hood / 2.0 + r * 0.3],
        [0.01, 0.003, r * 0.6],
        BLACK,
    );
    b.add_detail(
        [0.0, d * 0.425 + 0.001, plinth + trunk * 0.55],
        [w * 0.45, 0.002, trunk * 0.7],
        shade(ctx.color, 0.5),
    );
    b.add_detail(
        [0.0, d * 0.425 + 0.002, plinth + trunk * 0.3],
        [w * 0.16, 0.002, w * 0.16],
        [0.75, 0.6, 0.25],
    );
    single(b.finish()?, vec![])
}

/// Wall-mounted flat TV: a thin panel with a dark screen and a slim bezel.
fn wall_tv(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.add_box([0.0, d * 0.25, h / 2.0], [w * 0.3, d * 0.5, h * 0.3], BLACK)?;
    b.shell(Some(0.003));
    b.add_box([0.0, d * 0.5 + d * 0.25, h / 2.0], [w, d * 0.5, h], BLACK)?;
    b.shell(None);
    b.add_detail(
        [0.0, d + 0.0005, h / 2.0],
        [w - 0.02, 0.001, h - 0.02],
        SCREEN,
    );
    single(b.finish()?, vec![])
}

/// Boards: whiteboard (white with a marker tray), `chalkboard` (green with a chalk ledge),
/// `bulletin` (cork with pinned notes).
fn board(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let f = 0.025;
    let face = match ctx.variant {
        "chalkboard" => [0.04, 0.16, 0.09],
        "bulletin" => [0.55, 0.38, 0.22],
        _ => [0.95, 0.95, 0.95],
    };
    let t = d * 0.7;
    b.add_box(
        [0.0, t / 2.0, h / 2.0],
        [w - 2.0 * f + 0.002, t, h - 2.0 * f + 0.002],
        face,
    )?;
    frame(&mut b, w, h, d, f, ctx.accent_color)?;
    let mut surfaces: Vec<SurfaceRecord> = Vec::new();
    if ctx.variant != "bulletin" {
        b.add_box([0.0, d / 2.0, 0.01], [w * 0.6, d, 0.02], ctx.accent_color)?;
        surfaces.push(surface(
            "tray",
            "body",
            [0.0, d / 2.0 + 0.005, 0.02],
            [w * 0.6, d - 0.02],
            0.1,
        ));
    } else {
        for k in 0..5 {
            let x = -w * 0.35 + k as f64 * w * 0.17;
            let z = h * (0.35 + 0.3 * ((k * 7 % 3) as f64 / 2.0));
            b.add_detail(
                [x, t + 0.001, z],
                [w * 0.12, 0.001, h * 0.15],
                ctx.palette(k),
            );
        }
    }
    if ctx.variant.is_empty() {
        // Marker scribbles.
        for k in 0..3 {
            b.add_detail(
                [
                    -w * 0.2 + k as f64 * 0.1,
                    t + 0.0008,
                    h * (0.6 - 0.1 * k as f64),
                ],
                [w * 0.3, 0.0008, 0.006],
                [0.1, 0.2, 0.6],
            );
        }
    }
    single(b.finish()?, surfaces)
}

/// Wall cabinet with hinged doors and a shelf; the `medicine` variant has a mirror door.
fn wall_cabinet(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    // Build a floor-standing carcass, then shift it so its back is at y = 0.
    let mut cb = LinkBuilder::new("tmp", crate::scene::Pose::IDENTITY, ctx.material);
    let front_t = 0.018;
    let c0 = carcass(&mut cb, w, d, h, 0.0, front_t, ctx.color, false)?;
    let shift = crate::scene::Pose::from_xyz(0.0, d / 2.0, 0.0);
    for p in &cb.collisions {
        b.add_collision(p.transformed(&shift));
    }
    for v in &cb.visuals {
        b.add_visual_rgba(v.mesh.transformed(&shift), v.color);
    }
    let c = super::storage::Carcass {
        y_back: c0.y_back + d / 2.0,
        y_front: c0.y_front + d / 2.0,
        ..c0
    };
    let mid_z = (c.z0 + c.z1) / 2.0;
    b.add_box(
        [0.0, c.cy(), mid_z],
        [c.inner_w() - 0.002, c.inner_d() - 0.01, PANEL],
        ctx.color,
    )?;
    let surfaces = vec![
        surface(
            "shelf_0",
            "body",
            [0.0, c.cy(), c.z0],
            [c.inner_w() - 0.01, c.inner_d() - 0.01],
            mid_z - PANEL / 2.0 - c.z0,
        ),
        surface(
            "shelf_1",
            "body",
            [0.0, c.cy(), mid_z + PANEL / 2.0],
            [c.inner_w() - 0.01, c.inner_d() - 0.01],
            c.z1 - mid_z - PANEL / 2.0,
        ),
    ];
    let medicine = ctx.variant == "medicine";
    let lk = Look {
        material: ctx.material,
        front: if medicine {
            MIRROR
        } else {
            shade(ctx.color, 0.97)
        },
        inner: shade(ctx.color, 0.8),
        handle: METAL,
    };
    let ov = PANEL / 2.0 - 0.002;
    let full = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: c.z0,
        z1: c.z1,
    };
    let parts = if w > 0.7 && !medicine {
        door_pair("body", full, c.y_front, ov, front_t, 1.75, false, lk)?.into()
    } else {
        vec![door(
            "door",
            "body",
            full,
            c.y_front,
            ov,
            front_t,
            Hinge::Left,
            1.75,
            false,
            lk,
        )?]
    };
    let mut links = vec![b.finish()?];
    let mut joints = Vec::new();
    for (l, j) in parts {
        links.push(l);
        joints.push(j);
    }
    Ok(Generated {
        links,
        joints,
        surfaces,
    })
}

/// Racks on a back board: `spice` (two or three rails-fronted shelves), `mug` (a shelf over
/// a row of pegs), `coat` (a row of double hooks), `barre` (a long rod on brackets).
fn wall_rack(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let back_t = 0.015;
    let mut surfaces = Vec::new();
    match ctx.variant {
        "barre" => {
            let z = h - 0.025;
            b.add_rod(
                [-w / 2.0, d - 0.025, z],
                [w / 2.0, d - 0.025, z],
                0.02,
                ctx.color,
            )?;
            let n = ((w / 1.5).ceil() as usize).max(2);
            for i in 0..=n {
                let x = -w / 2.0 + 0.05 + (w - 0.1) * i as f64 / n as f64;
                b.add_box([x, 0.01, z / 2.0], [0.04, 0.02, z], ctx.accent_color)?;
                b.add_rod([x, 0.02, z], [x, d - 0.045, z], 0.01, ctx.accent_color)?;
            }
            return single(b.finish()?, surfaces);
        }
        _ => {
            b.add_box([0.0, back_t / 2.0, h / 2.0], [w, back_t, h], ctx.color)?;
        }
    }
    match ctx.variant {
        "spice" => {
            let n = ((h / 0.14).floor() as usize).clamp(1, 4);
            let pitch = h / n as f64;
            for sx in [-1.0, 1.0] {
                b.add_box(
                    [sx * (w / 2.0 - 0.008), d / 2.0, h / 2.0],
                    [0.016, d, h],
                    ctx.color,
                )?;
            }
            for i in 0..n {
                let z = i as f64 * pitch + 0.006;
                b.add_box(
                    [0.0, (back_t + d) / 2.0, z],
                    [w - 0.032, d - back_t, 0.012],
                    ctx.color,
                )?;
                b.add_rod(
                    [-w / 2.0 + 0.016, d - 0.006, z + 0.05],
                    [w / 2.0 - 0.016, d - 0.006, z + 0.05],
                    0.004,
                    ctx.accent_color,
                )?;
                surfaces.push(surface(
                    &format!("shelf_{i}"),
                    "body",
                    [0.0, (back_t + d - 0.012) / 2.0, z + 0.006],
                    [w - 0.04, d - back_t - 0.014],
                    pitch - 0.02,
                ));
            }
        }
        "mug" => {
            let st = 0.02;
            b.add_box(
                [0.0, (back_t + d) / 2.0, h - st / 2.0],
                [w, d - back_t, st],
                ctx.color,
            )?;
            surfaces.push(surface(
                "top",
                "body",
                [0.0, (back_t + d) / 2.0, h],
                [w, d - back_t],
                0.25,
            ));
            let n = ((w / 0.12).floor() as usize).max(2);
            for i in 0..n {
                let x = -w / 2.0 + (i as f64 + 0.5) * w / n as f64;
                b.add_tube(
                    &[
                        [x, back_t, h * 0.45],
                        [x, d * 0.8, h * 0.45],
                        [x, d * 0.85, h * 0.55],
                    ],
                    0.006,
                    ctx.accent_color,
                )?;
            }
        }
        _ => {
            let n = ((w / 0.15).floor() as usize).max(2);
            for i in 0..n {
                let x = -w / 2.0 + (i as f64 + 0.5) * w / n as f64;
                b.add_tube(
                    &[
                        [x, back_t, h * 0.5],
                        [x, d - 0.01, h * 0.62],
                        [x, d - 0.01, h * 0.75],
                    ],
                    0.007,
                    ctx.accent_color,
                )?;
                b.add_tube(
                    &[[x, back_t, h * 0.45], [x, d * 0.5, h * 0.35]],
                    0.006,
                    ctx.accent_color,
                )?;
            }
        }
    }
    single(b.finish()?, surfaces)
}

/// Towel bar: two brackets and a rod (a folded towel hangs over it in the `towel` variant).
fn towel_bar(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let z = h - 0.02;
    for sx in [-1.0, 1.0] {
        let x = sx * (w / 2.0 - 0.02);
        b.add_frustum([x, 0.0, z], [x, d - 0.015, z], 0.02, 0.01, METAL)?;
    }
    b.add_rod(
        [-w / 2.0 + 0.02, d - 0.015, z],
        [w / 2.0 - 0.02, d - 0.015, z],
        0.01,
        METAL,
    )?;
    b.density(300.0);
    b.add_box(
        [0.0, d - 0.015, (z - 0.012) / 2.0],
        [w * 0.6, 0.02, z - 0.012],
        ctx.color,
    )?;
    single(b.finish()?, vec![])
}

/// Pull-down projector screen: a housing tube at the top, a white screen, a bottom bar.
fn projector_screen(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let r = d / 2.0;
    b.add_rod([-w / 2.0, r, h - r], [w / 2.0, r, h - r], r, WHITE)?;
    b.add_box(
        [0.0, r, (h - 2.0 * r) / 2.0 + 0.02],
        [w - 0.1, 0.003, h - 2.0 * r - 0.02],
        [0.97, 0.97, 0.97],
    )?;
    b.add_box([0.0, r, 0.012], [w - 0.08, 0.02, 0.024], BLACK)?;
    single(b.finish()?, vec![])
}

/// Split air-conditioner indoor unit: a rounded box with a vent slot.
fn air_conditioner(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.shell(Some(0.003));
    b.add_rounded_box([0.0, d / 2.0, h / 2.0], [w, d, h], 0.03, WHITE)?;
    b.shell(None);
    b.add_detail(
        [0.0, d * 0.6, 0.004],
        [w * 0.85, d * 0.5, 0.008],
        shade(WHITE, 0.6),
    );
    b.add_detail(
        [w * 0.35, d + 0.0005, h * 0.6],
        [0.04, 0.001, 0.01],
        [0.2, 0.7, 0.3],
    );
    single(b.finish()?, vec![])
}

/// Range hood: a canopy over the hob (hollow, its filter underneath), a sloped shoulder and a
/// chimney up the wall.
fn range_hood(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let canopy = (h * 0.15).clamp(0.06, 0.15);
    let shoulder = (h * 0.15).clamp(0.06, 0.2);
    // Sheet steel around air: about 20 kg at the typical size.
    b.density(150.0);
    b.shell(Some(0.004));
    b.add_box([0.0, d / 2.0, canopy / 2.0], [w, d, canopy], ctx.color)?;
    b.add_box(
        [0.0, d * 0.35, canopy + shoulder / 2.0],
        [w * 0.85, d * 0.7, shoulder],
        ctx.color,
    )?;
    b.shell(None);
    let chimney = h - canopy - shoulder;
    if chimney > 0.02 {
        b.add_box(
            [0.0, d * 0.2, canopy + shoulder + chimney / 2.0],
            [w * 0.35, d * 0.4, chimney],
            ctx.color,
        )?;
    }
    b.add_detail(
        [0.0, d * 0.5, 0.0005],
        [w * 0.8, d * 0.8, 0.001],
        shade(METAL, 0.5),
    );
    single(b.finish()?, vec![])
}
