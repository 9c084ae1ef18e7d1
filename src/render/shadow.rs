//! Soft contact shadows on the floor: what stands above the floor, seen from straight above,
//! blurred into an occlusion map that darkens the floor under and around furniture (the look
//! of diffuse ceiling light, which grounds objects without harsh cast shadows).

use super::RenderError;
use super::camera::Camera;
use super::raster::{self, DrawItem};

/// Occlusion of the floor seen from above, in [0, 1], on a regular XY grid.
#[derive(Debug, Clone, PartialEq)]
pub struct FloorShadow {
    /// World XY of the grid's first cell corner.
    min: [f32; 2],
    /// Cell size, metres.
    cell: f32,
    width: usize,
    height: usize,
    /// Row-major, row 0 at `min[1]`.
    occlusion: Vec<f32>,
    /// Darkening at full occlusion, [0, 1].
    strength: f32,
}

/// Largest grid side, cells.
const MAX_CELLS: f64 = 1024.0;

impl FloorShadow {
    /// Occlusion of the XY rectangle `min..max` by `casters` standing higher than `floor_z +
    /// 3 cm`, with a cell of `cell_m` metres (coarsened to at most 1024 cells a side) and a
    /// blur of about `blur_m`.
    pub fn build(
        casters: &[DrawItem<'_>],
        min: [f64; 2],
        max: [f64; 2],
        floor_z: f64,
        cell_m: f64,
        blur_m: f64,
        strength: f32,
    ) -> Result<FloorShadow, RenderError> {
        let (w_m, h_m) = (max[0] - min[0], max[1] - min[1]);
        let cell = cell_m.max(w_m / MAX_CELLS).max(h_m / MAX_CELLS).max(1e-3);
        let width = ((w_m / cell).ceil() as u32).max(1);
        let height = ((h_m / cell).ceil() as u32).max(1);
        let max = [
            min[0] + f64::from(width) * cell,
            min[1] + f64::from(height) * cell,
        ];
        let top_z = floor_z + 10.0;
        let camera = Camera::top_down(min, max, top_z)?;
        let heights = raster::heights_from_above(casters, &camera, width, height)?;
        let limit = (floor_z + 0.03) as f32;
        let mut occ: Vec<f32> = heights
            .iter()
            .map(|h| {
                if h.is_some_and(|z| z > limit) {
                    1.0
                } else {
                    0.0
                }
            })
            .collect();
        // Image rows run top (max y) to bottom; flip so row 0 is at min y.
        let (w, h) = (width as usize, height as usize);
        for y in 0..h / 2 {
            for x in 0..w {
                occ.swap(y * w + x, (h - 1 - y) * w + x);
            }
        }
        let r = ((blur_m / cell / 2.0).round() as usize).max(1);
        // Two box passes approximate a Gaussian.
        for _ in 0..2 {
            occ = box_blur(&occ, w, h, r);
        }
        Ok(FloorShadow {
            min: [min[0] as f32, min[1] as f32],
            cell: cell as f32,
            width: w,
            height: h,
            occlusion: occ,
            strength: strength.clamp(0.0, 1.0),
        })
    }

    /// Light factor at world `(x, y)`: 1 in the open, down to `1 - strength` under things.
    #[inline]
    pub fn light_at(&self, x: f32, y: f32) -> f32 {
        let gx = (x - self.min[0]) / self.cell - 0.5;
        let gy = (y - self.min[1]) / self.cell - 0.5;
        if !(gx > -1.0 && gy > -1.0) || gx >= self.width as f32 || gy >= self.height as f32 {
            return 1.0;
        }
        let (x0, y0) = (gx.floor(), gy.floor());
        let (fx, fy) = (gx - x0, gy - y0);
        let at = |xi: f32, yi: f32| -> f32 {
            if xi < 0.0 || yi < 0.0 || xi >= self.width as f32 || yi >= self.height as f32 {
                return 0.0;
            }
            self.occlusion[yi as usize * self.width + xi as usize]
        };
        let top = at(x0, y0) + (at(x0 + 1.0, y0) - at(x0, y0)) * fx;
        let bot = at(x0, y0 + 1.0) + (at(x0 + 1.0, y0 + 1.0) - at(x0, y0 + 1.0)) * fx;
        1.0 - self.strength * (top + (bot - top) * fy)
    }
}

/// Separable box blur of radius `r` cells (edges clamp to zero outside).
fn box_blur(src: &[f32], w: usize, h: usize, r: usize) -> Vec<f32> {
    let norm = 1.0 / (2 * r + 1) as f32;
    let mut tmp = vec![0.0f32; src.len()];
    for y in 0..h {
        let row = &src[y * w..(y + 1) * w];
        let mut acc: f32 = row.iter().take(r + 1).sum();
        for x in 0..w {
            tmp[y * w + x] = acc * norm;
            if x + r + 1 < w {
                acc += row[x + r + 1];
            }
            if x >= r {
                acc -= row[x - r];
            }
        }
    }
    let mut out = vec![0.0f32; src.len()];
    for x in 0..w {
        let mut acc: f32 = (0..=r.min(h.saturating_sub(1)))
            .map(|y| tmp[y * w + x])
            .sum();
        for y in 0..h {
            out[y * w + x] = acc * norm;
            if y + r + 1 < h {
                acc += tmp[(y + r + 1) * w + x];
            }
            if y >= r {
                acc -= tmp[(y - r) * w + x];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::mesh::box_mesh;
    use crate::render::scene::RenderMesh;
    use crate::scene::Pose;

    #[test]
    fn floor_is_dark_under_a_table_top_and_light_away_from_it() {
        // A 1 x 1 m slab 0.7 m above the floor, centred at the origin.
        let top = RenderMesh::from_trimesh(
            &box_mesh([0.0, 0.0, 0.7], [1.0, 1.0, 0.04]),
            &Pose::IDENTITY,
            [0.5, 0.5, 0.5, 1.0],
            None,
        );
        let s = FloorShadow::build(
            &[DrawItem::new(&top)],
            [-2.0, -2.0],
            [2.0, 2.0],
            0.0,
            0.02,
            0.1,
            0.5,
        )
        .unwrap();
        assert!(
            (s.light_at(0.0, 0.0) - 0.5).abs() < 0.01,
            "{}",
            s.light_at(0.0, 0.0)
        );
        assert!((s.light_at(1.5, 1.5) - 1.0).abs() < 1e-6);
        assert!((s.light_at(9.0, 0.0) - 1.0).abs() < 1e-6);
        // Soft edge: half occluded at the slab's border, with a gradient.
        let edge = s.light_at(0.5, 0.0);
        assert!(edge > 0.6 && edge < 0.9, "{edge}");
        // Asymmetric scene: the map is not mirrored.
        let left = RenderMesh::from_trimesh(
            &box_mesh([-1.0, 1.0, 0.5], [0.4, 0.4, 1.0]),
            &Pose::IDENTITY,
            [0.5, 0.5, 0.5, 1.0],
            None,
        );
        let s = FloorShadow::build(
            &[DrawItem::new(&left)],
            [-2.0, -2.0],
            [2.0, 2.0],
            0.0,
            0.02,
            0.1,
            0.5,
        )
        .unwrap();
        assert!(s.light_at(-1.0, 1.0) < 0.6 && s.light_at(1.0, -1.0) > 0.99);
    }
}
