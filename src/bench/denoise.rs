//! `glint bench denoise`: what denoising one render costs, the colour alone and guided by albedo
//! and normal in each guide mode and network quality (best of N wall times, the device made once),
//! how far each result is from the guided all-high one, and, given one, from a converged reference.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use indicatif::ProgressBar;

use super::error::BenchError;
use super::input::Input;
use crate::film::denoise::{DenoiseOptions, DenoiseQuality, Denoiser, GuideMode};
use crate::film::{read_exr, Image};
use crate::render::job::{JobOptions, RenderJob};
use crate::render::RenderSettings;

/// One way of denoising.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Variant {
    pub quality: DenoiseQuality,
    /// None: the colour alone.
    pub guides: Option<GuideMode>,
    /// The guides' cleaning passes' quality (with `GuideMode::Prefiltered`).
    pub prefilter: DenoiseQuality,
}

impl Variant {
    fn options(&self) -> DenoiseOptions {
        DenoiseOptions {
            quality: self.quality,
            guides: self.guides.unwrap_or_default(),
            prefilter: self.prefilter,
        }
    }
}

/// The variants measured: the colour alone, then guided in each way (prefiltered at fast gives
/// balanced's image in balanced's time, so it is left out).
pub const VARIANTS: [Variant; 8] = {
    use DenoiseQuality::{Balanced, Fast, High};
    use GuideMode::{Noisy, Prefiltered, Trusted};
    const fn v(
        quality: DenoiseQuality,
        guides: Option<GuideMode>,
        prefilter: DenoiseQuality,
    ) -> Variant {
        Variant {
            quality,
            guides,
            prefilter,
        }
    }
    [
        v(High, None, High),
        v(High, Some(Prefiltered), High),
        v(High, Some(Prefiltered), Balanced),
        v(Balanced, Some(Prefiltered), Balanced),
        v(High, Some(Trusted), High),
        v(Balanced, Some(Trusted), High),
        v(High, Some(Noisy), High),
        v(Fast, Some(Noisy), High),
    ]
};

#[derive(Clone, Debug)]
pub struct Row {
    pub variant: Variant,
    pub seconds: f64,
    /// Mean absolute difference from the guided all-high prefiltered image, relative to its mean.
    pub difference: f64,
    /// relMSE against the converged reference, when one was given.
    pub rel_mse: Option<f64>,
}

/// What one run of the bench found.
#[derive(Clone, Debug)]
pub struct Report {
    pub settings: RenderSettings,
    pub threads: usize,
    /// relMSE of the raw render against the reference, when one was given.
    pub raw_rel_mse: Option<f64>,
    pub rows: Vec<Row>,
}

/// Renders the scene once with feature images, then denoises it `repeat` times per variant on a
/// device of `threads` threads (0: all), each result measured against `reference` if given (a
/// converged render of the same scene and size, another seed).
pub fn run(
    input: &Input,
    opts: &JobOptions,
    (threads, repeat): (usize, usize),
    reference: Option<&Path>,
) -> Result<Report, BenchError> {
    let scene = input.load()?;
    let job = RenderJob::prepare(scene, opts)?;
    let settings = RenderSettings {
        feature_images: true,
        ..job.settings.clone()
    };
    let reference = reference
        .map(|path| {
            let image = read_exr(path)?;
            let size = (image.width, image.height);
            if size != (settings.width, settings.height) {
                return Err(BenchError::ReferenceSize {
                    path: path.to_path_buf(),
                    got: size,
                    want: (settings.width, settings.height),
                });
            }
            Ok(image)
        })
        .transpose()?;
    let out = job.render_with(&settings, &ProgressBar::hidden());
    let features = out
        .features
        .as_ref()
        .expect("feature images were asked for");
    let mut images: Vec<(Variant, f64, Image)> = Vec::new();
    for v in VARIANTS {
        let d = Denoiser::new(threads, v.options())?;
        let guides = v.guides.map(|_| features.guides());
        let mut best = f64::INFINITY;
        let mut image = None;
        for _ in 0..repeat.max(1) {
            let t = Instant::now();
            let img = d.denoise(&out.image, guides)?;
            best = best.min(t.elapsed().as_secs_f64());
            image = Some(img);
        }
        images.push((v, best, image.expect("at least one repetition")));
    }
    let high = images[1].2.clone();
    let rows = images
        .into_iter()
        .map(|(variant, seconds, img)| Row {
            variant,
            seconds,
            difference: high.mean_abs_diff(&img) / high.mean_rgb().max(1e-12),
            rel_mse: reference.as_ref().map(|r| img.rel_mse(r)),
        })
        .collect();
    Ok(Report {
        settings,
        threads,
        raw_rel_mse: reference.as_ref().map(|r| out.image.rel_mse(r)),
        rows,
    })
}

impl Report {
    pub fn table(&self, input: &Input) -> String {
        let (settings, threads) = (&self.settings, self.threads);
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{input}: {}x{}, {} spp, denoiser threads {}",
            settings.width,
            settings.height,
            settings.spp,
            if threads == 0 {
                "all".to_string()
            } else {
                threads.to_string()
            }
        );
        if let Some(e) = self.raw_rel_mse {
            let _ = writeln!(s, "raw render: relMSE {e:.3e} against the reference");
        }
        let _ = writeln!(
            s,
            "{:<10} {:<20} {:>9} {:>14} {:>11}",
            "network", "guides", "seconds", "vs high/high", "relMSE"
        );
        for r in &self.rows {
            let v = &r.variant;
            let guides = match v.guides {
                None => "none".to_string(),
                Some(GuideMode::Prefiltered) => format!("prefiltered {}", name(v.prefilter)),
                Some(m) => name(m),
            };
            let rel_mse = r.rel_mse.map_or("-".to_string(), |e| format!("{e:.3e}"));
            let _ = writeln!(
                s,
                "{:<10} {:<20} {:>9.3} {:>14.2e} {:>11}",
                name(v.quality),
                guides,
                r.seconds,
                r.difference,
                rel_mse
            );
        }
        s
    }
}

/// An option's name as the command line spells it.
fn name(v: impl clap::ValueEnum) -> String {
    v.to_possible_value()
        .map_or_else(String::new, |p| p.get_name().to_string())
}
