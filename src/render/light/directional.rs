//! Directional lights: irradiance arriving from one direction at infinity, a delta light (sampled,
//! never hit). Power is the flux through the scene's bounding disk.

use glam::Vec3;

use crate::render::bsdf::luminance;
use crate::scene::DirectionalLight;

/// Direction towards the light, infinite distance and the irradiance it brings.
pub(super) fn sample(l: &DirectionalLight) -> (Vec3, f32, Vec3) {
    (-l.direction.normalize(), f32::INFINITY, l.irradiance)
}

/// The light's weight among the lights: the luminance of its flux through `far_disk`, the area of
/// the scene's bounding disk.
pub(super) fn power(l: &DirectionalLight, far_disk: f32) -> f32 {
    far_disk * luminance(l.irradiance)
}
