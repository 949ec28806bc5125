//! Feature images (AOVs) and how they are written: channels of the one multi-layer EXR, or PNG files
//! beside the output (`out.albedo.png`, after the `out.spp.png` pattern), each in its own encoding.

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::layers::{write_layers, Layer, Values};
use super::{write_png_bytes, write_with, Display, FilmError, Format, Image, ViewTransform};
use crate::geometry::hash::mix64;

/// Id of pixels whose camera rays hit nothing.
pub const NO_ID: u32 = u32::MAX;

/// What a render can write besides its beauty image.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, clap::ValueEnum)]
pub enum Aov {
    /// Base colour at the first non-specular surface (what the denoiser is guided by).
    Albedo,
    /// Shading normal there, world space, unit length.
    Normal,
    /// Distance along the camera's view axis to the camera ray's hit.
    Depth,
    /// World-space position of the camera ray's hit.
    Position,
    /// Instance id of the camera ray's hit (the sample nearest the pixel centre).
    Instance,
    /// Material id (index in the file's materials) of the camera ray's hit.
    Material,
    /// Variance of the pixel's estimate, per channel.
    Variance,
    /// Samples the pixel took.
    Spp,
    /// The beauty before denoising (with --denoise).
    BeautyRaw,
}

impl Aov {
    /// The name in file names (`out.NAME.png`) and the EXR layer name.
    pub fn file_name(self) -> &'static str {
        match self {
            Aov::Albedo => "albedo",
            Aov::Normal => "normal",
            Aov::Depth => "depth",
            Aov::Position => "position",
            Aov::Instance => "instance",
            Aov::Material => "material",
            Aov::Variance => "variance",
            Aov::Spp => "spp",
            Aov::BeautyRaw => "beauty-raw",
        }
    }

    /// Whether the render must accumulate feature images for it.
    pub fn needs_features(self) -> bool {
        !matches!(self, Aov::Spp | Aov::BeautyRaw)
    }
}

/// Feature images, row-major, one value per pixel.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FeatureImages {
    pub width: usize,
    pub height: usize,
    pub albedo: Vec<Vec3>,
    /// Unit shading normals (world space, facing the camera), zero where nothing was hit.
    pub normal: Vec<Vec3>,
    /// Distance along the view axis; infinite where nothing was hit.
    pub depth: Vec<f32>,
    /// World-space position; zero where nothing was hit.
    pub position: Vec<Vec3>,
    pub instance: Vec<u32>,
    pub material: Vec<u32>,
    pub variance: Vec<Vec3>,
    /// The fewest samples any pixel's features average.
    pub min_spp: u32,
}

impl FeatureImages {
    /// What the denoiser is guided by.
    pub fn guides(&self) -> super::denoise::Guides<'_> {
        super::denoise::Guides {
            albedo: &self.albedo,
            normal: &self.normal,
            samples: self.min_spp,
        }
    }
}

/// Everything a render can write: the beauty (denoised or not) and what the AOVs are made from.
#[derive(Clone, Copy, Debug)]
pub struct Outputs<'a> {
    pub beauty: &'a Image,
    /// The beauty before denoising, when it was denoised.
    pub raw: Option<&'a Image>,
    pub features: Option<&'a FeatureImages>,
    pub spp: &'a [u32],
}

/// `out.exr` -> `out.spp.exr`: an AOV's file beside the output, in the output's format.
pub fn aov_path(output: &Path, aov: &str) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    let ext = output.extension().unwrap_or_default().to_string_lossy();
    output.with_file_name(format!("{stem}.{aov}.{ext}"))
}

impl Outputs<'_> {
    fn features(&self, aov: Aov) -> Result<&FeatureImages, FilmError> {
        self.features.ok_or(FilmError::MissingAov(aov.file_name()))
    }

    /// The EXR layer of `aov` (channel names as compositors group them).
    fn layer(&self, aov: Aov) -> Result<Layer<'_>, FilmError> {
        let (name, values) = match aov {
            Aov::Albedo => ("albedo", Values::Rgb(&self.features(aov)?.albedo)),
            Aov::Normal => ("N", Values::Xyz(&self.features(aov)?.normal)),
            Aov::Depth => ("Z", Values::Scalar(&self.features(aov)?.depth)),
            Aov::Position => ("P", Values::Xyz(&self.features(aov)?.position)),
            Aov::Instance => ("instance.id", Values::Uint(&self.features(aov)?.instance)),
            Aov::Material => ("material.id", Values::Uint(&self.features(aov)?.material)),
            Aov::Variance => ("variance", Values::Rgb(&self.features(aov)?.variance)),
            Aov::Spp => ("spp.count", Values::Uint(self.spp)),
            Aov::BeautyRaw => {
                let raw = self.raw.ok_or(FilmError::MissingAov(aov.file_name()))?;
                ("raw", Values::Rgba(&raw.pixels))
            }
        };
        Ok(Layer { name, values })
    }

    /// Writes the beauty to `path` and the AOVs: as layers of the same file for .exr, as files
    /// beside it for .png. Without AOVs the file is what `film::write_with` writes.
    pub fn write(&self, aovs: &[Aov], path: &Path, display: &Display) -> Result<(), FilmError> {
        if aovs.is_empty() {
            return write_with(self.beauty, path, display);
        }
        if Format::from_path(path)? == Format::Exr {
            let layers = aovs
                .iter()
                .map(|&a| self.layer(a))
                .collect::<Result<Vec<_>, _>>()?;
            return write_layers(self.beauty, &layers, path);
        }
        write_with(self.beauty, path, display)?;
        for &a in aovs {
            self.write_png(a, &aov_path(path, a.file_name()), display)?;
        }
        Ok(())
    }

    /// One AOV as an 8-bit PNG: colours through the display (albedo, raw beauty, variance as a
    /// standard deviation, sample counts over the most), data as plain bytes (normals as n / 2 +
    /// 1/2, depth and position scaled to the range hit, ids in hashed colours; black where nothing was hit).
    fn write_png(&self, aov: Aov, path: &Path, display: &Display) -> Result<(), FilmError> {
        let (w, h) = (self.beauty.width, self.beauty.height);
        let plain = Display::new(0.0, ViewTransform::Standard);
        let colour = |v: &[Vec3], d: &Display| {
            let img = Image {
                width: w,
                height: h,
                pixels: v.iter().map(|c| c.extend(1.0)).collect(),
            };
            write_with(&img, path, d)
        };
        match aov {
            Aov::BeautyRaw => write_with(
                self.raw.ok_or(FilmError::MissingAov("beauty-raw"))?,
                path,
                display,
            ),
            Aov::Albedo => colour(&self.features(aov)?.albedo, &plain),
            Aov::Variance => {
                let sd: Vec<Vec3> = self
                    .features(aov)?
                    .variance
                    .iter()
                    .map(|v| Vec3::from_array(v.to_array().map(|c| c.max(0.0).sqrt())))
                    .collect();
                colour(&sd, display)
            }
            Aov::Spp => {
                let most = self.spp.iter().copied().max().unwrap_or(0).max(1) as f32;
                let v: Vec<f32> = self.spp.iter().map(|&n| n as f32 / most).collect();
                write_with(&Image::from_scalars(w, h, &v), path, &plain)
            }
            _ => write_png_bytes(path, w, h, &data_bytes(aov, self.features(aov)?)),
        }
    }
}

/// The 8-bit RGB encoding of a data AOV (normal, depth, position, ids).
fn data_bytes(aov: Aov, f: &FeatureImages) -> Vec<u8> {
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    let rgb = |c: Vec3| [byte(c.x), byte(c.y), byte(c.z)];
    let px: Vec<[u8; 3]> = match aov {
        Aov::Normal => f
            .normal
            .iter()
            .map(|&n| {
                if n == Vec3::ZERO {
                    [0; 3]
                } else {
                    rgb(n * 0.5 + 0.5)
                }
            })
            .collect(),
        Aov::Depth => {
            let far = f
                .depth
                .iter()
                .copied()
                .filter(|z| z.is_finite())
                .fold(0.0f32, f32::max)
                .max(1e-12);
            f.depth
                .iter()
                .map(|&z| {
                    if z.is_finite() {
                        [byte(z / far); 3]
                    } else {
                        [0; 3]
                    }
                })
                .collect()
        }
        Aov::Position => {
            let hit = |i: usize| f.depth[i].is_finite();
            let pts = || {
                f.position
                    .iter()
                    .enumerate()
                    .filter(|(i, _)| hit(*i))
                    .map(|(_, p)| *p)
            };
            let lo = pts().fold(Vec3::INFINITY, Vec3::min);
            let size = (pts().fold(Vec3::NEG_INFINITY, Vec3::max) - lo).max(Vec3::splat(1e-12));
            f.position
                .iter()
                .enumerate()
                .map(|(i, &p)| if hit(i) { rgb((p - lo) / size) } else { [0; 3] })
                .collect()
        }
        _ => {
            let ids = if aov == Aov::Instance {
                &f.instance
            } else {
                &f.material
            };
            ids.iter()
                .map(|&id| {
                    if id == NO_ID {
                        [0; 3]
                    } else {
                        hashed_colour(id)
                    }
                })
                .collect()
        }
    };
    px.concat()
}

/// A bright, well-spread colour for an id (neighbouring ids look different).
fn hashed_colour(id: u32) -> [u8; 3] {
    let h = mix64(id as u64 + 1);
    [0, 8, 16].map(|s| 64 + ((h >> s) & 0xff) as u8 % 192)
}
