//! Point lights: intensity in W/sr from one position, a delta light (sampled, never hit).
//! Power is its flux over the whole sphere of directions.

use std::f32::consts::PI;

use glam::Vec3;

use super::bounds::LightBounds;
use crate::geometry::Aabb;
use crate::render::bsdf::luminance;
use crate::scene::PointLight;

/// Direction, distance and arriving intensity (already divided by distance squared) from `p`.
pub(super) fn sample(l: &PointLight, p: Vec3) -> Option<(Vec3, f32, Vec3)> {
    let to = l.position - p;
    let d2 = to.length_squared();
    (d2 > 0.0).then(|| (to / d2.sqrt(), d2.sqrt(), l.intensity / d2))
}

/// The light's weight among the lights: the luminance of its flux.
pub(super) fn power(l: &PointLight) -> f32 {
    4.0 * PI * luminance(l.intensity)
}

/// The bounds of the light's emission, of power `phi`, for the light BVH.
pub(super) fn bounds(l: &PointLight, phi: f32) -> LightBounds {
    LightBounds::omni(Aabb::from_points([l.position]), phi)
}
