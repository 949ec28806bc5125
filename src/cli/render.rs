//! `glint render`: flags into `JobOptions`, the job set up and run, the image and AOVs written, the
//! summary printed.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use glam::Vec3;

use super::args::{
    filter_radius, finite, parse_duration, parse_vec3, Args, DenoiseArgs, LensArgs, TimeArgs,
};
use super::progress_bar;
use crate::film::aov::{Aov, Outputs};
use crate::film::filter::FilterKind;
use crate::film::shard::{self, SampleShard, Shard};
use crate::film::{self, Display, Format, Image, ViewTransform};
use crate::render::job::{
    Basics, CameraChoice, CameraRef, Environment, JobOptions, Overrides, RenderJob, Setup, View,
};
use crate::render::{AdaptiveMode, EmissionSplits, LightSampler, RenderOutput, RenderSettings};
use crate::sample::SamplerKind;

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// A .gltf, .glb, .obj or .toml file.
    pub input: PathBuf,
    /// Output image: .png or .exr.
    #[arg(short, long)]
    pub output: PathBuf,
    #[command(flatten)]
    pub common: Args,
    /// Camera of the file to use, by index or name (default: the first; framed when the file has none).
    #[arg(long)]
    pub camera: Option<CameraRef>,
    /// Camera position (x,y,z); overrides the file's camera.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub eye: Option<Vec3>,
    /// Point the camera looks at (x,y,z); defaults to the centre of the model.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub look_at: Option<Vec3>,
    /// Up direction (x,y,z) for --eye/--look-at.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub up: Option<Vec3>,
    /// Light the model with an environment map: a lat-long (equirectangular) .exr or .hdr image of
    /// linear radiance, +Y up, its centre column facing +X (the glTF Sample Viewer's orientation). It
    /// replaces the default rig's constant environment, or the file's environment.
    #[arg(long, value_name = "FILE.exr|.hdr")]
    pub env: Option<PathBuf>,
    /// Multiplier on the --env map's radiance.
    #[arg(long, value_parser = finite, default_value_t = 1.0, requires = "env")]
    pub env_strength: f32,
    /// Turn the --env map about +Y by this many degrees (counter-clockwise seen from above).
    #[arg(
        long,
        value_parser = finite,
        default_value_t = 0.0,
        allow_hyphen_values = true,
        requires = "env"
    )]
    pub env_rotation: f32,
    /// Print the features the scene uses and the ones glint skips for it.
    #[arg(short, long)]
    pub verbose: bool,
    /// Sample generator (Owen-scrambled Sobol by default) [default: sobol]
    #[arg(long, value_enum)]
    pub sampler: Option<SamplerKind>,
    /// How light samples choose among the lights: by power, or through the light BVH (by a bound
    /// on what each light sends the shading point; less noise among many lights); auto takes the
    /// BVH from two lights on that are not at infinity (emissive triangles count one each)
    #[arg(long, value_enum, default_value_t = LightSampler::Auto)]
    pub light_sampler: LightSampler,
    /// Camera rays a path takes for the emission it sees directly, in pixels where emitters
    /// (emissive or unlit surfaces, area lights) have edges: those edges are most of the noise
    /// where small emitters are in view; 1 turns the search for edges off
    #[arg(long, value_enum, default_value_t = EmissionSplits::default())]
    pub emission_splits: EmissionSplits,
    /// Pixel reconstruction filter [default: gaussian]
    #[arg(long, value_enum)]
    pub filter: Option<FilterKind>,
    /// Filter radius in pixels (default: box 0.5, tent 1, gaussian 1.5, mitchell 2).
    #[arg(long, value_parser = filter_radius)]
    pub filter_radius: Option<f32>,
    /// Adaptive sampling: rounds until the image's estimated relative RMS error is under
    /// --target-error, samples going where they cut the error most per ray; converged pixels stop.
    #[arg(long)]
    pub adaptive: bool,
    /// Adaptive method: variance (error from half buffers, in rounds) or corners (Whitted-style
    /// subdivision where corner samples differ); implies --adaptive.
    #[arg(long, value_enum)]
    pub adaptive_mode: Option<AdaptiveMode>,
    /// Adaptive threshold: the image's relative RMS error (variance) or corner contrast (corners).
    #[arg(long, value_parser = finite, default_value_t = 0.01)]
    pub target_error: f32,
    /// Fewest samples an adaptive pixel takes.
    #[arg(long, default_value_t = 16)]
    pub min_spp: u32,
    /// Most samples an adaptive pixel takes.
    #[arg(long, default_value_t = 1024)]
    pub max_spp: u32,
    /// Render progressively until this time is spent (e.g. 30s, 2m, 500ms); --spp is then ignored.
    #[arg(long = "time", value_parser = parse_duration)]
    pub time_budget: Option<std::time::Duration>,
    /// Also write the samples each pixel took (.exr: counts; .png: counts / the most).
    #[arg(long)]
    pub spp_map: Option<PathBuf>,
    /// Feature images, comma separated: layers of the output for .exr (`albedo.R`, `N.X`, `Z`,
    /// `P.X`, `instance.id`, `material.id`, `variance.R`, `spp.count`, `raw.R`), files beside it for
    /// .png (`out.albedo.png`, `out.spp.png`, ...).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub aov: Vec<Aov>,
    #[command(flatten)]
    pub denoise: DenoiseArgs,
    /// Render only the sample indices i with i mod N == I of every pixel (machine I of N), into an
    /// .exr shard holding exact sums; `glint merge` adds the N shards into the whole render.
    #[arg(long, value_name = "I/N")]
    pub sample_shard: Option<Shard>,
    #[command(flatten)]
    pub lens: LensArgs,
    #[command(flatten)]
    pub time: TimeArgs,
}

impl RenderArgs {
    /// The job these flags ask for.
    pub fn options(&self) -> JobOptions {
        JobOptions {
            defaults: Basics::default(),
            flags: Overrides {
                sampler: self.sampler,
                filter: self.filter,
                ..self.common.overrides()
            },
            sampling: RenderSettings {
                filter_radius: self.filter_radius,
                adaptive: match (self.adaptive, self.adaptive_mode) {
                    (_, Some(m)) => m,
                    (true, None) => AdaptiveMode::Variance,
                    (false, None) => AdaptiveMode::Off,
                },
                target_error: self.target_error,
                min_spp: self.min_spp,
                max_spp: self.max_spp,
                time_budget: self.time_budget,
                light_sampler: self.light_sampler,
                emission_splits: self.emission_splits,
                ..RenderSettings::default()
            },
            view: View {
                camera: self
                    .camera
                    .clone()
                    .map_or(CameraChoice::First, CameraChoice::File),
                eye: self.eye,
                look_at: self.look_at,
                up: self.up,
                fov: self.common.fov,
            },
            environment: self.env.clone().map(|path| Environment {
                path,
                strength: self.env_strength,
                rotation: self.env_rotation,
            }),
            default_lights: self.common.default_lights,
            lens: self.lens.options(),
            time: self.time.options(),
            variant: self.common.variant.clone(),
            up_axis: self.common.model_up,
            scene: self.common.scene.clone().unwrap_or_default(),
        }
    }
}

/// A sample shard needs an .exr output and a fixed sample count (the same samples on every machine).
fn check_sample_shard(args: &RenderArgs) -> Result<()> {
    if args.sample_shard.is_none() {
        return Ok(());
    }
    if Format::from_path(&args.output)? != Format::Exr {
        bail!(
            "{}: --sample-shard writes an .exr shard (exact sums for `glint merge`)",
            args.output.display()
        );
    }
    if args.adaptive || args.adaptive_mode.is_some() || args.time_budget.is_some() {
        bail!("--sample-shard needs a fixed --spp: adaptive sampling and --time choose samples per machine");
    }
    if args.denoise.denoise || !args.aov.is_empty() {
        bail!("--sample-shard keeps sums only: denoise and take AOVs of the merged image instead");
    }
    Ok(())
}

/// AOVs and denoising need what only the filtered modes give.
fn check_aovs(args: &RenderArgs) -> Result<()> {
    if args.aov.contains(&Aov::BeautyRaw) && !args.denoise.denoise {
        bail!("--aov beauty-raw is the image before denoising: it needs --denoise");
    }
    let features = args.denoise.denoise || args.aov.iter().any(|a| a.needs_features());
    if features && args.adaptive_mode == Some(AdaptiveMode::Corners) {
        bail!("--denoise and feature AOVs need filtered samples: not with --adaptive-mode corners");
    }
    Ok(())
}

/// What makes two renders' pixels differ: the glint version, the input file's bytes (and the
/// environment map's), the job's options and the resolved settings and camera.
fn settings_hash(args: &RenderArgs, job: &RenderJob) -> Result<u64> {
    let read = |p: &Path| std::fs::read(p).with_context(|| format!("reading {}", p.display()));
    let input = read(&args.input)?;
    let env = args
        .env
        .as_deref()
        .map(read)
        .transpose()?
        .unwrap_or_default();
    let text = format!(
        "{}\n{:?}\n{:?}\n{:?}",
        env!("CARGO_PKG_VERSION"),
        args.options(),
        job.settings,
        job.camera
    );
    Ok(shard::settings_hash(&[&input, &env, text.as_bytes()]))
}

/// Checks the flags against each other and the output's folder before any work.
fn check(args: &mut RenderArgs) -> Result<()> {
    // Fail on a bad output name before spending time on the render.
    Format::from_path(&args.output)?;
    args.aov.sort_unstable();
    args.aov.dedup();
    if let Some(map) = &args.spp_map {
        Format::from_path(map)?;
    }
    if let Some(parent) = args.output.parent().filter(|p| !p.as_os_str().is_empty()) {
        if !parent.is_dir() {
            bail!("{}: output folder does not exist", parent.display());
        }
    }
    check_sample_shard(args)?;
    check_aovs(args)
}

/// What an earlier, killed render of these outputs left: temporary files of dead processes.
fn remove_stale_temps(args: &RenderArgs) {
    for out in std::iter::once(&args.output).chain(&args.spp_map) {
        let name = out.file_name().unwrap_or_default();
        let dir = out.parent().unwrap_or(Path::new(""));
        film::remove_stale_temps(dir, |n| std::ffi::OsStr::new(n) == name);
    }
}

pub fn run(mut args: RenderArgs) -> Result<()> {
    check(&mut args)?;
    args.common.set_threads()?;
    remove_stale_temps(&args);
    // Before the render: a build without the denoiser says so at once.
    let denoiser = args.denoise.denoiser(args.common.threads)?;

    let mut warn = |w: &str| eprintln!("warning: {}: {w}", args.input.display());
    let job = Setup::load(&args.input, &args.options(), &mut warn)?.build()?;
    let progress = progress_bar(
        args.common.quiet,
        "{spinner} rendering [{bar:40}] {percent}% tiles, eta {eta}",
    );
    if args.verbose {
        eprintln!("{}: {}", args.input.display(), job.features().describe());
    }
    let settings = RenderSettings {
        sample_shard: args.sample_shard,
        feature_images: denoiser.is_some() || args.aov.iter().any(|a| a.needs_features()),
        ..job.settings.clone()
    };
    let out = job.render_with(&settings, &progress);
    if args.verbose {
        eprintln!(
            "emission splits: {} pixels take {} camera rays a path",
            out.stats.split_pixels, settings.emission_splits
        );
    }
    let denoised = denoiser
        .as_ref()
        .map(|d| DenoiseArgs::run(d, &out.image, out.features.as_ref()))
        .transpose()?;
    match args.sample_shard {
        Some(shard) => shard::write_sample_shard(
            &SampleShard {
                shard,
                settings: settings_hash(&args, &job)?,
                width: settings.width,
                height: settings.height,
                sums: out.sums.clone(),
            },
            &args.output,
        )?,
        None => Outputs {
            beauty: denoised.as_ref().map_or(&out.image, |d| &d.0),
            raw: denoised.is_some().then_some(&out.image),
            features: out.features.as_ref(),
            spp: &out.spp,
        }
        .write(&args.aov, &args.output, &args.common.display())?,
    }
    if let Some(path) = &args.spp_map {
        write_spp_map(&out, path)?;
    }
    if !args.common.quiet {
        eprintln!("{}", summary(&args, &job, &out, denoised.map(|d| d.1)));
    }
    Ok(())
}

/// The samples each pixel took, into `path` (.exr: counts; .png: counts over the most).
fn write_spp_map(out: &RenderOutput, path: &Path) -> Result<()> {
    let scale = match Format::from_path(path)? {
        Format::Exr => 1.0,
        Format::Png => 1.0 / out.stats.max_spp.max(1) as f32,
    };
    let values: Vec<f32> = out.spp.iter().map(|&n| n as f32 * scale).collect();
    // Counts are data, not light: shown as they are, no tone curve.
    let plain = Display::new(0.0, ViewTransform::Standard);
    let (w, h) = (out.image.width, out.image.height);
    film::write_with(&Image::from_scalars(w, h, &values), path, &plain)?;
    Ok(())
}

/// The summary line: size, samples, backend, time, rays (and the denoiser's seconds).
fn summary(args: &RenderArgs, job: &RenderJob, out: &RenderOutput, denoise: Option<f64>) -> String {
    let (s, stats) = (&job.settings, out.stats);
    let spp_text = if stats.min_spp == stats.max_spp {
        format!("{}", stats.max_spp)
    } else {
        format!(
            "{:.1} (min {}, max {}, {} rounds)",
            out.mean_spp(),
            stats.min_spp,
            stats.max_spp,
            stats.rounds
        )
    };
    let denoise_text = denoise.map_or(String::new(), |t| format!(", denoised in {t:.2} s"));
    format!(
        "{}: {}x{} at {} spp with {} in {:.2} s: {} rays, {:.2} Mrays/s (load {:.2} s, build {:.3} s){denoise_text}",
        args.output.display(),
        s.width,
        s.height,
        spp_text,
        job.accel.name(),
        stats.seconds,
        stats.rays,
        stats.mrays_per_second(),
        job.load_seconds,
        job.build_seconds
    )
}
