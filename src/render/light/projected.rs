//! Sampling a planar light by projected solid angle: directions cosine-distributed about the shading
//! point's normal, kept where they meet the light (rejection), where the light fills much of the sky.
//!
//! For a Lambertian surface under a light of constant radiance this leaves no variance at all: the
//! estimate is radiance x projected solid angle, Lambert's closed form. Uniform solid-angle
//! sampling (spherical triangles and rectangles) misses the cosine, which matters where the light
//! spans a wide range of it: a ceiling 1 cm above a Cornell box's light sees it fill most of the
//! hemisphere below, at every cosine from 0 to 1.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use crate::geometry::{mix64, Frame};
use crate::sample::unit_float;
use crate::sample::warp::cosine_hemisphere;

/// Lights whose projected solid angle is below this fraction of pi (the whole hemisphere's) are
/// left to the other samplers: each sample costs pi / projected solid angle tries on average.
/// bunny-cornell's noise per sample (32 spp x 6 seeds) from 0.25 down to 0.02: 0.1641, 0.1635 at
/// 0.1, 0.1628, all at the time a sample of the solid-angle samplers alone (0.1729).
const MIN_FRACTION: f32 = 0.1;

/// Tries before a sample gives up. The pdf counts the give-ups (`kept`), so this stays unbiased; at
/// the smallest fraction 0.75^16 = 1% of samples are lost.
const TRIES: i32 = 64;

/// Points nearer the polygon's plane than this times its size are taken to lie in it.
const IN_PLANE: f32 = 1e-4;

/// A planar convex polygon as sampled by projected solid angle from one point.
#[derive(Clone, Copy, Debug)]
pub(super) struct ProjectedPolygon {
    /// Around the normal on the polygon's side.
    frame: Frame,
    /// The projected solid angle (sr): the integral of the cosine over the polygon's directions.
    psa: f32,
    /// The probability that some try of `TRIES` meets the polygon.
    kept: f32,
}

impl ProjectedPolygon {
    /// The polygon of `corners` (in order around it) seen from `p` with unit normal `n` (either
    /// side), where it lies wholly on one side of `p`'s tangent plane and fills at least
    /// `MIN_FRACTION` of the projected hemisphere; None elsewhere and without a normal.
    pub fn new<const N: usize>(p: Vec3, n: Vec3, corners: &[Vec3; N]) -> Option<Self> {
        if n == Vec3::ZERO {
            return None;
        }
        // A point in the polygon's own plane (on the light itself) sees it edge on: nothing, though
        // rounding can put all its corners to one side of the point there.
        let c0 = corners[0];
        let normal = (corners[1] - c0).cross(corners[2] - c0);
        let size = corners.iter().map(|c| c.distance(c0)).fold(0.0, f32::max);
        if normal.dot(p - c0).abs() <= IN_PLANE * normal.length() * size {
            return None;
        }
        let heights = corners.iter().map(|c| n.dot(*c - p));
        let m = if heights.clone().all(|h| h > 0.0) {
            n
        } else if heights.clone().all(|h| h < 0.0) {
            -n
        } else {
            return None;
        };
        let w = corners.map(|c| (c - p).normalize());
        // Lambert's formula: half the sum over the edges of their angle times the cosine between m
        // and the normal of the plane through p and the edge.
        let mut sum = 0.0;
        for (i, a) in w.iter().enumerate() {
            let b = w[(i + 1) % N];
            let c = a.cross(b);
            let len = c.length();
            if len > 0.0 {
                sum += len.atan2(a.dot(b)) * m.dot(c) / len;
            }
        }
        let psa = 0.5 * sum.abs();
        let fraction = psa / PI;
        if !(MIN_FRACTION..=1.0).contains(&fraction) {
            return None;
        }
        Some(Self {
            frame: Frame::from_normal(m),
            psa,
            kept: 1.0 - (1.0 - fraction).powi(TRIES),
        })
    }

    /// A direction towards the polygon and where it meets it, found by `meets` (what it knows of
    /// the point along a unit direction, where there is one), from `u` and tries hashed from it.
    pub fn sample<T>(&self, u: Vec2, meets: impl Fn(Vec3) -> Option<T>) -> Option<(Vec3, T)> {
        let mut key = (u.x.to_bits() as u64) << 32 | u.y.to_bits() as u64;
        let mut u = u;
        for _ in 0..TRIES {
            let d = self.frame.to_world(cosine_hemisphere(u));
            if let Some(q) = meets(d) {
                return Some((d, q));
            }
            key = mix64(key);
            u = Vec2::new(unit_float(key), unit_float(key << 24));
        }
        None
    }

    /// The solid-angle pdf of `sample` picking unit direction `d` (one that meets the polygon).
    pub fn pdf(&self, d: Vec3) -> f32 {
        self.frame.n.dot(d).max(0.0) / self.psa * self.kept
    }

    /// `pdf` of the direction along `to` (from the point to one on the polygon; 0 if zero).
    pub fn pdf_along(&self, to: Vec3) -> f32 {
        to.try_normalize().map_or(0.0, |d| self.pdf(d))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sample::chi_square::pearson_p_value;

    fn hash(k: u64) -> f32 {
        unit_float(mix64(k ^ 0x5bd1_e995))
    }

    /// The projected solid angle of the rectangle [0, x] x [0, y] in the plane at height 1 above a
    /// point under its corner (the parallel-rectangle form factor times pi).
    fn corner_rectangle(x: f64, y: f64) -> f64 {
        let (sx, sy) = ((1.0 + x * x).sqrt(), (1.0 + y * y).sqrt());
        0.5 * (x / sx * (y / sx).atan() + y / sy * (x / sy).atan())
    }

    /// Lambert's closed form, from samples: every sample's cosine over its pdf is the projected
    /// solid angle (times the tries' keep rate), for rectangles above and below the point, as
    /// the parallel-rectangle form factor gives it (four corner rectangles about the foot).
    #[test]
    fn each_sample_gives_the_projected_solid_angle() {
        let (x0, x1, y0, y1) = (-0.7f32, 1.3f32, -0.4f32, 0.9f32);
        let expected = corner_rectangle(-x0 as f64, -y0 as f64)
            + corner_rectangle(x1 as f64, -y0 as f64)
            + corner_rectangle(-x0 as f64, y1 as f64)
            + corner_rectangle(x1 as f64, y1 as f64);
        for (h, n) in [(1.0f32, Vec3::Z), (-1.0, Vec3::Z), (1.0, -Vec3::Z)] {
            let corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)].map(|(x, y)| Vec3::new(x, y, h));
            let s = ProjectedPolygon::new(Vec3::ZERO, n, &corners).expect("wide light");
            assert!(
                (s.psa as f64 - expected).abs() < 1e-5 * expected,
                "{} vs {expected}",
                s.psa
            );
            for k in 0..1000 {
                let u = Vec2::new(hash(2 * k), hash(2 * k + 1));
                let meets = |d: Vec3| {
                    let t = h / d.z;
                    let q = d * t;
                    (t > 0.0 && (x0..=x1).contains(&q.x) && (y0..=y1).contains(&q.y)).then_some(q)
                };
                let (d, q) = s.sample(u, meets).expect("a wide light is met");
                assert!((q.normalize() - d).length() < 1e-5);
                let per_sample = d.z.abs() / s.pdf(d) * s.kept;
                assert!(
                    (per_sample - s.psa).abs() < 1e-4 * s.psa,
                    "sample {k}: {per_sample}"
                );
            }
        }
    }

    /// Directions land on a triangle as its pdf says (Pearson's chi-square over an 8 x 8 grid of
    /// barycentric cells, the pdf integrated over each), from a point it fills a fifth of the
    /// projected hemisphere of, off to the side (where a third of the tries miss it).
    #[test]
    fn directions_follow_the_pdf() {
        let (a, b, c) = (
            Vec3::new(-0.2, 0.3, 0.6),
            Vec3::new(1.6, -0.4, 0.9),
            Vec3::new(0.5, 1.4, 0.3),
        );
        let p = Vec3::ZERO;
        let n = Vec3::new(0.1, 0.0, 1.0).normalize();
        let s = ProjectedPolygon::new(p, n, &[a, b, c]).expect("wide light");
        let (e1, e2) = (b - a, c - a);
        let normal = e1.cross(e2).normalize();
        let meets = |d: Vec3| {
            let t = normal.dot(a - p) / normal.dot(d);
            let q = p + d * t;
            let (b1, b2) = barycentrics(q - a, e1, e2);
            (t > 0.0 && b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0).then_some(q)
        };
        const CELLS: usize = 8;
        // The cell of the triangle's (b1, b2) square (folded over the diagonal) a point lies in.
        let cell = |q: Vec3| {
            let (b1, b2) = barycentrics(q - a, e1, e2);
            let (i, j) = ((b1 * CELLS as f32) as usize, (b2 * CELLS as f32) as usize);
            i.min(CELLS - 1) * CELLS + j.min(CELLS - 1)
        };
        let n_samples = 200_000;
        let mut observed = vec![0.0f64; CELLS * CELLS];
        for k in 0..n_samples {
            let u = Vec2::new(hash(2 * k), hash(2 * k + 1));
            if let Some((_, q)) = s.sample(u, meets) {
                observed[cell(q)] += 1.0;
            }
        }
        // Expected: the pdf times cos / dist^2 over the area of each cell's part of the triangle.
        let mut expected = vec![0.0f64; CELLS * CELLS];
        const SUB: usize = 64;
        let area = e1.cross(e2).length();
        let step = 1.0 / (CELLS * SUB) as f32;
        for i in 0..CELLS * SUB {
            for j in 0..CELLS * SUB - i {
                let (b1, b2) = ((i as f32 + 0.5) * step, (j as f32 + 0.5) * step);
                if b1 + b2 > 1.0 {
                    continue;
                }
                let q = a + e1 * b1 + e2 * b2;
                let to = q - p;
                let d = to.normalize();
                let solid_angle = (area * step * step) * normal.dot(d).abs() / to.length_squared();
                expected[cell(q)] += (s.pdf(d) * solid_angle) as f64 * n_samples as f64;
            }
        }
        let fraction = s.psa / PI;
        assert!((0.15..0.3).contains(&fraction), "fraction {fraction}");
        let p_value = pearson_p_value(&observed, &expected);
        assert!(p_value > 1e-3, "p-value {p_value}");
    }

    /// Barycentrics (of `e1` and `e2`) of a point `r` relative to the first corner in their plane.
    fn barycentrics(r: Vec3, e1: Vec3, e2: Vec3) -> (f32, f32) {
        let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let (r1, r2) = (r.dot(e1), r.dot(e2));
        let det = d11 * d22 - d12 * d12;
        ((d22 * r1 - d12 * r2) / det, (d11 * r2 - d12 * r1) / det)
    }

    /// Lights across the horizon, too small a part of the sky, or seen without a normal are left
    /// to the other samplers.
    #[test]
    fn declines_where_it_does_not_apply() {
        let square =
            |h: f32, r: f32| [(-r, -r), (r, -r), (r, r), (-r, r)].map(|(x, y)| Vec3::new(x, y, h));
        assert!(ProjectedPolygon::new(Vec3::ZERO, Vec3::Z, &square(1.0, 1.0)).is_some());
        assert!(ProjectedPolygon::new(Vec3::ZERO, Vec3::ZERO, &square(1.0, 1.0)).is_none());
        assert!(ProjectedPolygon::new(Vec3::ZERO, Vec3::Z, &square(5.0, 1.0)).is_none());
        let tilted = Vec3::new(1.0, 0.0, 0.5).normalize();
        assert!(ProjectedPolygon::new(Vec3::ZERO, tilted, &square(1.0, 1.0)).is_none());
        // Degenerate input: a NaN point, a triangle of no area, a point at a corner.
        let nan = Vec3::splat(f32::NAN);
        assert!(ProjectedPolygon::new(nan, Vec3::Z, &square(1.0, 1.0)).is_none());
        let flat = [
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(2.0, 0.0, 1.0),
        ];
        assert!(ProjectedPolygon::new(Vec3::ZERO, Vec3::Z, &flat).is_none());
        let corner = square(1.0, 1.0)[0];
        assert!(ProjectedPolygon::new(corner, Vec3::Z, &square(1.0, 1.0)).is_none());
        // On the polygon's own plane (off it by rounding alone).
        let on = Vec3::new(0.1, 0.2, 1.0 + f32::EPSILON);
        assert!(ProjectedPolygon::new(on, Vec3::Z, &square(1.0, 1.0)).is_none());
    }
}
