//! Kitchen and laundry: base cabinets and counter runs (with a sink basin or as an island),
//! refrigerators, stoves and ovens, dishwashers, microwaves, washing machines and dryers,
//! water dispensers.
//!
//! Appliance bodies are real carcasses (sides, top, bottom, back), so a fridge, an oven or a
//! microwave has an interior with shelves behind its door. Their panels are foam-insulated
//! sheet metal, about 500 kg/m^3 over the panel volume.

use super::parts::{BLACK, METAL, WHITE, body, knob, shade, surface};
use super::storage::{PANEL, carcass, carcass_opts};
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::articulated::parts::{Hinge, Look, Opening, door, drawer};
use crate::assets::{Joint, Link, LinkBuilder, Material};
use crate::geometry::GeometryError;
use crate::scene::SurfaceRecord;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("kitchen_counter", kitchen_counter),
    ("refrigerator", refrigerator),
    ("stove", stove),
    ("dishwasher", dishwasher),
    ("microwave", microwave),
    ("washing_machine", washing_machine),
    ("water_dispenser", water_dispenser),
];

/// Effective density of insulated appliance panels, kg/m^3.
const APPLIANCE: f64 = 500.0;
/// Height of a faucet above its worktop, metres (sink sizes include it).
pub(super) const FAUCET: f64 = 0.28;

fn appliance_material(ctx: &GenContext) -> Material {
    Material {
        density: APPLIANCE,
        ..ctx.material
    }
}

fn assemble(
    b: LinkBuilder,
    parts: Vec<(Link, Joint)>,
    surfaces: Vec<SurfaceRecord>,
) -> Result<Generated, GeometryError> {
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

/// A countertop slab from `x0` to `x1` (depth `d`, top at `z_top`) with a rectangular basin
/// `bw` x `bd` x `depth` cut into it at `bx`: the top is four boxes around the hole and the
/// basin an open box below it, so dishes can go in. Adds a faucet [`FAUCET`] tall behind the
/// basin.
#[allow(clippy::too_many_arguments)]
pub(super) fn top_with_basin(
    b: &mut LinkBuilder,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    z_top: f64,
    t: f64,
    bx: f64,
    by: f64,
    bw: f64,
    bd: f64,
    depth: f64,
    top_color: [f64; 3],
    basin_color: [f64; 3],
) -> Result<SurfaceRecord, GeometryError> {
    let zc = z_top - t / 2.0;
    let (hx0, hx1, hy0, hy1) = (bx - bw / 2.0, bx + bw / 2.0, by - bd / 2.0, by + bd / 2.0);
    b.add_box(
        [(x0 + hx0) / 2.0, (y0 + y1) / 2.0, zc],
        [hx0 - x0, y1 - y0, t],
        top_color,
    )?;
    b.add_box(
        [(hx1 + x1) / 2.0, (y0 + y1) / 2.0, zc],
        [x1 - hx1, y1 - y0, t],
        top_color,
    )?;
    b.add_box([bx, (y0 + hy0) / 2.0, zc], [bw, hy0 - y0, t], top_color)?;
    b.add_box([bx, (hy1 + y1) / 2.0, zc], [bw, y1 - hy1, t], top_color)?;
    let wt = 0.008;
    let zb = z_top - t - depth;
    b.add_box([bx, by, zb + wt / 2.0], [bw, bd, wt], basin_color)?;
    let wall_h = depth;
    let zw = zb + wt + (wall_h - wt) / 2.0 - 0.0;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [bx + sx * (bw / 2.0 - wt / 2.0), by, zw],
            [wt, bd - 2.0 * wt, wall_h - wt],
            basin_color,
        )?;
    }
    for sy in [-1.0, 1.0] {
        b.add_box(
            [bx, by + sy * (bd / 2.0 - wt / 2.0), zw],
            [bw, wt, wall_h - wt],
            basin_color,
        )?;
    }
    // Faucet: a goose neck behind the basin.
    let fy = (y0 + hy0) / 2.0;
    let spout = (bd * 0.35).min(0.18);
    let f = FAUCET - 0.012;
    b.add_tube(
        &[
            [bx, fy, z_top],
            [bx, fy, z_top + f * 0.83],
            [bx, fy + spout * 0.6, z_top + f],
            [bx, fy + spout, z_top + f * 0.73],
        ],
        0.012,
        METAL,
    )?;
    b.add_rod(
        [bx + 0.06, fy, z_top],
        [bx + 0.06, fy, z_top + 0.06],
        0.012,
        METAL,
    )?;
    Ok(surface(
        "basin",
        "body",
        [bx, by, zb + wt],
        [bw - 2.0 * wt, bd - 2.0 * wt],
        wall_h + 0.2,
    ))
}

/// The countertop left and right of a basin cut at `bx` (width `bw`) into a top from `x0` to
/// `x1` and `y0` to `y1` (the first argument) at `z_top`, as surfaces `top_left` and `top_right` (2 cm in from
/// every edge; a strip narrower than 8 cm is left out).
pub(super) fn tops_beside_basin(
    [x0, x1, y0, y1]: [f64; 4],
    z_top: f64,
    bx: f64,
    bw: f64,
    clearance: f64,
) -> Vec<SurfaceRecord> {
    let m = 0.02;
    let depth = y1 - y0 - 2.0 * m;
    [
        ("top_left", x0 + m, bx - bw / 2.0 - m),
        ("top_right", bx + bw / 2.0 + m, x1 - m),
    ]
    .into_iter()
    .filter(|(_, a, b)| b - a >= 0.08 && depth >= 0.08)
    .map(|(id, a, b)| {
        surface(
            id,
            "body",
            [(a + b) / 2.0, (y0 + y1) / 2.0, z_top],
            [b - a, depth],
            clearance,
        )
    })
    .collect()
}

/// Counter runs: base cabinet modules (a drawer over a door each) under a countertop.
/// Variants: `""` against a wall, `island` (overhang at the back for stools), `sink` (the
/// middle module holds a basin and faucet).
fn kitchen_counter(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let top_t = 0.03;
    let overhang_back = if ctx.variant == "island" {
        0.25_f64.min(d * 0.3)
    } else {
        0.0
    };
    let cab_d = d - 0.025 - overhang_back;
    let cab_w = w - 0.0;
    // Carcass runs along the back; build it shifted by the island overhang.
    let mut cb = LinkBuilder::new("tmp", crate::scene::Pose::IDENTITY, ctx.material);
    let worktop = h - if ctx.variant == "sink" { FAUCET } else { 0.0 };
    let c0 = carcass_opts(
        &mut cb,
        cab_w,
        cab_d,
        worktop - top_t,
        0.1,
        0.02,
        ctx.color,
        false,
        false,
    )?;
    let shift_y = -d / 2.0 + overhang_back + cab_d / 2.0;
    for (piece, fill) in cb.collisions.iter().zip(&cb.fills) {
        b.density(fill.density);
        b.add_collision(piece.transformed(&crate::scene::Pose::from_xyz(0.0, shift_y, 0.0)));
    }
    b.material_density();
    for v in cb.visuals {
        b.add_visual_rgba(
            v.mesh
                .transformed(&crate::scene::Pose::from_xyz(0.0, shift_y, 0.0)),
            v.color,
        );
    }
    let c = super::storage::Carcass {
        y_back: c0.y_back + shift_y,
        y_front: c0.y_front + shift_y,
        ..c0
    };
    let n = ((w / 0.6).round() as usize).max(1);
    let mw = c.inner_w() / n as f64;
    let sink_module = if ctx.variant == "sink" {
        Some(n / 2)
    } else {
        None
    };
    let stone = ctx.accent_color;
    let mut surfaces = Vec::new();
    let mut parts = Vec::new();
    let lk = Look {
        material: ctx.material,
        front: shade(ctx.color, 0.97),
        inner: shade(ctx.color, 0.8),
        handle: METAL,
    };
    let drawer_h = 0.14;
    for i in 0..n {
        let x0 = c.x0 + mw * i as f64;
        let x1 = x0 + mw;
        if i > 0 {
            b.add_box(
                [x0, c.cy(), (c.z0 + c.z1) / 2.0],
                [PANEL, c.inner_d(), c.z1 - c.z0],
                ctx.color,
            )?;
        }
        let ox0 = x0 + if i > 0 { PANEL / 2.0 } else { 0.0 };
        let ox1 = x1 - if i + 1 < n { PANEL / 2.0 } else { 0.0 };
        let rail_z = c.z1 - drawer_h - PANEL;
        let door_top = if sink_module == Some(i) { c.z1 } else { rail_z };
        if sink_module != Some(i) {
            b.add_box(
                [(ox0 + ox1) / 2.0, c.cy(), rail_z + PANEL / 2.0],
                [ox1 - ox0, c.inner_d(), PANEL],
                ctx.color,
            )?;
            let o = Opening {
                x0: ox0,
                x1: ox1,
                z0: rail_z + PANEL,
                z1: c.z1 - 0.004,
            };
            let (l, j, s) = drawer(
                &format!("drawer_{i}"),
                "body",
                o,
                c.y_front,
                c.inner_d() - 0.03,
                PANEL / 2.0 - 0.0015,
                lk,
            )?;
            parts.push((l, j));
            surfaces.push(s);
        }
        let o = Opening {
            x0: ox0,
            x1: ox1,
            z0: c.z0,
            z1: door_top,
        };
        let hinge = if i % 2 == 0 {
            Hinge::Left
        } else {
            Hinge::Right
        };
        // Neighbouring doors hinge on the same divider: stop before their handles meet.
        parts.push(door(
            &format!("door_{i}"),
            "body",
            o,
            c.y_front,
            PANEL / 2.0 - 0.0015,
            0.02,
            hinge,
            1.45,
            false,
            lk,
        )?);
        surfaces.push(surface(
            &format!("shelf_{i}"),
            "body",
            [(ox0 + ox1) / 2.0, c.cy(), c.z0],
            [ox1 - ox0 - 0.01, c.inner_d() - 0.01],
            door_top - c.z0 - PANEL,
        ));
    }
    let z_top = h - if sink_module.is_some() { FAUCET } else { 0.0 };
    let (y0, y1) = (-d / 2.0, d / 2.0);
    if let Some(k) = sink_module {
        let bx = c.x0 + mw * (k as f64 + 0.5);
        let bw = (mw - 0.1).clamp(0.3, 0.7);
        let bd = (cab_d - 0.2).clamp(0.3, 0.45);
        let by = (c.y_back + c.y_front) / 2.0 + 0.03;
        surfaces.push(top_with_basin(
            &mut b,
            -w / 2.0,
            w / 2.0,
            y0,
            y1,
            z_top,
            top_t,
            bx,
            by,
            bw,
            bd,
            0.18,
            stone,
            METAL,
        )?);
        surfaces.push(surface("top", "body", [0.0, 0.0, z_top], [w, d], 0.6));
    } else {
        b.add_box([0.0, 0.0, z_top - top_t / 2.0], [w, d, top_t], stone)?;
        surfaces.push(surface("top", "body", [0.0, 0.0, z_top], [w, d], 0.6));
    }
    assemble(b, parts, surfaces)
}

/// Refrigerator: an insulated carcass with a freezer compartment on top, two doors hinged on
/// the right, glass shelves inside both.
fn refrigerator(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mat = appliance_material(ctx);
    let mut b = LinkBuilder::new("body", crate::scene::Pose::IDENTITY, mat);
    let door_t = 0.05;
    let c = carcass(&mut b, w, d, h, 0.05, door_t, ctx.color, false)?;
    let split = c.z0 + (c.z1 - c.z0) * 0.7;
    b.add_box(
        [0.0, c.cy(), split],
        [c.inner_w(), c.inner_d(), 0.04],
        ctx.color,
    )?;
    let mut surfaces = vec![c.top_surface(w, d, h, 0.4)];
    // Fresh-food shelves.
    let n = 3;
    let pitch = (split - 0.02 - c.z0) / n as f64;
    let sd = c.inner_d() - 0.03;
    for i in 0..n {
        let z = c.z0 + pitch * i as f64;
        if i > 0 {
            b.add_part_rgba(
                crate::geometry::mesh::box_mesh(
                    [0.0, c.y_back + sd / 2.0, z],
                    [c.inner_w() - 0.004, sd, 0.006],
                ),
                crate::geometry::ConvexPiece::cuboid(
                    [0.0, c.y_back + sd / 2.0, z],
                    [c.inner_w() - 0.004, sd, 0.006],
                )?,
                [0.8, 0.9, 0.95, 0.5],
            );
        }
        let base = if i > 0 { z + 0.003 } else { z };
        surfaces.push(surface(
            &format!("shelf_{i}"),
            "body",
            [0.0, c.y_back + sd / 2.0, base],
            [c.inner_w() - 0.01, sd],
            pitch - 0.01,
        ));
    }
    surfaces.push(surface(
        "freezer",
        "body",
        [0.0, c.y_back + sd / 2.0, split + 0.02],
        [c.inner_w() - 0.01, sd],
        c.z1 - split - 0.02,
    ));
    let lk = Look {
        material: mat,
        front: shade(ctx.color, 1.02),
        inner: WHITE,
        handle: METAL,
    };
    let ov = PANEL / 2.0 - 0.002;
    let lower = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: c.z0,
        z1: split - 0.02 - ov - 0.002,
    };
    let upper = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: split + 0.02 + ov + 0.002,
        z1: c.z1,
    };
    let parts = vec![
        door(
            "door",
            "body",
            lower,
            c.y_front,
            ov,
            door_t,
            Hinge::Right,
            1.75,
            false,
            lk,
        )?,
        door(
            "freezer_door",
            "body",
            upper,
            c.y_front,
            ov,
            door_t,
            Hinge::Right,
            1.75,
            false,
            lk,
        )?,
    ];
    assemble(b, parts, surfaces)
}

/// Stove (range): an oven cavity behind a door hinged at the bottom, a cooktop with four
/// burners and a back panel with knobs. The `oven` variant has a plain top and the controls
/// above the door.
fn stove(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mat = appliance_material(ctx);
    let mut b = LinkBuilder::new("body", crate::scene::Pose::IDENTITY, mat);
    let door_t = 0.04;
    let range = ctx.variant != "oven";
    let body_h = if range { h - 0.1 } else { h };
    let c = carcass(&mut b, w, d, body_h, 0.1, door_t, ctx.color, false)?;
    let panel_h = if range { 0.0 } else { 0.12 };
    let cavity_top = c.z1 - panel_h - if range { 0.1 } else { 0.0 };
    // Divider between the cavity and the control zone.
    b.add_box(
        [0.0, c.cy(), cavity_top],
        [c.inner_w(), c.inner_d(), 0.02],
        BLACK,
    )?;
    let rack_z = c.z0 + (cavity_top - c.z0) * 0.4;
    for k in 0..5 {
        let x = c.x0 + 0.04 + k as f64 * (c.inner_w() - 0.08) / 4.0;
        b.add_rod(
            [x, c.y_back + 0.02, rack_z],
            [x, c.y_front - 0.03, rack_z],
            0.004,
            METAL,
        )?;
    }
    let mut surfaces = vec![surface(
        "rack",
        "body",
        [0.0, c.cy(), rack_z + 0.004],
        [c.inner_w() - 0.08, c.inner_d() - 0.05],
        cavity_top - rack_z - 0.02,
    )];
    if range {
        // Cooktop, burners and the back panel.
        let top = c.top_surface(w, d, body_h, 0.0);
        b.add_box(
            [0.0, top.center[1], body_h + 0.005],
            [w, top.size[1], 0.01],
            BLACK,
        )?;
        for (bx, by) in [(-0.25, 0.1), (0.25, 0.1), (-0.25, -0.2), (0.25, -0.2)] {
            let (x, y) = (bx * w * 0.8, by * d);
            b.add_detail(
                [x, y, body_h + 0.0115],
                [0.16, 0.16, 0.003],
                [0.15, 0.15, 0.15],
            );
            b.add_detail(
                [x, y, body_h + 0.013],
                [0.08, 0.08, 0.002],
                [0.25, 0.08, 0.05],
            );
        }
        b.add_box(
            [0.0, -d / 2.0 + 0.04, h - 0.045],
            [w, 0.08, 0.09],
            shade(ctx.color, 0.9),
        )?;
        for k in 0..4 {
            let x = -w * 0.3 + k as f64 * w * 0.2;
            knob(&mut b, [x, -d / 2.0 + 0.08, h - 0.045], BLACK)?;
        }
        surfaces.push(surface(
            "top",
            "body",
            [0.0, top.center[1], body_h + 0.01],
            [w - 0.05, top.size[1] - 0.1],
            0.5,
        ));
    } else {
        b.add_detail(
            [0.0, c.y_front + 0.001, c.z1 - panel_h / 2.0],
            [w * 0.3, 0.002, 0.04],
            [0.05, 0.2, 0.1],
        );
        for k in 0..2 {
            knob(
                &mut b,
                [
                    -w * 0.3 + k as f64 * w * 0.6,
                    c.y_front,
                    c.z1 - panel_h / 2.0,
                ],
                BLACK,
            )?;
        }
        surfaces.push(c.top_surface(w, d, h, 0.5));
    }
    let lk = Look {
        material: mat,
        front: shade(ctx.color, 0.95),
        inner: BLACK,
        handle: METAL,
    };
    let ov = PANEL / 2.0 - 0.002;
    let o = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: c.z0,
        z1: cavity_top - 0.01 - ov - 0.002,
    };
    let parts = vec![door(
        "oven_door",
        "body",
        o,
        c.y_front,
        ov,
        door_t,
        Hinge::Bottom,
        1.55,
        true,
        lk,
    )?];
    assemble(b, parts, surfaces)
}

/// Dishwasher: a tub behind a door that folds down, with a rack inside.
fn dishwasher(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mat = appliance_material(ctx);
    let mut b = LinkBuilder::new("body", crate::scene::Pose::IDENTITY, mat);
    let door_t = 0.04;
    let c = carcass(&mut b, w, d, h, 0.1, door_t, ctx.color, false)?;
    let rack_z = c.z0 + 0.05;
    let sd = c.inner_d() - 0.04;
    for k in 0..6 {
        let x = c.x0 + 0.03 + k as f64 * (c.inner_w() - 0.06) / 5.0;
        b.add_rod(
            [x, c.y_back + 0.02, rack_z],
            [x, c.y_back + 0.02 + sd, rack_z],
            0.004,
            METAL,
        )?;
    }
    let surfaces = vec![
        surface(
            "rack",
            "body",
            [0.0, c.y_back + 0.02 + sd / 2.0, rack_z + 0.004],
            [c.inner_w() - 0.06, sd],
            c.z1 - rack_z - 0.05,
        ),
        c.top_surface(w, d, h, 0.5),
    ];
    let lk = Look {
        material: mat,
        front: shade(ctx.color, 0.97),
        inner: METAL,
        handle: METAL,
    };
    let ov = PANEL / 2.0 - 0.002;
    let o = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: c.z0,
        z1: c.z1,
    };
    let parts = vec![door(
        "door",
        "body",
        o,
        c.y_front,
        ov,
        door_t,
        Hinge::Bottom,
        1.55,
        false,
        lk,
    )?];
    assemble(b, parts, surfaces)
}

/// Microwave: a cavity behind a glass door hinged on the left, controls on the right.
fn microwave(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mat = appliance_material(ctx);
    let mut b = LinkBuilder::new("body", crate::scene::Pose::IDENTITY, mat);
    let door_t = 0.03;
    let c = carcass(&mut b, w, d, h, 0.0, door_t, ctx.color, false)?;
    let panel_w = (w * 0.25).max(0.08);
    let split = c.x1 - panel_w;
    b.add_box(
        [split + PANEL / 2.0, c.cy(), (c.z0 + c.z1) / 2.0],
        [PANEL, c.inner_d(), c.z1 - c.z0],
        shade(ctx.color, 0.9),
    )?;
    b.add_box(
        [
            (split + PANEL + c.x1) / 2.0,
            c.y_front - 0.01,
            (c.z0 + c.z1) / 2.0,
        ],
        [c.x1 - split - PANEL, 0.02, c.z1 - c.z0],
        BLACK,
    )?;
    b.add_detail(
        [(split + PANEL + c.x1) / 2.0, c.y_front + 0.001, c.z1 - 0.04],
        [panel_w * 0.6, 0.002, 0.025],
        [0.1, 0.5, 0.2],
    );
    let surfaces = vec![
        surface(
            "inside",
            "body",
            [(c.x0 + split) / 2.0, c.cy(), c.z0],
            [split - c.x0 - 0.02, c.inner_d() - 0.02],
            c.z1 - c.z0,
        ),
        c.top_surface(w, d, h, 0.3),
    ];
    let lk = Look {
        material: mat,
        front: BLACK,
        inner: BLACK,
        handle: METAL,
    };
    let o = Opening {
        x0: c.x0,
        x1: split - 0.004,
        z0: c.z0,
        z1: c.z1,
    };
    let parts = vec![door(
        "door",
        "body",
        o,
        c.y_front,
        PANEL / 2.0 - 0.002,
        door_t,
        Hinge::Left,
        1.75,
        true,
        lk,
    )?];
    assemble(b, parts, surfaces)
}

/// Front-loading washing machine (or dryer, variant `dryer`): a cabinet with a control strip
/// and a round porthole door hinged on the left.
fn washing_machine(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mat = appliance_material(ctx);
    let mut b = LinkBuilder::new("body", crate::scene::Pose::IDENTITY, mat);
    let door_t = 0.05;
    b.shell(Some(0.02));
    b.add_rounded_box(
        [0.0, -door_t / 2.0, h / 2.0],
        [w, d - door_t, h],
        0.02,
        ctx.color,
    )?;
    b.shell(None);
    let y_front = d / 2.0 - door_t;
    b.add_detail(
        [0.0, y_front + 0.001, h - 0.08],
        [w * 0.9, 0.002, 0.1],
        shade(ctx.color, 0.9),
    );
    knob(&mut b, [w * 0.25, y_front, h - 0.08], METAL)?;
    b.add_detail(
        [-w * 0.2, y_front + 0.002, h - 0.08],
        [w * 0.25, 0.002, 0.04],
        if ctx.variant == "dryer" {
            [0.6, 0.2, 0.1]
        } else {
            [0.1, 0.3, 0.6]
        },
    );
    let r = (w * 0.34).min((h - 0.2) * 0.4);
    let zc = (h - 0.16) * 0.52;
    // The hinge runs along the porthole's front left edge (as for every door), so the door
    // never swings back into the cabinet.
    let dt = door_t - 0.01;
    let mut dl = LinkBuilder::new(
        "door",
        crate::scene::Pose::from_xyz(-r, y_front + 0.002 + dt, zc),
        mat,
    );
    let ring: Vec<[f64; 2]> = crate::geometry::mesh::circle_ring(0.0, 0.0, r, 24);
    let ring_piece = crate::geometry::ConvexPiece::from_points(
        &ring
            .iter()
            .flat_map(|p| [[p[0] + r, -dt, p[1]], [p[0] + r, 0.0, p[1]]])
            .collect::<Vec<_>>(),
    )?;
    let door_mesh = super::shapes::frustum_mesh([r, -dt, 0.0], [r, 0.0, 0.0], r, r * 0.92, 32);
    dl.add_part(door_mesh, ring_piece, METAL);
    dl.add_visual_rgba(
        super::shapes::frustum_mesh([r, -0.0005, 0.0], [r, 0.0005, 0.0], r * 0.7, r * 0.7, 32),
        [0.3, 0.4, 0.5, 0.6],
    );
    let joint = Joint {
        name: "door_hinge".into(),
        kind: crate::assets::JointKind::Revolute,
        parent: "body".into(),
        child: "door".into(),
        axis: [0.0, 0.0, 1.0],
        lower: 0.0,
        upper: 1.75,
        damping: 0.5,
        effort: 20.0,
    };
    let surfaces = vec![surface(
        "top",
        "body",
        [0.0, -door_t / 2.0, h],
        [w - 0.04, d - door_t - 0.04],
        0.5,
    )];
    assemble(b, vec![(dl.finish()?, joint)], surfaces)
}

/// Water dispenser: a cabinet with two taps and a big blue bottle upside down on top.
fn water_dispenser(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let cab_h = h * 0.68;
    b.shell(Some(0.003));
    b.add_rounded_box([0.0, 0.0, cab_h / 2.0], [w, d, cab_h], 0.02, ctx.color)?;
    b.shell(None);
    b.add_detail(
        [0.0, d / 2.0 + 0.001, cab_h * 0.72],
        [w * 0.6, 0.002, 0.12],
        shade(ctx.color, 0.7),
    );
    for (x, col) in [(-0.05, [0.7, 0.1, 0.1]), (0.05, [0.1, 0.3, 0.8])] {
        b.add_box(
            [x * w / 0.32, d / 2.0 - 0.01, cab_h * 0.75],
            [0.03, 0.02, 0.04],
            col,
        )?;
    }
    let r = (w.min(d) / 2.0) * 0.85;
    b.density(1000.0);
    b.shell(Some(0.003));
    b.add_part_rgba(
        super::shapes::solid_lathe_mesh(
            &[
                (0.04, cab_h),
                (0.04, cab_h + 0.05),
                (r, cab_h + 0.12),
                (r, h - 0.05),
                (r * 0.9, h),
            ],
            32,
        ),
        crate::geometry::ConvexPiece::cylinder(0.0, 0.0, r, cab_h, h, 16)?,
        [0.35, 0.6, 0.9, 0.55],
    );
    b.shell(None);
    single_body(b, vec![])
}

fn single_body(b: LinkBuilder, surfaces: Vec<SurfaceRecord>) -> Result<Generated, GeometryError> {
    super::parts::single(b.finish()?, surfaces)
}
