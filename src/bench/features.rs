//! `glint bench features`: what each effect costs and what skipping unused ones saves: the scene as
//! derived, with each effect it uses taken away, and with the machinery it skips forced on (same image).

use std::fmt::Write as _;

use indicatif::ProgressBar;

use super::input::Input;
use crate::film::Image;
use crate::geometry::Motion;
use crate::render::job::{JobError, JobOptions, Setup};
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
        m.layers.diffuse_transmission = None;
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

/// What each variant changes, and when it applies.
const VARIANTS: [Variant; 9] = [
    variant("+ motion machinery", |f| !f.motion, force_motion),
    variant("+ lens sampling", |f| !f.lens, force_lens),
    variant("+ thin-wall shadows", |f| !f.thin_walls, force_thin),
    variant(
        "all three forced",
        |f| !f.motion && !f.lens && !f.thin_walls,
        |s, c| {
            force_motion(s, c);
            force_lens(s, c);
            force_thin(s, c);
        },
    ),
    variant("- motion blur", |f| f.motion, without_motion),
    variant("- depth of field", |f| f.lens, without_lens),
    variant("- transmission", |f| f.transmission, without_transmission),
    variant("- soft shadows", |f| f.area_lights, without_area_lights),
    variant("- glossy (rough 1)", |_| true, without_glossy),
];

const fn variant(
    name: &'static str,
    applies: fn(&Features) -> bool,
    change: fn(&mut Scene, &mut Camera),
) -> Variant {
    Variant {
        name,
        applies,
        change,
    }
}

/// Renders `scene` set up as `opts` say (`glint render`'s camera and lights) as derived and in
/// every variant that applies, `repeat` times each.
pub fn run(
    scene: Scene,
    opts: &JobOptions,
    repeat: usize,
) -> Result<(Features, Vec<Row>), JobError> {
    let base = Setup::new(scene, opts)?;
    let features = Features::of(&base.scene, &base.camera);
    let derived = variant("as derived", |_| true, |_, _| {});
    let variants: Vec<(&Variant, Setup)> = std::iter::once(&derived)
        .chain(VARIANTS.iter())
        .filter(|v| (v.applies)(&features))
        .map(|v| {
            let mut setup = base.clone();
            (v.change)(&mut setup.scene, &mut setup.camera);
            (v, setup)
        })
        .collect();
    // Repeats go round the variants, so a slow spell of the machine falls on all of them alike.
    let mut best = vec![(f64::INFINITY, f64::INFINITY); variants.len()];
    let mut images: Vec<Option<Image>> = vec![None; variants.len()];
    for _ in 0..repeat.max(1) {
        for (k, (_, setup)) in variants.iter().enumerate() {
            let job = setup.clone().build()?;
            let out = job.render(&ProgressBar::hidden());
            best[k] = (
                best[k].0.min(job.build_seconds),
                best[k].1.min(out.stats.seconds),
            );
            images[k] = Some(out.image);
        }
    }
    let images: Vec<Image> = images.into_iter().flatten().collect();
    let reference = &images[0];
    let rows = variants
        .iter()
        .zip(&best)
        .zip(&images)
        .map(|(((v, _), &(build_seconds, render_seconds)), image)| Row {
            variant: v.name,
            build_seconds,
            render_seconds,
            image_difference: image.mean_abs_diff(reference) / reference.mean_rgb().max(1e-12),
        })
        .collect();
    Ok((features, rows))
}

pub fn table(input: &Input, features: &Features, rows: &[Row]) -> String {
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
