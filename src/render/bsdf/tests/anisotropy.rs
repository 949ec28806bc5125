//! KHR_materials_anisotropy's tests: chi-square of the anisotropic visible-normal sampling over
//! strengths, rotations and roughnesses, reciprocity, the white furnace and the spec's formulas.

use std::f32::consts::PI;

use glam::Vec3;

use super::super::microfacet::Ggx;
use super::{albedo, albedos, chi_square, hash};
use crate::geometry::Frame;
use crate::render::bsdf::Bsdf;

/// A tangent in the plane of `frame`, turned by `angle` from its own tangent.
fn turned(frame: &Frame, angle: f32) -> Vec3 {
    frame.t * angle.cos() + frame.b * angle.sin()
}

/// Sampled directions follow the pdf eval reports, for anisotropic metal, dielectric and rough
/// glass, over strengths, tangent rotations, roughnesses and views. (Bitangent alphas under about
/// 0.04 make lobes narrower than the cells' 24 x 24 pdf integration resolves.)
#[test]
fn anisotropic_sampling_passes_chi_square() {
    let frame = Frame::from_normal(Vec3::new(0.1, -0.2, 0.95).normalize());
    let tint = Vec3::new(0.8, 0.5, 0.3);
    let mut cases = Vec::new();
    for (strength, angle, rough) in [
        (0.3, 0.0, 0.3),
        (0.7, 0.6, 0.3),
        (1.0, 1.2, 0.3),
        (0.9, 2.5, 0.2),
        (0.5, -0.8, 0.7),
    ] {
        let t = turned(&frame, angle);
        let label = format!("strength {strength} angle {angle} roughness {rough}");
        let metal = Bsdf::new(frame, tint, 1.0, rough, 1.0).with_anisotropy(strength, t);
        cases.push((format!("metal {label}"), metal));
        let plastic = Bsdf::new(frame, tint, 0.0, rough, 1.0).with_anisotropy(strength, t);
        cases.push((format!("dielectric {label}"), plastic));
    }
    let glass = Bsdf::new(frame, Vec3::ONE, 0.0, 0.5, 1.0)
        .with_dielectric(1.0, 1.5, false, true)
        .with_anisotropy(0.8, turned(&frame, 0.4));
    cases.push(("rough glass strength 0.8".into(), glass));
    for (label, bsdf) in &cases {
        for wo in [Vec3::new(0.3, 0.1, 0.9), Vec3::new(0.9, 0.2, 0.2)] {
            let wo = bsdf.frame.to_world(wo.normalize());
            let p = chi_square(bsdf, wo, 400_000);
            eprintln!(
                "chi-square anisotropic {label} wo.z {:.2}: p = {p:.3}",
                bsdf.frame.to_local(wo).z
            );
            assert!(p > 1e-3, "{label}: chi-square p-value {p}");
        }
    }
}

/// The albedo by importance sampling equals uniform integration of eval (pdf and sample agree).
#[test]
fn anisotropic_sampled_albedo_matches_uniform_integration() {
    let frame = Frame::from_normal(Vec3::new(0.2, 0.3, 0.9).normalize());
    for (metallic, rough, strength) in [
        (1.0, 0.2, 0.6),
        (0.0, 0.4, 1.0),
        (1.0, 0.6, 0.9),
        (1.0, 0.3, 1.0),
    ] {
        let b = Bsdf::new(frame, Vec3::new(0.8, 0.5, 0.3), metallic, rough, 1.0)
            .with_anisotropy(strength, turned(&frame, 0.7));
        for wo in [Vec3::new(0.5, 0.1, 0.6), Vec3::new(0.1, 0.9, 0.2)] {
            let wo = b.frame.to_world(wo.normalize());
            let (is, uni) = albedos(&b, wo, 1_000_000);
            assert!(
                (is - uni).abs() < 0.015 * uni.max(0.05),
                "metallic {metallic} roughness {rough} strength {strength}: {is} vs {uni}"
            );
        }
    }
}

/// Anisotropic reflection is reciprocal: f(o, i) = f(i, o).
#[test]
fn anisotropic_reflection_is_reciprocal() {
    let frame = Frame::from_normal(Vec3::new(0.1, -0.2, 1.0).normalize());
    let b = Bsdf::new(frame, Vec3::new(0.7, 0.6, 0.2), 0.4, 0.3, 1.0)
        .with_anisotropy(0.8, turned(&frame, 0.3));
    for k in 0..200 {
        let dir = |a: u32| {
            let z = hash(a).max(0.02);
            let phi = 2.0 * PI * hash(a + 1);
            let r = (1.0 - z * z).sqrt();
            b.frame.to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z))
        };
        let (o, i) = (dir(4 * k + 11), dir(4 * k + 13));
        let (a, c) = (b.eval(o, i).0, b.eval(i, o).0);
        assert!(
            (a - c).abs().max_element() <= 1e-5 * a.max_element().max(1e-3),
            "{a} vs {c}"
        );
    }
}

/// White furnace: a white anisotropic metal (F = 1) reflects at most 1 from every view; what it
/// loses is single-scattering GGX's masking, which grows with the tangent's alpha (up to about
/// half at strength 1, where the surface is a field of alpha-1 grooves); the figures are printed.
#[test]
fn anisotropic_white_furnace_reflects_at_most_one() {
    let frame = Frame::from_normal(Vec3::Z);
    for (rough, strength) in [(0.0, 1.0), (0.3, 0.5), (0.3, 1.0), (0.7, 1.0)] {
        let b = Bsdf::new(frame, Vec3::ONE, 1.0, rough, 1.0).with_anisotropy(strength, Vec3::X);
        let mut figures = Vec::new();
        for cos in [1.0f32, 0.7, 0.4, 0.15] {
            for phi in [0.0f32, 1.0] {
                let s = (1.0 - cos * cos).sqrt();
                let wo = Vec3::new(s * phi.cos(), s * phi.sin(), cos);
                let a = albedo(&b, wo, 200_000);
                figures.push(format!("{cos}/{phi}: {a:.4}"));
                assert!(a < 1.0 + 5e-3, "roughness {rough} strength {strength}: {a}");
                assert!(a > 0.4, "roughness {rough} strength {strength}: {a}");
            }
        }
        eprintln!(
            "furnace anisotropic metal roughness {rough} strength {strength} (cos/phi): {}",
            figures.join(", ")
        );
    }
}

/// KHR_materials_anisotropy's BRDF_specularAnisotropicGGX, line by line (F is the metal's Schlick).
fn spec_anisotropic_ggx(f: Frame, v: Vec3, l: Vec3, alpha: f32, strength: f32) -> f32 {
    let h = (v + l).normalize();
    let at = alpha * (1.0 - strength * strength) + strength * strength;
    let ab = alpha;
    let (nl, nv, nh) = (f.n.dot(l), f.n.dot(v), f.n.dot(h));
    let (tv, bv, tl, bl, th, bh) = (
        f.t.dot(v),
        f.b.dot(v),
        f.t.dot(l),
        f.b.dot(l),
        f.t.dot(h),
        f.b.dot(h),
    );
    let ggxv = nl * Vec3::new(at * tv, ab * bv, nv).length();
    let ggxl = nv * Vec3::new(at * tl, ab * bl, nl).length();
    let vis = (0.5 / (ggxv + ggxl)).clamp(0.0, 1.0);
    let a2 = at * ab;
    let ff = Vec3::new(ab * th, at * bh, a2 * nh);
    let w2 = a2 / ff.dot(ff);
    let d = a2 * w2 * w2 / PI;
    if 0.5 / (ggxv + ggxl) > 1.0 {
        return f32::NAN;
    }
    vis * d
}

/// eval of an anisotropic metal against the spec's formulas at random directions, within 1e-4.
/// The spec clamps V to at most 1 (a rasteriser's guard at grazing angles that glint does not
/// copy: it would cut energy the sampler accounts for), so pairs where it bites are left out.
#[test]
fn anisotropic_eval_matches_the_spec_formulas() {
    let frame = Frame::from_normal(Vec3::new(0.2, 0.1, 0.97).normalize());
    let base = Vec3::new(0.9, 0.6, 0.3);
    for (rough, strength, angle) in [(0.4f32, 0.6f32, 0.3f32), (0.2, 1.0, -1.1), (0.7, 0.3, 2.0)] {
        let b = Bsdf::new(frame, base, 1.0, rough, 1.0)
            .with_anisotropy(strength, turned(&frame, angle));
        // The tangent frame the spec's TBN and direction give.
        let t = turned(&frame, angle);
        let f = Frame {
            t,
            b: frame.n.cross(t),
            n: frame.n,
        };
        let mut checked = 0;
        for k in 0..1000 {
            let dir = |a: u32| {
                let z = hash(a).max(0.02);
                let phi = 2.0 * PI * hash(a + 1);
                let r = (1.0 - z * z).sqrt();
                frame.to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z))
            };
            let (v, l) = (dir(10 * k + 100), dir(10 * k + 103));
            let vh = v.dot((v + l).normalize());
            let fresnel = base + (Vec3::ONE - base) * (1.0 - vh).powi(5);
            let spec = fresnel * spec_anisotropic_ggx(f, v, l, rough * rough, strength);
            if spec.is_nan() {
                continue;
            }
            checked += 1;
            let got = b.eval(v, l).0;
            let err = ((got - spec).abs() / spec.max(Vec3::splat(1e-3))).max_element();
            assert!(err < 1e-4, "v {v} l {l}: eval {got} vs spec {spec} ({err})");
        }
        assert!(checked > 300, "{checked} pairs checked");
    }
}

/// Strength 0 leaves the material exactly as it was; the anisotropic formulas at equal alphas
/// agree with the isotropic ones.
#[test]
fn zero_strength_is_isotropic() {
    let frame = Frame::from_normal(Vec3::new(0.3, 0.1, 0.9).normalize());
    let iso = Bsdf::new(frame, Vec3::new(0.5, 0.6, 0.7), 0.5, 0.4, 1.0);
    let zero = iso.with_anisotropy(0.0, Vec3::X);
    let (o, i) = (
        frame.to_world(Vec3::new(0.3, 0.2, 0.9).normalize()),
        frame.to_world(Vec3::new(-0.4, 0.1, 0.8).normalize()),
    );
    assert_eq!(iso.eval(o, i), zero.eval(o, i));
    let g = Ggx::iso(0.3);
    let stretched = Ggx {
        ax: 0.3,
        ay: 0.3 + 1e-7,
    };
    let h = Vec3::new(0.2, -0.3, 0.9).normalize();
    assert!((g.d(h) - stretched.d(h)).abs() < 1e-4 * g.d(h));
    assert!((g.g2(o, i) - stretched.g2(o, i)).abs() < 1e-5);
}
