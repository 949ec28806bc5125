//! Renders the generated CSG showcase (`scene::generate::csg_showcase`) with each backend named on the
//! command line (default: the default one) to /tmp/csg/showcase-<backend>.png.
//!
//! `cargo run --release --example csg_showcase -- [bvh|grid|embree ...] [--size 640x400] [--spp 64] [--depth 4]`

use std::path::Path;
use std::sync::Arc;

use glint::accel::{self, Backend};
use glint::film;
use glint::render::{self, RenderSettings};
use glint::scene::{defaults, generate};

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
    let mut scene = generate::csg_showcase();
    let mut camera = defaults::default_camera(&scene, width as f32 / height as f32);
    // A little lower and closer than the framing default, to look into the box's cavity.
    camera = glint::scene::Camera::look_at(
        glam::Vec3::new(2.5, 4.5, 9.5),
        glam::Vec3::new(0.0, 0.6, 0.5),
        glam::Vec3::Y,
        camera_fov(&camera),
    );
    defaults::light_if_unlit(&mut scene, &camera.to_world);
    let scene = Arc::new(scene);
    std::fs::create_dir_all("/tmp/csg")?;
    for backend in backends {
        let accel = accel::build(scene.clone(), backend)?;
        let settings = RenderSettings {
            width,
            height,
            spp,
            max_depth: depth,
            ..Default::default()
        };
        let (image, stats) = render::render(
            &scene,
            accel.as_ref(),
            &camera,
            &settings,
            &indicatif::ProgressBar::hidden(),
        );
        let path = format!("/tmp/csg/showcase-{backend}.png");
        film::write(&image, Path::new(&path), 0.0)?;
        println!("{path}: {:.2} Mrays/s", stats.mrays_per_second());
    }
    Ok(())
}

fn camera_fov(c: &glint::scene::Camera) -> f32 {
    match c.projection {
        glint::scene::Projection::Perspective { yfov, .. } => yfov,
        _ => defaults::DEFAULT_FOV_DEG.to_radians(),
    }
}
