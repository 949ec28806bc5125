//! KHR_materials_diffuse_transmission's lobe: the dielectric base's diffuse part becomes
//! mix(diffuse_brdf(baseColor), diffuse_btdf(colour), factor), a Lambertian BTDF into the lower hemisphere.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::luminance;
use crate::sample::warp::cosine_hemisphere;

#[derive(Clone, Copy, Debug)]
pub struct DiffuseTransmission {
    /// diffuseTransmissionFactor (times its texture's A), in (0, 1].
    pub factor: f32,
    /// diffuseTransmissionColor (linear, times its texture's RGB).
    pub color: Vec3,
}

impl DiffuseTransmission {
    pub fn new(factor: f32, color: Vec3) -> Self {
        Self {
            factor: factor.clamp(0.0, 1.0),
            color: color.clamp(Vec3::ZERO, Vec3::ONE),
        }
    }

    /// The diffuse part of the base for local directions `o` (above) and `i`, before the Fresnel
    /// share the specular layer takes: base / pi on `o`'s side, colour / pi on the other, mixed.
    pub fn eval(&self, base: Vec3, i: Vec3) -> Vec3 {
        if i.z > 0.0 {
            base * ((1.0 - self.factor) * FRAC_1_PI)
        } else {
            self.color * (self.factor * FRAC_1_PI)
        }
    }

    /// The diffuse part's rough albedo (for choosing among the base's lobes).
    pub fn weight(&self, base: Vec3) -> f32 {
        luminance(base.lerp(self.color, self.factor))
    }

    /// Probability that a diffuse sample goes through the surface: the transmitted share of the
    /// diffuse part's rough albedo (the factor itself where both colours are black).
    pub fn through_probability(&self, base: Vec3) -> f32 {
        let r = (1.0 - self.factor) * luminance(base);
        let t = self.factor * luminance(self.color);
        if r + t > 0.0 {
            t / (r + t)
        } else {
            self.factor
        }
    }

    /// Density of `sample` at local `i` (cosine on each side, weighted by the side's probability).
    pub fn pdf(&self, through: f32, i: Vec3) -> f32 {
        let side = if i.z > 0.0 { 1.0 - through } else { through };
        side * i.z.abs() * FRAC_1_PI
    }

    /// A cosine-distributed direction, sent through the surface when `u_side < through`.
    pub fn sample(&self, through: f32, u_side: f32, u: Vec2) -> Vec3 {
        let d = cosine_hemisphere(u);
        if u_side < through {
            Vec3::new(d.x, d.y, -d.z)
        } else {
            d
        }
    }
}
