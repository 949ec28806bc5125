//! Emissive triangles, two-sided, one entry per world-space triangle of each static emissive
//! instance (but for pairs that make a rectangle, `quad.rs`): sampled by projected solid angle
//! where they fill a tenth of the sky or more (`projected.rs`), in the solid angle they subtend
//! where that is large (warped by the cosines at the shading point, as pbrt-v4 does), by area where
//! it is tiny; rays find them through the accelerators, so only their pdf is asked for on BSDF
//! hits. Projected sampling on bunny-cornell with its light made a trapezoid of two triangles
//! (32 spp x 6 seeds): sigma 0.1898 -> 0.1833 at the same time a sample.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::area::{
    area_sample, facing, solid_angle_sample, surely_smaller, two_sided_area_pdf, Way,
    SPHERICAL_SOLID_ANGLES,
};
use super::bounds::LightBounds;
use super::projected::ProjectedPolygon;
use super::{LightContext, LightSample};
use crate::geometry::triangle::{self, RayShear};
use crate::geometry::Hit;
use crate::render::bsdf::luminance;
use crate::render::surface::emission;
use crate::sample::warp::{
    bilinear, bilinear_pdf, spherical_triangle, spherical_triangle_area,
    spherical_triangle_inverse, uniform_triangle,
};
use crate::scene::{Material, Mesh, Scene};

#[derive(Clone, Debug)]
pub(super) struct Triangle {
    inst: u32,
    prim: u32,
    /// World-space vertices.
    v: [Vec3; 3],
    area: f32,
    /// Unit normal (either side; zero for a degenerate triangle), and the bounding sphere about
    /// the centroid: what area sampling and the cheap bounds on the solid angle need.
    n: Vec3,
    centre: Vec3,
    r2: f32,
}

impl Triangle {
    pub fn new(scene: &Scene, inst: u32, prim: u32) -> Self {
        Self::from_vertices(inst, prim, scene.world_triangle(inst, prim))
    }

    fn from_vertices(inst: u32, prim: u32, v: [Vec3; 3]) -> Self {
        let cross = (v[1] - v[0]).cross(v[2] - v[0]);
        let centre = (v[0] + v[1] + v[2]) / 3.0;
        let r2 = v
            .map(|v| v.distance_squared(centre))
            .into_iter()
            .fold(0.0, f32::max);
        Self {
            inst,
            prim,
            v,
            area: 0.5 * cross.length(),
            n: cross.normalize_or_zero(),
            centre,
            r2,
        }
    }

    /// The world-space vertices.
    pub fn vertices(&self) -> &[Vec3; 3] {
        &self.v
    }

    /// The triangle's weight among the lights: the luminance of its (estimated) flux.
    pub fn power(&self, scene: &Scene, mat: &Material, mesh: &Mesh) -> f32 {
        PI * self.area * mean_emission(scene, mat, mesh, self.prim)
    }

    pub fn sample(
        &self,
        scene: &Scene,
        ctx: &LightContext,
        u: Vec2,
        choice: f32,
    ) -> Option<LightSample> {
        let p = ctx.p;
        let (q, (b1, b2), pdf) = match self.way(ctx) {
            Way::Projected(s) => {
                let (d, (q, b1, b2)) = s.sample(u, |d| self.crossing(p, d))?;
                (q, (b1, b2), choice * s.pdf(d))
            }
            Way::Spherical((omega, [a, b, c])) => {
                let (u, warp_pdf) = match cosine_weights(ctx.n, [a, b, c]) {
                    Some(w) => {
                        let warped = bilinear(u, w);
                        (warped, bilinear_pdf(warped, w))
                    }
                    None => (u, 1.0),
                };
                let bary = self.barycentrics_along(p, spherical_triangle(a, b, c, u)?)?;
                (self.point(bary), bary, choice * warp_pdf / omega)
            }
            Way::Area => {
                let bary = uniform_triangle(u);
                let q = self.point(bary);
                let li = self.emission(scene, bary.0, bary.1);
                return area_sample(p, q, facing(self.n, p, q), self.area, li, choice);
            }
        };
        solid_angle_sample(p, q, self.emission(scene, b1, b2), pdf)
    }

    /// Where the ray from `o` (shear `sh`) meets the triangle, either face, before `t_max`: the
    /// accelerators' watertight test on the same world-space vertices.
    pub fn hit(&self, o: Vec3, sh: &RayShear, t_min: f32, t_max: f32) -> Option<Hit> {
        let [a, b, c] = self.v;
        triangle::intersect(o, sh, a, b, c, t_min, t_max).map(|h| Hit {
            t: h.t,
            u: h.u,
            v: h.v,
            inst: self.inst,
            prim: self.prim,
        })
    }

    /// The bounds of the triangle's emission, of power `phi`, for the light BVH.
    pub fn bounds(&self, phi: f32) -> LightBounds {
        // A degenerate triangle (no normal) gets any: its power is zero.
        let n = if self.n == Vec3::ZERO {
            Vec3::Z
        } else {
            self.n
        };
        LightBounds::planar(&self.v, n, phi, true)
    }

    /// The solid-angle pdf, times `choice`, with which `sample` picks point `q` (normal `nq`) for
    /// `ctx`.
    pub fn pdf(&self, choice: f32, ctx: &LightContext, q: Vec3, nq: Vec3) -> f32 {
        let p = ctx.p;
        match self.way(ctx) {
            Way::Projected(s) => choice * s.pdf_along(q - p),
            Way::Spherical((omega, [a, b, c])) => {
                let Some(w) = cosine_weights(ctx.n, [a, b, c]) else {
                    return choice / omega;
                };
                let warp_pdf = (q - p)
                    .try_normalize()
                    .and_then(|d| spherical_triangle_inverse(a, b, c, d))
                    .map_or(0.0, |u| bilinear_pdf(u, w));
                choice * warp_pdf / omega
            }
            Way::Area => two_sided_area_pdf(choice, p, q, nq, self.area),
        }
    }
}

impl Triangle {
    /// How the triangle is sampled for `ctx`: by projected solid angle where it fills enough of
    /// the sky, by solid angle (with its solid angle and unit corner directions) where it looks
    /// larger than `NEAR_SOLID_ANGLE`, by area elsewhere.
    fn way(&self, ctx: &LightContext) -> Way<(f32, [Vec3; 3])> {
        let p = ctx.p;
        // Bounds without trigonometry first (on bunny-cornell they decide most points of the box).
        let h = self.n.dot(p - self.v[0]).abs();
        if surely_smaller(p, self.centre, self.r2, self.area, h, NEAR_SOLID_ANGLE) {
            return Way::Area;
        }
        if let Some(s) = ProjectedPolygon::new(p, ctx.n, &self.v) {
            return Way::Projected(s);
        }
        let [a, b, c] = self.v.map(|v| (v - p).normalize_or_zero());
        let omega = spherical_triangle_area(a, b, c);
        if omega >= NEAR_SOLID_ANGLE && SPHERICAL_SOLID_ANGLES.contains(&omega) {
            Way::Spherical((omega, [a, b, c]))
        } else {
            Way::Area
        }
    }

    /// The point at barycentrics `(b1, b2)` (of corners 1 and 2).
    fn point(&self, (b1, b2): (f32, f32)) -> Vec3 {
        let v = &self.v;
        v[0] * (1.0 - b1 - b2) + v[1] * b1 + v[2] * b2
    }

    /// Barycentrics (of corners 1 and 2) where the ray from `p` along `w` meets the triangle's
    /// plane, clamped into the triangle against rounding.
    fn barycentrics_along(&self, p: Vec3, w: Vec3) -> Option<(f32, f32)> {
        let (b1, b2, _) = self.plane_crossing(p, w)?;
        let b1 = b1.clamp(0.0, 1.0);
        Some((b1, b2.clamp(0.0, 1.0 - b1)))
    }

    /// Barycentrics (of corners 1 and 2) and distance where the ray from `p` along `w` meets the
    /// triangle's plane (Moller-Trumbore).
    fn plane_crossing(&self, p: Vec3, w: Vec3) -> Option<(f32, f32, f32)> {
        let [v0, v1, v2] = self.v;
        let (e1, e2) = (v1 - v0, v2 - v0);
        let s1 = w.cross(e2);
        let div = s1.dot(e1);
        if div == 0.0 || !div.is_finite() {
            return None;
        }
        let s = p - v0;
        let s2 = s.cross(e1);
        Some((s.dot(s1) / div, w.dot(s2) / div, e2.dot(s2) / div))
    }

    /// The point and barycentrics where the ray from `p` along unit `d` meets the triangle.
    fn crossing(&self, p: Vec3, d: Vec3) -> Option<(Vec3, f32, f32)> {
        let (b1, b2, t) = self.plane_crossing(p, d)?;
        (t > 0.0 && b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0).then(|| (p + d * t, b1, b2))
    }

    /// Emitted radiance at barycentrics `(b1, b2)`.
    fn emission(&self, scene: &Scene, b1: f32, b2: f32) -> Vec3 {
        let mesh = scene.mesh_of(self.inst);
        let mat = &scene.materials[mesh.material as usize];
        emission(scene, mat, mesh.uv_at(self.prim, b1, b2))
    }
}

/// Triangles that look smaller than this (sr) are sampled by area: on bunny-cornell (its ceiling
/// light is two triangles) the noise per sample was the same (0.205) with solid-angle sampling from
/// 0.05 sr up as from pbrt-v4's 3e-4 sr, for 0.82x the time a sample (57.7 against 70.4 ms), and
/// 0.206 from 0.2 sr up for 0.94x 0.05's time (42.5, 42.4 against 44.6, 45.9 ms, alternated); 0.208
/// from 0.5 up; with none sampled by solid angle it was 0.243.
const NEAR_SOLID_ANGLE: f32 = 0.2;

/// The weights of the bilinear warp of the square before the spherical triangle map: the cosine
/// at the shading point's normal `n` towards the corner each square corner maps to (b at u.y = 0,
/// a and c at u.y = 1), kept above 0.01 so no direction becomes unreachable. None without a
/// normal (a point in a medium, or none known).
fn cosine_weights(n: Vec3, [a, b, c]: [Vec3; 3]) -> Option<[f32; 4]> {
    (n != Vec3::ZERO).then(|| [b, b, a, c].map(|w| n.dot(w).abs().max(0.01)))
}

/// Barycentric points where a textured triangle's emission is probed: vertices, edge midpoints and
/// centroid.
const EMISSION_PROBES: [(f32, f32); 7] = [
    (0.0, 0.0),
    (1.0, 0.0),
    (0.0, 1.0),
    (0.5, 0.0),
    (0.0, 0.5),
    (0.5, 0.5),
    (1.0 / 3.0, 1.0 / 3.0),
];

/// Estimated mean emitted luminance over a triangle. With an emission texture (glowing details on a
/// mostly dark surface) the factor alone would give every triangle of the mesh a share of light
/// samples; a few texture probes put them where the glow is. A triangle whose probes all miss its
/// glow is still found by BSDF sampling (MIS then gives that hit weight 1), so this stays unbiased.
fn mean_emission(scene: &Scene, mat: &Material, mesh: &Mesh, prim: u32) -> f32 {
    if mat.emissive_tex.is_none() {
        return luminance(mat.emissive);
    }
    let sum: f32 = EMISSION_PROBES
        .iter()
        .map(|&(b1, b2)| luminance(emission(scene, mat, mesh.uv_at(prim, b1, b2))))
        .sum();
    sum / EMISSION_PROBES.len() as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bounding-cap test only ever declines triangles that the exact solid angle would have
    /// left to area sampling too (so it changes the cost, not the estimator).
    #[test]
    fn the_cheap_bound_declines_only_small_triangles() {
        let mut k = 0u64;
        let mut r = || {
            k += 1;
            (crate::geometry::mix64(k) >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
        };
        let (mut declined, mut spherical) = (0, 0);
        for _ in 0..20_000 {
            let centre = Vec3::new(r(), r(), r()) * 2.0;
            let size = 0.05 + (r() + 1.0);
            let v = [0; 3].map(|_| centre + Vec3::new(r(), r(), r()) * size);
            let t = Triangle::from_vertices(0, 0, v);
            let p = Vec3::new(r(), r(), r());
            let exact = spherical_triangle_area(
                (v[0] - p).normalize(),
                (v[1] - p).normalize(),
                (v[2] - p).normalize(),
            );
            // Without a normal, projected sampling never applies.
            match t.way(&LightContext { p, n: Vec3::ZERO }) {
                Way::Spherical((omega, _)) => {
                    spherical += 1;
                    assert!(omega >= NEAR_SOLID_ANGLE);
                }
                Way::Projected(_) => unreachable!("no normal, no projected sampling"),
                Way::Area if SPHERICAL_SOLID_ANGLES.contains(&exact) => {
                    declined += 1;
                    assert!(
                        exact < NEAR_SOLID_ANGLE,
                        "declined {v:?} from {p}: {exact} sr"
                    );
                }
                Way::Area => {}
            }
        }
        // Both outcomes occur often enough for the check to mean something.
        eprintln!("cap test: declined {declined}, spherical {spherical} of 20000");
        assert!(
            declined > 1000 && spherical > 1000,
            "declined {declined}, spherical {spherical}"
        );
    }
}
