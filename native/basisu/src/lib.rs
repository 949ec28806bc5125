//! Safe calls into the vendored Basis Universal transcoder: one ETC1S or UASTC image to RGBA8.
//! Buffer sizes are checked here before the C++ code sees a pointer; corrupt bitstreams are errors.

use std::os::raw::c_int;

extern "C" {
    fn glint_etc1s_to_rgba(
        endpoints: *const u8,
        endpoints_len: u32,
        num_endpoints: u32,
        selectors: *const u8,
        selectors_len: u32,
        num_selectors: u32,
        tables: *const u8,
        tables_len: u32,
        level: *const u8,
        level_len: u32,
        rgb_offset: u32,
        rgb_len: u32,
        alpha_offset: u32,
        alpha_len: u32,
        width: u32,
        height: u32,
        out: *mut u8,
        out_pixels: u32,
    ) -> c_int;
    fn glint_uastc_to_rgba(
        blocks: *const u8,
        blocks_len: u32,
        width: u32,
        height: u32,
        has_alpha: c_int,
        out: *mut u8,
        out_pixels: u32,
    ) -> c_int;
}

/// Why a transcode failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TranscodeError {
    /// A buffer or size does not fit what the call needs (checked before the transcoder runs).
    Size,
    /// The ETC1S endpoint or selector codebook is corrupt.
    Codebooks,
    /// The ETC1S Huffman tables are corrupt.
    Tables,
    /// The image's blocks are corrupt.
    Blocks,
}

impl std::fmt::Display for TranscodeError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            TranscodeError::Size => "a size does not fit its buffer",
            TranscodeError::Codebooks => "corrupt ETC1S codebooks",
            TranscodeError::Tables => "corrupt ETC1S Huffman tables",
            TranscodeError::Blocks => "corrupt compressed blocks",
        })
    }
}

impl std::error::Error for TranscodeError {}

/// The ETC1S global codebooks of a KTX2 file (BasisLZ supercompression global data).
pub struct Etc1sCodebooks<'a> {
    pub endpoints: &'a [u8],
    pub num_endpoints: u32,
    pub selectors: &'a [u8],
    pub num_selectors: u32,
    pub tables: &'a [u8],
}

/// Where an image's slices lie in its level's bytes.
#[derive(Clone, Copy, Debug)]
pub struct Etc1sSlices {
    pub rgb: (u32, u32),
    /// (offset, length); length 0 when the image has no alpha slice.
    pub alpha: (u32, u32),
}

fn len32(b: &[u8]) -> Result<u32, TranscodeError> {
    u32::try_from(b.len()).map_err(|_| TranscodeError::Size)
}

/// Checks that `out` holds exactly `width * height` RGBA8 pixels and returns that count.
fn out_pixels(out: &[u8], width: u32, height: u32) -> Result<u32, TranscodeError> {
    let n = (width as u64) * (height as u64);
    if width == 0 || height == 0 || n * 4 != out.len() as u64 || n > u32::MAX as u64 {
        return Err(TranscodeError::Size);
    }
    Ok(n as u32)
}

fn within(range: (u32, u32), len: usize) -> bool {
    (range.0 as u64 + range.1 as u64) <= len as u64
}

/// Transcodes one ETC1S image (`slices` inside `level`) to `out` (width x height RGBA8).
pub fn etc1s_to_rgba(
    books: &Etc1sCodebooks,
    level: &[u8],
    slices: Etc1sSlices,
    width: u32,
    height: u32,
    out: &mut [u8],
) -> Result<(), TranscodeError> {
    let pixels = out_pixels(out, width, height)?;
    if !within(slices.rgb, level.len()) || !within(slices.alpha, level.len()) || slices.rgb.1 == 0 {
        return Err(TranscodeError::Size);
    }
    // SAFETY: every pointer comes with the length of its slice, checked to fit u32; `out` holds
    // exactly `pixels` RGBA8 pixels and the slice ranges lie inside `level`.
    let rc = unsafe {
        glint_etc1s_to_rgba(
            books.endpoints.as_ptr(),
            len32(books.endpoints)?,
            books.num_endpoints,
            books.selectors.as_ptr(),
            len32(books.selectors)?,
            books.num_selectors,
            books.tables.as_ptr(),
            len32(books.tables)?,
            level.as_ptr(),
            len32(level)?,
            slices.rgb.0,
            slices.rgb.1,
            slices.alpha.0,
            slices.alpha.1,
            width,
            height,
            out.as_mut_ptr(),
            pixels,
        )
    };
    match rc {
        0 => Ok(()),
        1 => Err(TranscodeError::Codebooks),
        2 => Err(TranscodeError::Tables),
        _ => Err(TranscodeError::Blocks),
    }
}

/// Transcodes one UASTC image (16-byte 4x4 blocks, row by row) to `out` (width x height RGBA8).
pub fn uastc_to_rgba(
    blocks: &[u8],
    width: u32,
    height: u32,
    has_alpha: bool,
    out: &mut [u8],
) -> Result<(), TranscodeError> {
    let pixels = out_pixels(out, width, height)?;
    let need = width.div_ceil(4) as u64 * height.div_ceil(4) as u64 * 16;
    if blocks.len() as u64 != need {
        return Err(TranscodeError::Size);
    }
    // SAFETY: `blocks` holds exactly the image's blocks and `out` exactly `pixels` RGBA8 pixels.
    let rc = unsafe {
        glint_uastc_to_rgba(
            blocks.as_ptr(),
            len32(blocks)?,
            width,
            height,
            has_alpha as c_int,
            out.as_mut_ptr(),
            pixels,
        )
    };
    if rc == 0 {
        Ok(())
    } else {
        Err(TranscodeError::Blocks)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrong_sizes_are_refused_before_the_transcoder_runs() {
        let mut out = vec![0u8; 4 * 4 * 4];
        assert_eq!(
            uastc_to_rgba(&[0; 15], 4, 4, true, &mut out),
            Err(TranscodeError::Size)
        );
        assert_eq!(
            uastc_to_rgba(&[0; 16], 4, 5, true, &mut out),
            Err(TranscodeError::Size)
        );
    }
}
