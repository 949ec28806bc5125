//! Directional lights: irradiance arriving from one direction at infinity, a delta light (sampled,
//! never hit). Power is the flux through the scene's bounding disk.

use glam::Vec3;

use crate::render::bsdf::luminance;

/// Direction towards the light, infinite distance and the irradiance it brings; `direction` is where
/// the light travels to.
pub(super) fn sample(direction: Vec3, irradiance: Vec3) -> (Vec3, f32, Vec3) {
    (-direction.normalize(), f32::INFINITY, irradiance)
}

/// The light's weight among the lights: the luminance of its flux through `far_disk`, the area of
/// the scene's bounding disk.
pub(super) fn power(irradiance: Vec3, far_disk: f32) -> f32 {
    far_disk * luminance(irradiance)
}
