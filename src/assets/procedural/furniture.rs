//! Floor-standing furniture made of boxes: tables, chairs, cabinets, shelves.

use rand::RngExt;

use super::{GenContext, Generated};
use crate::assets::{Joint, JointKind, LinkBuilder};
use crate::geometry::GeometryError;
use crate::scene::{Pose, SurfaceRecord};

/// Darker shade of a colour, for trims and handles.
pub(crate) fn shade(c: [f64; 3], f: f64) -> [f64; 3] {
    c.map(|v| (v * f).clamp(0.0, 1.0))
}

/// A horizontal support surface record.
pub(crate) fn surface(
    id: &str,
    link: &str,
    center: [f64; 3],
    size: [f64; 2],
    clearance: f64,
) -> SurfaceRecord {
    SurfaceRecord {
        id: id.to_string(),
        link: link.to_string(),
        center,
        size,
        clearance,
    }
}

/// Four-legged table: a top and square legs inset from the corners.
pub(crate) fn table(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let top_t = (0.03 + 0.01 * ctx.rng.random_range(0.0..1.0_f64)).min(h * 0.1);
    let leg = (0.035 + 0.015 * (w.max(d) / 2.0).min(1.0)).min(w.min(d) * 0.15);
    let inset = 0.03;
    let mut body = LinkBuilder::new("body", Pose::IDENTITY, ctx.material);
    body.add_box([0.0, 0.0, h - top_t / 2.0], [w, d, top_t], ctx.color)?;
    let lx = w / 2.0 - inset - leg / 2.0;
    let ly = d / 2.0 - inset - leg / 2.0;
    let leg_h = h - top_t;
    let leg_color = shade(ctx.color, 0.85);
    for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        body.add_box(
            [sx * lx, sy * ly, leg_h / 2.0],
            [leg, leg, leg_h],
            leg_color,
        )?;
    }
    Ok(Generated {
        links: vec![body.finish()?],
        joints: vec![],
        surfaces: vec![surface("top", "body", [0.0, 0.0, h], [w, d], 1.0)],
    })
}

/// Chair facing +Y: legs, a seat at 45-50 % of the height, a backrest at the back (-Y).
pub(crate) fn chair(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let seat_h = (h * 0.5).clamp(0.4, 0.5);
    let seat_t = 0.04;
    let leg = 0.035;
    let back_t = 0.03;
    let mut body = LinkBuilder::new("body", Pose::IDENTITY, ctx.material);
    let leg_h = seat_h - seat_t;
    let (lx, ly) = (w / 2.0 - leg / 2.0, d / 2.0 - leg / 2.0);
    for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        body.add_box(
            [sx * lx, sy * ly, leg_h / 2.0],
            [leg, leg, leg_h],
            shade(ctx.color, 0.85),
        )?;
    }
    body.add_box([0.0, 0.0, seat_h - seat_t / 2.0], [w, d, seat_t], ctx.color)?;
    // Back posts continue the rear legs; a panel spans them in the upper part.
    let post_h = h - seat_h;
    for sx in [-1.0, 1.0] {
        body.add_box(
            [sx * lx, -d / 2.0 + back_t / 2.0, seat_h + post_h / 2.0],
            [leg, back_t, post_h],
            shade(ctx.color, 0.85),
        )?;
    }
    let panel_h = post_h * 0.45;
    body.add_box(
        [0.0, -d / 2.0 + back_t / 2.0, h - panel_h / 2.0],
        [w - 2.0 * leg, back_t * 0.8, panel_h],
        ctx.color,
    )?;
    let seat_depth = d - back_t;
    Ok(Generated {
        links: vec![body.finish()?],
        joints: vec![],
        surfaces: vec![surface(
            "seat",
            "body",
            [0.0, back_t / 2.0, seat_h],
            [w - 2.0 * leg, seat_depth],
            0.4,
        )],
    })
}

/// Panel thickness of case furniture, metres.
const PANEL: f64 = 0.018;

/// Box cabinet with one hinged door on the front (+Y), an inner shelf and a plinth.
///
/// The door link's frame sits on the hinge line (front-left vertical edge); the door opens
/// outward for positive joint angles, up to 100 degrees.
pub(crate) fn cabinet(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let door_t = PANEL;
    let cd = d - door_t; // carcass depth; the door adds its thickness in front
    let y_back = -d / 2.0;
    let y_front = y_back + cd;
    let cy = (y_back + y_front) / 2.0;
    let plinth = 0.06_f64.min(h * 0.1);
    let mut body = LinkBuilder::new("body", Pose::IDENTITY, ctx.material);
    // Sides, bottom, top, back.
    for sx in [-1.0, 1.0] {
        body.add_box(
            [sx * (w / 2.0 - PANEL / 2.0), cy, h / 2.0],
            [PANEL, cd, h],
            ctx.color,
        )?;
    }
    let inner_w = w - 2.0 * PANEL;
    body.add_box(
        [0.0, cy, plinth + PANEL / 2.0],
        [inner_w, cd, PANEL],
        ctx.color,
    )?;
    body.add_box([0.0, cy, h - PANEL / 2.0], [inner_w, cd, PANEL], ctx.color)?;
    body.add_box(
        [
            0.0,
            y_back + PANEL / 2.0,
            (plinth + PANEL + h - PANEL) / 2.0,
        ],
        [inner_w, PANEL, h - PANEL - plinth - PANEL],
        shade(ctx.color, 0.9),
    )?;
    // Plinth board at the front, recessed.
    body.add_box(
        [0.0, y_front - 0.04, plinth / 2.0],
        [inner_w, PANEL, plinth],
        shade(ctx.color, 0.7),
    )?;
    // Inner shelf halfway up the inside.
    let inner_bottom = plinth + PANEL;
    let inner_top = h - PANEL;
    let shelf_z = (inner_bottom + inner_top) / 2.0;
    let inner_d = cd - PANEL - 0.01;
    let shelf_cy = y_back + PANEL + inner_d / 2.0;
    body.add_box(
        [0.0, shelf_cy, shelf_z],
        [inner_w - 0.002, inner_d, PANEL],
        ctx.color,
    )?;

    let door_w = w - 0.004;
    let door_h = h - plinth - 0.004;
    let hinge_x = -w / 2.0 + 0.002;
    let mut door = LinkBuilder::new(
        "door",
        Pose::from_xyz(hinge_x, y_front, plinth + 0.002),
        ctx.material,
    );
    door.add_box(
        [door_w / 2.0, door_t / 2.0, door_h / 2.0],
        [door_w, door_t, door_h],
        shade(ctx.color, 0.97),
    )?;
    // Handle near the free edge.
    let handle_h = (door_h * 0.15).clamp(0.08, 0.2);
    door.add_box(
        [door_w - 0.05, door_t + 0.0125, door_h * 0.6],
        [0.015, 0.025, handle_h],
        [0.7, 0.7, 0.72],
    )?;

    let joints = vec![Joint {
        name: "door_hinge".into(),
        kind: JointKind::Revolute,
        parent: "body".into(),
        child: "door".into(),
        axis: [0.0, 0.0, 1.0],
        lower: 0.0,
        upper: 100f64.to_radians(),
        damping: 0.5,
        effort: 20.0,
    }];
    let inner_clear = shelf_z - PANEL / 2.0 - inner_bottom;
    Ok(Generated {
        links: vec![body.finish()?, door.finish()?],
        joints,
        surfaces: vec![
            surface("top", "body", [0.0, cy, h], [w, cd], 1.0),
            surface(
                "shelf_0",
                "body",
                [0.0, shelf_cy, inner_bottom],
                [inner_w, inner_d],
                inner_clear,
            ),
            surface(
                "shelf_1",
                "body",
                [0.0, shelf_cy, shelf_z + PANEL / 2.0],
                [inner_w, inner_d],
                inner_top - shelf_z - PANEL / 2.0,
            ),
        ],
    })
}

/// Open shelf unit with two usable levels below the top board, facing +Y.
pub(crate) fn shelf(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let board = 0.022;
    let plinth = 0.05_f64.min(h * 0.08);
    let mut body = LinkBuilder::new("body", Pose::IDENTITY, ctx.material);
    for sx in [-1.0, 1.0] {
        body.add_box(
            [sx * (w / 2.0 - board / 2.0), 0.0, h / 2.0],
            [board, d, h],
            ctx.color,
        )?;
    }
    let inner_w = w - 2.0 * board;
    let back = 0.008;
    body.add_box(
        [0.0, -d / 2.0 + back / 2.0, h / 2.0],
        [inner_w, back, h],
        shade(ctx.color, 0.8),
    )?;
    let board_d = d - back;
    let board_cy = -d / 2.0 + back + board_d / 2.0;
    let levels = 2;
    // Boards: bottom (on the plinth), one middle, top.
    let bottom_z = plinth + board / 2.0;
    let top_z = h - board / 2.0;
    let pitch = (top_z - bottom_z) / levels as f64;
    let mut surfaces = Vec::new();
    for i in 0..=levels {
        let z = bottom_z + pitch * i as f64;
        body.add_box([0.0, board_cy, z], [inner_w, board_d, board], ctx.color)?;
        if i < levels {
            surfaces.push(surface(
                &format!("shelf_{i}"),
                "body",
                [0.0, board_cy, z + board / 2.0],
                [inner_w, board_d],
                pitch - board,
            ));
        }
    }
    body.add_box(
        [0.0, d / 2.0 - board / 2.0, plinth / 2.0],
        [inner_w, board, plinth],
        shade(ctx.color, 0.75),
    )?;
    surfaces.push(surface("top", "body", [0.0, 0.0, h], [w, d], 0.6));
    Ok(Generated {
        links: vec![body.finish()?],
        joints: vec![],
        surfaces,
    })
}
