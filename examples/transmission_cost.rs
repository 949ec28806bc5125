//! What transmission costs a render: the same model rendered as loaded and with every material made
//! opaque (transmission 0), alternating, with times, rays and Mrays/s. Not a test: run by hand:
//!
//!     cargo run --release --example transmission_cost -- MODEL [SPP] [WIDTH] [HEIGHT] [REPEATS]

use std::path::PathBuf;

use glint::accel::Backend;
use glint::render::job::{JobOptions, Overrides, Setup};
use glint::scene::Scene;

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = PathBuf::from(
        args.first()
            .ok_or_else(|| anyhow::anyhow!("usage: transmission_cost MODEL [SPP] [W] [H] [N]"))?,
    );
    let num = |i: usize, d: usize| args.get(i).and_then(|a| a.parse().ok()).unwrap_or(d);
    let (spp, width, height, repeats) = (num(1, 32) as u32, num(2, 320), num(3, 240), num(4, 2));
    let flags = Overrides {
        width: Some(width),
        height: Some(height),
        spp: Some(spp),
        max_depth: Some(8),
        backend: Some(Backend::Bvh),
        ..Default::default()
    };
    let opts = JobOptions {
        flags,
        ..Default::default()
    };
    // Set up as `glint render` would; the opaque copy shares the camera and lights.
    let setup = Setup::new(Scene::load(&path)?, &opts)?;
    let scene = &setup.scene;
    let transmissive = scene
        .materials
        .iter()
        .filter(|m| m.is_transmissive())
        .count();
    let mut opaque = setup.clone();
    for m in &mut opaque.scene.materials {
        m.transmission = 0.0;
    }
    println!(
        "{}: {transmissive} of {} materials transmissive; {width}x{height} at {spp} spp",
        path.display(),
        scene.materials.len()
    );
    let setups = [("as loaded", setup), ("opaque", opaque)];
    for round in 0..repeats {
        for (label, s) in &setups {
            let job = s.clone().build()?;
            let stats = job.render(&indicatif::ProgressBar::hidden()).stats;
            println!(
                "round {round} {label:>9}: {:.2} s, {} rays, {:.2} Mrays/s",
                stats.seconds,
                stats.rays,
                stats.mrays_per_second()
            );
        }
    }
    Ok(())
}
