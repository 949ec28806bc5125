//! The watertight ray/triangle test of Woop, Benthin and Wald (JCGT 2013), shared by the Rust backends.
//! Edge functions are evaluated in a ray-aligned shear space, so a ray through a shared edge or vertex
//! hits at least one of the triangles meeting there: no cracks for rays to slip through.

use glam::Vec3;

/// Per-ray constants of the watertight test: the axis permutation and shear that map the ray onto +Z.
#[derive(Clone, Copy, Debug)]
pub struct RayShear {
    pub kx: usize,
    pub ky: usize,
    pub kz: usize,
    pub sx: f32,
    pub sy: f32,
    pub sz: f32,
}

impl RayShear {
    pub fn new(d: Vec3) -> Self {
        let kz = d.abs().max_position();
        let mut kx = (kz + 1) % 3;
        let mut ky = (kx + 1) % 3;
        // Keep the winding: swap when the dominant component is negative.
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        Self {
            kx,
            ky,
            kz,
            sx: d[kx] / d[kz],
            sy: d[ky] / d[kz],
            sz: 1.0 / d[kz],
        }
    }
}

/// A hit of one triangle: distance and barycentrics of vertices 1 and 2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriHit {
    pub t: f32,
    pub u: f32,
    pub v: f32,
}

/// Intersects the ray `o + t d` (with `sh = RayShear::new(d)`) with triangle `(a, b, c)`, both faces,
/// accepting `t` in `(t_min, t_max)`.
#[inline(always)]
pub fn intersect(
    o: Vec3,
    sh: &RayShear,
    a: Vec3,
    b: Vec3,
    c: Vec3,
    t_min: f32,
    t_max: f32,
) -> Option<TriHit> {
    let a = a - o;
    let b = b - o;
    let c = c - o;
    let ax = a[sh.kx] - sh.sx * a[sh.kz];
    let ay = a[sh.ky] - sh.sy * a[sh.kz];
    let bx = b[sh.kx] - sh.sx * b[sh.kz];
    let by = b[sh.ky] - sh.sy * b[sh.kz];
    let cx = c[sh.kx] - sh.sx * c[sh.kz];
    let cy = c[sh.ky] - sh.sy * c[sh.kz];
    let mut u = cx * by - cy * bx;
    let mut v = ax * cy - ay * cx;
    let mut w = bx * ay - by * ax;
    // An edge function that is exactly zero is recomputed in double precision, so that the sign on
    // shared edges is consistent between neighbouring triangles.
    if u == 0.0 || v == 0.0 || w == 0.0 {
        u = (cx as f64 * by as f64 - cy as f64 * bx as f64) as f32;
        v = (ax as f64 * cy as f64 - ay as f64 * cx as f64) as f32;
        w = (bx as f64 * ay as f64 - by as f64 * ax as f64) as f32;
    }
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        return None;
    }
    let az = sh.sz * a[sh.kz];
    let bz = sh.sz * b[sh.kz];
    let cz = sh.sz * c[sh.kz];
    let t_scaled = u * az + v * bz + w * cz;
    let inv = 1.0 / det;
    let t = t_scaled * inv;
    if !(t > t_min && t < t_max) {
        return None;
    }
    // u weights vertex a, v vertex b, w vertex c: report the weights of b and c.
    Some(TriHit {
        t,
        u: v * inv,
        v: w * inv,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hit(o: Vec3, d: Vec3, tri: [Vec3; 3]) -> Option<TriHit> {
        intersect(
            o,
            &RayShear::new(d),
            tri[0],
            tri[1],
            tri[2],
            0.0,
            f32::INFINITY,
        )
    }

    #[test]
    fn barycentrics_and_distance() {
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let h = hit(Vec3::new(0.25, 0.5, 2.0), -Vec3::Z, tri).unwrap();
        assert!((h.t - 2.0).abs() < 1e-6);
        assert!((h.u - 0.25).abs() < 1e-6 && (h.v - 0.5).abs() < 1e-6);
        // Both faces are hit.
        let h = hit(Vec3::new(0.25, 0.5, -2.0), Vec3::Z, tri).unwrap();
        assert!((h.t - 2.0).abs() < 1e-6);
        assert!(hit(Vec3::new(1.0, 1.0, 2.0), -Vec3::Z, tri).is_none());
    }

    #[test]
    fn shared_edge_is_never_missed() {
        // Two triangles sharing the diagonal of a unit square; rays exactly on the diagonal.
        let t1 = [
            Vec3::ZERO,
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
        ];
        let t2 = [
            Vec3::ZERO,
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        for i in 1..1000 {
            let s = i as f32 / 1000.0;
            let d = Vec3::new(0.013 * s, -0.007, -1.0);
            let o = Vec3::new(s, s, 0.0) - d;
            assert!(
                hit(o, d, t1).is_some() || hit(o, d, t2).is_some(),
                "ray {i} slipped through the shared edge"
            );
        }
    }
}

#[cfg(test)]
mod direction_tests {
    use super::*;

    #[test]
    fn every_direction_hits_a_triangle_around_its_target() {
        let tri = [
            Vec3::new(-1.0, -1.0, 0.3),
            Vec3::new(1.5, -0.5, -0.2),
            Vec3::new(0.0, 1.2, 0.1),
        ];
        let target = (tri[0] + tri[1] + tri[2]) / 3.0;
        let mut missed = 0;
        for i in 0..2000 {
            let a = i as f32 * 0.618;
            let b = i as f32 * 0.377;
            let d = Vec3::new(a.cos() * b.sin(), a.sin() * b.sin(), b.cos()).normalize();
            let o = target - d * 3.0;
            if intersect(
                o,
                &RayShear::new(d),
                tri[0],
                tri[1],
                tri[2],
                0.0,
                f32::INFINITY,
            )
            .is_none()
            {
                missed += 1;
                if missed < 4 {
                    eprintln!("missed d = {d:?}");
                }
            }
        }
        assert_eq!(missed, 0);
    }
}
