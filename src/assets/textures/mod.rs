//! Procedural textures (RGBA8, sRGB-encoded as glTF expects): tileable material surfaces for
//! room floors and walls ([`surface_texture`]: wood planks, parquet, tile, carpet, concrete,
//! plaster, marble, stone, brick, ...), patterns for rugs, tablecloths and placemats
//! ([`pattern`]), and generated artwork for paintings and posters ([`artwork`]).
//!
//! Everything is seeded: the same arguments give the same pixels. Tileable textures wrap
//! seamlessly (their noise lattices are periodic in the image size).

use std::sync::Arc;

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};

use super::Texture;

mod art;

pub use art::{Art, artwork, rug};

/// A tileable surface texture and how many metres one repeat covers.
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceTexture {
    /// The image.
    pub texture: Texture,
    /// Edge length of one repeat of the image on the surface, metres.
    pub metres_per_repeat: f64,
}

/// Linear colour channel to an sRGB byte.
fn srgb8(v: f64) -> u8 {
    let v = v.clamp(0.0, 1.0);
    let s = if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

pub(super) fn lerp3(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    let t = t.clamp(0.0, 1.0);
    [0, 1, 2].map(|i| a[i] + (b[i] - a[i]) * t)
}

pub(super) fn scale3(a: [f64; 3], f: f64) -> [f64; 3] {
    a.map(|v| (v * f).clamp(0.0, 1.0))
}

/// A linear-RGB raster being painted.
pub(super) struct Canvas {
    pub(super) w: u32,
    pub(super) h: u32,
    pub(super) px: Vec<[f64; 3]>,
}

impl Canvas {
    pub(super) fn new(w: u32, h: u32, fill: [f64; 3]) -> Canvas {
        Canvas {
            w,
            h,
            px: vec![fill; (w * h) as usize],
        }
    }

    pub(super) fn each(&mut self, f: impl Fn(f64, f64, [f64; 3]) -> [f64; 3]) {
        let (w, h) = (self.w as f64, self.h as f64);
        for y in 0..self.h {
            for x in 0..self.w {
                let i = (y * self.w + x) as usize;
                self.px[i] = f((x as f64 + 0.5) / w, (y as f64 + 0.5) / h, self.px[i]);
            }
        }
    }

    /// Fills the axis-aligned rectangle (in 0..1 image coordinates).
    pub(super) fn rect(&mut self, x0: f64, y0: f64, x1: f64, y1: f64, c: [f64; 3]) {
        self.each(|u, v, p| {
            if u >= x0 && u < x1 && v >= y0 && v < y1 {
                c
            } else {
                p
            }
        });
    }

    /// Fills a disc (image coordinates, radius relative to the width).
    pub(super) fn disc(&mut self, cx: f64, cy: f64, r: f64, c: [f64; 3]) {
        let aspect = self.h as f64 / self.w as f64;
        self.each(|u, v, p| {
            let (dx, dy) = (u - cx, (v - cy) * aspect);
            if dx * dx + dy * dy < r * r { c } else { p }
        });
    }

    /// Fills a convex or star-shaped polygon (image coordinates) by the even-odd rule.
    pub(super) fn polygon(&mut self, pts: &[[f64; 2]], c: [f64; 3]) {
        let pts = pts.to_vec();
        self.each(|u, v, p| {
            let mut inside = false;
            let n = pts.len();
            for i in 0..n {
                let (a, b) = (pts[i], pts[(i + 1) % n]);
                if (a[1] > v) != (b[1] > v) && u < a[0] + (v - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
                {
                    inside = !inside;
                }
            }
            if inside { c } else { p }
        });
    }

    pub(super) fn texture(&self, name: &str) -> Texture {
        let mut rgba = Vec::with_capacity(self.px.len() * 4);
        for p in &self.px {
            rgba.extend_from_slice(&[srgb8(p[0]), srgb8(p[1]), srgb8(p[2]), 255]);
        }
        Texture {
            name: name.to_string(),
            width: self.w,
            height: self.h,
            rgba: Arc::new(rgba),
        }
    }
}

/// Periodic value noise: a `period` x `period` lattice of random values, smoothly
/// interpolated, wrapping at the edges so textures tile.
struct Noise {
    period: usize,
    grid: Vec<f64>,
}

impl Noise {
    fn new(period: usize, rng: &mut ChaCha8Rng) -> Noise {
        let period = period.max(1);
        Noise {
            period,
            grid: (0..period * period)
                .map(|_| rng.random_range(0.0..1.0))
                .collect(),
        }
    }

    /// Noise at image coordinates (u, v) in 0..1 (wrapping).
    fn at(&self, u: f64, v: f64) -> f64 {
        let p = self.period as f64;
        let (x, y) = (u.rem_euclid(1.0) * p, v.rem_euclid(1.0) * p);
        let (x0, y0) = (
            x.floor() as usize % self.period,
            y.floor() as usize % self.period,
        );
        let (x1, y1) = ((x0 + 1) % self.period, (y0 + 1) % self.period);
        let s = |t: f64| t * t * (3.0 - 2.0 * t);
        let (fx, fy) = (s(x - x.floor()), s(y - y.floor()));
        let g = |i: usize, j: usize| self.grid[j * self.period + i];
        let a = g(x0, y0) + (g(x1, y0) - g(x0, y0)) * fx;
        let b = g(x0, y1) + (g(x1, y1) - g(x0, y1)) * fx;
        a + (b - a) * fy
    }
}

/// Fractal sum of periodic noise octaves, in about 0..1.
pub(super) struct Fbm {
    octaves: Vec<Noise>,
}

impl Fbm {
    pub(super) fn new(base: usize, octaves: usize, rng: &mut ChaCha8Rng) -> Fbm {
        Fbm {
            octaves: (0..octaves).map(|k| Noise::new(base << k, rng)).collect(),
        }
    }
    pub(super) fn at(&self, u: f64, v: f64) -> f64 {
        let mut sum = 0.0;
        let mut amp = 0.5;
        let mut norm = 0.0;
        for n in &self.octaves {
            sum += amp * n.at(u, v);
            norm += amp;
            amp *= 0.5;
        }
        sum / norm
    }
}

/// Tileable patterns for floors, walls, rugs and textiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Pattern {
    /// Wood planks with grain, staggered joints.
    Planks,
    /// Herringbone parquet.
    Parquet,
    /// Square tiles with grout lines.
    Tiles,
    /// Soft fibrous noise (carpet, felt).
    Carpet,
    /// Grey mottled noise with pores.
    Concrete,
    /// Faint warm mottling (painted plaster).
    Plaster,
    /// White stone with dark veins.
    Marble,
    /// Irregular flagstones / granite speckle.
    Stone,
    /// Running-bond bricks.
    Brick,
    /// Straight stripes.
    Stripes,
    /// Checkerboard.
    Checker,
    /// Tartan plaid.
    Plaid,
    /// Polka dots.
    Dots,
    /// Stepped diamonds (kilim / southwestern rugs).
    Kilim,
    /// Woven texture with a soft grid (linen, burlap).
    Weave,
    /// Scattered five-point stars.
    Stars,
    /// Six-armed snowflakes.
    Snowflakes,
    /// Blocky pixels (voxel games).
    Pixels,
}

impl Pattern {
    /// The pattern a style motif suggests.
    pub fn for_motif(motif: &str) -> Pattern {
        match motif {
            "stars" => Pattern::Stars,
            "snowflakes" => Pattern::Snowflakes,
            "pixels" => Pattern::Pixels,
            "dots" | "emblem" => Pattern::Dots,
            "plaid" => Pattern::Plaid,
            "kilim" | "glyphs" | "dinosaurs" | "crest" | "damask" | "gears" => Pattern::Kilim,
            "grid" => Pattern::Checker,
            "stripes" | "fan" | "atomic" => Pattern::Stripes,
            "cubist" => Pattern::Checker,
            _ => Pattern::Weave,
        }
    }
}

pub(super) fn paint_pattern(
    c: &mut Canvas,
    kind: Pattern,
    colors: &[[f64; 3]],
    rng: &mut ChaCha8Rng,
) {
    let col = |i: usize| colors[i % colors.len().max(1)];
    let base = col(0);
    match kind {
        Pattern::Planks => {
            let grain = Fbm::new(4, 3, rng);
            let rows = 4.0;
            let offsets: Vec<f64> = (0..4).map(|_| rng.random_range(0.0..1.0)).collect();
            let tints: Vec<f64> = (0..16).map(|_| rng.random_range(0.85..1.12)).collect();
            c.each(|u, v, _| {
                let row = (v * rows).floor() as usize % 4;
                let along = (u + offsets[row]).rem_euclid(1.0);
                let plank = (along * 2.0).floor() as usize;
                let tint = tints[(row * 4 + plank) % 16];
                let g = grain.at(u * 0.25, v * 4.0);
                let stripes = ((v * rows * 9.0 + g * 6.0).sin() * 0.5 + 0.5) * 0.12;
                let joint = (v * rows).fract() < 0.03 || (along * 2.0).fract() < 0.008;
                if joint {
                    scale3(base, 0.45)
                } else {
                    scale3(base, tint * (0.9 + stripes))
                }
            });
        }
        Pattern::Parquet => {
            let grain = Fbm::new(8, 2, rng);
            c.each(|u, v, _| {
                let n = 8.0;
                let (x, y) = (u * n, v * n);
                let cell = ((x.floor() + y.floor()) as i64).rem_euclid(2);
                let (along, across) = if cell == 0 {
                    (x.fract(), y.fract())
                } else {
                    (y.fract(), x.fract())
                };
                let t = 0.88 + 0.18 * grain.at(u * 2.0, v * 2.0) + 0.05 * (along * 20.0).sin();
                let line = across < 0.04 || along < 0.02;
                if line {
                    scale3(base, 0.5)
                } else {
                    scale3(if cell == 0 { base } else { scale3(base, 0.9) }, t)
                }
            });
        }
        Pattern::Tiles => {
            let tone = Fbm::new(4, 2, rng);
            let grout = if colors.len() > 1 {
                col(1)
            } else {
                [0.6, 0.6, 0.58]
            };
            c.each(|u, v, _| {
                let n = 4.0;
                let (fx, fy) = ((u * n).fract(), (v * n).fract());
                if fx < 0.025 || fy < 0.025 {
                    grout
                } else {
                    scale3(base, 0.95 + 0.1 * tone.at(u, v))
                }
            });
        }
        Pattern::Carpet => {
            let fine = Fbm::new(32, 3, rng);
            let coarse = Fbm::new(4, 2, rng);
            c.each(|u, v, _| scale3(base, 0.8 + 0.25 * fine.at(u, v) + 0.1 * coarse.at(u, v)));
        }
        Pattern::Concrete | Pattern::Plaster => {
            let f = Fbm::new(8, 4, rng);
            let pores = Noise::new(64, rng);
            let depth = if kind == Pattern::Concrete { 0.3 } else { 0.1 };
            c.each(|u, v, _| {
                let pore = if kind == Pattern::Concrete && pores.at(u, v) > 0.92 {
                    0.75
                } else {
                    1.0
                };
                scale3(base, (1.0 - depth / 2.0 + depth * f.at(u, v)) * pore)
            });
        }
        Pattern::Marble => {
            let f = Fbm::new(4, 5, rng);
            let vein = if colors.len() > 1 {
                col(1)
            } else {
                [0.25, 0.25, 0.27]
            };
            c.each(|u, v, _| {
                let t = (std::f64::consts::TAU * (u + v) + 8.0 * f.at(u, v))
                    .sin()
                    .abs();
                lerp3(vein, base, t.powf(0.25))
            });
        }
        Pattern::Stone => {
            let f = Fbm::new(16, 3, rng);
            let speck = Noise::new(128, rng);
            c.each(|u, v, _| {
                let s = speck.at(u, v);
                let k = if s > 0.85 {
                    1.3
                } else if s < 0.15 {
                    0.6
                } else {
                    1.0
                };
                scale3(base, (0.85 + 0.25 * f.at(u, v)) * k)
            });
        }
        Pattern::Brick => {
            let tone = Fbm::new(8, 2, rng);
            let mortar = [0.7, 0.68, 0.62];
            c.each(|u, v, _| {
                let rows = 8.0;
                let row = (v * rows).floor();
                let x = u * 4.0 + if row as i64 % 2 == 0 { 0.0 } else { 0.5 };
                if (v * rows).fract() < 0.1 || x.fract() < 0.04 {
                    mortar
                } else {
                    scale3(base, 0.85 + 0.3 * tone.at(u * 2.0, v))
                }
            });
        }
        Pattern::Stripes => {
            let n = 6.0;
            c.each(|u, _v, _| {
                let k = (u * n).floor() as usize;
                col(k % colors.len().max(1))
            });
        }
        Pattern::Checker => {
            c.each(|u, v, _| {
                let k = ((u * 8.0).floor() + (v * 8.0).floor()) as usize;
                col(k % 2)
            });
        }
        Pattern::Plaid => {
            c.each(|u, v, _| {
                let band = |t: f64| {
                    let f = (t * 4.0).fract();
                    if f < 0.25 {
                        1.0
                    } else if f > 0.45 && f < 0.52 {
                        0.6
                    } else {
                        0.0
                    }
                };
                let k = 0.5 * (band(u) + band(v));
                lerp3(base, col(1), k)
            });
        }
        Pattern::Dots => {
            c.each(|u, v, _| {
                let n = 6.0;
                let (fx, fy) = ((u * n).fract() - 0.5, (v * n).fract() - 0.5);
                if fx * fx + fy * fy < 0.09 {
                    col(1)
                } else {
                    base
                }
            });
        }
        Pattern::Kilim => {
            c.each(|u, v, _| {
                let (fx, fy) = ((u * 4.0).fract() - 0.5, (v * 4.0).fract() - 0.5);
                let d = fx.abs() + fy.abs();
                let step = ((d * 8.0).floor() as usize) % 3;
                col(step)
            });
        }
        Pattern::Weave => {
            let f = Fbm::new(32, 2, rng);
            c.each(|u, v, _| {
                let a = ((u * 64.0 * std::f64::consts::PI).sin()
                    * (v * 64.0 * std::f64::consts::PI).sin())
                .abs();
                scale3(base, 0.85 + 0.1 * a + 0.1 * f.at(u, v))
            });
        }
        Pattern::Stars | Pattern::Snowflakes | Pattern::Pixels => {
            if kind == Pattern::Pixels {
                let cells = 16usize;
                let picks: Vec<usize> = (0..cells * cells)
                    .map(|_| rng.random_range(0..colors.len().max(1)))
                    .collect();
                c.each(|u, v, _| {
                    let (i, j) = (
                        (u * cells as f64) as usize % cells,
                        (v * cells as f64) as usize % cells,
                    );
                    scale3(col(picks[j * cells + i]), 0.9 + 0.1 * ((i + j) % 2) as f64)
                });
                return;
            }
            let n = 5usize;
            for k in 0..n * 2 {
                let (cx, cy) = (rng.random_range(0.1..0.9), rng.random_range(0.1..0.9));
                let r = rng.random_range(0.04..0.08);
                let color = col(1 + k % (colors.len().max(2) - 1));
                if kind == Pattern::Stars {
                    let pts: Vec<[f64; 2]> = (0..10)
                        .map(|i| {
                            let a = std::f64::consts::TAU * i as f64 / 10.0
                                - std::f64::consts::FRAC_PI_2;
                            let rr = if i % 2 == 0 { r } else { r * 0.4 };
                            [cx + rr * a.cos(), cy + rr * a.sin()]
                        })
                        .collect();
                    c.polygon(&pts, color);
                } else {
                    for arm in 0..6 {
                        let a = std::f64::consts::TAU * arm as f64 / 6.0;
                        let (dx, dy) = (a.cos(), a.sin());
                        let w = r * 0.12;
                        let pts = [
                            [cx - dy * w, cy + dx * w],
                            [cx + dx * r - dy * w, cy + dy * r + dx * w],
                            [cx + dx * r + dy * w, cy + dy * r - dx * w],
                            [cx + dy * w, cy - dx * w],
                        ];
                        c.polygon(&pts, color);
                    }
                }
            }
        }
    }
}

/// A `size` x `size` tileable pattern in the given colours (the first is the ground).
pub fn pattern(kind: Pattern, colors: &[[f64; 3]], size: u32, seed: u64) -> Texture {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let colors: Vec<[f64; 3]> = if colors.is_empty() {
        vec![[0.5, 0.5, 0.5]]
    } else {
        colors.to_vec()
    };
    let mut c = Canvas::new(size, size, colors[0]);
    paint_pattern(&mut c, kind, &colors, &mut rng);
    let name = format!(
        "{}_{}",
        serde_json::to_value(kind)
            .ok()
            .and_then(|v| v.as_str().map(String::from))
            .unwrap_or_default(),
        short_hash(&colors, seed)
    );
    c.texture(&name)
}

pub(super) fn short_hash(colors: &[[f64; 3]], seed: u64) -> String {
    let key = serde_json::json!({"c": colors, "s": seed});
    let h = blake3::hash(key.to_string().as_bytes());
    h.to_hex()[..8].to_string()
}

/// The tileable texture of a room surface material (`oak`, `tile`, `carpet`, `concrete`,
/// `plaster`, `marble`, `stone`, `brick`, ...) and its metres per repeat; unknown names get a
/// plain mottled texture in the material table's colour (or mid grey).
pub fn surface_texture(material: &str, seed: u64) -> SurfaceTexture {
    let mat_color = super::material::material(material).map(|m| m.color);
    let base = mat_color.unwrap_or([0.5, 0.5, 0.5]);
    let (kind, colors, repeat): (Pattern, Vec<[f64; 3]>, f64) = match material {
        "wood" | "oak" | "walnut" | "pine" | "cherry" | "maple" | "mahogany" | "teak" | "birch"
        | "bamboo" | "laminate" => (Pattern::Planks, vec![base], 2.0),
        "parquet" => (Pattern::Parquet, vec![[0.55, 0.38, 0.22]], 1.0),
        "tile" | "ceramic" | "porcelain" => (Pattern::Tiles, vec![base, [0.62, 0.62, 0.6]], 1.2),
        "carpet" | "wool" | "felt" => (Pattern::Carpet, vec![base], 1.0),
        "concrete" | "cement" => (Pattern::Concrete, vec![base], 2.0),
        "plaster" | "paint" | "drywall" => (Pattern::Plaster, vec![base], 2.0),
        "marble" => (Pattern::Marble, vec![base, [0.35, 0.35, 0.37]], 1.5),
        "stone" | "granite" | "terracotta" => (Pattern::Stone, vec![base], 1.0),
        "brick" => (Pattern::Brick, vec![[0.45, 0.12, 0.07]], 1.6),
        "linen" | "cotton" | "fabric" | "upholstery" => (Pattern::Weave, vec![base], 0.5),
        _ => (Pattern::Plaster, vec![base], 2.0),
    };
    let mut tex = pattern(kind, &colors, 256, seed);
    tex.name = format!("{}_{}", crate::scene::sanitize_name(material), tex.name);
    SurfaceTexture {
        texture: tex,
        metres_per_repeat: repeat,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixel(t: &Texture, x: u32, y: u32) -> [u8; 4] {
        let i = ((y * t.width + x) * 4) as usize;
        [t.rgba[i], t.rgba[i + 1], t.rgba[i + 2], t.rgba[i + 3]]
    }

    #[test]
    fn surface_textures_tile_and_repeat() {
        for m in [
            "oak", "tile", "carpet", "concrete", "plaster", "marble", "stone", "brick", "parquet",
        ] {
            let s = surface_texture(m, 3);
            assert_eq!((s.texture.width, s.texture.height), (256, 256));
            assert!(s.metres_per_repeat > 0.1 && s.metres_per_repeat < 5.0);
            let t = &s.texture;
            // Seamless noise: the wrap-around step is no bigger than a typical step inside.
            if matches!(m, "carpet" | "concrete" | "plaster" | "marble" | "stone") {
                let step = |a: [u8; 4], b: [u8; 4]| {
                    (0..3)
                        .map(|k| (a[k] as i64 - b[k] as i64).abs())
                        .sum::<i64>()
                };
                let mut edge = 0i64;
                let mut inner = 0i64;
                for y in 0..t.height {
                    edge += step(pixel(t, 0, y), pixel(t, t.width - 1, y));
                    inner += (1..t.width)
                        .map(|x| step(pixel(t, x - 1, y), pixel(t, x, y)))
                        .sum::<i64>();
                }
                let mean = inner as f64 / (t.width - 1) as f64;
                assert!(
                    (edge as f64) < mean * 3.0 + 500.0,
                    "{m}: seam {edge} vs mean step {mean}"
                );
            }
            // Not a flat colour.
            let distinct: std::collections::BTreeSet<[u8; 4]> = (0..t.height)
                .step_by(7)
                .flat_map(|y| (0..t.width).step_by(5).map(move |x| (x, y)))
                .map(|(x, y)| pixel(t, x, y))
                .collect();
            assert!(distinct.len() > 10, "{m} is flat");
        }
        assert_eq!(surface_texture("oak", 3), surface_texture("oak", 3));
        assert_ne!(
            surface_texture("oak", 3).texture.rgba,
            surface_texture("oak", 4).texture.rgba
        );
    }

    #[test]
    fn artwork_and_rugs_are_varied_images() {
        for kind in [
            Art::Landscape,
            Art::Abstract,
            Art::StillLife,
            Art::Poster,
            Art::PopArt,
        ] {
            let t = artwork(kind, &[], 128, 96, 1);
            assert_eq!(t.rgba.len(), 128 * 96 * 4);
            let distinct: std::collections::BTreeSet<[u8; 4]> = (0..96)
                .flat_map(|y| (0..128).map(move |x| (x, y)))
                .map(|(x, y)| pixel(&t, x, y))
                .collect();
            assert!(distinct.len() > 3, "{kind:?}");
        }
        let r = rug(&[], Pattern::Kilim, false, 128, 2);
        assert_ne!(pixel(&r, 1, 1), pixel(&r, 64, 40));
    }
}
