//! `glint bench convergence`: error against run time for each sampler and adaptive mode.
//!
//! A converged reference (Sobol, many samples, an independent seed) is rendered once and cached as
//! EXR in the output folder; then every mode renders a ladder of sample counts (or adaptive targets)
//! and each run's render time, RMSE and relative MSE (pbrt's: mean of (x - ref)^2 / (ref^2 + 0.01))
//! against the reference are recorded. Writes `convergence.csv`, `summary.csv` and a log-log plot
//! `convergence.png`; the fitted slope of log error against log time per mode is the convergence
//! rate (about -0.5 for RMSE of independent random samples).

use std::fmt::{self, Write as _};
use std::path::{Path, PathBuf};

use indicatif::ProgressBar;

use super::error::{BenchError, Result};
use crate::film::denoise::{DenoiseOptions, Denoiser};
use crate::film::filter::FilterKind;
use crate::film::{self, Image};
use crate::render::job::{Basics, JobOptions, Overrides, RenderJob};
use crate::render::{AdaptiveMode, RenderSettings};
use crate::sample::SamplerKind;
use crate::scene::Scene;

#[derive(Clone, Debug)]
pub struct ConvergenceConfig {
    /// Image size, depth, seed, filter and backend (each run sets its own spp and sampler).
    pub basics: Basics,
    pub filter_radius: Option<f32>,
    /// Sample counts of the uniform runs.
    pub ladder: Vec<u32>,
    pub ref_spp: u32,
    pub samplers: Vec<SamplerKind>,
    /// Targets (the image's relative RMS error) of the variance-adaptive runs (Sobol); empty: the
    /// errors uniform Sobol (or the first sampler) reached at `adaptive_min_spp` and more.
    pub adaptive_targets: Vec<f32>,
    pub adaptive_min_spp: u32,
    pub adaptive_max_spp: u32,
    /// Contrast thresholds of the corner-subdivision runs.
    pub corner_targets: Vec<f32>,
    pub corner_max_spp: u32,
    /// Fraction of pixels with the largest errors left out of the trimmed metrics (fireflies, in a
    /// run or in the reference, otherwise dominate a mean of squares).
    pub trim: f64,
    /// Also the uniform Sobol ladder denoised with these options (guided by albedo and normal); a
    /// run's time includes the denoising.
    pub denoise: Option<DenoiseOptions>,
}

impl Default for ConvergenceConfig {
    fn default() -> Self {
        Self {
            basics: Basics {
                width: 160,
                height: 120,
                seed: 1,
                filter: FilterKind::Box,
                ..Basics::default()
            },
            filter_radius: None,
            ladder: (0..=8).map(|k| 1 << k).collect(),
            ref_spp: 4096,
            samplers: vec![
                SamplerKind::Random,
                SamplerKind::Stratified,
                SamplerKind::Sobol,
            ],
            adaptive_targets: Vec::new(),
            adaptive_min_spp: 16,
            adaptive_max_spp: 1024,
            corner_targets: vec![0.8, 0.4, 0.2, 0.1, 0.05],
            corner_max_spp: 289,
            trim: 0.001,
            denoise: None,
        }
    }
}

/// How a run spreads its samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// The same spp in every pixel, from this sampler.
    Uniform(SamplerKind),
    /// Sobol, variance-adaptive (`AdaptiveMode::Variance`).
    AdaptiveVariance,
    /// Sobol, corner subdivision (`AdaptiveMode::Corners`).
    AdaptiveCorners,
    /// Uniform Sobol, then denoised.
    Denoised,
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Mode::Uniform(k) => f.pad(&k.to_string()),
            Mode::AdaptiveVariance => f.pad("adaptive-variance"),
            Mode::AdaptiveCorners => f.pad("adaptive-corners"),
            Mode::Denoised => f.pad("sobol+denoise"),
        }
    }
}

/// One render of the ladder.
#[derive(Clone, Debug)]
pub struct Run {
    pub mode: Mode,
    /// The ladder parameter: spp, or the adaptive target.
    pub param: f64,
    pub mean_spp: f64,
    pub seconds: f64,
    pub rmse: f64,
    pub rel_mse: f64,
    /// The same less the reference's estimated noise, with the `trim` fraction of pixels left out at
    /// either end (what slopes and ratios use).
    pub rmse_trim: f64,
    pub rel_mse_trim: f64,
}

impl Run {
    /// Mean spp, seconds, RMSE, relMSE, RMSE* and relMSE*: the order of the table's and the CSV's
    /// columns after the mode and parameter.
    fn figures(&self) -> [f64; 6] {
        [
            self.mean_spp,
            self.seconds,
            self.rmse,
            self.rel_mse,
            self.rmse_trim,
            self.rel_mse_trim,
        ]
    }
}

/// Mean of the values once the `trim` fraction of largest ones and as many of the smallest ones
/// (pixels where the reference's own noise was large) are left out.
fn trimmed_mean(mut v: Vec<f64>, trim: f64) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    let k = ((v.len() as f64 * trim).floor() as usize).min(v.len().saturating_sub(1) / 2);
    let kept = &v[k..v.len() - k];
    kept.iter().sum::<f64>() / kept.len().max(1) as f64
}

#[derive(Clone, Debug)]
pub struct ModeSummary {
    pub mode: Mode,
    /// Least-squares slope of the corrected RMSE against mean spp, in log-log space.
    pub slope_rmse_spp: f64,
    /// On the metrics less the reference's noise, trimmed (what slopes and ratios use).
    pub corrected: Fit,
    /// The same on the plain metrics (no noise correction or trimming: outliers count).
    pub raw: Fit,
}

/// How one pair of error metrics (RMSE, relMSE) of a mode falls with render time.
#[derive(Clone, Copy, Debug)]
pub struct Fit {
    /// Least-squares slopes in log-log space.
    pub slope_rmse_time: f64,
    pub slope_relmse_time: f64,
    /// Time this mode needs to reach the RMSE of `random` at its largest spp, over random's time.
    pub time_ratio_rmse_vs_random: Option<f64>,
    /// Time this mode needs to reach the relMSE of uniform `sobol` at its largest spp, over sobol's.
    pub time_ratio_relmse_vs_sobol: Option<f64>,
}

pub struct Report {
    pub scene: String,
    pub reference: PathBuf,
    pub runs: Vec<Run>,
    pub summary: Vec<ModeSummary>,
}

pub fn run(input: &Path, out_dir: &Path, cfg: &ConvergenceConfig, verbose: bool) -> Result<Report> {
    std::fs::create_dir_all(out_dir).map_err(|source| BenchError::CreateDir {
        path: out_dir.to_path_buf(),
        source,
    })?;
    // Set up as `glint render` does by default: the first camera (or a framing one), the default
    // light rig when the model has no lights.
    let opts = JobOptions {
        defaults: cfg.basics,
        flags: Overrides::all(cfg.basics),
        sampling: RenderSettings {
            filter_radius: cfg.filter_radius,
            ..RenderSettings::default()
        },
        ..JobOptions::default()
    };
    let job = RenderJob::prepare(Scene::load(input)?, &opts)?;
    let reference = Reference::load_or_render(&job, input, out_dir, cfg, verbose)?;
    let ladder = Ladder {
        job: &job,
        reference: &reference,
        hidden: ProgressBar::hidden(),
        trim: cfg.trim,
        verbose,
    };
    let mut runs = ladder.run_all(cfg);
    if let Some(q) = cfg.denoise {
        runs.extend(ladder.run_denoised(&Denoiser::new(0, q)?, &cfg.ladder)?);
    }
    let summary = summarise(&runs);
    let report = Report {
        scene: input.display().to_string(),
        reference: reference.path,
        runs,
        summary,
    };
    report.write_csv(
        &out_dir.join("convergence.csv"),
        &out_dir.join("summary.csv"),
    )?;
    report.plot(&out_dir.join("convergence.png"))?;
    Ok(report)
}

/// The converged reference. It is two independent halves (ref_spp / 2 each): their mean is the
/// reference, and their difference estimates the reference's own noise, which is subtracted from
/// each run's squared error (so a noisy reference does not flatten the curves into a floor).
struct Reference {
    /// The first half's file, named in the report.
    path: PathBuf,
    image: Image,
    /// Per pixel and channel, the estimated variance of `image`.
    var: Vec<[f64; 3]>,
}

impl Reference {
    /// Reads both halves from `out_dir` where a render of the same settings left them, renders
    /// (and caches) them otherwise.
    fn load_or_render(
        job: &RenderJob,
        input: &Path,
        out_dir: &Path,
        cfg: &ConvergenceConfig,
        verbose: bool,
    ) -> Result<Self> {
        let base = &job.settings;
        let stem = input
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        let name = |half: u64| {
            format!(
                "reference-{stem}-{}x{}-{}spp-{}{}-d{}-half{half}.exr",
                base.width,
                base.height,
                cfg.ref_spp,
                base.filter,
                cfg.filter_radius
                    .map(|r| format!("{r}"))
                    .unwrap_or_default(),
                base.max_depth
            )
        };
        let mut halves = Vec::new();
        for half in 0..2u64 {
            let path = out_dir.join(name(half));
            halves.push(reference_half(job, &path, half, cfg.ref_spp, verbose)?);
        }
        let (width, height) = (base.width, base.height);
        let mut image = Image::new(width, height);
        let mut var = vec![[0.0f64; 3]; width * height];
        for (i, p) in image.pixels.iter_mut().enumerate() {
            let (a, b) = (halves[0].pixels[i], halves[1].pixels[i]);
            *p = (a + b) * 0.5;
            for c in 0..3 {
                let d = (a[c] - b[c]) as f64;
                var[i][c] = d * d / 4.0;
            }
        }
        Ok(Self {
            path: out_dir.join(name(0)),
            image,
            var,
        })
    }

    /// Per pixel: squared error less the reference's estimated variance, absolute and relative.
    fn errors(&self, image: &Image) -> (Vec<f64>, Vec<f64>) {
        let (mut abs, mut rel) = (Vec::new(), Vec::new());
        for (i, (x, r)) in image.pixels.iter().zip(&self.image.pixels).enumerate() {
            let (mut ea, mut er) = (0.0, 0.0);
            for c in 0..3 {
                let (xv, rv) = (x[c] as f64, r[c] as f64);
                let e = (xv - rv) * (xv - rv) - self.var[i][c];
                ea += e / 3.0;
                er += e / (rv * rv + 0.01) / 3.0;
            }
            abs.push(ea);
            rel.push(er);
        }
        (abs, rel)
    }
}

/// One half of the reference: read from `path` when it holds an image of the job's size, else
/// rendered (Sobol, `ref_spp / 2`) and written there.
fn reference_half(
    job: &RenderJob,
    path: &Path,
    half: u64,
    ref_spp: u32,
    verbose: bool,
) -> Result<Image> {
    let base = &job.settings;
    match film::read_exr(path) {
        Ok(img) if img.width == base.width && img.height == base.height => {
            if verbose {
                eprintln!("reusing reference half {}", path.display());
            }
            Ok(img)
        }
        _ => {
            let spp = (ref_spp / 2).max(1);
            if verbose {
                eprintln!(
                    "rendering reference half ({spp} spp, sobol) to {}",
                    path.display()
                );
            }
            let s = RenderSettings {
                spp,
                sampler: SamplerKind::Sobol,
                // Independent of every ladder run's samples and of the other half.
                seed: base.seed ^ (0x5EED_F2EF + half),
                ..base.clone()
            };
            let out = job.render_with(&s, &ProgressBar::hidden());
            film::write(&out.image, path, 0.0)?;
            if verbose {
                eprintln!("  took {:.1} s", out.stats.seconds);
            }
            Ok(out.image)
        }
    }
}

/// Renders the ladder's runs and measures each against the reference.
struct Ladder<'a> {
    job: &'a RenderJob,
    reference: &'a Reference,
    hidden: ProgressBar,
    trim: f64,
    verbose: bool,
}

impl Ladder<'_> {
    /// Every uniform run, then the variance-adaptive and the corner-subdivision ones.
    fn run_all(&self, cfg: &ConvergenceConfig) -> Vec<Run> {
        let base = &self.job.settings;
        let mut runs = Vec::new();
        for &sampler in &cfg.samplers {
            for &spp in &cfg.ladder {
                let s = RenderSettings {
                    spp,
                    sampler,
                    ..base.clone()
                };
                runs.push(self.measure(Mode::Uniform(sampler), spp as f64, &s));
            }
        }
        let (min, max) = (cfg.adaptive_min_spp, cfg.adaptive_max_spp);
        for t in adaptive_targets(cfg, &runs) {
            let s = adaptive(base, AdaptiveMode::Variance, t, min, max);
            runs.push(self.measure(Mode::AdaptiveVariance, short(t), &s));
        }
        for &t in &cfg.corner_targets {
            let s = adaptive(base, AdaptiveMode::Corners, t, 4, cfg.corner_max_spp);
            runs.push(self.measure(Mode::AdaptiveCorners, short(t), &s));
        }
        runs
    }

    /// The uniform Sobol ladder again, each image denoised with its albedo and normal.
    fn run_denoised(&self, d: &Denoiser, ladder: &[u32]) -> Result<Vec<Run>> {
        let mut runs = Vec::new();
        for &spp in ladder {
            let s = RenderSettings {
                spp,
                sampler: SamplerKind::Sobol,
                feature_images: true,
                ..self.job.settings.clone()
            };
            let out = self.job.render_with(&s, &self.hidden);
            let t = std::time::Instant::now();
            let guides = out.features.as_ref().map(|f| f.guides());
            let image = d.denoise(&out.image, guides)?;
            let seconds = out.stats.seconds + t.elapsed().as_secs_f64();
            runs.push(self.score(
                Mode::Denoised,
                spp as f64,
                (out.mean_spp(), seconds),
                &image,
            ));
        }
        Ok(runs)
    }

    fn measure(&self, mode: Mode, param: f64, s: &RenderSettings) -> Run {
        let out = self.job.render_with(s, &self.hidden);
        self.score(mode, param, (out.mean_spp(), out.stats.seconds), &out.image)
    }

    /// A run's errors against the reference (`cost`: its mean spp and seconds).
    fn score(&self, mode: Mode, param: f64, cost: (f64, f64), image: &Image) -> Run {
        let reference = &self.reference.image;
        let (abs, rel) = self.reference.errors(image);
        let run = Run {
            mode,
            param,
            mean_spp: cost.0,
            seconds: cost.1,
            rmse: image.rmse(reference),
            rel_mse: image.rel_mse(reference),
            rmse_trim: trimmed_mean(abs, self.trim).max(1e-12).sqrt(),
            rel_mse_trim: trimmed_mean(rel, self.trim).max(1e-12),
        };
        if self.verbose {
            eprintln!(
                "  {:<18} {:>8} spp={:>8.1} t={:>8.3}s rmse={:.5} relmse={:.3e} trimmed {:.5} {:.3e}",
                run.mode,
                run.param,
                run.mean_spp,
                run.seconds,
                run.rmse,
                run.rel_mse,
                run.rmse_trim,
                run.rel_mse_trim
            );
        }
        run
    }
}

/// Sobol with an adaptive `mode` aiming at `target`.
fn adaptive(
    base: &RenderSettings,
    mode: AdaptiveMode,
    target: f32,
    min_spp: u32,
    max_spp: u32,
) -> RenderSettings {
    RenderSettings {
        sampler: SamplerKind::Sobol,
        adaptive: mode,
        target_error: target,
        min_spp,
        max_spp,
        ..base.clone()
    }
}

/// The variance-adaptive runs' targets: the configured ones, or by default the errors uniform
/// Sobol (or else the first sampler) reached from the adaptive minimum up, so their curve spans
/// the same range whatever the scene's noise.
fn adaptive_targets(cfg: &ConvergenceConfig, runs: &[Run]) -> Vec<f32> {
    if !cfg.adaptive_targets.is_empty() {
        return cfg.adaptive_targets.clone();
    }
    let uniform = match cfg.samplers.iter().find(|&&k| k == SamplerKind::Sobol) {
        Some(k) => Some(k),
        None => cfg.samplers.first(),
    }
    .map(|&k| Mode::Uniform(k));
    runs.iter()
        .filter(|r| Some(r.mode) == uniform)
        .filter(|r| r.param >= cfg.adaptive_min_spp as f64 && r.rel_mse > 0.0)
        .map(|r| r.rel_mse.sqrt() as f32)
        .collect()
}

fn modes(runs: &[Run]) -> Vec<Mode> {
    let mut m: Vec<Mode> = Vec::new();
    for r in runs {
        if !m.contains(&r.mode) {
            m.push(r.mode);
        }
    }
    m
}

/// Least-squares slope of log y against log x.
pub fn fit_slope(points: &[(f64, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 2 {
        return f64::NAN;
    }
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    sxy / sxx
}

/// The time at which a mode's error curve (sorted by time) first reaches `target`: log-log
/// interpolation between the bracketing runs, or extrapolation along the fitted slope past the last.
fn time_to_reach(points: &[(f64, f64)], target: f64, slope: f64) -> Option<f64> {
    let mut p: Vec<(f64, f64)> = points.to_vec();
    p.sort_by(|a, b| a.0.total_cmp(&b.0));
    if p.is_empty() {
        return None;
    }
    if p[0].1 <= target {
        return Some(p[0].0);
    }
    for w in p.windows(2) {
        let ((t0, e0), (t1, e1)) = (w[0], w[1]);
        if e1 <= target && e0 > target {
            let f = (target.ln() - e0.ln()) / (e1.ln() - e0.ln());
            return Some((t0.ln() + f * (t1.ln() - t0.ln())).exp());
        }
    }
    let (tl, el) = *p.last().unwrap();
    (slope < 0.0).then(|| tl * (target / el).powf(1.0 / slope))
}

fn summarise(runs: &[Run]) -> Vec<ModeSummary> {
    modes(runs)
        .into_iter()
        .map(|m| {
            let spp: Vec<(f64, f64)> = runs
                .iter()
                .filter(|r| r.mode == m)
                .map(|r| (r.mean_spp, r.rmse_trim))
                .collect();
            ModeSummary {
                mode: m,
                slope_rmse_spp: fit_slope(&spp),
                corrected: Fit::of(runs, m, |r| r.rmse_trim, |r| r.rel_mse_trim),
                raw: Fit::of(runs, m, |r| r.rmse, |r| r.rel_mse),
            }
        })
        .collect()
}

impl Fit {
    /// Mode `m`'s fit of the metrics `rmse` and `rel_mse`; the ratios' targets are the most
    /// accurate run of random (RMSE) and of uniform sobol (relMSE).
    fn of(runs: &[Run], m: Mode, rmse: fn(&Run) -> f64, rel_mse: fn(&Run) -> f64) -> Self {
        let series = |f: fn(&Run) -> f64| -> Vec<(f64, f64)> {
            runs.iter()
                .filter(|r| r.mode == m)
                .map(|r| (r.seconds, f(r)))
                .collect()
        };
        let best = |of: Mode, f: fn(&Run) -> f64| {
            runs.iter()
                .filter(|r| r.mode == of)
                .max_by(|a, b| a.param.total_cmp(&b.param))
                .map(|r| (r.seconds, f(r)))
        };
        let ratio = |points: &[(f64, f64)], best: Option<(f64, f64)>, slope: f64| {
            best.and_then(|(t, e)| time_to_reach(points, e, slope).map(|x| x / t))
        };
        let (rm, rel) = (series(rmse), series(rel_mse));
        let (slope_rmse_time, slope_relmse_time) = (fit_slope(&rm), fit_slope(&rel));
        let random = best(Mode::Uniform(SamplerKind::Random), rmse);
        let sobol = best(Mode::Uniform(SamplerKind::Sobol), rel_mse);
        Self {
            slope_rmse_time,
            slope_relmse_time,
            time_ratio_rmse_vs_random: ratio(&rm, random, slope_rmse_time),
            time_ratio_relmse_vs_sobol: ratio(&rel, sobol, slope_relmse_time),
        }
    }
}

fn opt(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.3}")).unwrap_or_else(|| "-".into())
}

/// A figure of a mode's summary: a fitted slope, or a time ratio (absent when never reached).
enum Figure {
    Slope(f64),
    Ratio(Option<f64>),
}

impl Figure {
    /// Slopes with `digits` decimals, ratios with three ("-" when absent).
    fn text(&self, digits: usize) -> String {
        match self {
            Figure::Slope(x) => format!("{x:.digits$}"),
            Figure::Ratio(r) => opt(*r),
        }
    }
}

impl ModeSummary {
    /// The figures in the order of the table's and the CSV's columns.
    fn columns(&self) -> [Figure; 8] {
        use Figure::{Ratio, Slope};
        [
            Slope(self.corrected.slope_rmse_time),
            Slope(self.corrected.slope_relmse_time),
            Slope(self.slope_rmse_spp),
            Ratio(self.corrected.time_ratio_rmse_vs_random),
            Ratio(self.corrected.time_ratio_relmse_vs_sobol),
            Slope(self.raw.slope_rmse_time),
            Ratio(self.raw.time_ratio_rmse_vs_random),
            Ratio(self.raw.time_ratio_relmse_vs_sobol),
        ]
    }
}

impl Report {
    pub fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{} (reference {})", self.scene, self.reference.display());
        let _ = writeln!(
            s,
            "RMSE*, relMSE*: less the reference's own noise (from its two halves), 0.1% of pixels trimmed at each end"
        );
        let _ = writeln!(
            s,
            "{:<18} {:>8} {:>9} {:>9} {:>10} {:>11} {:>10} {:>11}",
            "mode", "param", "mean spp", "time s", "RMSE", "relMSE", "RMSE*", "relMSE*"
        );
        for r in &self.runs {
            let [spp, seconds, rmse, rel, rmse_t, rel_t] = r.figures();
            let _ = writeln!(
                s,
                "{:<18} {:>8} {spp:>9.1} {seconds:>9.3} {rmse:>10.5} {rel:>11.3e} {rmse_t:>10.5} {rel_t:>11.3e}",
                r.mode, r.param
            );
        }
        let _ = writeln!(
            s,
            "\n{:<18} {:>13} {:>15} {:>15} {:>17} {:>18} {:>13} {:>17} {:>18}",
            "mode",
            "slope RMSE*/t",
            "slope relMSE*/t",
            "slope RMSE*/spp",
            "t/t_random RMSE*",
            "t/t_sobol relMSE*",
            "slope RMSE/t",
            "t/t_random RMSE",
            "t/t_sobol relMSE"
        );
        for m in &self.summary {
            let _ = write!(s, "{:<18}", m.mode);
            for (f, w) in m.columns().iter().zip([13, 15, 15, 17, 18, 13, 17, 18]) {
                let _ = write!(s, " {:>w$}", f.text(3));
            }
            s.push('\n');
        }
        if let Some(c) = self.denoise_comparison(16, 128) {
            s.push_str(&c);
        }
        s
    }

    /// The denoised `few`-spp image against raw uniform Sobol at `many` spp (relMSE, raw and
    /// trimmed), and the spp at which raw Sobol reaches the denoised image's relMSE (interpolated
    /// in log-log, or extrapolated along its fitted slope).
    pub fn denoise_comparison(&self, few: u32, many: u32) -> Option<String> {
        let find = |m: Mode, spp: u32| {
            self.runs
                .iter()
                .find(|r| r.mode == m && r.param == spp as f64)
        };
        let d = find(Mode::Denoised, few)?;
        let sobol = Mode::Uniform(SamplerKind::Sobol);
        let (spp, rel): (Vec<f64>, Vec<f64>) = self
            .runs
            .iter()
            .filter(|r| r.mode == sobol)
            .map(|r| (r.mean_spp, r.rel_mse))
            .unzip();
        let by_spp: Vec<(f64, f64)> = spp.into_iter().zip(rel).collect();
        let catch_up = time_to_reach(&by_spp, d.rel_mse, fit_slope(&by_spp));
        let mut s = format!(
            "\ndenoised {few} spp: relMSE {:.3e} (relMSE* {:.3e}, {:.2} s with denoising)\n",
            d.rel_mse, d.rel_mse_trim, d.seconds
        );
        if let Some(r) = find(sobol, many) {
            let _ = writeln!(
                s,
                "raw sobol {many} spp: relMSE {:.3e} (relMSE* {:.3e}, {:.2} s)",
                r.rel_mse, r.rel_mse_trim, r.seconds
            );
        }
        let _ = writeln!(
            s,
            "raw sobol reaches the denoised {few}-spp relMSE at {} spp{}",
            catch_up.map_or("-".into(), |x| format!("{x:.0}")),
            if by_spp.is_empty() {
                " (no sobol ladder)"
            } else {
                ""
            }
        );
        Some(s)
    }

    pub fn write_csv(&self, runs_path: &Path, summary_path: &Path) -> Result<()> {
        let mut s = String::from(
            "scene,mode,param,mean_spp,seconds,rmse,relmse,rmse_corrected,relmse_corrected,slope_rmse_time,slope_relmse_time,slope_rmse_spp\n",
        );
        for r in &self.runs {
            let m = self.summary.iter().find(|m| m.mode == r.mode).unwrap();
            let [spp, seconds, errors @ ..] = r.figures();
            let errors = errors.map(|e| format!("{e:.6e}")).join(",");
            let _ = writeln!(
                s,
                "{},{},{},{spp:.3},{seconds:.6},{errors},{:.4},{:.4},{:.4}",
                self.scene,
                r.mode,
                r.param,
                m.corrected.slope_rmse_time,
                m.corrected.slope_relmse_time,
                m.slope_rmse_spp
            );
        }
        std::fs::write(runs_path, s).map_err(BenchError::write(runs_path))?;
        let mut s = String::from(
            "scene,mode,slope_rmse_time,slope_relmse_time,slope_rmse_spp,time_ratio_rmse_vs_random,time_ratio_relmse_vs_sobol,slope_rmse_time_raw,time_ratio_rmse_vs_random_raw,time_ratio_relmse_vs_sobol_raw\n",
        );
        for m in &self.summary {
            let figures: Vec<String> = m.columns().iter().map(|f| f.text(4)).collect();
            let _ = writeln!(s, "{},{},{}", self.scene, m.mode, figures.join(","));
        }
        std::fs::write(summary_path, s).map_err(BenchError::write(summary_path))
    }

    /// Two log-log panels (RMSE and relMSE against seconds), one series per mode.
    pub fn plot(&self, path: &Path) -> Result<()> {
        use plotters::prelude::*;
        static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSansMono.ttf");
        // Registering twice is harmless; the font is bundled, so no system font library is needed.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
        let (w, h) = (1200u32, 520u32);
        let mut buf = vec![0u8; (w * h * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
            root.fill(&WHITE).map_err(BenchError::plot)?;
            let panels = root.split_evenly((1, 2));
            let rmse: Panel = ("RMSE", |r| r.rmse, |f| f.slope_rmse_time);
            let rel_mse: Panel = ("relMSE", |r| r.rel_mse, |f| f.slope_relmse_time);
            for (area, panel) in panels.iter().zip([rmse, rel_mse]) {
                self.draw_panel(area, panel)?;
            }
            root.present().map_err(BenchError::plot)?;
        }
        image::save_buffer_with_format(
            path,
            &buf,
            w,
            h,
            image::ColorType::Rgb8,
            image::ImageFormat::Png,
        )
        .map_err(|source| BenchError::WriteImage {
            path: path.to_path_buf(),
            source,
        })
    }

    /// One panel: the metric of every mode against seconds, each labelled with its raw slope.
    fn draw_panel(
        &self,
        area: &plotters::drawing::DrawingArea<
            plotters::prelude::BitMapBackend<'_>,
            plotters::coord::Shift,
        >,
        (name, f, slope_of): Panel,
    ) -> Result<()> {
        use plotters::prelude::*;
        let colors = [RED, BLUE, GREEN, MAGENTA, CYAN, BLACK];
        let pts = self.points(|_| true, f);
        let (tmin, tmax) = pts
            .iter()
            .fold((f64::MAX, 0.0f64), |(a, b), p| (a.min(p.0), b.max(p.0)));
        let (emin, emax) = pts
            .iter()
            .fold((f64::MAX, 0.0f64), |(a, b), p| (a.min(p.1), b.max(p.1)));
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("{name} vs render time (legend: fitted slope)"),
                ("sans-serif", 18),
            )
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (tmin * 0.8..tmax * 1.25).log_scale(),
                (emin * 0.8..emax * 1.25).log_scale(),
            )
            .map_err(BenchError::plot)?;
        chart
            .configure_mesh()
            .x_desc("seconds")
            .y_desc(name)
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()
            .map_err(BenchError::plot)?;
        for (i, m) in modes(&self.runs).iter().enumerate() {
            let c = colors[i % colors.len()];
            let mut series = self.points(|r| &r.mode == m, f);
            series.sort_by(|a, b| a.0.total_cmp(&b.0));
            let slope = self
                .summary
                .iter()
                .find(|s| &s.mode == m)
                .map(|s| slope_of(&s.raw))
                .unwrap_or(f64::NAN);
            chart
                .draw_series(LineSeries::new(series.clone(), c.stroke_width(2)))
                .map_err(BenchError::plot)?
                .label(format!("{m} ({slope:.2})"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 16, y)], c.stroke_width(2))
                });
            chart
                .draw_series(series.iter().map(|&p| Circle::new(p, 3, c.filled())))
                .map_err(BenchError::plot)?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::LowerLeft)
            .draw()
            .map_err(BenchError::plot)
    }

    /// (seconds, metric) of the runs `keep` keeps, clamped away from zero for the log axes.
    fn points(&self, keep: impl Fn(&Run) -> bool, f: fn(&Run) -> f64) -> Vec<(f64, f64)> {
        self.runs
            .iter()
            .filter(|r| keep(r))
            .map(|r| (r.seconds.max(1e-4), f(r).max(1e-12)))
            .collect()
    }
}

/// A plot panel: its metric's name, the metric, and the fitted slope shown in its legend.
type Panel = (&'static str, fn(&Run) -> f64, fn(&Fit) -> f64);

/// An f32 parameter as the f64 it was written as (0.4, not 0.4000000059604645).
fn short(t: f32) -> f64 {
    format!("{t}").parse().unwrap_or(t as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report() -> Report {
        let fit = Fit {
            slope_rmse_time: -0.5,
            slope_relmse_time: -1.0,
            time_ratio_rmse_vs_random: Some(0.75),
            time_ratio_relmse_vs_sobol: None,
        };
        Report {
            scene: "s.glb".into(),
            reference: "r.exr".into(),
            runs: vec![Run {
                mode: Mode::Uniform(SamplerKind::Sobol),
                param: 16.0,
                mean_spp: 16.25,
                seconds: 1.23456,
                rmse: 0.0123456,
                rel_mse: 0.000123456,
                rmse_trim: 0.0111111,
                rel_mse_trim: 0.0000999,
            }],
            summary: vec![ModeSummary {
                mode: Mode::Uniform(SamplerKind::Sobol),
                slope_rmse_spp: -0.49,
                corrected: fit,
                raw: fit,
            }],
        }
    }

    /// The figures of a run sit in the table's and the CSV's columns with their own precision.
    #[test]
    fn a_run_prints_in_its_columns() {
        let r = report();
        let row = format!(
            "{:<18} {:>8} {:>9.1} {:>9.3} {:>10.5} {:>11.3e} {:>10.5} {:>11.3e}",
            "sobol", 16, 16.25, 1.23456, 0.0123456, 0.000123456, 0.0111111, 0.0000999
        );
        assert!(r.table().lines().any(|l| l == row), "{}", r.table());
        let dir = tempfile::tempdir().unwrap();
        let (runs, summary) = (dir.path().join("r.csv"), dir.path().join("s.csv"));
        r.write_csv(&runs, &summary).unwrap();
        let csv = std::fs::read_to_string(&runs).unwrap();
        assert_eq!(
            csv.lines().nth(1).unwrap(),
            "s.glb,sobol,16,16.250,1.234560,1.234560e-2,1.234560e-4,1.111110e-2,9.990000e-5,-0.5000,-1.0000,-0.4900"
        );
    }
}
