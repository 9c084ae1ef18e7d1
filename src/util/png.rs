//! PNG encoding of 8-bit RGBA images (textures, renders).

/// Encodes `rgba` (row-major, 4 bytes per pixel, `width * height` pixels) as PNG.
pub fn encode_rgba(width: u32, height: u32, rgba: &[u8]) -> Result<Vec<u8>, String> {
    if rgba.len() != width as usize * height as usize * 4 {
        return Err(format!(
            "RGBA buffer has {} bytes, {width}x{height} needs {}",
            rgba.len(),
            width as usize * height as usize * 4
        ));
    }
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(png::ColorType::Rgba);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(|e| e.to_string())?;
        writer.write_image_data(rgba).map_err(|e| e.to_string())?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encodes_a_tiny_image() {
        let png = encode_rgba(2, 1, &[255, 0, 0, 255, 0, 255, 0, 255]).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        assert!(encode_rgba(2, 2, &[0; 4]).is_err());
    }
}
