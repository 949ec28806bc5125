//! The flags several commands share (one flattened `Args`, the lens and time groups) and the parsers
//! of their values; each group turns into the typed options of `render::job`.

use anyhow::{Context, Result};
use glam::Vec3;

use crate::accel::Backend;
use crate::film::aov::FeatureImages;
use crate::film::denoise::{DenoiseError, DenoiseOptions, DenoiseQuality, Denoiser, GuideMode};
use crate::film::filter::MAX_RADIUS;
use crate::film::{Display, Image, ViewTransform};
use crate::render::job::{DefaultLights, LensOptions, Overrides, Time};
use crate::scene::{GgxScattering, Layering, SceneChoice, UpAxis};

/// What `render` and `turntable` share: image size, sampling, backend, seed, lights, exposure,
/// threads. Those a scene file may set are `Option`s: given or not, the job decides (the command
/// line beats the file, the file beats the default shown).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Image width in pixels [default: 800]
    #[arg(long)]
    pub width: Option<usize>,
    /// Image height in pixels [default: 600]
    #[arg(long)]
    pub height: Option<usize>,
    /// Samples per pixel [default: 16]
    #[arg(long)]
    pub spp: Option<u32>,
    /// Bounces after the camera ray (1 = direct light only) [default: 5]
    #[arg(long)]
    pub max_depth: Option<u32>,
    #[cfg_attr(
        feature = "embree",
        doc = "Ray-tracing backend (obvhs only when built with that feature) [default: embree]"
    )]
    #[cfg_attr(
        not(feature = "embree"),
        doc = "Ray-tracing backend (obvhs only when built with that feature) [default: bvh]"
    )]
    #[arg(long, value_enum)]
    pub backend: Option<Backend>,
    /// Noise seed: the same seed gives the same image whatever --threads is (a turntable frame
    /// mixes in its index, so it is the same on any machine) [default: 0]
    #[arg(long)]
    pub seed: Option<u64>,
    /// Vertical field of view in degrees.
    #[arg(long, value_parser = finite)]
    pub fov: Option<f32>,
    /// Exposure in stops, applied to PNG output (the same on every frame of a sequence).
    #[arg(long, value_parser = finite, default_value_t = 0.0, allow_hyphen_values = true)]
    pub exposure: f32,
    /// View transform of PNG output and previews, after the exposure (EXR stays linear).
    #[arg(long, value_enum, default_value_t = ViewTransform::KhronosPbrNeutral)]
    pub view: ViewTransform,
    /// The default light rig (environment + key light), placed relative to the (frame-0) camera.
    #[arg(long, value_enum, default_value_t = DefaultLights::Auto)]
    pub default_lights: DefaultLights,
    /// Material variant to render (KHR_materials_variants; `glint info` lists a file's variants).
    #[arg(long, value_name = "NAME")]
    pub variant: Option<String>,
    /// The axis the model file calls up (z: scans and CAD exports); the scene is turned so that it
    /// points up in the image.
    #[arg(long, value_enum, default_value_t = UpAxis::Y)]
    pub model_up: UpAxis,
    /// Which scene of a glTF file that has several: its index or name (`glint info` lists them)
    /// [default: the file's default scene]
    #[arg(long, value_name = "N|NAME")]
    pub scene: Option<SceneChoice>,
    /// How the dielectric specular layer weights the diffuse under it: the glTF spec's fresnel_mix
    /// or Blender-style albedo scaling [default: spec]
    #[arg(long, value_enum)]
    pub layering: Option<Layering>,
    /// GGX scattering of the specular lobes: the glTF spec's single scattering, or multiple
    /// scattering's energy restored (Turquin 2019) [default: single]
    #[arg(long, value_enum)]
    pub ggx: Option<GgxScattering>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// No progress bar or summary.
    #[arg(short, long)]
    pub quiet: bool,
}

impl Args {
    /// The file-overridable settings these flags give.
    pub fn overrides(&self) -> Overrides {
        Overrides {
            width: self.width,
            height: self.height,
            spp: self.spp,
            max_depth: self.max_depth,
            seed: self.seed,
            backend: self.backend,
            layering: self.layering,
            ggx: self.ggx,
            ..Default::default()
        }
    }

    /// How PNG output shows the linear image.
    pub fn display(&self) -> Display {
        Display::new(self.exposure, self.view)
    }

    /// Sizes the global thread pool when `--threads` is given.
    pub fn set_threads(&self) -> Result<()> {
        if let Some(n) = self.threads {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n.max(1))
                .build_global()
                .context("setting up the thread pool")?;
        }
        Ok(())
    }
}

/// Denoising with Intel Open Image Denoise.
#[derive(clap::Args, Debug, Default)]
pub struct DenoiseArgs {
    /// Denoise the image (Open Image Denoise's RT filter, HDR, guided by albedo and normal images
    /// taken at the first non-specular surface: prefiltered below 64 spp, trusted from there, unless
    /// --denoise-guides says otherwise).
    #[arg(long)]
    pub denoise: bool,
    /// The denoiser's speed/quality trade.
    #[arg(long, value_enum, default_value_t = DenoiseQuality::High, requires = "denoise")]
    pub denoise_quality: DenoiseQuality,
    /// What the albedo and normal guides go through first.
    #[arg(long, value_enum, default_value_t = GuideMode::default(), requires = "denoise")]
    pub denoise_guides: GuideMode,
}

impl DenoiseArgs {
    /// The denoiser when asked for (on `threads` threads, default all), or an error naming why
    /// there is none.
    pub fn denoiser(&self, threads: Option<usize>) -> Result<Option<Denoiser>> {
        if !self.denoise {
            return Ok(None);
        }
        let d = Denoiser::new(threads.unwrap_or(0), self.options()).context("--denoise")?;
        Ok(Some(d))
    }

    /// How to denoise, as the flags say.
    fn options(&self) -> DenoiseOptions {
        DenoiseOptions {
            quality: self.denoise_quality,
            guides: self.denoise_guides,
            ..DenoiseOptions::default()
        }
    }

    /// How to denoise, if asked.
    pub fn asked(&self) -> Option<DenoiseOptions> {
        self.denoise.then(|| self.options())
    }

    /// Fails when denoising is asked of a build without the denoiser.
    pub fn check(&self) -> Result<()> {
        if self.denoise && !Denoiser::AVAILABLE {
            return Err(DenoiseError::NotBuilt).context("--denoise");
        }
        Ok(())
    }

    /// The denoised image and the seconds it took.
    pub fn run(
        d: &Denoiser,
        image: &Image,
        features: Option<&FeatureImages>,
    ) -> Result<(Image, f64)> {
        let t = std::time::Instant::now();
        let out = d.denoise(image, features.map(FeatureImages::guides))?;
        Ok((out, t.elapsed().as_secs_f64()))
    }
}

/// Depth of field: a thin lens, by aperture radius or f-number, focused at a distance or on a pixel.
#[derive(clap::Args, Debug, Default)]
pub struct LensArgs {
    /// Lens aperture radius in scene units (a thin lens; 0 or absent = pinhole).
    #[arg(long, value_parser = finite, conflicts_with = "fstop")]
    pub aperture: Option<f32>,
    /// Lens f-number; the focal length comes from the vertical field of view on a 24 mm (full-frame)
    /// sensor with scene units in metres: f = 12 mm / tan(fov / 2), aperture radius f / (2 N).
    #[arg(long, value_parser = finite)]
    pub fstop: Option<f32>,
    /// Distance of the plane in focus, along the view axis (default: the model's centre).
    #[arg(long, value_parser = finite, conflicts_with = "focus_on")]
    pub focus_distance: Option<f32>,
    /// Focus on what pixel X,Y sees (its depth along the view axis).
    #[arg(long, value_parser = parse_pixel)]
    pub focus_on: Option<[u32; 2]>,
}

impl LensArgs {
    pub fn options(&self) -> LensOptions {
        LensOptions {
            aperture: self.aperture,
            fstop: self.fstop,
            focus_distance: self.focus_distance,
            focus_on: self.focus_on,
        }
    }
}

/// Motion blur and animation time.
#[derive(clap::Args, Debug, Default)]
pub struct TimeArgs {
    /// Shutter interval OPEN,CLOSE in seconds relative to --frame-time (e.g. 0,0.033); equal values
    /// mean no motion blur.
    #[arg(long, value_parser = parse_shutter, allow_hyphen_values = true)]
    pub shutter: Option<[f32; 2]>,
    /// Seconds into the file's animation at which the frame is taken.
    #[arg(long, value_parser = finite, default_value_t = 0.0, allow_hyphen_values = true)]
    pub frame_time: f32,
    /// Which of the file's animations plays, by index (default: the first).
    #[arg(long, default_value_t = 0)]
    pub animation: usize,
}

impl TimeArgs {
    pub fn options(&self) -> Time {
        Time {
            animation: self.animation,
            frame_time: self.frame_time,
            shutter: self.shutter.unwrap_or([0.0, 0.0]),
        }
    }
}

/// Parses a finite number: NaN or an infinity in a numeric flag would run on into a black or empty
/// image rather than an error.
pub fn finite(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("'{s}': expected a finite number")),
        Err(e) => Err(format!("'{s}': {e}")),
    }
}

/// Parses a reconstruction filter's radius in pixels: above 0 and at most `MAX_RADIUS`.
pub fn filter_radius(s: &str) -> Result<f32, String> {
    match finite(s)? {
        r if r > 0.0 && r <= MAX_RADIUS => Ok(r),
        _ => Err(format!(
            "'{s}': expected a radius in pixels above 0 and at most {MAX_RADIUS}"
        )),
    }
}

/// Parses `s` as numbers separated by commas (`what` names the expected form in the error).
fn numbers<T: std::str::FromStr>(s: &str, what: &str) -> Result<Vec<T>, String>
where
    T::Err: std::fmt::Display,
{
    s.split(',')
        .map(|c| c.trim().parse::<T>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("'{s}': {e} (expected {what})"))
}

pub fn parse_pixel(s: &str) -> Result<[u32; 2], String> {
    match numbers::<u32>(s, "X,Y").as_deref() {
        Ok(&[x, y]) => Ok([x, y]),
        _ => Err(format!(
            "'{s}': expected a pixel X,Y (two non-negative integers)"
        )),
    }
}

pub fn parse_shutter(s: &str) -> Result<[f32; 2], String> {
    match numbers::<f32>(s, "OPEN,CLOSE in seconds")?[..] {
        [a, b] if a.is_finite() && b.is_finite() && a <= b => Ok([a, b]),
        _ => Err(format!(
            "'{s}': expected OPEN,CLOSE in seconds with OPEN <= CLOSE"
        )),
    }
}

pub fn parse_vec3(s: &str) -> Result<Vec3, String> {
    match numbers::<f32>(s, "x,y,z")?[..] {
        [x, y, z] if x.is_finite() && y.is_finite() && z.is_finite() => Ok(Vec3::new(x, y, z)),
        _ => Err(format!("'{s}': expected three finite numbers x,y,z")),
    }
}

/// A duration such as `30s`, `1.5m`, `500ms` or `20` (seconds).
pub fn parse_duration(s: &str) -> Result<std::time::Duration, String> {
    let t = s.trim();
    let (num, scale) = if let Some(n) = t.strip_suffix("ms") {
        (n, 1e-3)
    } else if let Some(n) = t.strip_suffix('s') {
        (n, 1.0)
    } else if let Some(n) = t.strip_suffix('m') {
        (n, 60.0)
    } else if let Some(n) = t.strip_suffix('h') {
        (n, 3600.0)
    } else {
        (t, 1.0)
    };
    match num.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(std::time::Duration::from_secs_f64(v * scale)),
        _ => Err(format!(
            "'{s}': expected a positive duration such as 30s, 2m or 500ms"
        )),
    }
}
