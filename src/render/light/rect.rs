//! One-sided parallelogram ("rect") lights: sampled uniformly over their two edges, hit where a ray
//! meets their plane inside both edges.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::area::{area_pdf, area_sample, hit_plane, AreaLight};
use super::bounds::LightBounds;
use super::LightSample;
use crate::render::bsdf::luminance;
use crate::scene::RectLight;

/// The scene's parallelogram with its unit normal and area.
#[derive(Clone, Debug)]
pub(super) struct Rect {
    shape: RectLight,
    /// Unit `edge_u x edge_v`, the emitting side.
    normal: Vec3,
    area: f32,
}

impl Rect {
    pub fn new(shape: RectLight) -> Self {
        let c = shape.edge_u.cross(shape.edge_v);
        Self {
            shape,
            normal: c.normalize_or_zero(),
            area: c.length(),
        }
    }

    /// Whether `q`, on the plane, lies inside the parallelogram (coordinates by the dual basis of
    /// the two edges).
    fn contains(&self, q: Vec3) -> bool {
        let (edge_u, edge_v) = (self.shape.edge_u, self.shape.edge_v);
        let q = q - self.shape.corner;
        let (uu, uv, vv) = (
            edge_u.length_squared(),
            edge_u.dot(edge_v),
            edge_v.length_squared(),
        );
        let (qu, qv) = (q.dot(edge_u), q.dot(edge_v));
        let det = uu * vv - uv * uv;
        let (s, r) = ((qu * vv - qv * uv) / det, (qv * uu - qu * uv) / det);
        (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&r)
    }
}

impl AreaLight for Rect {
    fn radiance(&self) -> Vec3 {
        self.shape.radiance
    }

    fn power(&self) -> f32 {
        PI * self.area * luminance(self.shape.radiance)
    }

    fn sample(&self, p: Vec3, u: Vec2, choice: f32) -> Option<LightSample> {
        let s = &self.shape;
        let q = s.corner + s.edge_u * u.x + s.edge_v * u.y;
        area_sample(p, q, self.normal, self.area, s.radiance, choice)
    }

    fn hit(&self, o: Vec3, d: Vec3) -> Option<(f32, f32)> {
        hit_plane(o, d, self.shape.corner, self.normal)
            .filter(|&(t, _)| self.contains(o + d * t))
            .map(|(t, cos)| (t, area_pdf(1.0, t * t, cos, self.area)))
    }

    fn bounds(&self, phi: f32) -> LightBounds {
        let s = &self.shape;
        let corners = [
            s.corner,
            s.corner + s.edge_u,
            s.corner + s.edge_v,
            s.corner + s.edge_u + s.edge_v,
        ];
        LightBounds::planar(&corners, self.normal, phi, false)
    }
}
