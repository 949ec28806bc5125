//! What the area-sampled lights share: the trait of the analytic area lights (found by rays, not by
//! the accelerators) and the conversion of a uniform area sample to a solid-angle pdf.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::bounds::LightBounds;
use super::projected::ProjectedPolygon;
use super::LightSample;

/// How a planar light is sampled from a point: by projected solid angle where it fills much of
/// the sky there, by solid angle (with what the shape's spherical map needs) where it looks large,
/// by area elsewhere. A shape decides once per point, for its sample and its pdf alike.
pub(super) enum Way<S> {
    Projected(ProjectedPolygon),
    Spherical(S),
    Area,
}

/// An analytic area light (sphere, disk, rectangle): it emits and is seen but occludes nothing, so
/// rays find it through `hit` and light sampling through `sample`, both with the same pdf.
pub(super) trait AreaLight {
    fn radiance(&self) -> Vec3;

    /// The light's weight among the lights: the luminance of its flux.
    fn power(&self) -> f32;

    /// A point on the light seen from `p`, with the solid-angle pdf times `choice` (the probability
    /// of having picked this light).
    fn sample(&self, p: Vec3, u: Vec2, choice: f32) -> Option<LightSample>;

    /// The distance along unit `d` from `o` to the light's emitting side, and the solid-angle pdf
    /// (choice left out) with which `sample` picks that direction from `o`.
    fn hit(&self, o: Vec3, d: Vec3) -> Option<(f32, f32)>;

    /// The bounds of the light's emission, of power `phi`, for the light BVH.
    fn bounds(&self, phi: f32) -> LightBounds;
}

/// The solid angles (sr) between which emissive triangles and rectangles are sampled by solid
/// angle (pbrt-v4's bounds): below, area sampling is as good and the spherical warps lose
/// precision; above, the light nearly fills a hemisphere and the warps' corner angles do.
pub(super) const SPHERICAL_SOLID_ANGLES: std::ops::RangeInclusive<f32> = 3e-4..=6.22;

/// The solid-angle pdf, times `scale`, of a point drawn uniformly over `area`, seen from squared
/// distance `d2` at cosine `cos` to its normal. Light sampling passes its choice probability as
/// `scale` and rays finding a light pass 1 and weigh after: the order the renders were made with.
pub(super) fn area_pdf(scale: f32, d2: f32, cos: f32, area: f32) -> f32 {
    scale * d2 / (cos * area)
}

/// The light sample towards point `q` (normal `n`, emitting towards `n`) drawn uniformly over `area`
/// from `p`, with radiance `li`; `None` when `q` faces away from `p`.
pub(super) fn area_sample(
    p: Vec3,
    q: Vec3,
    n: Vec3,
    area: f32,
    li: Vec3,
    choice: f32,
) -> Option<LightSample> {
    let to = q - p;
    let d2 = to.length_squared();
    let dist = d2.sqrt();
    if dist <= 0.0 || area <= 0.0 {
        return None;
    }
    let wi = to / dist;
    let cos_l = -n.dot(wi);
    (cos_l > 0.0).then(|| LightSample {
        wi,
        dist,
        li,
        pdf: area_pdf(choice, d2, cos_l, area),
        is_delta: false,
    })
}

/// The light sample towards point `q`, drawn from `p` with solid-angle pdf `pdf` (the choice
/// included); `None` where `q` is `p`.
pub(super) fn solid_angle_sample(p: Vec3, q: Vec3, li: Vec3, pdf: f32) -> Option<LightSample> {
    let to = q - p;
    let dist = to.length();
    (dist > 0.0).then(|| LightSample {
        wi: to / dist,
        dist,
        li,
        pdf,
        is_delta: false,
    })
}

/// The normal of a two-sided planar light of unit normal `n` on the side facing `p` from its point
/// `q`: what `area_sample` takes for such lights.
pub(super) fn facing(n: Vec3, p: Vec3, q: Vec3) -> Vec3 {
    if n.dot(q - p) > 0.0 {
        -n
    } else {
        n
    }
}

/// The pdf of `area_sample` on a two-sided light for point `q` (unit normal `nq`, either side) from `p`.
pub(super) fn two_sided_area_pdf(choice: f32, p: Vec3, q: Vec3, nq: Vec3, area: f32) -> f32 {
    let to = q - p;
    let d2 = to.length_squared();
    let cos_l = nq.dot(to.normalize_or_zero()).abs();
    if cos_l <= 0.0 || area <= 0.0 {
        return 0.0;
    }
    area_pdf(choice, d2, cos_l, area)
}

/// Whether a planar light of `area`, within the sphere of squared radius `r2` about `centre`, surely
/// looks smaller than `limit` (sr) from `p`, at height `h` over its plane, without trigonometry:
/// from outside the sphere its cap, of solid angle 2 pi (1 - cos) <= pi r^2 / (d^2 - r^2), bounds
/// it; and since every point of the light is at least d - r away, so does the integral of
/// cos / dist^2 = h / dist^3 over its area, at most A h / (d - r)^3 (tighter off to the side and
/// far away). From inside the sphere nothing is sure.
pub(super) fn surely_smaller(
    p: Vec3,
    centre: Vec3,
    r2: f32,
    area: f32,
    h: f32,
    limit: f32,
) -> bool {
    let d2 = centre.distance_squared(p);
    let excess = d2 - r2;
    if excess <= 0.0 {
        return false;
    }
    if PI * r2 < limit * excess {
        return true;
    }
    let near = d2.sqrt() - r2.sqrt();
    near > 0.0 && area * h < limit * near * near * near
}

/// Distance along unit `d` from `o` to the plane through `p` with unit normal `n`, when `o` is on
/// the side `n` faces and `d` goes towards the plane; also `cos` between `-d` and `n`.
pub(super) fn hit_plane(o: Vec3, d: Vec3, p: Vec3, n: Vec3) -> Option<(f32, f32)> {
    let cos = -d.dot(n);
    let h = (o - p).dot(n);
    if cos <= 0.0 || h <= 0.0 {
        return None;
    }
    Some((h / cos, cos))
}
