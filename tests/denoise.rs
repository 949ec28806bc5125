//! Denoising end to end (`denoise` feature): a denoised noisy render of the demo is closer to a converged
//! reference than the raw one; `glint render --denoise` and `glint turntable --denoise` write images.
#![cfg(feature = "denoise")]

mod common;

use std::process::Command;

use glint::accel::{self, Backend};
use glint::film::denoise::{DenoiseOptions, Denoiser};
use glint::render::{self, RenderSettings};

#[test]
fn a_denoised_noisy_render_is_closer_to_the_reference_than_the_raw_one() {
    let (w, h) = (64, 48);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/demo/demo.glb");
    let (scene, camera) = common::load_for_render(&path, w, h);
    let accel = accel::build(scene.clone(), Backend::Bvh).unwrap();
    let render = |spp: u32, seed: u64| {
        let s = RenderSettings {
            width: w,
            height: h,
            spp,
            seed,
            feature_images: true,
            ..Default::default()
        };
        let hidden = indicatif::ProgressBar::hidden();
        render::render_full(&scene, accel.as_ref(), &camera, &s, &hidden)
    };
    let reference = render(256, 11).image;
    let noisy = render(4, 1);
    // The guides know how many samples they average (what the default guide mode decides by).
    assert_eq!(noisy.features.as_ref().map(|f| f.min_spp), Some(4));
    let d = Denoiser::new(2, DenoiseOptions::default()).unwrap();
    let guides = noisy.features.as_ref().map(|f| f.guides());
    let denoised = d.denoise(&noisy.image, guides).unwrap();
    let plain = d.denoise(&noisy.image, None).unwrap();
    let (raw, den, col) = (
        noisy.image.rel_mse(&reference),
        denoised.rel_mse(&reference),
        plain.rel_mse(&reference),
    );
    eprintln!("relMSE raw 4 spp {raw:.4e}, denoised with guides {den:.4e}, colour only {col:.4e}");
    assert!(den < raw / 2.0, "denoised {den} vs raw {raw}");
    assert!(col < raw, "colour-only denoised {col} vs raw {raw}");
}

#[test]
fn render_and_turntable_write_denoised_images() {
    let dir = tempfile::tempdir().unwrap();
    let glint = || {
        let mut c = Command::new(env!("CARGO_BIN_EXE_glint"));
        c.current_dir(env!("CARGO_MANIFEST_DIR"));
        c
    };
    let out = dir.path().join("d.exr");
    let o = glint()
        .args([
            "render",
            "assets/demo/demo.glb",
            "--width",
            "32",
            "--height",
            "24",
        ])
        .args([
            "--spp",
            "2",
            "--quiet",
            "--denoise",
            "--aov",
            "beauty-raw,albedo",
        ])
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let ch = |n: &str| glint::film::layers::read_channel(&out, n).unwrap().unwrap();
    // The beauty is the denoised one, `raw.*` the render: they differ, both finite.
    let (r, raw) = (ch("R"), ch("raw.R"));
    assert!(r.iter().chain(&raw).all(|v| v.is_finite()));
    assert_ne!(r, raw);
    let frames = dir.path().join("frames");
    let o = glint()
        .args([
            "turntable",
            "assets/demo/demo.glb",
            "--frames",
            "2",
            "--width",
            "16",
        ])
        .args(["--height", "12", "--spp", "2", "--quiet", "--denoise", "-o"])
        .arg(&frames)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(frames.join("frame_0000.png").is_file() && frames.join("frame_0001.png").is_file());
}
