//! The film: a linear RGBA float image that the integrator fills, and its output as PNG or EXR.
//! Files are written to a temporary name beside the target and renamed, so no half image is ever left.

pub mod aov;
pub mod denoise;
pub mod filter;
pub mod layers;
pub mod shard;
pub mod view;

use std::fs;
use std::path::{Path, PathBuf};

use glam::Vec4;

pub use view::{Display, ViewTransform};

#[derive(Debug, thiserror::Error)]
pub enum FilmError {
    #[error("{}: unsupported output type (expected .png or .exr)", .0.display())]
    UnsupportedFormat(PathBuf),
    #[error("writing {}", path.display())]
    Write {
        path: PathBuf,
        #[source]
        source: EncodeError,
    },
    #[error("renaming into {}", path.display())]
    Rename {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("the {0} image was asked for but not rendered")]
    MissingAov(&'static str),
    #[error("{}: {error}", path.display())]
    ReadExr {
        path: PathBuf,
        error: exr::error::Error,
    },
}

/// Why an image could not be encoded into its file.
#[derive(Debug, thiserror::Error)]
pub enum EncodeError {
    #[error(transparent)]
    Png(#[from] image::ImageError),
    #[error("{0}")]
    Exr(exr::error::Error),
}

/// A linear-light RGBA image, row-major, first row at the top.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Image {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<Vec4>,
}

impl Image {
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            pixels: vec![Vec4::ZERO; width * height],
        }
    }

    pub fn get(&self, x: usize, y: usize) -> Vec4 {
        self.pixels[y * self.width + x]
    }

    /// Mean of the RGB channels over all pixels.
    pub fn mean_rgb(&self) -> f64 {
        let s: f64 = self
            .pixels
            .iter()
            .map(|p| (p.x + p.y + p.z) as f64 / 3.0)
            .sum();
        s / self.pixels.len().max(1) as f64
    }

    /// Mean absolute difference of RGB with another image of the same size.
    pub fn mean_abs_diff(&self, other: &Image) -> f64 {
        assert_eq!((self.width, self.height), (other.width, other.height));
        let s: f64 = self
            .pixels
            .iter()
            .zip(&other.pixels)
            .map(|(a, b)| ((*a - *b).truncate().abs().element_sum() / 3.0) as f64)
            .sum();
        s / self.pixels.len().max(1) as f64
    }

    pub fn has_non_finite(&self) -> bool {
        self.pixels.iter().any(|p| !p.is_finite())
    }

    /// Root mean squared error of RGB against a reference of the same size.
    pub fn rmse(&self, reference: &Image) -> f64 {
        assert_eq!(
            (self.width, self.height),
            (reference.width, reference.height)
        );
        let s: f64 = self
            .pixels
            .iter()
            .zip(&reference.pixels)
            .map(|(a, b)| {
                let d = (*a - *b).truncate().as_dvec3();
                d.length_squared()
            })
            .sum();
        (s / (3 * self.pixels.len().max(1)) as f64).sqrt()
    }

    /// pbrt's relative MSE of RGB: mean of (x - ref)^2 / (ref^2 + 0.01).
    pub fn rel_mse(&self, reference: &Image) -> f64 {
        assert_eq!(
            (self.width, self.height),
            (reference.width, reference.height)
        );
        let mut s = 0.0f64;
        for (a, b) in self.pixels.iter().zip(&reference.pixels) {
            for c in 0..3 {
                let (x, r) = (a[c] as f64, b[c] as f64);
                s += (x - r) * (x - r) / (r * r + 0.01);
            }
        }
        s / (3 * self.pixels.len().max(1)) as f64
    }

    /// A grey image of per-pixel values (e.g. sample counts), for writing as an AOV.
    pub fn from_scalars(width: usize, height: usize, values: &[f32]) -> Image {
        assert_eq!(values.len(), width * height);
        Image {
            width,
            height,
            pixels: values.iter().map(|&v| Vec4::new(v, v, v, 1.0)).collect(),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Png,
    Exr,
}

impl Format {
    pub fn from_path(path: &Path) -> Result<Self, FilmError> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .as_deref()
        {
            Some("png") => Ok(Format::Png),
            Some("exr") => Ok(Format::Exr),
            _ => Err(FilmError::UnsupportedFormat(path.to_path_buf())),
        }
    }
}

/// Writes the image (format from the extension) through a temporary file and an atomic rename; a
/// PNG is shown with `exposure` stops through the default view transform.
pub fn write(image: &Image, path: &Path, exposure: f32) -> Result<(), FilmError> {
    write_with(
        image,
        path,
        &Display::new(exposure, ViewTransform::default()),
    )
}

/// `write`, a PNG shown as `display` says (an EXR is linear and ignores it).
pub fn write_with(image: &Image, path: &Path, display: &Display) -> Result<(), FilmError> {
    let format = Format::from_path(path)?;
    write_through_temp(path, |tmp| match format {
        Format::Png => write_png(image, tmp, display),
        Format::Exr => write_exr(image, tmp),
    })
}

/// Encodes into a temporary file beside `path` and renames it into place, so a failed or killed
/// write never leaves a partial file under the final name.
pub(crate) fn write_through_temp(
    path: &Path,
    encode: impl FnOnce(&Path) -> Result<(), EncodeError>,
) -> Result<(), FilmError> {
    let tmp = temp_path(path);
    if let Err(source) = encode(&tmp) {
        let _ = fs::remove_file(&tmp);
        return Err(FilmError::Write {
            path: path.to_path_buf(),
            source,
        });
    }
    fs::rename(&tmp, path).map_err(|source| FilmError::Rename {
        path: path.to_path_buf(),
        source,
    })
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    // Keep the extension last so format-sniffing encoders see the right type.
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Removes the temporary files that killed writes left in `dir` (see `write_through_temp`): those of
/// a final name `ours` accepts whose writing process is gone. A live process's file is left to it, so
/// that a run resuming beside another (an overlapping shard) never pulls a file from under it.
/// Returns how many were removed.
pub fn remove_stale_temps(dir: &Path, ours: impl Fn(&str) -> bool) -> usize {
    let dir = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    let Ok(entries) = fs::read_dir(dir) else {
        return 0;
    };
    entries
        .flatten()
        .filter(|e| {
            let name = e.file_name();
            let Some((target, pid)) = name.to_str().and_then(parse_temp_name) else {
                return false;
            };
            ours(target) && !process_alive(pid) && fs::remove_file(e.path()).is_ok()
        })
        .count()
}

/// The final name and writer's process id of a temporary file name `.{name}.{pid}.tmp`.
fn parse_temp_name(file: &str) -> Option<(&str, u32)> {
    let rest = file.strip_prefix('.')?.strip_suffix(".tmp")?;
    let (name, pid) = rest.rsplit_once('.')?;
    Some((name, pid.parse().ok()?))
}

/// Whether process `pid` runs; without /proc nothing can be told and it counts as running.
fn process_alive(pid: u32) -> bool {
    let proc = Path::new("/proc");
    !proc.join("self").exists() || proc.join(pid.to_string()).exists()
}

fn write_png(image: &Image, path: &Path, display: &Display) -> Result<(), EncodeError> {
    // Opaque RGB: the background is what the camera sees there (alpha is kept in EXR).
    let mut buf = Vec::with_capacity(image.width * image.height * 3);
    for p in &image.pixels {
        buf.extend_from_slice(&display.encode(p.truncate()));
    }
    image::save_buffer_with_format(
        path,
        &buf,
        image.width as u32,
        image.height as u32,
        image::ColorType::Rgb8,
        image::ImageFormat::Png,
    )?;
    Ok(())
}

/// Writes 8-bit RGB bytes (data, no tone curve) as a PNG, through a temporary file.
pub(crate) fn write_png_bytes(
    path: &Path,
    w: usize,
    h: usize,
    rgb: &[u8],
) -> Result<(), FilmError> {
    write_through_temp(path, |tmp| {
        image::save_buffer_with_format(
            tmp,
            rgb,
            w as u32,
            h as u32,
            image::ColorType::Rgb8,
            image::ImageFormat::Png,
        )?;
        Ok(())
    })
}

fn write_exr(image: &Image, path: &Path) -> Result<(), EncodeError> {
    use exr::prelude::{SpecificChannels, Vec2, WritableImage};
    let w = image.width;
    let channels = SpecificChannels::rgba(|Vec2(x, y)| {
        let p: Vec4 = image.pixels[y * w + x];
        (p.x, p.y, p.z, p.w)
    });
    // Compressed blocks in file order, not in the order threads finish them: the same image gives
    // the same bytes (sharded frames and merged stills are compared byte for byte).
    exr::prelude::Image::from_channels((image.width, image.height), channels)
        .write()
        .non_parallel()
        .to_file(path)
        .map_err(EncodeError::Exr)
}

/// Reads an EXR written by `write` back into linear RGBA (for tests and reference images).
pub fn read_exr(path: &Path) -> Result<Image, FilmError> {
    use exr::prelude::{read_first_rgba_layer_from_file, Vec2};
    let img = read_first_rgba_layer_from_file(
        path,
        |res, _| {
            let (w, h) = (res.width(), res.height());
            (w, vec![glam::Vec4::ZERO; w * h])
        },
        |(w, px), Vec2(x, y), (r, g, b, a): (f32, f32, f32, f32)| {
            px[y * *w + x] = glam::Vec4::new(r, g, b, a)
        },
    )
    .map_err(|error| FilmError::ReadExr {
        path: path.to_path_buf(),
        error,
    })?;
    let size = img.layer_data.size;
    Ok(Image {
        width: size.width(),
        height: size.height(),
        pixels: img.layer_data.channel_data.pixels.1,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stale_temps_of_our_names_go_and_live_or_other_ones_stay() {
        let dir = tempfile::tempdir().unwrap();
        // Beyond any pid_max (4194304): no such process.
        let dead = 4_000_000_000u32;
        let live = std::process::id();
        let names = [
            format!(".a.png.{dead}.tmp"),
            format!(".a.png.{live}.tmp"),
            format!(".b.png.{dead}.tmp"),
            format!("a.png.{dead}.tmp"),
        ];
        for n in &names {
            fs::write(dir.path().join(n), b"partial").unwrap();
        }
        assert_eq!(remove_stale_temps(dir.path(), |n| n == "a.png"), 1);
        assert!(!dir.path().join(&names[0]).exists());
        for n in &names[1..] {
            assert!(dir.path().join(n).exists(), "{n}");
        }
        assert_eq!(parse_temp_name(".x.y.exr.12.tmp"), Some(("x.y.exr", 12)));
        assert_eq!(parse_temp_name(".x.exr.tmp"), None);
    }

    #[test]
    fn exr_round_trip_is_exact_and_png_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let mut img = Image::new(3, 2);
        for (i, p) in img.pixels.iter_mut().enumerate() {
            *p = Vec4::new(i as f32 * 0.5, 1e-3, 100.0, 1.0);
        }
        let exr = dir.path().join("a.exr");
        write(&img, &exr, 0.0).unwrap();
        assert_eq!(read_exr(&exr).unwrap(), img);
        let png = dir.path().join("a.png");
        write(&img, &png, 0.0).unwrap();
        let back = image::open(&png).unwrap().to_rgba8();
        assert_eq!(back.dimensions(), (3, 2));
        // Only the two outputs: no temporary left behind.
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 2);
    }

    #[test]
    fn unknown_extension_is_an_error_and_writes_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let err = write(&Image::new(1, 1), &dir.path().join("a.bmp"), 0.0).unwrap_err();
        assert!(err.to_string().contains("a.bmp"));
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
