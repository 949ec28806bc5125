//! `glint bench denoise`: what denoising one render costs, the colour alone and guided by albedo
//! and normal, at each quality of the network and of the guides' prefilter passes (best of N wall
//! times, the device made once), and how far each result is from the guided all-high one.

use std::fmt::Write as _;
use std::time::Instant;

use indicatif::ProgressBar;

use super::error::BenchError;
use super::input::Input;
use crate::film::denoise::{DenoiseQuality, Denoiser};
use crate::film::Image;
use crate::render::job::{JobOptions, RenderJob};
use crate::render::RenderSettings;

/// One way of denoising.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Variant {
    pub quality: DenoiseQuality,
    /// None: the colour alone; else the guides, cleaned at this quality.
    pub prefilter: Option<DenoiseQuality>,
}

/// The variants measured: the colour alone, then guided with the guides cleaned at each quality.
pub const VARIANTS: [Variant; 6] = {
    use DenoiseQuality::{Balanced, Fast, High};
    [
        Variant {
            quality: High,
            prefilter: None,
        },
        Variant {
            quality: High,
            prefilter: Some(High),
        },
        Variant {
            quality: High,
            prefilter: Some(Balanced),
        },
        Variant {
            quality: High,
            prefilter: Some(Fast),
        },
        Variant {
            quality: Balanced,
            prefilter: Some(Fast),
        },
        Variant {
            quality: Fast,
            prefilter: Some(Fast),
        },
    ]
};

#[derive(Clone, Debug)]
pub struct Row {
    pub variant: Variant,
    pub seconds: f64,
    /// Mean absolute difference from the guided high/high image, relative to its mean.
    pub difference: f64,
}

/// Renders the scene once with feature images, then denoises it `repeat` times per variant on a
/// device of `threads` threads (0: all).
pub fn run(
    input: &Input,
    opts: &JobOptions,
    threads: usize,
    repeat: usize,
) -> Result<(RenderSettings, Vec<Row>), BenchError> {
    let scene = input.load()?;
    let job = RenderJob::prepare(scene, opts)?;
    let settings = RenderSettings {
        feature_images: true,
        ..job.settings.clone()
    };
    let out = job.render_with(&settings, &ProgressBar::hidden());
    let features = out
        .features
        .as_ref()
        .expect("feature images were asked for");
    let mut images: Vec<(Variant, f64, Image)> = Vec::new();
    for v in VARIANTS {
        let d = Denoiser::new(threads, v.quality)?.with_prefilter(v.prefilter.unwrap_or(v.quality));
        let guides = v.prefilter.map(|_| features.guides());
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
    let reference = images[1].2.clone();
    let rows = images
        .into_iter()
        .map(|(variant, seconds, img)| Row {
            variant,
            seconds,
            difference: reference.mean_abs_diff(&img) / reference.mean_rgb().max(1e-12),
        })
        .collect();
    Ok((settings, rows))
}

pub fn table(input: &Input, settings: &RenderSettings, threads: usize, rows: &[Row]) -> String {
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
    let _ = writeln!(
        s,
        "{:<10} {:<10} {:>9} {:>12}",
        "network", "guides", "seconds", "vs high/high"
    );
    for r in rows {
        let guides = match r.variant.prefilter {
            None => "none".to_string(),
            Some(q) => format!("{q:?}").to_lowercase(),
        };
        let _ = writeln!(
            s,
            "{:<10} {:<10} {:>9.3} {:>12.2e}",
            format!("{:?}", r.variant.quality).to_lowercase(),
            guides,
            r.seconds,
            r.difference
        );
    }
    s
}
