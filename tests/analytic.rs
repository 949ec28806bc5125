//! Renders with closed-form answers: a Lambertian plane lit by a point light and by a directional light.

mod common;

use std::f32::consts::PI;
use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};
use glint::accel::Backend;
use glint::render::RenderSettings;
use glint::scene::{Camera, Instance, Light, Material, Mesh, Scene};

/// A 200 x 200 square in the y = 0 plane, of a pure Lambertian material with albedo `rho`.
fn lambert_plane(rho: f32, lights: Vec<Light>) -> Arc<Scene> {
    let s = 100.0;
    let mesh = Mesh {
        name: "plane".into(),
        positions: vec![
            Vec3::new(-s, 0.0, -s),
            Vec3::new(s, 0.0, -s),
            Vec3::new(s, 0.0, s),
            Vec3::new(-s, 0.0, s),
        ],
        normals: vec![Vec3::Y; 4],
        indices: vec![[0, 2, 1], [0, 3, 2]],
        ..Default::default()
    };
    let material = Material {
        base_color: Vec4::new(rho, rho, rho, 1.0),
        metallic: 0.0,
        specular: 0.0,
        ..Default::default()
    };
    Arc::new(Scene {
        meshes: vec![mesh],
        instances: vec![Instance::new(0, Mat4::IDENTITY)],
        materials: vec![material],
        lights,
        ..Default::default()
    })
}

/// The centre pixel of a narrow view straight down at the origin.
fn centre_radiance(scene: &Arc<Scene>, backend: Backend) -> Vec3 {
    let camera = Camera::look_at(Vec3::new(0.0, 5.0, 0.0), Vec3::ZERO, Vec3::Z, 1e-3);
    let settings = RenderSettings {
        width: 5,
        height: 5,
        spp: 4,
        max_depth: 2,
        seed: 3,
        ..Default::default()
    };
    let img = common::render_with(scene, &camera, backend, &settings);
    img.get(2, 2).truncate()
}

#[test]
fn lambertian_plane_under_a_point_light() {
    let (rho, intensity, h) = (0.6, 40.0, 2.5);
    let scene = lambert_plane(
        rho,
        vec![Light::Point {
            position: Vec3::new(0.0, h, 0.0),
            intensity: Vec3::splat(intensity),
        }],
    );
    let expected = rho * intensity / (PI * h * h);
    for backend in Backend::all_available() {
        let l = centre_radiance(&scene, backend);
        for c in l.to_array() {
            assert!(
                (c - expected).abs() <= 0.01 * expected,
                "{backend}: radiance {c}, expected {expected}"
            );
        }
    }
}

#[test]
fn lambertian_plane_under_a_directional_light() {
    let (rho, irradiance) = (0.3, 2.0);
    let theta = 0.6f32;
    let scene = lambert_plane(
        rho,
        vec![Light::Directional {
            direction: -Vec3::new(theta.sin(), theta.cos(), 0.0),
            irradiance: Vec3::splat(irradiance),
        }],
    );
    let expected = rho / PI * irradiance * theta.cos();
    for backend in Backend::all_available() {
        let l = centre_radiance(&scene, backend);
        assert!(
            (l.x - expected).abs() <= 0.01 * expected,
            "{backend}: radiance {}, expected {expected}",
            l.x
        );
    }
}
