//! `glint bench features`: what each effect costs and what skipping unused ones saves: the scene as
//! derived, with each effect it uses taken away, and with the machinery it skips forced on (same image).

use std::fmt::Write as _;
use std::sync::Arc;
use std::time::Instant;

use anyhow::Result;
use indicatif::ProgressBar;

use super::rays::load_input;
use crate::accel::{self, Backend};
use crate::film::Image;
use crate::geometry::Motion;
use crate::render::{self, RenderSettings};
use crate::scene::features::Features;
use crate::scene::{defaults, Camera, Lens, Material, Scene};

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

/// A change to the scene and camera: what it is called, and whether it applies given what the
/// scene uses (forcing makes sense for what a scene skips, removing for what it uses).
struct Variant {
    name: &'static str,
    applies: fn(&Features) -> bool,
    change: fn(&mut Scene, &mut Camera),
}

fn force_motion(scene: &mut Scene, _: &mut Camera) {
    // Two equal steps: every instance goes through the moving set and rays carry times, while the
    // image stays the same.
    for inst in &mut scene.instances {
        inst.motion.get_or_insert(Motion {
            steps: vec![inst.to_world; 2],
        });
    }
}

fn force_lens(scene: &mut Scene, cam: &mut Camera) {
    // A lens far below a pixel: lens samples are drawn, the image is a pinhole's.
    let (center, _) = defaults::bounding_sphere(&scene.bounds());
    cam.lens = Some(Lens {
        radius: 1e-7,
        focus_distance: (center - cam.position()).length().max(1e-3),
    });
}

fn force_thin(scene: &mut Scene, _: &mut Camera) {
    // An unused thin transmissive material switches the integrator to its thin-wall shadow path
    // (shadow rays walk surfaces with closest-hit queries).
    scene.materials.push(Material {
        name: "forced thin wall".into(),
        transmission: 1.0,
        metallic: 0.0,
        ..Material::default()
    });
}

fn without_motion(scene: &mut Scene, cam: &mut Camera) {
    for inst in &mut scene.instances {
        inst.motion = None;
    }
    let csg = std::mem::take(&mut scene.csg);
    scene.csg = csg
        .into_iter()
        .map(|c| {
            let rest = c.to_world;
            c.with_motion(Motion { steps: vec![rest] })
        })
        .collect();
    cam.motion = None;
}

fn without_lens(_: &mut Scene, cam: &mut Camera) {
    cam.lens = None;
}

fn without_transmission(scene: &mut Scene, _: &mut Camera) {
    for m in &mut scene.materials {
        m.transmission = 0.0;
    }
}

fn without_area_lights(scene: &mut Scene, _: &mut Camera) {
    // Each analytic area light becomes a point light of the same power at its centre: hard shadows.
    for l in &mut scene.lights {
        if let Some(point) = l.as_point_light() {
            *l = point;
        }
    }
}

fn without_glossy(scene: &mut Scene, _: &mut Camera) {
    // Every lobe fully rough: no sharp highlights or reflections to resolve.
    for m in &mut scene.materials {
        m.roughness = 1.0;
    }
}

const VARIANTS: [Variant; 9] = [
    Variant {
        name: "+ motion machinery",
        applies: |f| !f.motion,
        change: force_motion,
    },
    Variant {
        name: "+ lens sampling",
        applies: |f| !f.lens,
        change: force_lens,
    },
    Variant {
        name: "+ thin-wall shadows",
        applies: |f| !f.thin_walls,
        change: force_thin,
    },
    Variant {
        name: "all three forced",
        applies: |f| !f.motion && !f.lens && !f.thin_walls,
        change: |s, c| {
            force_motion(s, c);
            force_lens(s, c);
            force_thin(s, c);
        },
    },
    Variant {
        name: "- motion blur",
        applies: |f| f.motion,
        change: without_motion,
    },
    Variant {
        name: "- depth of field",
        applies: |f| f.lens,
        change: without_lens,
    },
    Variant {
        name: "- transmission",
        applies: |f| f.transmission,
        change: without_transmission,
    },
    Variant {
        name: "- soft shadows",
        applies: |f| f.area_lights,
        change: without_area_lights,
    },
    Variant {
        name: "- glossy (rough 1)",
        applies: |_| true,
        change: without_glossy,
    },
];

pub fn run(
    input: &str,
    backend: Backend,
    settings: &RenderSettings,
    repeat: usize,
) -> Result<(Features, Vec<Row>)> {
    let mut base = load_input(input)?;
    let aspect = settings.width as f32 / settings.height as f32;
    let camera = defaults::default_view(&mut base, aspect);
    let features = Features::of(&base, &camera);
    let derived = Variant {
        name: "as derived",
        applies: |_| true,
        change: |_, _| {},
    };
    let variants: Vec<(&Variant, Arc<Scene>, Camera)> = std::iter::once(&derived)
        .chain(VARIANTS.iter())
        .filter(|v| (v.applies)(&features))
        .map(|v| {
            let (mut scene, mut cam) = (base.clone(), camera.clone());
            (v.change)(&mut scene, &mut cam);
            (v, Arc::new(scene), cam)
        })
        .collect();
    // Repeats go round the variants, so a slow spell of the machine falls on all of them alike.
    let mut best = vec![(f64::INFINITY, f64::INFINITY); variants.len()];
    let mut images: Vec<Option<Image>> = vec![None; variants.len()];
    for _ in 0..repeat.max(1) {
        for (k, (_, scene, cam)) in variants.iter().enumerate() {
            let t = Instant::now();
            let accel = accel::build(scene.clone(), backend)?;
            let build = t.elapsed().as_secs_f64();
            let out =
                render::render_full(scene, accel.as_ref(), cam, settings, &ProgressBar::hidden());
            best[k] = (best[k].0.min(build), best[k].1.min(out.stats.seconds));
            images[k] = Some(out.image);
        }
    }
    let images: Vec<Image> = images.into_iter().flatten().collect();
    let reference = &images[0];
    let rows = variants
        .iter()
        .zip(&best)
        .zip(&images)
        .map(
            |(((v, _, _), &(build_seconds, render_seconds)), image)| Row {
                variant: v.name,
                build_seconds,
                render_seconds,
                image_difference: image.mean_abs_diff(reference) / reference.mean_rgb().max(1e-12),
            },
        )
        .collect();
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
          derived image's mean. `+` rows force machinery the scene skips and keep its image, up to\n\
          sampling that the extra dimensions shift; `-` rows take away an effect the scene uses)\n";
    s
}
