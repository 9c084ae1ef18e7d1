//! Small manipulable objects: mugs, plates, books.

use rand::RngExt;

use super::furniture::{shade, surface};
use super::{GenContext, Generated};
use crate::assets::LinkBuilder;
use crate::geometry::convex::revolved_pieces;
use crate::geometry::{ConvexPiece, GeometryError, mesh};
use crate::scene::Pose;

/// Mug: an open cylinder with a thick base and a handle on +X.
///
/// Collision: a base disc plus one hull per wall sector, so the cavity stays open and things
/// (spoons, pens) can go inside.
pub(crate) fn mug(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    // The handle takes part of the width budget.
    let r = (w / 2.0) * 0.78;
    let wall = (r * 0.1).clamp(0.003, 0.006);
    let base = 0.008;
    let profile = [
        (0.0, 0.0),
        (r, 0.0),
        (r, h),
        (r - wall, h),
        (r - wall, base),
        (0.0, base),
    ];
    let mut body = LinkBuilder::new("body", Pose::IDENTITY, ctx.material);
    body.add_visual(mesh::lathe_mesh(&profile, 32), ctx.color);
    body.add_collision(ConvexPiece::cylinder(0.0, 0.0, r, 0.0, base, 16)?);
    let wall_profile = [(r - wall, base), (r, base), (r, h), (r - wall, h)];
    for piece in revolved_pieces(&wall_profile, 16)? {
        body.add_collision(piece);
    }
    // Handle: two arms and a grip, on +X, inside the width budget.
    let reach = (w / 2.0 - r).max(0.012);
    let t = 0.009;
    let grip_x = r + reach - t / 2.0;
    let arm_len = reach;
    let handle_color = ctx.color;
    for z in [h * 0.78, h * 0.3] {
        body.add_box(
            [r + arm_len / 2.0 - 0.001, 0.0, z],
            [arm_len, t, t],
            handle_color,
        )?;
    }
    let grip_h = h * 0.48 - t;
    body.add_box(
        [grip_x, 0.0, (h * 0.78 + h * 0.3) / 2.0],
        [t, t, grip_h],
        handle_color,
    )?;
    let link = body.finish()?;
    Ok(Generated {
        links: vec![link],
        joints: vec![],
        surfaces: vec![],
    })
}

/// Plate: a flat base disc and a sloped rim; plates nest when stacked.
pub(crate) fn plate(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, _d, h] = ctx.size;
    let r_out = w / 2.0;
    let r_base = r_out * 0.68;
    let base_t = (h * 0.25).clamp(0.003, 0.007);
    let rim_t = (h * 0.2).clamp(0.003, 0.006);
    let mut body = LinkBuilder::new("body", Pose::IDENTITY, ctx.material);
    let visual_profile = [
        (0.0, 0.0),
        (r_base, 0.0),
        (r_out, h - rim_t),
        (r_out, h),
        (r_base - 0.002, base_t),
        (0.0, base_t),
    ];
    body.add_visual(mesh::lathe_mesh(&visual_profile, 40), ctx.color);
    body.add_collision(ConvexPiece::cylinder(0.0, 0.0, r_base, 0.0, base_t, 16)?);
    let rim_profile = [
        (r_base - 0.002, 0.0),
        (r_out, h - rim_t),
        (r_out, h),
        (r_base - 0.002, base_t),
    ];
    for piece in revolved_pieces(&rim_profile, 16)? {
        body.add_collision(piece);
    }
    Ok(Generated {
        links: vec![body.finish()?],
        joints: vec![],
        surfaces: vec![surface(
            "top",
            "body",
            [0.0, 0.0, base_t],
            [r_base * 1.4, r_base * 1.4],
            0.3,
        )],
    })
}

/// Book standing upright: spine towards +Y, thickness along X, height along Z.
pub(crate) fn book(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
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
    let cover = COVERS[ctx.rng.random_range(0..COVERS.len())];
    let mut body = LinkBuilder::new("body", Pose::IDENTITY, ctx.material);
    // One collision box for the whole book; visuals show covers and a page block.
    body.add_collision(ConvexPiece::cuboid([0.0, 0.0, h / 2.0], [t, d, h])?);
    let c = 0.0025_f64.min(t * 0.2);
    body.add_visual(
        mesh::box_mesh([-(t - c) / 2.0, 0.0, h / 2.0], [c, d, h]),
        cover,
    );
    body.add_visual(
        mesh::box_mesh([(t - c) / 2.0, 0.0, h / 2.0], [c, d, h]),
        cover,
    );
    body.add_visual(
        mesh::box_mesh([0.0, d / 2.0 - c / 2.0, h / 2.0], [t - 2.0 * c, c, h]),
        shade(cover, 0.8),
    );
    body.add_visual(
        mesh::box_mesh(
            [0.0, -c / 2.0, h / 2.0],
            [t - 2.0 * c, d - c - 0.004, h - 0.006],
        ),
        [0.95, 0.93, 0.86],
    );
    Ok(Generated {
        links: vec![body.finish()?],
        joints: vec![],
        surfaces: vec![],
    })
}
