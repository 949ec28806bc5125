//! `glint bench ...`: the benchmark subcommands and their flags.
//! The measuring lives in `crate::bench`; this file only parses and prints.

use std::path::PathBuf;

use anyhow::Result;
use clap::Subcommand;

use super::args::{filter_radius, finite};
use crate::accel::Backend;
use crate::bench::input::Input;
use crate::bench::rays::{self, RayKind, RaysConfig};
use crate::film::filter::FilterKind;
use crate::render::job::{Basics, JobOptions, Overrides};
use crate::sample::SamplerKind;

/// An image size with a command's own defaults (W x H, given in each command's description).
/// Not clap's `default_value_t`: its default string is a static inside a generic function, which
/// every `Size<W, H>` shares, so all commands got the first one evaluated.
#[derive(clap::Args, Debug)]
pub struct Size<const W: usize, const H: usize> {
    /// Image width in pixels [default: the command's own]
    #[arg(long)]
    width: Option<usize>,
    /// Image height in pixels [default: the command's own]
    #[arg(long)]
    height: Option<usize>,
}

impl<const W: usize, const H: usize> Size<W, H> {
    pub fn width(&self) -> usize {
        self.width.unwrap_or(W)
    }

    pub fn height(&self) -> usize {
        self.height.unwrap_or(H)
    }
}

#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// Ray throughput of each backend on the same rays: build time and memory, Mrays/s per thread
    /// count, agreement with Embree. Primary rays of a 1024 x 768 image unless told.
    Rays(RaysArgs),
    /// Error against render time for each sampler and adaptive mode, against a cached converged
    /// reference: CSV, log-log plot, fitted convergence slopes. 160 x 120 unless told.
    Convergence(ConvergenceArgs),
    /// How many ray/triangle tests cheap per-object tests (bounding sphere, box, nearest-first
    /// order) save over brute force, on the same primary, shadow and diffuse rays (of a 320 x 240
    /// image unless told).
    FastFailure(FastFailureArgs),
    /// What skipping unused features saves: a static, pinhole, opaque scene rendered as derived and
    /// with motion, lens and thin-wall machinery forced on (the same image; 320 x 240 unless told).
    Features(FeaturesArgs),
    /// What denoising one render costs: the colour alone and guided by albedo and normal, in each
    /// guide mode and network quality, with each result's error against --reference if given
    /// (1280 x 720 unless told).
    Denoise(DenoiseArgs),
}

#[derive(clap::Args, Debug)]
pub struct DenoiseArgs {
    /// A .gltf, .glb, .obj or .toml file, or `icosphere:N`.
    pub input: Input,
    #[command(flatten)]
    pub size: Size<1280, 720>,
    #[arg(long, default_value_t = 4)]
    pub spp: u32,
    /// Denoiser threads (0: all cores).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Timed repetitions per variant (the best is reported).
    #[arg(long, default_value_t = 3)]
    pub repeat: usize,
    /// A converged EXR of the same scene and size (e.g. `glint render` at thousands of spp and
    /// another seed): each result's relMSE against it is reported.
    #[arg(long)]
    pub reference: Option<PathBuf>,
}

#[derive(clap::Args, Debug)]
pub struct FeaturesArgs {
    /// A .gltf, .glb, .obj or .toml file, or `icosphere:N`.
    pub input: Input,
    #[command(flatten)]
    pub size: Size<320, 240>,
    #[arg(long, default_value_t = 16)]
    pub spp: u32,
    #[arg(long, value_enum, default_value_t = Backend::default_available())]
    pub backend: Backend,
    /// Timed repetitions per variant (the best is reported).
    #[arg(long, default_value_t = 3)]
    pub repeat: usize,
}

#[derive(clap::Args, Debug)]
pub struct FastFailureArgs {
    /// A .gltf, .glb, .obj or .toml file, or `icosphere:N`.
    pub input: Input,
    /// Rays per kind (an even sample of the full set; brute force is slow).
    #[arg(long, default_value_t = 20_000)]
    pub rays: usize,
    #[command(flatten)]
    pub size: Size<320, 240>,
}

#[derive(clap::Args, Debug)]
pub struct ConvergenceArgs {
    /// A .gltf, .glb or .obj file.
    pub input: PathBuf,
    /// Output folder: reference EXR (reused when present), convergence.csv, summary.csv, convergence.png.
    #[arg(long)]
    pub out: PathBuf,
    #[command(flatten)]
    pub size: Size<160, 120>,
    /// Largest sample count of the uniform ladder (1, 2, 4, ... up to this).
    #[arg(long, default_value_t = 256)]
    pub max_spp: u32,
    /// Samples per pixel of the reference.
    #[arg(long, default_value_t = 4096)]
    pub ref_spp: u32,
    #[arg(long, default_value_t = 5)]
    pub max_depth: u32,
    #[arg(long, value_enum, default_value_t = FilterKind::Box)]
    pub filter: FilterKind,
    #[arg(long, value_parser = filter_radius)]
    pub filter_radius: Option<f32>,
    /// Samplers of the uniform ladders, comma separated.
    #[arg(long, value_enum, value_delimiter = ',', default_values_t = [SamplerKind::Random, SamplerKind::Stratified, SamplerKind::Sobol])]
    pub samplers: Vec<SamplerKind>,
    /// Targets of the variance-adaptive runs (the image's relative RMS error), comma separated
    /// (default: the errors uniform sobol reached from --adaptive-min-spp spp up).
    #[arg(long, value_delimiter = ',')]
    pub adaptive_targets: Vec<f32>,
    /// Fewest samples a pixel of an adaptive run takes.
    #[arg(long, default_value_t = 16)]
    pub adaptive_min_spp: u32,
    /// Most samples a pixel of an adaptive run takes.
    #[arg(long, default_value_t = 1024)]
    pub adaptive_max_spp: u32,
    /// Contrast thresholds of the corner-subdivision runs, comma separated.
    #[arg(long, value_delimiter = ',', default_values_t = [0.8f32, 0.4, 0.2, 0.1, 0.05])]
    pub corner_targets: Vec<f32>,
    #[arg(long, value_enum, default_value_t = Backend::default_available())]
    pub backend: Backend,
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Also the uniform Sobol ladder denoised with Open Image Denoise (albedo and normal guides),
    /// compared with raw sampling.
    #[arg(long)]
    pub denoise: bool,
    /// Only the tables, no per-run log.
    #[arg(short, long)]
    pub quiet: bool,
}

#[derive(clap::Args, Debug)]
pub struct RaysArgs {
    /// A .gltf, .glb or .obj file, or `icosphere:N` for a generated displaced icosphere of 20*4^N
    /// triangles (N = 8 gives 1.3M), or `csg:showcase`, `csg:spheres` (64 CSG spheres on a ground
    /// plane) or `mesh:spheres[:N]` (the same spheres as icospheres of N subdivisions, default 4).
    pub input: Input,
    /// Backends, comma separated (default: all built in, Embree both robust and fast).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub backend: Vec<Backend>,
    /// Ray kinds, comma separated: primary, shadow, diffuse, packets, shadow-packets, diffuse-packets.
    #[arg(long, value_delimiter = ',', default_values_t = RayKind::ALL)]
    pub kinds: Vec<RayKind>,
    /// Thread counts to measure, comma separated.
    #[arg(long, value_delimiter = ',', default_values_t = [1usize, 2])]
    pub threads: Vec<usize>,
    /// Primary rays are one per pixel of a WIDTHxHEIGHT image.
    #[command(flatten)]
    pub size: Size<1024, 768>,
    /// Timed repetitions per measurement (the best is reported).
    #[arg(long, default_value_t = 3)]
    pub repeat: usize,
    /// Also write the figures as JSON.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Shutter OPEN,CLOSE in seconds: measure the file's animation with motion blur (rays at random
    /// times in the shutter).
    #[arg(long, value_parser = super::args::parse_shutter, allow_hyphen_values = true)]
    pub shutter: Option<[f32; 2]>,
    /// Seconds into the animation (with --shutter).
    #[arg(long, value_parser = finite, default_value_t = 0.0, allow_hyphen_values = true)]
    pub frame_time: f32,
}

pub fn run(cmd: BenchCommand) -> Result<()> {
    match cmd {
        BenchCommand::Convergence(a) => convergence(a),
        BenchCommand::FastFailure(a) => fast_failure(a),
        BenchCommand::Features(a) => features(a),
        BenchCommand::Denoise(a) => denoise(a),
        BenchCommand::Rays(a) => rays(a),
    }
}

fn convergence(a: ConvergenceArgs) -> Result<()> {
    use crate::bench::convergence::{self, ConvergenceConfig};
    use crate::film::denoise::DenoiseOptions;
    let mut ladder = vec![1u32];
    while ladder.last().unwrap() * 2 <= a.max_spp.max(1) {
        ladder.push(ladder.last().unwrap() * 2);
    }
    let config = ConvergenceConfig {
        basics: Basics {
            width: a.size.width().max(1),
            height: a.size.height().max(1),
            max_depth: a.max_depth,
            seed: a.seed,
            backend: a.backend,
            filter: a.filter,
            ..ConvergenceConfig::default().basics
        },
        filter_radius: a.filter_radius,
        ladder,
        ref_spp: a.ref_spp.max(1),
        samplers: a.samplers,
        adaptive_targets: a.adaptive_targets,
        adaptive_min_spp: a.adaptive_min_spp.max(1),
        adaptive_max_spp: a.adaptive_max_spp,
        corner_targets: a.corner_targets,
        denoise: a.denoise.then(DenoiseOptions::default),
        ..Default::default()
    };
    let report = convergence::run(&a.input, &a.out, &config, !a.quiet)?;
    super::print_out(&report.table())?;
    Ok(())
}

fn fast_failure(a: FastFailureArgs) -> Result<()> {
    use crate::bench::fastfail;
    let (w, h) = (a.size.width().max(1), a.size.height().max(1));
    let rows = fastfail::run(&a.input, w, h, a.rays)?;
    let objects = a.input.load()?.instances.len();
    super::print_out(&fastfail::table(&a.input, objects, &rows))
}

fn features(a: FeaturesArgs) -> Result<()> {
    use crate::bench::features;
    let basics = Basics {
        width: a.size.width().clamp(1, 8192),
        height: a.size.height().clamp(1, 8192),
        spp: a.spp.clamp(1, 1 << 16),
        backend: a.backend,
        ..Basics::default()
    };
    let opts = JobOptions {
        defaults: basics,
        flags: Overrides::all(basics),
        ..JobOptions::default()
    };
    let (f, rows) = features::run(a.input.load()?, &opts, a.repeat)?;
    super::print_out(&features::table(&a.input, &f, &rows))
}

fn denoise(a: DenoiseArgs) -> Result<()> {
    use crate::bench::denoise;
    let basics = Basics {
        width: a.size.width().clamp(1, 8192),
        height: a.size.height().clamp(1, 8192),
        spp: a.spp.clamp(1, 1 << 16),
        ..Basics::default()
    };
    let opts = JobOptions {
        defaults: basics,
        flags: Overrides::all(basics),
        ..JobOptions::default()
    };
    let report = denoise::run(
        &a.input,
        &opts,
        (a.threads, a.repeat),
        a.reference.as_deref(),
    )?;
    super::print_out(&report.table(&a.input))
}

fn rays(a: RaysArgs) -> Result<()> {
    let config = RaysConfig {
        backends: if a.backend.is_empty() {
            let mut all = Backend::all_available();
            if all.contains(&Backend::Embree) {
                all.push(Backend::EmbreeFast);
            }
            all
        } else {
            a.backend
        },
        kinds: a.kinds,
        threads: a.threads,
        width: a.size.width(),
        height: a.size.height(),
        repeat: a.repeat.max(1),
        shutter: a.shutter,
        frame_time: a.frame_time,
    };
    let report = rays::run(&a.input, &config)?;
    super::print_out(&report.table())?;
    if let Some(path) = a.json {
        report.write_json(&path)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::{Cli, Command};
    use clap::Parser;

    fn bench(args: &[&str]) -> super::BenchCommand {
        let argv = ["glint", "bench"].iter().chain(args).copied();
        match Cli::try_parse_from(argv).unwrap().command {
            Command::Bench(b) => b,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn each_bench_command_keeps_its_own_default_size() {
        let size = |b: super::BenchCommand| match b {
            super::BenchCommand::Rays(a) => (a.size.width(), a.size.height()),
            super::BenchCommand::Convergence(a) => (a.size.width(), a.size.height()),
            super::BenchCommand::FastFailure(a) => (a.size.width(), a.size.height()),
            super::BenchCommand::Features(a) => (a.size.width(), a.size.height()),
            super::BenchCommand::Denoise(a) => (a.size.width(), a.size.height()),
        };
        // Parsed in an order that once let the first default evaluated win everywhere.
        assert_eq!(size(bench(&["rays", "x.glb"])), (1024, 768));
        assert_eq!(
            size(bench(&["convergence", "x.glb", "--out", "o"])),
            (160, 120)
        );
        assert_eq!(size(bench(&["fast-failure", "x.glb"])), (320, 240));
        assert_eq!(
            size(bench(&["features", "x.glb", "--width", "7"])),
            (7, 240)
        );
        assert_eq!(size(bench(&["denoise", "x.glb"])), (1280, 720));
    }
}
