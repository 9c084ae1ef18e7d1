//! The software rasterizer: triangle meshes + a camera -> an sRGB image.
//!
//! Deferred and supersampled. Pass 1 clips each triangle against the near plane, projects it
//! to sample space (the image times the supersampling factor) and bins it into horizontal
//! bands. Pass 2 rasterizes the bands in parallel into a visibility buffer (nearness key,
//! triangle, screen barycentrics); each band draws its triangles in submission order, so the
//! result does not depend on thread scheduling. Pass 3 resolves output pixels in parallel:
//! each sample is shaded once (perspective-correct attributes, Lambert key + fill + hemisphere
//! ambient, two-sided, bilinear textures), edge lines are found from the visibility buffer
//! (object changes, creases, depth steps, silhouettes), and the samples are averaged in linear
//! light before conversion to sRGB.
//!
//! It does not do shadows, transparency or mipmapping.

use nalgebra::Vector3;
use rayon::prelude::*;

use super::RenderError;
use super::camera::Camera;
use super::image::{Image, srgb_u8_to_linear};
use super::scene::RenderMesh;
use crate::assets::Texture;

/// One mesh to draw, with per-view overrides.
#[derive(Debug, Clone, Copy)]
pub struct DrawItem<'a> {
    /// The mesh.
    pub mesh: &'a RenderMesh,
    /// Replaces the mesh's base colour (linear RGB); the texture is then ignored.
    pub color: Option<[f32; 3]>,
    /// Draws the base colour as is, without lighting (plan walls).
    pub unlit: bool,
}

impl<'a> DrawItem<'a> {
    /// The mesh with its own colours, lit.
    pub fn new(mesh: &'a RenderMesh) -> Self {
        DrawItem {
            mesh,
            color: None,
            unlit: false,
        }
    }
}

/// Lights, all in the world frame. Intensities multiply the base colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lighting {
    /// Direction *towards* the key light (normalised when used).
    pub key_dir: [f32; 3],
    /// Key light intensity.
    pub key: f32,
    /// Light from the eye (keeps faces turned towards the viewer readable).
    pub fill: f32,
    /// Ambient light on faces pointing up.
    pub ambient_sky: f32,
    /// Ambient light on faces pointing down.
    pub ambient_ground: f32,
}

impl Default for Lighting {
    fn default() -> Self {
        // A soft indoor look: a high key light from one side, a camera fill and a hemisphere
        // ambient, summing to ~1 on the best-lit faces so light materials do not clip.
        Lighting {
            key_dir: [0.35, -0.55, 0.9],
            key: 0.45,
            fill: 0.25,
            ambient_sky: 0.38,
            ambient_ground: 0.22,
        }
    }
}

/// How to rasterize.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RasterOptions {
    /// Output width, pixels.
    pub width: u32,
    /// Output height, pixels.
    pub height: u32,
    /// Samples per pixel along each axis (2 = 4 samples per pixel).
    pub supersample: u32,
    /// Background, linear RGB.
    pub background: [f32; 3],
    /// Draw silhouette, crease and object-boundary lines.
    pub edges: bool,
    /// Line colour, linear RGB.
    pub edge_color: [f32; 3],
    /// Line opacity in [0, 1].
    pub edge_strength: f32,
    /// Lights.
    pub lighting: Lighting,
}

impl RasterOptions {
    /// Defaults for a `width x height` image: 2x2 supersampling, edge lines, light grey
    /// background.
    pub fn new(width: u32, height: u32) -> Self {
        RasterOptions {
            width,
            height,
            supersample: 2,
            background: [0.82, 0.83, 0.85],
            edges: true,
            edge_color: [0.02, 0.02, 0.025],
            edge_strength: 0.75,
            lighting: Lighting::default(),
        }
    }
}

/// What an object covers in the image.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Coverage {
    /// Visible samples.
    pub samples: u64,
    /// Sum of visible sample x (sample units).
    sum_x: u64,
    /// Sum of visible sample y (sample units).
    sum_y: u64,
    /// Bounding box of visible samples, pixels: `[x0, y0, x1, y1]`.
    pub bbox: [f64; 4],
    /// Visible area in output pixels.
    pub pixels: f64,
    /// Centroid of the visible samples, pixels.
    pub centroid: [f64; 2],
}

/// A rendered image and what each object covers in it.
#[derive(Debug, Clone)]
pub struct RasterOutput {
    /// The image.
    pub image: Image,
    /// Per object index (as in [`super::scene::RenderMesh::object`]).
    pub coverage: Vec<Coverage>,
}

/// Largest output side accepted, pixels.
pub const MAX_SIDE: u32 = 8192;

/// Rasterizes `items` seen by `camera`. `n_objects` sizes the coverage table (object indices
/// at or above it are not counted).
pub fn render(
    items: &[DrawItem<'_>],
    camera: &Camera,
    opts: &RasterOptions,
    n_objects: usize,
) -> Result<RasterOutput, RenderError> {
    let s = opts.supersample.clamp(1, 4);
    if opts.width == 0 || opts.height == 0 || opts.width > MAX_SIDE || opts.height > MAX_SIDE {
        return Err(RenderError::InvalidSize {
            width: opts.width,
            height: opts.height,
        });
    }
    let (sw, sh) = (opts.width * s, opts.height * s);
    let geo = Geometry::flatten(items, camera);
    let tris = setup(&geo, camera, sw, sh);
    let vis = rasterize(&tris, sw, sh);
    Ok(resolve(&geo, &tris, &vis, camera, opts, s, n_objects))
}

/// All vertices and triangles of the draw list in flat arrays.
struct Geometry<'a> {
    /// World positions.
    world: Vec<[f32; 3]>,
    /// Camera coordinates (x right, y up, z depth).
    cam: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    uvs: Vec<[f32; 2]>,
    tris: Vec<TriInfo>,
    items: &'a [DrawItem<'a>],
}

#[derive(Clone, Copy)]
struct TriInfo {
    v: [u32; 3],
    item: u32,
    object: u32,
    face_normal: [f32; 3],
}

impl<'a> Geometry<'a> {
    fn flatten(items: &'a [DrawItem<'a>], camera: &Camera) -> Geometry<'a> {
        let nv: usize = items.iter().map(|i| i.mesh.positions.len()).sum();
        let nt: usize = items.iter().map(|i| i.mesh.triangles.len()).sum();
        let mut g = Geometry {
            world: Vec::with_capacity(nv),
            cam: Vec::with_capacity(nv),
            normals: Vec::with_capacity(nv),
            uvs: Vec::with_capacity(nv),
            tris: Vec::with_capacity(nt),
            items,
        };
        let eye = camera.eye.map(|v| v as f32);
        let (r, u, f) = (
            camera.right.map(|v| v as f32),
            camera.up.map(|v| v as f32),
            camera.forward.map(|v| v as f32),
        );
        for (ii, item) in items.iter().enumerate() {
            let m = item.mesh;
            let base = g.world.len() as u32;
            for (k, p) in m.positions.iter().enumerate() {
                let d = Vector3::new(p[0], p[1], p[2]) - eye;
                g.world.push(*p);
                g.cam.push([d.dot(&r), d.dot(&u), d.dot(&f)]);
                g.normals
                    .push(m.normals.get(k).copied().unwrap_or([0.0, 0.0, 1.0]));
                g.uvs.push(m.uvs.get(k).copied().unwrap_or([0.0, 0.0]));
            }
            let object = m.object.map_or(u32::MAX, |o| o as u32);
            for t in &m.triangles {
                let p = t.map(|i| Vector3::from(m.positions[i as usize]));
                let n = (p[1] - p[0]).cross(&(p[2] - p[0]));
                let Some(n) = n.try_normalize(1e-20) else {
                    continue;
                };
                g.tris.push(TriInfo {
                    v: t.map(|i| base + i),
                    item: ii as u32,
                    object,
                    face_normal: [n.x, n.y, n.z],
                });
            }
        }
        g
    }
}

/// A projected (possibly clipped) triangle ready for scan conversion, sample space.
#[derive(Clone, Copy)]
struct ScreenTri {
    /// Screen barycentrics of vertices 1 and 2 as affine functions `a x + b y + c`.
    l1: [f64; 3],
    l2: [f64; 3],
    /// Nearness key at the three vertices (larger is nearer).
    key: [f32; 3],
    /// 1 / depth at the vertices (1 for orthographic), for perspective-correct interpolation.
    winv: [f32; 3],
    /// Barycentrics in the original triangle of each screen vertex.
    obary: [[f32; 3]; 3],
    /// Index into `Geometry::tris`.
    tri: u32,
    /// Sample rows covered (inclusive).
    y0: u32,
    y1: u32,
}

/// A vertex during clipping: camera coordinates + barycentrics in the source triangle.
#[derive(Clone, Copy)]
struct ClipVert {
    c: [f64; 3],
    b: [f64; 3],
}

fn lerp3(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [
        a[0] + (b[0] - a[0]) * t,
        a[1] + (b[1] - a[1]) * t,
        a[2] + (b[2] - a[2]) * t,
    ]
}

/// Clips a triangle against `z >= near` (Sutherland-Hodgman); returns 0, 3 or 4 vertices.
fn clip_near(v: [ClipVert; 3], near: f64) -> ([ClipVert; 4], usize) {
    let mut out = [v[0]; 4];
    let mut n = 0;
    for i in 0..3 {
        let a = v[i];
        let b = v[(i + 1) % 3];
        let (ia, ib) = (a.c[2] >= near, b.c[2] >= near);
        if ia {
            out[n] = a;
            n += 1;
        }
        if ia != ib {
            let t = (near - a.c[2]) / (b.c[2] - a.c[2]);
            out[n] = ClipVert {
                c: lerp3(a.c, b.c, t),
                b: lerp3(a.b, b.b, t),
            };
            n += 1;
        }
    }
    (out, n)
}

fn setup(geo: &Geometry<'_>, camera: &Camera, sw: u32, sh: u32) -> Vec<ScreenTri> {
    let scale = camera.pixel_scale(sw, sh);
    let (cx, cy) = camera.principal_point(sw, sh);
    let persp = camera.is_perspective();
    let near = camera.near;
    let mut out = Vec::with_capacity(geo.tris.len());
    for (ti, t) in geo.tris.iter().enumerate() {
        let vs = t.v.map(|i| {
            let c = geo.cam[i as usize];
            [f64::from(c[0]), f64::from(c[1]), f64::from(c[2])]
        });
        let src = [
            ClipVert {
                c: vs[0],
                b: [1.0, 0.0, 0.0],
            },
            ClipVert {
                c: vs[1],
                b: [0.0, 1.0, 0.0],
            },
            ClipVert {
                c: vs[2],
                b: [0.0, 0.0, 1.0],
            },
        ];
        if vs.iter().all(|c| c[2] >= near) {
            push_tri(&mut out, src, ti, scale, cx, cy, persp, sw, sh);
            continue;
        }
        let (poly, n) = clip_near(src, near);
        for k in 1..n.saturating_sub(1) {
            push_tri(
                &mut out,
                [poly[0], poly[k], poly[k + 1]],
                ti,
                scale,
                cx,
                cy,
                persp,
                sw,
                sh,
            );
        }
    }
    out
}

#[allow(clippy::too_many_arguments)]
fn push_tri(
    out: &mut Vec<ScreenTri>,
    v: [ClipVert; 3],
    tri: usize,
    scale: f64,
    cx: f64,
    cy: f64,
    persp: bool,
    sw: u32,
    sh: u32,
) {
    let mut p = [[0.0f64; 2]; 3];
    let mut key = [0.0f32; 3];
    let mut winv = [1.0f32; 3];
    for k in 0..3 {
        let c = v[k].c;
        if persp {
            let iz = 1.0 / c[2];
            p[k] = [cx + c[0] * iz * scale, cy - c[1] * iz * scale];
            key[k] = iz as f32;
            winv[k] = iz as f32;
        } else {
            p[k] = [cx + c[0] * scale, cy - c[1] * scale];
            key[k] = -c[2] as f32;
        }
    }
    let area =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if !area.is_finite() || area.abs() < 1e-9 {
        return;
    }
    let ymin = p.iter().map(|q| q[1]).fold(f64::INFINITY, f64::min);
    let ymax = p.iter().map(|q| q[1]).fold(f64::NEG_INFINITY, f64::max);
    let xmin = p.iter().map(|q| q[0]).fold(f64::INFINITY, f64::min);
    let xmax = p.iter().map(|q| q[0]).fold(f64::NEG_INFINITY, f64::max);
    if ymax < 0.0 || xmax < 0.0 || ymin > f64::from(sh) || xmin > f64::from(sw) {
        return;
    }
    // Sample centres at +0.5: rows whose centre can lie inside.
    let y0 = (ymin - 0.5).ceil().max(0.0);
    let y1 = (ymax - 0.5).floor().min(f64::from(sh) - 1.0);
    if y1 < y0 {
        return;
    }
    // lambda_1 = edge(p2 -> p0) / area, lambda_2 = edge(p0 -> p1) / area, as affine functions.
    let edge = |a: [f64; 2], b: [f64; 2]| -> [f64; 3] {
        // (b - a) x (q - a) = (bx-ax)(qy-ay) - (by-ay)(qx-ax)
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        [-dy / area, dx / area, (dy * a[0] - dx * a[1]) / area]
    };
    let obary = v.map(|q| q.b.map(|x| x as f32));
    out.push(ScreenTri {
        l1: edge(p[2], p[0]),
        l2: edge(p[0], p[1]),
        key,
        winv,
        obary,
        tri: tri as u32,
        y0: y0 as u32,
        y1: y1 as u32,
    });
}

/// Sample rows per band.
const BAND: u32 = 16;
/// No triangle.
const NONE: u32 = u32::MAX;

/// The visibility buffer: per sample, the nearest triangle and where on it.
struct Visibility {
    key: Vec<f32>,
    tri: Vec<u32>,
    l1: Vec<f32>,
    l2: Vec<f32>,
    width: u32,
    height: u32,
}

fn rasterize(tris: &[ScreenTri], sw: u32, sh: u32) -> Visibility {
    let bands = sh.div_ceil(BAND) as usize;
    let mut bins: Vec<Vec<u32>> = vec![Vec::new(); bands];
    for (i, t) in tris.iter().enumerate() {
        for b in (t.y0 / BAND)..=(t.y1 / BAND) {
            bins[b as usize].push(i as u32);
        }
    }
    let n = sw as usize * sh as usize;
    let mut vis = Visibility {
        key: vec![f32::NEG_INFINITY; n],
        tri: vec![NONE; n],
        l1: vec![0.0; n],
        l2: vec![0.0; n],
        width: sw,
        height: sh,
    };
    let band_len = BAND as usize * sw as usize;
    vis.key
        .par_chunks_mut(band_len)
        .zip(vis.tri.par_chunks_mut(band_len))
        .zip(vis.l1.par_chunks_mut(band_len))
        .zip(vis.l2.par_chunks_mut(band_len))
        .zip(bins.par_iter())
        .enumerate()
        .for_each(|(b, ((((key, tri), l1), l2), bin))| {
            let row0 = b as u32 * BAND;
            let rows = (key.len() / sw as usize) as u32;
            for &ti in bin {
                let t = &tris[ti as usize];
                let ya = t.y0.max(row0);
                let yb = t.y1.min(row0 + rows - 1);
                for y in ya..=yb {
                    let yc = f64::from(y) + 0.5;
                    let Some((xa, xb)) = span(t, yc, sw) else {
                        continue;
                    };
                    let off = (y - row0) as usize * sw as usize;
                    let kf = [
                        f64::from(t.key[0]),
                        f64::from(t.key[1]) - f64::from(t.key[0]),
                        f64::from(t.key[2]) - f64::from(t.key[0]),
                    ];
                    // Incremental along the row; `while` because range iterators cost a
                    // call per step in unoptimised builds.
                    let xc = f64::from(xa) + 0.5;
                    let mut a = t.l1[0] * xc + t.l1[1] * yc + t.l1[2];
                    let mut c = t.l2[0] * xc + t.l2[1] * yc + t.l2[2];
                    let mut k = kf[0] + a * kf[1] + c * kf[2];
                    let dk = t.l1[0] * kf[1] + t.l2[0] * kf[2];
                    let mut i = off + xa as usize;
                    let end = off + xb as usize;
                    while i <= end {
                        let kk = k as f32;
                        if kk > key[i] {
                            key[i] = kk;
                            tri[i] = ti;
                            l1[i] = a as f32;
                            l2[i] = c as f32;
                        }
                        a += t.l1[0];
                        c += t.l2[0];
                        k += dk;
                        i += 1;
                    }
                }
            }
        });
    vis
}

/// Columns of row centre `yc` inside the triangle (all three barycentrics >= 0).
fn span(t: &ScreenTri, yc: f64, sw: u32) -> Option<(u32, u32)> {
    // lambda_0 = 1 - lambda_1 - lambda_2.
    let l0 = [
        -t.l1[0] - t.l2[0],
        -t.l1[1] - t.l2[1],
        1.0 - t.l1[2] - t.l2[2],
    ];
    let mut lo = 0.5f64;
    let mut hi = f64::from(sw) - 0.5;
    // A hair of slack: shared edges then overlap (the depth test picks one) instead of
    // leaving single-sample cracks.
    const SLACK: f64 = 1e-7;
    for f in [l0, t.l1, t.l2] {
        let a = f[0];
        let r = f[1] * yc + f[2] + SLACK;
        if a.abs() < 1e-15 {
            if r < 0.0 {
                return None;
            }
        } else if a > 0.0 {
            lo = lo.max(-r / a);
        } else {
            hi = hi.min(-r / a);
        }
    }
    let xa = (lo - 0.5).ceil();
    let xb = (hi - 0.5).floor();
    if xb < xa || xb < 0.0 {
        return None;
    }
    Some((xa.max(0.0) as u32, xb.min(f64::from(sw) - 1.0) as u32))
}

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
        if item.unlit {
            return base;
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

fn resolve(
    geo: &Geometry<'_>,
    tris: &[ScreenTri],
    vis: &Visibility,
    camera: &Camera,
    opts: &RasterOptions,
    s: u32,
    n_objects: usize,
) -> RasterOutput {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::image::linear_to_srgb_u8;
    use crate::render::scene::Role;

    fn quad(z: f32, color: [f32; 3], object: usize) -> RenderMesh {
        RenderMesh {
            positions: vec![
                [-1.0, -1.0, z],
                [1.0, -1.0, z],
                [1.0, 1.0, z],
                [-1.0, 1.0, z],
            ],
            normals: vec![[0.0, 0.0, 1.0]; 4],
            uvs: vec![],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            color,
            texture: None,
            object: Some(object),
            role: Role::Object,
        }
    }

    #[test]
    fn clipping_keeps_the_part_in_front() {
        let v = |z: f64, b: [f64; 3]| ClipVert {
            c: [0.0, 0.0, z],
            b,
        };
        let (_, n) = clip_near(
            [
                v(1.0, [1.0, 0.0, 0.0]),
                v(-1.0, [0.0, 1.0, 0.0]),
                v(2.0, [0.0, 0.0, 1.0]),
            ],
            0.1,
        );
        assert_eq!(n, 4);
        let (_, n) = clip_near(
            [
                v(-1.0, [1.0, 0.0, 0.0]),
                v(-1.0, [0.0, 1.0, 0.0]),
                v(2.0, [0.0, 0.0, 1.0]),
            ],
            0.1,
        );
        assert_eq!(n, 3);
        let (_, n) = clip_near(
            [
                v(-1.0, [1.0, 0.0, 0.0]),
                v(-1.0, [0.0, 1.0, 0.0]),
                v(-2.0, [0.0, 0.0, 1.0]),
            ],
            0.1,
        );
        assert_eq!(n, 0);
    }

    #[test]
    fn a_quad_through_the_near_plane_covers_the_bottom_of_the_image() {
        // A floor from behind the camera to far ahead: clipped, not lost or inverted.
        let floor = RenderMesh {
            positions: vec![
                [-5.0, -5.0, 0.0],
                [5.0, -5.0, 0.0],
                [5.0, 20.0, 0.0],
                [-5.0, 20.0, 0.0],
            ],
            normals: vec![[0.0, 0.0, 1.0]; 4],
            uvs: vec![],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
            color: [0.5, 0.5, 0.5],
            texture: None,
            object: Some(0),
            role: Role::Object,
        };
        let cam = Camera::look_at([0.0, 0.0, 1.0], [0.0, 5.0, 1.0], [0.0, 0.0, 1.0], 60.0).unwrap();
        let mut opts = RasterOptions::new(64, 48);
        opts.edges = false;
        let out = render(&[DrawItem::new(&floor)], &cam, &opts, 1).unwrap();
        let bg = linear_to_srgb_u8(opts.background[0]);
        let bottom = out.image.pixel(32, 47).unwrap();
        let top = out.image.pixel(32, 0).unwrap();
        assert_ne!(bottom[0], bg);
        assert_eq!(top[0], bg);
        assert!(out.coverage[0].pixels > 64.0 * 20.0);
    }

    #[test]
    fn nearer_quad_wins_regardless_of_order() {
        let near = quad(1.0, [1.0, 0.0, 0.0], 0);
        let far = quad(0.0, [0.0, 0.0, 1.0], 1);
        let cam = Camera::top_down([-2.0, -2.0], [2.0, 2.0], 5.0).unwrap();
        let opts = RasterOptions::new(40, 40);
        for order in [[&near, &far], [&far, &near]] {
            let items: Vec<_> = order.iter().map(|m| DrawItem::new(m)).collect();
            let out = render(&items, &cam, &opts, 2).unwrap();
            let p = out.image.pixel(20, 20).unwrap();
            assert!(p[0] > 100 && p[2] < 30, "{p:?}");
            assert!(out.coverage[1].samples == 0);
        }
    }
}
