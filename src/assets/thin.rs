//! Thin coverings: rugs (rectangular, round, runners, bath and door mats, yoga mats),
//! tablecloths and placemats lying on a surface (bottom at z = 0), posters and paintings on a
//! wall (back at y = 0). Thin closed slabs whose top or front face carries a procedural PNG
//! texture: tileable patterns for textiles, generated artwork for pictures.
//!
//! The texture follows the request's style (palette and motif) and seed, so "a Frozen rug"
//! gets snowflakes and "a Picasso-style painting" a cubist composition.

use super::procedural::parts::{body, shade, single};
use super::procedural::shapes::{TexFace, textured_slab};
use super::procedural::{GenContext, Generated, GeneratorFn};
use super::textures::{self, Art, Pattern};
use crate::geometry::{ConvexPiece, GeometryError};

pub(crate) const GENERATORS: &[(&str, GeneratorFn)] = &[
    ("rug", rug),
    ("table_linen", table_linen),
    ("picture", picture),
];

fn seed_of(ctx: &mut GenContext) -> u64 {
    (ctx.uniform(0.0, 1.0) * 1e9) as u64
}

/// Palette for a textile: the style's, or the request colour with two companions.
fn textile_palette(ctx: &GenContext) -> Vec<[f64; 3]> {
    match &ctx.style {
        Some(s) if s.palette.len() >= 2 => {
            let mut p = vec![ctx.color];
            p.extend(s.palette.iter().copied());
            p
        }
        _ => vec![ctx.color, shade(ctx.color, 1.8), shade(ctx.color, 0.45)],
    }
}

/// Rugs and mats by variant: `""` rectangular with border and medallion, `round`, `runner`,
/// `bath`, `door`, `yoga` (plain rubber).
fn rug(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let seed = seed_of(ctx);
    let palette = textile_palette(ctx);
    let motif = ctx
        .style
        .as_ref()
        .map_or(Pattern::Kilim, |s| Pattern::for_motif(&s.motif));
    let round = ctx.variant == "round";
    let tex = match ctx.variant {
        "yoga" => textures::pattern(Pattern::Carpet, &[ctx.color], 64, seed),
        "bath" | "door" => textures::pattern(Pattern::Carpet, &[ctx.color], 128, seed),
        "runner" => textures::pattern(Pattern::Stripes, &palette, 256, seed),
        _ => textures::rug(&palette, motif, round, 256, seed),
    };
    if round {
        let r = w.min(d) / 2.0;
        let mut m = crate::geometry::mesh::cylinder_mesh(0.0, 0.0, r, 0.0, h, 48);
        m.uvs = m
            .positions
            .iter()
            .map(|p| [0.5 + p[0] / (2.0 * r), 0.5 - p[1] / (2.0 * r)])
            .collect();
        b.add_collision(ConvexPiece::cylinder(0.0, 0.0, r, 0.0, h, 24)?);
        b.add_textured_visual(m, tex);
    } else {
        let repeat = if ctx.variant == "runner" {
            [1.0, (d / w).max(1.0).round()]
        } else {
            [1.0, 1.0]
        };
        b.add_collision(ConvexPiece::cuboid([0.0, 0.0, h / 2.0], [w, d, h])?);
        b.add_textured_visual(
            textured_slab([0.0, 0.0, h / 2.0], [w, d, h], TexFace::Top, repeat),
            tex,
        );
    }
    single(
        b.finish()?,
        vec![super::procedural::parts::surface(
            "top",
            "body",
            [0.0, 0.0, h],
            [w, d],
            2.5,
        )],
    )
}

/// Tablecloths (`""`) and placemats (`placemat`): thin fabric slabs with a tileable pattern
/// (checks, plaid, stripes or the style's motif).
fn table_linen(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let seed = seed_of(ctx);
    let palette = textile_palette(ctx);
    let kind = match &ctx.style {
        Some(s) => Pattern::for_motif(&s.motif),
        None if ctx.variant == "placemat" => Pattern::Weave,
        None => [Pattern::Checker, Pattern::Plaid, Pattern::Stripes][seed as usize % 3],
    };
    let colors = if kind == Pattern::Checker {
        vec![palette[0], [0.95, 0.95, 0.93]]
    } else {
        palette
    };
    let tex = textures::pattern(kind, &colors, 128, seed);
    let tile = if ctx.variant == "placemat" { 0.45 } else { 0.5 };
    b.add_collision(ConvexPiece::cuboid([0.0, 0.0, h / 2.0], [w, d, h])?);
    b.add_textured_visual(
        textured_slab(
            [0.0, 0.0, h / 2.0],
            [w, d, h],
            TexFace::Top,
            [w / tile, d / tile],
        ),
        tex,
    );
    single(
        b.finish()?,
        vec![super::procedural::parts::surface(
            "top",
            "body",
            [0.0, 0.0, h],
            [w, d],
            1.0,
        )],
    )
}

/// Pictures on a wall: `poster` (a printed sheet), `""` painting (canvas on a stretcher in a
/// frame), `photo` (framed print with a mat). Artwork follows the style: cubist for Picasso,
/// pop art for comics, a landscape or still life otherwise.
fn picture(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let seed = seed_of(ctx);
    let palette: Vec<[f64; 3]> = ctx
        .style
        .as_ref()
        .map(|s| s.palette.clone())
        .unwrap_or_default();
    let art = match ctx.style_name() {
        "cubist" | "art_deco" | "modern" | "minimalist" | "mid_century" => Art::Abstract,
        "pop_art" | "superhero" => Art::PopArt,
        "" if ctx.variant == "poster" => Art::Poster,
        "" => [Art::Landscape, Art::StillLife, Art::Abstract][seed as usize % 3],
        _ => Art::Poster,
    };
    let px_w = 256u32;
    let px_h = ((px_w as f64) * h / w).round().clamp(64.0, 512.0) as u32;
    let tex = textures::artwork(art, &palette, px_w, px_h, seed);
    if ctx.variant == "poster" {
        b.add_collision(ConvexPiece::cuboid([0.0, d / 2.0, h / 2.0], [w, d, h])?);
        b.add_textured_visual(
            textured_slab(
                [0.0, d / 2.0, h / 2.0],
                [w, d, h],
                TexFace::Front,
                [1.0, 1.0],
            ),
            tex,
        );
        return single(b.finish()?, vec![]);
    }
    let f = (w.min(h) * 0.06).clamp(0.02, 0.07);
    let frame = ctx.accent_color;
    b.add_box([0.0, d / 2.0, f / 2.0], [w, d, f], frame)?;
    b.add_box([0.0, d / 2.0, h - f / 2.0], [w, d, f], frame)?;
    for sx in [-1.0, 1.0] {
        b.add_box(
            [sx * (w / 2.0 - f / 2.0), d / 2.0, h / 2.0],
            [f, d, h - 2.0 * f],
            frame,
        )?;
    }
    let inner = [w - 2.0 * f, h - 2.0 * f];
    let (img, mat_border) = if ctx.variant == "photo" {
        ([inner[0] * 0.75, inner[1] * 0.75], true)
    } else {
        (inner, false)
    };
    let depth = d * 0.6;
    if mat_border {
        // The mat carries the collision; the print sits 1.5 mm proud of it.
        b.add_box(
            [0.0, depth / 2.0, h / 2.0],
            [inner[0], depth, inner[1]],
            [0.95, 0.94, 0.9],
        )?;
        let pd = depth + 0.0015;
        b.add_textured_visual(
            textured_slab(
                [0.0, pd / 2.0, h / 2.0],
                [img[0], pd, img[1]],
                TexFace::Front,
                [1.0, 1.0],
            ),
            tex,
        );
    } else {
        b.add_collision(ConvexPiece::cuboid(
            [0.0, depth / 2.0, h / 2.0],
            [img[0], depth, img[1]],
        )?);
        b.add_textured_visual(
            textured_slab(
                [0.0, depth / 2.0, h / 2.0],
                [img[0], depth, img[1]],
                TexFace::Front,
                [1.0, 1.0],
            ),
            tex,
        );
    }
    single(b.finish()?, vec![])
}
