//! Cameras: a perspective pinhole (`look_at`) and an orthographic top-down view over XY
//! bounds. World Z is up. Pixel coordinates have their origin at the top-left image corner;
//! the centre of pixel `(i, j)` is at `(i + 0.5, j + 0.5)`.

use nalgebra::Vector3;

use super::RenderError;

/// How camera coordinates map to the image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Projection {
    /// Pinhole with a vertical field of view (the horizontal one follows the image aspect).
    Perspective {
        /// `tan(fov_y / 2)`.
        tan_half_fov_y: f64,
    },
    /// Parallel projection showing at least `half_width x half_height` metres around the
    /// optical axis; pixels stay square, so the longer image side shows more.
    Orthographic {
        /// Half the extent along the camera's right axis, metres.
        half_width: f64,
        /// Half the extent along the camera's up axis, metres.
        half_height: f64,
    },
}

/// A camera: position, orthonormal axes and projection. `forward` is the viewing direction;
/// camera coordinates are `(x right, y up, z forward)` with depth `z > 0` in front.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Eye position, world, metres.
    pub eye: Vector3<f64>,
    /// Image right, world unit vector.
    pub right: Vector3<f64>,
    /// Image up, world unit vector.
    pub up: Vector3<f64>,
    /// Viewing direction, world unit vector.
    pub forward: Vector3<f64>,
    /// Projection.
    pub projection: Projection,
    /// Nearest depth drawn, metres (geometry closer is clipped).
    pub near: f64,
    /// Offset of the image centre from the optical axis along (right, up), in image-plane
    /// units (`x / z` for perspective, metres for orthographic). A level camera with a
    /// vertical shift keeps verticals vertical (two-point perspective) while framing the floor.
    pub lens_shift: [f64; 2],
}

impl Camera {
    /// A perspective camera at `eye` looking at `target`, with `up` (world, usually +Z) as the
    /// approximate image up and a vertical field of view of `fov_y_deg` degrees.
    pub fn look_at(
        eye: [f64; 3],
        target: [f64; 3],
        up: [f64; 3],
        fov_y_deg: f64,
    ) -> Result<Camera, RenderError> {
        if !(fov_y_deg > 0.5 && fov_y_deg < 179.0) {
            return Err(RenderError::InvalidCamera(format!(
                "vertical field of view {fov_y_deg} deg is outside (0.5, 179)"
            )));
        }
        let (right, up, forward) = basis(eye, target, up)?;
        Ok(Camera {
            eye: Vector3::from(eye),
            right,
            up,
            forward,
            projection: Projection::Perspective {
                tan_half_fov_y: (fov_y_deg.to_radians() / 2.0).tan(),
            },
            near: 0.02,
            lens_shift: [0.0, 0.0],
        })
    }

    /// An orthographic camera looking straight down (-Z) over the XY rectangle `min..max`,
    /// +X to the right and +Y up in the image. `top_z` is the height of the eye; geometry
    /// above it is clipped.
    pub fn top_down(min: [f64; 2], max: [f64; 2], top_z: f64) -> Result<Camera, RenderError> {
        let (w, h) = (max[0] - min[0], max[1] - min[1]);
        if !(w > 0.0 && h > 0.0 && w.is_finite() && h.is_finite() && top_z.is_finite()) {
            return Err(RenderError::InvalidCamera(format!(
                "top-down bounds {min:?}..{max:?} are empty or not finite"
            )));
        }
        Ok(Camera {
            eye: Vector3::new((min[0] + max[0]) / 2.0, (min[1] + max[1]) / 2.0, top_z),
            right: Vector3::x(),
            up: Vector3::y(),
            forward: -Vector3::z(),
            projection: Projection::Orthographic {
                half_width: w / 2.0,
                half_height: h / 2.0,
            },
            near: 0.0,
            lens_shift: [0.0, 0.0],
        })
    }

    /// `p` in camera coordinates `(x right, y up, z depth)`.
    pub fn to_camera(&self, p: [f64; 3]) -> Vector3<f64> {
        let d = Vector3::from(p) - self.eye;
        Vector3::new(d.dot(&self.right), d.dot(&self.up), d.dot(&self.forward))
    }

    /// Pixels per unit of camera-plane coordinate for a `width x height` image: for
    /// perspective, per unit of `x / z`; for orthographic, per metre.
    pub fn pixel_scale(&self, width: u32, height: u32) -> f64 {
        let (w, h) = (f64::from(width), f64::from(height));
        match self.projection {
            Projection::Perspective { tan_half_fov_y } => h / 2.0 / tan_half_fov_y,
            Projection::Orthographic {
                half_width,
                half_height,
            } => (w / 2.0 / half_width).min(h / 2.0 / half_height),
        }
    }

    /// Pixel position of the optical axis in a `width x height` image (the image centre
    /// moved by the lens shift).
    pub fn principal_point(&self, width: u32, height: u32) -> (f64, f64) {
        let s = self.pixel_scale(width, height);
        (
            f64::from(width) / 2.0 - self.lens_shift[0] * s,
            f64::from(height) / 2.0 + self.lens_shift[1] * s,
        )
    }

    /// Projects a point in camera coordinates to `(pixel x, pixel y, depth)`; `None` when it
    /// lies closer than the near plane.
    pub fn project_camera(&self, c: Vector3<f64>, width: u32, height: u32) -> Option<[f64; 3]> {
        let s = self.pixel_scale(width, height);
        let (cx, cy) = self.principal_point(width, height);
        match self.projection {
            Projection::Perspective { .. } => {
                if c.z < self.near {
                    return None;
                }
                Some([cx + c.x / c.z * s, cy - c.y / c.z * s, c.z])
            }
            Projection::Orthographic { .. } => {
                if c.z < self.near {
                    return None;
                }
                Some([cx + c.x * s, cy - c.y * s, c.z])
            }
        }
    }

    /// Projects a world point to `(pixel x, pixel y, depth)` in a `width x height` image;
    /// `None` when it lies closer than the near plane (or behind the camera).
    pub fn project(&self, p: [f64; 3], width: u32, height: u32) -> Option<[f64; 3]> {
        self.project_camera(self.to_camera(p), width, height)
    }

    /// True for perspective cameras.
    pub fn is_perspective(&self) -> bool {
        matches!(self.projection, Projection::Perspective { .. })
    }
}

/// Right, up and forward unit vectors.
type Basis = (Vector3<f64>, Vector3<f64>, Vector3<f64>);

/// Right, up and forward unit vectors of a camera at `eye` looking at `target`.
fn basis(eye: [f64; 3], target: [f64; 3], up: [f64; 3]) -> Result<Basis, RenderError> {
    let bad =
        |why: &str| RenderError::InvalidCamera(format!("eye {eye:?}, target {target:?}: {why}"));
    let forward = (Vector3::from(target) - Vector3::from(eye))
        .try_normalize(1e-9)
        .ok_or_else(|| bad("eye and target coincide or are not finite"))?;
    let right = forward
        .cross(&Vector3::from(up))
        .try_normalize(1e-9)
        .ok_or_else(|| bad("the view direction is parallel to the up vector"))?;
    let cam_up = right.cross(&forward);
    Ok((right, cam_up, forward))
}

/// Picks how far back along `-forward` (from `target`) a perspective camera must stand so that
/// every point of `points` projects inside the image with `margin` (fraction of the half size)
/// to spare; returns the fitted camera. The camera keeps its direction and field of view and
/// is shifted sideways so the points' projection is centred.
pub fn fit_perspective(
    direction: [f64; 3],
    up: [f64; 3],
    fov_y_deg: f64,
    aspect: f64,
    points: &[[f64; 3]],
    margin: f64,
) -> Result<Camera, RenderError> {
    if points.is_empty() {
        return Err(RenderError::InvalidCamera("nothing to frame".into()));
    }
    let dir = Vector3::from(direction);
    let origin = [0.0; 3];
    let probe = Camera::look_at(origin, [dir.x, dir.y, dir.z], up, fov_y_deg)?;
    let Projection::Perspective { tan_half_fov_y } = probe.projection else {
        return Err(RenderError::InvalidCamera(
            "not a perspective camera".into(),
        ));
    };
    let ty = tan_half_fov_y * (1.0 - margin).clamp(0.05, 1.0);
    let tx = ty * aspect;
    // In the camera basis, a point (x, y, z) fits when |x - sx| <= tx (z + d) and likewise for
    // y, with the eye moved to -d along forward and shifted by (sx, sy). For fixed d, the best
    // shift centres the extreme bounds; the fit is then a 1-D search on d, monotone in d.
    let cam: Vec<Vector3<f64>> = points
        .iter()
        .map(|p| {
            let v = Vector3::from(*p);
            Vector3::new(v.dot(&probe.right), v.dot(&probe.up), v.dot(&probe.forward))
        })
        .collect();
    let solve_shift = |d: f64, t: f64, coord: fn(&Vector3<f64>) -> f64| -> Option<f64> {
        // Need max_i (c_i - t (z_i + d)) <= s <= min_i (c_i + t (z_i + d)).
        let mut lo = f64::NEG_INFINITY;
        let mut hi = f64::INFINITY;
        for c in &cam {
            let depth = c.z + d;
            if depth <= 1e-6 {
                return None;
            }
            lo = lo.max(coord(c) - t * depth);
            hi = hi.min(coord(c) + t * depth);
        }
        (lo <= hi).then_some((lo + hi) / 2.0)
    };
    let fits =
        |d: f64| solve_shift(d, tx, |c| c.x).is_some() && solve_shift(d, ty, |c| c.y).is_some();
    let min_z = cam.iter().map(|c| c.z).fold(f64::INFINITY, f64::min);
    let mut lo = -min_z + 1e-3;
    let mut hi = lo.max(0.0) + 1.0;
    let mut guard = 0;
    while !fits(hi) && guard < 60 {
        hi = hi * 2.0 + 1.0;
        guard += 1;
    }
    for _ in 0..60 {
        let mid = (lo + hi) / 2.0;
        if fits(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let d = hi;
    let sx = solve_shift(d, tx, |c| c.x).unwrap_or(0.0);
    let sy = solve_shift(d, ty, |c| c.y).unwrap_or(0.0);
    let eye = probe.right * sx + probe.up * sy - probe.forward * d;
    Ok(Camera {
        eye,
        near: (d * 0.01).clamp(0.005, 0.05),
        ..probe
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_at_maps_target_to_centre_and_right_to_right() {
        let cam =
            Camera::look_at([0.0, -5.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 90.0).unwrap();
        let p = cam.project([0.0, 0.0, 0.0], 200, 100).unwrap();
        assert!((p[0] - 100.0).abs() < 1e-9 && (p[1] - 50.0).abs() < 1e-9);
        // At depth 5 with tan(45 deg) = 1, half the image height (50 px) spans 5 m.
        let q = cam.project([1.0, 0.0, 2.0], 200, 100).unwrap();
        assert!((q[0] - 110.0).abs() < 1e-9, "{q:?}");
        assert!((q[1] - 30.0).abs() < 1e-9, "{q:?}");
        assert!(cam.project([0.0, -6.0, 0.0], 200, 100).is_none());
    }

    #[test]
    fn top_down_keeps_pixels_square() {
        let cam = Camera::top_down([0.0, 0.0], [4.0, 2.0], 5.0).unwrap();
        let p = cam.project([4.0, 2.0, 0.0], 400, 400).unwrap();
        assert!(
            (p[0] - 400.0).abs() < 1e-9 && (p[1] - 100.0).abs() < 1e-9,
            "{p:?}"
        );
        assert!(Camera::top_down([0.0, 0.0], [0.0, 1.0], 1.0).is_err());
    }

    #[test]
    fn fitted_camera_frames_every_point() {
        let pts: Vec<[f64; 3]> = (0..8)
            .map(|i| {
                [
                    if i & 1 == 0 { -1.0 } else { 2.0 },
                    if i & 2 == 0 { -0.5 } else { 0.5 },
                    if i & 4 == 0 { 0.0 } else { 1.5 },
                ]
            })
            .collect();
        let cam =
            fit_perspective([-1.0, 1.0, -0.6], [0.0, 0.0, 1.0], 40.0, 1.5, &pts, 0.1).unwrap();
        let (w, h) = (300u32, 200u32);
        let mut touch = [false; 4];
        for p in &pts {
            let q = cam.project(*p, w, h).unwrap();
            assert!(
                q[0] > 0.0 && q[0] < 300.0 && q[1] > 0.0 && q[1] < 200.0,
                "{q:?}"
            );
            touch[0] |= q[0] < 300.0 * 0.06;
            touch[1] |= q[0] > 300.0 * 0.94;
            touch[2] |= q[1] < 200.0 * 0.06;
            touch[3] |= q[1] > 200.0 * 0.94;
        }
        // Tight along at least one axis: the fit does not leave the object tiny.
        assert!(
            (touch[0] && touch[1]) || (touch[2] && touch[3]),
            "{touch:?}"
        );
    }
}
