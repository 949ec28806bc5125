//! Texture images decoded from bytes (PNG, JPEG, WebP, GIF, KTX2; told by their content) into RGBA8,
//! with the pixel cap checked on the header before any pixel buffer is allocated.
//!
//! Every loader that reads a texture (glTF embedded, data-URI or file images, OBJ/MTL maps) comes
//! through here, and so does the fuzzing; a new format is one more arm in `decode_rgba8`.

use std::io::Cursor;

/// The most pixels an image (a texture or an environment map) may have: 8192 x 8192. A small file
/// can declare a huge image (a PNG of zeros compresses a thousandfold), so the size is refused
/// before decoding rather than found out by running out of memory.
pub const MAX_IMAGE_PIXELS: u64 = 1 << 26;

/// An RGBA8 image, rows top first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rgba8 {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<[u8; 4]>,
}

#[derive(Debug, thiserror::Error)]
pub enum DecodeError {
    #[error("{width} x {height} pixels is over the limit of {MAX_IMAGE_PIXELS} (8192 x 8192)")]
    TooLarge { width: u64, height: u64 },
    #[error("cannot decode image: {0}")]
    Image(#[from] image::ImageError),
    #[error("cannot decode image: {0}")]
    Io(#[from] std::io::Error),
    #[error("KTX2: {0}")]
    Ktx2(#[from] super::ktx2::Ktx2Error),
}

/// Refuses an image size over the cap (also what the environment map readers call).
pub fn check_size(width: u64, height: u64) -> Result<(), DecodeError> {
    match width.checked_mul(height) {
        Some(n) if n <= MAX_IMAGE_PIXELS => Ok(()),
        _ => Err(DecodeError::TooLarge { width, height }),
    }
}

/// Decodes an image file's bytes into RGBA8 (grey replicated, 16-bit and float quantised).
pub fn decode_rgba8(bytes: &[u8]) -> Result<Rgba8, DecodeError> {
    if super::ktx2::is_ktx2(bytes) {
        let img = super::ktx2::decode(bytes)?;
        check_size(img.width as u64, img.height as u64)?;
        return Ok(img);
    }
    let reader = || image::ImageReader::new(Cursor::new(bytes)).with_guessed_format();
    let (w, h) = reader()?.into_dimensions()?;
    check_size(w.into(), h.into())?;
    let mut limits = image::Limits::default();
    // The widest decoded form (16-bit RGBA) of the largest image allowed, and a little for the codec.
    limits.max_alloc = Some(MAX_IMAGE_PIXELS * 8 + (1 << 20));
    let mut r = reader()?;
    r.limits(limits);
    let img = r.decode()?.into_rgba8();
    let (width, height) = (img.width() as usize, img.height() as usize);
    Ok(Rgba8 {
        width,
        height,
        pixels: img
            .into_raw()
            .chunks_exact(4)
            .map(|p| [p[0], p[1], p[2], p[3]])
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(width: u32, height: u32) -> Vec<u8> {
        let mut out = Vec::new();
        let img = image::RgbaImage::from_pixel(width, height, image::Rgba([10, 20, 30, 255]));
        img.write_to(&mut Cursor::new(&mut out), image::ImageFormat::Png)
            .unwrap();
        out
    }

    #[test]
    fn a_small_png_decodes_to_its_pixels() {
        let img = decode_rgba8(&png(3, 2)).unwrap();
        assert_eq!((img.width, img.height), (3, 2));
        assert_eq!(img.pixels, vec![[10, 20, 30, 255]; 6]);
    }

    #[test]
    fn a_header_over_the_cap_is_refused_before_decoding() {
        // A 1 x 1 PNG whose IHDR is rewritten to claim 65536 x 65536 (the CRC is fixed up too): the
        // refusal must come from the header, not from an allocation of 16 GiB.
        let mut bytes = png(1, 1);
        bytes[16..20].copy_from_slice(&65536u32.to_be_bytes());
        bytes[20..24].copy_from_slice(&65536u32.to_be_bytes());
        let crc = crc32(&bytes[12..29]);
        bytes[29..33].copy_from_slice(&crc.to_be_bytes());
        let e = decode_rgba8(&bytes).unwrap_err();
        assert!(
            matches!(
                e,
                DecodeError::TooLarge {
                    width: 65536,
                    height: 65536
                }
            ),
            "{e}"
        );
        assert!(e.to_string().contains("65536 x 65536"), "{e}");
        assert!(check_size(8192, 8192).is_ok());
        assert!(check_size(8193, 8192).is_err());
        assert!(check_size(u64::MAX, 2).is_err());
    }

    fn crc32(data: &[u8]) -> u32 {
        let mut c = 0xFFFF_FFFFu32;
        for &b in data {
            c ^= b as u32;
            for _ in 0..8 {
                c = if c & 1 != 0 {
                    0xEDB8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
        }
        !c
    }
}
