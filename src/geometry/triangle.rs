//! The watertight ray/triangle test of Woop, Benthin and Wald (JCGT 2013), shared by the Rust backends.
//! Edge functions are evaluated in a ray-aligned shear space, so a ray through a shared edge or vertex
//! hits at least one of the triangles meeting there: no cracks for rays to slip through.

use glam::Vec3;

use super::f4::F4;
#[cfg(target_arch = "x86_64")]
use super::lanes::F8;
use super::lanes::{LaneMask, Lanes};

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
mod packet_tests {
    use super::*;

    /// Each lane of a group test, as `(t, u, v)` bits where it hits.
    fn lanes(h: &Hits, n: usize) -> Vec<Option<[u32; 3]>> {
        (0..n)
            .map(|l| (h.mask >> l & 1 == 1).then(|| [h.t[l], h.u[l], h.v[l]].map(f32::to_bits)))
            .collect()
    }

    /// Both packets at once in eight AVX lanes.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    fn pair(o: Vec3, sh: &RayShear, packets: &[Tri4; 2], t_max: f32) -> Hits {
        intersect_packets::<F8, _>(o, sh, packets, 0.0, t_max)
    }

    /// Every lane of `intersect4`, and of the eight-lane test of two packets, gives the scalar
    /// test's bits: on random triangles around the ray, and on rays through a shared vertex and
    /// along edges (exact zero edge functions, the lane-by-lane path), with some lanes unused.
    #[test]
    fn packet_lanes_match_the_scalar_test_bit_for_bit() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 40) as f32 / (1u64 << 24) as f32 - 0.5
        };
        let grid = |i: i32, j: i32| Vec3::new(i as f32 * 0.25, j as f32 * 0.25, 0.0);
        let mut groups = 0;
        let mut hits = 0;
        for round in 0..4000 {
            let (o, d) = if round % 2 == 0 {
                let d = Vec3::new(next(), next(), next() - 0.7).normalize();
                (Vec3::new(next(), next(), 1.0 + next()), d)
            } else {
                // Straight down onto a grid corner or edge: edge functions of exactly zero.
                let (i, j) = ((round / 2 % 5) as i32, (round / 10 % 5) as i32);
                let at = grid(i, j) + Vec3::new(0.125 * (round / 50 % 2) as f32, 0.0, 0.0);
                (at + Vec3::Z, -Vec3::Z)
            };
            let sh = RayShear::new(d);
            let used = 1 + round % 8;
            let tris: Vec<[Vec3; 3]> = (0..used)
                .map(|k| {
                    if round % 2 == 0 {
                        [0, 1, 2].map(|_| Vec3::new(next(), next(), next() * 0.2))
                    } else {
                        let (i, j) = ((k % 4) as i32, (k / 4) as i32);
                        [grid(i, j), grid(i + 1, j), grid(i + 1, j + 1)]
                    }
                })
                .collect();
            let packets = [
                Tri4::new(&tris[..used.min(4)]),
                Tri4::new(&tris[used.min(4)..]),
            ];
            let t_max = if round % 3 == 0 { 1.2 } else { f32::INFINITY };
            let want: Vec<_> = (0..8)
                .map(|l| {
                    let t = tris.get(l)?;
                    let h = intersect(o, &sh, t[0], t[1], t[2], 0.0, t_max)?;
                    Some([h.t, h.u, h.v].map(f32::to_bits))
                })
                .collect();
            let fours: Vec<_> = packets
                .iter()
                .flat_map(|p| lanes(&intersect4(o, &sh, p, 0.0, t_max), 4))
                .collect();
            assert_eq!(fours, want, "four lanes, round {round}");
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx") {
                // SAFETY: the CPU has AVX (checked just above).
                let h = unsafe { pair(o, &sh, &packets, t_max) };
                assert_eq!(lanes(&h, 8), want, "eight lanes, round {round}");
            }
            groups += 1;
            hits += want.iter().flatten().count();
        }
        assert!(hits > groups / 5, "{hits} hits in {groups} groups");
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

impl AsRef<Tri4> for Tri4 {
    fn as_ref(&self) -> &Tri4 {
        self
    }
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

/// Hits of a group of triangles (one packet of four, or two side by side): a bit per lane that hit
/// (`mask`), and per lane the distance and barycentrics (meaningful only where `mask` is set).
#[derive(Clone, Copy, Debug)]
pub struct Hits {
    pub mask: u32,
    pub t: [f32; 8],
    pub u: [f32; 8],
    pub v: [f32; 8],
}

/// Lanes that hold a whole number of packets, tested together: `F4` one, `F8` two.
pub trait PacketLanes: Lanes {
    /// Packets per group.
    const PACKETS: usize = Self::N / 4;
    /// Coordinate `axis` of vertex `vertex` of the `PACKETS` packets at the start of `packets`.
    fn coord<T: AsRef<Tri4>>(packets: &[T], vertex: usize, axis: usize) -> Self;
}

impl PacketLanes for F4 {
    #[inline(always)]
    fn coord<T: AsRef<Tri4>>(packets: &[T], vertex: usize, axis: usize) -> Self {
        F4::load(&packets[0].as_ref().p[vertex][axis])
    }
}

#[cfg(target_arch = "x86_64")]
impl PacketLanes for F8 {
    #[inline(always)]
    fn coord<T: AsRef<Tri4>>(packets: &[T], vertex: usize, axis: usize) -> Self {
        let [lo, hi] = &packets[..2] else {
            unreachable!("two packets")
        };
        let (lo, hi) = (&lo.as_ref().p[vertex][axis], &hi.as_ref().p[vertex][axis]);
        F8::halves(F4::load(lo), F4::load(hi))
    }
}

/// The watertight test of `intersect` on four triangles at once: the same operations per lane (so
/// both give bit-identical hits), on four lanes at a time. A lane with an edge function of exactly
/// zero (a ray through an edge or vertex) takes the scalar path, with its double-precision retry.
#[inline(always)]
pub fn intersect4(o: Vec3, sh: &RayShear, tri: &Tri4, t_min: f32, t_max: f32) -> Hits {
    intersect_packets::<F4, _>(o, sh, std::slice::from_ref(tri), t_min, t_max)
}

/// `intersect4` on the `L::PACKETS` packets at the start of `packets` at once (lane `4k + l`:
/// packet `k`, lane `l`), with the same bits in each lane at either width. `L` must be usable here
/// (`F8`: in code compiled for AVX).
#[inline(always)]
pub fn intersect_packets<L: PacketLanes, T: AsRef<Tri4>>(
    o: Vec3,
    sh: &RayShear,
    packets: &[T],
    t_min: f32,
    t_max: f32,
) -> Hits {
    let oa = o.to_array();
    let (kx, ky, kz) = (sh.kx, sh.ky, sh.kz);
    let (sx, sy, sz) = (L::splat(sh.sx), L::splat(sh.sy), L::splat(sh.sz));
    // No closure here: one that LLVM left out of line would not be compiled for AVX.
    #[inline(always)]
    fn rel<L: PacketLanes, T: AsRef<Tri4>>(p: &[T], o: &[f32; 3], vertex: usize, axis: usize) -> L {
        L::coord(p, vertex, axis) - L::splat(o[axis])
    }
    let p = packets;
    let (az, bz, cz) = (
        rel::<L, T>(p, &oa, 0, kz),
        rel(p, &oa, 1, kz),
        rel(p, &oa, 2, kz),
    );
    let ax = rel::<L, T>(p, &oa, 0, kx) - sx * az;
    let ay = rel::<L, T>(p, &oa, 0, ky) - sy * az;
    let bx = rel::<L, T>(p, &oa, 1, kx) - sx * bz;
    let by = rel::<L, T>(p, &oa, 1, ky) - sy * bz;
    let cx = rel::<L, T>(p, &oa, 2, kx) - sx * cz;
    let cy = rel::<L, T>(p, &oa, 2, ky) - sy * cz;
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    let zero = L::splat(0.0);
    if L::bits(u.eq(zero).or(v.eq(zero)).or(w.eq(zero))) != 0 {
        return intersect_lanes(oa, sh, &packets[..L::PACKETS], t_min, t_max);
    }
    let t_scaled = u * (sz * az) + v * (sz * bz) + w * (sz * cz);
    let neg = u.lt(zero).or(v.lt(zero)).or(w.lt(zero));
    let pos = u.gt(zero).or(v.gt(zero)).or(w.gt(zero));
    let det = u + v + w;
    let inv = L::splat(1.0) / det;
    let t = t_scaled * inv;
    let ok = t
        .gt(L::splat(t_min))
        .and(t.lt(L::splat(t_max)))
        .and_not(neg.and(pos))
        .and_not(det.eq(zero));
    let mut out = Hits {
        mask: L::bits(ok),
        t: [0.0; 8],
        u: [0.0; 8],
        v: [0.0; 8],
    };
    t.store(&mut out.t);
    (v * inv).store(&mut out.u);
    (w * inv).store(&mut out.v);
    out
}

/// `intersect_packets` lane by lane, for groups where some edge function is exactly zero.
#[cold]
#[inline(never)]
fn intersect_lanes<T: AsRef<Tri4>>(
    o: [f32; 3],
    sh: &RayShear,
    packets: &[T],
    t_min: f32,
    t_max: f32,
) -> Hits {
    let mut out = Hits {
        mask: 0,
        t: [f32::INFINITY; 8],
        u: [0.0; 8],
        v: [0.0; 8],
    };
    for (k, tri) in packets.iter().enumerate() {
        let tri = tri.as_ref();
        let at = |vertex: usize, l: usize| {
            let p = &tri.p[vertex];
            [
                p[sh.kx][l] - o[sh.kx],
                p[sh.ky][l] - o[sh.ky],
                p[sh.kz][l] - o[sh.kz],
            ]
        };
        for l in 0..4 {
            let s = Sheared::new(sh, at(0, l), at(1, l), at(2, l));
            let e = s.edges();
            if let Some(h) = s.finish(sh, e, s.t_scaled(sh, e), t_min, t_max) {
                let lane = 4 * k + l;
                out.mask |= 1 << lane;
                out.t[lane] = h.t;
                out.u[lane] = h.u;
                out.v[lane] = h.v;
            }
        }
    }
    out
}
