//! The feature images (AOVs) of a render, accumulated per pixel from the same samples and filter
//! weights as the beauty: albedo, normal, depth, position, instance and material ids, variance.

use glam::{DVec3, DVec4, Vec2, Vec3};

use super::features::PathFeatures;
use crate::film::aov::{FeatureImages, NO_ID};

/// Where depth is measured from: the camera's position and viewing axis (depth is the distance along
/// the axis, so a plane facing the camera has one depth; EXR's `Z` convention).
#[derive(Clone, Copy, Debug)]
pub struct DepthAxis {
    pub eye: Vec3,
    pub forward: Vec3,
}

/// One pixel's running sums.
#[derive(Clone, Copy, Debug)]
pub struct FeatureAcc {
    w: f64,
    /// Sum of squared weights (the effective sample count is w^2 / w2).
    w2: f64,
    /// Sums of w L and w L^2 of the beauty's samples (per channel).
    l: DVec3,
    l2: DVec3,
    albedo: DVec3,
    normal: DVec3,
    /// Weight, depth and position of the samples whose camera ray hit something.
    hit_w: f64,
    z: f64,
    p: DVec3,
    /// Ids of the sample nearest the pixel centre (ids do not average), with its squared distance.
    nearest: f32,
    instance: u32,
    material: u32,
}

impl Default for FeatureAcc {
    fn default() -> Self {
        Self {
            w: 0.0,
            w2: 0.0,
            l: DVec3::ZERO,
            l2: DVec3::ZERO,
            albedo: DVec3::ZERO,
            normal: DVec3::ZERO,
            hit_w: 0.0,
            z: 0.0,
            p: DVec3::ZERO,
            nearest: f32::INFINITY,
            instance: NO_ID,
            material: NO_ID,
        }
    }
}

impl FeatureAcc {
    /// Adds one sample: its features, the radiance the beauty took (`l`, already made finite), its
    /// filter weight and its offset from the pixel centre.
    pub fn add(&mut self, f: &PathFeatures, l: DVec4, w: f64, offset: Vec2, axis: &DepthAxis) {
        let l = l.truncate();
        self.w += w;
        self.w2 += w * w;
        self.l += l * w;
        self.l2 += l * l * w;
        self.albedo += f.albedo.as_dvec3() * w;
        self.normal += f.normal.as_dvec3() * w;
        let Some(hit) = f.first else {
            return;
        };
        self.hit_w += w;
        self.z += (hit.p - axis.eye).dot(axis.forward) as f64 * w;
        self.p += hit.p.as_dvec3() * w;
        let d = offset.length_squared();
        if d < self.nearest {
            (self.nearest, self.instance, self.material) = (d, hit.instance, hit.material);
        }
    }

    fn mean(&self, sum: DVec3, w: f64) -> Vec3 {
        if w != 0.0 {
            (sum / w).as_vec3()
        } else {
            Vec3::ZERO
        }
    }

    /// Variance of the pixel's weighted mean, per channel: the samples' weighted variance times
    /// sum(w^2) / sum(w)^2, corrected as Bessel's is (exact for equal weights: s^2 / n).
    fn variance(&self) -> Vec3 {
        let k = if self.w != 0.0 {
            self.w2 / (self.w * self.w)
        } else {
            1.0
        };
        if k >= 1.0 {
            return Vec3::ZERO;
        }
        let mean = self.l / self.w;
        let spread = (self.l2 / self.w - mean * mean).max(DVec3::ZERO);
        (spread * (k / (1.0 - k))).as_vec3()
    }
}

/// The feature images from per-pixel sums (row-major), of pixels that took at least `min_spp`
/// samples each.
pub fn images(width: usize, height: usize, acc: &[FeatureAcc], min_spp: u32) -> FeatureImages {
    let map = |f: &dyn Fn(&FeatureAcc) -> Vec3| acc.iter().map(f).collect::<Vec<_>>();
    FeatureImages {
        width,
        height,
        albedo: map(&|a| a.mean(a.albedo, a.w)),
        normal: map(&|a| a.mean(a.normal, a.w).normalize_or_zero()),
        depth: acc
            .iter()
            .map(|a| match a.hit_w {
                0.0 => f32::INFINITY,
                w => (a.z / w) as f32,
            })
            .collect(),
        position: map(&|a| a.mean(a.p, a.hit_w)),
        instance: acc.iter().map(|a| a.instance).collect(),
        material: acc.iter().map(|a| a.material).collect(),
        variance: map(&|a| a.variance()),
        min_spp,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variance_of_equal_weights_is_the_sample_variance_over_n() {
        let mut a = FeatureAcc::default();
        let axis = DepthAxis {
            eye: Vec3::ZERO,
            forward: Vec3::NEG_Z,
        };
        let f = PathFeatures::default();
        for v in [1.0, 2.0, 3.0, 6.0] {
            a.add(&f, DVec4::splat(v), 1.0, Vec2::ZERO, &axis);
        }
        // Mean 3, sample variance (4 + 1 + 0 + 9) / 3, over n = 4.
        let want = (14.0 / 3.0 / 4.0) as f32;
        assert!((a.variance() - Vec3::splat(want)).abs().max_element() < 1e-6);
        let one = images(1, 1, &[a], 4);
        assert_eq!(one.depth, [f32::INFINITY]);
        assert_eq!(one.instance, [NO_ID]);
        assert_eq!(one.normal, [Vec3::ZERO]);
    }
}
