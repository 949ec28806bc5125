use clap::ValueEnum;
use glam::Vec3;

use super::*;

/// A smooth picture (two ramps and a disc edge) and the same picture with per-pixel noise.
fn pictures(w: usize, h: usize, noise: f32) -> (Image, Image, Vec<Vec3>, Vec<Vec3>) {
    let mut clean = Image::new(w, h);
    let mut albedo = vec![Vec3::ZERO; w * h];
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut noisy = clean.clone();
    for y in 0..h {
        for x in 0..w {
            let (u, v) = (x as f32 / w as f32, y as f32 / h as f32);
            let inside = (u - 0.5).powi(2) + (v - 0.5).powi(2) < 0.09;
            let a = if inside {
                Vec3::new(0.8, 0.2, 0.1)
            } else {
                Vec3::splat(0.5)
            };
            let c = a * (0.3 + 0.7 * u);
            let i = y * w + x;
            clean.pixels[i] = c.extend(1.0);
            albedo[i] = a;
            // Uniform noise of the given relative amplitude from a 64-bit LCG.
            let mut r = || {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                ((state >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
            };
            let n = Vec3::new(r(), r(), r()) * noise;
            noisy.pixels[i] = (c * (Vec3::ONE + n)).max(Vec3::ZERO).extend(1.0);
        }
    }
    let normal = vec![Vec3::Z; w * h];
    (clean, noisy, albedo, normal)
}

#[test]
fn denoising_brings_a_noisy_picture_closer_to_the_clean_one() {
    let (clean, noisy, albedo, normal) = pictures(96, 64, 0.6);
    let guides = Some(Guides {
        albedo: &albedo,
        normal: &normal,
        samples: 4,
    });
    let mut outs = vec![Denoiser::new(2, DenoiseOptions::default())
        .unwrap()
        .denoise(&noisy, None)
        .unwrap()];
    for mode in GuideMode::value_variants() {
        let options = DenoiseOptions {
            guides: *mode,
            ..DenoiseOptions::default()
        };
        let d = Denoiser::new(2, options).unwrap();
        outs.push(d.denoise(&noisy, guides).unwrap());
    }
    let raw = noisy.rel_mse(&clean);
    for out in &outs {
        assert!(!out.has_non_finite());
        // Not black (a wrong format code would give zeros and no error but a device error).
        assert!(out.mean_rgb() > 0.5 * clean.mean_rgb());
        let e = out.rel_mse(&clean);
        assert!(e < raw / 4.0, "denoised relMSE {e} vs raw {raw}");
    }
    // The modes reach the library: declared-noisy and trusted guides pick different networks.
    let [_, auto, prefiltered, noisy_guides, trusted] = &outs[..] else {
        panic!("{} images", outs.len())
    };
    assert_ne!(noisy_guides.pixels, trusted.pixels);
    // Guides of 4 samples a pixel are prefiltered by default, of 64 trusted.
    assert_eq!(auto.pixels, prefiltered.pixels);
    let many = guides.map(|g| Guides {
        samples: TRUSTED_FROM_SPP,
        ..g
    });
    let auto = Denoiser::new(2, DenoiseOptions::default()).unwrap();
    assert_eq!(auto.denoise(&noisy, many).unwrap().pixels, trusted.pixels);
    // Alpha is kept.
    assert!(outs.iter().all(|o| o.pixels.iter().all(|p| p.w == 1.0)));
}

#[test]
fn guides_of_the_wrong_size_are_refused() {
    let (_, noisy, albedo, _) = pictures(8, 8, 0.1);
    let d = Denoiser::new(
        1,
        DenoiseOptions {
            quality: DenoiseQuality::Fast,
            ..DenoiseOptions::default()
        },
    )
    .unwrap();
    let short = vec![Vec3::Z; 3];
    let err = d
        .denoise(
            &noisy,
            Some(Guides {
                albedo: &albedo,
                normal: &short,
                samples: 1,
            }),
        )
        .err()
        .unwrap();
    assert!(err.to_string().contains("normal has 3 pixels"), "{err}");
}

#[test]
fn auto_guides_are_trusted_from_enough_samples() {
    use GuideMode::*;
    assert_eq!(Auto.resolve(TRUSTED_FROM_SPP - 1), Prefiltered);
    assert_eq!(Auto.resolve(TRUSTED_FROM_SPP), Trusted);
    for mode in [Prefiltered, Noisy, Trusted] {
        assert_eq!(mode.resolve(1), mode);
        assert_eq!(mode.resolve(1 << 20), mode);
    }
}
