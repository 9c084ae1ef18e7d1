//! RGBA8 images, colour-space conversion and the few pixel operations the views need (fill,
//! blend, blit). Images are always opaque sRGB: the rasterizer resolves to sRGB, overlays blend
//! onto it.

use std::path::Path;
use std::sync::OnceLock;

use super::RenderError;

/// An 8-bit sRGB image, row-major, top row first, 4 bytes per pixel (RGBA, alpha 255).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// `width * height * 4` bytes.
    pub rgba: Vec<u8>,
}

impl Image {
    /// A `width x height` image filled with `color` (sRGB bytes).
    pub fn new(width: u32, height: u32, color: [u8; 4]) -> Image {
        let n = width as usize * height as usize;
        let mut rgba = Vec::with_capacity(n * 4);
        for _ in 0..n {
            rgba.extend_from_slice(&color);
        }
        Image {
            width,
            height,
            rgba,
        }
    }

    /// PNG bytes of the image.
    pub fn encode_png(&self) -> Result<Vec<u8>, RenderError> {
        crate::util::png::encode_rgba(self.width, self.height, &self.rgba).map_err(RenderError::Png)
    }

    /// Writes the image as PNG, atomically (a half-written file never appears at `path`).
    pub fn save_png(&self, path: &Path) -> Result<(), RenderError> {
        let bytes = self.encode_png()?;
        crate::util::fsx::write_atomic(path, &bytes)?;
        Ok(())
    }

    /// The pixel at `(x, y)`, or `None` outside the image.
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 4;
        let p = self.rgba.get(i..i + 4)?;
        Some([p[0], p[1], p[2], p[3]])
    }

    /// Blends `color` (sRGB) over the pixel at `(x, y)` with opacity `alpha` in [0, 1]; pixels
    /// outside the image are ignored.
    pub fn blend(&mut self, x: i64, y: i64, color: [u8; 3], alpha: f32) {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return;
        }
        let a = alpha.clamp(0.0, 1.0);
        if a <= 0.0 {
            return;
        }
        let i = (y as usize * self.width as usize + x as usize) * 4;
        for c in 0..3 {
            let dst = f32::from(self.rgba[i + c]);
            let v = dst + (f32::from(color[c]) - dst) * a;
            self.rgba[i + c] = v.round().clamp(0.0, 255.0) as u8;
        }
        self.rgba[i + 3] = 255;
    }

    /// Blends a filled axis-aligned rectangle `[x0, x1) x [y0, y1)` (pixels, clipped).
    pub fn fill_rect(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, color: [u8; 3], alpha: f32) {
        let (x0, x1) = (x0.max(0), x1.min(i64::from(self.width)));
        let (y0, y1) = (y0.max(0), y1.min(i64::from(self.height)));
        for y in y0..y1 {
            for x in x0..x1 {
                self.blend(x, y, color, alpha);
            }
        }
    }

    /// Copies `src` with its top-left corner at `(x, y)` (clipped to this image).
    pub fn blit(&mut self, src: &Image, x: i64, y: i64) {
        for sy in 0..i64::from(src.height) {
            let ty = y + sy;
            if ty < 0 || ty >= i64::from(self.height) {
                continue;
            }
            for sx in 0..i64::from(src.width) {
                let tx = x + sx;
                if tx < 0 || tx >= i64::from(self.width) {
                    continue;
                }
                let si = (sy as usize * src.width as usize + sx as usize) * 4;
                let ti = (ty as usize * self.width as usize + tx as usize) * 4;
                self.rgba[ti..ti + 4].copy_from_slice(&src.rgba[si..si + 4]);
            }
        }
    }

    /// The image as a tiny-skia pixmap (for anti-aliased vector overlays). Our images are
    /// opaque, so straight and premultiplied alpha coincide.
    pub(crate) fn to_pixmap(&self) -> Option<tiny_skia::Pixmap> {
        let size = tiny_skia::IntSize::from_wh(self.width, self.height)?;
        tiny_skia::Pixmap::from_vec(self.rgba.clone(), size)
    }

    /// Takes the pixels back from a pixmap drawn with opaque content.
    pub(crate) fn from_pixmap(pixmap: tiny_skia::Pixmap) -> Image {
        let (width, height) = (pixmap.width(), pixmap.height());
        let mut rgba = pixmap.take();
        for px in rgba.chunks_exact_mut(4) {
            px[3] = 255;
        }
        Image {
            width,
            height,
            rgba,
        }
    }
}

/// Linear -> sRGB byte conversion through a 4096-entry table: finer than one sRGB step
/// everywhere, and the same bytes on every machine (no libm `powf` at render time).
#[derive(Debug, Clone, Copy)]
pub struct SrgbEncoder {
    lut: &'static [u8; 4096],
}

impl SrgbEncoder {
    /// The shared table.
    pub fn get() -> SrgbEncoder {
        static LUT: OnceLock<[u8; 4096]> = OnceLock::new();
        let lut = LUT.get_or_init(|| {
            let mut t = [0u8; 4096];
            for (i, slot) in t.iter_mut().enumerate() {
                let l = i as f64 / 4095.0;
                let s = if l <= 0.003_130_8 {
                    12.92 * l
                } else {
                    1.055 * l.powf(1.0 / 2.4) - 0.055
                };
                *slot = (s * 255.0).round().clamp(0.0, 255.0) as u8;
            }
            t
        });
        SrgbEncoder { lut }
    }

    /// Linear [0, 1] (clamped) -> sRGB byte.
    #[inline(always)]
    pub fn encode(&self, v: f32) -> u8 {
        // NaN and negatives land on 0, values above 1 on the last entry.
        let x = v * 4095.0 + 0.5;
        let i = if x > 0.0 { x as usize } else { 0 };
        self.lut[if i > 4095 { 4095 } else { i }]
    }
}

/// Linear [0, 1] -> sRGB byte.
pub fn linear_to_srgb_u8(v: f32) -> u8 {
    SrgbEncoder::get().encode(v)
}

/// sRGB byte -> linear [0, 1].
pub fn srgb_u8_to_linear(v: u8) -> f32 {
    static LUT: OnceLock<[f32; 256]> = OnceLock::new();
    let lut = LUT.get_or_init(|| {
        let mut t = [0.0f32; 256];
        for (i, slot) in t.iter_mut().enumerate() {
            let s = i as f64 / 255.0;
            let l = if s <= 0.040_45 {
                s / 12.92
            } else {
                ((s + 0.055) / 1.055).powf(2.4)
            };
            *slot = l as f32;
        }
        t
    });
    lut[v as usize]
}

/// Linear RGB -> sRGB bytes.
pub fn linear_rgb_to_srgb(c: [f32; 3]) -> [u8; 3] {
    [
        linear_to_srgb_u8(c[0]),
        linear_to_srgb_u8(c[1]),
        linear_to_srgb_u8(c[2]),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips_every_byte() {
        for b in 0..=255u8 {
            assert_eq!(linear_to_srgb_u8(srgb_u8_to_linear(b)), b);
        }
        assert_eq!(linear_to_srgb_u8(0.5), 188);
    }

    #[test]
    fn blend_and_blit_stay_inside() {
        let mut img = Image::new(4, 3, [0, 0, 0, 255]);
        img.blend(1, 1, [255, 255, 255], 0.5);
        assert_eq!(img.pixel(1, 1), Some([128, 128, 128, 255]));
        img.blend(-1, 9, [255, 0, 0], 1.0);
        img.fill_rect(2, 0, 10, 1, [255, 0, 0], 1.0);
        assert_eq!(img.pixel(3, 0), Some([255, 0, 0, 255]));
        assert_eq!(img.pixel(1, 0), Some([0, 0, 0, 255]));
        let src = Image::new(2, 2, [9, 9, 9, 255]);
        img.blit(&src, 3, 2);
        assert_eq!(img.pixel(3, 2), Some([9, 9, 9, 255]));
        assert_eq!(img.pixel(2, 2), Some([0, 0, 0, 255]));
        assert_eq!(img.pixel(4, 0), None);
    }
}
