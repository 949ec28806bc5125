//! KTX2 textures (KHR_texture_basisu and plain KTX2): the container read and checked, Zstandard
//! inflated, ETC1S (BasisLZ) and UASTC transcoded to RGBA8, uncompressed RGBA8/RGB8 copied.
//!
//! glint samples level 0 of the first layer and face (a glTF texture is one 2D image). Every count
//! and size is checked against the bytes that hold it before anything is allocated: the level's
//! byte range by the `ktx2` reader, the image size against `MAX_EDGE` and `MAX_PIXELS`, a level's
//! inflated size against what its blocks need, the BasisLZ global data against its own length.
//! Corrupt bitstreams are the transcoder's errors. Nothing here panics on any input.

mod basislz;

use std::io::Read;

use glint_basisu::TranscodeError;
use ktx2::{ColorModel, Format, SupercompressionScheme};

/// The longest edge glint decodes.
pub const MAX_EDGE: u32 = 16384;
/// The most pixels glint decodes for one texture (256 MiB of RGBA8).
pub const MAX_PIXELS: u64 = 1 << 26;

pub use super::decode::Rgba8;

#[derive(Debug, thiserror::Error)]
pub enum Ktx2Error {
    #[error("not a valid KTX2 file: {0}")]
    Container(String),
    #[error("a {0}x{1} image is larger than glint reads (at most {MAX_EDGE} per edge, {MAX_PIXELS} pixels)")]
    TooLarge(u32, u32),
    #[error(
        "{0} textures are not supported (glint reads 2D ETC1S, UASTC, RGBA8 and RGB8 KTX2 images)"
    )]
    Unsupported(String),
    #[error("the file has no image level")]
    NoLevel,
    #[error("level 0 inflates to {declared} bytes by its index, but its image needs {needed}")]
    LevelSize { declared: u64, needed: u64 },
    #[error("Zstandard stream of level 0: {0}")]
    Zstd(String),
    #[error("BasisLZ global data: {0}")]
    BasisLz(&'static str),
    #[error("transcoding level 0: {0}")]
    Transcode(#[from] TranscodeError),
}

/// Whether `bytes` start with the KTX2 identifier.
pub fn is_ktx2(bytes: &[u8]) -> bool {
    bytes.starts_with(&[
        0xAB, b'K', b'T', b'X', b' ', b'2', b'0', 0xBB, b'\r', b'\n', 0x1A, b'\n',
    ])
}

/// Decodes level 0 (first layer, first face) of a KTX2 file to RGBA8.
pub fn decode(bytes: &[u8]) -> Result<Rgba8, Ktx2Error> {
    // The `ktx2` crate panics on some malformed data format descriptors (a texel block dimension
    // of 255 overflows its `dim + 1`); that is a bad file like any other.
    let reader = crate::scene::quiet_panic::catch(|| ktx2::Reader::new(bytes))
        .ok_or_else(|| Ktx2Error::Container("malformed data format descriptor".into()))?
        .map_err(|e| Ktx2Error::Container(e.to_string()))?;
    let header = reader.header();
    let (width, height) = (header.pixel_width, header.pixel_height.max(1));
    if header.pixel_depth > 1 {
        return Err(Ktx2Error::Unsupported("3D".into()));
    }
    if header.face_count != 1 {
        return Err(Ktx2Error::Unsupported("cube map".into()));
    }
    if width > MAX_EDGE || height > MAX_EDGE || width as u64 * height as u64 > MAX_PIXELS {
        return Err(Ktx2Error::TooLarge(width, height));
    }
    let mut out = vec![0u8; width as usize * height as usize * 4];
    transcode_level0(&reader, &mut out)?;
    Ok(Rgba8 {
        width: width as usize,
        height: height as usize,
        pixels: out
            .chunks_exact(4)
            .map(|p| [p[0], p[1], p[2], p[3]])
            .collect(),
    })
}

/// Level 0 of the first layer and face, as RGBA8 into `out` (width x height x 4 bytes).
fn transcode_level0(reader: &ktx2::Reader<&[u8]>, out: &mut [u8]) -> Result<(), Ktx2Error> {
    let header = reader.header();
    let (width, height) = (header.pixel_width, header.pixel_height.max(1));
    let level = reader.levels().next().ok_or(Ktx2Error::NoLevel)?;
    let layers = header.layer_count.max(1) as u64;
    let scheme = header.supercompression_scheme;
    // Every layer's bytes are declared; the first layer's `image` bytes are the texture.
    let inflated = |image: u64| {
        inflate(
            level.data,
            level.uncompressed_byte_length,
            scheme,
            image * layers,
        )
    };
    let model = reader.basic_dfd().and_then(|d| d.color_model);
    match (header.format, model, scheme) {
        (None, Some(ColorModel::ETC1S), Some(SupercompressionScheme::BasisLZ)) => {
            let books = basislz::GlobalData::parse(
                reader.supercompression_global_data(),
                header.level_count.max(1),
                header.layer_count.max(1),
            )?;
            let slices = books.first_image_slices(level.data.len())?;
            glint_basisu::etc1s_to_rgba(
                &books.codebooks(),
                level.data,
                slices,
                width,
                height,
                out,
            )?;
        }
        (None, Some(ColorModel::UASTC), None | Some(SupercompressionScheme::Zstandard)) => {
            let image = width.div_ceil(4) as u64 * height.div_ceil(4) as u64 * 16;
            let data = inflated(image)?;
            let first = &data[..image as usize];
            glint_basisu::uastc_to_rgba(first, width, height, true, out)?;
        }
        (
            Some(f @ (Format::R8G8B8A8_UNORM | Format::R8G8B8A8_SRGB)),
            _,
            None | Some(SupercompressionScheme::Zstandard),
        )
        | (
            Some(f @ (Format::R8G8B8_UNORM | Format::R8G8B8_SRGB)),
            _,
            None | Some(SupercompressionScheme::Zstandard),
        ) => {
            let channels: u64 = if matches!(f, Format::R8G8B8_UNORM | Format::R8G8B8_SRGB) {
                3
            } else {
                4
            };
            let image = width as u64 * height as u64 * channels;
            let data = inflated(image)?;
            for (o, p) in out
                .chunks_exact_mut(4)
                .zip(data.chunks_exact(channels as usize))
            {
                o[..channels as usize].copy_from_slice(p);
                if channels == 3 {
                    o[3] = 255;
                }
            }
        }
        (format, model, scheme) => return Err(unsupported(format, model, scheme)),
    }
    Ok(())
}

fn unsupported(
    format: Option<Format>,
    model: Option<ColorModel>,
    scheme: Option<SupercompressionScheme>,
) -> Ktx2Error {
    let what = match (format, model) {
        (Some(f), _) => format!("{f:?}"),
        (None, Some(m)) => format!("{m:?}"),
        (None, None) => "undescribed".to_string(),
    };
    let how = scheme.map_or(String::new(), |s| format!(" ({s:?} supercompressed)"));
    Ktx2Error::Unsupported(format!("{what}{how}"))
}

/// Level 0's bytes, inflated when Zstandard-compressed: exactly `needed` bytes, the size the level
/// index declares (checked before anything is allocated, and against what the stream yields).
fn inflate(
    data: &[u8],
    declared: u64,
    scheme: Option<SupercompressionScheme>,
    needed: u64,
) -> Result<std::borrow::Cow<'_, [u8]>, Ktx2Error> {
    if declared != needed {
        return Err(Ktx2Error::LevelSize { declared, needed });
    }
    if scheme.is_none() {
        return if data.len() as u64 == needed {
            Ok(std::borrow::Cow::Borrowed(data))
        } else {
            Err(Ktx2Error::LevelSize {
                declared: data.len() as u64,
                needed,
            })
        };
    }
    let mut source = data;
    let decoder = ruzstd::decoding::StreamingDecoder::new(&mut source)
        .map_err(|e| Ktx2Error::Zstd(e.to_string()))?;
    let mut out = Vec::with_capacity(needed as usize);
    // One byte more than needed shows a stream that runs on.
    decoder
        .take(needed + 1)
        .read_to_end(&mut out)
        .map_err(|e| Ktx2Error::Zstd(e.to_string()))?;
    if out.len() as u64 != needed {
        return Err(Ktx2Error::Zstd(format!(
            "inflates to {}{} bytes, not the {needed} its index declares",
            out.len(),
            if out.len() as u64 > needed {
                " or more"
            } else {
                ""
            }
        )));
    }
    Ok(std::borrow::Cow::Owned(out))
}

#[cfg(test)]
mod tests;
