//! The BSDF's tests: sampling against eval by albedo, energy, reciprocity and delta lobes of the
//! base; chi-square, furnace and spec transcriptions of the clearcoat, sheen and layered material
//! (and, in `tests/`, of each extension's own lobe).

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::fresnel::schlick;
use super::*;
use crate::geometry::Frame;
use crate::sample::chi_square::pearson_p_value;

mod anisotropy;
mod diffuse_transmission;
mod dispersion;
mod iridescence;
mod shading_model;

fn hash(i: u32) -> f32 {
    (crate::geometry::mix64(i as u64) >> 40) as f32 / (1u64 << 24) as f32
}

/// The albedo from `sample` against uniform integration of `eval` over the whole sphere, for one
/// BSDF and outgoing direction; returns (sampled, uniform).
fn albedos(bsdf: &Bsdf, wo: Vec3, n: u32) -> (f64, f64) {
    let mut is = 0.0f64;
    for k in 0..n {
        let u = Vec2::new(hash(3 * k + 1), hash(3 * k + 2));
        if let Some(s) = bsdf.sample(wo, hash(3 * k), u) {
            assert!(!s.delta);
            is += (luminance(s.f) * s.wi.dot(bsdf.frame.n).abs() / s.pdf) as f64;
        }
    }
    // Uniform over the sphere (pdf 1 / (4 pi)), jittered on a grid of strata in (z, phi) so
    // that the narrow rough lobes still converge.
    let m = (n as f64).sqrt() as u32;
    let mut uni = 0.0f64;
    for a in 0..m {
        for b in 0..m {
            let k = a * m + b;
            let z = 2.0 * (a as f32 + hash(2 * k + 5)) / m as f32 - 1.0;
            let phi = 2.0 * PI * (b as f32 + hash(2 * k + 6)) / m as f32;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let wi = bsdf
                .frame
                .to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z));
            uni += (luminance(bsdf.eval(wo, wi).0) * z.abs() * 4.0 * PI) as f64;
        }
    }
    (is / n as f64, uni / (m * m) as f64)
}

/// A surface that scatters nothing is exactly that: zero from `eval` and from `sample`, for
/// every pair of directions; black metal (Schlick's grazing reflection), a black dielectric with
/// a specular layer, a coat or a sheen over black, and black glass seen from inside (total
/// internal reflection) all scatter.
#[test]
fn black_surfaces_scatter_nothing_and_nothing_else_is_black() {
    let frame = Frame::from_normal(Vec3::new(0.1, -0.3, 0.9).normalize());
    for rough in [0.0, 0.5, 1.0] {
        let black = Bsdf::new(frame, Vec3::ZERO, 0.0, rough, 0.0);
        assert!(black.scatters_nothing());
        for k in 0..2000 {
            let dir = |a: u32| {
                let (z, phi) = (2.0 * hash(a) - 1.0, 2.0 * PI * hash(a + 1));
                let r = (1.0 - z * z).max(0.0).sqrt();
                Vec3::new(r * phi.cos(), r * phi.sin(), z)
            };
            let (wo, wi) = (dir(4 * k), dir(4 * k + 2));
            assert_eq!(black.eval(wo, wi).0, Vec3::ZERO, "{wo} {wi}");
            let u = Vec2::new(hash(9 * k + 7), hash(9 * k + 8));
            if let Some(s) = black.sample(wo, hash(9 * k + 6), u) {
                assert_eq!(s.f, Vec3::ZERO, "{wo}");
            }
        }
        let scattering = [
            Bsdf::new(frame, Vec3::ZERO, 1.0, rough, 0.0),
            Bsdf::new(frame, Vec3::ZERO, 0.0, rough, 1.0),
            with_coat(Bsdf::new(frame, Vec3::ZERO, 0.0, rough, 0.0), 1.0, 0.3),
            with_sheen(
                Bsdf::new(frame, Vec3::ZERO, 0.0, rough, 0.0),
                Vec3::ONE,
                0.5,
            ),
            Bsdf::new(frame, Vec3::ZERO, 0.0, rough, 0.0).with_dielectric(1.0, 1.5, false, false),
            Bsdf::new(frame, Vec3::splat(0.01), 0.0, rough, 0.0),
        ];
        for (i, b) in scattering.iter().enumerate() {
            assert!(!b.scatters_nothing(), "surface {i}, roughness {rough}");
        }
    }
}

/// The albedo estimated by importance sampling must equal the one from uniform sampling (a check
/// that `sample`'s pdf is the density it really draws from, and that `eval` is consistent), for
/// reflection, thick (entering and leaving) and thin rough transmission; and no lobe mix
/// reflects or transmits more than comes in.
#[test]
fn sampled_albedo_matches_uniform_integration() {
    let frame = Frame::from_normal(Vec3::new(0.2, 0.3, 0.9).normalize());
    let base = Vec3::new(0.8, 0.5, 0.3);
    // (metallic, roughness, specular, transmission, thin, entering)
    for (metallic, roughness, specular, transmission, thin, entering) in [
        (0.0, 0.5, 1.0, 0.0, true, true),
        (1.0, 0.3, 1.0, 0.0, true, true),
        (0.5, 0.8, 1.0, 0.0, true, true),
        (0.0, 1.0, 1.0, 0.0, true, true),
        (0.0, 0.4, 0.0, 0.0, true, true),
        (0.0, 0.3, 1.0, 1.0, false, true),
        (0.0, 0.5, 1.0, 1.0, false, false),
        (0.0, 0.7, 1.0, 0.6, false, true),
        (0.0, 0.4, 1.0, 1.0, true, true),
        (0.3, 0.6, 1.0, 0.5, true, true),
    ] {
        let bsdf = Bsdf::new(frame, base, metallic, roughness, specular).with_dielectric(
            transmission,
            1.5,
            thin,
            entering,
        );
        for wo in [Vec3::new(0.5, 0.1, 0.6), Vec3::new(0.9, 0.0, 0.15)] {
            let wo = frame.to_world(wo.normalize());
            let (is, uni) = albedos(&bsdf, wo, 1_000_000);
            let label = format!(
                "metallic {metallic} roughness {roughness} transmission {transmission} \
                 thin {thin} entering {entering}"
            );
            assert!(
                (is - uni).abs() < 0.015 * uni.max(0.05),
                "{label}: sampled {is} vs uniform {uni}"
            );
            assert!(is < 1.0, "{label}: albedo {is}");
        }
    }
}

/// White rough glass: what single scattering loses is the GGX masking, a few percent, never a gain,
/// from either side (KHR_materials_volume's BTDF has no 1 / eta^2 radiance scaling, so an
/// interface's weights sum to at most 1 whichever way the light crosses).
#[test]
fn rough_glass_interface_conserves_energy() {
    let frame = Frame::from_normal(Vec3::Z);
    for (entering, cos) in [(true, 0.9f32), (true, 0.3), (false, 0.95), (false, 0.5)] {
        let bsdf =
            Bsdf::new(frame, Vec3::ONE, 0.0, 0.3, 1.0).with_dielectric(1.0, 1.5, false, entering);
        let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
        let n = 400_000;
        let mut sum = 0.0f64;
        for k in 0..n {
            let u = Vec2::new(hash(3 * k + 1), hash(3 * k + 2));
            if let Some(s) = bsdf.sample(wo, hash(3 * k), u) {
                sum += (s.f.x * s.wi.z.abs() / s.pdf) as f64;
            }
        }
        let e = sum / n as f64;
        assert!(
            e > 0.9 && e < 1.0 + 3e-3,
            "entering {entering} cos {cos}: energy {e}"
        );
    }
}

/// Generalised reciprocity of the refraction BTDF in KHR_materials_volume's form (ior_o^2 of the
/// side `i` lies on in the numerator): f(o -> i) / eta_i^2 = f(i -> o) / eta_o^2, so from air into
/// glass of IOR 1.5 it is 2.25 times the reverse; and plain reciprocity of the reflection.
#[test]
fn btdf_is_reciprocal() {
    let n = Vec3::new(0.1, -0.2, 1.0).normalize();
    let outside = Bsdf::new(Frame::from_normal(n), Vec3::ONE, 0.0, 0.45, 1.0)
        .with_dielectric(1.0, 1.5, false, true);
    let inside = Bsdf::new(Frame::from_normal(-n), Vec3::ONE, 0.0, 0.45, 1.0)
        .with_dielectric(1.0, 1.5, false, false);
    let o = outside.frame.to_world(Vec3::new(0.4, 0.2, 0.8).normalize());
    for i in [
        Vec3::new(-0.3, -0.1, -0.9),
        Vec3::new(-0.2, -0.2, -0.95),
        Vec3::new(-0.4, -0.1, -0.85),
    ] {
        let i = outside.frame.to_world(i.normalize());
        let (f_oi, _) = outside.eval(o, i);
        let (f_io, _) = inside.eval(i, o);
        assert!(f_oi.x > 0.0);
        assert!(
            (f_oi.x - 2.25 * f_io.x).abs() < 1e-3 * f_oi.x,
            "{} vs {}",
            f_oi.x,
            2.25 * f_io.x
        );
    }
    let r = Bsdf::new(
        Frame::from_normal(n),
        Vec3::new(0.7, 0.6, 0.2),
        0.3,
        0.5,
        1.0,
    );
    let i = r.frame.to_world(Vec3::new(-0.6, 0.3, 0.5).normalize());
    let (a, b) = (r.eval(o, i).0, r.eval(i, o).0);
    assert!((a - b).abs().max_element() < 1e-5 * a.max_element());
}

/// Beyond the critical angle, from inside glass, every sample reflects with weight exactly 1;
/// below it, smooth glass splits the energy into Fresnel reflection and transmission, summing to 1.
#[test]
fn smooth_glass_reflects_totally_beyond_the_critical_angle() {
    let frame = Frame::from_normal(Vec3::Z);
    let inside = Bsdf::new(frame, Vec3::ONE, 0.0, 0.0, 1.0).with_dielectric(1.0, 1.5, false, false);
    assert!(inside.is_delta());
    let critical = (1.0f32 / 1.5).asin();
    let theta = critical + 0.05;
    let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
    for k in 0..1000 {
        let s = inside
            .sample(wo, hash(k), Vec2::new(hash(k + 7), 0.5))
            .expect("always reflects");
        assert!(s.delta && s.wi.z > 0.0);
        assert!((s.wi - Vec3::new(-wo.x, 0.0, wo.z)).length() < 1e-6);
        assert!((s.f.x * s.wi.z / s.pdf - 1.0).abs() < 1e-5);
    }
    // Below it, each lobe's weight times its choice probability is its Fresnel share, so the
    // expected weights add up to 1.
    for theta in [critical - 0.05, 0.2] {
        let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
        let fr = fresnel_exact(wo.z, inside.eta);
        let lobes = inside.lobes(wo.z);
        assert!((lobes.reflect + lobes.transmit - 1.0).abs() < 1e-6);
        let (mut refl, mut trans) = (false, false);
        for k in 0..200 {
            let s = inside.sample(wo, hash(k), Vec2::ZERO).unwrap();
            let w = s.f.x * s.wi.z.abs() / s.pdf;
            if s.wi.z > 0.0 {
                refl = true;
                assert!((w * lobes.reflect - fr).abs() < 1e-5);
            } else {
                trans = true;
                // Snell's law, and no radiance scaling: the refracted weight is 1 - F.
                assert!((s.wi.x * inside.eta + wo.x).abs() < 1e-5);
                assert!((w * lobes.transmit - (1.0 - fr)).abs() < 1e-5);
            }
        }
        assert!(refl && trans);
    }
}

/// Between equal indices roughness cannot bend light: a rough boundary of ior 1 passes it straight.
#[test]
fn index_matched_rough_boundary_is_straight() {
    let frame = Frame::from_normal(Vec3::Z);
    let b = Bsdf::new(frame, Vec3::ONE, 0.0, 0.8, 1.0).with_dielectric(1.0, 1.0, false, true);
    let wo = Vec3::new(0.6, 0.0, 0.8);
    for k in 0..100 {
        let s = b
            .sample(wo, hash(k), Vec2::new(hash(k + 1), hash(k + 2)))
            .unwrap();
        assert!(s.delta && (s.wi + wo).length() < 1e-6);
        assert!((s.f.x * s.wi.z.abs() / s.pdf - 1.0).abs() < 1e-5);
    }
}

/// A smooth metal is a mirror: one delta sample with weight Schlick(base, cos).
#[test]
fn smooth_metal_is_a_delta_mirror() {
    let frame = Frame::from_normal(Vec3::Z);
    let base = Vec3::new(0.9, 0.6, 0.3);
    let m = Bsdf::new(frame, base, 1.0, 0.0, 1.0);
    assert!(m.is_delta());
    let wo = Vec3::new(0.6, 0.0, 0.8);
    let s = m.sample(wo, 0.5, Vec2::new(0.3, 0.7)).unwrap();
    assert!(s.delta && !s.straight);
    assert!((s.wi - Vec3::new(-0.6, 0.0, 0.8)).length() < 1e-6);
    let w = s.f * s.wi.z / s.pdf;
    assert!((w - schlick(base, 0.8)).abs().max_element() < 1e-6);
    // Nothing for light sampling to find.
    assert_eq!(m.eval(wo, s.wi).0, Vec3::ZERO);
}

/// A thin smooth wall lets light straight through, tinted by the base colour and less Fresnel.
#[test]
fn thin_smooth_wall_passes_light_straight() {
    let frame = Frame::from_normal(Vec3::Z);
    let tint = Vec3::new(1.0, 0.5, 0.25);
    let b = Bsdf::new(frame, tint, 0.0, 0.0, 1.0).with_dielectric(1.0, 1.5, true, false);
    let wo = Vec3::new(0.0, 0.6, 0.8);
    let expected = tint * (1.0 - fresnel_exact(0.8, 1.5));
    assert!(
        (b.straight_transmittance(wo) - expected)
            .abs()
            .max_element()
            < 1e-6
    );
    let mut seen = false;
    for k in 0..100 {
        let s = b.sample(wo, hash(k), Vec2::ZERO).unwrap();
        if s.wi.z < 0.0 {
            seen = true;
            assert!(s.straight && (s.wi + wo).length() < 1e-6);
            let w = s.f * s.wi.z.abs() / s.pdf * b.lobes(0.8).transmit;
            assert!((w - expected).abs().max_element() < 1e-5);
        }
    }
    assert!(seen);
    // Rough thin walls scatter instead: shadow rays do not pass them.
    let rough = Bsdf::new(frame, tint, 0.0, 0.4, 1.0).with_dielectric(1.0, 1.5, true, false);
    assert_eq!(rough.straight_transmittance(wo), Vec3::ZERO);
}

#[test]
fn frame_is_orthonormal() {
    for n in [Vec3::Z, -Vec3::Z, Vec3::new(0.3, -0.4, 0.2).normalize()] {
        let f = Frame::from_normal(n);
        assert!(f.t.dot(f.b).abs() < 1e-6 && f.t.dot(n).abs() < 1e-6);
        assert!((f.t.cross(f.b) - n).length() < 1e-5);
    }
}

// ---- Layers: chi-square of sampling, white furnace, and the spec's formulas transcribed ----

const THETA_BINS: usize = 16;
const PHI_BINS: usize = 32;

/// Pearson's chi-square test of `sample`'s directions against its `eval` pdf, Mitsuba-style: the
/// sphere in (cos theta, phi) cells, expected counts from the pdf integrated over each cell (24 x 24
/// points), cells expecting under 5 pooled. Returns the p-value.
fn chi_square(bsdf: &Bsdf, wo: Vec3, n: u32) -> f64 {
    let cell = |w: Vec3| {
        let l = bsdf.frame.to_local(w);
        let a = (((l.z + 1.0) * 0.5 * THETA_BINS as f32) as usize).min(THETA_BINS - 1);
        let phi = l.y.atan2(l.x).rem_euclid(2.0 * PI);
        let b = ((phi / (2.0 * PI) * PHI_BINS as f32) as usize).min(PHI_BINS - 1);
        a * PHI_BINS + b
    };
    let mut observed = vec![0.0f64; THETA_BINS * PHI_BINS];
    for k in 0..n {
        let u = Vec2::new(hash(3 * k + 1 + 7_000_000), hash(3 * k + 2 + 7_000_000));
        if let Some(s) = bsdf.sample(wo, hash(3 * k + 7_000_000), u) {
            assert!(!s.delta && s.pdf > 0.0 && s.f.is_finite());
            observed[cell(s.wi)] += 1.0;
        }
    }
    let mut expected = vec![0.0f64; THETA_BINS * PHI_BINS];
    const SUB: usize = 24;
    let dz = 2.0 / THETA_BINS as f32;
    let dphi = 2.0 * PI / PHI_BINS as f32;
    for a in 0..THETA_BINS {
        for b in 0..PHI_BINS {
            let mut sum = 0.0f64;
            for sa in 0..SUB {
                for sb in 0..SUB {
                    let z = -1.0 + (a as f32 + (sa as f32 + 0.5) / SUB as f32) * dz;
                    let phi = (b as f32 + (sb as f32 + 0.5) / SUB as f32) * dphi;
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    let wi = bsdf
                        .frame
                        .to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z));
                    sum += bsdf.eval(wo, wi).1 as f64;
                }
            }
            expected[a * PHI_BINS + b] = sum / (SUB * SUB) as f64 * (dz * dphi) as f64 * n as f64;
        }
    }
    pearson_p_value(&observed, &expected)
}

/// A white Lambert base (no specular layer), for isolating the layers above it.
fn white_lambert(frame: Frame) -> Bsdf {
    Bsdf::new(frame, Vec3::ONE, 0.0, 1.0, 0.0)
}

fn with_coat(mut b: Bsdf, weight: f32, roughness: f32) -> Bsdf {
    b.coat = Some(Coat::new(b.frame, weight, roughness));
    b
}

fn with_sheen(mut b: Bsdf, color: Vec3, roughness: f32) -> Bsdf {
    b.sheen = Some(Sheen::new(color, roughness));
    b
}

/// Sampled directions follow the pdf eval reports, for the coat, the sheen and both over rough and
/// metal bases, over a grid of roughnesses and views.
#[test]
fn layered_sampling_passes_chi_square() {
    let frame = Frame::from_normal(Vec3::new(0.1, -0.2, 0.95).normalize());
    let tint = Vec3::new(0.8, 0.5, 0.3);
    let mut cases = Vec::new();
    for r in [0.2, 0.5, 0.9] {
        cases.push((format!("coat {r}"), with_coat(white_lambert(frame), 1.0, r)));
        cases.push((
            format!("sheen {r}"),
            with_sheen(white_lambert(frame), Vec3::ONE, r),
        ));
        let metal = Bsdf::new(frame, tint, 1.0, 0.4, 1.0);
        let both = with_coat(with_sheen(metal, Vec3::new(0.9, 0.7, 0.8), r), 0.7, r);
        cases.push((format!("coat+sheen over metal {r}"), both));
        let glass =
            Bsdf::new(frame, Vec3::ONE, 0.0, 0.5, 1.0).with_dielectric(1.0, 1.5, false, true);
        cases.push((
            format!("coat over rough glass {r}"),
            with_coat(glass, 1.0, r),
        ));
    }
    let mut spec = Bsdf::new(frame, tint, 0.0, 0.5, 0.8);
    spec.specular_color = Vec3::new(1.5, 0.5, 0.2);
    cases.push(("specular colour".into(), spec));
    for (label, bsdf) in &cases {
        for wo in [Vec3::new(0.3, 0.1, 0.9), Vec3::new(0.9, 0.2, 0.2)] {
            let wo = frame.to_world(wo.normalize());
            let p = chi_square(bsdf, wo, 400_000);
            eprintln!(
                "chi-square {label} wo.z {:.2}: p = {p:.3}",
                frame.to_local(wo).z
            );
            assert!(p > 1e-3, "{label}: chi-square p-value {p}");
        }
    }
}

/// The albedo (mean of f cos / pdf) of `bsdf` at `wo`.
fn albedo(bsdf: &Bsdf, wo: Vec3, n: u32) -> f64 {
    let mut sum = 0.0f64;
    for k in 0..n {
        let u = Vec2::new(hash(3 * k + 1), hash(3 * k + 2));
        if let Some(s) = bsdf.sample(wo, hash(3 * k), u) {
            sum += (s.f.max_element() * s.wi.dot(bsdf.frame.n).abs() / s.pdf) as f64;
        }
    }
    sum / n as f64
}

/// White furnace per layer: a white Lambert base under each layer (and both) reflects at most 1
/// from every view; the figures are printed (`cargo test -- --nocapture`).
#[test]
fn white_furnace_per_layer_reflects_at_most_one() {
    let frame = Frame::from_normal(Vec3::Z);
    for r in [0.1, 0.5, 1.0] {
        let cases = [
            ("coat", with_coat(white_lambert(frame), 1.0, r)),
            ("sheen", with_sheen(white_lambert(frame), Vec3::ONE, r)),
            (
                "coat+sheen",
                with_coat(with_sheen(white_lambert(frame), Vec3::ONE, r), 1.0, r),
            ),
        ];
        for (label, bsdf) in cases {
            let mut figures = Vec::new();
            for cos in [1.0f32, 0.7, 0.4, 0.15, 0.05] {
                let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
                let a = albedo(&bsdf, wo, 200_000);
                figures.push(format!("{cos}: {a:.4}"));
                assert!(
                    a < 1.0 + 5e-3,
                    "{label} roughness {r} cos {cos}: albedo {a}"
                );
                // What single-scattering GGX loses at grazing views of rough coats stays lost.
                assert!(a > 0.5, "{label} roughness {r} cos {cos}: albedo {a}");
            }
            eprintln!("furnace {label} roughness {r}: {}", figures.join(", "));
        }
    }
}

/// GGX D and the height-correlated V of the glTF spec's appendix B, as the Khronos sample renderer
/// writes them.
pub(super) fn spec_specular_brdf(n: Vec3, v: Vec3, l: Vec3, alpha: f32) -> f32 {
    let h = (v + l).normalize();
    let (nl, nv, nh) = (n.dot(l), n.dot(v), n.dot(h));
    let a2 = alpha * alpha;
    let d = a2 / (PI * (nh * nh * (a2 - 1.0) + 1.0).powi(2));
    let ggxv = nl * (nv * nv * (1.0 - a2) + a2).sqrt();
    let ggxl = nv * (nl * nl * (1.0 - a2) + a2).sqrt();
    d * 0.5 / (ggxv + ggxl)
}

/// KHR_materials_sheen's implementation notes, line by line (alphaG = sheenRoughness^2).
fn spec_sheen_brdf(n: Vec3, v: Vec3, l: Vec3, color: Vec3, rough: f32) -> Vec3 {
    let alpha_g = rough * rough;
    let h = (v + l).normalize();
    let inv_r = 1.0 / alpha_g;
    let cos2h = n.dot(h) * n.dot(h);
    let sin2h = 1.0 - cos2h;
    let dist = (2.0 + inv_r) * sin2h.powf(inv_r * 0.5) / (2.0 * PI);
    let lf = |x: f32| {
        let t = (1.0 - alpha_g) * (1.0 - alpha_g);
        let mix = |a: f32, b: f32| a * (1.0 - t) + b * t;
        mix(21.5473, 25.3245) / (1.0 + mix(3.82987, 3.32435) * x.powf(mix(0.19823, 0.16801)))
            + mix(-1.97760, -1.27393) * x
            + mix(-4.32054, -4.85967)
    };
    let lambda = |c: f32| {
        if c.abs() < 0.5 {
            lf(c).exp()
        } else {
            (2.0 * lf(0.5) - lf(1.0 - c)).exp()
        }
    };
    let (nv, nl) = (n.dot(v), n.dot(l));
    let vis = 1.0 / ((1.0 + lambda(nv) + lambda(nl)) * (4.0 * nv * nl));
    color * dist * vis
}

/// eval of the layered material against the specs' formulas: coated = mix(material, coat_brdf,
/// clearcoat * Schlick(0.04, V.Nc)) over f_sheen + f_diffuse * sheenAlbedoScaling, at random
/// directions, within 1e-4 (relative).
#[test]
fn layered_eval_matches_the_spec_formulas() {
    let n = Vec3::new(0.2, 0.1, 0.97).normalize();
    let frame = Frame::from_normal(n);
    let base = Vec3::new(0.6, 0.4, 0.2);
    let (cc, cc_r, sheen_c, sheen_r) = (0.8f32, 0.35f32, Vec3::new(0.9, 0.5, 0.7), 0.6f32);
    let mut b = Bsdf::new(frame, base, 0.0, 1.0, 0.0);
    b.coat = Some(Coat::new(frame, cc, cc_r));
    b.sheen = Some(Sheen::new(sheen_c, sheen_r));
    let mut checked = 0;
    for k in 0..2000 {
        let dir = |a: u32| {
            let z = hash(a);
            let phi = 2.0 * PI * hash(a + 1);
            let r = (1.0 - z * z).sqrt();
            frame.to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z.max(0.02)).normalize())
        };
        let (v, l) = (dir(10 * k + 100), dir(10 * k + 103));
        let (nv, nl) = (n.dot(v), n.dot(l));
        let fr = 0.04 + 0.96 * (1.0 - nv).powi(5);
        let e = |c: f32| sheen::albedo(c, sheen_r);
        let scaling =
            (1.0 - sheen_c.max_element() * e(nv)).min(1.0 - sheen_c.max_element() * e(nl));
        let material = spec_sheen_brdf(n, v, l, sheen_c, sheen_r) + base / PI * scaling;
        let coat = spec_specular_brdf(n, v, l, cc_r * cc_r);
        let spec = material.lerp(Vec3::splat(coat), cc * fr);
        let got = b.eval(v, l).0;
        let err = ((got - spec).abs() / spec.max(Vec3::splat(1e-3))).max_element();
        assert!(err < 1e-4, "v {v} l {l}: eval {got} vs spec {spec} ({err})");
        checked += 1;
    }
    assert_eq!(checked, 2000);
}

/// The sheen's albedo table against a fine Monte Carlo integration of the lobe.
#[test]
fn sheen_albedo_table_matches_integration() {
    for r in [0.3f32, 0.6, 1.0] {
        let s = Sheen::new(Vec3::ONE, r);
        for cos in [0.9f32, 0.5, 0.2] {
            let o = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            let n = 400_000;
            let mut sum = 0.0f64;
            for k in 0..n {
                // Uniform over the hemisphere, stratified in cos.
                let z = (k as f32 + hash(2 * k)) / n as f32;
                let phi = 2.0 * PI * hash(2 * k + 1);
                let rr = (1.0 - z * z).max(0.0).sqrt();
                let i = Vec3::new(rr * phi.cos(), rr * phi.sin(), z);
                sum += (s.eval(o, i).0.x * z * 2.0 * PI) as f64;
            }
            let mc = sum / n as f64;
            let table = s.albedo(cos) as f64;
            assert!(
                (mc - table).abs() < 0.01 + 0.02 * mc,
                "r {r} cos {cos}: {table} vs {mc}"
            );
        }
    }
}

/// The Lambert-only shortcut of eval and sample (no specular layer, metal or transmission) gives
/// the very bits of the full lobe mix, for smooth and rough roughness and both layerings; and a
/// material with a specular layer does not take it.
#[test]
fn lambert_shortcut_gives_the_bits_of_the_full_lobe_mix() {
    let frame = Frame::from_normal(Vec3::new(0.3, -0.2, 0.9).normalize());
    let base = Vec3::new(0.7, 0.4, 0.2);
    assert!(Bsdf::new(frame, base, 0.0, 0.5, 1.0)
        .lambert_only()
        .is_none());
    for roughness in [0.0, 0.5, 1.0] {
        for layering in [crate::scene::Layering::Spec, crate::scene::Layering::Albedo] {
            let mut b = Bsdf::new(frame, base, 0.0, roughness, 0.0);
            b.model.layering = layering;
            assert!(b.lambert_only().is_some());
            for k in 0..2000 {
                let o = Vec3::new(hash(5 * k) - 0.5, hash(5 * k + 1) - 0.5, hash(5 * k + 4))
                    .normalize();
                let (u_lobe, u) = (hash(5 * k + 2), Vec2::new(hash(5 * k + 3), hash(k + 7)));
                let fast = b.base_sample(frame.to_world(o), u_lobe, u);
                let full = b.lobe_mix_sample(o, u_lobe, u);
                assert_eq!(
                    fast.map(|s| (s.wi, s.f, s.pdf)),
                    full.map(|s| (s.wi, s.f, s.pdf))
                );
                for i in [o, -o, Vec3::new(-o.x, -o.y, o.z), Vec3::Z] {
                    assert_eq!(b.base_eval(o, i), b.lobe_mix_eval(o, i), "{o} {i}");
                }
            }
        }
    }
}

/// Lobe choice: probabilities sum to one; zero weights are never chosen; lobes under the negligible
/// share keep their bare proportion, the others their proportion mixed with a uniform tenth.
#[test]
fn choice_probabilities_boost_only_lobes_that_count() {
    for w in [
        [0.8, 0.2, 0.0],
        [0.9, 0.001, 0.0],
        [0.5, 0.005, 0.4],
        [0.0, 1.0, 0.0],
        [0.3, 0.3, 0.3],
    ] {
        let p = choice_probabilities(w);
        let total: f32 = w.iter().sum();
        assert!((p.iter().sum::<f32>() - 1.0).abs() < 1e-6, "{w:?}: {p:?}");
        for (x, q) in w.iter().zip(p) {
            if *x == 0.0 {
                assert_eq!(q, 0.0);
            } else if *x < NEGLIGIBLE_SHARE * total {
                assert!((q - x / total).abs() < 1e-7, "{w:?}: {p:?}");
            } else {
                assert!(q > 0.9 * x / total, "{w:?}: {p:?}");
            }
        }
    }
    // All lobes counting: the plain mix.
    let p = choice_probabilities([0.8, 0.2, 0.0]);
    assert!((p[0] - (0.9 * 0.8 + 0.05)).abs() < 1e-6 && (p[1] - (0.9 * 0.2 + 0.05)).abs() < 1e-6);
}

/// A BSDF that says it does not choose a lobe samples the same direction whatever its lobe
/// number (the integrator then does not draw one); one that says it does, does not.
#[test]
fn only_bsdfs_that_choose_a_lobe_read_the_lobe_number() {
    let frame = Frame::from_normal(Vec3::Z);
    let wo = Vec3::new(0.3, -0.2, 0.9).normalize();
    let lambert = Bsdf::new(frame, Vec3::new(0.7, 0.5, 0.3), 0.0, 1.0, 0.0);
    assert!(!lambert.chooses_lobe());
    for k in 0..64 {
        let u = Vec2::new(k as f32 / 64.0, (k * 37 % 64) as f32 / 64.0 + 0.004);
        let [a, b] = [0.0, 0.999_999].map(|l| lambert.sample(wo, l, u).map(|s| (s.wi, s.f, s.pdf)));
        assert_eq!(a, b, "sample {k}");
    }
    for chooses in [
        Bsdf::new(frame, Vec3::ONE, 0.0, 0.5, 1.0),
        Bsdf::new(frame, Vec3::ONE, 0.5, 1.0, 0.0),
        Bsdf::new(frame, Vec3::ZERO, 0.0, 1.0, 0.0),
        Bsdf::new(frame, Vec3::ONE, 0.0, 1.0, 0.0).with_dielectric(0.5, 1.5, true, true),
    ] {
        assert!(chooses.chooses_lobe());
    }
}
