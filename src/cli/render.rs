//! `glint render`: flags into `JobOptions`, the job set up and run, the image and AOVs written, the
//! summary printed.

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use glam::Vec3;

use super::args::{parse_duration, parse_vec3, Args, LensArgs, TimeArgs};
use super::progress_bar;
use crate::film::filter::FilterKind;
use crate::film::shard::{self, SampleShard, Shard};
use crate::film::{self, Display, Format, Image, ViewTransform};
use crate::render::job::{
    Basics, CameraChoice, CameraRef, Environment, JobOptions, Overrides, Setup, View,
};
use crate::render::{AdaptiveMode, RenderSettings};
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
    #[arg(long, default_value_t = 1.0, requires = "env")]
    pub env_strength: f32,
    /// Turn the --env map about +Y by this many degrees (counter-clockwise seen from above).
    #[arg(
        long,
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
    /// Pixel reconstruction filter [default: gaussian]
    #[arg(long, value_enum)]
    pub filter: Option<FilterKind>,
    /// Filter radius in pixels (default: box 0.5, tent 1, gaussian 1.5, mitchell 2).
    #[arg(long)]
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
    #[arg(long, default_value_t = 0.01)]
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
    /// Extra images beside the output, comma separated: `spp` writes OUTPUT's name with `.spp`
    /// before the extension (what --spp-map FILE writes elsewhere).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub aov: Vec<Aov>,
    /// Render only the sample indices i with i mod N == I of every pixel (machine I of N), into an
    /// .exr shard holding exact sums; `glint merge` adds the N shards into the whole render.
    #[arg(long, value_name = "I/N")]
    pub sample_shard: Option<Shard>,
    #[command(flatten)]
    pub lens: LensArgs,
    #[command(flatten)]
    pub time: TimeArgs,
}

/// Per-pixel images a render can write beside its output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Aov {
    /// Samples each pixel took.
    Spp,
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
        }
    }
}

/// `out.exr` -> `out.spp.exr`: an AOV's file beside the output, in the output's format.
fn aov_path(output: &Path, aov: &str) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    let ext = output.extension().unwrap_or_default().to_string_lossy();
    output.with_file_name(format!("{stem}.{aov}.{ext}"))
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
    Ok(())
}

/// What makes two renders' pixels differ: the glint version, the input file's bytes (and the
/// environment map's), the job's options and the resolved settings and camera.
fn settings_hash(args: &RenderArgs, job: &crate::render::job::RenderJob) -> Result<u64> {
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

pub fn run(mut args: RenderArgs) -> Result<()> {
    // Fail on a bad output name before spending time on the render.
    Format::from_path(&args.output)?;
    if args.aov.contains(&Aov::Spp) && args.spp_map.is_none() {
        args.spp_map = Some(aov_path(&args.output, "spp"));
    }
    if let Some(map) = &args.spp_map {
        Format::from_path(map)?;
    }
    if let Some(parent) = args.output.parent().filter(|p| !p.as_os_str().is_empty()) {
        if !parent.is_dir() {
            bail!("{}: output folder does not exist", parent.display());
        }
    }
    check_sample_shard(&args)?;
    args.common.set_threads()?;

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
        ..job.settings.clone()
    };
    let out = job.render_with(&settings, &progress);
    let (s, stats) = (&job.settings, out.stats);
    match args.sample_shard {
        Some(shard) => shard::write_sample_shard(
            &SampleShard {
                shard,
                settings: settings_hash(&args, &job)?,
                width: s.width,
                height: s.height,
                sums: out.sums.clone(),
            },
            &args.output,
        )?,
        None => film::write_with(&out.image, &args.output, &args.common.display())?,
    }
    if let Some(path) = &args.spp_map {
        let scale = match Format::from_path(path)? {
            Format::Exr => 1.0,
            Format::Png => 1.0 / stats.max_spp.max(1) as f32,
        };
        let values: Vec<f32> = out.spp.iter().map(|&n| n as f32 * scale).collect();
        // Counts are data, not light: shown as they are, no tone curve.
        let plain = Display::new(0.0, ViewTransform::Standard);
        film::write_with(
            &Image::from_scalars(s.width, s.height, &values),
            path,
            &plain,
        )?;
    }
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
    if !args.common.quiet {
        eprintln!(
            "{}: {}x{} at {} spp with {} in {:.2} s: {} rays, {:.2} Mrays/s (load {:.2} s, build {:.3} s)",
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
        );
    }
    Ok(())
}
