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
    // Plain arrays: indexing them by the per-ray axis is a load, where indexing a Vec3 is a match.
    let a = (a - o).to_array();
    let b = (b - o).to_array();
    let c = (c - o).to_array();
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
    let t_scaled = u * (sh.sz * a[sh.kz]) + v * (sh.sz * b[sh.kz]) + w * (sh.sz * c[sh.kz]);
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

/// Four triangles side by side, `p[vertex][axis][lane]`, for testing one ray against all of them with
/// vector instructions. Unused lanes are skipped by the caller's lane count.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct Tri4 {
    pub p: [[[f32; 4]; 3]; 3],
}

impl Tri4 {
    pub fn new(tris: &[[Vec3; 3]]) -> Self {
        assert!(tris.len() <= 4);
        let mut p = [[[f32::NAN; 4]; 3]; 3];
        for (lane, t) in tris.iter().enumerate() {
            for (vertex, v) in t.iter().enumerate() {
                for axis in 0..3 {
                    p[vertex][axis][lane] = v[axis];
                }
            }
        }
        Self { p }
    }
}

/// Hits of up to four triangles: per lane the distance (`f32::INFINITY` for a miss) and barycentrics.
#[derive(Clone, Copy, Debug)]
pub struct Hits4 {
    pub t: [f32; 4],
    pub u: [f32; 4],
    pub v: [f32; 4],
}

/// The watertight test of `intersect` on four triangles at once. Each lane performs exactly the
/// operations of the scalar test, in the same order, so both give bit-identical hits.
#[inline(always)]
pub fn intersect4(o: Vec3, sh: &RayShear, tri: &Tri4, t_min: f32, t_max: f32) -> Hits4 {
    let o = o.to_array();
    let (kx, ky, kz) = (sh.kx, sh.ky, sh.kz);
    let rel = |vertex: usize, axis: usize| -> [f32; 4] {
        let c = &tri.p[vertex][axis];
        [
            c[0] - o[axis],
            c[1] - o[axis],
            c[2] - o[axis],
            c[3] - o[axis],
        ]
    };
    let (a_x, a_y, a_z) = (rel(0, kx), rel(0, ky), rel(0, kz));
    let (b_x, b_y, b_z) = (rel(1, kx), rel(1, ky), rel(1, kz));
    let (c_x, c_y, c_z) = (rel(2, kx), rel(2, ky), rel(2, kz));
    let mut out = Hits4 {
        t: [f32::INFINITY; 4],
        u: [0.0; 4],
        v: [0.0; 4],
    };
    let mut eu = [0.0f32; 4];
    let mut ev = [0.0f32; 4];
    let mut ew = [0.0f32; 4];
    let mut t_scaled = [0.0f32; 4];
    for l in 0..4 {
        let ax = a_x[l] - sh.sx * a_z[l];
        let ay = a_y[l] - sh.sy * a_z[l];
        let bx = b_x[l] - sh.sx * b_z[l];
        let by = b_y[l] - sh.sy * b_z[l];
        let cx = c_x[l] - sh.sx * c_z[l];
        let cy = c_y[l] - sh.sy * c_z[l];
        eu[l] = cx * by - cy * bx;
        ev[l] = ax * cy - ay * cx;
        ew[l] = bx * ay - by * ax;
        t_scaled[l] =
            eu[l] * (sh.sz * a_z[l]) + ev[l] * (sh.sz * b_z[l]) + ew[l] * (sh.sz * c_z[l]);
    }
    for l in 0..4 {
        let (mut u, mut v, mut w) = (eu[l], ev[l], ew[l]);
        let mut ts = t_scaled[l];
        if u == 0.0 || v == 0.0 || w == 0.0 {
            // The rare exact-zero case: recompute as the scalar test does.
            let ax = a_x[l] - sh.sx * a_z[l];
            let ay = a_y[l] - sh.sy * a_z[l];
            let bx = b_x[l] - sh.sx * b_z[l];
            let by = b_y[l] - sh.sy * b_z[l];
            let cx = c_x[l] - sh.sx * c_z[l];
            let cy = c_y[l] - sh.sy * c_z[l];
            u = (cx as f64 * by as f64 - cy as f64 * bx as f64) as f32;
            v = (ax as f64 * cy as f64 - ay as f64 * cx as f64) as f32;
            w = (bx as f64 * ay as f64 - by as f64 * ax as f64) as f32;
            ts = u * (sh.sz * a_z[l]) + v * (sh.sz * b_z[l]) + w * (sh.sz * c_z[l]);
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            continue;
        }
        let det = u + v + w;
        if det == 0.0 {
            continue;
        }
        let inv = 1.0 / det;
        let t = ts * inv;
        if t > t_min && t < t_max {
            out.t[l] = t;
            out.u[l] = v * inv;
            out.v[l] = w * inv;
        }
    }
    out
}
