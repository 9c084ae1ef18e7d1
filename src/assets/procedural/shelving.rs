//! Open shelving and racks: shoe racks, shelves and bookshelves with real clearance between
//! levels (every level is a `shelf_N` surface), metal shelving units, server racks.

use super::parts::{BLACK, METAL, body, shade, surface};
use super::storage::{FRONT, PANEL, assemble, carcass};
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::articulated::parts::{Hinge, Look, Opening, door};
use crate::geometry::GeometryError;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("shoe_rack", shoe_rack),
    ("shelf", shelf),
    ("shelving_unit", shelving_unit),
    ("server_rack", server_rack),
];

/// Shoe rack: open frame with slanted rails on three levels.
fn shoe_rack(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - 0.01), 0.0, h / 2.0],
            [0.02, d, h],
            ctx.color,
        )?;
    }
    let levels = ((h / 0.2).floor() as usize).clamp(2, 5);
    let mut surfaces = Vec::new();
    for i in 0..levels {
        let z = 0.04 + i as f64 * (h - 0.06) / levels as f64;
        for k in 0..2 {
            let y = -d / 2.0 + 0.04 + k as f64 * (d - 0.08);
            b.add_rod(
                [-w / 2.0 + 0.02, y, z + 0.03 * k as f64],
                [w / 2.0 - 0.02, y, z + 0.03 * k as f64],
                0.008,
                ctx.accent_color,
            )?;
        }
        surfaces.push(surface(
            &format!("shelf_{i}"),
            "body",
            [0.0, 0.0, z + 0.03],
            [w - 0.05, d - 0.04],
            (h - 0.06) / levels as f64 - 0.03,
        ));
    }
    b.add_box([0.0, 0.0, h - 0.01], [w, d, 0.02], ctx.color)?;
    surfaces.push(surface("top", "body", [0.0, 0.0, h], [w, d], 0.5));
    assemble(b, vec![], surfaces)
}

/// Open shelving with real clearance between levels, facing +Y: `""` two levels under the top
/// board (the starter shelf), `bookshelf` four or five levels, `wall` / `spice` mounted with
/// its back at y = 0 (see [`super::wall`]).
fn shelf(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let board = 0.022;
    let plinth = 0.05_f64.min(h * 0.08);
    let mut b = body(ctx);
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - board / 2.0), 0.0, h / 2.0],
            [board, d, h],
            ctx.color,
        )?;
    }
    let inner_w = w - 2.0 * board;
    let back = 0.008;
    b.add_box(
        [0.0, -d / 2.0 + back / 2.0, h / 2.0],
        [inner_w, back, h],
        shade(ctx.color, 0.8),
    )?;
    let board_d = d - back;
    let board_cy = -d / 2.0 + back + board_d / 2.0;
    let levels = match ctx.variant {
        "bookshelf" => ((h / 0.36).floor() as usize).clamp(3, 6),
        _ => ((h / 0.45).floor() as usize).clamp(1, 2),
    };
    let bottom_z = plinth + board / 2.0;
    let top_z = h - board / 2.0;
    let pitch = (top_z - bottom_z) / levels as f64;
    let mut surfaces = Vec::new();
    for i in 0..=levels {
        let z = bottom_z + pitch * i as f64;
        b.add_box([0.0, board_cy, z], [inner_w, board_d, board], ctx.color)?;
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
    b.add_box(
        [0.0, d / 2.0 - board / 2.0, plinth / 2.0],
        [inner_w, board, plinth],
        shade(ctx.color, 0.75),
    )?;
    surfaces.push(surface("top", "body", [0.0, 0.0, h], [w, d], 0.6));
    assemble(b, vec![], surfaces)
}

/// Metal shelving unit: four corner posts and four or five steel shelves, open all round.
fn shelving_unit(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let post = 0.03;
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            b.add_box(
                [
                    sx * (w / 2.0 - post / 2.0),
                    sy * (d / 2.0 - post / 2.0),
                    h / 2.0,
                ],
                [post, post, h],
                ctx.accent_color,
            )?;
        }
    }
    let levels = ((h / 0.4).floor() as usize).clamp(3, 6);
    let t = 0.02;
    let bottom = 0.08;
    let pitch = (h - t - bottom) / (levels as f64 - 1.0);
    let mut surfaces = Vec::new();
    for i in 0..levels {
        let z = bottom + pitch * i as f64;
        b.shell(Some(0.001));
        b.add_box(
            [0.0, 0.0, z + t / 2.0],
            [w - 2.0 * post + 0.002, d - 0.004, t],
            ctx.color,
        )?;
        b.shell(None);
        let clearance = if i + 1 < levels { pitch - t } else { 0.6 };
        let id = if i + 1 < levels {
            format!("shelf_{i}")
        } else {
            "top".to_string()
        };
        surfaces.push(surface(
            &id,
            "body",
            [0.0, 0.0, z + t],
            [w - 2.0 * post, d - 0.004],
            clearance,
        ));
    }
    assemble(b, vec![], surfaces)
}

/// Server rack: a tall black cabinet with a perforated glass door and rack units inside.
fn server_rack(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    b.shell(Some(0.002));
    let c = carcass(&mut b, w, d, h, 0.06, FRONT, BLACK, false)?;
    b.shell(None);
    // Equipment: 1U/2U boxes with blinking-light strips, with gaps between.
    let mut z = c.z0 + 0.05;
    let unit = 0.0445;
    let mut k = 0;
    let ew = c.inner_w() - 0.02;
    let ed = c.inner_d() - 0.12;
    while z + 2.0 * unit < c.z1 - 0.1 && k < 14 {
        let units = if k % 3 == 0 { 2.0 } else { 1.0 };
        let hh = units * unit - 0.004;
        b.shell(Some(0.0015));
        b.add_box(
            [0.0, c.y_front - 0.02 - ed / 2.0, z + hh / 2.0],
            [ew, ed, hh],
            [0.08, 0.08, 0.09],
        )?;
        b.shell(None);
        b.add_detail(
            [ew * 0.3, c.y_front - 0.019, z + hh / 2.0],
            [0.08, 0.002, 0.006],
            if k % 2 == 0 {
                [0.1, 0.8, 0.2]
            } else {
                [0.2, 0.4, 0.9]
            },
        );
        z += units * unit + 0.015;
        k += 1;
    }
    let lk = Look {
        material: ctx.material,
        front: [0.05, 0.05, 0.06],
        inner: BLACK,
        handle: METAL,
    };
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
        PANEL / 2.0 - 0.002,
        FRONT,
        Hinge::Left,
        1.75,
        true,
        lk,
    )?];
    let surfaces = vec![c.top_surface(w, d, h, 0.3)];
    assemble(b, parts, surfaces)
}
