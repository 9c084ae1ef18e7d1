//! The resolve pass of the rasterizer: shades each visible sample once (perspective-correct
//! attributes, Lambert key + fill + hemisphere ambient, two-sided, bilinear textures, the
//! optional floor shadow), finds edge lines in the visibility buffer (object changes, creases,
//! depth steps, silhouettes), averages the samples of each pixel in linear light and
//! converts to sRGB, and measures what each object covers.

use rayon::prelude::*;

use super::camera::Camera;
use super::image::{Image, srgb_u8_to_linear};
use super::raster::{
    Coverage, Geometry, Lighting, NONE, RasterOptions, RasterOutput, ScreenTri, Visibility,
};
use super::shadow::FloorShadow;
use crate::assets::Texture;

/// What the resolve pass knows about one visible sample.
#[derive(Clone, Copy)]
struct SampleRef {
    screen: u32,
    key: f32,
    object: u32,
    normal: [f32; 3],
}

struct Shader<'a> {
    geo: &'a Geometry<'a>,
    /// Object of each screen triangle (saves two lookups per sample in edge tests).
    st_object: Vec<u32>,
    /// Face normal of each screen triangle.
    st_normal: Vec<[f32; 3]>,
    tris: &'a [ScreenTri],
    vis: &'a Visibility,
    eye: [f32; 3],
    forward: [f32; 3],
    persp: bool,
    light: [f32; 3],
    lighting: Lighting,
    shadow: Option<&'a FloorShadow>,
}

impl Shader<'_> {
    fn sample_ref(&self, x: i64, y: i64) -> Option<SampleRef> {
        let (w, h) = (i64::from(self.vis.width), i64::from(self.vis.height));
        let (x, y) = (x.clamp(0, w - 1), y.clamp(0, h - 1));
        let i = (y * w + x) as usize;
        let st = self.vis.tri[i];
        if st == NONE {
            return None;
        }
        Some(SampleRef {
            screen: st,
            key: self.vis.key[i],
            object: self.st_object[st as usize],
            normal: self.st_normal[st as usize],
        })
    }

    /// Shaded linear colour of the sample with screen barycentrics `(a, c)` on screen
    /// triangle `st`. Plain array arithmetic: this runs per pixel, and generic vector code
    /// is very slow in unoptimised (test) builds.
    fn shade(&self, st: u32, a: f32, c: f32) -> [f32; 3] {
        let s = &self.tris[st as usize];
        let t = &self.geo.tris[s.tri as usize];
        let item = &self.geo.items[t.item as usize];
        let lam = [1.0 - a - c, a, c];
        let w = [lam[0] * s.winv[0], lam[1] * s.winv[1], lam[2] * s.winv[2]];
        let sum = w[0] + w[1] + w[2];
        let w = if sum.abs() > 1e-30 {
            let k = 1.0 / sum;
            [w[0] * k, w[1] * k, w[2] * k]
        } else {
            lam
        };
        let o = &s.obary;
        let b = [
            w[0] * o[0][0] + w[1] * o[1][0] + w[2] * o[2][0],
            w[0] * o[0][1] + w[1] * o[1][1] + w[2] * o[2][1],
            w[0] * o[0][2] + w[1] * o[1][2] + w[2] * o[2][2],
        ];
        let (i0, i1, i2) = (t.v[0] as usize, t.v[1] as usize, t.v[2] as usize);
        let base = match item.color {
            Some(c) => c,
            None => {
                let mut col = item.mesh.color;
                if let Some(tex) = &item.mesh.texture {
                    let (uv0, uv1, uv2) = (self.geo.uvs[i0], self.geo.uvs[i1], self.geo.uvs[i2]);
                    let u = uv0[0] * b[0] + uv1[0] * b[1] + uv2[0] * b[2];
                    let v = uv0[1] * b[0] + uv1[1] * b[1] + uv2[1] * b[2];
                    let texel = sample_bilinear(tex, u, v);
                    col = [col[0] * texel[0], col[1] * texel[1], col[2] * texel[2]];
                }
                col
            }
        };
        let shadow = match self.shadow {
            Some(map) if item.receives_shadow => {
                let p = interp(&self.geo.world, i0, i1, i2, b);
                map.light_at(p[0], p[1])
            }
            _ => 1.0,
        };
        if item.unlit {
            return [base[0] * shadow, base[1] * shadow, base[2] * shadow];
        }
        let view = if self.persp {
            let p = interp(&self.geo.world, i0, i1, i2, b);
            normalized(sub(self.eye, p)).unwrap_or(neg(self.forward))
        } else {
            neg(self.forward)
        };
        let n = interp(&self.geo.normals, i0, i1, i2, b);
        let mut n = normalized(n).unwrap_or(t.face_normal);
        // Two-sided: light the side the viewer sees (thin parts, open meshes).
        if dot(t.face_normal, view) < 0.0 {
            n = neg(n);
        }
        let l = &self.lighting;
        let hemi = 0.5 + 0.5 * n[2];
        let intensity = l.ambient_ground
            + (l.ambient_sky - l.ambient_ground) * hemi
            + l.key * dot(n, self.light).max(0.0)
            + l.fill * dot(n, view).max(0.0);
        let intensity = intensity * shadow;
        [
            base[0] * intensity,
            base[1] * intensity,
            base[2] * intensity,
        ]
    }

    /// True when the sample at `(x, y)` lies on a line: a silhouette, a boundary between
    /// objects, a crease or a depth step.
    #[inline(always)]
    fn is_edge(&self, x: i64, y: i64, st: u32) -> bool {
        if st == NONE {
            return false;
        }
        // Inside one triangle nothing changes (its depth is affine): the common case.
        let (w, h) = (i64::from(self.vis.width), i64::from(self.vis.height));
        if x > 0 && y > 0 && x + 1 < w && y + 1 < h {
            let i = (y * w + x) as usize;
            let t = &self.vis.tri[..];
            let wu = w as usize;
            if t[i - 1] == st && t[i + 1] == st && t[i - wu] == st && t[i + wu] == st {
                return false;
            }
        }
        let Some(c) = self.sample_ref(x, y) else {
            return false;
        };
        let persp = self.persp;
        let mut nb = [None; 4];
        for (k, (dx, dy)) in [(-1, 0), (1, 0), (0, -1), (0, 1)].into_iter().enumerate() {
            nb[k] = self.sample_ref(x + dx, y + dy);
        }
        for n in &nb {
            let Some(n) = n else {
                return true;
            };
            if n.object != c.object {
                return true;
            }
            if n.screen != c.screen {
                let d = dot(n.normal, c.normal);
                if d < 0.82 {
                    return true;
                }
            }
        }
        // Depth steps: the key is affine in screen space on a plane (1/z for perspective,
        // z for orthographic), so its second difference is zero there and large at a step.
        for (a, b) in [(nb[0], nb[1]), (nb[2], nb[3])] {
            if let (Some(a), Some(b)) = (a, b) {
                let lap = (a.key + b.key - 2.0 * c.key).abs();
                let limit = if persp { 0.04 * c.key.abs() } else { 0.03 };
                if lap > limit {
                    return true;
                }
            }
        }
        false
    }
}

#[inline(always)]
fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
fn neg(a: [f32; 3]) -> [f32; 3] {
    [-a[0], -a[1], -a[2]]
}

#[inline(always)]
fn normalized(a: [f32; 3]) -> Option<[f32; 3]> {
    let n2 = dot(a, a);
    if n2 > 1e-24 {
        let k = 1.0 / n2.sqrt();
        Some([a[0] * k, a[1] * k, a[2] * k])
    } else {
        None
    }
}

#[inline(always)]
fn interp(arr: &[[f32; 3]], i0: usize, i1: usize, i2: usize, b: [f32; 3]) -> [f32; 3] {
    let (p, q, r) = (arr[i0], arr[i1], arr[i2]);
    [
        p[0] * b[0] + q[0] * b[1] + r[0] * b[2],
        p[1] * b[0] + q[1] * b[1] + r[1] * b[2],
        p[2] * b[0] + q[2] * b[1] + r[2] * b[2],
    ]
}

fn sample_bilinear(tex: &Texture, u: f32, v: f32) -> [f32; 3] {
    let (w, h) = (tex.width as i64, tex.height as i64);
    if w == 0 || h == 0 || tex.rgba.len() < (w * h * 4) as usize || !u.is_finite() || !v.is_finite()
    {
        return [1.0; 3];
    }
    let x = u as f64 * w as f64 - 0.5;
    let y = v as f64 * h as f64 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = ((x - x0) as f32, (y - y0) as f32);
    let texel = |xi: i64, yi: i64| -> [f32; 3] {
        let xi = xi.rem_euclid(w) as usize;
        let yi = yi.rem_euclid(h) as usize;
        let i = (yi * w as usize + xi) * 4;
        [
            srgb_u8_to_linear(tex.rgba[i]),
            srgb_u8_to_linear(tex.rgba[i + 1]),
            srgb_u8_to_linear(tex.rgba[i + 2]),
        ]
    };
    let (x0, y0) = (x0 as i64, y0 as i64);
    let (a, b, c, d) = (
        texel(x0, y0),
        texel(x0 + 1, y0),
        texel(x0, y0 + 1),
        texel(x0 + 1, y0 + 1),
    );
    let mut out = [0.0; 3];
    for k in 0..3 {
        let top = a[k] + (b[k] - a[k]) * fx;
        let bot = c[k] + (d[k] - c[k]) * fx;
        out[k] = top + (bot - top) * fy;
    }
    out
}

pub(super) fn resolve(
    geo: &Geometry<'_>,
    tris: &[ScreenTri],
    vis: &Visibility,
    camera: &Camera,
    opts: &RasterOptions,
    n_objects: usize,
    shadow: Option<&FloorShadow>,
) -> RasterOutput {
    let s = opts.supersample.clamp(1, 4);
    let kd = opts.lighting.key_dir;
    let shader = Shader {
        geo,
        st_object: tris
            .iter()
            .map(|t| geo.tris[t.tri as usize].object)
            .collect(),
        st_normal: tris
            .iter()
            .map(|t| geo.tris[t.tri as usize].face_normal)
            .collect(),
        tris,
        vis,
        eye: [
            camera.eye.x as f32,
            camera.eye.y as f32,
            camera.eye.z as f32,
        ],
        forward: [
            camera.forward.x as f32,
            camera.forward.y as f32,
            camera.forward.z as f32,
        ],
        persp: camera.is_perspective(),
        light: normalized(kd).unwrap_or([0.0, 0.0, 1.0]),
        lighting: opts.lighting,
        shadow,
    };
    let (w, h) = (opts.width as usize, opts.height as usize);
    let mut rgba = vec![255u8; w * h * 4];
    let si = s as i64;
    let vw = i64::from(vis.width);
    let (vtri, vl1, vl2) = (&vis.tri[..], &vis.l1[..], &vis.l2[..]);
    let st_object = &shader.st_object[..];
    let srgb = super::image::SrgbEncoder::get();
    let stats = rgba
        .par_chunks_mut(w * 4)
        .enumerate()
        .fold(
            || vec![Acc::default(); n_objects],
            |mut acc, (py, row)| {
                let mut ids = [NONE; 16];
                let mut edge = [false; 16];
                let n = (si * si) as usize;
                let inv_n = 1.0 / n as f32;
                let mut px = 0usize;
                while px < w {
                    let (x0, y0) = (px as i64 * si, py as i64 * si);
                    let first = vtri[(y0 * vw + x0) as usize];
                    let mut uniform = true;
                    let (mut a_sum, mut c_sum) = (0.0f32, 0.0f32);
                    let mut j = 0usize;
                    while j < n {
                        let (x, y) = (x0 + j as i64 % si, y0 + j as i64 / si);
                        let i = (y * vw + x) as usize;
                        let st = vtri[i];
                        ids[j] = st;
                        edge[j] = opts.edges && shader.is_edge(x, y, st);
                        uniform &= st == first && !edge[j];
                        a_sum += vl1[i];
                        c_sum += vl2[i];
                        if st != NONE {
                            let o = st_object[st as usize] as usize;
                            if o < acc.len() {
                                acc[o].add(x as u64, y as u64);
                            }
                        }
                        j += 1;
                    }
                    let col = if uniform {
                        // One triangle covers the whole pixel and no line crosses it: shade once
                        // at the samples' mean position.
                        if first == NONE {
                            opts.background
                        } else {
                            shader.shade(first, a_sum * inv_n, c_sum * inv_n)
                        }
                    } else {
                        let mut sum = [0.0f32; 3];
                        let mut j = 0usize;
                        while j < n {
                            let (x, y) = (x0 + j as i64 % si, y0 + j as i64 / si);
                            let i = (y * vw + x) as usize;
                            let mut col = if ids[j] == NONE {
                                opts.background
                            } else {
                                shader.shade(ids[j], vl1[i], vl2[i])
                            };
                            if edge[j] {
                                let a = opts.edge_strength;
                                let e = opts.edge_color;
                                col = [
                                    col[0] + (e[0] - col[0]) * a,
                                    col[1] + (e[1] - col[1]) * a,
                                    col[2] + (e[2] - col[2]) * a,
                                ];
                            }
                            sum = [sum[0] + col[0], sum[1] + col[1], sum[2] + col[2]];
                            j += 1;
                        }
                        [sum[0] * inv_n, sum[1] * inv_n, sum[2] * inv_n]
                    };
                    let o = px * 4;
                    row[o] = srgb.encode(col[0]);
                    row[o + 1] = srgb.encode(col[1]);
                    row[o + 2] = srgb.encode(col[2]);
                    row[o + 3] = 255;
                    px += 1;
                }
                acc
            },
        )
        .reduce(
            || vec![Acc::default(); n_objects],
            |mut a, b| {
                for (x, y) in a.iter_mut().zip(&b) {
                    x.merge(y);
                }
                a
            },
        );
    let sf = f64::from(s);
    let coverage = stats
        .iter()
        .map(|a| {
            if a.n == 0 {
                return Coverage::default();
            }
            Coverage {
                samples: a.n,
                sum_x: a.sx,
                sum_y: a.sy,
                bbox: [
                    a.x0 as f64 / sf,
                    a.y0 as f64 / sf,
                    (a.x1 + 1) as f64 / sf,
                    (a.y1 + 1) as f64 / sf,
                ],
                pixels: a.n as f64 / (sf * sf),
                centroid: [
                    (a.sx as f64 / a.n as f64 + 0.5) / sf,
                    (a.sy as f64 / a.n as f64 + 0.5) / sf,
                ],
            }
        })
        .collect();
    RasterOutput {
        image: Image {
            width: opts.width,
            height: opts.height,
            rgba,
        },
        coverage,
    }
}

/// Integer accumulators (exact, so the parallel reduction is order independent).
#[derive(Clone, Copy)]
struct Acc {
    n: u64,
    sx: u64,
    sy: u64,
    x0: u64,
    y0: u64,
    x1: u64,
    y1: u64,
}

impl Default for Acc {
    fn default() -> Self {
        Acc {
            n: 0,
            sx: 0,
            sy: 0,
            x0: u64::MAX,
            y0: u64::MAX,
            x1: 0,
            y1: 0,
        }
    }
}

impl Acc {
    #[inline(always)]
    fn add(&mut self, x: u64, y: u64) {
        self.n += 1;
        self.sx += x;
        self.sy += y;
        // Plain comparisons: `min`/`max` are calls in unoptimised builds, and this runs per
        // sample.
        if x < self.x0 {
            self.x0 = x;
        }
        if y < self.y0 {
            self.y0 = y;
        }
        if x > self.x1 {
            self.x1 = x;
        }
        if y > self.y1 {
            self.y1 = y;
        }
    }

    fn merge(&mut self, o: &Acc) {
        self.n += o.n;
        self.sx += o.sx;
        self.sy += o.sy;
        self.x0 = self.x0.min(o.x0);
        self.y0 = self.y0.min(o.y0);
        self.x1 = self.x1.max(o.x1);
        self.y1 = self.y1.max(o.y1);
    }
}
