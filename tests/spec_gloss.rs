//! KHR_materials_pbrSpecularGlossiness: factors and textures become glint's metallic-roughness +
//! specular-colour material as the extension's BRDF inputs say, and the spec's own gold example
//! renders like the metallic-roughness gold it pairs with it.

mod common;

use std::path::{Path, PathBuf};

use glint::render::RenderSettings;
use glint::Scene;

fn asset() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/specgloss/specgloss.gltf")
}

fn material<'a>(scene: &'a Scene, name: &str) -> &'a glint::scene::Material {
    scene.materials.iter().find(|m| m.name == name).unwrap()
}

#[test]
fn factors_give_the_extensions_f0_diffuse_and_roughness() {
    let scene = Scene::load(&asset()).unwrap();
    let gold = material(&scene, "gold");
    assert_eq!(gold.metallic, 0.0);
    assert!((gold.roughness - 0.1).abs() < 1e-6, "{}", gold.roughness);
    assert_eq!(gold.base_color, glam::Vec4::new(0.0, 0.0, 0.0, 1.0));
    // glint's dielectric F0 is min(F0(ior) * specular colour, 1) with F0(1.5) = 0.04.
    let f0 = (gold.layers.specular_color * 0.04).min(glam::Vec3::ONE);
    let want = glam::Vec3::new(1.0, 0.766, 0.336);
    assert!((f0 - want).abs().max_element() < 1e-5, "{f0}");
    assert!(gold.metallic_roughness_tex.is_none() && gold.base_color_tex.is_none());
}

#[test]
fn textures_give_diffuse_specular_colour_and_roughness_from_glossiness() {
    let scene = Scene::load(&asset()).unwrap();
    let m = material(&scene, "textured");
    let diffuse = &scene.textures[m.base_color_tex.unwrap().texture as usize];
    assert!(diffuse.srgb);
    assert_eq!(diffuse.pixels[0], [200, 30, 30, 255]);
    let spec = &scene.textures[m.layers.specular_color_tex.unwrap().texture as usize];
    assert!(spec.srgb, "the specular colour is sRGB-encoded");
    assert_eq!(spec.pixels[3], [60, 90, 120, 64]);
    // Roughness 1 - glossinessFactor * A, in G of a linear texture, the factor 1.
    assert_eq!(m.roughness, 1.0);
    let rough = &scene.textures[m.metallic_roughness_tex.unwrap().texture as usize];
    assert!(!rough.srgb);
    let g: Vec<u8> = rough.pixels.iter().map(|p| p[1]).collect();
    let want: Vec<u8> = [255.0f32, 128.0, 0.0, 64.0]
        .iter()
        .map(|a| ((1.0 - 0.5 * a / 255.0) * 255.0).round() as u8)
        .collect();
    assert_eq!(g, want);
    assert!(rough.pixels.iter().all(|p| p[2] == 0), "metalness 0");
    assert!((m.layers.specular_color - glam::Vec3::splat(0.05 / 0.04)).length() < 1e-5);
}

#[test]
fn the_specs_gold_renders_like_its_metallic_roughness_fallback() {
    // The spec: "the specular property ... is the same as the base color value from the
    // metallic-roughness material model for metals". glint's tinted dielectric Fresnel rises to 1
    // at grazing angles as the metal's Schlick Fresnel does, so the two agree to within the
    // difference of those rises.
    let dir = tempfile::tempdir().unwrap();
    let mut doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(asset()).unwrap()).unwrap();
    doc["materials"][0]
        .as_object_mut()
        .unwrap()
        .remove("extensions");
    let fallback = dir.path().join("fallback.gltf");
    std::fs::write(&fallback, doc.to_string()).unwrap();
    let settings = RenderSettings {
        width: 64,
        height: 32,
        spp: 32,
        max_depth: 3,
        seed: 5,
        ..Default::default()
    };
    let backend = common::render_backends()[0];
    let render = |p: &Path| {
        let (s, c) = common::load_for_render(p, settings.width, settings.height);
        common::render_with(&s, &c, backend, &settings)
    };
    let (sg, mr) = (render(&asset()), render(&fallback));
    // The left half holds the gold sphere.
    let left_mean = |img: &glint::film::Image| {
        let mut sum = glam::Vec3::ZERO;
        for y in 0..img.height {
            for x in 0..img.width / 2 {
                sum += img.get(x, y).truncate();
            }
        }
        sum / (img.width * img.height / 2) as f32
    };
    let (a, b) = (left_mean(&sg), left_mean(&mr));
    let rel = (a - b).abs() / b.max(glam::Vec3::splat(1e-4));
    eprintln!("spec-gloss gold {a} vs metal-rough gold {b}: relative {rel}");
    assert!(rel.max_element() < 0.03, "{a} vs {b}");
    assert!(!sg.has_non_finite());
}
