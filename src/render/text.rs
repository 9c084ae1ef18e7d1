//! Text on images with the bundled DejaVu Sans (`src/data/fonts/`, Bitstream Vera licence):
//! measuring and drawing a single line at a pixel size.

use std::sync::OnceLock;

use ab_glyph::{Font, FontRef, GlyphId, PxScale, ScaleFont, point};

use super::RenderError;
use super::image::Image;

static FONT_BYTES: &[u8] = include_bytes!("../data/fonts/DejaVuSans.ttf");

/// The bundled font.
fn font() -> Result<&'static FontRef<'static>, RenderError> {
    static FONT: OnceLock<Option<FontRef<'static>>> = OnceLock::new();
    FONT.get_or_init(|| FontRef::try_from_slice(FONT_BYTES).ok())
        .as_ref()
        .ok_or_else(|| RenderError::Font("the bundled DejaVu Sans does not parse".into()))
}

/// Extent of a line of text: advance width and the line's ascent/descent (pixels).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TextMetrics {
    /// Advance width, pixels.
    pub width: f32,
    /// Height above the baseline, pixels.
    pub ascent: f32,
    /// Depth below the baseline, pixels (positive).
    pub descent: f32,
}

impl TextMetrics {
    /// Ascent + descent.
    pub fn height(&self) -> f32 {
        self.ascent + self.descent
    }
}

fn glyph_ids<F: Font>(scaled: &impl ScaleFont<F>, text: &str) -> Vec<GlyphId> {
    text.chars().map(|c| scaled.glyph_id(c)).collect()
}

/// Measures `text` at `size_px`.
pub fn measure(text: &str, size_px: f32) -> Result<TextMetrics, RenderError> {
    let f = font()?;
    let scaled = f.as_scaled(PxScale::from(size_px));
    let ids = glyph_ids(&scaled, text);
    let mut width = 0.0;
    for (i, id) in ids.iter().enumerate() {
        if i > 0 {
            width += scaled.kern(ids[i - 1], *id);
        }
        width += scaled.h_advance(*id);
    }
    Ok(TextMetrics {
        width,
        ascent: scaled.ascent(),
        descent: -scaled.descent(),
    })
}

/// Draws `text` with its baseline starting at `(x, baseline)` in `color` (sRGB), anti-aliased.
pub fn draw_text(
    img: &mut Image,
    x: f32,
    baseline: f32,
    text: &str,
    size_px: f32,
    color: [u8; 3],
) -> Result<(), RenderError> {
    let f = font()?;
    let scale = PxScale::from(size_px);
    let scaled = f.as_scaled(scale);
    let ids = glyph_ids(&scaled, text);
    let mut pen = x;
    for (i, id) in ids.iter().enumerate() {
        if i > 0 {
            pen += scaled.kern(ids[i - 1], *id);
        }
        let glyph = id.with_scale_and_position(scale, point(pen, baseline));
        pen += scaled.h_advance(*id);
        if let Some(outline) = f.outline_glyph(glyph) {
            let b = outline.px_bounds();
            let (ox, oy) = (b.min.x as i64, b.min.y as i64);
            outline.draw(|gx, gy, coverage| {
                img.blend(ox + i64::from(gx), oy + i64::from(gy), color, coverage);
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_draws_ink_inside_its_box_only() {
        let mut img = Image::new(120, 30, [255, 255, 255, 255]);
        let m = measure("chair_0", 16.0).unwrap();
        assert!(m.width > 40.0 && m.width < 80.0, "{m:?}");
        draw_text(&mut img, 10.0, 20.0, "chair_0", 16.0, [0, 0, 0]).unwrap();
        let mut ink = 0;
        for y in 0..30 {
            for x in 0..120 {
                let p = img.pixel(x, y).unwrap();
                if p[0] < 128 {
                    ink += 1;
                    assert!(f32::from(x as u16) >= 9.0 && (x as f32) <= 11.0 + m.width);
                    assert!(
                        (y as f32) >= 20.0 - m.ascent - 1.0 && (y as f32) <= 20.0 + m.descent + 1.0
                    );
                }
            }
        }
        assert!(ink > 60, "{ink}");
    }
}
