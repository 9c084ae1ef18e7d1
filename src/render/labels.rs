//! Object labels: small text on a background box, placed greedily so boxes do not overlap
//! (highest priority first; a label that cannot sit on its anchor moves to a nearby free spot
//! and gets a leader line back to it).

use super::RenderError;
use super::image::Image;
use super::text::{draw_text, measure};

/// A label to place.
#[derive(Debug, Clone, PartialEq)]
pub struct Label {
    /// The text.
    pub text: String,
    /// The point it names, pixels.
    pub anchor: [f64; 2],
    /// Placed first when higher.
    pub priority: f64,
    /// Text size, pixels.
    pub size_px: f32,
    /// Pixel box of the thing labelled, when known: labels keep off small things (their own
    /// included) so the label does not hide what it names.
    pub target: Option<[f64; 4]>,
}

/// Where a label went.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placed {
    /// Box `[x0, y0, x1, y1]`, pixels.
    pub rect: [f64; 4],
    /// The box is away from its anchor (a leader line is drawn).
    pub moved: bool,
}

const PAD_X: f64 = 3.0;
const PAD_Y: f64 = 1.5;

fn overlap(a: &[f64; 4], b: &[f64; 4]) -> f64 {
    let w = (a[2].min(b[2]) - a[0].max(b[0])).max(0.0);
    let h = (a[3].min(b[3]) - a[1].max(b[1])).max(0.0);
    w * h
}

/// Places `labels` inside a `width x height` image avoiding `obstacles` and each other.
/// Returns one placement per label, in the input order.
pub fn place(
    labels: &[Label],
    width: u32,
    height: u32,
    obstacles: &[[f64; 4]],
) -> Result<Vec<Placed>, RenderError> {
    let mut order: Vec<usize> = (0..labels.len()).collect();
    // Stable: equal priorities keep input order, so placement is deterministic.
    order.sort_by(|&a, &b| labels[b].priority.total_cmp(&labels[a].priority));
    // (box, weight): other labels and the obstacles weigh 1, small labelled things less.
    let mut taken: Vec<([f64; 4], f64)> = obstacles.iter().map(|o| (*o, 1.0)).collect();
    for l in labels {
        let Some(t) = l.target else {
            continue;
        };
        let m = measure(&l.text, l.size_px)?;
        let label_area = (f64::from(m.width) + 2.0 * PAD_X) * (f64::from(m.height()) + 2.0 * PAD_Y);
        if (t[2] - t[0]) * (t[3] - t[1]) < 2.0 * label_area {
            taken.push((t, 0.2));
        }
    }
    let mut out = vec![
        Placed {
            rect: [0.0; 4],
            moved: false
        };
        labels.len()
    ];
    let (w, h) = (f64::from(width), f64::from(height));
    for i in order {
        let l = &labels[i];
        let m = measure(&l.text, l.size_px)?;
        let bw = f64::from(m.width) + 2.0 * PAD_X;
        let bh = f64::from(m.height()) + 2.0 * PAD_Y;
        let [ax, ay] = l.anchor;
        let mut candidates = vec![(0.0, 0.0)];
        for ring in 1..=4 {
            let r = f64::from(ring);
            let dy = (bh + 2.0) * r;
            let dx = (bw / 2.0 + 6.0) * r;
            candidates.extend([
                (0.0, -dy),
                (0.0, dy),
                (dx, 0.0),
                (-dx, 0.0),
                (dx, -dy),
                (-dx, -dy),
                (dx, dy),
                (-dx, dy),
            ]);
        }
        let mut best: Option<(f64, [f64; 4], bool)> = None;
        for (k, (dx, dy)) in candidates.iter().enumerate() {
            let cx = (ax + dx).clamp(bw / 2.0 + 1.0, (w - bw / 2.0 - 1.0).max(bw / 2.0));
            let cy = (ay + dy).clamp(bh / 2.0 + 1.0, (h - bh / 2.0 - 1.0).max(bh / 2.0));
            let rect = [cx - bw / 2.0, cy - bh / 2.0, cx + bw / 2.0, cy + bh / 2.0];
            let cost: f64 = taken.iter().map(|(t, w)| w * overlap(&rect, t)).sum();
            // Prefer free spots; among overlapping ones, the least overlap, then the nearest.
            let score = cost * 1000.0 + k as f64;
            if best.as_ref().is_none_or(|b| score < b.0) {
                let moved = (cx - ax).abs() > bw / 2.0 || (cy - ay).abs() > bh / 2.0;
                best = Some((score, rect, moved));
            }
            if cost == 0.0 {
                break;
            }
        }
        if let Some((_, rect, moved)) = best {
            taken.push((rect, 1.0));
            out[i] = Placed { rect, moved };
        }
    }
    Ok(out)
}

/// Draws placed labels: leader lines and anchor dots first, then boxes and text.
pub fn draw(img: &mut Image, labels: &[Label], placed: &[Placed]) -> Result<(), RenderError> {
    if let Some(mut pm) = img.to_pixmap() {
        let mut paint = tiny_skia::Paint::default();
        paint.set_color_rgba8(40, 40, 48, 230);
        paint.anti_alias = true;
        let stroke = tiny_skia::Stroke {
            width: 1.2,
            ..Default::default()
        };
        for (l, p) in labels.iter().zip(placed) {
            if !p.moved {
                continue;
            }
            let [ax, ay] = l.anchor.map(|v| v as f32);
            let r = p.rect.map(|v| v as f32);
            // Leader to the nearest point of the box.
            let tx = ax.clamp(r[0], r[2]);
            let ty = ay.clamp(r[1], r[3]);
            let mut pb = tiny_skia::PathBuilder::new();
            pb.move_to(ax, ay);
            pb.line_to(tx, ty);
            if let Some(path) = pb.finish() {
                pm.stroke_path(
                    &path,
                    &paint,
                    &stroke,
                    tiny_skia::Transform::identity(),
                    None,
                );
            }
            if let Some(dot) = tiny_skia::PathBuilder::from_circle(ax, ay, 2.0) {
                pm.fill_path(
                    &dot,
                    &paint,
                    tiny_skia::FillRule::Winding,
                    tiny_skia::Transform::identity(),
                    None,
                );
            }
        }
        *img = Image::from_pixmap(pm);
    }
    for (l, p) in labels.iter().zip(placed) {
        let r = p.rect;
        let (x0, y0, x1, y1) = (
            r[0].round() as i64,
            r[1].round() as i64,
            r[2].round() as i64,
            r[3].round() as i64,
        );
        img.fill_rect(x0, y0, x1, y1, [255, 255, 250], 0.9);
        let border = [70, 70, 80];
        img.fill_rect(x0, y0, x1, y0 + 1, border, 0.7);
        img.fill_rect(x0, y1 - 1, x1, y1, border, 0.7);
        img.fill_rect(x0, y0 + 1, x0 + 1, y1 - 1, border, 0.7);
        img.fill_rect(x1 - 1, y0 + 1, x1, y1 - 1, border, 0.7);
        let m = measure(&l.text, l.size_px)?;
        draw_text(
            img,
            (r[0] + PAD_X) as f32,
            (r[1] + PAD_Y) as f32 + m.ascent,
            &l.text,
            l.size_px,
            [20, 20, 28],
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crowded_labels_do_not_overlap_when_there_is_room() {
        let labels: Vec<Label> = (0..6)
            .map(|i| Label {
                text: format!("mug_{i}"),
                anchor: [100.0 + f64::from(i), 100.0],
                priority: 0.0,
                size_px: 12.0,
                target: None,
            })
            .collect();
        let placed = place(&labels, 300, 200, &[]).unwrap();
        for i in 0..placed.len() {
            for j in i + 1..placed.len() {
                assert_eq!(overlap(&placed[i].rect, &placed[j].rect), 0.0);
            }
            let r = placed[i].rect;
            assert!(r[0] >= 0.0 && r[1] >= 0.0 && r[2] <= 300.0 && r[3] <= 200.0);
        }
        assert!(!placed[0].moved);
        assert!(placed.iter().skip(1).all(|p| p.moved));
    }
}
