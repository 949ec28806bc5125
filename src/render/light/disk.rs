//! One-sided disk lights: sampled uniformly by area through the concentric map, hit where a ray
//! meets their plane within the radius.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::area::{area_sample, hit_plane, AreaLight};
use super::bounds::LightBounds;
use super::LightSample;
use crate::render::bsdf::luminance;
use crate::sample::warp::concentric_disk;
use crate::scene::DiskLight;

/// The scene's disk with its normal made unit.
#[derive(Clone, Debug)]
pub(super) struct Disk {
    shape: DiskLight,
    /// The emitting side.
    normal: Vec3,
}

impl Disk {
    pub fn new(shape: DiskLight) -> Self {
        let normal = shape.normal.normalize_or_zero();
        Self { shape, normal }
    }

    fn area(&self) -> f32 {
        PI * self.shape.radius * self.shape.radius
    }
}

impl AreaLight for Disk {
    fn radiance(&self) -> Vec3 {
        self.shape.radiance
    }

    fn power(&self) -> f32 {
        PI * PI * self.shape.radius * self.shape.radius * luminance(self.shape.radiance)
    }

    fn sample(&self, p: Vec3, u: Vec2, choice: f32) -> Option<LightSample> {
        let (t, b) = self.normal.any_orthonormal_pair();
        let d = concentric_disk(u) * self.shape.radius;
        let q = self.shape.center + t * d.x + b * d.y;
        area_sample(p, q, self.normal, self.area(), self.shape.radiance, choice)
    }

    fn hit(&self, o: Vec3, d: Vec3) -> Option<(f32, f32)> {
        let (center, radius) = (self.shape.center, self.shape.radius);
        hit_plane(o, d, center, self.normal)
            .filter(|&(t, _)| (o + d * t - center).length_squared() <= radius * radius)
            // `area_pdf(1.0, t * t, cos, self.area())`, multiplied out in the order the renders
            // were made with: the folded form changes the last bits of images with disk lights.
            .map(|(t, cos)| (t, t * t / (cos * PI * radius * radius)))
    }

    fn bounds(&self, phi: f32) -> LightBounds {
        // The disk's box: along each axis its extent is the radius times the sine to the normal.
        let n = self.normal;
        let e = (Vec3::ONE - n * n).max(Vec3::ZERO).powf(0.5) * self.shape.radius;
        let c = self.shape.center;
        LightBounds::planar(&[c - e, c + e], n, phi, false)
    }
}
