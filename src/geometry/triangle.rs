//! The watertight ray/triangle test of Woop, Benthin and Wald (JCGT 2013), shared by the Rust backends.
//! Edge functions are evaluated in a ray-aligned shear space, so a ray through a shared edge or vertex
//! hits at least one of the triangles meeting there: no cracks for rays to slip through.

use glam::Vec3;

use super::f4::F4;

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

/// One triangle's vertices relative to the ray origin, permuted into the ray's axis order and
/// sheared so that the ray runs along +z: `x`, `y` across the ray, `z` along it (not yet scaled).
#[derive(Clone, Copy, Debug)]
struct Sheared {
    ax: f32,
    ay: f32,
    az: f32,
    bx: f32,
    by: f32,
    bz: f32,
    cx: f32,
    cy: f32,
    cz: f32,
}

impl Sheared {
    /// From the vertices' coordinates relative to the origin, given as (kx, ky, kz) components.
    #[inline(always)]
    fn new(sh: &RayShear, a: [f32; 3], b: [f32; 3], c: [f32; 3]) -> Self {
        Self {
            ax: a[0] - sh.sx * a[2],
            ay: a[1] - sh.sy * a[2],
            az: a[2],
            bx: b[0] - sh.sx * b[2],
            by: b[1] - sh.sy * b[2],
            bz: b[2],
            cx: c[0] - sh.sx * c[2],
            cy: c[1] - sh.sy * c[2],
            cz: c[2],
        }
    }

    /// The edge functions (u, v, w) in single precision.
    #[inline(always)]
    fn edges(&self) -> [f32; 3] {
        [
            self.cx * self.by - self.cy * self.bx,
            self.ax * self.cy - self.ay * self.cx,
            self.bx * self.ay - self.by * self.ax,
        ]
    }

    /// The hit distance times the determinant, from the edge functions.
    #[inline(always)]
    fn t_scaled(&self, sh: &RayShear, [u, v, w]: [f32; 3]) -> f32 {
        u * (sh.sz * self.az) + v * (sh.sz * self.bz) + w * (sh.sz * self.cz)
    }

    /// Finishes the test from the edge functions and `t_scaled` of them: a hit with `t` in
    /// `(t_min, t_max)`, or none.
    #[inline(always)]
    fn finish(
        &self,
        sh: &RayShear,
        [mut u, mut v, mut w]: [f32; 3],
        mut t_scaled: f32,
        t_min: f32,
        t_max: f32,
    ) -> Option<TriHit> {
        // An edge function that is exactly zero is recomputed in double precision, so that the sign
        // on shared edges is consistent between neighbouring triangles.
        if u == 0.0 || v == 0.0 || w == 0.0 {
            let (ax, ay, bx, by, cx, cy) = (
                self.ax as f64,
                self.ay as f64,
                self.bx as f64,
                self.by as f64,
                self.cx as f64,
                self.cy as f64,
            );
            u = (cx * by - cy * bx) as f32;
            v = (ax * cy - ay * cx) as f32;
            w = (bx * ay - by * ax) as f32;
            t_scaled = self.t_scaled(sh, [u, v, w]);
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
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
    let k = |p: Vec3| {
        let p = (p - o).to_array();
        [p[sh.kx], p[sh.ky], p[sh.kz]]
    };
    let s = Sheared::new(sh, k(a), k(b), k(c));
    let e = s.edges();
    s.finish(sh, e, s.t_scaled(sh, e), t_min, t_max)
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(super) fn hit(o: Vec3, d: Vec3, tri: [Vec3; 3]) -> Option<TriHit> {
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
            if super::tests::hit(o, d, tri).is_none() {
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

    /// The triangles `tris[i]` for `i` in `indices`, in order, four to a packet, each packet with
    /// its lanes' indices (`u32::MAX` for the unused lanes of the last one, which never hit).
    pub fn packets<'a>(
        indices: &'a [u32],
        tris: &'a [[Vec3; 3]],
    ) -> impl Iterator<Item = (Tri4, [u32; 4])> + 'a {
        indices.chunks(4).map(move |chunk| {
            let mut packet = [[Vec3::ZERO; 3]; 4];
            let mut lanes = [u32::MAX; 4];
            for (lane, &i) in chunk.iter().enumerate() {
                packet[lane] = tris[i as usize];
                lanes[lane] = i;
            }
            (Tri4::new(&packet[..chunk.len()]), lanes)
        })
    }
}

/// Hits of up to four triangles: a bit per lane that hit (`mask`), and per lane the distance and
/// barycentrics (meaningful only where `mask` is set).
#[derive(Clone, Copy, Debug)]
pub struct Hits4 {
    pub mask: u32,
    pub t: [f32; 4],
    pub u: [f32; 4],
    pub v: [f32; 4],
}

/// The watertight test of `intersect` on four triangles at once: the same operations per lane (so
/// both give bit-identical hits), on four lanes at a time. A lane with an edge function of exactly
/// zero (a ray through an edge or vertex) takes the scalar path, with its double-precision retry.
#[inline(always)]
pub fn intersect4(o: Vec3, sh: &RayShear, tri: &Tri4, t_min: f32, t_max: f32) -> Hits4 {
    let o = o.to_array();
    let (kx, ky, kz) = (sh.kx, sh.ky, sh.kz);
    let rel = |vertex: usize, axis: usize| F4::load(&tri.p[vertex][axis]) - F4::splat(o[axis]);
    let (sx, sy, sz) = (F4::splat(sh.sx), F4::splat(sh.sy), F4::splat(sh.sz));
    let (az, bz, cz) = (rel(0, kz), rel(1, kz), rel(2, kz));
    let ax = rel(0, kx) - sx * az;
    let ay = rel(0, ky) - sy * az;
    let bx = rel(1, kx) - sx * bz;
    let by = rel(1, ky) - sy * bz;
    let cx = rel(2, kx) - sx * cz;
    let cy = rel(2, ky) - sy * cz;
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    let zero = F4::splat(0.0);
    if u.eq(zero).or(v.eq(zero)).or(w.eq(zero)).bits() != 0 {
        return intersect4_lanes(o, sh, tri, t_min, t_max);
    }
    let t_scaled = u * (sz * az) + v * (sz * bz) + w * (sz * cz);
    let neg = u.lt(zero).or(v.lt(zero)).or(w.lt(zero));
    let pos = u.gt(zero).or(v.gt(zero)).or(w.gt(zero));
    let det = u + v + w;
    let inv = F4::splat(1.0) / det;
    let t = t_scaled * inv;
    let ok = t
        .gt(F4::splat(t_min))
        .and(t.lt(F4::splat(t_max)))
        .and_not(neg.and(pos))
        .and_not(det.eq(zero));
    Hits4 {
        mask: ok.bits(),
        t: t.to_array(),
        u: (v * inv).to_array(),
        v: (w * inv).to_array(),
    }
}

/// `intersect4` lane by lane, for packets where some edge function is exactly zero.
#[cold]
#[inline(never)]
fn intersect4_lanes(o: [f32; 3], sh: &RayShear, tri: &Tri4, t_min: f32, t_max: f32) -> Hits4 {
    let mut out = Hits4 {
        mask: 0,
        t: [f32::INFINITY; 4],
        u: [0.0; 4],
        v: [0.0; 4],
    };
    let k = |vertex: usize, l: usize| {
        let p = &tri.p[vertex];
        [
            p[sh.kx][l] - o[sh.kx],
            p[sh.ky][l] - o[sh.ky],
            p[sh.kz][l] - o[sh.kz],
        ]
    };
    for l in 0..4 {
        let s = Sheared::new(sh, k(0, l), k(1, l), k(2, l));
        let e = s.edges();
        if let Some(h) = s.finish(sh, e, s.t_scaled(sh, e), t_min, t_max) {
            out.mask |= 1 << l;
            out.t[l] = h.t;
            out.u[l] = h.u;
            out.v[l] = h.v;
        }
    }
    out
}
