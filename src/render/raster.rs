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
use super::image::Image;
use super::scene::RenderMesh;
use super::shadow::FloorShadow;

/// One mesh to draw, with per-view overrides.
#[derive(Debug, Clone, Copy)]
pub struct DrawItem<'a> {
    /// The mesh.
    pub mesh: &'a RenderMesh,
    /// Replaces the mesh's base colour (linear RGB); the texture is then ignored.
    pub color: Option<[f32; 3]>,
    /// Draws the base colour as is, without lighting (plan walls).
    pub unlit: bool,
    /// Darkened by the [`FloorShadow`] passed to [`render_with_shadow`] (floors).
    pub receives_shadow: bool,
}

impl<'a> DrawItem<'a> {
    /// The mesh with its own colours, lit.
    pub fn new(mesh: &'a RenderMesh) -> Self {
        DrawItem {
            mesh,
            color: None,
            unlit: false,
            receives_shadow: false,
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
    pub(super) sum_x: u64,
    /// Sum of visible sample y (sample units).
    pub(super) sum_y: u64,
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
    render_with_shadow(items, camera, opts, n_objects, None)
}

/// [`render`], with `shadow` darkening the items that receive it.
pub fn render_with_shadow(
    items: &[DrawItem<'_>],
    camera: &Camera,
    opts: &RasterOptions,
    n_objects: usize,
    shadow: Option<&FloorShadow>,
) -> Result<RasterOutput, RenderError> {
    let s = opts.supersample.clamp(1, 4);
    check_size(opts.width, opts.height)?;
    let (sw, sh) = (opts.width * s, opts.height * s);
    let geo = Geometry::flatten(items, camera);
    let tris = setup(&geo, camera, sw, sh);
    let vis = rasterize(&tris, sw, sh);
    Ok(super::resolve::resolve(
        &geo, &tris, &vis, camera, opts, n_objects, shadow,
    ))
}

fn check_size(width: u32, height: u32) -> Result<(), RenderError> {
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(RenderError::InvalidSize { width, height });
    }
    Ok(())
}

/// World height of the nearest surface in each pixel of an orthographic top-down `camera`
/// (`None` where nothing is), row-major from the top image row; no shading.
pub(super) fn heights_from_above(
    items: &[DrawItem<'_>],
    camera: &Camera,
    width: u32,
    height: u32,
) -> Result<Vec<Option<f32>>, RenderError> {
    check_size(width, height)?;
    let geo = Geometry::flatten(items, camera);
    let tris = setup(&geo, camera, width, height);
    let vis = rasterize(&tris, width, height);
    let top = camera.eye.z as f32;
    // Orthographic key = -depth = z - eye z.
    Ok(vis
        .tri
        .iter()
        .zip(&vis.key)
        .map(|(&t, &k)| (t != NONE).then_some(top + k))
        .collect())
}

/// All vertices and triangles of the draw list in flat arrays.
pub(super) struct Geometry<'a> {
    /// World positions.
    pub(super) world: Vec<[f32; 3]>,
    /// Camera coordinates (x right, y up, z depth).
    pub(super) cam: Vec<[f32; 3]>,
    pub(super) normals: Vec<[f32; 3]>,
    pub(super) uvs: Vec<[f32; 2]>,
    pub(super) tris: Vec<TriInfo>,
    pub(super) items: &'a [DrawItem<'a>],
}

#[derive(Clone, Copy)]
pub(super) struct TriInfo {
    pub(super) v: [u32; 3],
    pub(super) item: u32,
    pub(super) object: u32,
    pub(super) face_normal: [f32; 3],
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
pub(super) struct ScreenTri {
    /// Screen barycentrics of vertices 1 and 2 as affine functions `a x + b y + c`.
    pub(super) l1: [f64; 3],
    pub(super) l2: [f64; 3],
    /// Nearness key at the three vertices (larger is nearer).
    pub(super) key: [f32; 3],
    /// 1 / depth at the vertices (1 for orthographic), for perspective-correct interpolation.
    pub(super) winv: [f32; 3],
    /// Barycentrics in the original triangle of each screen vertex.
    pub(super) obary: [[f32; 3]; 3],
    /// Index into `Geometry::tris`.
    pub(super) tri: u32,
    /// Sample rows covered (inclusive).
    pub(super) y0: u32,
    pub(super) y1: u32,
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
pub(super) const NONE: u32 = u32::MAX;

/// The visibility buffer: per sample, the nearest triangle and where on it.
pub(super) struct Visibility {
    pub(super) key: Vec<f32>,
    pub(super) tri: Vec<u32>,
    pub(super) l1: Vec<f32>,
    pub(super) l2: Vec<f32>,
    pub(super) width: u32,
    pub(super) height: u32,
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
