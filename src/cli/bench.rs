//! `glint bench ...`: the benchmark subcommands and their flags.
//! The measuring lives in `crate::bench`; this file only parses and prints.

use std::path::PathBuf;

use anyhow::Result;
use clap::Subcommand;

use crate::accel::Backend;
use crate::bench::rays::{self, RayKind, RaysConfig};

#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// Ray throughput of each backend on the same rays: build time and memory, Mrays/s per thread
    /// count, agreement with Embree.
    Rays(RaysArgs),
}

#[derive(clap::Args, Debug)]
pub struct RaysArgs {
    /// A .gltf, .glb or .obj file, or `icosphere:N` for a generated displaced icosphere of 20*4^N
    /// triangles (N = 8 gives 1.3M).
    pub input: String,
    /// Backends, comma separated (default: all built in).
    #[arg(long, value_delimiter = ',')]
    pub backend: Vec<Backend>,
    /// Ray kinds, comma separated: primary, shadow, diffuse.
    #[arg(long, value_delimiter = ',', default_values_t = RayKind::ALL)]
    pub kinds: Vec<RayKind>,
    /// Thread counts to measure, comma separated.
    #[arg(long, value_delimiter = ',', default_values_t = [1usize, 2])]
    pub threads: Vec<usize>,
    /// Primary rays are one per pixel of a WIDTHxHEIGHT image.
    #[arg(long, default_value_t = 1024)]
    pub width: usize,
    #[arg(long, default_value_t = 768)]
    pub height: usize,
    /// Timed repetitions per measurement (the best is reported).
    #[arg(long, default_value_t = 3)]
    pub repeat: usize,
    /// Also write the figures as JSON.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

pub fn run(cmd: BenchCommand) -> Result<()> {
    match cmd {
        BenchCommand::Rays(a) => {
            let config = RaysConfig {
                backends: if a.backend.is_empty() {
                    Backend::all_available()
                } else {
                    a.backend
                },
                kinds: a.kinds,
                threads: a.threads,
                width: a.width,
                height: a.height,
                repeat: a.repeat.max(1),
            };
            let report = rays::run(&a.input, &config)?;
            print!("{}", report.table());
            if let Some(path) = a.json {
                report.write_json(&path)?;
            }
            Ok(())
        }
    }
}
