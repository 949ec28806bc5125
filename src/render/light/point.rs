//! Point lights: intensity in W/sr from one position, a delta light (sampled, never hit).
//! Power is its flux over the whole sphere of directions.

use std::f32::consts::PI;

use glam::Vec3;

use super::bounds::LightBounds;
use crate::geometry::Aabb;
use crate::render::bsdf::luminance;

/// Direction, distance and arriving intensity (already divided by distance squared) from `p`.
pub(super) fn sample(position: Vec3, intensity: Vec3, p: Vec3) -> Option<(Vec3, f32, Vec3)> {
    let to = position - p;
    let d2 = to.length_squared();
    (d2 > 0.0).then(|| (to / d2.sqrt(), d2.sqrt(), intensity / d2))
}

/// The light's weight among the lights: the luminance of its flux.
pub(super) fn power(intensity: Vec3) -> f32 {
    4.0 * PI * luminance(intensity)
}

/// The bounds of the light's emission, of power `phi`, for the light BVH.
pub(super) fn bounds(position: Vec3, phi: f32) -> LightBounds {
    LightBounds::omni(Aabb::from_points([position]), phi)
}
