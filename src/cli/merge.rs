//! `glint merge`: adds the sample shards of a still (`render --sample-shard I/N`) into the image the
//! whole render gives, refusing shards of other scenes or settings and naming the missing ones.

use std::path::PathBuf;

use anyhow::{Context, Result};

use super::args::finite;
use crate::film::{self, shard, Format};

#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The shard EXRs, in any order (every index 0..N once).
    #[arg(required = true)]
    pub shards: Vec<PathBuf>,
    /// The merged image: .exr (linear, as the whole render writes it) or .png.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Exposure in stops for a PNG output.
    #[arg(long, value_parser = finite, default_value_t = 0.0, allow_hyphen_values = true)]
    pub exposure: f32,
    /// View transform for a PNG output.
    #[arg(long, value_enum, default_value_t = film::ViewTransform::KhronosPbrNeutral)]
    pub view: film::ViewTransform,
}

pub fn run(args: MergeArgs) -> Result<()> {
    Format::from_path(&args.output)?;
    let shards = args
        .shards
        .iter()
        .map(|p| Ok((p.clone(), shard::read_sample_shard(p)?)))
        .collect::<Result<Vec<_>, shard::MergeError>>()?;
    let image = shard::merge(&shards).context("merging sample shards")?;
    film::write_with(
        &image,
        &args.output,
        &film::Display::new(args.exposure, args.view),
    )?;
    Ok(())
}
