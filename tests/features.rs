//! Features derived from what a material can do at any texel: a factor with a texture may take any
//! value between 0 and the factor. A thin transmissive pane whose metalness comes from a texture
//! passes shadow rays, TransmissionRoughnessTest (metalness from textures) reports transmission
//! under --verbose, and COLOR_0's alpha cuts out a masked mesh.

mod common;

use std::f32::consts::PI;
use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};
use glint::accel::Backend;
use glint::render::RenderSettings;
use glint::scene::features::Features;
use glint::scene::{
    AlphaMode, Camera, Instance, Light, Material, Mesh, PointLight, Scene, TexRef, Texture,
    TextureFilter, Wrap,
};

/// A horizontal square of half-size `s` at height `y`, facing up.
fn quad(y: f32, s: f32, material: u32) -> Mesh {
    Mesh {
        name: "quad".into(),
        positions: vec![
            Vec3::new(-s, y, s),
            Vec3::new(s, y, s),
            Vec3::new(s, y, -s),
            Vec3::new(-s, y, -s),
        ],
        normals: vec![Vec3::Y; 4],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        material,
        ..Default::default()
    }
}

/// A 1x1 linear texture of one texel.
fn texel(rgba: [u8; 4]) -> Texture {
    Texture {
        name: "texel".into(),
        width: 1,
        height: 1,
        pixels: vec![rgba],
        srgb: false,
        wrap_s: Wrap::Repeat,
        wrap_t: Wrap::Repeat,
        filter: TextureFilter::Linear,
    }
}

/// A floor of albedo `rho` under a pane at height 1 and a point light above it; the camera looks
/// straight down through the pane.
fn pane_scene(pane: Material, textures: Vec<Texture>) -> Arc<Scene> {
    let floor = Material {
        base_color: Vec4::new(0.6, 0.6, 0.6, 1.0),
        metallic: 0.0,
        specular: 0.0,
        ..Default::default()
    };
    Arc::new(Scene {
        meshes: vec![quad(0.0, 100.0, 0), quad(1.0, 100.0, 1)],
        instances: vec![
            Instance::new(0, Mat4::IDENTITY),
            Instance::new(1, Mat4::IDENTITY),
        ],
        materials: vec![floor, pane],
        textures,
        lights: vec![Light::Point(PointLight {
            position: Vec3::new(0.0, 2.5, 0.0),
            intensity: Vec3::splat(40.0),
        })],
        ..Default::default()
    })
}

fn centre_mean(scene: &Arc<Scene>) -> Vec3 {
    let camera = Camera::look_at(Vec3::new(0.0, 2.0, 0.0), Vec3::ZERO, Vec3::Z, 1e-3);
    let settings = RenderSettings {
        width: 5,
        height: 5,
        spp: 64,
        max_depth: 3,
        seed: 7,
        ..Default::default()
    };
    let img = common::render_with(scene, &camera, Backend::Bvh, &settings);
    (0..25)
        .map(|i| img.get(i % 5, i / 5).truncate())
        .sum::<Vec3>()
        / 25.0
}

#[test]
fn a_thin_pane_whose_metalness_comes_from_a_texture_passes_direct_light() {
    let tint = Vec3::new(1.0, 0.8, 0.5);
    // Metallic factor 1, times the texture's B = 0: a dielectric everywhere, as the factor-0 pane.
    let textured = Material {
        base_color: tint.extend(1.0),
        metallic: 1.0,
        roughness: 0.0,
        metallic_roughness_tex: Some(TexRef::new(0)),
        transmission: 1.0,
        ..Default::default()
    };
    assert!(textured.is_transmissive() && textured.is_thin_walled());
    let scene = pane_scene(textured, vec![texel([0, 255, 0, 255])]);
    let camera = Camera::look_at(Vec3::Y * 2.0, Vec3::ZERO, Vec3::Z, 1e-3);
    let f = Features::of(&scene, &camera);
    assert!(f.transmission && f.thin_walls, "{}", f.describe());
    // The closed form of tests/materials.rs: through the pane both ways, 1 - F = 0.96 each.
    let t = tint * 0.96;
    let expected = t * t * (0.6 * 40.0 / (PI * 2.5 * 2.5));
    let got = centre_mean(&scene);
    assert!(
        (got - expected).abs().max_element() < 0.01 * expected.max_element(),
        "{got} vs {expected}"
    );
    // A truly metallic pane (no texture) is opaque: no transmission feature, no thin walls.
    let metal = Material {
        metallic: 1.0,
        transmission: 1.0,
        ..Default::default()
    };
    assert!(!metal.is_transmissive());
}

#[test]
fn transmission_roughness_test_reports_transmission_under_verbose() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let path =
        shared.join("gltf/TransmissionRoughnessTest/glTF-Binary/TransmissionRoughnessTest.glb");
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t.png");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .args([
            "render",
            path.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ])
        .args(["--width", "8", "--height", "8", "--spp", "1", "--verbose"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    let line = err
        .lines()
        .find(|l| l.contains("uses:"))
        .expect("a features line");
    let (uses, skips) = line.split_once("skips:").unwrap();
    // Its glass takes metallicFactor 1 (the default) times textures whose B is 0; thick (a volume).
    assert!(uses.contains("transmission"), "{line}");
    assert!(skips.contains("thin walls"), "{line}");
}

#[test]
fn vertex_alpha_cuts_out_a_masked_mesh() {
    let mut scene = Scene {
        meshes: vec![quad(0.0, 1.0, 0)],
        instances: vec![Instance::new(0, Mat4::IDENTITY)],
        materials: vec![Material {
            alpha_mode: AlphaMode::Mask(0.5),
            ..Default::default()
        }],
        ..Default::default()
    };
    assert!(!scene.mesh_needs_alpha_test(0), "opaque everywhere");
    scene.meshes[0].colors = vec![Vec4::new(1.0, 1.0, 1.0, 0.0); 4];
    assert!(scene.mesh_needs_alpha_test(0));
    let scene = Arc::new(scene);
    let camera = Camera::look_at(Vec3::Y * 2.0, Vec3::ZERO, Vec3::Z, 0.3);
    assert!(Features::of(&scene, &camera).alpha);
    for backend in common::render_backends() {
        let accel = glint::accel::build(scene.clone(), backend).unwrap();
        let ray = glint::geometry::Ray::new(Vec3::Y * 2.0, -Vec3::Y);
        assert!(
            accel.intersect(&ray).is_none(),
            "{backend}: alpha 0 is cut out"
        );
    }
}
