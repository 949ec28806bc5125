//! What transmission costs a render: the same model rendered as loaded and with every material made
//! opaque (transmission 0), alternating, with times, rays and Mrays/s. Not a test: run by hand:
//!
//!     cargo run --release --example transmission_cost -- MODEL [SPP] [WIDTH] [HEIGHT] [REPEATS]

use std::path::PathBuf;
use std::sync::Arc;

use glint::accel::{self, Backend};
use glint::render::{self, RenderSettings};
use glint::scene::{defaults, Scene};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = PathBuf::from(
        args.first()
            .ok_or_else(|| anyhow::anyhow!("usage: transmission_cost MODEL [SPP] [W] [H] [N]"))?,
    );
    let num = |i: usize, d: usize| args.get(i).and_then(|a| a.parse().ok()).unwrap_or(d);
    let (spp, width, height, repeats) = (num(1, 32) as u32, num(2, 320), num(3, 240), num(4, 2));
    let mut scene = Scene::load(&path)?;
    let camera = defaults::default_view(&mut scene, width as f32 / height as f32);
    let transmissive = scene
        .materials
        .iter()
        .filter(|m| m.is_transmissive())
        .count();
    let mut opaque = scene.clone();
    for m in &mut opaque.materials {
        m.transmission = 0.0;
    }
    println!(
        "{}: {transmissive} of {} materials transmissive; {width}x{height} at {spp} spp",
        path.display(),
        scene.materials.len()
    );
    let settings = RenderSettings {
        width,
        height,
        spp,
        max_depth: 8,
        ..Default::default()
    };
    let scenes = [("as loaded", Arc::new(scene)), ("opaque", Arc::new(opaque))];
    for round in 0..repeats {
        for (label, s) in &scenes {
            let accel = accel::build(s.clone(), Backend::Bvh)?;
            let (_, stats) = render::render(
                s,
                accel.as_ref(),
                &camera,
                &settings,
                &indicatif::ProgressBar::hidden(),
            );
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
