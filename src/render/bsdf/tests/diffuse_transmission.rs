//! KHR_materials_diffuse_transmission's tests: chi-square of the base and layered material with the
//! Lambertian BTDF over a grid of factors, roughnesses and thin/thick walls, the white furnace, and
//! eval against the extension's dielectric_brdf transcribed.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::super::fresnel::fresnel_exact;
use super::{albedos, chi_square, hash, white_lambert, with_coat, with_sheen};
use crate::geometry::Frame;
use crate::render::bsdf::{Bsdf, DiffuseTransmission};

/// A dielectric base with diffuse transmission (`thin`: no volume; else entering a volume).
fn translucent(frame: Frame, roughness: f32, factor: f32, color: Vec3, thin: bool) -> Bsdf {
    let mut b = Bsdf::new(frame, Vec3::new(0.8, 0.6, 0.4), 0.0, roughness, 1.0);
    b.diffuse_transmission = Some(DiffuseTransmission::new(factor, color));
    b.with_dielectric(0.0, 1.5, thin, true)
}

/// Sampled directions follow eval's pdf for the base with its BTDF alone, mixed with specular
/// transmission, and under a coat and a sheen, over factors, roughnesses, thin and thick walls.
#[test]
fn diffuse_transmission_passes_chi_square() {
    let frame = Frame::from_normal(Vec3::new(0.1, -0.2, 0.95).normalize());
    let color = Vec3::new(0.9, 0.3, 0.2);
    let mut cases = Vec::new();
    for factor in [0.25, 0.6, 1.0] {
        for r in [0.2, 0.7] {
            for thin in [true, false] {
                let b = translucent(frame, r, factor, color, thin);
                cases.push((format!("dt {factor} rough {r} thin {thin}"), b));
            }
            let b = translucent(frame, r, factor, color, true);
            cases.push((
                format!("dt {factor} rough {r} coated"),
                with_coat(b, 0.8, r),
            ));
            let sheen = with_sheen(b, Vec3::new(0.7, 0.7, 0.9), r + 0.2);
            cases.push((format!("dt {factor} rough {r} sheen"), sheen));
        }
        let mut mixed = translucent(frame, 0.5, factor, color, false);
        mixed.transmission = 0.5;
        cases.push((format!("dt {factor} + transmission 0.5"), mixed));
    }
    let mut ps = Vec::new();
    for (label, bsdf) in &cases {
        for wo in [Vec3::new(0.3, 0.1, 0.9), Vec3::new(0.9, 0.2, 0.2)] {
            let wo = frame.to_world(wo.normalize());
            let p = chi_square(bsdf, wo, 200_000);
            assert!(p > 1e-3, "{label}: chi-square p-value {p}");
            ps.push(p);
        }
    }
    let (lo, hi) = ps
        .iter()
        .fold((1.0f64, 0.0f64), |(a, b), &p| (a.min(p), b.max(p)));
    eprintln!(
        "chi-square diffuse transmission: {} cases, p in [{lo:.3}, {hi:.3}]",
        ps.len()
    );
}

/// Importance-sampled albedo equals uniform integration of eval over the whole sphere.
#[test]
fn diffuse_transmission_albedo_matches_uniform_integration() {
    let frame = Frame::from_normal(Vec3::new(0.2, 0.3, 0.9).normalize());
    for (factor, r, thin) in [(0.5, 0.4, true), (1.0, 0.8, false), (0.3, 0.2, false)] {
        let b = translucent(frame, r, factor, Vec3::new(0.5, 0.9, 0.7), thin);
        let wo = frame.to_world(Vec3::new(0.5, 0.1, 0.6).normalize());
        let (is, uni) = albedos(&b, wo, 400_000);
        assert!(
            (is - uni).abs() < 0.015 * uni,
            "factor {factor} rough {r} thin {thin}: sampled {is} vs uniform {uni}"
        );
    }
}

/// Reflected and transmitted albedo (max channel) of `b` at `wo`, by sampling.
fn split_albedo(b: &Bsdf, wo: Vec3, n: u32) -> (f64, f64) {
    let (mut r, mut t) = (0.0f64, 0.0f64);
    for k in 0..n {
        let u = Vec2::new(hash(3 * k + 1), hash(3 * k + 2));
        if let Some(s) = b.sample(wo, hash(3 * k), u) {
            let w = (s.f.max_element() * s.wi.z.abs() / s.pdf) as f64;
            if s.wi.z > 0.0 {
                r += w;
            } else {
                t += w;
            }
        }
    }
    (r / n as f64, t / n as f64)
}

/// White furnace: a white, non-absorbing Lambert base (no specular layer) gives reflection plus
/// transmission of exactly 1, split (1 - factor, factor). With the specular layer on, diffuse
/// transmission only moves light: R + T equals the same material's R without it (whatever the
/// glTF base itself loses or gains), and T grows linearly with the factor; thin or into a volume.
#[test]
fn white_furnace_diffuse_transmission_sums_to_one() {
    let frame = Frame::from_normal(Vec3::Z);
    let n = 100_000;
    for cos in [1.0f32, 0.6, 0.2] {
        let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
        for factor in [0.5f32, 1.0] {
            let mut b = white_lambert(frame);
            b.diffuse_transmission = Some(DiffuseTransmission::new(factor, Vec3::ONE));
            let b = b.with_dielectric(0.0, 1.5, true, true);
            let (r, t) = split_albedo(&b, wo, n);
            eprintln!(
                "furnace diffuse transmission {factor} (no specular) cos {cos}: R {r:.4} T {t:.4}"
            );
            assert!(
                (r + t - 1.0).abs() < 2e-3,
                "factor {factor} cos {cos}: {r} + {t}"
            );
            assert!(
                (t - factor as f64).abs() < 1e-2,
                "factor {factor} cos {cos}: T {t}"
            );
        }
        for thin in [true, false] {
            let plain =
                Bsdf::new(frame, Vec3::ONE, 0.0, 0.5, 1.0).with_dielectric(0.0, 1.5, thin, true);
            let (r0, _) = split_albedo(&plain, wo, n);
            let [(rh, th), (r1, t1)] = [0.5, 1.0].map(|factor| {
                let mut b = Bsdf::new(frame, Vec3::ONE, 0.0, 0.5, 1.0);
                b.diffuse_transmission = Some(DiffuseTransmission::new(factor, Vec3::ONE));
                split_albedo(&b.with_dielectric(0.0, 1.5, thin, true), wo, n)
            });
            eprintln!(
                "furnace specular 1 rough 0.5 thin {thin} cos {cos}: without R {r0:.4}; \
                 factor 0.5 R {rh:.4} T {th:.4}; factor 1 R {r1:.4} T {t1:.4}"
            );
            let label = format!("thin {thin} cos {cos}");
            assert!((rh + th - r0).abs() < 5e-3, "{label}: {rh} + {th} vs {r0}");
            assert!((r1 + t1 - r0).abs() < 5e-3, "{label}: {r1} + {t1} vs {r0}");
            assert!((th - 0.5 * t1).abs() < 5e-3, "{label}: T {th} vs {t1} / 2");
            assert!(t1 > 0.5, "{label}: T {t1}");
        }
    }
}

/// eval against the extension's dielectric_brdf, fresnel_mix(specular_brdf, mix(diffuse_brdf,
/// diffuse_btdf, factor)), with glint's Fresnel (exact, at V.H, H for the transmitted side from L
/// mirrored up), at random directions on both sides, within 1e-4.
#[test]
fn diffuse_transmission_eval_matches_the_spec() {
    let n = Vec3::new(0.2, -0.1, 0.97).normalize();
    let frame = Frame::from_normal(n);
    let (base, color, factor, rough) =
        (Vec3::new(0.6, 0.4, 0.2), Vec3::new(0.3, 0.8, 0.5), 0.7, 0.4);
    let b = translucent(frame, rough, factor, color, true);
    let b = Bsdf { base, ..b };
    let alpha = rough * rough;
    for k in 0..2000 {
        let dir = |a: u32, below: bool| {
            let z = hash(a).max(0.02);
            let phi = 2.0 * PI * hash(a + 1);
            let r = (1.0 - z * z).sqrt();
            let z = if below { -z } else { z };
            frame.to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z))
        };
        let below = k % 2 == 1;
        let (v, l) = (dir(10 * k + 100, false), dir(10 * k + 103, below));
        let l_up = if below { l - 2.0 * n.dot(l) * n } else { l };
        let h = (v + l_up).normalize();
        let f = fresnel_exact(v.dot(h), 1.5);
        let spec = if below {
            Vec3::ZERO
        } else {
            Vec3::splat(f * super::spec_specular_brdf(n, v, l, alpha))
        };
        let diffuse = if below {
            color * factor / PI
        } else {
            base * (1.0 - factor) / PI
        };
        let want = spec + diffuse * (1.0 - f);
        let got = b.eval(v, l).0;
        let err = ((got - want).abs() / want.max(Vec3::splat(1e-3))).max_element();
        assert!(err < 1e-4, "v {v} l {l}: eval {got} vs spec {want} ({err})");
    }
}

/// A material without the extension has no BTDF below a Lambert base; a factor of 0 (which the
/// loader drops) and none give the same values.
#[test]
fn diffuse_transmission_transmits_and_only_when_on() {
    let frame = Frame::from_normal(Vec3::Z);
    let plain = Bsdf::new(frame, Vec3::ONE, 0.0, 0.5, 1.0).with_dielectric(0.0, 1.5, true, true);
    assert!(!plain.transmits());
    let on = translucent(frame, 0.5, 1.0, Vec3::ONE, true);
    assert!(on.transmits() && on.thin);
    let thick = translucent(frame, 0.5, 1.0, Vec3::ONE, false);
    assert!(thick.transmits() && !thick.thin);
    let (o, i) = (
        Vec3::new(0.3, 0.0, 0.95).normalize(),
        Vec3::new(0.1, 0.2, -0.9).normalize(),
    );
    assert_eq!(plain.eval(o, i).0, Vec3::ZERO);
    assert!(on.eval(o, i).0.min_element() > 0.0);
    // Shadow rays do not see straight through a diffuse transmitter (it scatters).
    assert_eq!(on.straight_transmittance(o), Vec3::ZERO);
}
