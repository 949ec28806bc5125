//! Inverse trigonometry without libm's calls: `acos` and `atan2` as short polynomials, for the
//! per-ray lookups of environment maps (libm's took 15% of a render of the sky alone).
//!
//! Error bounds (against f64, tested below): `acos` within 5e-7 rad over [-1, 1]; `atan2` within
//! 3e-7 rad: two ulps of pi, where libm's f32 results are within half of one. An environment
//! texel of a 4096-wide map spans 1.5e-3 rad.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// Arc cosine of `x` in [-1, 1] (clamped): Abramowitz & Stegun 4.4.46, acos |x| = sqrt(1 - |x|)
/// times a degree-7 polynomial (2e-8 in exact arithmetic), mirrored for negative x. The polynomial
/// by Estrin's scheme: pairs of terms side by side, three multiply-add levels deep rather than
/// Horner's seven (the lookup of a sky pixel waits on this chain).
#[inline]
// The coefficients as published (rounded to f32 by the compiler).
#[allow(clippy::excessive_precision)]
pub fn acos(x: f32) -> f32 {
    let a = x.abs().min(1.0);
    let a2 = a * a;
    let a4 = a2 * a2;
    let p01 = 1.570_796_305_0 - 0.214_598_801_6 * a;
    let p23 = 0.088_978_987_4 - 0.050_174_304_6 * a;
    let p45 = 0.030_891_881_0 - 0.017_088_125_6 * a;
    let p67 = 0.006_670_090_1 - 0.001_262_491_1 * a;
    let p = (p01 + a2 * p23) + a4 * (p45 + a2 * p67);
    let r = (1.0 - a).sqrt() * p;
    if x < 0.0 {
        PI - r
    } else {
        r
    }
}

/// The angle of (x, y) in [-pi, pi], as `f32::atan2` (0 at the origin): the ratio of the smaller
/// to the larger coordinate, its arc tangent by Cephes' `atanf` polynomial after reduction to
/// [-tan(pi/8), tan(pi/8)], then turned into the octant.
#[inline]
#[allow(clippy::excessive_precision)]
pub fn atan2(y: f32, x: f32) -> f32 {
    let (ax, ay) = (x.abs(), y.abs());
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    // The origin, infinities and NaNs as std has them (never for the unit directions looked up).
    if !(hi > 0.0 && hi < f32::INFINITY) || x.is_nan() || y.is_nan() {
        return y.atan2(x);
    }
    // tan(pi/8): above it, atan t = pi/4 + atan((t - 1) / (t + 1)), where t = lo / hi, so
    // (lo - hi) / (lo + hi): one division either way, chosen before it is made.
    let upper = lo > 0.414_213_57 * hi;
    let (base, z) = if upper {
        (FRAC_PI_4, (lo - hi) / (lo + hi))
    } else {
        (0.0, lo / hi)
    };
    let z2 = z * z;
    let z4 = z2 * z2;
    let poly = (1.997_771_1e-1 * z2 - 3.333_295e-1) + z4 * (8.053_744_5e-2 * z2 - 1.387_768_6e-1);
    let mut r = base + (poly * z2 * z + z);
    if ay > ax {
        r = FRAC_PI_2 - r;
    }
    if x < 0.0 {
        r = PI - r;
    }
    // The sign of y, zero's included, says which side of the cut: as f32::atan2.
    r.copysign(y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn acos_is_within_its_bound() {
        let n = 2_000_001;
        let mut worst = 0.0f64;
        for i in 0..n {
            let x = -1.0 + 2.0 * i as f32 / (n - 1) as f32;
            let err = (acos(x) as f64 - (x as f64).acos()).abs();
            worst = worst.max(err);
        }
        assert!(worst < 5e-7, "{worst}");
        assert_eq!(acos(1.0), 0.0);
        assert!((acos(-1.0) - PI).abs() < 3e-7);
        assert!((acos(0.0) - FRAC_PI_2).abs() < 3e-7);
        // Out of range clamps, as `x.clamp(-1, 1).acos()`.
        assert_eq!(acos(1.5), 0.0);
    }

    #[test]
    fn atan2_is_within_its_bound_all_round() {
        let n = 1_000_000;
        let mut worst = 0.0f64;
        for i in 0..n {
            let a = (i as f64 + 0.5) / n as f64 * std::f64::consts::TAU - std::f64::consts::PI;
            for r in [1e-20f32, 0.37, 1.0, 5e3] {
                let (y, x) = ((a.sin() as f32) * r, (a.cos() as f32) * r);
                let err = (atan2(y, x) as f64 - (y as f64).atan2(x as f64)).abs();
                worst = worst.max(err);
            }
        }
        assert!(worst < 3e-7, "{worst}");
    }

    #[test]
    fn atan2_keeps_the_special_cases_of_std() {
        for (y, x) in [
            (0.0f32, 0.0f32),
            (-0.0, 0.0),
            (0.0, -0.0),
            (-0.0, -0.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (-0.0, 1.0),
            (0.0, 1.0),
            (1.0, 0.0),
            (-1.0, 0.0),
            (1.0, 1.0),
            (f32::INFINITY, 1.0),
        ] {
            assert!((atan2(y, x) - y.atan2(x)).abs() < 3e-7, "atan2({y}, {x})");
            assert_eq!(
                atan2(y, x).is_sign_negative(),
                y.atan2(x).is_sign_negative()
            );
        }
        assert!(atan2(f32::NAN, 1.0).is_nan() && atan2(1.0, f32::NAN).is_nan());
        assert_eq!(
            atan2(f32::INFINITY, f32::INFINITY),
            f32::INFINITY.atan2(f32::INFINITY)
        );
    }
}
