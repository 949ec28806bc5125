//! What glint adds when a file has no camera or no lights: a camera that frames the model's bounds the
//! way a viewer does, and a light rig (a soft environment plus a key light) so any asset reads clearly.

use glam::{Mat4, Vec3};

use super::{Camera, DirectionalLight, Light, Scene};
use crate::geometry::Aabb;

/// Default vertical field of view of the framing camera, in degrees.
pub const DEFAULT_FOV_DEG: f32 = 40.0;
/// Radiance of the default environment light.
pub const ENVIRONMENT_RADIANCE: f32 = 0.4;
/// Irradiance of the default key light.
pub const KEY_IRRADIANCE: f32 = 2.5;

/// The direction (from the target) in which the framing camera sits: in front, a little right and above.
pub fn default_view_direction() -> Vec3 {
    Vec3::new(0.45, 0.35, 1.0).normalize()
}

/// Camera distance at which a sphere of `radius` fills the narrower of the two fields of view.
pub fn framing_distance(radius: f32, yfov: f32, aspect: f32) -> f32 {
    let xfov = 2.0 * ((yfov * 0.5).tan() * aspect).atan();
    let fov = yfov.min(xfov);
    radius / (fov * 0.5).sin()
}

/// A camera looking at the centre of `bounds` from `direction`, far enough to see all of it.
pub fn frame_bounds(bounds: &Aabb, direction: Vec3, yfov: f32, aspect: f32) -> Camera {
    let (center, radius) = bounding_sphere(bounds);
    let eye = center + direction.normalize() * framing_distance(radius, yfov, aspect) * 1.05;
    let up = if direction.normalize().cross(Vec3::Y).length() < 1e-3 {
        Vec3::Z
    } else {
        Vec3::Y
    };
    let mut cam = Camera::look_at(eye, center, up, yfov);
    cam.name = "framed".into();
    cam
}

/// The camera glint renders through unless told otherwise: the file's first, or one framing the model.
pub fn default_camera(scene: &Scene, aspect: f32) -> Camera {
    scene.cameras.first().cloned().unwrap_or_else(|| {
        frame_bounds(
            &scene.bounds(),
            default_view_direction(),
            DEFAULT_FOV_DEG.to_radians(),
            aspect,
        )
    })
}

/// The view glint renders a scene from when told nothing: `default_camera`, with the light rig
/// placed from it added when the scene has no light of its own (`light_if_unlit`).
pub fn default_view(scene: &mut Scene, aspect: f32) -> Camera {
    let camera = default_camera(scene, aspect);
    light_if_unlit(scene, &camera.to_world);
    camera
}

/// Adds the light rig (placed relative to the camera) when the scene has no light of its own.
pub fn light_if_unlit(scene: &mut Scene, camera_to_world: &Mat4) {
    if !has_own_lights(scene) {
        scene.lights.extend(light_rig(camera_to_world));
    }
}

/// The light rig with `environment` in place of its constant environment (what `glint render --env`
/// uses: the map lights the model, the key light still shapes it).
pub fn light_rig_with_environment(camera_to_world: &Mat4, environment: Light) -> Vec<Light> {
    let mut rig = light_rig(camera_to_world);
    for l in &mut rig {
        if matches!(l, Light::Environment { .. }) {
            *l = environment.clone();
        }
    }
    rig
}

/// Centre and radius of the sphere around a box (a unit sphere for an empty box, so that empty files
/// still render).
pub fn bounding_sphere(bounds: &Aabb) -> (Vec3, f32) {
    if bounds.is_empty() {
        return (Vec3::ZERO, 1.0);
    }
    let r = bounds.extent().length() * 0.5;
    (bounds.center(), if r > 0.0 { r } else { 1.0 })
}

/// Emitting surfaces light the scene themselves when their flux is at least this share of the flux
/// the default environment would send into the model's bounding sphere. Measured shares: the Cornell
/// box 0.146 (its ceiling light), many-emitters 0.28, EmissiveStrengthTest 0.18 (glowing cubes, the
/// model's subject); AnisotropyBarnLamp 0.024 (a bulb hidden in its shade: alone it lit nothing in
/// view) and TextureEncodingTest 0.0045 (an emissive swatch among lit ones: alone the rest was black).
pub const OWN_EMISSION_SHARE: f64 = 0.05;

/// Whether the scene has light of its own: any `Light` (punctual, sphere, disk, rectangle or
/// environment), or untextured emissive surfaces bright and large enough to light it
/// (`OWN_EMISSION_SHARE`, as in a Cornell box). Textured emission (glowing details) does not count.
pub fn has_own_lights(scene: &Scene) -> bool {
    !scene.lights.is_empty() || emission_share(scene) >= OWN_EMISSION_SHARE
}

/// The flux of the scene's untextured emissive triangles (luminance times area) over that of the
/// default environment into the bounding sphere (`ENVIRONMENT_RADIANCE` times the sphere's area);
/// the factor pi of both fluxes cancels.
pub fn emission_share(scene: &Scene) -> f64 {
    let mut flux = 0.0f64;
    for (i, inst) in scene.instances.iter().enumerate() {
        let m = scene.material_of_mesh(inst.mesh);
        if !m.is_emissive() || m.emissive_tex.is_some() {
            continue;
        }
        let luminance = crate::geometry::colour::luminance(m.emissive) as f64;
        let mesh = &scene.meshes[inst.mesh as usize];
        let area: f64 = (0..mesh.indices.len() as u32)
            .map(|prim| {
                let [a, b, c] = scene.world_triangle(i as u32, prim);
                0.5 * (b - a).cross(c - a).length() as f64
            })
            .sum();
        flux += luminance * area;
    }
    let (_, r) = bounding_sphere(&scene.bounds());
    flux / (ENVIRONMENT_RADIANCE as f64 * 4.0 * std::f64::consts::PI * (r as f64).powi(2))
}

/// A soft environment and a key light from above and to the left of the camera.
pub fn light_rig(camera_to_world: &Mat4) -> Vec<Light> {
    let right = camera_to_world.x_axis.truncate().normalize();
    let up = camera_to_world.y_axis.truncate().normalize();
    let back = camera_to_world.z_axis.truncate().normalize();
    let towards_light = (-0.6 * right + 1.0 * up + 0.8 * back).normalize();
    vec![
        Light::Environment {
            radiance: Vec3::splat(ENVIRONMENT_RADIANCE),
            map: None,
        },
        Light::Directional(DirectionalLight {
            direction: -towards_light,
            irradiance: Vec3::splat(KEY_IRRADIANCE),
        }),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::RayCamera;
    use crate::scene::generate::{box_mesh, scene_of};
    use crate::scene::{Instance, Material, TexRef};

    /// A closed room (the box from -1 to 1) with a thin emissive slab of radiance `radiance` under
    /// its ceiling, the whole scene scaled by `scale`.
    fn room(radiance: f32, scale: f32) -> Scene {
        let mut light = box_mesh(Vec3::new(-0.25, 0.98, -0.25), Vec3::new(0.25, 0.99, 0.25));
        light.material = 1;
        let to_world = Mat4::from_scale(Vec3::splat(scale));
        let mut scene = scene_of(
            vec![box_mesh(Vec3::splat(-1.0), Vec3::splat(1.0)), light],
            vec![Instance::new(0, to_world), Instance::new(1, to_world)],
        );
        scene.materials.push(Material {
            emissive: Vec3::splat(radiance),
            ..Default::default()
        });
        scene
    }

    /// The share is the slab's luminance times its area over the default environment's radiance
    /// times the bounding sphere's area, at any scale; a bright ceiling light is the room's own
    /// light, a dim one is not, nor is a textured one however bright, and a punctual light always is.
    #[test]
    fn emitters_light_the_scene_when_their_flux_is_large_enough() {
        let area = 2.0 * (0.5 * 0.5 + 2.0 * 0.5 * 0.01);
        let sphere = 4.0 * std::f64::consts::PI * 3.0;
        for scale in [1.0, 2.0, 0.01] {
            let share = emission_share(&room(10.0, scale));
            let expected = 10.0 * area / (ENVIRONMENT_RADIANCE as f64 * sphere);
            assert!(
                (share / expected - 1.0).abs() < 1e-4,
                "scale {scale}: {share} against {expected}"
            );
        }
        assert!(has_own_lights(&room(10.0, 1.0)));
        assert!(!has_own_lights(&room(0.5, 1.0)));
        let mut textured = room(10.0, 1.0);
        textured.materials[1].emissive_tex = Some(TexRef {
            texture: 0,
            uv_transform: TexRef::IDENTITY_UV,
            tex_coord: 0,
        });
        assert_eq!(emission_share(&textured), 0.0);
        let mut lit = room(0.0, 1.0);
        lit.lights.push(Light::Directional(DirectionalLight {
            direction: -Vec3::Y,
            irradiance: Vec3::ONE,
        }));
        assert!(has_own_lights(&lit));
        assert!(!has_own_lights(&room(0.0, 1.0)));
    }

    #[test]
    fn framed_box_is_inside_the_image() {
        let b = Aabb {
            min: Vec3::new(10.0, -3.0, 2.0),
            max: Vec3::new(14.0, 5.0, 3.0),
        };
        for aspect in [0.5, 1.0, 2.0] {
            let cam = frame_bounds(&b, default_view_direction(), 0.7, aspect);
            let (w, h) = ((100.0 * aspect) as usize, 100);
            let rc = RayCamera::new(&cam, w, h);
            for i in 0..8 {
                let c = Vec3::new(
                    if i & 1 == 0 { b.min.x } else { b.max.x },
                    if i & 2 == 0 { b.min.y } else { b.max.y },
                    if i & 4 == 0 { b.min.z } else { b.max.z },
                );
                let p = rc.project(c).unwrap();
                assert!(p.x > 0.0 && p.x < w as f32 && p.y > 0.0 && p.y < h as f32);
            }
            let centre = rc.project(b.center()).unwrap();
            assert!((centre - glam::Vec2::new(w as f32, h as f32) * 0.5).length() < 1.0);
        }
    }
}
