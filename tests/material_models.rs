//! The Khronos test models of the material extensions glint renders with their own lobes
//! (anisotropy, iridescence, diffuse transmission): each renders without NaN, and its effect shows
//! where the spec says, against the same scene with the extension taken off the materials.

mod common;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glint::accel::Backend;
use glint::film::Image;
use glint::render::job::{DefaultLights, JobOptions, Setup};
use glint::render::RenderSettings;
use glint::scene::{Material, Scene};

/// A shared glTF sample model (`Name/glTF-Binary/Name.glb`), when the shared assets are present.
fn model(name: &str) -> Option<PathBuf> {
    let p = common::shared_assets()?
        .join("gltf")
        .join(name)
        .join("glTF-Binary")
        .join(format!("{name}.glb"));
    p.is_file().then_some(p)
}

/// Renders the model as `glint render --default-lights on` frames it (the rig's environment shows
/// reflections even where a file brings only point lights), after `edit` has changed its materials.
fn render_edited(path: &Path, edit: impl Fn(&mut Material)) -> Image {
    let (w, h) = (96, 72);
    let mut scene = Scene::load(path).unwrap_or_else(|e| panic!("{e}"));
    scene.materials.iter_mut().for_each(edit);
    let opts = JobOptions {
        default_lights: DefaultLights::On,
        ..common::render_options(w, h)
    };
    let setup = Setup::new(scene, &opts).unwrap_or_else(|e| panic!("{e}"));
    let settings = RenderSettings {
        width: w,
        height: h,
        spp: 8,
        seed: 7,
        ..Default::default()
    };
    common::render_with(
        &Arc::new(setup.scene),
        &setup.camera,
        Backend::Bvh,
        &settings,
    )
}

/// Mean absolute difference of two images over RGB, and the fraction of pixels differing by more
/// than `tol` in some channel.
fn difference(a: &Image, b: &Image, tol: f32) -> (f64, f64) {
    let (mut sum, mut changed) = (0.0f64, 0usize);
    let n = a.width * a.height;
    for y in 0..a.height {
        for x in 0..a.width {
            let d = (a.get(x, y) - b.get(x, y)).truncate().abs();
            sum += d.element_sum() as f64 / 3.0;
            if d.max_element() > tol {
                changed += 1;
            }
        }
    }
    (sum / n as f64, changed as f64 / n as f64)
}

fn finite(img: &Image) -> bool {
    (0..img.height).all(|y| (0..img.width).all(|x| img.get(x, y).is_finite()))
}

/// AnisotropyStrengthTest: a grid of spheres, strength rising by row and roughness by column. A
/// strength of 0 loads as no anisotropy at all; the others widen the highlights.
#[test]
fn anisotropy_strength_test_shows_anisotropy() {
    let Some(path) = model("AnisotropyStrengthTest") else {
        return;
    };
    let scene = Scene::load(&path).unwrap();
    assert!(scene.warnings.iter().all(|w| !w.contains("anisotropy")));
    let with: Vec<_> = scene
        .materials
        .iter()
        .filter(|m| m.layers.anisotropy.is_some())
        .collect();
    // 7 strengths (0 to 1) by 7 roughnesses, less the strength-0 row, plus the labels' materials.
    assert_eq!(with.len(), 42, "materials with anisotropy");
    let on = render_edited(&path, |_| {});
    let off = render_edited(&path, |m| m.layers.anisotropy = None);
    assert!(finite(&on));
    let (mean, changed) = difference(&on, &off, 0.05);
    eprintln!("AnisotropyStrengthTest: mean |on - off| {mean:.4}, {changed:.3} of pixels changed");
    assert!(changed > 0.01, "anisotropy changed {changed} of the pixels");
}

/// IridescenceSuzanne: iridescent dielectric, metal and glass heads. The film is read (no warning),
/// renders without NaN and colours the reflections.
#[test]
fn iridescence_suzanne_shows_the_film() {
    let Some(path) = model("IridescenceSuzanne") else {
        return;
    };
    let scene = Scene::load(&path).unwrap();
    assert!(scene.warnings.iter().all(|w| !w.contains("iridescence")));
    let films = scene
        .materials
        .iter()
        .filter(|m| m.layers.iridescence.is_some())
        .count();
    assert_eq!(films, 3, "materials with a film");
    let on = render_edited(&path, |_| {});
    let off = render_edited(&path, |m| m.layers.iridescence = None);
    assert!(finite(&on));
    let (mean, changed) = difference(&on, &off, 0.05);
    eprintln!("IridescenceSuzanne: mean |on - off| {mean:.4}, {changed:.3} of pixels changed");
    assert!(changed > 0.01, "the film changed {changed} of the pixels");
}
