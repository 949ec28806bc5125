//! Renders with closed-form answers: a Lambertian plane lit by a point light, a directional light, disk,
//! sphere and rectangle lights, and constant and mapped environments.

mod common;

use std::f32::consts::PI;
use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};
use glint::accel::Backend;
use glint::render::{LightSampler, RenderSettings};
use glint::scene::{
    Camera, DirectionalLight, DiskLight, EnvMap, Instance, Light, Material, Mesh, PointLight,
    RectLight, Scene, SphereLight,
};

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
        vec![Light::Point(PointLight {
            position: Vec3::new(0.0, h, 0.0),
            intensity: Vec3::splat(intensity),
        })],
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
        vec![Light::Directional(DirectionalLight {
            direction: -Vec3::new(theta.sin(), theta.cos(), 0.0),
            irradiance: Vec3::splat(irradiance),
        })],
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

/// The converged radiance at the centre pixel of a tiny, narrow image of `scene` seen by `camera`,
/// through the whole integrator with MIS, lights chosen by `light_sampler`.
fn area_lit_radiance(
    scene: &Arc<Scene>,
    camera: &Camera,
    backend: Backend,
    light_sampler: LightSampler,
) -> Vec3 {
    let settings = RenderSettings {
        width: 3,
        height: 3,
        spp: 2048,
        max_depth: 2,
        seed: 5,
        light_sampler,
        ..Default::default()
    };
    common::render_with(scene, camera, backend, &settings)
        .get(1, 1)
        .truncate()
}

/// Checks, on every backend, that the plane at the origin seen obliquely (Lambertian: any view will
/// do, and this one passes beside the lights above the origin) has grey radiance `expected` (1%).
fn assert_radiance(scene: &Arc<Scene>, expected: f32, what: &str) {
    assert_radiance_from(
        scene,
        &oblique_camera(),
        LightSampler::Power,
        expected,
        what,
    );
}

fn oblique_camera() -> Camera {
    Camera::look_at(Vec3::new(4.0, 1.0, 0.0), Vec3::ZERO, Vec3::Y, 1e-3)
}

fn assert_radiance_from(
    scene: &Arc<Scene>,
    camera: &Camera,
    light_sampler: LightSampler,
    expected: f32,
    what: &str,
) {
    for backend in Backend::all_available() {
        let l = area_lit_radiance(scene, camera, backend, light_sampler);
        for c in l.to_array() {
            assert!(
                (c - expected).abs() <= 0.01 * expected,
                "{what} ({backend}, lights by {light_sampler}): radiance {c}, expected {expected}"
            );
        }
    }
}

#[test]
fn lambertian_plane_under_a_disk_light() {
    // Irradiance pi L sin^2(theta) from a disk seen under half-angle theta; radiance rho E / pi.
    let (rho, l, h, r) = (0.5, 4.0, 1.5, 1.2);
    let scene = lambert_plane(
        rho,
        vec![Light::Disk(DiskLight {
            center: Vec3::new(0.0, h, 0.0),
            normal: -Vec3::Y,
            radius: r,
            radiance: Vec3::splat(l),
        })],
    );
    let sin2 = r * r / (r * r + h * h);
    assert_radiance(&scene, rho * l * sin2, "disk");
}

#[test]
fn lambertian_plane_under_a_sphere_light() {
    let (rho, l, d, r) = (0.7, 3.0, 2.0, 0.5);
    let scene = lambert_plane(
        rho,
        vec![Light::Sphere(SphereLight {
            center: Vec3::new(0.0, d, 0.0),
            radius: r,
            radiance: Vec3::splat(l),
        })],
    );
    assert_radiance(&scene, rho * l * (r / d) * (r / d), "sphere");
}

#[test]
fn lambertian_plane_under_a_rect_light() {
    // A 2a x 2b rectangle centred above the point: four corner form factors.
    let (rho, l, h, a, b) = (0.6f32, 2.0f32, 1.0f32, 0.8f32, 0.5f32);
    let scene = lambert_plane(
        rho,
        vec![Light::Rect(RectLight {
            corner: Vec3::new(-a, h, -b),
            edge_u: Vec3::new(2.0 * a, 0.0, 0.0),
            edge_v: Vec3::new(0.0, 0.0, 2.0 * b),
            radiance: Vec3::splat(l),
        })],
    );
    let (x, y) = (a / h, b / h);
    let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
    let f = 4.0 * (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * PI);
    assert_radiance(&scene, rho * l * f, "rect");
}

#[test]
fn constant_environment_map_renders_like_a_constant_environment() {
    // The plane sees the upper hemisphere: irradiance pi L, radiance rho L.
    let (rho, l) = (0.4, 1.5);
    let mut seen = Vec::new();
    for map in [None, Some(Arc::new(EnvMap::constant(16, 8, Vec3::ONE)))] {
        let scene = lambert_plane(
            rho,
            vec![Light::Environment {
                radiance: Vec3::splat(l),
                map,
            }],
        );
        assert_radiance(&scene, rho * l, "environment");
        seen.push(area_lit_radiance(
            &scene,
            &oblique_camera(),
            Backend::default_available(),
            LightSampler::Power,
        ));
    }
    assert!((seen[0] - seen[1]).abs().max_element() <= 0.01 * rho * l);
}

/// The form factor from a point of the y = 0 plane (facing +y) at the origin to the rectangle
/// [0, x] x [0, z] at height h above it, signed by the corner's quadrant (corners add up).
fn corner_form_factor(x: f64, z: f64, h: f64) -> f64 {
    let (sx, sz) = ((x * x + h * h).sqrt(), (z * z + h * h).sqrt());
    (x / sx * (z / sx).atan() + z / sz * (x / sz).atan()) / (2.0 * std::f64::consts::PI)
}

#[test]
fn lambertian_plane_beside_an_emissive_quad_hovering_1_cm_above_it() {
    // The Cornell box's ceiling beside its light: every light direction grazes, so a shadow ray
    // leaving an origin offset along the normal met the light's plane early and was blocked.
    let (rho, l, h) = (0.8f32, 5.0f32, 0.01f32);
    let (x0, x1, z0, z1) = (-0.5f32, -0.03f32, -0.2f32, 0.2f32);
    let scene = with_emissive_quad(lambert_plane(rho, Vec::new()), [x0, x1, z0, z1], h, l, 1);
    let f = |x: f32, z: f32| corner_form_factor(x as f64, z as f64, h as f64);
    let ff = f(x1, z1) - f(x0, z1) - f(x1, z0) + f(x0, z0);
    // Straight down and narrow: the irradiance changes fast with the distance to the light, so
    // an oblique pixel's footprint would average it over millimetres.
    let camera = Camera::look_at(Vec3::new(0.0, 5.0, 0.0), Vec3::ZERO, Vec3::Z, 1e-4);
    let expected = rho * l * ff.abs() as f32;
    assert_radiance_from(
        &scene,
        &camera,
        LightSampler::Power,
        expected,
        "beside a hovering quad",
    );
}

/// `scene` with a black rectangle [x0, x1] x [z0, z1] at height `h` that emits `l` (and so only
/// emits: nothing comes back from what it lights), cut into n x n squares of two triangles each.
fn with_emissive_quad(
    scene: Arc<Scene>,
    [x0, x1, z0, z1]: [f32; 4],
    h: f32,
    l: f32,
    n: u32,
) -> Arc<Scene> {
    let mut scene = Arc::unwrap_or_clone(scene);
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    let lerp = |a: f32, b: f32, t: u32| a + (b - a) * t as f32 / n as f32;
    for i in 0..=n {
        for j in 0..=n {
            positions.push(Vec3::new(lerp(x0, x1, i), h, lerp(z0, z1, j)));
        }
    }
    let at = |i: u32, j: u32| i * (n + 1) + j;
    for i in 0..n {
        for j in 0..n {
            indices.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            indices.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    scene.meshes.push(Mesh {
        name: "light".into(),
        normals: vec![-Vec3::Y; positions.len()],
        positions,
        indices,
        material: scene.materials.len() as u32,
        ..Default::default()
    });
    scene.materials.push(Material {
        emissive: Vec3::splat(l),
        base_color: Vec4::new(0.0, 0.0, 0.0, 1.0),
        metallic: 0.0,
        specular: 0.0,
        ..Default::default()
    });
    scene
        .instances
        .push(Instance::new(scene.meshes.len() as u32 - 1, Mat4::IDENTITY));
    Arc::new(scene)
}

#[test]
fn lambertian_plane_under_an_emissive_quad_of_512_triangles_by_power_and_by_bvh() {
    // Many emitters of one closed form: the light BVH must choose among them without bias.
    let (rho, l, h) = (0.6f32, 3.0f32, 0.7f32);
    let rect = [-0.9f32, 0.4, -0.3, 0.8];
    let scene = with_emissive_quad(lambert_plane(rho, Vec::new()), rect, h, l, 16);
    let [x0, x1, z0, z1] = rect.map(|v| v as f64);
    let f = |x: f64, z: f64| corner_form_factor(x, z, h as f64);
    let ff = f(x1, z1) - f(x0, z1) - f(x1, z0) + f(x0, z0);
    for sampler in [LightSampler::Power, LightSampler::Bvh] {
        let what = "under a tessellated quad";
        assert_radiance_from(
            &scene,
            &oblique_camera(),
            sampler,
            rho * l * ff as f32,
            what,
        );
    }
}

/// Direct light only (depth 1): the path's last ray only looks for emitters, and where they are a
/// few sampled triangles (up to 16) the integrator tests those and asks the accelerator only
/// whether the nearest is blocked. Both ways (8 triangles, and 18: the closest-hit query) must meet
/// the closed form, with MIS between the light and BSDF samples.
#[test]
fn last_ray_finds_few_emitters_as_the_closest_hit_does() {
    let (rho, l, h) = (0.7f32, 4.0f32, 0.5f32);
    let rect = [-0.6f32, 0.5, -0.4, 0.7];
    let [x0, x1, z0, z1] = rect.map(|v| v as f64);
    let f = |x: f64, z: f64| corner_form_factor(x, z, h as f64);
    let expected = rho * l * (f(x1, z1) - f(x0, z1) - f(x1, z0) + f(x0, z0)) as f32;
    for n in [2, 3] {
        let scene = with_emissive_quad(lambert_plane(rho, Vec::new()), rect, h, l, n);
        for backend in Backend::all_available() {
            let settings = RenderSettings {
                width: 3,
                height: 3,
                spp: 4096,
                max_depth: 1,
                seed: 9,
                ..Default::default()
            };
            let c = common::render_with(&scene, &oblique_camera(), backend, &settings).get(1, 1);
            for c in c.truncate().to_array() {
                assert!(
                    (c - expected).abs() <= 0.01 * expected,
                    "{} triangles ({backend}): radiance {c}, expected {expected}",
                    2 * n * n
                );
            }
        }
    }
}

/// A camera ray that meets nothing takes `Integrator::missed`, a short path; it must bring exactly
/// what the whole path would: the mapped environment everywhere, plus a rect light where the ray
/// passes through it (and then full coverage).
#[test]
fn missed_camera_rays_bring_what_the_whole_path_does() {
    use glint::render::{FirstHit, Integrator};
    use glint::sample::{AnySampler, Sampler, SamplerKind};
    use glint::scene::features::Features;
    let (w, h) = (64usize, 32usize);
    let pixels = (0..w * h)
        .map(|i| Vec3::new((i % w) as f32 / w as f32, (i / w) as f32 / h as f32, 0.5) * 3.0)
        .collect();
    let scene = Arc::new(Scene {
        lights: vec![
            Light::Environment {
                radiance: Vec3::splat(0.7),
                map: Some(Arc::new(EnvMap::new(w, h, pixels).unwrap())),
            },
            Light::Rect(RectLight {
                corner: Vec3::new(-1.0, 3.0, -1.0),
                edge_u: Vec3::new(2.0, 0.0, 0.0),
                edge_v: Vec3::new(0.0, 0.0, 2.0),
                radiance: Vec3::splat(5.0),
            }),
        ],
        ..Default::default()
    });
    let camera = Camera::look_at(Vec3::ZERO, Vec3::Y, Vec3::Z, 1.0);
    let accel = glint::accel::build(scene.clone(), Backend::Bvh).unwrap();
    let features = Features::of(&scene, &camera);
    let integrator = Integrator::new(&scene, accel.as_ref(), 5, &features, LightSampler::Power);
    let mut sampler = AnySampler::new(SamplerKind::Sobol, 1, 1);
    let (mut lit, mut unlit) = (0, 0);
    for i in 0..2000u32 {
        let t = i as f32 * 0.618_034;
        let d = Vec3::new((t * 7.0).sin(), (t * 3.0).cos(), (t * 5.0).sin()).normalize();
        let ray = glint::geometry::Ray::new(Vec3::ZERO, d);
        sampler.start(i % 7, i / 7, i);
        let whole = integrator.li(ray, FirstHit::Traced(None), &mut sampler);
        let short = integrator.missed(&ray);
        assert_eq!(whole.radiance, short.radiance, "direction {d}");
        assert_eq!(whole.rays, short.rays);
        if short.radiance.w == 1.0 {
            lit += 1;
        } else {
            unlit += 1;
        }
    }
    // Both kinds of ray were asked about.
    assert!(
        lit > 20 && unlit > 20,
        "{lit} through the light, {unlit} past it"
    );
}
