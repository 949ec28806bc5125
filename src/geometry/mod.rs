//! The bottom layer: small value types and the math every stage shares (rays, hits, boxes, frames,
//! motion, the watertight triangle test, hashing, colour transfer). It uses no other glint module.

use glam::Vec3;

pub mod colour;
pub(crate) mod f4;
pub mod frame;
pub mod hash;
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
}
