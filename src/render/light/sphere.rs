//! Spherical area lights, emitting outwards: sampled uniformly over the cone they subtend (which
//! sees only their visible side), hit by an analytic ray-sphere test.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::area::AreaLight;
use super::bounds::LightBounds;
use super::LightSample;
use crate::geometry::Aabb;
use crate::render::bsdf::luminance;
use crate::sample::warp::{uniform_cone, uniform_cone_pdf, uniform_cone_solid_angle};
use crate::scene::SphereLight;

impl AreaLight for SphereLight {
    fn radiance(&self) -> Vec3 {
        self.radiance
    }

    fn power(&self) -> f32 {
        PI * 4.0 * PI * self.radius * self.radius * luminance(self.radiance)
    }

    fn sample(&self, p: Vec3, u: Vec2, choice: f32) -> Option<LightSample> {
        let to_c = self.center - p;
        let dc2 = to_c.length_squared();
        let r2 = self.radius * self.radius;
        let omc_max = cone(dc2, r2)?;
        let (local, sin) = uniform_cone(u, omc_max);
        let cos = local.z;
        let dc = dc2.sqrt();
        let w = to_c / dc;
        let (t, b) = w.any_orthonormal_pair();
        let wi = (t * local.x + b * local.y + w * local.z).normalize();
        // Nearer intersection with the sphere along wi (clamped at grazing directions).
        let dist = dc * cos - (r2 - dc2 * sin * sin).max(0.0).sqrt();
        Some(LightSample {
            wi,
            dist: dist.max(0.0),
            li: self.radiance,
            pdf: choice / uniform_cone_solid_angle(omc_max),
            is_delta: false,
        })
    }

    fn hit(&self, o: Vec3, d: Vec3) -> Option<(f32, f32)> {
        let t = hit_sphere(o, d, self.center, self.radius)?;
        let omc_max = cone(
            (self.center - o).length_squared(),
            self.radius * self.radius,
        )?;
        Some((t, uniform_cone_pdf(omc_max)))
    }

    fn bounds(&self, phi: f32) -> LightBounds {
        let r = Vec3::splat(self.radius);
        LightBounds::omni(Aabb::from_points([self.center - r, self.center + r]), phi)
    }
}

/// `1 - cos(theta_max)` of the cone a sphere (squared radius `r2`) subtends from squared distance
/// `dc2` to its centre; `None` from inside, where an outward-emitting sphere sends nothing.
fn cone(dc2: f32, r2: f32) -> Option<f32> {
    if dc2 <= r2 {
        return None;
    }
    let sin2 = r2 / dc2;
    let omc = sin2 / (1.0 + (1.0 - sin2).max(0.0).sqrt());
    (omc > 0.0).then_some(omc)
}

/// Distance along unit `d` from `o` (outside) to the near side of a sphere.
fn hit_sphere(o: Vec3, d: Vec3, center: Vec3, radius: f32) -> Option<f32> {
    let oc = o - center;
    let c = oc.length_squared() - radius * radius;
    if c <= 0.0 {
        return None;
    }
    let b = oc.dot(d);
    // Ray Tracing Gems ch. 7: the discriminant from the distance to the closest approach.
    let closest = oc - d * b;
    let disc = radius * radius - closest.length_squared();
    if b >= 0.0 || disc < 0.0 {
        return None;
    }
    let q = -b + disc.sqrt();
    let t = c / q;
    (t > 0.0).then_some(t)
}
