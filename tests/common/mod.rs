//! Helpers shared by the integration tests: where the assets are, and small renders.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glint::accel::{self, Backend};
use glint::film::Image;
use glint::render::job::{JobOptions, Overrides, Setup};
use glint::render::{self, RenderSettings};
use glint::scene::{Camera, Scene};

/// The shared asset folder (`../shared/assets` beside the checkout), when present.
pub fn shared_assets() -> Option<PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/assets");
    if p.is_dir() {
        Some(p)
    } else {
        eprintln!("shared assets not found at {}: skipping those", p.display());
        None
    }
}

/// Every model file under a folder (.gltf, .glb, .obj), sorted.
pub fn model_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if matches!(
                p.extension().and_then(|e| e.to_str()),
                Some("gltf" | "glb" | "obj")
            ) {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The project's own assets plus the shared ones (when present), less the files that require an
/// extension glint refuses by design (their refusal is tested in bad_input).
pub fn all_model_files() -> Vec<PathBuf> {
    let mut files = model_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("assets"));
    if let Some(shared) = shared_assets() {
        files.extend(model_files(&shared));
    }
    files.retain(|f| match Scene::load(f) {
        Err(e) if e.to_string().contains("requires unsupported extension") => {
            eprintln!("{}: refused by design, skipped: {e}", f.display());
            false
        }
        _ => true,
    });
    files
}

/// The job options of `glint render` at this size with no other flag.
pub fn render_options(width: usize, height: usize) -> JobOptions {
    let flags = Overrides {
        width: Some(width),
        height: Some(height),
        ..Default::default()
    };
    JobOptions {
        flags,
        ..Default::default()
    }
}

/// Loads a model as `glint render` does (through its render job, without building): posed, the
/// file's first camera or a framing one, and the default light rig when it has no lights of its own.
pub fn load_for_render(path: &Path, width: usize, height: usize) -> (Arc<Scene>, Camera) {
    let scene = Scene::load(path).unwrap_or_else(|e| panic!("{e}"));
    let setup = Setup::new(scene, &render_options(width, height)).unwrap_or_else(|e| panic!("{e}"));
    (Arc::new(setup.scene), setup.camera)
}

/// The backends that trace whole scenes (obvhs, a bench peer, traces triangles only).
pub fn render_backends() -> Vec<Backend> {
    Backend::all_available()
        .into_iter()
        .filter(|&b| b != Backend::Obvhs)
        .collect()
}

pub fn render_with(
    scene: &Arc<Scene>,
    camera: &Camera,
    backend: Backend,
    settings: &RenderSettings,
) -> Image {
    let accel = accel::build(scene.clone(), backend).unwrap();
    render::render(
        scene,
        accel.as_ref(),
        camera,
        settings,
        &indicatif::ProgressBar::hidden(),
    )
    .0
}

/// Centroid and variance (per axis, pixels^2) of the image's red channel, weighted by value.
pub fn moments(img: &Image) -> (f64, f64, f64, f64) {
    let (mut s, mut sx, mut sy, mut sxx, mut syy) = (0.0f64, 0.0, 0.0, 0.0, 0.0);
    for y in 0..img.height {
        for x in 0..img.width {
            let w = img.get(x, y).x as f64;
            let (fx, fy) = (x as f64 + 0.5, y as f64 + 0.5);
            s += w;
            sx += w * fx;
            sy += w * fy;
            sxx += w * fx * fx;
            syy += w * fy * fy;
        }
    }
    let (mx, my) = (sx / s, sy / s);
    (mx, my, sxx / s - mx * mx, syy / s - my * my)
}
