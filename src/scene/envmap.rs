//! Environment maps: a latitude-longitude (equirectangular) image of linear RGB radiance around the
//! scene, loaded from OpenEXR or Radiance HDR, and looked up by world direction.
//!
//! Orientation (+Y up, as glTF, and as the Khronos glTF Sample Viewer and three.js read panoramas):
//! the top row is straight up (+Y), the bottom row straight down; along a row the azimuth
//! `phi = atan2(d.z, d.x)` runs from -pi at the left edge through +X at the centre column to +pi at the
//! right edge (so a quarter of the width right of the centre is +Z, a quarter left of it is -Z).
//! `rotation` turns the map about +Y (or any rotation, e.g. from a turntable) before that lookup.

use std::f32::consts::PI;
use std::io::Cursor;
use std::path::Path;
use std::sync::Arc;

use glam::{Mat3, Vec2, Vec3};

use super::texture::wrap_index;
use super::LoadError;
use crate::geometry::inverse_trig;

/// A lat-long radiance map. Cloning is cheap: the pixels are shared.
#[derive(Clone, Debug)]
pub struct EnvMap {
    pub width: usize,
    pub height: usize,
    /// Row-major linear RGB, top row first.
    pub pixels: Arc<Vec<Vec3>>,
    /// Map space to world space (a rotation).
    pub rotation: Mat3,
}

impl PartialEq for EnvMap {
    fn eq(&self, other: &Self) -> bool {
        self.width == other.width
            && self.height == other.height
            && self.rotation == other.rotation
            && (Arc::ptr_eq(&self.pixels, &other.pixels) || self.pixels == other.pixels)
    }
}

impl EnvMap {
    /// A map from pixels (row-major, top row first); `None` when the size and the pixel count differ
    /// or the map is empty.
    pub fn new(width: usize, height: usize, pixels: Vec<Vec3>) -> Option<Self> {
        (width > 0 && height > 0 && pixels.len() == width * height).then(|| Self {
            width,
            height,
            pixels: Arc::new(pixels),
            rotation: Mat3::IDENTITY,
        })
    }

    /// A map of one colour (for tests: it must render like a constant environment).
    pub fn constant(width: usize, height: usize, value: Vec3) -> Self {
        Self::new(width, height, vec![value; width * height]).expect("non-empty")
    }

    /// Loads a .exr or .hdr file; errors name the file and the problem. Non-finite or negative
    /// values are clamped to zero, since one of them would poison every pixel that sees it.
    pub fn load(path: &Path) -> Result<Self, LoadError> {
        let err = |e: EnvMapError| LoadError::new(path, e.to_string());
        format_of(path).map_err(err)?;
        let bytes = std::fs::read(path).map_err(|e| err(EnvMapError::Open(e)))?;
        Self::from_bytes(path, &bytes)
    }

    /// Reads a .exr or .hdr file whose bytes are in hand; `path` names it (and its extension the
    /// format). The image size is checked against the pixel cap before its pixels are allocated.
    pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<Self, LoadError> {
        let err = |e: EnvMapError| LoadError::new(path, e.to_string());
        let (w, h, mut px) = match format_of(path).map_err(err)? {
            Format::Exr => read_exr(bytes).map_err(err)?,
            Format::Hdr => read_hdr(bytes).map_err(err)?,
        };
        for p in &mut px {
            *p = Vec3::from_array(
                p.to_array()
                    .map(|c| if c.is_finite() { c.max(0.0) } else { 0.0 }),
            );
        }
        Self::new(w, h, px).ok_or_else(|| err(EnvMapError::Empty))
    }

    /// The map turned by `angle` radians about +Y (counter-clockwise seen from above).
    pub fn rotated_y(mut self, angle: f32) -> Self {
        self.rotation = Mat3::from_rotation_y(angle) * self.rotation;
        self
    }

    /// Lat-long coordinates in [0,1)^2 of a world direction (u across, v down from the top).
    #[inline(always)]
    pub fn direction_to_uv(&self, d: Vec3) -> Vec2 {
        let m = self.rotation.transpose() * d;
        let theta = inverse_trig::acos(m.y);
        let phi = inverse_trig::atan2(m.z, m.x);
        Vec2::new(0.5 + phi / (2.0 * PI), theta / PI)
    }

    /// The world direction at lat-long coordinates `uv`, and `sin(theta)` there (the solid-angle
    /// Jacobian's factor).
    pub fn uv_to_direction(&self, uv: Vec2) -> (Vec3, f32) {
        let theta = uv.y * PI;
        let phi = (uv.x - 0.5) * 2.0 * PI;
        let (st, ct) = theta.sin_cos();
        let (sp, cp) = phi.sin_cos();
        (self.rotation * Vec3::new(st * cp, ct, st * sp), st)
    }

    /// The pixel (column, row) holding `uv`.
    #[inline(always)]
    pub fn pixel_of(&self, uv: Vec2) -> (usize, usize) {
        // u wraps around.
        let x = wrap_index((uv.x * self.width as f32) as i64, self.width as i64) as usize;
        let y = ((uv.y * self.height as f32) as usize).min(self.height - 1);
        (x, y)
    }

    /// Radiance arriving from world direction `d` (nearest pixel: piecewise constant, which is what
    /// the importance sampling's pdf assumes).
    #[inline(always)]
    pub fn lookup(&self, d: Vec3) -> Vec3 {
        self.at_uv(self.direction_to_uv(d))
    }

    /// The radiance of the pixel holding lat-long coordinates `uv` (for callers that have them).
    #[inline(always)]
    pub fn at_uv(&self, uv: Vec2) -> Vec3 {
        let (x, y) = self.pixel_of(uv);
        self.pixels[y * self.width + x]
    }
}

/// The two formats an environment map may have.
enum Format {
    Exr,
    Hdr,
}

fn format_of(path: &Path) -> Result<Format, EnvMapError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("exr") => Ok(Format::Exr),
        Some("hdr") => Ok(Format::Hdr),
        _ => Err(EnvMapError::Format),
    }
}

/// Why an environment map cannot be read.
#[derive(Debug, thiserror::Error)]
enum EnvMapError {
    #[error("environment maps must be .exr or .hdr (lat-long, linear RGB)")]
    Format,
    #[error("the image is empty")]
    Empty,
    #[error("reading OpenEXR: {0}")]
    Exr(exr::error::Error),
    #[error("{0}")]
    Open(std::io::Error),
    #[error("reading Radiance HDR: {0}")]
    Hdr(image::ImageError),
    #[error(transparent)]
    Size(#[from] super::decode::DecodeError),
    #[error("tiles of {} x {} pixels in an image of {} x {}", tile.0, tile.1, image.0, image.1)]
    Tiles {
        tile: (u64, u64),
        image: (usize, usize),
    },
    #[error(
        "the header declares {chunks} chunks, more than the {bytes} bytes of the file can index"
    )]
    Chunks { chunks: usize, bytes: usize },
    #[error("bands of {lines} lines in an image of {} x {}", image.0, image.1)]
    Bands { lines: u64, image: (usize, usize) },
    #[error(
        "a DWA block declares {declared} bytes, more than its {bound}-byte tile or band can hold"
    )]
    DwaCounter { declared: u64, bound: u64 },
}

/// The largest tile an EXR may use whatever its image's size (256 x 256: tiles larger than their
/// image only waste the decoder's memory).
const MAX_TILE_PIXELS: u64 = 1 << 16;

/// The largest band of lines an EXR may use whatever its image's size (256 lines of 8192 pixels).
const MAX_BAND_PIXELS: u64 = 1 << 21;

fn read_exr(bytes: &[u8]) -> Result<(usize, usize, Vec<Vec3>), EnvMapError> {
    use exr::prelude::{ReadChannels, ReadLayers, Vec2};
    // The header alone first: the reader below allocates the whole image from the size it declares.
    let meta = exr::meta::MetaData::read_from_buffered(Cursor::new(bytes), false)
        .map_err(EnvMapError::Exr)?;
    for header in &meta.headers {
        let size = header.layer_size;
        super::decode::check_size(size.width() as u64, size.height() as u64)?;
        // The reader allocates a whole tile or band of lines to read and decode into, whatever the
        // image's size.
        let image = size.area() as u64;
        match header.blocks {
            exr::meta::BlockDescription::Tiles(t) => {
                let (w, h) = (t.tile_size.width() as u64, t.tile_size.height() as u64);
                if w.saturating_mul(h) > image.max(MAX_TILE_PIXELS) {
                    return Err(EnvMapError::Tiles {
                        tile: (w, h),
                        image: (size.width(), size.height()),
                    });
                }
            }
            // A band keeps its full count of lines even past the image's last line (DWAB's 256
            // lines in an image of 4 x 820,000 pixels made 1.7 GB).
            exr::meta::BlockDescription::ScanLines => {
                let lines = header.compression.scan_lines_per_block() as u64;
                if lines.saturating_mul(size.width() as u64) > image.max(MAX_BAND_PIXELS) {
                    return Err(EnvMapError::Bands {
                        lines,
                        image: (size.width(), size.height()),
                    });
                }
            }
        }
    }
    // Each chunk (a tile or a band of lines, of every mip or rip level) has an 8-byte entry in the
    // offset tables the reader allocates up front: a file shorter than its tables declares chunks it
    // does not hold (tiles of 1 x 1 pixel in rip maps reach gigabytes from a header of 500 bytes).
    let chunks: usize = meta.headers.iter().map(|h| h.chunk_count).sum();
    if chunks.saturating_mul(8) > bytes.len() {
        return Err(EnvMapError::Chunks {
            chunks,
            bytes: bytes.len(),
        });
    }
    check_dwa_blocks(bytes, &meta)?;
    let img = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            // The pixels are allocated when the first block has decoded, not from the header: a
            // file of a few hundred bytes may declare 60 million pixels and hold none of them.
            |res, _| ((res.width(), res.height()), Vec::new()),
            |((w, h), px): &mut ((usize, usize), Vec<Vec3>),
             Vec2(x, y),
             (r, g, b, _a): (f32, f32, f32, f32)| {
                if px.is_empty() {
                    px.resize(*w * *h, Vec3::ZERO);
                }
                px[y * *w + x] = Vec3::new(r, g, b)
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(Cursor::new(bytes))
        .map_err(EnvMapError::Exr)?;
    let size = img.layer_data.size;
    Ok((
        size.width(),
        size.height(),
        img.layer_data.channel_data.pixels.1,
    ))
}

/// DWA blocks open with counters of their sections' sizes, from which the reader allocates before it
/// inflates anything (a 682-byte file reached 1 GB). A block decodes to at most its tile or band of
/// lines, padded to the 8 x 8 DCT blocks, so any counter above twice that (room for RLE's expansion)
/// or a compressed section longer than the block is refused before the real read.
fn check_dwa_blocks(bytes: &[u8], meta: &exr::meta::MetaData) -> Result<(), EnvMapError> {
    use exr::block::chunk::CompressedBlock;
    use exr::compression::Compression::{DWAA, DWAB};
    let dwa = |h: &exr::meta::header::Header| matches!(h.compression, DWAA(_) | DWAB(_));
    if !meta.headers.iter().any(dwa) {
        return Ok(());
    }
    let bounds: Vec<u64> = (meta.headers.iter())
        .map(|h| {
            let (w, lines) = match h.blocks {
                exr::meta::BlockDescription::Tiles(t) => {
                    (t.tile_size.width(), t.tile_size.height())
                }
                exr::meta::BlockDescription::ScanLines => {
                    (h.layer_size.width(), h.compression.scan_lines_per_block())
                }
            };
            let pad = |n: usize| (n as u64).div_ceil(8) * 8;
            2 * pad(w) * pad(lines) * h.channels.bytes_per_pixel as u64 + 4096
        })
        .collect();
    let chunks = exr::block::read(Cursor::new(bytes), false)
        .and_then(|r| r.all_chunks(false))
        .map_err(EnvMapError::Exr)?;
    for chunk in chunks {
        let chunk = chunk.map_err(EnvMapError::Exr)?;
        let (Some(h), Some(&bound)) = (
            meta.headers.get(chunk.layer_index),
            bounds.get(chunk.layer_index),
        ) else {
            continue;
        };
        let data = match &chunk.compressed_block {
            CompressedBlock::ScanLine(b) if dwa(h) => &b.compressed_pixels_le,
            CompressedBlock::Tile(b) if dwa(h) => &b.compressed_pixels_le,
            _ => continue,
        };
        // Version, then the section sizes and counts (a short block is the reader's error to give).
        let counter = |i: usize| {
            data.get(8 * i..8 * i + 8)
                .map(|b| u64::from_le_bytes(b.try_into().expect("eight bytes")))
        };
        for i in 1..10 {
            let Some(declared) = counter(i) else { break };
            // Counters 2 to 5 are compressed sizes, which the block itself must hold.
            let bound = if (2..=5).contains(&i) {
                data.len() as u64
            } else {
                bound
            };
            if declared > bound {
                return Err(EnvMapError::DwaCounter { declared, bound });
            }
        }
    }
    Ok(())
}

fn read_hdr(bytes: &[u8]) -> Result<(usize, usize, Vec<Vec3>), EnvMapError> {
    let decoder =
        image::codecs::hdr::HdrDecoder::new(Cursor::new(bytes)).map_err(EnvMapError::Hdr)?;
    let meta = decoder.metadata();
    super::decode::check_size(meta.width.into(), meta.height.into())?;
    let img = image::DynamicImage::from_decoder(decoder)
        .map_err(EnvMapError::Hdr)?
        .into_rgb32f();
    let (w, h) = (img.width() as usize, img.height() as usize);
    let px = img
        .pixels()
        .map(|p| Vec3::new(p.0[0], p.0[1], p.0[2]))
        .collect();
    Ok((w, h, px))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_and_coordinates_round_trip_with_the_documented_orientation() {
        let m = EnvMap::constant(8, 4, Vec3::ONE);
        let uv = |d: Vec3| m.direction_to_uv(d.normalize());
        assert!((uv(Vec3::Y).y).abs() < 1e-6);
        assert!((uv(-Vec3::Y).y - 1.0).abs() < 1e-6);
        assert!((uv(Vec3::X) - Vec2::new(0.5, 0.5)).length() < 1e-6);
        assert!((uv(Vec3::Z) - Vec2::new(0.75, 0.5)).length() < 1e-6);
        assert!((uv(-Vec3::Z) - Vec2::new(0.25, 0.5)).length() < 1e-6);
        let r = m.clone().rotated_y(0.7);
        for d in [Vec3::new(0.3, 0.5, -0.8), Vec3::new(-0.9, -0.2, 0.1)] {
            let d = d.normalize();
            for map in [&m, &r] {
                let (back, st) = map.uv_to_direction(map.direction_to_uv(d));
                assert!((back - d).length() < 1e-5, "{back} vs {d}");
                assert!((st - (1.0 - d.y * d.y).sqrt()).abs() < 1e-5);
            }
        }
        // Rotating the map by +90 degrees about Y carries what was at +X to -Z.
        let q = m.clone().rotated_y(std::f32::consts::FRAC_PI_2);
        assert!((q.direction_to_uv(-Vec3::Z) - Vec2::new(0.5, 0.5)).length() < 1e-5);
    }

    #[test]
    fn load_errors_name_the_file() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["sky.exr", "sky.hdr", "sky.png"] {
            let p = dir.path().join(name);
            std::fs::write(&p, b"not an image").unwrap();
            let e = EnvMap::load(&p).unwrap_err().to_string();
            assert!(e.contains(name), "{e}");
        }
        let e = EnvMap::load(&dir.path().join("missing.exr"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing.exr"), "{e}");
    }

    /// Fuzzers' files whose headers promise far more than the image holds, each refused before
    /// the reader allocates for it.
    #[test]
    fn exrs_whose_blocks_dwarf_their_image_are_refused_from_the_header() {
        let cases = [
            // 500 bytes: an 8 x 4 image in tiles of 64 x 27 million pixels, which the reader
            // allocated (1.8 GB) before it found the data missing.
            (
                "exr-tile-64x27m-in-8x4-image.exr",
                "tiles of 64 x 27262976 pixels in an image of 8 x 4",
            ),
            // 682 bytes: DWAB's bands of 256 lines in an image of 16 million x 4 pixels (within
            // the pixel cap), for which the reader reserved 1.7 GB a band.
            (
                "exr-dwab-256-line-bands-in-4-line-image.exr",
                "bands of 256 lines in an image of 16383994 x 4",
            ),
        ];
        for (file, expected) in cases {
            let path = Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("fuzz/regressions/envmap_load")
                .join(file);
            let bytes = std::fs::read(&path).unwrap();
            let e = EnvMap::from_bytes(&path, &bytes).unwrap_err().to_string();
            assert!(e.contains(expected), "{file}: {e}");
        }
    }

    #[test]
    fn a_dwa_block_whose_counters_outgrow_its_band_is_refused_before_the_read() {
        use exr::prelude::*;
        // A real DWAB file (one band of 16 x 16 pixels), then its block's "unknown" section
        // claims a terabyte: the reader would reserve that to inflate into.
        let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| (x as f32, y as f32, 0.5));
        let encoding = Encoding {
            compression: Compression::DWAB(None),
            blocks: Blocks::ScanLines,
            line_order: LineOrder::Increasing,
        };
        let mut file = Cursor::new(Vec::new());
        Image::from_encoded_channels((16, 16), encoding, channels)
            .write()
            .non_parallel()
            .to_buffered(&mut file)
            .unwrap();
        let mut bytes = file.into_inner();
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("dwab.exr");
        assert!(EnvMap::from_bytes(&p, &bytes).is_ok());
        // The offset table (one entry) is the 8 bytes before the first block, which opens with its
        // line (4 bytes), its size (4) and the DWA counters (version, then the unknown section's).
        let table = (0..bytes.len() - 8)
            .find(|&i| u64::from_le_bytes(bytes[i..i + 8].try_into().unwrap()) == i as u64 + 8)
            .expect("the offset table points just past itself");
        let counter = table + 8 + 8 + 8;
        bytes[counter..counter + 8].copy_from_slice(&(1u64 << 40).to_le_bytes());
        let e = EnvMap::from_bytes(&p, &bytes).unwrap_err().to_string();
        assert!(
            e.contains("a DWA block declares 1099511627776 bytes"),
            "{e}"
        );
    }

    #[test]
    fn an_exr_cut_inside_its_offset_tables_is_refused_before_the_read() {
        // glint writes EXRs in tiles of 64 x 64, so an 8192 x 256 image has 512 chunks and 4 KiB of
        // offset table: cut to 2000 bytes it declares chunks its bytes cannot index.
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("wide.exr");
        crate::film::write(&crate::film::Image::new(8192, 256), &p, 0.0).unwrap();
        let bytes = std::fs::read(&p).unwrap();
        let e = EnvMap::from_bytes(&p, &bytes[..2000])
            .unwrap_err()
            .to_string();
        assert!(e.contains("chunks, more than the 2000 bytes"), "{e}");
        assert!(EnvMap::from_bytes(&p, &bytes).is_ok());
    }

    #[test]
    fn exr_maps_load_with_rows_top_first() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("grad.exr");
        let mut img = crate::film::Image::new(4, 2);
        for (i, px) in img.pixels.iter_mut().enumerate() {
            *px = glam::Vec4::new(i as f32, 0.5, 2.0, 1.0);
        }
        crate::film::write(&img, &p, 0.0).unwrap();
        let m = EnvMap::load(&p).unwrap();
        assert_eq!((m.width, m.height), (4, 2));
        assert_eq!(m.lookup(Vec3::new(0.01, 1.0, 0.0).normalize()).x, 2.0);
        assert_eq!(m.lookup(-Vec3::Y).y, 0.5);
    }
}
