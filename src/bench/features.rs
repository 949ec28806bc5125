//! `glint bench features`: what skipping unused features saves on a static, pinhole, opaque scene:
//! the same render with motion, lens and thin-wall machinery forced on (same image), timed.

use std::fmt::Write as _;
use std::sync::Arc;
use std::time::Instant;

use anyhow::Result;
use indicatif::ProgressBar;

use super::rays::load_input;
use crate::accel::{self, Backend};
use crate::render::{self, RenderSettings};
use crate::scene::features::Features;
use crate::scene::{defaults, Lens, Material, Motion, Scene};

/// One variant of the scene: what was forced, build and render time (best of the repeats), and how
/// far its image is from the derived one.
#[derive(Clone, Debug)]
pub struct Row {
    pub variant: &'static str,
    pub build_seconds: f64,
    pub render_seconds: f64,
    /// Mean absolute difference from the derived render, relative to its mean.
    pub image_difference: f64,
}

#[derive(Clone, Copy, Debug)]
struct Force {
    motion: bool,
    lens: bool,
    thin: bool,
}

const VARIANTS: [(&str, Force); 5] = [
    (
        "derived (skips unused)",
        Force {
            motion: false,
            lens: false,
            thin: false,
        },
    ),
    (
        "+ motion machinery",
        Force {
            motion: true,
            lens: false,
            thin: false,
        },
    ),
    (
        "+ lens sampling",
        Force {
            motion: false,
            lens: true,
            thin: false,
        },
    ),
    (
        "+ thin-wall shadows",
        Force {
            motion: false,
            lens: false,
            thin: true,
        },
    ),
    (
        "all forced",
        Force {
            motion: true,
            lens: true,
            thin: true,
        },
    ),
];

pub fn run(
    input: &str,
    backend: Backend,
    settings: &RenderSettings,
    repeat: usize,
) -> Result<(Features, Vec<Row>)> {
    let mut base = load_input(input)?;
    let aspect = settings.width as f32 / settings.height as f32;
    let camera = defaults::default_camera(&base, aspect);
    defaults::light_if_unlit(&mut base, &camera.to_world);
    let features = Features::of(&base, &camera);
    let mut rows = Vec::new();
    let mut reference: Option<Vec<glam::Vec4>> = None;
    for (variant, force) in VARIANTS {
        let mut scene: Scene = base.clone();
        let mut cam = camera.clone();
        if force.motion {
            // Two equal steps: every instance goes through the moving set and rays carry times,
            // while the image stays the same.
            for inst in &mut scene.instances {
                inst.motion.get_or_insert(Motion {
                    steps: vec![inst.to_world; 2],
                });
            }
        }
        if force.lens && cam.lens.is_none() {
            // A lens far below a pixel: lens samples are drawn, the image is a pinhole's.
            let (center, _) = defaults::bounding_sphere(&scene.bounds());
            cam.lens = Some(Lens {
                radius: 1e-7,
                focus_distance: (center - cam.position()).length().max(1e-3),
            });
        }
        if force.thin {
            // An unused thin transmissive material switches the integrator to its thin-wall
            // shadow path (shadow rays walk surfaces with closest-hit queries).
            scene.materials.push(Material {
                name: "forced thin wall".into(),
                transmission: 1.0,
                metallic: 0.0,
                ..Material::default()
            });
        }
        let scene = Arc::new(scene);
        let (mut build_seconds, mut render_seconds) = (f64::INFINITY, f64::INFINITY);
        let mut image = None;
        for _ in 0..repeat.max(1) {
            let t = Instant::now();
            let accel = accel::build(scene.clone(), backend)?;
            build_seconds = build_seconds.min(t.elapsed().as_secs_f64());
            let out = render::render_full(
                &scene,
                accel.as_ref(),
                &cam,
                settings,
                &ProgressBar::hidden(),
            );
            render_seconds = render_seconds.min(out.stats.seconds);
            image = Some(out.image.pixels);
        }
        let image = image.expect("rendered at least once");
        let image_difference = match &reference {
            None => 0.0,
            Some(r) => {
                let (mut d, mut m) = (0.0f64, 0.0f64);
                for (a, b) in image.iter().zip(r) {
                    d += (*a - *b).truncate().abs().element_sum() as f64;
                    m += b.truncate().abs().element_sum() as f64;
                }
                d / m.max(1e-12)
            }
        };
        if reference.is_none() {
            reference = Some(image);
        }
        rows.push(Row {
            variant,
            build_seconds,
            render_seconds,
            image_difference,
        });
    }
    Ok((features, rows))
}

pub fn table(input: &str, features: &Features, rows: &[Row]) -> String {
    let mut s = format!("{input}: {}\n", features.describe());
    let _ = writeln!(
        s,
        "{:<24} {:>9} {:>10} {:>8} {:>12}",
        "variant", "build s", "render s", "ratio", "image diff"
    );
    let base = rows.first().map_or(1.0, |r| r.render_seconds);
    for r in rows {
        let _ = writeln!(
            s,
            "{:<24} {:>9.4} {:>10.3} {:>8.3} {:>12.2e}",
            r.variant,
            r.build_seconds,
            r.render_seconds,
            r.render_seconds / base.max(1e-12),
            r.image_difference
        );
    }
    s += "(ratio: render time over the derived render's; image diff: mean |difference| over the\n\
          derived image's mean; forcing keeps the image, up to sampling that the extra dimensions shift)\n";
    s
}
