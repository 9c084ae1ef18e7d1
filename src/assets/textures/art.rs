//! Generated artwork for paintings and posters, and rug faces (border, field pattern,
//! medallion). One image covers the object; these do not tile.

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};

use super::{Canvas, Fbm, Pattern, lerp3, paint_pattern, scale3, short_hash};
use crate::assets::Texture;

/// Kinds of generated artwork.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Art {
    /// Landscape: sky gradient, sun, hills, a lake.
    Landscape,
    /// Cubist / geometric composition of overlapping polygons.
    Abstract,
    /// A still life: a vase and fruit on a table.
    StillLife,
    /// Poster: bold background, a large emblem, bands where a title would be.
    Poster,
    /// Comic-style pop art: halftone dots, a burst, thick outlines.
    PopArt,
}

/// Generated artwork, `w` x `h` pixels, in a palette (the style's, or a default).
pub fn artwork(kind: Art, palette: &[[f64; 3]], w: u32, h: u32, seed: u64) -> Texture {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let default = [
        [0.55, 0.05, 0.04],
        [0.05, 0.2, 0.5],
        [0.8, 0.55, 0.08],
        [0.1, 0.35, 0.12],
        [0.85, 0.85, 0.82],
        [0.04, 0.04, 0.05],
    ];
    let pal: Vec<[f64; 3]> = if palette.is_empty() {
        default.to_vec()
    } else {
        palette.to_vec()
    };
    let p = |i: usize| pal[i % pal.len()];
    let mut c = Canvas::new(w, h, p(0));
    match kind {
        Art::Landscape => {
            let sky_top = [0.15, 0.35, 0.75];
            let sky_low = [0.85, 0.6, 0.45];
            c.each(|_u, v, _| lerp3(sky_top, sky_low, v / 0.6));
            let sun = (rng.random_range(0.2..0.8), rng.random_range(0.15..0.35));
            c.disc(sun.0, sun.1, 0.07, [1.0, 0.85, 0.4]);
            let hills = Fbm::new(4, 3, &mut rng);
            for (k, (level, col)) in [(0.55, [0.25, 0.4, 0.25]), (0.68, [0.12, 0.3, 0.12])]
                .iter()
                .enumerate()
            {
                let off = k as f64 * 0.37;
                let col = *col;
                let level = *level;
                c.each(|u, v, px| {
                    if v > level - 0.12 * hills.at(u + off, 0.5) {
                        col
                    } else {
                        px
                    }
                });
            }
            c.each(|u, v, px| {
                if v > 0.8 && (u - 0.6).abs() < 0.3 - (v - 0.8) {
                    [0.2, 0.35, 0.6]
                } else {
                    px
                }
            });
        }
        Art::Abstract => {
            for k in 0..9 {
                let n = rng.random_range(3..6);
                let (cx, cy) = (rng.random_range(0.1..0.9), rng.random_range(0.1..0.9));
                let r = rng.random_range(0.12..0.35);
                let rot = rng.random_range(0.0..std::f64::consts::TAU);
                let pts: Vec<[f64; 2]> = (0..n)
                    .map(|i| {
                        let a = rot + std::f64::consts::TAU * i as f64 / n as f64;
                        [
                            cx + r * a.cos(),
                            cy + r * a.sin() * rng.random_range(0.6..1.4),
                        ]
                    })
                    .collect();
                c.polygon(&pts, p(k + 1));
            }
            // Heavy outlines: darken pixels near colour changes.
            let src = c.px.clone();
            let (wi, hi) = (c.w as usize, c.h as usize);
            for y in 1..hi - 1 {
                for x in 1..wi - 1 {
                    let i = y * wi + x;
                    if src[i] != src[i + 1] || src[i] != src[i + wi] {
                        c.px[i] = [0.02, 0.02, 0.02];
                    }
                }
            }
        }
        Art::StillLife => {
            c.each(|_u, v, _| {
                if v > 0.7 {
                    [0.35, 0.2, 0.1]
                } else {
                    scale3(p(4), 0.7)
                }
            });
            c.polygon(
                &[
                    [0.4, 0.7],
                    [0.6, 0.7],
                    [0.62, 0.45],
                    [0.55, 0.3],
                    [0.45, 0.3],
                    [0.38, 0.45],
                ],
                p(1),
            );
            for (x, col) in [
                (0.25, [0.7, 0.08, 0.05]),
                (0.72, [0.9, 0.5, 0.05]),
                (0.8, [0.5, 0.6, 0.1]),
            ] {
                c.disc(x, 0.66, 0.06, col);
            }
        }
        Art::Poster => {
            c.each(|_u, v, _| lerp3(p(0), scale3(p(0), 0.5), v));
            c.disc(0.5, 0.42, 0.28, p(1));
            let star: Vec<[f64; 2]> = (0..10)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / 10.0 - std::f64::consts::FRAC_PI_2;
                    let rr = if i % 2 == 0 { 0.22 } else { 0.09 };
                    [
                        0.5 + rr * a.cos(),
                        0.42 + rr * a.sin() * w as f64 / h as f64,
                    ]
                })
                .collect();
            c.polygon(&star, p(2));
            c.rect(0.1, 0.8, 0.9, 0.86, p(3));
            c.rect(0.25, 0.89, 0.75, 0.92, p(4));
        }
        Art::PopArt => {
            c.each(|u, v, _| {
                let (fx, fy) = ((u * 24.0).fract() - 0.5, (v * 24.0).fract() - 0.5);
                if fx * fx + fy * fy < 0.08 {
                    scale3(p(1), 0.8)
                } else {
                    p(0)
                }
            });
            let burst: Vec<[f64; 2]> = (0..16)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / 16.0;
                    let rr = if i % 2 == 0 { 0.4 } else { 0.25 };
                    [0.5 + rr * a.cos(), 0.5 + rr * a.sin()]
                })
                .collect();
            c.polygon(&burst, p(2));
            c.disc(0.5, 0.5, 0.15, p(3));
        }
    }
    let name = format!(
        "art_{}",
        short_hash(
            &pal,
            seed ^ (kind as u64) << 32 ^ u64::from(w) << 16 ^ u64::from(h)
        )
    );
    c.texture(&name)
}

/// A rug face: a border, an inner field in a pattern and (for rectangular rugs) a centre
/// medallion; round rugs get concentric rings. Not tileable: one image covers the rug.
pub fn rug(palette: &[[f64; 3]], motif: Pattern, round: bool, size: u32, seed: u64) -> Texture {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let pal: Vec<[f64; 3]> = if palette.len() >= 3 {
        palette.to_vec()
    } else {
        vec![[0.45, 0.08, 0.08], [0.85, 0.75, 0.55], [0.1, 0.15, 0.35]]
    };
    let mut field = Canvas::new(size, size, pal[0]);
    let field_colors = [pal[0], pal[1 % pal.len()], pal[2 % pal.len()]];
    paint_pattern(&mut field, motif, &field_colors, &mut rng);
    let fibre = Fbm::new(32, 2, &mut rng);
    let border = pal[2 % pal.len()];
    let trim = pal[1 % pal.len()];
    let mut c = Canvas::new(size, size, pal[0]);
    let n = size as usize;
    for y in 0..n {
        for x in 0..n {
            let (u, v) = (
                (x as f64 + 0.5) / size as f64,
                (y as f64 + 0.5) / size as f64,
            );
            let edge = if round {
                0.5 - ((u - 0.5).powi(2) + (v - 0.5).powi(2)).sqrt()
            } else {
                u.min(v).min(1.0 - u).min(1.0 - v)
            };
            let mut col = if edge < 0.06 {
                border
            } else if edge < 0.08 {
                trim
            } else {
                field.px[y * n + x]
            };
            if !round {
                let d = (u - 0.5).abs() + (v - 0.5).abs();
                if d < 0.16 {
                    col = if d < 0.1 { trim } else { border };
                }
            } else if ((u - 0.5).powi(2) + (v - 0.5).powi(2)).sqrt() < 0.12 {
                col = trim;
            }
            c.px[y * n + x] = scale3(col, 0.88 + 0.2 * fibre.at(u, v));
        }
    }
    c.texture(&format!(
        "rug_{}",
        short_hash(&pal, seed ^ u64::from(round))
    ))
}
