//! Samplers, filters and adaptive sampling in whole renders: determinism across thread counts for
//! every sampler and mode, the minimum sample count of adaptive pixels (through the spp AOV), and
//! adaptive sampling spending less on a plain background than on the object.

mod common;

use std::path::Path;
use std::sync::Arc;

use glint::accel::{self, Backend};
use glint::film::filter::FilterKind;
use glint::render::{self, AdaptiveMode, RenderOutput, RenderSettings};
use glint::sample::SamplerKind;
use glint::scene::{defaults, generate, Camera, Scene};

fn demo() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/demo/demo.glb")
}

fn render_full(scene: &Arc<Scene>, camera: &Camera, settings: &RenderSettings) -> RenderOutput {
    let accel = accel::build(scene.clone(), Backend::Bvh).unwrap();
    render::render_full(
        scene,
        accel.as_ref(),
        camera,
        settings,
        &indicatif::ProgressBar::hidden(),
    )
}

fn with_threads<T: Send>(n: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .unwrap()
        .install(f)
}

#[test]
fn every_sampler_and_mode_is_deterministic_across_thread_counts() {
    let (w, h) = (24, 18);
    let (scene, camera) = common::load_for_render(&demo(), w, h);
    let base = RenderSettings {
        width: w,
        height: h,
        spp: 4,
        max_depth: 3,
        seed: 5,
        ..Default::default()
    };
    let mut cases = Vec::new();
    for sampler in [
        SamplerKind::Random,
        SamplerKind::Stratified,
        SamplerKind::Sobol,
    ] {
        for filter in [FilterKind::Box, FilterKind::Gaussian, FilterKind::Mitchell] {
            cases.push(RenderSettings {
                sampler,
                filter,
                ..base.clone()
            });
        }
        cases.push(RenderSettings {
            sampler,
            adaptive: AdaptiveMode::Variance,
            target_error: 0.1,
            min_spp: 2,
            max_spp: 16,
            ..base.clone()
        });
    }
    cases.push(RenderSettings {
        adaptive: AdaptiveMode::Corners,
        target_error: 0.3,
        min_spp: 4,
        max_spp: 25,
        ..base.clone()
    });
    let mut images = Vec::new();
    for s in &cases {
        let one = with_threads(1, || render_full(&scene, &camera, s));
        let two = with_threads(2, || render_full(&scene, &camera, s));
        assert_eq!(one.image, two.image, "{s:?}");
        assert_eq!(one.spp, two.spp, "{s:?}");
        assert!(!one.image.has_non_finite(), "{s:?}");
        images.push(one.image);
    }
    // The samplers really differ.
    assert_ne!(images[0], images[4]);
    assert_ne!(images[4], images[8]);
}

#[test]
fn adaptive_pixels_never_stop_below_the_minimum() {
    let (w, h) = (32, 24);
    let (scene, camera) = common::load_for_render(&demo(), w, h);
    let s = RenderSettings {
        width: w,
        height: h,
        max_depth: 3,
        adaptive: AdaptiveMode::Variance,
        target_error: 0.05,
        min_spp: 8,
        max_spp: 64,
        ..Default::default()
    };
    let out = render_full(&scene, &camera, &s);
    assert_eq!(out.spp.len(), w * h);
    assert!(out.spp.iter().all(|&n| (8..=64).contains(&n)));
    assert_eq!(out.stats.min_spp, *out.spp.iter().min().unwrap());
    assert!(out.stats.max_spp > 8, "nothing was refined");
    assert!(out.stats.rounds > 1);
}

#[test]
fn adaptive_spends_fewer_samples_on_a_plain_background() {
    let (w, h) = (40, 30);
    let mut scene = generate::single_mesh_scene(generate::icosphere(2, 0.0));
    // Frame the sphere loosely so that about half the image is background.
    let camera = defaults::frame_bounds(
        &scene.bounds(),
        defaults::default_view_direction(),
        70f32.to_radians(),
        w as f32 / h as f32,
    );
    scene.lights.extend(defaults::light_rig(&camera.to_world));
    let scene = Arc::new(scene);
    let s = RenderSettings {
        width: w,
        height: h,
        max_depth: 3,
        filter: FilterKind::Box,
        adaptive: AdaptiveMode::Variance,
        target_error: 0.02,
        min_spp: 8,
        max_spp: 128,
        ..Default::default()
    };
    let out = render_full(&scene, &camera, &s);
    let (mut bg, mut obj) = (Vec::new(), Vec::new());
    for (p, &n) in out.image.pixels.iter().zip(&out.spp) {
        if p.w == 0.0 {
            bg.push(n as f64);
        } else if p.w == 1.0 {
            obj.push(n as f64);
        }
    }
    assert!(
        bg.len() > 50 && obj.len() > 50,
        "{} {}",
        bg.len(),
        obj.len()
    );
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    assert!(
        mean(&bg) * 2.0 < mean(&obj),
        "background {} spp, object {} spp",
        mean(&bg),
        mean(&obj)
    );
}

/// `glint render` of the demo to `out` with `args`; panics with its stderr if it fails.
fn glint_render_demo(out: &Path, args: &[&str]) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(["render", demo().to_str().unwrap(), "-o"])
        .arg(out)
        .args(args)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn cli_writes_the_spp_map_and_honours_a_time_budget() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("spp.exr");
    let adaptive: Vec<&str> = "--width 32 --height 24 --adaptive --min-spp 4 --max-spp 32 \
                               --target-error 0.05 --sampler stratified --filter tent"
        .split_whitespace()
        .collect();
    let mut args = adaptive.clone();
    args.extend(["--spp-map", map.to_str().unwrap()]);
    glint_render_demo(&dir.path().join("a.exr"), &args);
    let spp = glint::film::read_exr(&map).unwrap();
    assert!(spp.pixels.iter().all(|p| p.x >= 4.0 && p.x <= 32.0));
    // `--aov spp` puts the same counts into the output's `spp.count` channel.
    let mut args = adaptive.clone();
    args.extend(["--aov", "spp"]);
    glint_render_demo(&dir.path().join("b.exr"), &args);
    let counts = glint::film::layers::read_channel(&dir.path().join("b.exr"), "spp.count")
        .unwrap()
        .unwrap();
    let want: Vec<f32> = spp.pixels.iter().map(|p| p.x).collect();
    assert_eq!(counts, want);
    // ... and beside a PNG output, as `.spp.png`.
    let mut args = adaptive.clone();
    args.extend(["--aov", "spp"]);
    glint_render_demo(&dir.path().join("c.png"), &args);
    assert!(dir.path().join("c.spp.png").is_file());
    let png = dir.path().join("t.png");
    glint_render_demo(
        &png,
        &["--width", "16", "--height", "12", "--time", "300ms"],
    );
    assert!(png.is_file());
}
