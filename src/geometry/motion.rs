//! `Motion`: an instance's or camera's transforms sampled over the shutter, interpolated linearly.
//! Every backend and the camera read the same steps, so a moving object is where Embree puts it.

use glam::{Mat4, Vec3};

use super::Aabb;

/// Transforms at evenly spaced normalised shutter times (step `i` at `i / (len - 1)`), linearly
/// interpolated between steps: what Embree does with a geometry's time steps, so every backend moves
/// an instance the same way.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    pub steps: Vec<Mat4>,
}

/// Most time steps one moving instance or camera gets.
pub const MAX_STEPS: usize = 129;

impl Motion {
    /// The transform at normalised time `time` in [0, 1].
    #[inline]
    pub fn at(&self, time: f32) -> Mat4 {
        let last = self.steps.len() - 1;
        let x = time.clamp(0.0, 1.0) * last as f32;
        let k = (x as usize).min(last.saturating_sub(1));
        if last == 0 {
            return self.steps[0];
        }
        let f = x - k as f32;
        let (a, b) = (self.steps[k], self.steps[k + 1]);
        a * (1.0 - f) + b * f
    }

    /// Bounds of `object` over the whole shutter: the union over steps contains every linear
    /// interpolation of the step matrices, since each corner moves on straight segments.
    pub fn bounds(&self, object: &Aabb) -> Aabb {
        self.steps
            .iter()
            .fold(Aabb::EMPTY, |b, m| b.union(object.transformed(m)))
    }

    /// The motion of `object` (local bounds) placed by `f` (normalised time -> transform), sampled
    /// within `MOTION_TOLERANCE` of the object's size. None when nothing moves.
    pub fn of_object(f: impl Fn(f32) -> Mat4, object: &Aabb) -> Option<Motion> {
        let tol = MOTION_TOLERANCE * object.extent().length().max(1e-6);
        Self::sample(f, object, tol)
    }

    /// Samples `f` (normalised time -> transform) at as few evenly spaced steps as keep the linear
    /// interpolation within `tolerance` of the truth for the corners of `object`, checked halfway
    /// between steps (2, 3, 5, 9, ... steps). None when nothing moves.
    pub fn sample(f: impl Fn(f32) -> Mat4, object: &Aabb, tolerance: f32) -> Option<Motion> {
        let corners = |m: &Mat4| -> [Vec3; 8] {
            std::array::from_fn(|i| {
                m.transform_point3(Vec3::new(
                    if i & 1 == 0 {
                        object.min.x
                    } else {
                        object.max.x
                    },
                    if i & 2 == 0 {
                        object.min.y
                    } else {
                        object.max.y
                    },
                    if i & 4 == 0 {
                        object.min.z
                    } else {
                        object.max.z
                    },
                ))
            })
        };
        let dist = |a: &Mat4, b: &Mat4| {
            corners(a)
                .iter()
                .zip(corners(b))
                .map(|(p, q)| p.distance(q))
                .fold(0.0f32, f32::max)
        };
        let (m0, m1) = (f(0.0), f(1.0));
        let mid = f(0.5);
        if dist(&m0, &m1) <= tolerance && dist(&m0, &mid) <= tolerance {
            return None;
        }
        let mut n = 2usize;
        loop {
            let steps: Vec<Mat4> = (0..n).map(|i| f(i as f32 / (n - 1) as f32)).collect();
            let motion = Motion { steps };
            let worst = (0..n - 1)
                .map(|i| {
                    let t = (i as f32 + 0.5) / (n - 1) as f32;
                    dist(&motion.at(t), &f(t))
                })
                .fold(0.0f32, f32::max);
            if worst <= tolerance || n >= MAX_STEPS {
                return Some(motion);
            }
            n = 2 * n - 1;
        }
    }
}

/// Relative tolerance of motion sampling: a fraction of the object's bounding-box diagonal.
pub const MOTION_TOLERANCE: f32 = 1e-3;
