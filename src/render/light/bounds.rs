//! Bounds on what a group of lights can send a shading point (Conty Estevez & Kulla 2018, as in
//! pbrt-v4's `LightBounds`): a box, a cone of emitting normals with its spread, and the total power.
//!
//! `importance` is an upper bound (up to the power's scale) on the light the group sends to a point
//! with a given normal; it is zero only where no light of the group can reach, so a choice made in
//! proportion to it stays unbiased.

use std::f32::consts::PI;

use glam::Vec3;

use crate::geometry::f4::F4;
use crate::geometry::lanes::Lanes;
#[cfg(target_arch = "x86_64")]
use crate::geometry::lanes::{F8, M8};
use crate::geometry::Aabb;

/// A cone of directions about unit `w`: every direction within angle acos(`cos_theta`) of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Cone {
    pub w: Vec3,
    pub cos_theta: f32,
}

impl Cone {
    pub const SPHERE: Cone = Cone {
        w: Vec3::Z,
        cos_theta: -1.0,
    };

    /// The smallest cone (about the great circle through both axes) that holds `a` and `b`.
    fn union(a: Cone, b: Cone) -> Cone {
        let (theta_a, theta_b) = (safe_acos(a.cos_theta), safe_acos(b.cos_theta));
        let theta_d = angle_between(a.w, b.w);
        if (theta_d + theta_b).min(PI) <= theta_a {
            return a;
        }
        if (theta_d + theta_a).min(PI) <= theta_b {
            return b;
        }
        let theta_o = (theta_a + theta_d + theta_b) / 2.0;
        if theta_o >= PI {
            return Cone::SPHERE;
        }
        // Turn a's axis towards b's by theta_o - theta_a, in the plane of the two.
        let axis = a.w.cross(b.w);
        if axis.length_squared() == 0.0 {
            return Cone::SPHERE;
        }
        let w = glam::Quat::from_axis_angle(axis.normalize(), theta_o - theta_a) * a.w;
        Cone {
            w: w.normalize(),
            cos_theta: theta_o.cos(),
        }
    }
}

/// What bounds the emission of a group of lights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct LightBounds {
    pub bounds: Aabb,
    /// The group's power (the light set's weights).
    pub phi: f32,
    /// The cone holding every emitting normal (`theta_o`).
    pub normals: Cone,
    /// How far past its normal each light still emits: cos(theta_e) (0 for area lights, a
    /// hemisphere about each normal).
    pub cos_theta_e: f32,
    /// Whether lights emit on both sides of their normals (emissive triangles).
    pub two_sided: bool,
}

impl LightBounds {
    /// Flat lights over `points`, emitting into the hemisphere about unit `normal` (and the
    /// opposite one when `two_sided`).
    pub fn planar(points: &[Vec3], normal: Vec3, phi: f32, two_sided: bool) -> LightBounds {
        LightBounds {
            bounds: Aabb::from_points(points.iter().copied()),
            phi,
            normals: Cone {
                w: normal,
                cos_theta: 1.0,
            },
            cos_theta_e: (PI / 2.0).cos(),
            two_sided,
        }
    }

    /// Lights in `bounds` that may emit in every direction (points, spheres).
    pub fn omni(bounds: Aabb, phi: f32) -> LightBounds {
        LightBounds {
            bounds,
            phi,
            normals: Cone::SPHERE,
            cos_theta_e: (PI / 2.0).cos(),
            two_sided: false,
        }
    }

    pub fn union(a: &LightBounds, b: &LightBounds) -> LightBounds {
        if a.phi == 0.0 {
            return *b;
        }
        if b.phi == 0.0 {
            return *a;
        }
        LightBounds {
            bounds: a.bounds.union(b.bounds),
            phi: a.phi + b.phi,
            normals: Cone::union(a.normals, b.normals),
            cos_theta_e: a.cos_theta_e.min(b.cos_theta_e),
            two_sided: a.two_sided || b.two_sided,
        }
    }

    pub fn centroid(&self) -> Vec3 {
        self.bounds.center()
    }

    /// The bound on the light the group sends to `p`, on a surface of unit normal `n` (zero: no
    /// surface, so no cosine there), relative to other groups' bounds.
    #[cfg(test)]
    pub fn importance(&self, p: Vec3, n: Vec3) -> f32 {
        self.packed().importance(p, n)
    }

    /// The bounds in the form `importance` reads fastest.
    pub fn packed(&self) -> PackedBounds {
        let half = self.bounds.extent() * 0.5;
        let cos_o = self.normals.cos_theta;
        PackedBounds {
            centre: self.bounds.center(),
            radius: half.length(),
            w: self.normals.w,
            phi: self.phi,
            cos_o,
            sin_o: safe_sqrt(1.0 - cos_o * cos_o),
            cos_e: self.cos_theta_e,
            two_sided: self.two_sided,
        }
    }

    /// The surface-area-orientation heuristic's cost of a group (Conty Estevez & Kulla, pbrt-v4's
    /// `EvaluateCost`): power times the solid angle its emission can fill times the box's area,
    /// `regularity` penalising thin boxes split across their long side.
    pub fn cost(&self, regularity: f32) -> f32 {
        let theta_o = safe_acos(self.normals.cos_theta);
        let theta_e = safe_acos(self.cos_theta_e);
        let theta_w = (theta_o + theta_e).min(PI);
        let sin_o = safe_sqrt(1.0 - self.normals.cos_theta * self.normals.cos_theta);
        let m_omega = 2.0 * PI * (1.0 - self.normals.cos_theta)
            + PI / 2.0
                * (2.0 * theta_w * sin_o - (theta_o - 2.0 * theta_w).cos() - 2.0 * theta_o * sin_o
                    + self.normals.cos_theta);
        self.phi * m_omega * regularity * self.bounds.surface_area()
    }
}

/// `LightBounds` reduced to what `importance` needs, with its square roots taken once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct PackedBounds {
    centre: Vec3,
    /// Of the box's bounding sphere: half its diagonal.
    radius: f32,
    w: Vec3,
    phi: f32,
    cos_o: f32,
    sin_o: f32,
    cos_e: f32,
    two_sided: bool,
}

impl PackedBounds {
    /// `LightBounds::importance`. The angles bound from the box's bounding sphere: theta_b, half
    /// the angle it subtends from `p`, widens both the emitter cone and the receiver's cosine, so
    /// the bound holds for every point of the box. The scalar form of `Bounds4::importance`, which
    /// the tree uses; kept as the readable reference the vector form is tested against.
    #[cfg(test)]
    pub fn importance(&self, p: Vec3, n: Vec3) -> f32 {
        let to = p - self.centre;
        let d2 = to.length_squared();
        let inv_d = if d2 > 0.0 { d2.sqrt().recip() } else { 0.0 };
        // Each cosine is a dot product with `to` over its length, and its sine sqrt(d^2 - dot^2)
        // over the same length: the sines' square roots need not wait for `inv_d`'s.
        let mut w_to = self.w.dot(to);
        if self.two_sided {
            w_to = w_to.abs();
        }
        let cos_w = w_to * inv_d;
        let sin_w = safe_sqrt(d2 - w_to * w_to) * inv_d;
        // From inside the bounding sphere every direction may hold light.
        let (sin_b, cos_b) = if d2 < self.radius * self.radius {
            (0.0, -1.0)
        } else {
            let r2 = self.radius * self.radius;
            ((self.radius * inv_d).min(1.0), safe_sqrt(d2 - r2) * inv_d)
        };
        // theta' = max(0, theta_w - theta_o - theta_b): the least angle between an emitting normal
        // and the direction to p.
        let cos_x = cos_sub_clamped(sin_w, cos_w, self.sin_o, self.cos_o);
        let sin_x = sin_sub_clamped(sin_w, cos_w, self.sin_o, self.cos_o);
        let cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
        // pbrt-v4's clamp of the distance, so that points inside the box do not blow up: half the
        // diagonal, a length set against a squared distance as pbrt-v4 has it.
        let mut importance = self.phi / d2.max(self.radius) * cos_p;
        if n != Vec3::ZERO {
            let n_to = to.dot(n).abs();
            let cos_i = n_to * inv_d;
            let sin_i = safe_sqrt(d2 - n_to * n_to) * inv_d;
            importance *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
        }
        // Selects rather than an early return: whether a bound is zero is hard to predict.
        if cos_p <= self.cos_e {
            0.0
        } else {
            importance.max(0.0)
        }
    }
}

/// `PackedBounds` lane by lane, for a wide node's children: `importance` evaluates all lanes at
/// once with the same formula (an empty lane has no power and a zero importance everywhere).
#[derive(Clone, Copy)]
pub(super) struct BoundsLanes<L: Lanes> {
    centre: [L; 3],
    radius: L,
    w: [L; 3],
    phi: L,
    cos_o: L,
    sin_o: L,
    cos_e: L,
    two_sided: L::Mask,
}

/// Four children's bounds, as wide nodes store them.
pub(super) type Bounds4 = BoundsLanes<F4>;

impl Bounds4 {
    /// Up to four bounds; lanes past the last are empty.
    pub fn new(lanes: &[PackedBounds]) -> Self {
        assert!(lanes.len() <= 4, "a wide node has at most four children");
        // An empty lane: no power, and an emission cone no direction is inside (cos_e above 1).
        let empty = PackedBounds {
            centre: Vec3::ZERO,
            radius: 0.0,
            w: Vec3::Z,
            phi: 0.0,
            cos_o: 1.0,
            sin_o: 0.0,
            cos_e: 2.0,
            two_sided: false,
        };
        let lane = |l: usize| lanes.get(l).unwrap_or(&empty);
        let f = |g: &dyn Fn(&PackedBounds) -> f32| F4::load(&std::array::from_fn(|l| g(lane(l))));
        let two: [f32; 4] = std::array::from_fn(|l| if lane(l).two_sided { 1.0 } else { 0.0 });
        Self {
            centre: [f(&|b| b.centre.x), f(&|b| b.centre.y), f(&|b| b.centre.z)],
            radius: f(&|b| b.radius),
            w: [f(&|b| b.w.x), f(&|b| b.w.y), f(&|b| b.w.z)],
            phi: f(&|b| b.phi),
            cos_o: f(&|b| b.cos_o),
            sin_o: f(&|b| b.sin_o),
            cos_e: f(&|b| b.cos_e),
            two_sided: F4::load(&two).gt(F4::splat(0.5)),
        }
    }
}

/// Eight children's bounds in AVX registers, from the two halves a wide node stores.
#[cfg(target_arch = "x86_64")]
impl BoundsLanes<F8> {
    #[inline(always)]
    pub fn halves(lo: &Bounds4, hi: &Bounds4) -> Self {
        let j = |a: F4, b: F4| F8::halves(a, b);
        Self {
            centre: std::array::from_fn(|k| j(lo.centre[k], hi.centre[k])),
            radius: j(lo.radius, hi.radius),
            w: std::array::from_fn(|k| j(lo.w[k], hi.w[k])),
            phi: j(lo.phi, hi.phi),
            cos_o: j(lo.cos_o, hi.cos_o),
            sin_o: j(lo.sin_o, hi.sin_o),
            cos_e: j(lo.cos_e, hi.cos_e),
            two_sided: M8::halves(lo.two_sided, hi.two_sided),
        }
    }
}

impl<L: Lanes> BoundsLanes<L> {
    /// `PackedBounds::importance` of the lanes, step for step (the same IEEE operations, so a lane
    /// equals the scalar bound but for the order of a dot product's sums, at either width).
    #[inline(always)]
    pub fn importance(&self, p: Vec3, n: Vec3) -> L {
        // Helpers are functions, not closures: a closure that LLVM leaves out of line is not
        // compiled for AVX, and the AVX instructions inside become calls.
        #[inline(always)]
        fn safe_sqrt<L: Lanes>(x: L) -> L {
            x.max(L::splat(0.0)).sqrt()
        }
        #[inline(always)]
        fn cos_sub<L: Lanes>(sin_a: L, cos_a: L, sin_b: L, cos_b: L) -> L {
            L::select(
                cos_a.gt(cos_b),
                L::splat(1.0),
                cos_a * cos_b + sin_a * sin_b,
            )
        }
        #[inline(always)]
        fn sin_sub<L: Lanes>(sin_a: L, cos_a: L, sin_b: L, cos_b: L) -> L {
            L::select(
                cos_a.gt(cos_b),
                L::splat(0.0),
                sin_a * cos_b - cos_a * sin_b,
            )
        }
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        let to = [
            L::splat(p.x) - self.centre[0],
            L::splat(p.y) - self.centre[1],
            L::splat(p.z) - self.centre[2],
        ];
        let d2 = to[0] * to[0] + to[1] * to[1] + to[2] * to[2];
        let inv_d = L::select(d2.gt(zero), one / d2.sqrt(), zero);
        let w_to = self.w[0] * to[0] + self.w[1] * to[1] + self.w[2] * to[2];
        let w_to = L::select(self.two_sided, w_to.abs(), w_to);
        let cos_w = w_to * inv_d;
        let sin_w = safe_sqrt(d2 - w_to * w_to) * inv_d;
        let r2 = self.radius * self.radius;
        let inside = d2.lt(r2);
        let sin_b = L::select(inside, zero, (self.radius * inv_d).min(one));
        let cos_b = L::select(inside, L::splat(-1.0), safe_sqrt(d2 - r2) * inv_d);
        let cos_x = cos_sub(sin_w, cos_w, self.sin_o, self.cos_o);
        let sin_x = sin_sub(sin_w, cos_w, self.sin_o, self.cos_o);
        let cos_p = cos_sub(sin_x, cos_x, sin_b, cos_b);
        let mut importance = self.phi / d2.max(self.radius) * cos_p;
        if n != Vec3::ZERO {
            let n_to =
                (to[0] * L::splat(n.x) + to[1] * L::splat(n.y) + to[2] * L::splat(n.z)).abs();
            let cos_i = n_to * inv_d;
            let sin_i = safe_sqrt(d2 - n_to * n_to) * inv_d;
            importance = importance * cos_sub(sin_i, cos_i, sin_b, cos_b);
        }
        // `max` keeps 0 where the bound is NaN; `gt` is false there too.
        L::select(cos_p.gt(self.cos_e), importance.max(zero), zero)
    }
}

fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

fn safe_acos(x: f32) -> f32 {
    x.clamp(-1.0, 1.0).acos()
}

/// The angle between unit vectors, accurate near 0 and pi (pbrt's `AngleBetween`).
fn angle_between(a: Vec3, b: Vec3) -> f32 {
    if a.dot(b) < 0.0 {
        PI - 2.0 * safe_asin((a + b).length() / 2.0)
    } else {
        2.0 * safe_asin((b - a).length() / 2.0)
    }
}

fn safe_asin(x: f32) -> f32 {
    x.clamp(-1.0, 1.0).asin()
}

/// cos(max(0, a - b)) from the sines and cosines of a and b in [0, pi].
#[cfg(test)]
fn cos_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        return 1.0;
    }
    cos_a * cos_b + sin_a * sin_b
}

/// sin(max(0, a - b)) from the sines and cosines of a and b in [0, pi].
#[cfg(test)]
fn sin_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        return 0.0;
    }
    sin_a * cos_b - cos_a * sin_b
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit(k: u64) -> f32 {
        (crate::geometry::mix64(k) >> 40) as f32 / (1u64 << 24) as f32
    }

    fn direction(k: u64) -> Vec3 {
        let (z, phi) = (1.0 - 2.0 * unit(2 * k), 2.0 * PI * unit(2 * k + 1));
        let r = safe_sqrt(1.0 - z * z);
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    #[test]
    fn cone_union_holds_both_cones() {
        for k in 0..2000u64 {
            let a = Cone {
                w: direction(3 * k),
                cos_theta: 1.0 - 2.0 * unit(7 * k + 1) * unit(7 * k + 2),
            };
            let b = Cone {
                w: direction(3 * k + 1),
                cos_theta: 1.0 - 2.0 * unit(7 * k + 3) * unit(7 * k + 4),
            };
            let u = Cone::union(a, b);
            // Every direction on the rim of either cone is inside the union.
            for c in [a, b] {
                let (t, s) = c.w.any_orthonormal_pair();
                let sin = safe_sqrt(1.0 - c.cos_theta * c.cos_theta);
                for j in 0..16 {
                    let phi = j as f32 * PI / 8.0;
                    let d = c.w * c.cos_theta + (t * phi.cos() + s * phi.sin()) * sin;
                    assert!(
                        u.w.dot(d) >= u.cos_theta - 1e-4,
                        "{a:?} + {b:?} = {u:?} misses {d}"
                    );
                }
            }
        }
    }

    /// A one-sided square light of side 0.2 at `c` facing `n`.
    fn square(c: Vec3, n: Vec3) -> LightBounds {
        let (t, s) = n.any_orthonormal_pair();
        let corners = [t + s, t - s, -t + s, -t - s].map(|v| c + v * 0.1);
        LightBounds {
            bounds: Aabb::from_points(corners),
            phi: 1.0,
            normals: Cone {
                w: n,
                cos_theta: 1.0,
            },
            cos_theta_e: 0.0,
            two_sided: false,
        }
    }

    #[test]
    fn importance_is_zero_only_behind_lights_and_receivers() {
        let b = square(Vec3::ZERO, Vec3::Y);
        // In front, at any angle up to grazing, and for receivers turned away (the bound has to
        // allow for the light's extent).
        assert!(b.importance(Vec3::new(0.0, 1.0, 0.0), -Vec3::Y) > 0.0);
        assert!(b.importance(Vec3::new(3.0, 0.05, 0.0), Vec3::ZERO) > 0.0);
        // Behind the light, and a receiver whose normal is perpendicular to all of the light.
        assert_eq!(b.importance(Vec3::new(0.0, -1.0, 0.0), Vec3::ZERO), 0.0);
        assert_eq!(b.importance(Vec3::new(0.0, -1.0, 0.0), Vec3::Y), 0.0);
        // A receiver's plane through a point light (the square's extent reaches either side).
        let point = LightBounds::omni(Aabb::from_points([Vec3::ZERO]), 1.0);
        assert_eq!(point.importance(Vec3::new(0.0, 5.0, 0.0), Vec3::X), 0.0);
        assert!(b.importance(Vec3::new(0.0, 5.0, 0.0), Vec3::X) > 0.0);
        // Two-sided, behind is lit too; and nearer is more important.
        let two = LightBounds {
            two_sided: true,
            ..b
        };
        assert!(two.importance(Vec3::new(0.0, -1.0, 0.0), Vec3::ZERO) > 0.0);
        assert!(b.importance(Vec3::Y, Vec3::ZERO) > b.importance(Vec3::Y * 2.0, Vec3::ZERO));
    }

    #[test]
    fn a_union_is_at_least_as_important_as_each_part() {
        for k in 0..500u64 {
            let a = square(direction(4 * k) * 2.0, direction(4 * k + 1));
            let b = square(direction(4 * k + 2) * 2.0, direction(4 * k + 3));
            let u = LightBounds::union(&a, &b);
            let p = direction(4 * k + 5) * 6.0 * unit(9 * k + 7);
            let n = direction(4 * k + 6);
            // The union's bound holds for each part, scaled to the union's power: it is a bound
            // wherever a part's light can reach (the parts' boxes are inside the union's).
            for part in [a, b] {
                if part.importance(p, n) > 0.0 {
                    assert!(u.importance(p, n) > 0.0, "{k}: {part:?} lit, {u:?} not");
                }
            }
        }
    }

    #[test]
    fn wide_importance_is_the_scalar_one_lane_by_lane() {
        let mut worst = 0.0f32;
        for k in 0..3000u64 {
            let lanes: Vec<PackedBounds> = (0..(1 + k % 4))
                .map(|j| {
                    let c = direction(9 * k + j) * (0.5 + 2.0 * unit(5 * k + j));
                    let mut b = square(c, direction(11 * k + j));
                    b.two_sided = (k + j) % 3 == 0;
                    b.cos_theta_e = 1.0 - unit(13 * k + j);
                    b.normals.cos_theta = 1.0 - 2.0 * unit(17 * k + j);
                    b.phi = 0.1 + unit(19 * k + j);
                    b.packed()
                })
                .collect();
            // Points near, inside and far from the bounds; receivers with and without a normal.
            let p = direction(23 * k) * (0.05 + 3.0 * unit(29 * k));
            let n = if k % 2 == 0 {
                Vec3::ZERO
            } else {
                direction(31 * k)
            };
            let four = Bounds4::new(&lanes);
            let wide = four.importance(p, n).to_array();
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx") {
                // Eight lanes (these and the same reversed, as a wide node's two halves) give the
                // same bits as the two four-lane evaluations.
                #[target_feature(enable = "avx")]
                fn eight(lo: &Bounds4, hi: &Bounds4, p: Vec3, n: Vec3) -> [f32; 8] {
                    BoundsLanes::halves(lo, hi).importance(p, n).to_array()
                }
                let reversed: Vec<PackedBounds> = lanes.iter().rev().copied().collect();
                let other = Bounds4::new(&reversed);
                // SAFETY: the CPU has AVX (checked above).
                let both = unsafe { eight(&four, &other, p, n) };
                let halves = [wide, other.importance(p, n).to_array()].concat();
                assert_eq!(
                    both.map(f32::to_bits)[..],
                    halves.iter().map(|x| x.to_bits()).collect::<Vec<_>>()[..]
                );
            }
            for (l, b) in lanes.iter().enumerate() {
                let scalar = b.importance(p, n);
                let err = (wide[l] - scalar).abs() / scalar.abs().max(1e-6);
                // Only the dot products' sums are ordered differently.
                assert!(err < 1e-4, "lane {l}: {} vs {scalar}", wide[l]);
                assert_eq!(
                    wide[l] > 0.0,
                    scalar > 0.0,
                    "lane {l}: {} vs {scalar}",
                    wide[l]
                );
                worst = worst.max(err);
            }
            for &w in &wide[lanes.len()..] {
                assert_eq!(w, 0.0, "an empty lane");
            }
        }
        assert!(worst < 1e-4, "{worst}");
    }
}
