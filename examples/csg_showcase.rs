//! Renders the generated CSG showcase (`scene::generate::csg_showcase`) with each backend named on the
//! command line (default: the default one) to /tmp/csg/showcase-<backend>.png.
//!
//! `cargo run --release --example csg_showcase -- [bvh|grid|embree ...] [--size 640x400] [--spp 64] [--depth 4]`

use std::path::Path;

use glam::Vec3;
use glint::accel::Backend;
use glint::film;
use glint::render::job::{JobOptions, Overrides, RenderJob, View};
use glint::scene::generate;

fn main() -> anyhow::Result<()> {
    let mut backends = Vec::new();
    let (mut width, mut height, mut spp, mut depth) = (640usize, 400usize, 64u32, 4u32);
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--size" => {
                let v = args.next().unwrap_or_default();
                let (w, h) = v
                    .split_once('x')
                    .ok_or_else(|| anyhow::anyhow!("--size WxH"))?;
                (width, height) = (w.parse()?, h.parse()?);
            }
            "--spp" => spp = args.next().unwrap_or_default().parse()?,
            "--depth" => depth = args.next().unwrap_or_default().parse()?,
            b => backends.push(b.parse::<Backend>().map_err(anyhow::Error::msg)?),
        }
    }
    if backends.is_empty() {
        backends.push(Backend::default_available());
    }
    std::fs::create_dir_all("/tmp/csg")?;
    for backend in backends {
        let flags = Overrides {
            width: Some(width),
            height: Some(height),
            spp: Some(spp),
            max_depth: Some(depth),
            backend: Some(backend),
            ..Default::default()
        };
        let opts = JobOptions {
            flags,
            // A little lower and closer than the framing default, to look into the box's cavity.
            view: View {
                eye: Some(Vec3::new(2.5, 4.5, 9.5)),
                look_at: Some(Vec3::new(0.0, 0.6, 0.5)),
                ..Default::default()
            },
            ..Default::default()
        };
        let job = RenderJob::prepare(generate::csg_showcase(), &opts)?;
        let out = job.render(&indicatif::ProgressBar::hidden());
        let path = format!("/tmp/csg/showcase-{backend}.png");
        film::write(&out.image, Path::new(&path), 0.0)?;
        println!("{path}: {:.2} Mrays/s", out.stats.mrays_per_second());
    }
    Ok(())
}
