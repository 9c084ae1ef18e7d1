//! Anti-aliased vector overlays (lines, polygons, arcs) in pixel coordinates, through
//! tiny-skia. Annotation code collects shapes on a [`Canvas`] and folds them back into the
//! image.

use tiny_skia::{FillRule, Paint, PathBuilder, Pixmap, Stroke, StrokeDash, Transform};

use super::image::Image;

/// A drawing surface over an image.
pub struct Canvas {
    pm: Option<Pixmap>,
    fallback: Option<Image>,
}

/// sRGB colour with opacity.
pub type Rgba = [u8; 4];

impl Canvas {
    /// Starts drawing on `img` (taken back with [`Canvas::finish`]).
    pub fn new(img: Image) -> Canvas {
        match img.to_pixmap() {
            Some(pm) => Canvas {
                pm: Some(pm),
                fallback: None,
            },
            None => Canvas {
                pm: None,
                fallback: Some(img),
            },
        }
    }

    /// The image with everything drawn.
    pub fn finish(self) -> Image {
        match (self.pm, self.fallback) {
            (Some(pm), _) => Image::from_pixmap(pm),
            (None, Some(img)) => img,
            (None, None) => Image::new(1, 1, [0, 0, 0, 255]),
        }
    }

    fn paint(color: Rgba) -> Paint<'static> {
        let mut p = Paint::default();
        p.set_color_rgba8(color[0], color[1], color[2], color[3]);
        p.anti_alias = true;
        p
    }

    /// A polyline through `pts` (closed when `closed`), `width` pixels wide, dashed when
    /// `dash` is `Some([on, off])`.
    pub fn polyline(
        &mut self,
        pts: &[[f64; 2]],
        closed: bool,
        color: Rgba,
        width: f32,
        dash: Option<[f32; 2]>,
    ) {
        let Some(pm) = self.pm.as_mut() else {
            return;
        };
        let Some(path) = path_of(pts, closed) else {
            return;
        };
        let stroke = Stroke {
            width,
            dash: dash.and_then(|d| StrokeDash::new(vec![d[0], d[1]], 0.0)),
            ..Default::default()
        };
        pm.stroke_path(
            &path,
            &Self::paint(color),
            &stroke,
            Transform::identity(),
            None,
        );
    }

    /// A straight line.
    pub fn line(&mut self, a: [f64; 2], b: [f64; 2], color: Rgba, width: f32) {
        self.polyline(&[a, b], false, color, width, None);
    }

    /// A filled polygon.
    pub fn fill(&mut self, pts: &[[f64; 2]], color: Rgba) {
        let Some(pm) = self.pm.as_mut() else {
            return;
        };
        let Some(path) = path_of(pts, true) else {
            return;
        };
        pm.fill_path(
            &path,
            &Self::paint(color),
            FillRule::Winding,
            Transform::identity(),
            None,
        );
    }

    /// Filled triangle arrow head at `tip` pointing along `dir` (pixels).
    pub fn arrow_head(&mut self, tip: [f64; 2], dir: [f64; 2], size: f64, color: Rgba) {
        let n = (dir[0] * dir[0] + dir[1] * dir[1]).sqrt();
        if n < 1e-9 {
            return;
        }
        let (dx, dy) = (dir[0] / n, dir[1] / n);
        let base = [tip[0] - dx * size, tip[1] - dy * size];
        let (px, py) = (-dy * size * 0.45, dx * size * 0.45);
        self.fill(
            &[
                tip,
                [base[0] + px, base[1] + py],
                [base[0] - px, base[1] - py],
            ],
            color,
        );
    }
}

fn path_of(pts: &[[f64; 2]], closed: bool) -> Option<tiny_skia::Path> {
    let (first, rest) = pts.split_first()?;
    let mut pb = PathBuilder::new();
    pb.move_to(first[0] as f32, first[1] as f32);
    for p in rest {
        pb.line_to(p[0] as f32, p[1] as f32);
    }
    if closed {
        pb.close();
    }
    pb.finish()
}

/// Points of a circular arc (centre, radius, start and end angle in radians, counter-clockwise
/// in the coordinates given), `segments` pieces.
pub fn arc_points(
    center: [f64; 2],
    radius: f64,
    a0: f64,
    a1: f64,
    segments: usize,
) -> Vec<[f64; 2]> {
    let n = segments.max(1);
    (0..=n)
        .map(|i| {
            let a = a0 + (a1 - a0) * i as f64 / n as f64;
            [center[0] + radius * a.cos(), center[1] + radius * a.sin()]
        })
        .collect()
}
