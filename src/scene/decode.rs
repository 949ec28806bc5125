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
    #[error("its header declares {width} x {height} pixels, more than {bytes} bytes of {format} can hold (a truncated or lying file)")]
    Unjustified {
        width: u64,
        height: u64,
        bytes: usize,
        format: &'static str,
    },
}

/// Refuses an image size over the cap (also what the environment map readers call).
pub fn check_size(width: u64, height: u64) -> Result<(), DecodeError> {
    match width.checked_mul(height) {
        Some(n) if n <= MAX_IMAGE_PIXELS => Ok(()),
        _ => Err(DecodeError::TooLarge { width, height }),
    }
}

/// Refuses a header that declares more pixels than the file's size can hold at the format's best
/// compression ratio: the decoders allocate the whole image from the header before they read any
/// pixel data, so a lying header of a few bytes would otherwise cost up to the cap in memory.
/// Formats that can code a constant image in a few bytes whatever its size (lossless WebP spends
/// no bits on a one-symbol Huffman code) are bounded by the cap alone.
fn check_justified(
    format: image::ImageFormat,
    width: u64,
    height: u64,
    bytes: usize,
) -> Result<(), DecodeError> {
    use image::ImageFormat as F;
    let len = bytes as u64;
    let (ok, name) = match format {
        // Deflate expands at most 1032-fold; every row holds a filter byte and at least one bit a
        // pixel.
        F::Png => (height * (1 + width.div_ceil(8)) <= 1032 * len + 1024, "PNG"),
        // Huffman-coded JPEG spends at least one bit on every 8 x 8 block of its full-size
        // component (arithmetic coding, which could spend less, is not decoded).
        F::Jpeg => (
            width.div_ceil(8) * height.div_ceil(8) <= 8 * len + 64,
            "JPEG",
        ),
        // An LZW code takes at least 3 bits and stands for at most 4096 pixels (the table's size).
        F::Gif => (width * height <= 4096 * (8 * len / 3 + 1), "GIF"),
        _ => (true, ""),
    };
    if ok {
        Ok(())
    } else {
        Err(DecodeError::Unjustified {
            width,
            height,
            bytes,
            format: name,
        })
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
    let probe = reader()?;
    let format = probe.format();
    let (w, h) = probe.into_dimensions()?;
    check_size(w.into(), h.into())?;
    if let Some(format) = format {
        check_justified(format, w.into(), h.into(), bytes.len())?;
    }
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
        resize_ihdr(&mut bytes, 65536, 65536);
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

    /// Rewrites a PNG's IHDR size (and its CRC).
    fn resize_ihdr(bytes: &mut [u8], width: u32, height: u32) {
        bytes[16..20].copy_from_slice(&width.to_be_bytes());
        bytes[20..24].copy_from_slice(&height.to_be_bytes());
        let crc = crc32fast::hash(&bytes[12..29]);
        bytes[29..33].copy_from_slice(&crc.to_be_bytes());
    }

    #[test]
    fn a_header_the_file_cannot_hold_is_refused_before_decoding() {
        // 4096 x 4096 is under the cap, but some 70 bytes of deflate cannot hold its 2 MB of rows.
        let mut bytes = png(1, 1);
        resize_ihdr(&mut bytes, 4096, 4096);
        let e = decode_rgba8(&bytes).unwrap_err();
        assert!(
            matches!(e, DecodeError::Unjustified { format: "PNG", .. }),
            "{e}"
        );
        assert!(e.to_string().contains("4096 x 4096"), "{e}");
        // A large image that really is that compressible still decodes: 2048^2 of one colour.
        let big = png(2048, 2048);
        assert!(big.len() < 100_000, "{}", big.len());
        assert_eq!(decode_rgba8(&big).unwrap().pixels.len(), 2048 * 2048);
        // The bounds of the other formats, at their edges.
        use image::ImageFormat as F;
        assert!(check_justified(F::Jpeg, 8 * 64, 8 * 64, 512 - 8).is_ok());
        assert!(check_justified(F::Jpeg, 8 * 64, 8 * 64 + 64, 512).is_err());
        assert!(check_justified(F::Gif, 4096, 9, 3).is_ok());
        assert!(check_justified(F::Gif, 4096, 10_000, 3).is_err());
        assert!(check_justified(F::WebP, 16383, 16383, 20).is_ok());
    }
}
