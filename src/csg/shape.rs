//! The analytic primitives of CSG in their own object space: where a line crosses each one (as at most
//! two entering/leaving spans), the normal of each face, and projection of a point back onto a face.

use glam::{DVec3, Vec3};

use crate::geometry::Aabb;

/// A primitive solid in its own object space. Axis-symmetric shapes stand on the y axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    Sphere {
        center: Vec3,
        radius: f32,
    },
    /// Axis-aligned box from `min` to `max`.
    Box {
        min: Vec3,
        max: Vec3,
    },
    /// Capped cylinder around the y axis, from y = -height/2 to y = +height/2.
    Cylinder {
        radius: f32,
        height: f32,
    },
    /// Capped cone around the y axis: base disc of `radius` at y = -height/2, apex at y = +height/2.
    Cone {
        radius: f32,
        height: f32,
    },
    /// Torus around the y axis: a tube of radius `minor` whose centre circle (radius `major`) lies in
    /// the xz plane.
    Torus {
        major: f32,
        minor: f32,
    },
    /// The solid `normal . p <= offset` (`normal` is unit length).
    HalfSpace {
        normal: Vec3,
        offset: f32,
    },
}

/// Where a line enters (`t0`, face `f0`) and leaves (`t1`, face `f1`) a primitive; `t0 < t1`, either
/// may be infinite (half-spaces).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span {
    pub t0: f32,
    pub t1: f32,
    pub f0: u32,
    pub f1: u32,
}

/// Up to two spans, in order (only a torus has two).
#[derive(Clone, Copy, Debug, Default)]
pub struct Spans {
    pub n: usize,
    pub s: [Option<Span>; 2],
}

impl Spans {
    fn one(t0: f32, f0: u32, t1: f32, f1: u32) -> Self {
        if t0 < t1 {
            Spans {
                n: 1,
                s: [Some(Span { t0, t1, f0, f1 }), None],
            }
        } else {
            Spans::default()
        }
    }

    pub fn iter(&self) -> impl Iterator<Item = Span> + '_ {
        self.s[..self.n].iter().flatten().copied()
    }
}

/// Face codes: box faces are `2 * axis + (1 on the max side)`; cylinder 0 side, 1 bottom, 2 top;
/// cone 0 side, 1 base; the others have one face, 0.
const SIDE: u32 = 0;
const BOTTOM: u32 = 1;
const TOP: u32 = 2;

/// Relative slack on edge tests (a side root just past a cap, a cap root just outside its disc), so
/// rays through an edge find both faces rather than neither.
const EDGE_SLACK: f64 = 1e-6;

/// Roots of `a t^2 + 2 b t + c = 0` in ascending order, computed without cancellation
/// (Ray Tracing Gems ch. 7); `None` without two real roots.
fn quadratic(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    if a == 0.0 {
        return None;
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    let q = -b - disc.sqrt().copysign(b);
    if q == 0.0 {
        return None;
    }
    let (t0, t1) = (c / q, q / a);
    Some(if t0 < t1 { (t0, t1) } else { (t1, t0) })
}

/// Roots of a sphere centred at `c` (radius `r`) on the line `o + t d`, with the discriminant formed
/// from the perpendicular distance to the centre so that it stays accurate far from the sphere
/// (Ray Tracing Gems ch. 7).
fn sphere_roots(o: DVec3, d: DVec3, c: DVec3, r: f64) -> Option<(f64, f64)> {
    let f = o - c;
    let a = d.dot(d);
    let b = f.dot(d);
    let l = f - d * (b / a);
    let disc = a * (r * r - l.dot(l));
    if disc < 0.0 || a == 0.0 {
        return None;
    }
    let q = -b - disc.sqrt().copysign(b);
    if q == 0.0 {
        return None;
    }
    let (t0, t1) = ((f.dot(f) - r * r) / q, q / a);
    Some(if t0 < t1 { (t0, t1) } else { (t1, t0) })
}

impl Shape {
    /// Object-space bounds (everything for a half-space).
    pub fn bounds(&self) -> Aabb {
        match *self {
            Shape::Sphere { center, radius } => Aabb {
                min: center - Vec3::splat(radius),
                max: center + Vec3::splat(radius),
            },
            Shape::Box { min, max } => Aabb { min, max },
            Shape::Cylinder { radius, height } | Shape::Cone { radius, height } => Aabb {
                min: Vec3::new(-radius, -height / 2.0, -radius),
                max: Vec3::new(radius, height / 2.0, radius),
            },
            Shape::Torus { major, minor } => {
                let e = major + minor;
                Aabb {
                    min: Vec3::new(-e, -minor, -e),
                    max: Vec3::new(e, minor, e),
                }
            }
            Shape::HalfSpace { .. } => Aabb {
                min: Vec3::splat(f32::NEG_INFINITY),
                max: Vec3::splat(f32::INFINITY),
            },
        }
    }

    /// Where the line `o + t d` (object space; `d` need not be unit) is inside the solid.
    /// Computed in f64 from the f32 inputs: the primitives' rounding then stays far below the
    /// rounding of the ray's transform to object space.
    pub fn spans(&self, o: Vec3, d: Vec3) -> Spans {
        let (o, d) = (o.as_dvec3(), d.as_dvec3());
        let one = |t0: f64, f0, t1: f64, f1| Spans::one(t0 as f32, f0, t1 as f32, f1);
        match *self {
            Shape::Sphere { center, radius } => {
                match sphere_roots(o, d, center.as_dvec3(), radius as f64) {
                    Some((t0, t1)) => one(t0, 0, t1, 0),
                    None => Spans::default(),
                }
            }
            Shape::Box { min, max } => {
                let (min, max) = (min.as_dvec3(), max.as_dvec3());
                let (mut t0, mut t1, mut f0, mut f1) = (f64::NEG_INFINITY, f64::INFINITY, 0, 0);
                for a in 0..3 {
                    let faces = (2 * a as u32, 2 * a as u32 + 1);
                    let slab = (min[a], max[a], faces);
                    if !clip_slab(o[a], d[a], slab, (&mut t0, &mut f0), (&mut t1, &mut f1)) {
                        return Spans::default();
                    }
                }
                one(t0, f0, t1, f1)
            }
            Shape::Cylinder { radius, height } => {
                let (r, h2) = (radius as f64, height as f64 / 2.0);
                // The infinite cylinder (a circle in xz), then the slab between the caps.
                let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
                let (mut f0, mut f1) = (SIDE, SIDE);
                let flat = |v: DVec3| DVec3::new(v.x, 0.0, v.z);
                if d.x == 0.0 && d.z == 0.0 {
                    if o.x * o.x + o.z * o.z > r * r {
                        return Spans::default();
                    }
                } else {
                    match sphere_roots(flat(o), flat(d), DVec3::ZERO, r) {
                        Some((a, b)) => (t0, t1) = (a, b),
                        None => return Spans::default(),
                    }
                }
                let slab = (-h2, h2, (BOTTOM, TOP));
                if !clip_slab(o.y, d.y, slab, (&mut t0, &mut f0), (&mut t1, &mut f1)) {
                    return Spans::default();
                }
                one(t0, f0, t1, f1)
            }
            Shape::Cone { radius, height } => {
                let (r, h) = (radius as f64, height as f64);
                let k2 = (r / h) * (r / h);
                // s: distance below the apex along the axis; the side is x^2 + z^2 = k^2 s^2, 0 <= s <= h.
                let (so, sd) = (h / 2.0 - o.y, -d.y);
                let mut cand = [(0.0f64, 0u32); 3];
                let mut n = 0;
                let a = d.x * d.x + d.z * d.z - k2 * sd * sd;
                let b = o.x * d.x + o.z * d.z - k2 * so * sd;
                let c = o.x * o.x + o.z * o.z - k2 * so * so;
                let mut side = |t: f64| {
                    let s = so + t * sd;
                    if s >= -EDGE_SLACK * h && s <= h * (1.0 + EDGE_SLACK) {
                        cand[n] = (t, SIDE);
                        n += 1;
                    }
                };
                if let Some((ta, tb)) = quadratic(a, b, c) {
                    side(ta);
                    side(tb);
                } else if a == 0.0 && b != 0.0 {
                    side(-c / (2.0 * b));
                }
                if d.y != 0.0 {
                    let t = (-h / 2.0 - o.y) / d.y;
                    let p = o + d * t;
                    if p.x * p.x + p.z * p.z <= r * r * (1.0 + EDGE_SLACK) {
                        cand[n] = (t, BOTTOM);
                        n += 1;
                    }
                }
                // A convex solid: the line is inside between its first and last crossing.
                if n < 2 {
                    return Spans::default();
                }
                let cand = &cand[..n];
                let lo = cand.iter().min_by(|x, y| x.0.total_cmp(&y.0)).unwrap();
                let hi = cand.iter().max_by(|x, y| x.0.total_cmp(&y.0)).unwrap();
                one(lo.0, lo.1, hi.0, hi.1)
            }
            Shape::Torus { major, minor } => torus_spans(o, d, major as f64, minor as f64),
            Shape::HalfSpace { normal, offset } => {
                let n = normal.as_dvec3();
                let (dn, on) = (n.dot(d), n.dot(o) - offset as f64);
                if dn == 0.0 {
                    return if on <= 0.0 {
                        one(f64::NEG_INFINITY, 0, f64::INFINITY, 0)
                    } else {
                        Spans::default()
                    };
                }
                let t = -on / dn;
                if dn > 0.0 {
                    one(f64::NEG_INFINITY, 0, t, 0)
                } else {
                    one(t, 0, f64::INFINITY, 0)
                }
            }
        }
    }

    /// The outward normal (not normalised) of face `face` at a point `p` on it, in object space.
    pub fn normal(&self, face: u32, p: Vec3) -> Vec3 {
        match *self {
            Shape::Sphere { center, .. } => p - center,
            Shape::Box { .. } => {
                let mut n = Vec3::ZERO;
                n[(face / 2) as usize] = if face % 2 == 1 { 1.0 } else { -1.0 };
                n
            }
            Shape::Cylinder { .. } => match face {
                BOTTOM => Vec3::NEG_Y,
                TOP => Vec3::Y,
                _ => Vec3::new(p.x, 0.0, p.z),
            },
            Shape::Cone { radius, height } => match face {
                BOTTOM => Vec3::NEG_Y,
                _ => {
                    let k = radius / height;
                    // Gradient of x^2 + z^2 - k^2 s^2 with s = h/2 - y; along the slant line at the apex.
                    let s = (height / 2.0 - p.y).max(0.0);
                    let n = Vec3::new(p.x, k * k * s, p.z);
                    if n.length_squared() > 0.0 {
                        n
                    } else {
                        Vec3::Y
                    }
                }
            },
            Shape::Torus { major, .. } => {
                let ring = Vec3::new(p.x, 0.0, p.z).normalize_or(Vec3::X) * major;
                p - ring
            }
            Shape::HalfSpace { normal, .. } => normal,
        }
    }

    /// `p` moved onto face `face` (the closest point, or a Newton step towards it): a hit found as
    /// `o + t d` can lie many ulps off the surface when `t` is large, and rays leaving it must start
    /// from a point whose error is bounded by the surface's own scale (pbrt's reprojection).
    pub fn project(&self, face: u32, p: Vec3) -> Vec3 {
        match *self {
            Shape::Sphere { center, radius } => {
                center + (p - center).normalize_or(Vec3::Y) * radius
            }
            Shape::Box { min, max } => {
                let mut q = p;
                let a = (face / 2) as usize;
                q[a] = if face % 2 == 1 { max[a] } else { min[a] };
                q
            }
            Shape::Cylinder { radius, height } => match face {
                BOTTOM => Vec3::new(p.x, -height / 2.0, p.z),
                TOP => Vec3::new(p.x, height / 2.0, p.z),
                _ => {
                    let r = Vec3::new(p.x, 0.0, p.z).normalize_or(Vec3::X) * radius;
                    Vec3::new(r.x, p.y, r.z)
                }
            },
            Shape::Cone { radius, height } => match face {
                BOTTOM => Vec3::new(p.x, -height / 2.0, p.z),
                _ => {
                    let k2 = (radius / height).powi(2);
                    let s = height / 2.0 - p.y;
                    let f = p.x * p.x + p.z * p.z - k2 * s * s;
                    let g = Vec3::new(2.0 * p.x, 2.0 * k2 * s, 2.0 * p.z);
                    let gg = g.length_squared();
                    if gg > 0.0 {
                        p - g * (f / gg)
                    } else {
                        p
                    }
                }
            },
            Shape::Torus { major, minor } => {
                let ring = Vec3::new(p.x, 0.0, p.z).normalize_or(Vec3::X) * major;
                ring + (p - ring).normalize_or(Vec3::Y) * minor
            }
            Shape::HalfSpace { normal, offset } => p - normal * (normal.dot(p) - offset),
        }
    }

    /// Whether object-space point `p` is strictly inside (for tests).
    pub fn contains(&self, p: Vec3) -> bool {
        match *self {
            Shape::Sphere { center, radius } => (p - center).length_squared() < radius * radius,
            Shape::Box { min, max } => p.cmpgt(min).all() && p.cmplt(max).all(),
            Shape::Cylinder { radius, height } => {
                p.x * p.x + p.z * p.z < radius * radius && p.y.abs() < height / 2.0
            }
            Shape::Cone { radius, height } => {
                let s = height / 2.0 - p.y;
                let rr = radius / height * s;
                s > 0.0 && s < height && p.x * p.x + p.z * p.z < rr * rr
            }
            Shape::Torus { major, minor } => {
                let q = Vec3::new(p.x, 0.0, p.z).length() - major;
                q * q + p.y * p.y < minor * minor
            }
            Shape::HalfSpace { normal, offset } => normal.dot(p) < offset,
        }
    }
}

/// Spans of a torus: the quartic in a parameter shifted to the point of the line closest to the
/// centre (its cubic term vanishes and the coefficients stay small), solved by Ferrari's method and
/// each root polished by Newton steps on the quartic itself; the inside is then read between
/// consecutive roots.
fn torus_spans(o: DVec3, d: DVec3, big: f64, small: f64) -> Spans {
    let len = d.length();
    if len == 0.0 || !len.is_finite() {
        return Spans::default();
    }
    let u = d / len;
    let sc = -o.dot(u);
    let p0 = o + u * sc;
    // |p0 + s u|^2 = s^2 + |p0|^2 since p0 . u = 0.
    let g = p0.dot(p0) + big * big - small * small;
    let r2 = 4.0 * big * big;
    let a2 = u.x * u.x + u.z * u.z;
    let b2 = p0.x * u.x + p0.z * u.z;
    let c2 = p0.x * p0.x + p0.z * p0.z;
    // s^4 + p s^2 + q s + r = 0
    let p = 2.0 * g - r2 * a2;
    let q = -2.0 * r2 * b2;
    let r = g * g - r2 * c2;
    let mut roots = [0.0f64; 4];
    let n = depressed_quartic(p, q, r, &mut roots);
    let f = |s: f64| ((s * s + p) * s + q) * s + r;
    let df = |s: f64| (4.0 * s * s + 2.0 * p) * s + q;
    for s in &mut roots[..n] {
        for _ in 0..3 {
            let dd = df(*s);
            if dd == 0.0 {
                break;
            }
            let step = f(*s) / dd;
            if !step.is_finite() {
                break;
            }
            *s -= step;
        }
    }
    let roots = &mut roots[..n];
    roots.sort_by(f64::total_cmp);
    let inside = |s: f64| {
        let x = p0 + u * s;
        let rho = (x.x * x.x + x.z * x.z).sqrt() - big;
        rho * rho + x.y * x.y < small * small
    };
    let mut out = Spans::default();
    for w in roots.windows(2) {
        if w[1] > w[0] && inside(0.5 * (w[0] + w[1])) && out.n < 2 {
            let t0 = ((sc + w[0]) / len) as f32;
            let t1 = ((sc + w[1]) / len) as f32;
            if t0 < t1 {
                out.s[out.n] = Some(Span {
                    t0,
                    t1,
                    f0: 0,
                    f1: 0,
                });
                out.n += 1;
            }
        }
    }
    out
}

/// Real roots of `s^4 + p s^2 + q s + r` (Ferrari): with `m` the largest root of the resolvent cubic
/// `8m^3 + 8p m^2 + (2p^2 - 8r) m - q^2`, the quartic splits into two quadratics.
fn depressed_quartic(p: f64, q: f64, r: f64, out: &mut [f64; 4]) -> usize {
    let mut n = 0;
    let mut push_quadratic = |b: f64, c: f64, out: &mut [f64; 4]| {
        // s^2 + b s + c = 0
        let disc = b * b - 4.0 * c;
        if disc >= 0.0 {
            let q = -0.5 * (b + disc.sqrt().copysign(b));
            if q != 0.0 {
                out[n] = q;
                out[n + 1] = c / q;
                n += 2;
            } else {
                out[n] = 0.0;
                out[n + 1] = 0.0;
                n += 2;
            }
        }
    };
    let scale = p.abs().max(r.abs().sqrt()).max(1e-300);
    if q.abs() <= 1e-14 * scale * scale.sqrt() {
        // Biquadratic: u = s^2.
        let disc = p * p - 4.0 * r;
        if disc < 0.0 {
            return 0;
        }
        let sq = disc.sqrt();
        let mut k = 0;
        for u in [(-p + sq) / 2.0, (-p - sq) / 2.0] {
            if u >= 0.0 {
                out[k] = u.sqrt();
                out[k + 1] = -u.sqrt();
                k += 2;
            }
        }
        return k;
    }
    let m = largest_cubic_root(p, p * p / 4.0 - r, -q * q / 8.0);
    // (Also rejects NaN.)
    if m.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return 0;
    }
    let s2m = (2.0 * m).sqrt();
    let h = q / (2.0 * s2m);
    push_quadratic(-s2m, p / 2.0 + m + h, out);
    push_quadratic(s2m, p / 2.0 + m - h, out);
    n
}

/// The largest real root of `m^3 + a m^2 + b m + c`, polished by Newton steps.
fn largest_cubic_root(a: f64, b: f64, c: f64) -> f64 {
    let q = (a * a - 3.0 * b) / 9.0;
    let r = (2.0 * a * a * a - 9.0 * a * b + 27.0 * c) / 54.0;
    let mut m = if r * r < q * q * q {
        let theta = (r / (q * q * q).sqrt()).clamp(-1.0, 1.0).acos();
        -2.0 * q.sqrt() * (theta / 3.0).cos() - a / 3.0
    } else {
        let big = -(r.abs() + (r * r - q * q * q).sqrt()).cbrt().copysign(r);
        let small = if big != 0.0 { q / big } else { 0.0 };
        big + small - a / 3.0
    };
    for _ in 0..4 {
        let f = ((m + a) * m + b) * m + c;
        let df = (3.0 * m + 2.0 * a) * m + b;
        if df == 0.0 {
            break;
        }
        let step = f / df;
        if !step.is_finite() {
            break;
        }
        m -= step;
    }
    m
}

/// Narrows the span from `(t0, f0)` to `(t1, f1)` (distances and faces) of the line `o + t d`, along
/// one axis, to the slab `(lo, hi, (face at lo, face at hi))`; false when the line runs parallel to
/// the slab outside it.
fn clip_slab(
    o: f64,
    d: f64,
    (lo, hi, (face_lo, face_hi)): (f64, f64, (u32, u32)),
    (t0, f0): (&mut f64, &mut u32),
    (t1, f1): (&mut f64, &mut u32),
) -> bool {
    if d == 0.0 {
        return !(o < lo || o > hi);
    }
    let (mut ta, mut tb) = ((lo - o) / d, (hi - o) / d);
    let (mut fa, mut fb) = (face_lo, face_hi);
    if ta > tb {
        std::mem::swap(&mut ta, &mut tb);
        std::mem::swap(&mut fa, &mut fb);
    }
    if ta > *t0 {
        (*t0, *f0) = (ta, fa);
    }
    if tb < *t1 {
        (*t1, *f1) = (tb, fb);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_spans(shape: Shape, o: Vec3, d: Vec3) {
        let spans = shape.spans(o, d);
        for s in spans.iter() {
            for t in [s.t0, s.t1] {
                // (Far crossings of near-parallel planes move too little per 1e-3 of t to test.)
                if t.is_finite() && t.abs() < 20.0 {
                    assert!(
                        !shape.contains(o + d * (t - 1e-3)) || !shape.contains(o + d * (t + 1e-3)),
                        "{shape:?}: no boundary at {t}"
                    );
                }
            }
            let mid = 0.5 * (s.t0.max(-1e3) + s.t1.min(1e3));
            assert!(
                shape.contains(o + d * mid),
                "{shape:?}: mid {mid} not inside"
            );
        }
    }

    #[test]
    fn quartic_roots_of_a_product() {
        // (s-1)(s+2)(s-3)(s+2.5) has no cubic term: 1 - 2 + 3 - 2.5 = -0.5: shift it instead.
        let roots = [-3.1, -0.4, 1.2, 2.3];
        let shift = roots.iter().sum::<f64>() / 4.0;
        let r: Vec<f64> = roots.iter().map(|x| x - shift).collect();
        // Expand (s - r0)(s - r1)(s - r2)(s - r3) with zero cubic term.
        let e2 = r[0] * r[1] + r[0] * r[2] + r[0] * r[3] + r[1] * r[2] + r[1] * r[3] + r[2] * r[3];
        let e3 = r[0] * r[1] * r[2] + r[0] * r[1] * r[3] + r[0] * r[2] * r[3] + r[1] * r[2] * r[3];
        let e4 = r[0] * r[1] * r[2] * r[3];
        let mut out = [0.0; 4];
        let n = depressed_quartic(e2, -e3, e4, &mut out);
        assert_eq!(n, 4);
        let mut got = out.to_vec();
        got.sort_by(f64::total_cmp);
        for (g, w) in got.iter().zip(&r) {
            assert!((g - w).abs() < 1e-9, "{got:?} vs {r:?}");
        }
    }

    #[test]
    fn torus_along_its_axis_plane() {
        let torus = Shape::Torus {
            major: 2.0,
            minor: 0.5,
        };
        // Along x through the centre: crossings at -2.5, -1.5, 1.5, 2.5.
        let s = torus.spans(Vec3::new(-10.0, 0.0, 0.0), Vec3::X);
        assert_eq!(s.n, 2);
        let got: Vec<f32> = s.iter().flat_map(|s| [s.t0, s.t1]).collect();
        for (g, w) in got.iter().zip([7.5, 8.5, 11.5, 12.5]) {
            assert!((g - w).abs() < 1e-5, "{got:?}");
        }
        // Far away along a scaled direction: t scales back.
        let s = torus.spans(Vec3::new(-1000.0, 0.1, 0.0), Vec3::X * 4.0);
        let want = (1000.0 - 2.0 - 0.24f64.sqrt()) / 4.0;
        assert!((s.s[0].unwrap().t0 as f64 - want).abs() < 1e-4, "{s:?}");
    }

    #[test]
    fn every_shape_reports_true_boundaries() {
        let shapes = [
            Shape::Sphere {
                center: Vec3::new(0.1, 0.2, -0.3),
                radius: 1.1,
            },
            Shape::Box {
                min: Vec3::new(-1.0, -0.5, -0.7),
                max: Vec3::new(0.8, 0.9, 1.0),
            },
            Shape::Cylinder {
                radius: 0.8,
                height: 1.5,
            },
            Shape::Cone {
                radius: 0.9,
                height: 1.7,
            },
            Shape::Torus {
                major: 1.0,
                minor: 0.3,
            },
            Shape::HalfSpace {
                normal: Vec3::new(0.0, 0.6, 0.8),
                offset: 0.2,
            },
        ];
        let mut rng = 0x9e37_79b9u64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
        };
        for shape in shapes {
            let mut hits = 0;
            for _ in 0..2000 {
                let o = Vec3::new(next(), next(), next()) * 3.0;
                let target = Vec3::new(next(), next(), next()) * 0.8;
                let d = target - o;
                check_spans(shape, o, d);
                hits += shape.spans(o, d).n;
            }
            assert!(hits > 300, "{shape:?}: {hits}");
        }
    }

    #[test]
    fn projection_lands_on_the_surface() {
        let sphere = Shape::Sphere {
            center: Vec3::ZERO,
            radius: 2.0,
        };
        let p = sphere.project(0, Vec3::new(1.0, 1.0, 1.5));
        assert!((p.length() - 2.0).abs() < 1e-6);
        let torus = Shape::Torus {
            major: 2.0,
            minor: 0.5,
        };
        let q = torus.project(0, Vec3::new(2.3, 0.3, 0.1));
        let rho = Vec3::new(q.x, 0.0, q.z).length() - 2.0;
        assert!((rho * rho + q.y * q.y).sqrt() - 0.5 < 1e-6);
    }
}
