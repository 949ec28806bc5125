//! The bottom layer: small value types and the math every stage shares (rays, hits, boxes, frames,
//! motion, the watertight triangle test, hashing, colour transfer). It uses no other glint module.

use glam::Vec3;

pub mod colour;
pub(crate) mod f4;
pub mod frame;
pub mod hash;
pub mod inverse_trig;
pub(crate) mod lanes;
pub mod median;
pub mod motion;
pub mod triangle;

pub use frame::Frame;
pub use hash::mix64;
pub use motion::Motion;

/// gamma(n) of pbrt: a bound on the relative error of n floating-point operations (n ulps / 2, exact
/// to first order), for conservative tests such as slab distances.
pub const fn gamma(n: i32) -> f32 {
    let e = f32::EPSILON * 0.5 * n as f32;
    e / (1.0 - e)
}

/// The factor by which a slab test widens its far distances so that rounding never culls a box the
/// ray touches (Ize 2013: the three roundings of `(bound - o) * (1 / d)` in the near and far distance).
pub const SLAB_WIDEN: f32 = 1.0 + 2.0 * gamma(3);

/// Asks the cache for every line of `*x` (a hint for data read soon, to overlap its misses with
/// other work; nothing elsewhere than x86_64).
#[inline(always)]
pub fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        let p = (x as *const T).cast::<i8>();
        for line in (0..std::mem::size_of::<T>()).step_by(64) {
            // SAFETY: `p + line` lies inside `*x`, a valid reference; a prefetch reads nothing
            // into the program.
            unsafe {
                std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(p.add(line))
            };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}

/// A ray segment `o + t d` for `t` in `(t_min, t_max)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub o: Vec3,
    pub d: Vec3,
    pub t_min: f32,
    pub t_max: f32,
    /// Random bits drawn from the sampler for the stochastic decisions made during traversal
    /// (alpha blending), so that every backend makes the same ones for the same path.
    pub seed: u32,
    /// Normalised time within the shutter, in [0, 1] (0 for static scenes): where moving instances
    /// are when the ray is traced. Shadow and bounce rays inherit it from the camera ray.
    pub time: f32,
}

impl Ray {
    pub fn new(o: Vec3, d: Vec3) -> Self {
        Self {
            o,
            d,
            t_min: 0.0,
            t_max: f32::INFINITY,
            seed: 0,
            time: 0.0,
        }
    }

    pub fn segment(o: Vec3, d: Vec3, t_max: f32) -> Self {
        Self {
            o,
            d,
            t_min: 0.0,
            t_max,
            seed: 0,
            time: 0.0,
        }
    }

    pub fn with_seed(self, seed: u32) -> Self {
        Self { seed, ..self }
    }

    pub fn with_time(self, time: f32) -> Self {
        Self { time, ..self }
    }

    /// Whether the ray can be traced: a finite, non-zero direction and limits that are not NaN.
    #[inline]
    pub fn is_valid(&self) -> bool {
        self.d.is_finite() && self.d != Vec3::ZERO && !(self.t_min.is_nan() || self.t_max.is_nan())
    }

    pub fn at(&self, t: f32) -> Vec3 {
        self.o + self.d * t
    }
}

/// The closest intersection of a ray: which triangle of which instance, where along the ray, and the
/// barycentric coordinates `(u, v)` of the hit (weights of vertices 1 and 2).
///
/// A hit on a CSG object (`Scene::csg`) sets the top bit of `inst` (`CSG_BIT`); the other bits name
/// the object, `prim` is the surface id (`CsgObject::surface_id`: the leaf primitive in the low bits,
/// its face (or a mesh operand's triangle) above them, bit 31 set where the normal is flipped by a
/// difference), and `u = v = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub u: f32,
    pub v: f32,
    pub inst: u32,
    pub prim: u32,
}

/// Marks `Hit::inst` as a CSG object index.
pub const CSG_BIT: u32 = 1 << 31;

impl Hit {
    /// The CSG object and surface id, for a hit on a CSG object.
    pub fn csg(&self) -> Option<(u32, u32)> {
        (self.inst & CSG_BIT != 0).then_some((self.inst & !CSG_BIT, self.prim))
    }
}

/// An axis-aligned bounding box; the empty box has `min > max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Self {
        points.into_iter().fold(Self::EMPTY, |b, p| b.grow(p))
    }

    pub fn grow(self, p: Vec3) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    pub fn union(self, o: Aabb) -> Self {
        Self {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y && self.min.z <= self.max.z)
    }

    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    pub fn extent(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            self.max - self.min
        }
    }

    pub fn surface_area(&self) -> f32 {
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// The part `(t0, t1)` of the parameter range `[t_min, t_max]` of the ray `o + t d` (given as `o` and
    /// `inv = 1 / d`) that lies in the box, or None where the ray misses it: the one scalar slab test.
    ///
    /// Conservative (Ize 2013): distances away from zero are widened by `SLAB_WIDEN` (for `t >= 0`
    /// the far one, for the negative distances of a whole line the near one), so rounding never culls
    /// a box the ray touches. A NaN distance (`0 * inf`: a ray in a face plane, parallel to it) leaves
    /// the range as it was, so such a ray is kept; a ray parallel to an axis outside the slab is not.
    #[inline(always)]
    pub fn clip(&self, o: Vec3, inv: Vec3, t_min: f32, t_max: f32) -> Option<(f32, f32)> {
        let (mut t0, mut t1) = (t_min, t_max);
        for a in 0..3 {
            let (lo, hi) = ((self.min[a] - o[a]) * inv[a], (self.max[a] - o[a]) * inv[a]);
            let (near, far) = if inv[a] < 0.0 { (hi, lo) } else { (lo, hi) };
            let near = if near < 0.0 { near * SLAB_WIDEN } else { near };
            let far = if far > 0.0 { far * SLAB_WIDEN } else { far };
            t0 = if near > t0 { near } else { t0 };
            t1 = if far < t1 { far } else { t1 };
        }
        (t0 <= t1).then_some((t0, t1))
    }

    /// The box that contains this one after an affine transform (all eight corners).
    pub fn transformed(&self, m: &glam::Mat4) -> Self {
        if self.is_empty() {
            return *self;
        }
        let mut out = Self::EMPTY;
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            );
            out = out.grow(m.transform_point3(c));
        }
        out
    }

    /// This box grown by a few ulps of its largest coordinate, so that a surface whose corners were
    /// rounded when transformed (as in `transformed`) never falls outside it by that rounding.
    pub fn padded(self) -> Self {
        if self.is_empty() {
            return self;
        }
        let pad = Vec3::splat(self.min.abs().max(self.max.abs()).max_element() * gamma(4));
        Self {
            min: self.min - pad,
            max: self.max + pad,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slab_test_keeps_rays_along_a_face_and_clips_segments() {
        let b = Aabb {
            min: Vec3::ZERO,
            max: Vec3::ONE,
        };
        let clip = |o: Vec3, d: Vec3, t_max: f32| b.clip(o, d.recip(), 0.0, t_max);
        // Parallel to x and z, exactly on the y = 0 face: inside the slab, so kept.
        let (t0, t1) = clip(Vec3::new(-1.0, 0.0, 0.5), Vec3::X, f32::INFINITY).unwrap();
        assert!(t0 <= 1.0 && t1 >= 2.0, "{t0} {t1}");
        assert!(clip(Vec3::new(-1.0, -0.01, 0.5), Vec3::X, f32::INFINITY).is_none());
        assert!(clip(Vec3::new(-1.0, -0.01, 0.5), -Vec3::X, f32::INFINITY).is_none());
        assert!(clip(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 0.5).is_none());
        assert!(clip(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 1.5).is_some());
        assert!(clip(Vec3::new(2.0, 0.5, 0.5), Vec3::X, f32::INFINITY).is_none());
        // A whole line finds the box behind its origin too.
        let behind = b.clip(
            Vec3::splat(3.0),
            Vec3::ONE.recip(),
            f32::NEG_INFINITY,
            f32::INFINITY,
        );
        let (t0, t1) = behind.unwrap();
        assert!(t0 <= -3.0 && t1 >= -2.0, "{t0} {t1}");
        // Rounding never culls a box whose face the ray just touches at a far distance.
        let far = Aabb {
            min: Vec3::new(1e4, 0.0, 0.0),
            max: Vec3::new(1e4, 1.0, 1.0),
        };
        let o = Vec3::new(0.1, 0.3, 0.7);
        let d = far.min + Vec3::new(0.0, 0.5, 0.25) - o;
        assert!(far.clip(o, d.recip(), 0.0, f32::INFINITY).is_some());
    }
}
