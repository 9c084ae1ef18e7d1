//! Bathroom fixtures: toilets (with a seat lid on a hinge), bathtubs and shower trays with
//! real cavities, shower enclosures, sink vanities (basin in the top, doors below) and
//! pedestal sinks.

use super::kitchen::{FAUCET, top_with_basin, tops_beside_basin};
use super::parts::{METAL, WHITE, body, shade, single, surface};
use super::storage::{PANEL, carcass_opts};
use super::{GenContext, Generated, GeneratorFn};
use crate::assets::articulated::parts::{Look, Opening, door_pair, lid};
use crate::geometry::GeometryError;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("toilet", toilet),
    ("bathtub", bathtub),
    ("shower", shower),
    ("sink_vanity", sink_vanity),
];

/// Toilet: a pedestal and an open bowl at the front, a cistern at the back, a seat ring and a
/// lid hinged behind the seat.
fn toilet(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let porcelain = ctx.color;
    let tank_d = (d * 0.25).clamp(0.15, 0.22);
    let y_tank_front = -d / 2.0 + tank_d;
    let rim = 0.4_f64.min(h * 0.55);
    // Cistern.
    b.shell(Some(0.01));
    b.add_rounded_box(
        [0.0, -d / 2.0 + tank_d / 2.0, (rim - 0.05 + h) / 2.0],
        [w, tank_d, h - rim + 0.05],
        0.02,
        porcelain,
    )?;
    b.shell(None);
    b.add_detail(
        [w * 0.25, -d / 2.0 + tank_d / 2.0, h + 0.0],
        [0.04, 0.02, 0.01],
        METAL,
    );
    // Pedestal.
    let bowl_len = d - tank_d - 0.04;
    let by = y_tank_front + 0.04 + bowl_len / 2.0;
    b.add_rounded_box(
        [0.0, by - 0.05, (rim - 0.12) / 2.0],
        [w * 0.5, bowl_len * 0.6, rim - 0.12],
        0.03,
        porcelain,
    )?;
    // Bowl: an elliptical vessel, built round then squashed in x.
    let r = bowl_len / 2.0;
    let sx = (w * 0.92 / 2.0) / r;
    let outer = [
        (r * 0.45, rim - 0.13),
        (r * 0.85, rim - 0.06),
        (r, rim - 0.005),
    ];
    let (visual, pieces) =
        super::shapes::vessel(&outer.map(|(a, z)| (a, z - (rim - 0.13))), 0.018, 0.02, 12)?;
    let place = crate::scene::Pose::from_xyz(0.0, by, rim - 0.13);
    let squash = |m: &crate::geometry::TriMesh| m.scaled([sx, 1.0, 1.0]).transformed(&place);
    for p in pieces {
        let pts: Vec<[f64; 3]> = p.vertices.iter().map(|v| [v[0] * sx, v[1], v[2]]).collect();
        b.add_collision(crate::geometry::ConvexPiece::from_points(&pts)?.transformed(&place));
    }
    b.add_visual(squash(&visual), porcelain);
    // Water in the bowl (visual).
    b.add_visual_rgba(
        super::shapes::ellipsoid_mesh([0.0, by, rim - 0.1], [r * 0.5 * sx, r * 0.5, 0.01], 16),
        [0.6, 0.75, 0.85, 0.7],
    );
    // Seat ring on the rim.
    let seat_t = 0.02;
    let seat_color = shade(porcelain, 0.98);
    let ring_r = r * 0.92;
    let n = 10;
    for i in 0..n {
        let a0 = std::f64::consts::TAU * i as f64 / n as f64;
        let a1 = std::f64::consts::TAU * (i + 1) as f64 / n as f64;
        let p = |a: f64| {
            [
                ring_r * a.cos() * sx,
                by + ring_r * a.sin(),
                rim + seat_t / 2.0,
            ]
        };
        b.add_rod(p(a0), p(a1), seat_t / 2.0, seat_color)?;
    }
    let lk = Look {
        material: ctx.material,
        front: seat_color,
        inner: seat_color,
        handle: seat_color,
    };
    let lid_y0 = y_tank_front + 0.005;
    let (lid_link, lid_joint) = lid(
        "lid",
        "body",
        [-ring_r * sx - 0.01, ring_r * sx + 0.01],
        [lid_y0, (by + r).min(d / 2.0)],
        rim + seat_t,
        0.018,
        1.5,
        lk,
    )?;
    Ok(Generated {
        links: vec![b.finish()?, lid_link],
        joints: vec![lid_joint],
        surfaces: vec![surface(
            "top",
            "body",
            [0.0, -d / 2.0 + tank_d / 2.0, h],
            [w * 0.9, tank_d * 0.8],
            0.4,
        )],
    })
}

/// Bathtub: a rectangular tub with a real basin (floor and four walls), rounded rim, faucet.
fn bathtub(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let wall = 0.06;
    let floor_t = 0.06;
    let c = ctx.color;
    // Apron panel base so the tub stands on the floor.
    b.add_box([0.0, 0.0, floor_t / 2.0], [w, d, floor_t], c)?;
    for sx in [-1.0, 1.0] {
        b.add_box([sx * (w / 2.0 - wall / 2.0), 0.0, h / 2.0], [wall, d, h], c)?;
    }
    for sy in [-1.0, 1.0] {
        b.add_box(
            [0.0, sy * (d / 2.0 - wall / 2.0), h / 2.0],
            [w - 2.0 * wall, wall, h],
            c,
        )?;
    }
    // Sloped back rest at the -x end (visual + collision wedge).
    let wedge = super::shapes::xz_prism_piece(
        &[
            [-w / 2.0 + wall, floor_t],
            [-w / 2.0 + wall + 0.25, floor_t],
            [-w / 2.0 + wall, h - 0.1],
        ],
        -d / 2.0 + wall,
        d / 2.0 - wall,
    )?;
    b.add_part(
        super::shapes::xz_prism_mesh(
            &[
                [-w / 2.0 + wall, floor_t],
                [-w / 2.0 + wall + 0.25, floor_t],
                [-w / 2.0 + wall, h - 0.1],
            ],
            -d / 2.0 + wall,
            d / 2.0 - wall,
        ),
        wedge,
        c,
    );
    // Faucet at the +x end.
    let fx = w / 2.0 - wall / 2.0;
    b.add_rod(
        [fx, 0.0, h - 0.03],
        [fx - 0.14, 0.0, h - 0.03],
        0.015,
        METAL,
    )?;
    single(
        b.finish()?,
        vec![
            surface(
                "basin",
                "body",
                [0.1, 0.0, floor_t],
                [w - 2.0 * wall - 0.3, d - 2.0 * wall],
                h - floor_t,
            ),
            surface(
                "rim",
                "body",
                [w / 2.0 - wall / 2.0, 0.0, h],
                [wall, d],
                0.4,
            ),
        ],
    )
}

/// Shower enclosure: a tray with a low lip, a back panel with a head on a riser, and glass on
/// the two open sides except the entry.
fn shower(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let tray_h = 0.1;
    let lip = 0.03;
    b.add_box([0.0, 0.0, 0.02], [w, d, 0.04], WHITE)?;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - lip / 2.0), 0.0, tray_h / 2.0],
            [lip, d, tray_h],
            WHITE,
        )?;
    }
    b.add_box(
        [0.0, d / 2.0 - lip / 2.0, tray_h / 2.0],
        [w - 2.0 * lip, lip, tray_h],
        WHITE,
    )?;
    b.add_box([0.0, -d / 2.0 + 0.02, h / 2.0], [w, 0.04, h], ctx.color)?;
    // Glass on the right side and half the front.
    b.density(2500.0);
    let glass = [0.75, 0.85, 0.9, 0.3];
    b.add_part_rgba(
        crate::geometry::mesh::box_mesh(
            [w / 2.0 - 0.005, 0.0, (tray_h + h) / 2.0],
            [0.01, d - 0.04, h - tray_h],
        ),
        crate::geometry::ConvexPiece::cuboid(
            [w / 2.0 - 0.005, 0.0, (tray_h + h) / 2.0],
            [0.01, d - 0.04, h - tray_h],
        )?,
        glass,
    );
    b.add_part_rgba(
        crate::geometry::mesh::box_mesh(
            [w / 4.0, d / 2.0 - 0.005, (tray_h + h) / 2.0],
            [w / 2.0, 0.01, h - tray_h],
        ),
        crate::geometry::ConvexPiece::cuboid(
            [w / 4.0, d / 2.0 - 0.005, (tray_h + h) / 2.0],
            [w / 2.0, 0.01, h - tray_h],
        )?,
        glass,
    );
    b.material_density();
    b.add_rod(
        [w / 2.0 - 0.005, d / 2.0 - 0.005, tray_h],
        [w / 2.0 - 0.005, d / 2.0 - 0.005, h],
        0.012,
        METAL,
    )?;
    // Riser, head and a mixer.
    let ry = -d / 2.0 + 0.06;
    b.add_rod([0.0, ry, 1.0], [0.0, ry, h - 0.15], 0.012, METAL)?;
    b.add_rod([0.0, ry, h - 0.15], [0.0, ry + 0.2, h - 0.15], 0.01, METAL)?;
    b.add_frustum(
        [0.0, ry + 0.2, h - 0.16],
        [0.0, ry + 0.2, h - 0.2],
        0.02,
        0.09,
        METAL,
    )?;
    b.add_box([0.0, ry - 0.015, 1.05], [0.12, 0.03, 0.06], METAL)?;
    single(
        b.finish()?,
        // The tray is a wet basin like a tub's: kept clear by the usual clutter.
        vec![surface(
            "basin",
            "body",
            [0.0, 0.0, 0.04],
            [w - 2.0 * lip, d - 0.1],
            h - 0.2,
        )],
    )
}

/// Headroom over a vanity's counter, metres (the mirror hangs higher, against the wall).
const VANITY_CLEARANCE: f64 = 0.35;

/// Sink vanity: a cabinet with two doors under a top with a basin and faucet; the `pedestal`
/// variant is a basin on a column.
fn sink_vanity(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    if ctx.variant == "pedestal" {
        let top = h - FAUCET;
        b.add_frustum(
            [0.0, -0.05, 0.0],
            [0.0, -0.05, top - 0.04 - 0.13],
            0.12,
            0.08,
            WHITE,
        )?;
        let s = top_with_basin(
            &mut b,
            -w / 2.0,
            w / 2.0,
            -d / 2.0,
            d / 2.0,
            top,
            0.04,
            0.0,
            0.03,
            w * 0.62,
            d * 0.55,
            0.13,
            WHITE,
            WHITE,
        )?;
        let mut surfaces = vec![s];
        surfaces.extend(tops_beside_basin(
            [-w / 2.0, w / 2.0, -d / 2.0, d / 2.0],
            top,
            0.0,
            w * 0.62,
            VANITY_CLEARANCE,
        ));
        return single(b.finish()?, surfaces);
    }
    let top_t = 0.03;
    let worktop = h - FAUCET;
    let c = carcass_opts(
        &mut b,
        w,
        d,
        worktop - top_t,
        0.08,
        0.02,
        ctx.color,
        false,
        false,
    )?;
    let bw = (w * 0.55).min(0.5);
    let bd = (d * 0.55).min(0.38);
    let by = -d / 2.0 + 0.12 + bd / 2.0;
    let basin = top_with_basin(
        &mut b,
        -w / 2.0,
        w / 2.0,
        -d / 2.0,
        d / 2.0,
        worktop,
        top_t,
        0.0,
        by,
        bw,
        bd,
        0.14,
        ctx.accent_color,
        WHITE,
    )?;
    // The basin hangs into the cabinet: keep the doors' shelf below it.
    let lk = Look {
        material: ctx.material,
        front: shade(ctx.color, 0.97),
        inner: shade(ctx.color, 0.8),
        handle: METAL,
    };
    let ov = PANEL / 2.0 - 0.0015;
    let full = Opening {
        x0: c.x0,
        x1: c.x1,
        z0: c.z0,
        z1: c.z1,
    };
    let parts = door_pair("body", full, c.y_front, ov, 0.02, 1.75, false, lk)?;
    let mut surfaces = vec![
        basin,
        surface(
            "shelf_0",
            "body",
            [0.0, c.cy(), c.z0],
            [c.inner_w() - 0.02, c.inner_d() - 0.02],
            worktop - top_t - 0.16 - c.z0,
        ),
    ];
    surfaces.extend(tops_beside_basin(
        [-w / 2.0, w / 2.0, -d / 2.0, d / 2.0],
        worktop,
        0.0,
        bw,
        VANITY_CLEARANCE,
    ));
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
