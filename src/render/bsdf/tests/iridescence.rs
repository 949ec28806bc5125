//! KHR_materials_iridescence's tests: the thin-film Fresnel against the extension's formulas, the
//! film's vanishing limit, chi-square over thicknesses, film IORs and roughnesses, reciprocity and
//! white furnaces.

use std::f64::consts::PI;

use glam::{DVec3, Vec2, Vec3};

use super::{chi_square, hash, spec_specular_brdf};
use crate::geometry::Frame;
use crate::render::bsdf::{Bsdf, Iridescence};

fn film(factor: f32, ior: f32, thickness: f32) -> Iridescence {
    Iridescence {
        factor,
        ior,
        thickness,
        outside_ior: 1.0,
    }
}

/// The extension's implementation notes (evalIridescence, evalSensitivity), line by line, in f64
/// and with OPD from the refracted cosine as the Sample Viewer has it.
fn spec_iridescence(outside: f64, eta2: f64, cos1: f64, d: f64, f0: DVec3) -> DVec3 {
    let sq = |x: f64| x * x;
    let smooth = {
        let t = (d / 0.03).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    };
    let ior = outside + (eta2 - outside) * smooth;
    let sin2 = sq(outside / ior) * (1.0 - sq(cos1));
    if 1.0 - sin2 < 0.0 {
        return DVec3::ONE;
    }
    let cos2 = (1.0 - sin2).sqrt();
    let f_schlick = |f0: f64, c: f64| f0 + (1.0 - f0) * (1.0 - c).powi(5);
    let ior_to_f0 = |t: f64, i: f64| sq((t - i) / (t + i));
    let r12 = f_schlick(ior_to_f0(ior, outside), cos1);
    let t121 = 1.0 - r12;
    let phi12 = if ior < outside { PI } else { 0.0 };
    let phi21 = PI - phi12;
    let f0 = f0.clamp(DVec3::ZERO, DVec3::splat(0.9999));
    let base = (DVec3::ONE + f0.map(f64::sqrt)) / (DVec3::ONE - f0.map(f64::sqrt));
    let r23 = base.map(|b| f_schlick(ior_to_f0(b, ior), cos2));
    let phi23 = base.map(|b| if b < ior { PI } else { 0.0 });
    let opd = 2.0 * ior * d * cos2;
    let phi = DVec3::splat(phi21) + phi23;
    let r123 = (r12 * r23).clamp(DVec3::splat(1e-5), DVec3::splat(0.9999));
    let r123s = r123.map(f64::sqrt);
    let rs = sq(t121) * r23 / (DVec3::ONE - r123);
    let mut i = r12 + rs;
    let mut cm = rs - t121;
    for m in 1..=2 {
        cm *= r123s;
        let (opd, shift) = (m as f64 * opd, m as f64 * phi);
        let phase = 2.0 * PI * opd * 1.0e-9;
        let val = DVec3::new(5.4856e-13, 4.4201e-13, 5.2481e-13);
        let pos = DVec3::new(1.6810e+06, 1.7953e+06, 2.2084e+06);
        let var = DVec3::new(4.3278e+09, 9.3046e+09, 6.6121e+09);
        let mut xyz = val
            * (2.0 * PI * var).map(f64::sqrt)
            * (pos * phase + shift).map(f64::cos)
            * (-sq(phase) * var).map(f64::exp);
        xyz.x += 9.7470e-14
            * (2.0 * PI * 4.5282e+09f64).sqrt()
            * (2.2399e+06 * phase + shift.x).cos()
            * (-4.5282e+09 * sq(phase)).exp();
        xyz /= 1.0685e-7;
        let rgb = DVec3::new(
            3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
            -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
            0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z,
        );
        i += cm * 2.0 * rgb;
    }
    // glint also clamps at 1 (a reflectance); the spec clamps only below.
    i.clamp(DVec3::ZERO, DVec3::ONE)
}

/// The film's Fresnel against the transcription at random cosines, thicknesses, IORs and bases.
#[test]
fn thin_film_fresnel_matches_the_spec() {
    for k in 0..2000u32 {
        let cos = hash(7 * k + 1).max(1e-3);
        let d = 50.0 + 1150.0 * hash(7 * k + 2);
        let ior = 1.0 + 1.5 * hash(7 * k + 3);
        let f0 = Vec3::new(hash(7 * k + 4), hash(7 * k + 5), hash(7 * k + 6)) * 0.9;
        let got = film(1.0, ior, d).fresnel(cos, f0);
        let want = spec_iridescence(1.0, ior as f64, cos as f64, d as f64, f0.as_dvec3());
        let err = (got.as_dvec3() - want).abs().max_element();
        assert!(
            err < 1e-4,
            "cos {cos} d {d} ior {ior} f0 {f0}: {got} vs {want}"
        );
    }
}

/// As the film vanishes its reflectance at normal incidence becomes the base's F0 (to the extension's
/// 1e-5 floor on R12 R23, which keeps a trace of the interference terms). Away from the normal the
/// extension's Schlick R12 = (1 - cos)^5 stays even for a vanished film, so only cos 1 is checked.
#[test]
fn vanishing_film_is_the_plain_fresnel() {
    let f0 = Vec3::new(0.04, 0.5, 0.9);
    let got = film(1.0, 1.6, 1e-4).fresnel(1.0, f0);
    assert!((got - f0).abs().max_element() < 1e-2, "{got} vs {f0}");
}

/// A metal's eval with a film is the spec's specular BRDF with F = mix(F_schlick, F_iridescence,
/// factor), at random directions, within 1e-4.
#[test]
fn iridescent_metal_eval_matches_the_spec() {
    let n = Vec3::new(0.2, 0.1, 0.97).normalize();
    let frame = Frame::from_normal(n);
    let base = Vec3::new(0.9, 0.6, 0.3);
    let (factor, ior, d, rough) = (0.8f32, 1.4f32, 380.0f32, 0.45f32);
    let mut b = Bsdf::new(frame, base, 1.0, rough, 1.0);
    b.iridescence = Some(film(factor, ior, d));
    for k in 0..1000 {
        let dir = |a: u32| {
            let z = hash(a).max(0.02);
            let phi = 2.0 * std::f32::consts::PI * hash(a + 1);
            let r = (1.0 - z * z).sqrt();
            frame.to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z))
        };
        let (v, l) = (dir(10 * k + 100), dir(10 * k + 103));
        let vh = v.dot((v + l).normalize()) as f64;
        let schlick = base.as_dvec3() + (DVec3::ONE - base.as_dvec3()) * (1.0 - vh).powi(5);
        let irid = spec_iridescence(1.0, ior as f64, vh, d as f64, base.as_dvec3());
        let f = schlick.lerp(irid, factor as f64);
        let spec = f * spec_specular_brdf(n, v, l, rough * rough) as f64;
        let got = b.eval(v, l).0.as_dvec3();
        let err = ((got - spec).abs() / spec.max(DVec3::splat(1e-3))).max_element();
        assert!(err < 1e-4, "v {v} l {l}: eval {got} vs spec {spec} ({err})");
    }
}

/// Sampling follows eval's pdf with a film on dielectric and metal bases, over film thicknesses,
/// film IORs and roughnesses.
#[test]
fn iridescent_sampling_passes_chi_square() {
    let frame = Frame::from_normal(Vec3::new(0.1, -0.2, 0.95).normalize());
    let tint = Vec3::new(0.8, 0.5, 0.3);
    for (metallic, rough, ior, d) in [
        (0.0, 0.3, 1.3, 150.0),
        (0.0, 0.6, 1.8, 400.0),
        (0.0, 0.4, 2.2, 800.0),
        (1.0, 0.3, 1.5, 300.0),
        (0.5, 0.5, 1.3, 600.0),
    ] {
        let mut b = Bsdf::new(frame, tint, metallic, rough, 1.0);
        b.iridescence = Some(film(1.0, ior, d));
        for wo in [Vec3::new(0.3, 0.1, 0.9), Vec3::new(0.9, 0.2, 0.2)] {
            let wo = frame.to_world(wo.normalize());
            let p = chi_square(&b, wo, 400_000);
            eprintln!(
                "chi-square iridescence metallic {metallic} roughness {rough} film ior {ior} \
                 thickness {d} wo.z {:.2}: p = {p:.3}",
                frame.to_local(wo).z
            );
            assert!(p > 1e-3, "chi-square p-value {p}");
        }
    }
}

/// The film's Fresnel is symmetric in the two directions (it depends on V.H = L.H), so reflection
/// stays reciprocal.
#[test]
fn iridescent_reflection_is_reciprocal() {
    let frame = Frame::from_normal(Vec3::new(0.1, -0.2, 1.0).normalize());
    let mut b = Bsdf::new(frame, Vec3::new(0.7, 0.6, 0.2), 0.3, 0.4, 1.0);
    b.iridescence = Some(film(1.0, 1.6, 500.0));
    for k in 0..200 {
        let dir = |a: u32| {
            let z = hash(a).max(0.02);
            let phi = 2.0 * std::f32::consts::PI * hash(a + 1);
            let r = (1.0 - z * z).sqrt();
            frame.to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z))
        };
        let (o, i) = (dir(4 * k + 11), dir(4 * k + 13));
        let (x, y) = (b.eval(o, i).0, b.eval(i, o).0);
        assert!((x - y).abs().max_element() <= 1e-5 * x.max_element().max(1e-3));
    }
}

/// The albedo per channel (mean of f cos / pdf) at `wo`: a coloured film's channels peak in
/// different directions, so the mean of each sample's largest channel would overstate it.
fn albedo_rgb(bsdf: &Bsdf, wo: Vec3, n: u32) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for k in 0..n {
        let u = glam::Vec2::new(hash(3 * k + 1), hash(3 * k + 2));
        if let Some(s) = bsdf.sample(wo, hash(3 * k), u) {
            sum += (s.f * s.wi.dot(bsdf.frame.n).abs() / s.pdf).as_dvec3();
        }
    }
    sum / n as f64
}

/// White furnace. A white metal under a film reflects at most 1 in every channel from every view. A
/// white dielectric follows the glTF spec's fresnel_mix at the half vector (diffuse times
/// 1 - F(V.H)), which gains energy at grazing views with or without a film; there the film is held
/// to the plain model's figures plus what its oscillating F adds (within 0.1). Figures printed.
#[test]
fn iridescent_white_furnace_reflects_at_most_one() {
    let frame = Frame::from_normal(Vec3::Z);
    for (metallic, rough, d) in [(1.0, 0.3, 300.0), (0.0, 0.3, 300.0), (0.0, 0.7, 700.0)] {
        let plain = Bsdf::new(frame, Vec3::ONE, metallic, rough, 1.0);
        let mut b = plain;
        b.iridescence = Some(film(1.0, 1.8, d));
        let mut figures = Vec::new();
        for cos in [1.0f32, 0.7, 0.4, 0.15] {
            let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            let a = albedo_rgb(&b, wo, 200_000);
            let p = albedo_rgb(&plain, wo, 200_000).max_element();
            figures.push(format!("{cos}: {:.4} (plain {p:.4})", a.max_element()));
            let bound = if metallic == 1.0 {
                1.0 + 5e-3
            } else {
                p.max(1.0) + 0.1
            };
            assert!(
                a.max_element() < bound,
                "metallic {metallic} cos {cos}: {a}"
            );
            assert!(a.min_element() > 0.3, "metallic {metallic} cos {cos}: {a}");
        }
        eprintln!(
            "furnace iridescence metallic {metallic} roughness {rough} thickness {d}: {}",
            figures.join(", ")
        );
    }
}

/// A smooth thin wall with a film absorbs nothing: per channel, what the film reflects and what
/// passes straight through add up to 1 at every angle (the film's colours in reflection and their
/// complement in transmission), by straight_transmittance and by sampling both delta lobes.
#[test]
fn iridescent_thin_wall_reflects_and_transmits_every_channel_wholly() {
    let frame = Frame::from_normal(Vec3::Z);
    for (factor, d) in [(1.0, 400.0), (0.6, 250.0), (1.0, 900.0)] {
        let mut b =
            Bsdf::new(frame, Vec3::ONE, 0.0, 0.0, 1.0).with_dielectric(1.0, 1.5, true, false);
        b.iridescence = Some(film(factor, 1.33, d));
        for cos in [1.0f32, 0.8, 0.5, 0.2] {
            let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            let (mut reflected, mut through) = (None, None);
            for k in 0..200 {
                let Some(s) = b.sample(wo, hash(k), Vec2::ZERO) else {
                    continue;
                };
                assert!(s.delta);
                let lobes = b.lobes(cos);
                let (p, slot) = if s.wi.z > 0.0 {
                    (lobes.reflect, &mut reflected)
                } else {
                    (lobes.transmit, &mut through)
                };
                *slot = Some(s.f * s.wi.z.abs() / s.pdf * p);
            }
            let (r, t) = (reflected.unwrap(), through.unwrap());
            let straight = b.straight_transmittance(wo);
            assert!(
                (straight - t).abs().max_element() < 1e-5,
                "{straight} vs {t}"
            );
            let sum = r + t;
            assert!(
                (sum - Vec3::ONE).abs().max_element() < 1e-5,
                "factor {factor} thickness {d} cos {cos}: reflected {r} + through {t} = {sum}"
            );
            // The film colours it: the channels differ (what a scalar 1 - max F would lose).
            assert!(r.max_element() - r.min_element() > 1e-3, "{r}");
        }
    }
}
