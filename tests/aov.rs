//! Feature images (AOVs) checked against geometry: albedo equals a flat base colour (also seen in a
//! mirror), sphere normals are unit and radial, a facing plane's depth is its distance; features leave
//! the beauty untouched; the CLI writes named EXR channels and PNG files beside the output.

mod common;

use std::process::Command;
use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};
use glint::accel::{self, Backend};
use glint::film::aov::{FeatureImages, NO_ID};
use glint::film::layers::read_channel;
use glint::render::{self, RenderOutput, RenderSettings};
use glint::scene::generate::icosphere;
use glint::scene::{Camera, Instance, Light, Material, Mesh, Scene};

fn render_full(
    scene: Scene,
    camera: &Camera,
    size: usize,
    spp: u32,
    features: bool,
) -> RenderOutput {
    let scene = Arc::new(scene);
    let accel = accel::build(scene.clone(), Backend::Bvh).unwrap();
    let settings = RenderSettings {
        width: size,
        height: size,
        spp,
        seed: 3,
        feature_images: features,
        ..Default::default()
    };
    render::render_full(
        &scene,
        accel.as_ref(),
        camera,
        &settings,
        &indicatif::ProgressBar::hidden(),
    )
}

fn features(scene: Scene, camera: &Camera, size: usize, spp: u32) -> FeatureImages {
    render_full(scene, camera, size, spp, true)
        .features
        .unwrap()
}

fn diffuse(rgb: Vec3) -> Material {
    Material {
        base_color: rgb.extend(1.0),
        metallic: 0.0,
        roughness: 1.0,
        ..Default::default()
    }
}

/// A unit sphere of `material` at the origin in a uniform environment, seen from +Z.
fn sphere_scene(material: Material) -> (Scene, Camera) {
    let scene = Scene {
        meshes: vec![icosphere(4, 0.0)],
        instances: vec![Instance::new(0, Mat4::IDENTITY)],
        materials: vec![material],
        lights: vec![Light::Environment {
            radiance: Vec3::ONE,
            map: None,
        }],
        ..Default::default()
    };
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 0.45);
    (scene, camera)
}

/// Pixels of a `size` image whose whole footprint lies well inside the sphere's disc.
fn on_sphere(size: usize) -> Vec<usize> {
    (0..size * size)
        .filter(|i| {
            let dx = (i % size) as f32 + 0.5 - size as f32 / 2.0;
            let dy = (i / size) as f32 + 0.5 - size as f32 / 2.0;
            // The unit sphere at distance 4 spans about 0.51 of the 0.45 rad field of view.
            (dx * dx + dy * dy).sqrt() < 0.4 * size as f32
        })
        .collect()
}

/// A square of half-size `s` through `centre` facing `n`.
fn quad(centre: Vec3, n: Vec3, s: f32, material: u32) -> Mesh {
    let t = n.any_orthonormal_vector();
    let b = n.cross(t);
    Mesh {
        name: "quad".into(),
        positions: [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(u, v)| centre + (t * u + b * v) * s)
            .to_vec(),
        normals: vec![n; 4],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        material,
        ..Default::default()
    }
}

#[test]
fn albedo_of_a_flat_diffuse_sphere_is_its_base_colour() {
    let base = Vec3::new(0.8, 0.3, 0.1);
    let (scene, camera) = sphere_scene(diffuse(base));
    let f = features(scene, &camera, 24, 8);
    let px = on_sphere(24);
    assert!(px.len() > 200);
    for &i in &px {
        assert!(
            (f.albedo[i] - base).abs().max_element() < 1e-6,
            "{}",
            f.albedo[i]
        );
        assert_eq!((f.instance[i], f.material[i]), (0, 0));
    }
    // A corner sees the environment: albedo 1 (all illumination), no surface, no ids.
    assert_eq!(f.albedo[0], Vec3::ONE);
    assert_eq!(f.normal[0], Vec3::ZERO);
    assert_eq!(f.depth[0], f32::INFINITY);
    assert_eq!((f.instance[0], f.material[0]), (NO_ID, NO_ID));
}

#[test]
fn sphere_normals_are_unit_and_radial_and_positions_lie_on_it() {
    let (scene, camera) = sphere_scene(diffuse(Vec3::splat(0.5)));
    let eye = camera.position();
    let f = features(scene, &camera, 24, 8);
    for i in on_sphere(24) {
        let (n, p) = (f.normal[i], f.position[i]);
        assert!((n.length() - 1.0).abs() < 1e-5, "|n| = {}", n.length());
        // Facets of a level-4 icosphere lie within 0.1% of the unit sphere, and the mean of the
        // points under the filter's footprint (3 pixels wide) a little inside the curved surface.
        assert!(
            p.length() < 1.0 && p.length() > 0.995,
            "|p| = {}",
            p.length()
        );
        // A pixel averages normals over its footprint: within a degree of the mean position's.
        assert!(n.dot(p.normalize()) > 0.9998, "n {n} at p {p}");
        assert!(n.dot(eye - p) > 0.0, "the normal faces the camera");
        // Depth along the view axis (the camera looks down -Z from z = 4).
        assert!((f.depth[i] - (4.0 - p.z)).abs() < 1e-4);
    }
}

#[test]
fn depth_of_a_facing_plane_is_its_distance() {
    let d = 3.25;
    let scene = Scene {
        meshes: vec![quad(Vec3::new(0.0, 0.0, -d), Vec3::Z, 10.0, 0)],
        instances: vec![Instance::new(0, Mat4::IDENTITY)],
        materials: vec![diffuse(Vec3::splat(0.5))],
        lights: vec![Light::Environment {
            radiance: Vec3::ONE,
            map: None,
        }],
        ..Default::default()
    };
    let camera = Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, Vec3::Y, 0.8);
    let f = features(scene, &camera, 16, 4);
    for (i, &z) in f.depth.iter().enumerate() {
        assert!((z - d).abs() < 1e-5 * d, "pixel {i}: depth {z}, want {d}");
        assert!((f.position[i].z + d).abs() < 1e-5);
        assert!((f.normal[i] - Vec3::Z).length() < 1e-6);
    }
}

#[test]
fn a_mirror_shows_the_albedo_and_normal_of_what_it_reflects() {
    // The camera at z = 2 looks at a mirror in the plane z = 0; behind the camera, at z = 4, a red
    // wall faces the mirror. Depth and ids stay the mirror's.
    let red = Vec3::new(0.9, 0.1, 0.2);
    let mirror = Material {
        base_color: Vec4::ONE,
        metallic: 1.0,
        roughness: 0.0,
        ..Default::default()
    };
    let scene = Scene {
        meshes: vec![
            quad(Vec3::ZERO, Vec3::Z, 10.0, 0),
            quad(Vec3::new(0.0, 0.0, 4.0), Vec3::NEG_Z, 20.0, 1),
        ],
        instances: vec![
            Instance::new(0, Mat4::IDENTITY),
            Instance::new(1, Mat4::IDENTITY),
        ],
        materials: vec![mirror, diffuse(red)],
        lights: vec![Light::Environment {
            radiance: Vec3::ONE,
            map: None,
        }],
        ..Default::default()
    };
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO, Vec3::Y, 0.6);
    let f = features(scene, &camera, 12, 4);
    for i in 0..f.albedo.len() {
        assert!(
            (f.albedo[i] - red).abs().max_element() < 1e-6,
            "{}",
            f.albedo[i]
        );
        assert!(
            (f.normal[i] - Vec3::NEG_Z).length() < 1e-6,
            "{}",
            f.normal[i]
        );
        assert!((f.depth[i] - 2.0).abs() < 1e-5);
        assert_eq!((f.instance[i], f.material[i]), (0, 0));
    }
}

#[test]
fn feature_images_leave_the_beauty_bit_identical() {
    let (scene, camera) = sphere_scene(diffuse(Vec3::new(0.2, 0.6, 0.4)));
    let plain = render_full(scene.clone(), &camera, 20, 6, false);
    let with = render_full(scene, &camera, 20, 6, true);
    assert!(plain.features.is_none());
    assert_eq!(plain.image, with.image);
    assert_eq!(plain.stats.rays, with.stats.rays);
    // Variance is positive where the sphere's lighting is noisy, zero nowhere on it.
    let f = with.features.unwrap();
    assert!(on_sphere(20)
        .iter()
        .all(|&i| f.variance[i].min_element() > 0.0));
}

fn glint(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_glint"))
        .args([
            "render",
            "assets/demo/demo.glb",
            "--width",
            "24",
            "--height",
            "16",
            "--spp",
            "2",
        ])
        .args(["--backend", "bvh", "--quiet"])
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap()
}

#[test]
fn cli_writes_named_exr_channels_and_png_files_beside_the_output() {
    let dir = tempfile::tempdir().unwrap();
    let exr = dir.path().join("a.exr");
    let all = "albedo,normal,depth,position,instance,material,variance,spp";
    let o = glint(&["-o", exr.to_str().unwrap(), "--aov", all]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let names = [
        "R",
        "G",
        "B",
        "A",
        "albedo.R",
        "albedo.G",
        "albedo.B",
        "N.X",
        "N.Y",
        "N.Z",
        "Z",
        "P.X",
        "P.Y",
        "P.Z",
        "instance.id",
        "material.id",
        "variance.R",
        "variance.G",
        "variance.B",
        "spp.count",
    ];
    for n in names {
        let ch = read_channel(&exr, n)
            .unwrap()
            .unwrap_or_else(|| panic!("no channel {n}"));
        assert_eq!(ch.len(), 24 * 16);
    }
    assert!(read_channel(&exr, "spp.count")
        .unwrap()
        .unwrap()
        .iter()
        .all(|&n| n == 2.0));
    // Only the one file.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);

    let png = dir.path().join("b.png");
    let o = glint(&[
        "-o",
        png.to_str().unwrap(),
        "--aov",
        "albedo,normal,depth,instance",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for name in [
        "b.png",
        "b.albedo.png",
        "b.normal.png",
        "b.depth.png",
        "b.instance.png",
    ] {
        let img = image::open(dir.path().join(name)).unwrap();
        assert_eq!((img.width(), img.height()), (24, 16), "{name}");
    }
}

#[test]
fn cli_refuses_beauty_raw_without_denoise_and_aovs_on_shards() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("a.exr");
    let o = glint(&["-o", out.to_str().unwrap(), "--aov", "beauty-raw"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("needs --denoise"));
    let o = glint(&[
        "-o",
        out.to_str().unwrap(),
        "--aov",
        "albedo",
        "--sample-shard",
        "0/2",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(!out.exists());
}
