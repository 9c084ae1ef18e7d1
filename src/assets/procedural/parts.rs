//! Small building blocks shared by the generator families: colours, surface records, legs,
//! single-link results.

use super::{GenContext, Generated};
use crate::assets::{Link, LinkBuilder};
use crate::geometry::GeometryError;
use crate::scene::{Pose, SurfaceRecord};

/// Brushed metal.
pub const METAL: [f64; 3] = [0.62, 0.63, 0.65];
/// Dark metal / black plastic.
pub const BLACK: [f64; 3] = [0.03, 0.03, 0.035];
/// Off-white plastic / enamel.
pub const WHITE: [f64; 3] = [0.88, 0.88, 0.86];
/// A switched-off screen.
pub const SCREEN: [f64; 3] = [0.015, 0.02, 0.03];
/// Leaf green.
pub const LEAF: [f64; 3] = [0.10, 0.32, 0.08];
/// Potting soil.
pub const SOIL: [f64; 3] = [0.10, 0.06, 0.035];
/// Mirror / glass tint.
pub const MIRROR: [f64; 3] = [0.70, 0.78, 0.82];
/// Bed linen.
pub const LINEN: [f64; 3] = [0.90, 0.89, 0.85];

/// Darker (f < 1) or lighter (f > 1) shade of a colour.
pub(crate) fn shade(c: [f64; 3], f: f64) -> [f64; 3] {
    c.map(|v| (v * f).clamp(0.0, 1.0))
}

/// Linear mix of two colours.
pub(crate) fn mix(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [0, 1, 2].map(|i| a[i] + (b[i] - a[i]) * t)
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

/// A new root link called `body` in the context's material.
pub(crate) fn body(ctx: &GenContext) -> LinkBuilder {
    LinkBuilder::new("body", Pose::IDENTITY, ctx.material)
}

/// One rigid link, no joints.
pub(crate) fn single(link: Link, surfaces: Vec<SurfaceRecord>) -> Result<Generated, GeometryError> {
    Ok(Generated {
        links: vec![link],
        joints: vec![],
        surfaces,
    })
}

/// How legs look.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum LegShape {
    /// Square section.
    Square,
    /// Round, tapering towards the floor (mid-century, art deco).
    Tapered,
    /// Round, straight (metal tube).
    Round,
}

impl LegShape {
    /// The leg shape a style suggests, `fallback` otherwise.
    pub(crate) fn for_style(ctx: &GenContext, fallback: LegShape) -> LegShape {
        match ctx.style_name() {
            "mid_century" | "art_deco" | "vintage" => LegShape::Tapered,
            "modern" | "industrial" | "steampunk" => LegShape::Round,
            "rustic" | "minimalist" => LegShape::Square,
            _ => fallback,
        }
    }
}

/// Four legs of section `t` from z = `z0` to `z1`, inset `inset` from a `w` x `d` rectangle
/// centred at (0, `cy`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn four_legs(
    b: &mut LinkBuilder,
    w: f64,
    d: f64,
    cy: f64,
    z0: f64,
    z1: f64,
    t: f64,
    inset: f64,
    shape: LegShape,
    color: [f64; 3],
) -> Result<(), GeometryError> {
    let lx = w / 2.0 - inset - t / 2.0;
    let ly = d / 2.0 - inset - t / 2.0;
    for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let (x, y) = (sx * lx, cy + sy * ly);
        match shape {
            LegShape::Square => {
                b.add_box([x, y, (z0 + z1) / 2.0], [t, t, z1 - z0], color)?;
            }
            LegShape::Round => {
                b.add_rod([x, y, z0], [x, y, z1], t / 2.0, color)?;
            }
            LegShape::Tapered => {
                b.add_frustum([x, y, z0], [x, y, z1], t * 0.3, t / 2.0, color)?;
            }
        }
    }
    Ok(())
}

/// An apron (rails under a top) of height `h` below `z_top` around a `w` x `d` rectangle.
pub(crate) fn apron(
    b: &mut LinkBuilder,
    w: f64,
    d: f64,
    z_top: f64,
    h: f64,
    t: f64,
    color: [f64; 3],
) -> Result<(), GeometryError> {
    let zc = z_top - h / 2.0;
    b.add_box([0.0, d / 2.0 - t / 2.0, zc], [w - 2.0 * t, t, h], color)?;
    b.add_box([0.0, -d / 2.0 + t / 2.0, zc], [w - 2.0 * t, t, h], color)?;
    b.add_box([w / 2.0 - t / 2.0, 0.0, zc], [t, d, h], color)?;
    b.add_box([-w / 2.0 + t / 2.0, 0.0, zc], [t, d, h], color)?;
    Ok(())
}

/// A bar handle (two posts and a grip) on the +Y face at `y`, horizontal when `vertical` is
/// false; the grip stands `reach` in front of the face.
pub(crate) fn bar_handle(
    b: &mut LinkBuilder,
    center: [f64; 3],
    length: f64,
    vertical: bool,
    color: [f64; 3],
) -> Result<(), GeometryError> {
    let reach = 0.025;
    let r = 0.006;
    let [x, y, z] = center;
    let (a, c) = if vertical {
        (
            [x, y + reach, z - length / 2.0],
            [x, y + reach, z + length / 2.0],
        )
    } else {
        (
            [x - length / 2.0, y + reach, z],
            [x + length / 2.0, y + reach, z],
        )
    };
    b.add_rod(a, c, r, color)?;
    for p in [a, c] {
        b.add_box([p[0], y + reach / 2.0, p[2]], [0.012, reach, 0.012], color)?;
    }
    Ok(())
}

/// A round knob on the +Y face.
pub(crate) fn knob(
    b: &mut LinkBuilder,
    center: [f64; 3],
    color: [f64; 3],
) -> Result<(), GeometryError> {
    let [x, y, z] = center;
    b.add_rod([x, y, z], [x, y + 0.022, z], 0.012, color)?;
    Ok(())
}
