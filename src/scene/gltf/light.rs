//! KHR_lights_punctual lights and glTF cameras, placed by their node's world transform: each is
//! built in the node's frame (at the origin, looking down -Z) and moved by `Light::transformed`.

use glam::{Mat4, Quat, Vec3};
use gltf::khr_lights_punctual::Kind;

use super::Loader;
use crate::scene::{Camera, DirectionalLight, Light, PointLight, Projection, SpotLight};

impl Loader<'_> {
    /// Adds a node's light, or a warning when its colour or direction is unusable; gives the light
    /// in its node's frame when it was added.
    pub(super) fn light(
        &mut self,
        light: &gltf::khr_lights_punctual::Light,
        world: Mat4,
        label: &str,
    ) -> Option<Light> {
        let color = Vec3::from(light.color()) * light.intensity();
        let local = match light.kind() {
            Kind::Point => Light::Point(PointLight {
                position: Vec3::ZERO,
                intensity: color,
            }),
            Kind::Spot {
                inner_cone_angle,
                outer_cone_angle,
            } => Light::Spot(SpotLight {
                position: Vec3::ZERO,
                direction: Vec3::NEG_Z,
                intensity: color,
                cos_inner: inner_cone_angle.cos(),
                cos_outer: outer_cone_angle.cos(),
            }),
            Kind::Directional => Light::Directional(DirectionalLight {
                direction: Vec3::NEG_Z,
                irradiance: color,
            }),
        };
        let placed = local.transformed(&world);
        let direction_lost = matches!(
            placed,
            Light::Spot(SpotLight { direction, .. }) | Light::Directional(DirectionalLight { direction, .. }) if direction == Vec3::ZERO
        );
        if !color.is_finite() || direction_lost {
            self.scene.warnings.push(format!(
                "{label}: light {} has no usable colour or direction; skipped",
                light.index()
            ));
            return None;
        }
        self.scene.lights.push(placed);
        Some(local)
    }
}

/// A node's camera: its world transform without scale, and the file's projection.
pub(super) fn camera(cam: &gltf::Camera, node: &gltf::Node, world: Mat4) -> Camera {
    let (_, rot, trans) = world.to_scale_rotation_translation();
    let rot = if rot.is_finite() && rot.length() > 0.0 {
        rot.normalize()
    } else {
        Quat::IDENTITY
    };
    let projection = match cam.projection() {
        gltf::camera::Projection::Perspective(p) => Projection::Perspective {
            yfov: p.yfov(),
            aspect: p.aspect_ratio(),
        },
        gltf::camera::Projection::Orthographic(o) => Projection::Orthographic {
            xmag: o.xmag(),
            ymag: o.ymag(),
        },
    };
    let name = cam
        .name()
        .or(node.name())
        .map(str::to_owned)
        .unwrap_or_else(|| format!("camera {}", cam.index()));
    Camera {
        name,
        to_world: Mat4::from_rotation_translation(rot, trans),
        projection,
        lens: None,
        motion: None,
    }
}
