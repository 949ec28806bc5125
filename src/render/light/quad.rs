//! Emissive rectangles: two triangles of an emissive mesh that together make a rectangle of one
//! constant emission, sampled as one two-sided light (by solid angle where it looks large).
//!
//! A quad light split into two triangles, each sampled on its own, leaves the choice between the
//! halves as noise wherever they send a point different light (near the light above all). As one
//! rectangle the choice is gone: on bunny-cornell, whose ceiling light is such a pair, noise per
//! sample fell from 0.188 to 0.174 (32 spp x 6 seeds) at 0.97x the time a sample. Where it fills
//! a tenth of the projected sky or more it is sampled by projected solid angle: 0.173 -> 0.163 on
//! bunny-cornell at the same time a sample (the ceiling in the 1 cm gap above the light).

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::area::{
    area_sample, facing, solid_angle_sample, surely_smaller, two_sided_area_pdf, Way,
    SPHERICAL_SOLID_ANGLES,
};
use super::bounds::LightBounds;
use super::projected::ProjectedPolygon;
use super::triangle::Triangle;
use super::{LightContext, LightSample};
use crate::geometry::triangle::RayShear;
use crate::geometry::Hit;
use crate::render::bsdf::luminance;
use crate::sample::warp::SphericalRectangle;

/// Relative tolerance of the rectangle test: the opposite corners' midpoints may differ by this
/// times the diagonal, and the corner angle's cosine by this from 0. The union of the halves then
/// strays from the sampled rectangle by rounding only.
const RECTANGLE_TOLERANCE: f32 = 1e-5;

/// Rectangles that look smaller than this (sr) are sampled by area. On bunny-cornell (noise per
/// sample and time, 32 spp x 6 seeds): 0.5 sr 0.174 at 0.97x the time of the two triangles it
/// replaced, 0.2 sr 0.172 at 1.02x (the spherical map's trigonometry at more points of the room).
const NEAR_SOLID_ANGLE: f32 = 0.5;

#[derive(Clone, Debug)]
pub(super) struct Quad {
    /// The two triangles, for rays that look for emitters themselves (`LightSet::nearest_emitter`).
    halves: [Triangle; 2],
    corner: Vec3,
    edge_u: Vec3,
    edge_v: Vec3,
    /// Unit normal (either side: the light is two-sided).
    normal: Vec3,
    area: f32,
    /// The centre and the squared half diagonal: the bounding sphere of the cheap solid-angle bound.
    centre: Vec3,
    r2: f32,
    radiance: Vec3,
}

impl Quad {
    /// The rectangle `a` and `b` make together, of constant `radiance`: where they share an edge,
    /// which is a diagonal of the rectangle that their other corners complete.
    pub fn pair(a: &Triangle, b: &Triangle, radiance: Vec3) -> Option<Self> {
        let (va, vb) = (a.vertices(), b.vertices());
        let shared = |i: usize| vb.contains(&va[i]);
        let (i, j) = match [0, 1, 2].map(shared) {
            [true, true, false] => (0, 1),
            [true, false, true] => (0, 2),
            [false, true, true] => (1, 2),
            _ => return None,
        };
        let x = va[3 - i - j];
        let y = *vb.iter().find(|v| **v != va[i] && **v != va[j])?;
        let (s0, s1) = (va[i], va[j]);
        let (edge_u, edge_v) = (s0 - x, s1 - x);
        let diagonal = (s1 - s0).length();
        let parallelogram = (x + y - s0 - s1).length() <= RECTANGLE_TOLERANCE * diagonal;
        let square_corner =
            edge_u.dot(edge_v).abs() <= RECTANGLE_TOLERANCE * edge_u.length() * edge_v.length();
        let cross = edge_u.cross(edge_v);
        let area = cross.length();
        if !(parallelogram && square_corner && area > 0.0 && area.is_finite()) {
            return None;
        }
        let centre = x + 0.5 * (edge_u + edge_v);
        Some(Self {
            halves: [a.clone(), b.clone()],
            corner: x,
            edge_u,
            edge_v,
            normal: cross / area,
            area,
            centre,
            r2: 0.25 * (edge_u + edge_v).length_squared(),
            radiance,
        })
    }

    /// The light's weight among the lights: the luminance of its flux.
    pub fn power(&self) -> f32 {
        PI * self.area * luminance(self.radiance)
    }

    pub fn sample(&self, ctx: &LightContext, u: Vec2, choice: f32) -> Option<LightSample> {
        let p = ctx.p;
        match self.way(ctx) {
            Way::Projected(s) => {
                let (d, q) = s.sample(u, |d| self.meets(p, d))?;
                solid_angle_sample(p, q, self.radiance, choice * s.pdf(d))
            }
            Way::Spherical(r) => {
                solid_angle_sample(p, r.sample(u), self.radiance, choice / r.solid_angle())
            }
            Way::Area => {
                let q = self.corner + self.edge_u * u.x + self.edge_v * u.y;
                area_sample(
                    p,
                    q,
                    facing(self.normal, p, q),
                    self.area,
                    self.radiance,
                    choice,
                )
            }
        }
    }

    /// The solid-angle pdf, times `choice`, with which `sample` picks point `q` for `ctx`.
    pub fn pdf(&self, choice: f32, ctx: &LightContext, q: Vec3) -> f32 {
        let p = ctx.p;
        match self.way(ctx) {
            Way::Projected(s) => choice * s.pdf_along(q - p),
            Way::Spherical(r) => choice / r.solid_angle(),
            Way::Area => two_sided_area_pdf(choice, p, q, self.normal, self.area),
        }
    }

    /// The nearer of the halves the ray from `o` (shear `sh`) meets before `t_max`.
    pub fn hit(&self, o: Vec3, sh: &RayShear, t_min: f32, t_max: f32) -> Option<Hit> {
        let first = self.halves[0].hit(o, sh, t_min, t_max);
        let t_max = first.map_or(t_max, |h| h.t);
        self.halves[1].hit(o, sh, t_min, t_max).or(first)
    }

    /// The bounds of the rectangle's emission, of power `phi`, for the light BVH.
    pub fn bounds(&self, phi: f32) -> LightBounds {
        let (c, u, v) = (self.corner, self.edge_u, self.edge_v);
        LightBounds::planar(&[c, c + u, c + v, c + u + v], self.normal, phi, true)
    }

    /// How the rectangle is sampled for `ctx`: by projected solid angle where it fills much of
    /// the sky, by solid angle where it looks large, by area elsewhere.
    fn way(&self, ctx: &LightContext) -> Way<SphericalRectangle> {
        let p = ctx.p;
        let h = self.normal.dot(p - self.corner).abs();
        if surely_smaller(p, self.centre, self.r2, self.area, h, NEAR_SOLID_ANGLE) {
            return Way::Area;
        }
        let (c, u, v) = (self.corner, self.edge_u, self.edge_v);
        if let Some(s) = ProjectedPolygon::new(p, ctx.n, &[c, c + u, c + u + v, c + v]) {
            return Way::Projected(s);
        }
        match SphericalRectangle::new(p, c, u, v) {
            Some(r)
                if r.solid_angle() >= NEAR_SOLID_ANGLE
                    && SPHERICAL_SOLID_ANGLES.contains(&r.solid_angle()) =>
            {
                Way::Spherical(r)
            }
            _ => Way::Area,
        }
    }

    /// The point where the ray from `p` along unit `d` meets the rectangle, either face.
    fn meets(&self, p: Vec3, d: Vec3) -> Option<Vec3> {
        let t = self.normal.dot(self.corner - p) / self.normal.dot(d);
        if !(t > 0.0 && t.is_finite()) {
            return None;
        }
        let q = p + d * t;
        let r = q - self.corner;
        let s = r.dot(self.edge_u) / self.edge_u.length_squared();
        let w = r.dot(self.edge_v) / self.edge_v.length_squared();
        ((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&w)).then_some(q)
    }
}
