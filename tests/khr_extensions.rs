//! glint's own test scenes of KHR_materials_diffuse_transmission and KHR_materials_dispersion
//! (assets/khr, made by make_khr.py): factor 0 renders byte for byte as without the extension, and
//! at full strength the effect is the number the optics predict.

mod common;

use std::path::Path;
use std::sync::Arc;

use glint::accel::Backend;
use glint::film::Image;
use glint::render::bsdf::channel_iors;
use glint::render::job::{DefaultLights, JobOptions, Setup};
use glint::render::RenderSettings;
use glint::scene::Scene;

fn render(name: &str, (w, h): (usize, usize), spp: u32) -> Image {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/khr")
        .join(name);
    let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{name}: {:?}", scene.warnings);
    let opts = JobOptions {
        default_lights: DefaultLights::Off,
        ..common::render_options(w, h)
    };
    let setup = Setup::new(scene, &opts).unwrap_or_else(|e| panic!("{e}"));
    let settings = RenderSettings {
        width: w,
        height: h,
        spp,
        seed: 7,
        max_depth: 16,
        ..Default::default()
    };
    common::render_with(
        &Arc::new(setup.scene),
        &setup.camera,
        Backend::Bvh,
        &settings,
    )
}

fn pixels(img: &Image) -> Vec<glam::Vec4> {
    (0..img.height)
        .flat_map(|y| (0..img.width).map(move |x| img.get(x, y)))
        .collect()
}

fn mean_rgb(img: &Image) -> glam::Vec3 {
    let px = pixels(img);
    px.iter().map(|p| p.truncate()).sum::<glam::Vec3>() / px.len() as f32
}

/// A white Lambert quad lit only from behind (irradiance pi): without the extension (or at factor
/// 0, byte for byte the same image) its front is black; at factor 1 it shows E / pi = 1 everywhere,
/// which only NEE through the surface can give. Inside a volume (a unit cube), light still
/// diffuses through both walls, less than through one.
#[test]
fn diffuse_transmission_lets_the_light_behind_through() {
    let size = (24, 24);
    let none = render("dt-none.gltf", size, 4);
    let zero = render("dt-0.gltf", size, 4);
    assert_eq!(
        pixels(&none),
        pixels(&zero),
        "factor 0 differs from no extension"
    );
    assert_eq!(mean_rgb(&none), glam::Vec3::ZERO);
    let one = render("dt-1.gltf", size, 4);
    let m = mean_rgb(&one);
    eprintln!("diffuse transmission 1: mean radiance in front {m} (closed form 1)");
    for p in pixels(&one) {
        assert!(
            (p.truncate() - glam::Vec3::ONE).abs().max_element() < 1e-4,
            "pixel {p}"
        );
    }
    let cube = mean_rgb(&render("dt-volume.gltf", size, 16));
    eprintln!("diffuse transmission 1 in a volume (unit cube): mean radiance in front {cube}");
    assert!(cube.x > 0.05 && cube.x < 0.9, "{cube}");
}

/// The centroid (world x) of channel `c` of the stripe's image within 0.2 of `around`.
fn centroid(img: &Image, c: usize, around: f32) -> f32 {
    let (mut s, mut sx) = (0.0f64, 0.0f64);
    for y in 0..img.height {
        for x in 0..img.width {
            let wx = ((x as f32 + 0.5) / img.width as f32 - 0.5) * 3.0;
            if (wx - around).abs() < 0.2 {
                let v = img.get(x, y)[c] as f64;
                s += v;
                sx += v * wx as f64;
            }
        }
    }
    (sx / s) as f32
}

/// The lateral offset of a ray through a slab of thickness `t` and IOR `n` at incidence `theta`.
fn slab_shift(t: f32, n: f32, theta: f32) -> f32 {
    let r = (theta.sin() / n).asin();
    t * (theta - r).sin() / r.cos()
}

/// A stripe seen through a glass slab turned 60 degrees: dispersion 0 renders byte for byte as
/// without the extension, and red, green and blue images coincide; with dispersion 3 each channel's
/// image moves by the slab's lateral shift at that channel's IOR (red least, blue most).
#[test]
fn dispersion_separates_the_channels_through_a_slab() {
    let size = (300, 100);
    let none = render("disp-none.gltf", size, 4);
    let zero = render("disp-0.gltf", size, 4);
    assert_eq!(
        pixels(&none),
        pixels(&zero),
        "dispersion 0 differs from no extension"
    );
    let peak = |img: &Image| {
        let col = |x: usize| (0..img.height).map(|y| img.get(x, y).y).sum::<f32>();
        let best = (0..img.width)
            .max_by(|&a, &b| col(a).total_cmp(&col(b)))
            .unwrap();
        ((best as f32 + 0.5) / img.width as f32 - 0.5) * 3.0
    };
    let p0 = peak(&none);
    let [r0, g0, b0] = [0, 1, 2].map(|c| centroid(&none, c, p0));
    assert!(
        (r0 - b0).abs() < 1e-4 && (g0 - b0).abs() < 1e-4,
        "{r0} {g0} {b0}"
    );
    let theta = 60f32.to_radians();
    let expected_g = slab_shift(2.0, 1.5, theta);
    assert!(
        (g0.abs() - expected_g).abs() < 0.02,
        "image at {g0}, slab shift {expected_g}"
    );
    let disp = render("disp-3.gltf", size, 16);
    let p = peak(&disp);
    let c = [0, 1, 2].map(|k| centroid(&disp, k, p));
    let iors = channel_iors(1.5, 3.0);
    let shift = [0, 1, 2].map(|k| slab_shift(2.0, iors[k], theta));
    eprintln!(
        "dispersion 3: centroids R {:.4} G {:.4} B {:.4}; predicted shifts {shift:?}",
        c[0], c[1], c[2]
    );
    let spread = (c[2] - c[0]).abs();
    let predicted = shift[2] - shift[0];
    assert!(
        (spread - predicted).abs() < 0.15 * predicted,
        "blue - red {spread}, predicted {predicted}"
    );
    // Blue moves furthest from where an unrefracted ray would see the stripe (x = 0).
    assert!(c[2].abs() > c[1].abs() && c[1].abs() > c[0].abs(), "{c:?}");
}
