//! Light-set checks against closed forms: irradiance from each analytic light kind by light sampling,
//! BSDF sampling and MIS, and the environment map's pdf against its samples.

use std::f64::consts::PI as PI64;
use std::sync::Arc;

use super::*;
use crate::render::bsdf::luminance;
use crate::sample::warp::concentric_disk;
use crate::scene::{
    DirectionalLight, DiskLight, EnvMap, PointLight, RectLight, SphereLight, SpotLight,
};

fn lights_only(lights: Vec<Light>, sampler: LightSampler) -> (Scene, LightSet) {
    let scene = Scene {
        lights,
        ..Default::default()
    };
    let set = LightSet::with_sampler(&scene, sampler);
    (scene, set)
}

/// The light context of the shading point of these tests: the origin, on a plane facing +Y.
const AT_ORIGIN: LightContext = LightContext {
    p: Vec3::ZERO,
    n: Vec3::Y,
};

/// A jittered n x n grid of points in [0, 1)^2 (fixed jitter from a hash, so tests repeat).
fn grid(n: usize) -> impl Iterator<Item = Vec2> {
    let jitter = |k: u64| {
        let mut x = k.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ 0x2545_f491_4f6c_dd1d;
        x ^= x >> 31;
        x = x.wrapping_mul(0xbf58_476d_1ce4_e5b9);
        x ^= x >> 29;
        (x >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..n * n).map(move |k| {
        Vec2::new(
            ((k % n) as f32 + jitter(2 * k as u64)) / n as f32,
            ((k / n) as f32 + jitter(2 * k as u64 + 1)) / n as f32,
        )
    })
}

/// Irradiance at the origin on a plane facing +Y, estimated three ways: light sampling alone,
/// cosine-weighted BSDF sampling alone (rays finding the lights), and both combined by MIS.
///
/// With one light the light BVH has only to agree with choosing by power: it picks the light with
/// probability 1 wherever the light can reach, so both give the same estimates.
fn irradiance(lights: Vec<Light>) -> [f64; 3] {
    let by_power = irradiance_by(lights.clone(), LightSampler::Power);
    if lights.len() == 1 {
        let by_bvh = irradiance_by(lights, LightSampler::Bvh);
        for (p, b) in by_power.iter().zip(by_bvh) {
            assert!((p - b).abs() <= 1e-9 * p.abs(), "power {p}, BVH {b}");
        }
    }
    by_power
}

fn irradiance_by(lights: Vec<Light>, sampler: LightSampler) -> [f64; 3] {
    let (scene, set) = lights_only(lights, sampler);
    let n = 256;
    let count = (n * n) as f64;
    let (mut light, mut bsdf, mut mis) = (0.0f64, 0.0f64, 0.0f64);
    for (k, u) in grid(n).enumerate() {
        // Light sampling (a light choice per stratum, decorrelated from `u`).
        let u_choice = ((k as f32) * 0.618_034).fract();
        if let Some(ls) = set.sample(&scene, &AT_ORIGIN, u_choice, u) {
            let cos = ls.wi.y;
            if cos > 0.0 && ls.pdf > 0.0 {
                let pdf_bsdf = cos / PI;
                let c = luminance(ls.li) * cos / ls.pdf;
                light += c as f64;
                let w = ls.pdf * ls.pdf / (ls.pdf * ls.pdf + pdf_bsdf * pdf_bsdf);
                mis += (c * w) as f64;
            }
        }
        // Cosine-weighted hemisphere sampling.
        let d = concentric_disk(u);
        let wi = Vec3::new(d.x, (1.0 - d.length_squared()).max(0.0).sqrt(), d.y);
        let pdf = wi.y / PI;
        if pdf <= 0.0 {
            continue;
        }
        let ray = Ray::new(Vec3::ZERO, wi);
        let le = set.emitted(&ray, f32::INFINITY, None) + set.escaped(wi, None);
        bsdf += (luminance(le) * wi.y / pdf) as f64;
        let prev = Some((pdf, AT_ORIGIN));
        let lw = set.emitted(&ray, f32::INFINITY, prev) + set.escaped(wi, prev);
        mis += (luminance(lw) * wi.y / pdf) as f64;
    }
    [light / count, bsdf / count, mis / count]
}

fn assert_close(got: [f64; 3], expected: f64, tol: f64, what: &str) {
    for (g, how) in got.iter().zip(["light sampling", "BSDF sampling", "MIS"]) {
        assert!(
            (g - expected).abs() <= tol * expected,
            "{what}, {how}: {g}, expected {expected}"
        );
    }
}

#[test]
fn disk_light_irradiance_is_pi_l_sin2_theta() {
    let (l, h) = (3.0f32, 1.5f32);
    for radius in [0.4f32, 1.5, 4.0] {
        let e = irradiance(vec![Light::Disk(DiskLight {
            center: Vec3::new(0.0, h, 0.0),
            normal: -Vec3::Y,
            radius,
            radiance: Vec3::splat(l),
        })]);
        let sin2 = (radius * radius / (radius * radius + h * h)) as f64;
        assert_close(
            e,
            PI64 * l as f64 * sin2,
            0.01,
            &format!("disk radius {radius}"),
        );
    }
    // Seen from behind it sends nothing.
    let e = irradiance(vec![Light::Disk(DiskLight {
        center: Vec3::new(0.0, h, 0.0),
        normal: Vec3::Y,
        radius: 1.0,
        radiance: Vec3::splat(l),
    })]);
    assert_eq!(e, [0.0; 3]);
}

#[test]
fn sphere_light_irradiance_is_pi_l_r2_over_d2() {
    let l = 2.0f32;
    for (r, d) in [(0.2f32, 3.0f32), (1.0, 1.6), (0.01, 2.0)] {
        let e = irradiance(vec![Light::Sphere(SphereLight {
            center: Vec3::new(0.0, d, 0.0),
            radius: r,
            radiance: Vec3::splat(l),
        })]);
        let expected = PI64 * l as f64 * (r as f64 / d as f64).powi(2);
        // Small spheres are found by few BSDF samples (0.4% and 0.001% of them), too few for a
        // tight bound on that estimator alone; light sampling and MIS still hold 1%.
        let tol = match r {
            r if r < 0.05 => [0.01, 0.5, 0.01],
            r if r < 0.5 => [0.01, 0.05, 0.01],
            _ => [0.01; 3],
        };
        for ((g, t), how) in e.iter().zip(tol).zip(["light", "BSDF", "MIS"]) {
            assert!(
                (g - expected).abs() <= t * expected,
                "sphere r {r} d {d}, {how}: {g} vs {expected}"
            );
        }
    }
}

/// Form factor from a point to a parallel a x b rectangle at height h with a corner straight above.
fn corner_form_factor(a: f64, b: f64, h: f64) -> f64 {
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI64)
}

#[test]
fn rect_light_irradiance_matches_the_form_factor() {
    let (l, h, a, b) = (1.5f32, 1.2f32, 2.0f32, 0.7f32);
    // Under a corner.
    let e = irradiance(vec![Light::Rect(RectLight {
        corner: Vec3::new(0.0, h, 0.0),
        edge_u: Vec3::new(a, 0.0, 0.0),
        edge_v: Vec3::new(0.0, 0.0, b),
        radiance: Vec3::splat(l),
    })]);
    let f = corner_form_factor(a as f64, b as f64, h as f64);
    assert_close(e, PI64 * l as f64 * f, 0.01, "rect, corner");
    // Under the centre: four corner rectangles of half the size.
    let e = irradiance(vec![Light::Rect(RectLight {
        corner: Vec3::new(-a / 2.0, h, -b / 2.0),
        edge_u: Vec3::new(a, 0.0, 0.0),
        edge_v: Vec3::new(0.0, 0.0, b),
        radiance: Vec3::splat(l),
    })]);
    let f = 4.0 * corner_form_factor(a as f64 / 2.0, b as f64 / 2.0, h as f64);
    assert_close(e, PI64 * l as f64 * f, 0.01, "rect, centre");
}

#[test]
fn many_lights_irradiance_sums_their_closed_forms_by_power_and_by_bvh() {
    let l = 1.3f32;
    let mut lights = Vec::new();
    let mut expected = 0.0f64;
    // Horizontal rectangles facing down at assorted offsets and heights; the last two face up,
    // away from the plane, and send nothing.
    for k in 0..8 {
        let (x0, z0) = (-1.5 + 0.45 * k as f32, -0.8 + 0.3 * (k % 3) as f32);
        let (a, b, h) = (0.3 + 0.05 * k as f32, 0.4, 0.8 + 0.25 * k as f32);
        let up = k >= 6;
        let (edge_u, edge_v) = (Vec3::new(a, 0.0, 0.0), Vec3::new(0.0, 0.0, b));
        lights.push(Light::Rect(RectLight {
            corner: Vec3::new(x0, h, z0),
            edge_u: if up { edge_v } else { edge_u },
            edge_v: if up { edge_u } else { edge_v },
            radiance: Vec3::splat(l * (1.0 + k as f32 * 0.3)),
        }));
        if !up {
            let f = |x: f32, z: f32| corner_form_factor(x as f64, z as f64, h as f64);
            let ff = f(x0 + a, z0 + b) - f(x0, z0 + b) - f(x0 + a, z0) + f(x0, z0);
            expected += PI64 * (l * (1.0 + k as f32 * 0.3)) as f64 * ff;
        }
    }
    // Spheres wholly above the plane: a point source of intensity pi r^2 L at the centre.
    for k in 0..4 {
        let c = Vec3::new(
            -1.0 + 0.7 * k as f32,
            1.0 + 0.4 * k as f32,
            0.5 - 0.3 * k as f32,
        );
        let r = 0.1 + 0.05 * k as f32;
        lights.push(Light::Sphere(SphereLight {
            center: c,
            radius: r,
            radiance: Vec3::splat(l),
        }));
        let (c, r) = (c.as_dvec3(), r as f64);
        expected += PI64 * l as f64 * r * r / c.length_squared() * c.y / c.length();
    }
    // And a disk straight above.
    let (radius, h) = (0.5f32, 2.5f32);
    lights.push(Light::Disk(DiskLight {
        center: Vec3::new(0.0, h, 0.0),
        normal: -Vec3::Y,
        radius,
        radiance: Vec3::splat(l),
    }));
    expected += PI64 * l as f64 * (radius * radius / (radius * radius + h * h)) as f64;
    assert!(lights_only(lights.clone(), LightSampler::Bvh).1.uses_bvh());
    for sampler in [LightSampler::Power, LightSampler::Bvh] {
        let e = irradiance_by(lights.clone(), sampler);
        assert_close(
            e,
            expected,
            0.01,
            &format!("{} lights by {sampler}", lights.len()),
        );
    }
}

#[test]
fn punctual_lights_irradiance_sums_their_closed_forms_by_power_and_by_bvh() {
    // Points above and below the plane, and spots: aimed at the origin (inside their inner cone),
    // aimed away (outside their outer cone), aimed at it from below the plane.
    let mut lights = Vec::new();
    let mut expected = 0.0f64;
    for k in 0..10 {
        let position = Vec3::new(
            -2.0 + 0.45 * k as f32,
            if k == 3 { -1.0 } else { 0.3 + 0.35 * k as f32 },
            1.2 - 0.27 * k as f32,
        );
        let intensity = 0.5 + 0.4 * k as f32;
        let to_origin = -position.normalize();
        let cos = (-to_origin.y).max(0.0) as f64;
        let lit = position.length_squared() as f64;
        let light = match k % 3 {
            0 => {
                expected += intensity as f64 * cos / lit;
                Light::Point(PointLight {
                    position,
                    intensity: Vec3::splat(intensity),
                })
            }
            1 => {
                expected += intensity as f64 * cos / lit;
                Light::Spot(SpotLight {
                    position,
                    direction: to_origin,
                    intensity: Vec3::splat(intensity),
                    cos_inner: 0.9,
                    cos_outer: 0.8,
                })
            }
            _ => Light::Spot(SpotLight {
                position,
                direction: -to_origin,
                intensity: Vec3::splat(intensity),
                cos_inner: 0.9,
                cos_outer: 0.8,
            }),
        };
        lights.push(light);
    }
    for sampler in [LightSampler::Power, LightSampler::Bvh] {
        let light = irradiance_by(lights.clone(), sampler)[0];
        assert!(
            (light - expected).abs() <= 0.01 * expected,
            "{sampler}: {light}, expected {expected}"
        );
    }
}

/// Inside its cone a spot lights a point as a point light of the same intensity does, however
/// narrow the cone: the light BVH chooses the two alike there (the power sampler, by flux, does
/// not).
#[test]
fn the_bvh_chooses_a_spot_as_a_point_light_of_its_intensity() {
    for cos_outer in [0.5, 0.95, 0.999] {
        let intensity = Vec3::new(3.0, 2.0, 1.0);
        let lights = vec![
            Light::Point(PointLight {
                position: Vec3::new(-1.0, 2.0, 0.0),
                intensity,
            }),
            Light::Spot(SpotLight {
                position: Vec3::new(1.0, 2.0, 0.0),
                direction: Vec3::new(-1.0, -2.0, 0.0).normalize(),
                intensity,
                cos_inner: (1.0 + cos_outer) / 2.0,
                cos_outer,
            }),
        ];
        let (_, set) = lights_only(lights, LightSampler::Bvh);
        let ctx = LightContext {
            p: Vec3::ZERO,
            n: Vec3::Y,
        };
        let (point, spot) = (set.chooser.pmf(&ctx, 0), set.chooser.pmf(&ctx, 1));
        assert!(
            (point - 0.5).abs() < 1e-5 && (spot - 0.5).abs() < 1e-5,
            "cos_outer {cos_outer}: point {point}, spot {spot}"
        );
    }
}

/// A 32 x 16 map: dark below the horizon, a sky gradient above, a small bright sun.
fn sky_map() -> EnvMap {
    let (w, h) = (32, 16);
    let px = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            if y >= h / 2 {
                Vec3::ZERO
            } else if (x, y) == (20, 3) {
                Vec3::new(400.0, 380.0, 300.0)
            } else {
                Vec3::new(0.3, 0.5, 1.0) * (1.0 + x as f32 / w as f32)
            }
        })
        .collect();
    EnvMap::new(w, h, px).unwrap()
}

#[test]
fn environment_map_pdf_integrates_to_one_and_matches_its_samples() {
    for map in [sky_map(), sky_map().rotated_y(0.9)] {
        let (scene, set) = lights_only(
            vec![Light::Environment {
                radiance: Vec3::ONE,
                map: Some(Arc::new(map)),
            }],
            LightSampler::Power,
        );
        // Midpoint rule over (theta, phi), fine enough to resolve every pixel.
        let (nt, np) = (512, 1024);
        let mut total = 0.0f64;
        for i in 0..nt {
            let theta = (i as f64 + 0.5) / nt as f64 * PI64;
            for j in 0..np {
                let phi = (j as f64 + 0.5) / np as f64 * 2.0 * PI64;
                let d = Vec3::new(
                    (theta.sin() * phi.cos()) as f32,
                    theta.cos() as f32,
                    (theta.sin() * phi.sin()) as f32,
                );
                let (_, pdf) = set.environment_radiance(0, d);
                total += pdf as f64 * theta.sin() * (PI64 / nt as f64) * (2.0 * PI64 / np as f64);
            }
        }
        assert!((total - 1.0).abs() < 2e-3, "pdf integrates to {total}");
        for u in grid(16) {
            let ls = set.sample(&scene, &AT_ORIGIN, 0.5, u).unwrap();
            let (li, pdf) = set.environment_radiance(0, ls.wi);
            // What a camera ray sees (no pdf taken) is the same radiance.
            assert_eq!(set.escaped(ls.wi, None), li);
            assert!((pdf - ls.pdf).abs() <= 1e-3 * pdf, "{pdf} vs {}", ls.pdf);
            assert!((li - ls.li).length() <= 1e-3 * li.length().max(1e-3));
        }
    }
}

/// The sum over a lat-long map's pixels of `lum` of their luminance times `row` of their row's
/// polar angles (theta0, theta1), times their width in phi.
fn map_sum(m: &EnvMap, row: impl Fn(f64, f64) -> f64, lum: impl Fn(f64) -> f64) -> f64 {
    let dphi = 2.0 * PI64 / m.width as f64;
    let mut sum = 0.0f64;
    for y in 0..m.height {
        let t = |k: usize| k as f64 / m.height as f64 * PI64;
        let r = row(t(y), t(y + 1));
        for x in 0..m.width {
            sum += lum(luminance(m.pixels[y * m.width + x]) as f64) * r * dphi;
        }
    }
    sum
}

/// Irradiance on the plane facing +Y from a map whose pixels have luminance `lum`: each row's
/// closed-form integral of cos(theta) sin(theta) above the horizon.
fn map_irradiance(m: &EnvMap, lum: impl Fn(f64) -> f64) -> f64 {
    let row = |t0: f64, t1: f64| {
        if t0 >= PI64 / 2.0 {
            0.0
        } else {
            0.5 * (t1.sin().powi(2) - t0.sin().powi(2))
        }
    };
    map_sum(m, row, lum)
}

/// The map's mean luminance over the sphere, by each row's solid angle.
fn map_mean(m: &EnvMap) -> f64 {
    map_sum(m, |t0, t1| t0.cos() - t1.cos(), |v| v) / (4.0 * PI64)
}

/// BSDF sampling and MIS find an environment's whole irradiance; light samples alone find only
/// what comes from the pixels above the map's mean (MIS compensation), and none of a constant.
#[test]
fn environment_irradiance_matches_closed_forms() {
    let l = 0.8f32;
    let lit = |map: Option<EnvMap>, l: f32| {
        irradiance(vec![Light::Environment {
            radiance: Vec3::splat(l),
            map: map.map(Arc::new),
        }])
    };
    let whole = PI64 * l as f64;
    for (what, map) in [
        ("constant", None),
        ("constant map", Some(EnvMap::constant(16, 8, Vec3::ONE))),
    ] {
        let e = lit(map, l);
        assert_eq!(e[0], 0.0, "{what}: light samples");
        assert!((e[1] - whole).abs() < 1e-4 && e[2] == e[1], "{what}: {e:?}");
    }
    // Lit only above the horizon: pi L on an upward plane, all of it from pixels above the mean.
    let upper = EnvMap::new(
        8,
        8,
        (0..64)
            .map(|i| Vec3::splat(if i < 32 { 1.0 } else { 0.0 }))
            .collect(),
    )
    .unwrap();
    let e = lit(Some(upper), l);
    assert!((e[0] - whole).abs() < 0.01 * whole, "upper: light {e:?}");
    assert!((e[1] - whole).abs() < 0.01 * whole, "upper: BSDF {e:?}");
    assert!((e[2] - whole).abs() < 0.01 * whole, "upper: MIS {e:?}");
    // The sky and sun map, integrated exactly pixel by pixel.
    let m = sky_map();
    let e = lit(Some(sky_map()), 1.0);
    let reference = map_irradiance(&m, |v| v);
    let mean = map_mean(&m);
    let above = map_irradiance(&m, |v| if v > mean { v } else { 0.0 });
    assert!(
        (e[0] - above).abs() < 0.01 * above && (e[2] - reference).abs() < 0.01 * reference,
        "sky: light {} (from above the mean {above}) MIS {} vs {reference}",
        e[0],
        e[2]
    );
    // BSDF sampling alone rarely finds the sun pixel: a looser check.
    assert!(
        (e[1] - reference).abs() < 0.05 * reference,
        "sky: BSDF {}",
        e[1]
    );
}

/// Irradiance at the origin (plane facing +Y) from a uniform polygon of radiance `l` with corners
/// `v`, by Lambert's formula: l/2 times the sum over edges of the angle they subtend times the
/// cosine of their plane's normal with +Y.
fn lambert_polygon(v: &[Vec3], l: f64) -> f64 {
    let mut s = 0.0f64;
    for i in 0..v.len() {
        let (a, b) = (
            v[i].as_dvec3().normalize(),
            v[(i + 1) % v.len()].as_dvec3().normalize(),
        );
        let theta = a.cross(b).length().atan2(a.dot(b));
        s += theta * a.cross(b).normalize().y;
    }
    0.5 * l * s.abs()
}

/// Light-sampled irradiance at the origin (plane facing +Y) from the emissive triangles of
/// instance 0, over a jittered n x n grid; each sample's pdf must be the one a BSDF-sampled ray
/// would be weighed with on reaching the same point of any of `prims` (unit normal `nq`).
fn sampled_irradiance_checking_pdfs(
    scene: &Scene,
    set: &LightSet,
    n: usize,
    prims: &[u32],
    nq: Vec3,
    what: &str,
) -> f64 {
    let mut e = 0.0f64;
    for (k, u) in grid(n).enumerate() {
        let ls = set.sample(scene, &AT_ORIGIN, (k as f32 * 0.618_034).fract(), u);
        let Some(ls) = ls else { continue };
        let q = ls.wi * ls.dist;
        for &prim in prims {
            let pdf = set.pdf_triangle(0, prim, &AT_ORIGIN, q, nq);
            assert!(
                (pdf - ls.pdf).abs() <= 1e-3 * ls.pdf,
                "{what}, sample {k}, triangle {prim}: {pdf} vs {}",
                ls.pdf
            );
        }
        e += (luminance(ls.li) * ls.wi.y.max(0.0) / ls.pdf) as f64;
    }
    e / (n * n) as f64
}

#[test]
fn emissive_triangle_irradiance_matches_lambert_near_and_far() {
    // Near (sampled by solid angle) and far (by area), each from both sides of the two-sided light.
    for (v, what) in [
        (
            [
                Vec3::new(-0.5, 0.3, -0.4),
                Vec3::new(1.2, 0.5, 0.1),
                Vec3::new(-0.2, 0.4, 0.9),
            ],
            "near",
        ),
        (
            [
                Vec3::new(-0.5, 3.0, -0.4),
                Vec3::new(0.2, 3.5, 0.1),
                Vec3::new(-0.2, 3.4, 0.3),
            ],
            "middle",
        ),
        (
            [
                Vec3::new(0.05, 0.003, -0.3),
                Vec3::new(0.6, 0.003, -0.2),
                Vec3::new(0.3, 0.003, 0.4),
            ],
            "grazing",
        ),
        (
            [
                Vec3::new(-0.05, 30.0, -0.04),
                Vec3::new(0.12, 30.0, 0.01),
                Vec3::new(-0.02, 30.0, 0.09),
            ],
            "far",
        ),
    ] {
        for winding in [[0, 1, 2], [0, 2, 1]] {
            let positions = winding.map(|i| v[i]).to_vec();
            let scene = emissive_mesh_scene(positions, vec![[0, 1, 2]], Vec3::splat(2.0));
            let set = LightSet::new(&scene);
            let nq = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
            let e = sampled_irradiance_checking_pdfs(&scene, &set, 128, &[0], nq, what);
            let expected = lambert_polygon(&v, 2.0);
            assert!(
                (e - expected).abs() < 2e-3 * expected,
                "{what}: {e} vs {expected}"
            );
        }
    }
}

#[test]
fn auto_takes_the_bvh_from_its_count_of_bounded_lights_on() {
    let points = |n: usize| {
        (0..n)
            .map(|k| {
                Light::Point(PointLight {
                    position: Vec3::new(k as f32, 1.0, 0.0),
                    intensity: Vec3::ONE,
                })
            })
            .collect::<Vec<_>>()
    };
    assert!(
        !lights_only(points(AUTO_BVH_LIGHTS - 1), LightSampler::Auto)
            .1
            .uses_bvh()
    );
    assert!(lights_only(points(AUTO_BVH_LIGHTS), LightSampler::Auto)
        .1
        .uses_bvh());
    assert!(!lights_only(points(AUTO_BVH_LIGHTS), LightSampler::Power)
        .1
        .uses_bvh());
    // Lights at infinity are chosen beside the tree, so they do not count towards it.
    let mut beside = points(AUTO_BVH_LIGHTS - 1);
    beside.push(Light::Directional(DirectionalLight {
        direction: -Vec3::Y,
        irradiance: Vec3::ONE,
    }));
    beside.push(Light::Environment {
        radiance: Vec3::ONE,
        map: None,
    });
    assert!(!lights_only(beside, LightSampler::Auto).1.uses_bvh());
}

/// The mean and variance of one-sample estimates `e(u)` over a jittered 64 x 64 grid.
fn mean_and_variance(e: impl Fn(Vec2) -> f64) -> (f64, f64) {
    let n = 64 * 64;
    let (s, s2) = grid(64)
        .map(&e)
        .fold((0.0, 0.0), |(s, s2), x| (s + x, s2 + x * x));
    let m = s / n as f64;
    (m, s2 / n as f64 - m * m)
}

/// The cosine warp of spherical triangle sampling: irradiance estimates from a large triangle that
/// spans the horizon of the shading plane vary less than uniform solid-angle samples do (the
/// warp's corner order decides this; measured 0.63x, and a wrong order raised the noise past the
/// mean's tolerance).
#[test]
fn the_cosine_warp_lowers_the_variance_of_a_near_triangle() {
    let v = [
        Vec3::new(-1.5, 0.05, -1.0),
        Vec3::new(1.5, 0.05, -1.0),
        Vec3::new(0.0, 2.0, 0.3),
    ];
    let scene = emissive_mesh_scene(v.to_vec(), vec![[0, 1, 2]], Vec3::ONE);
    let set = LightSet::new(&scene);
    let variance = |ctx: LightContext| {
        mean_and_variance(|u| {
            set.sample(&scene, &ctx, 0.5, u).map_or(0.0, |ls| {
                (luminance(ls.li) * ls.wi.y.max(0.0) / ls.pdf) as f64
            })
        })
    };
    let (warped, var_warped) = variance(AT_ORIGIN);
    let (uniform, var_uniform) = variance(LightContext {
        p: Vec3::ZERO,
        n: Vec3::ZERO,
    });
    let expected = lambert_polygon(&v, 1.0);
    for e in [warped, uniform] {
        assert!((e - expected).abs() < 3e-3 * expected, "{e} vs {expected}");
    }
    assert!(
        var_warped < 0.75 * var_uniform,
        "variance {var_warped} warped, {var_uniform} uniform"
    );
}

/// Sampling a rectangle by solid angle: from 0.3 below a 2 x 0.7 light, light-sampled irradiance
/// estimates vary far less than uniform area samples of the same light do (measured: 0.034x the
/// variance), and both average to the form factor's irradiance.
#[test]
fn a_near_rect_light_sampled_by_solid_angle_varies_less_than_by_area() {
    let (l, h, a, b) = (1.0f32, 0.3f32, 2.0f32, 0.7f32);
    let (corner, edge_u, edge_v) = (
        Vec3::new(-a / 2.0, h, -b / 2.0),
        Vec3::new(a, 0.0, 0.0),
        Vec3::new(0.0, 0.0, b),
    );
    let (scene, set) = lights_only(
        vec![Light::Rect(RectLight {
            corner,
            edge_u,
            edge_v,
            radiance: Vec3::splat(l),
        })],
        LightSampler::Power,
    );
    let (solid, var_solid) = mean_and_variance(|u| {
        set.sample(&scene, &AT_ORIGIN, 0.5, u).map_or(0.0, |ls| {
            (luminance(ls.li) * ls.wi.y.max(0.0) / ls.pdf) as f64
        })
    });
    let (area, var_area) = mean_and_variance(|u| {
        let q = corner + edge_u * u.x + edge_v * u.y;
        let (d2, cos) = (q.length_squared() as f64, (q.y / q.length()) as f64);
        l as f64 * cos * cos / d2 * (a * b) as f64
    });
    let expected =
        PI64 * l as f64 * 4.0 * corner_form_factor(a as f64 / 2.0, b as f64 / 2.0, h as f64);
    for e in [solid, area] {
        assert!((e - expected).abs() < 3e-3 * expected, "{e} vs {expected}");
    }
    assert!(
        var_solid < 0.1 * var_area,
        "variance {var_solid} by solid angle, {var_area} by area"
    );
}

/// The last ray's emitter test (`nearest_emitter`) stands in for the closest-hit query only where
/// the sampled triangles are every emitter, and opaque: rays pass an alpha-tested emitter's
/// cut-outs, the emitter test would not. Where it applies it finds the nearest of them.
#[test]
fn few_emitters_only_where_the_triangles_are_every_emitter() {
    let positions = vec![
        Vec3::new(-1.0, 1.0, -1.0),
        Vec3::new(1.0, 1.0, -1.0),
        Vec3::new(0.0, 1.0, 1.0),
    ];
    let scene = emissive_mesh_scene(positions, vec![[0, 1, 2]], Vec3::splat(2.0));
    let set = LightSet::new(&scene);
    assert!(set.few_emitters());
    let up = Ray::new(Vec3::ZERO, Vec3::Y);
    let hit = set
        .nearest_emitter(&up)
        .expect("the ray meets the triangle");
    assert!((hit.t - 1.0).abs() < 1e-6 && hit.inst == 0 && hit.prim == 0);
    assert!(set
        .nearest_emitter(&Ray::new(Vec3::ZERO, -Vec3::Y))
        .is_none());

    let mut masked = scene.clone();
    masked.materials[0].alpha_mode = crate::scene::AlphaMode::Mask(0.5);
    masked.materials[0].base_color.w = 0.25;
    assert!(masked.mesh_needs_alpha_test(0));
    assert!(!LightSet::new(&masked).few_emitters());

    let mut unlit = scene.clone();
    unlit.materials.push(crate::scene::Material {
        unlit: true,
        ..Default::default()
    });
    unlit.meshes.push(unlit.meshes[0].clone());
    unlit.meshes[1].material = 1;
    unlit
        .instances
        .push(crate::scene::Instance::new(1, glam::Mat4::IDENTITY));
    assert!(!LightSet::new(&unlit).few_emitters());
}

/// A scene of one emissive mesh of radiance 2 over `corners`, split into two triangles along the
/// diagonal `diagonal` (0: corners 0-2, 1: corners 1-3), in `winding` order.
fn emissive_quad_scene(corners: [Vec3; 4], diagonal: usize, flip: bool) -> Scene {
    let mut indices = if diagonal == 0 {
        vec![[0, 1, 2], [0, 2, 3]]
    } else {
        vec![[0, 1, 3], [1, 2, 3]]
    };
    if flip {
        indices.iter_mut().for_each(|t| t.swap(1, 2));
    }
    emissive_mesh_scene(corners.to_vec(), indices, Vec3::splat(2.0))
}

/// A scene of one mesh over `positions` and `indices` emitting `radiance` (vertex normals +Y:
/// emission is two-sided, and light sampling reads none).
fn emissive_mesh_scene(positions: Vec<Vec3>, indices: Vec<[u32; 3]>, radiance: Vec3) -> Scene {
    let mesh = crate::scene::Mesh {
        normals: vec![Vec3::Y; positions.len()],
        positions,
        indices,
        ..Default::default()
    };
    let mut scene = crate::scene::generate::single_mesh_scene(mesh);
    scene.materials[0].emissive = radiance;
    scene
}

/// Two triangles that make a rectangle of constant emission are one light, sampled as the
/// rectangle: from near, grazing (1 cm off its plane, as the Cornell box ceiling sees its light),
/// middle and far, on both sides, whichever diagonal splits it and either winding, light samples
/// average to Lambert's irradiance of the rectangle and carry the pdf that BSDF-sampled hits on
/// either triangle are weighed with.
#[test]
fn an_emissive_rectangle_of_two_triangles_is_one_light_matching_lambert() {
    let rect = |x0: f32, z0: f32, w: f32, d: f32, y: f32| {
        [
            Vec3::new(x0, y, z0),
            Vec3::new(x0 + w, y, z0),
            Vec3::new(x0 + w, y, z0 + d),
            Vec3::new(x0, y, z0 + d),
        ]
    };
    for (corners, what) in [
        (rect(-0.5, -0.4, 1.2, 0.9, 0.3), "near"),
        (rect(-0.3, -0.2, 0.47, 0.38, 0.01), "grazing above"),
        (rect(0.05, -0.2, 0.47, 0.38, 0.01), "grazing beside"),
        (rect(-0.3, -0.2, 0.47, 0.38, -0.01), "grazing below"),
        (rect(-0.5, -0.4, 0.7, 0.5, 3.0), "middle"),
        (rect(-0.05, -0.04, 0.17, 0.13, 30.0), "far"),
    ] {
        for diagonal in [0, 1] {
            for flip in [false, true] {
                let scene = emissive_quad_scene(corners, diagonal, flip);
                let set = LightSet::new(&scene);
                assert_eq!(set.entries.len(), 1, "{what}: one light");
                assert!(matches!(set.entries[0], Entry::Quad(_)), "{what}");
                let e = sampled_irradiance_checking_pdfs(&scene, &set, 256, &[0, 1], Vec3::Y, what);
                // Below the plane y = 0 only the part above the horizon counts: the grazing
                // light under the origin sends it nothing.
                let expected = if corners[0].y > 0.0 {
                    lambert_polygon(&corners, 2.0)
                } else {
                    0.0
                };
                assert!(
                    (e - expected).abs() <= 2e-3 * expected,
                    "{what}, diagonal {diagonal}, flipped {flip}: {e} vs {expected}"
                );
            }
        }
    }
}

/// Where an emissive triangle or rectangle fills much of a Lambertian point's sky, each light
/// sample alone brings Lambert's irradiance (projected solid-angle sampling: the cosine is in the
/// pdf), within the 0.12% that samples whose tries all miss can take from the rest.
#[test]
fn wide_lights_give_lambert_from_every_sample() {
    let tri = [
        Vec3::new(-0.9, 0.4, -0.6),
        Vec3::new(1.1, 0.5, -0.3),
        Vec3::new(0.1, 0.3, 1.2),
    ];
    let triangle = emissive_mesh_scene(tri.to_vec(), vec![[0, 1, 2]], Vec3::splat(2.0));
    let rect = [(-0.3, -0.2), (0.17, -0.2), (0.17, 0.18), (-0.3, 0.18)]
        .map(|(x, z)| Vec3::new(x, 0.01, z));
    for (scene, corners) in [
        (triangle, tri.to_vec()),
        (emissive_quad_scene(rect, 0, false), rect.to_vec()),
    ] {
        let set = LightSet::new(&scene);
        let expected = lambert_polygon(&corners, 2.0) as f32;
        for (k, u) in grid(16).enumerate() {
            let ls = set
                .sample(&scene, &AT_ORIGIN, 0.5, u)
                .expect("a wide light is met");
            let e = luminance(ls.li) * ls.wi.y / ls.pdf;
            assert!(
                e >= expected * (1.0 - 1e-4) && e <= expected * 1.002,
                "{} corners, sample {k}: {e} vs {expected}",
                corners.len()
            );
        }
    }
}

/// With one light there is nothing to choose: the light sample is the same whatever the choice
/// number (the integrator then does not draw one); with two, the choice is read.
#[test]
fn only_a_set_of_several_lights_reads_the_choice() {
    let corners =
        [(-0.3, -0.2), (0.17, -0.2), (0.17, 0.18), (-0.3, 0.18)].map(|(x, z)| Vec3::new(x, 0.5, z));
    let one = emissive_quad_scene(corners, 0, false);
    let set = LightSet::new(&one);
    assert!(!set.chooses());
    for u in grid(8) {
        let [a, b] = [0.0, 0.999_999].map(|c| {
            set.sample(&one, &AT_ORIGIN, c, u)
                .map(|ls| (ls.wi, ls.dist, ls.pdf))
        });
        assert_eq!(a, b);
    }
    let two = emissive_mesh_scene(corners.to_vec(), vec![[0, 1, 2], [2, 3, 1]], Vec3::ONE);
    assert!(LightSet::new(&two).chooses());
}

/// A point on an emissive rectangle (a path that bounces off the light) sees it edge on: no light
/// from it, though rounding puts all its corners to one side of the point.
#[test]
fn a_point_on_an_emissive_rectangle_gets_none_of_its_light() {
    // Tilted, so that points on it are off its plane by rounding.
    let tilt = glam::Quat::from_euler(glam::EulerRot::XYZ, 0.3, 0.2, -0.4);
    let corners = [(-0.3, -0.2), (0.17, -0.2), (0.17, 0.18), (-0.3, 0.18)]
        .map(|(x, z)| tilt * Vec3::new(x, 0.548_8, z));
    let scene = emissive_quad_scene(corners, 0, false);
    let set = LightSet::new(&scene);
    let normal = tilt * Vec3::Y;
    let (c, u, v) = (corners[0], corners[1] - corners[0], corners[3] - corners[0]);
    for (s, t) in [
        (0.013_7, 0.521_3),
        (0.971_9, 0.1),
        (0.1, 0.983_3),
        (0.5, 0.5),
    ] {
        let p = c + u * s + v * t;
        for n in [normal, -normal] {
            let ctx = LightContext { p, n };
            let mut e = 0.0;
            for u in grid(32) {
                if let Some(ls) = set.sample(&scene, &ctx, 0.5, u) {
                    e += luminance(ls.li) * ls.wi.dot(n).abs() / ls.pdf;
                }
            }
            assert!(e < 1e-3, "at {p}, normal {n}: {e}");
        }
    }
}

/// Only rectangles of constant emission merge: a skewed parallelogram, a rectangle with a corner
/// 1 mm off, and a textured emission stay two triangle lights; rays that look for emitters find
/// either half of a merged rectangle.
#[test]
fn only_rectangles_of_constant_emission_merge_and_rays_find_both_halves() {
    let square = [
        Vec3::new(-1.0, 1.0, -1.0),
        Vec3::new(1.0, 1.0, -1.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
    ];
    let set = LightSet::new(&emissive_quad_scene(square, 0, false));
    assert_eq!(set.entries.len(), 1);
    for (x, prim) in [(0.5, 0), (-0.5, 1)] {
        // Triangle 0 is corners 0, 1, 2 (x > z), triangle 1 corners 0, 2, 3.
        let ray = Ray::new(Vec3::new(x, 0.0, -x), Vec3::Y);
        let hit = set.nearest_emitter(&ray).expect("the ray meets the quad");
        assert!((hit.t - 1.0).abs() < 1e-6 && hit.prim == prim, "{hit:?}");
    }

    // Two squares and a lone triangle in one mesh: two rectangles, then the triangle, each
    // triangle mapped to its light.
    let mut three = emissive_quad_scene(square, 0, false);
    let mesh = &mut three.meshes[0];
    mesh.positions
        .extend(square.map(|v| v + Vec3::X * 3.0).iter().copied());
    mesh.indices.extend([[4, 5, 6], [4, 6, 7], [0, 5, 4]]);
    mesh.normals = vec![Vec3::Y; 8];
    let set = LightSet::new(&three);
    assert!(matches!(
        set.entries.as_slice(),
        [Entry::Quad(_), Entry::Quad(_), Entry::Triangle(_)]
    ));
    assert_eq!(set.triangle_entry, [0, 0, 1, 1, 2]);

    let mut skewed = square;
    skewed[2].x += 0.5;
    skewed[3].x += 0.5;
    let set = LightSet::new(&emissive_quad_scene(skewed, 0, false));
    assert_eq!(set.entries.len(), 2, "a parallelogram");

    let mut apart = emissive_quad_scene(square, 0, false);
    apart.meshes[0]
        .positions
        .push(Vec3::new(-1.0, 1.0, 1.0) + Vec3::X * 1e-3);
    apart.meshes[0].indices[1] = [0, 2, 4];
    assert_eq!(LightSet::new(&apart).entries.len(), 2, "a corner 1 mm off");

    let mut textured = emissive_quad_scene(square, 0, false);
    textured
        .textures
        .push(crate::scene::texture::Texture::repeating(
            "glow".into(),
            (1, 1),
            vec![[255; 4]],
            false,
        ));
    textured.materials[0].emissive_tex = Some(crate::scene::TexRef::new(0));
    assert_eq!(LightSet::new(&textured).entries.len(), 2, "textured");
}
