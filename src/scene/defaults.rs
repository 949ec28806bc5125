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

/// Whether the scene has light of its own: any `Light` (punctual, sphere, disk, rectangle or
/// environment), or an untextured emissive material (a deliberate light source, as in a Cornell box).
/// Textured emission (glowing details) does not count.
pub fn has_own_lights(scene: &Scene) -> bool {
    !scene.lights.is_empty()
        || scene.instances.iter().any(|i| {
            let m = scene.material_of_mesh(i.mesh);
            m.is_emissive() && m.emissive_tex.is_none()
        })
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
