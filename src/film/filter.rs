//! Pixel reconstruction filters, used by importance sampling (as pbrt-v4 does): each camera sample
//! is offset from the pixel centre with the filter's own distribution and carries the weight
//! f / pdf, so it stays in its pixel and a pixel is sum(w L) / sum(w). Tiles need no apron and
//! the same seed gives the same image whatever the thread count.

use glam::Vec2;

/// The filters, all separable: f(x, y) = f1(x) f1(y).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum FilterKind {
    /// Constant over the pixel (radius 0.5 by default).
    Box,
    /// Triangle (tent), radius 1.
    Tent,
    /// Gaussian with sigma = radius / 3, shifted to reach zero at the radius (1.5).
    #[default]
    Gaussian,
    /// Mitchell-Netravali with B = C = 1/3 (negative lobes), radius 2.
    Mitchell,
}

impl FilterKind {
    pub fn default_radius(self) -> f32 {
        match self {
            FilterKind::Box => 0.5,
            FilterKind::Tent => 1.0,
            FilterKind::Gaussian => 1.5,
            FilterKind::Mitchell => 2.0,
        }
    }
}

impl std::fmt::Display for FilterKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FilterKind::Box => "box",
            FilterKind::Tent => "tent",
            FilterKind::Gaussian => "gaussian",
            FilterKind::Mitchell => "mitchell",
        })
    }
}

/// Bins of the tabulated 1D distribution of |f1| that samples are drawn from.
const BINS: usize = 512;
/// The widest filter accepted, in pixels: already a blur ten times the widest default (Mitchell's
/// 2), and far below where the offsets of the camera rays lose their precision (a radius of 1e30
/// gave a black image).
pub const MAX_RADIUS: f32 = 16.0;

#[derive(Clone, Debug)]
pub struct Filter {
    pub kind: FilterKind,
    pub radius: f32,
    /// 1 / integral of the unnormalised f1 over [-r, r].
    norm: f32,
    /// Cumulative distribution of |f1| over BINS equal bins of [-r, r]; cdf[0] = 0, cdf[BINS] = 1.
    cdf: Vec<f64>,
}

impl Filter {
    pub fn new(kind: FilterKind, radius: Option<f32>) -> Self {
        let radius = radius
            .filter(|r| r.is_finite() && *r > 0.0)
            .unwrap_or(kind.default_radius());
        let mut f = Self {
            kind,
            radius,
            norm: 1.0,
            cdf: Vec::new(),
        };
        // Normalise f1 numerically (Simpson's rule; exact for box and tent up to rounding).
        let n = 4096;
        let h = 2.0 * radius as f64 / n as f64;
        let mut s = 0.0f64;
        for i in 0..=n {
            let x = -radius as f64 + i as f64 * h;
            let w = if i == 0 || i == n {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            };
            s += w * f.raw1(x as f32) as f64;
        }
        f.norm = (1.0 / (s * h / 3.0)) as f32;
        // Tabulate |f1| per bin (averaged over sub-points) for sampling.
        let bw = 2.0 * radius / BINS as f32;
        let mut cdf = vec![0.0f64; BINS + 1];
        for b in 0..BINS {
            let mut a = 0.0f64;
            for k in 0..8 {
                let x = -radius + (b as f32 + (k as f32 + 0.5) / 8.0) * bw;
                a += f.raw1(x).abs() as f64;
            }
            cdf[b + 1] = cdf[b] + a;
        }
        let total = cdf[BINS];
        f.cdf = cdf.iter().map(|c| c / total).collect();
        f
    }

    /// The unnormalised 1D profile.
    fn raw1(&self, x: f32) -> f32 {
        let r = self.radius;
        let ax = x.abs();
        if ax > r {
            return 0.0;
        }
        match self.kind {
            FilterKind::Box => 1.0,
            FilterKind::Tent => r - ax,
            FilterKind::Gaussian => {
                let sigma = r / 3.0;
                let g = |v: f32| (-v * v / (2.0 * sigma * sigma)).exp();
                (g(x) - g(r)).max(0.0)
            }
            FilterKind::Mitchell => {
                let (b, c) = (1.0 / 3.0, 1.0 / 3.0);
                let t = (2.0 * x / r).abs();
                if t > 1.0 {
                    ((-b - 6.0 * c) * t * t * t
                        + (6.0 * b + 30.0 * c) * t * t
                        + (-12.0 * b - 48.0 * c) * t
                        + (8.0 * b + 24.0 * c))
                        / 6.0
                } else {
                    ((12.0 - 9.0 * b - 6.0 * c) * t * t * t
                        + (-18.0 + 12.0 * b + 6.0 * c) * t * t
                        + (6.0 - 2.0 * b))
                        / 6.0
                }
            }
        }
    }

    /// The normalised 1D profile (integrates to one over [-r, r]).
    pub fn eval1(&self, x: f32) -> f32 {
        self.raw1(x) * self.norm
    }

    /// The normalised filter at offset (x, y) from the pixel centre; integrates to one.
    pub fn eval(&self, p: Vec2) -> f32 {
        self.eval1(p.x) * self.eval1(p.y)
    }

    fn sample1(&self, u: f32) -> (f32, f32) {
        if self.kind == FilterKind::Box {
            return ((2.0 * u - 1.0) * self.radius, 1.0);
        }
        // The bin whose cdf interval holds u, then uniform within it (monotone in u, so stratified
        // and low-discrepancy samples keep their structure).
        let u = u as f64;
        let b = self.cdf.partition_point(|&c| c <= u).clamp(1, BINS) - 1;
        let (c0, c1) = (self.cdf[b], self.cdf[b + 1]);
        let t = if c1 > c0 { (u - c0) / (c1 - c0) } else { 0.5 };
        let bw = 2.0 * self.radius as f64 / BINS as f64;
        let x = (-self.radius as f64 + (b as f64 + t.clamp(0.0, 1.0)) * bw) as f32;
        let pdf = (c1 - c0) / bw;
        let w = if pdf > 0.0 {
            (self.eval1(x) as f64 / pdf) as f32
        } else {
            0.0
        };
        (x, w)
    }

    /// An offset from the pixel centre drawn in proportion to |f|, and its weight f / pdf (about
    /// ±1; exactly 1 for the box).
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (x, wx) = self.sample1(u.x);
        let (y, wy) = self.sample1(u.y);
        (Vec2::new(x, y), wx * wy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [FilterKind; 4] = [
        FilterKind::Box,
        FilterKind::Tent,
        FilterKind::Gaussian,
        FilterKind::Mitchell,
    ];

    #[test]
    fn each_filter_integrates_to_one() {
        for kind in ALL {
            for radius in [None, Some(0.75), Some(2.5)] {
                let f = Filter::new(kind, radius);
                let r = f.radius;
                // Midpoint rule on a 400 x 400 grid over the support.
                let n = 400;
                let h = 2.0 * r / n as f32;
                let mut s = 0.0f64;
                for j in 0..n {
                    for i in 0..n {
                        let p = Vec2::new(-r + (i as f32 + 0.5) * h, -r + (j as f32 + 0.5) * h);
                        s += f.eval(p) as f64;
                    }
                }
                let integral = s * (h * h) as f64;
                assert!((integral - 1.0).abs() < 2e-3, "{kind} r={r}: {integral}");
            }
        }
    }

    #[test]
    fn sampled_weights_estimate_the_integral() {
        // E[f1 / pdf] = integral of f1 = 1 per axis (so 1 in 2D), on a fine stratified grid of u;
        // samples stay within the radius.
        for kind in ALL {
            let f = Filter::new(kind, None);
            let n = 1 << 16;
            let mut s = 0.0f64;
            for i in 0..n {
                let (x, w) = f.sample1((i as f32 + 0.5) / n as f32);
                assert!(x.abs() <= f.radius + 1e-5);
                s += w as f64;
            }
            let mean = s / n as f64;
            assert!((mean - 1.0).abs() < 1e-3, "{kind}: {mean}");
            let (p, w) = f.sample(Vec2::new(0.3, 0.8));
            assert_eq!(w, f.sample1(0.3).1 * f.sample1(0.8).1);
            assert!(p.abs().max_element() <= f.radius + 1e-5);
        }
    }

    #[test]
    fn mitchell_has_negative_lobes_and_box_weights_are_one() {
        let m = Filter::new(FilterKind::Mitchell, None);
        assert!(m.eval1(1.5) < 0.0);
        let (_, w) = m.sample(Vec2::new(0.01, 0.5));
        assert!(w < 0.0);
        let b = Filter::new(FilterKind::Box, None);
        assert_eq!(b.sample(Vec2::new(0.3, 0.9)).1, 1.0);
    }
}
