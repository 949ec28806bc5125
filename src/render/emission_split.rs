//! Camera-ray splitting for the emission seen directly: in pixels where an emitter's edge lies, each
//! path's camera ray has companions at other pixel positions that bring back only what they see.
//!
//! A path's value is what its camera ray sees (`Integrator::seen`) plus what its bounces bring. The
//! first part is replaced by the mean over the camera ray and its k - 1 companions: each companion
//! is a camera ray of the same distribution (its pixel position uniform over the filter as the
//! path's is), so the mean has the same expectation and the estimate stays unbiased. Where small
//! emitters are seen directly their edges are most of the image's noise (many-emitters: 47% of the
//! variance a sample), and a companion costs one coherent primary ray, not a path. Which pixels
//! split is decided before sampling, from a fixed lattice of rays, so it depends on no sample.
//!
//! The companions' positions: where the render is one pass of N samples, the pixel sequence's
//! next passes (`Sampler::get_2d_extension`), so that the N samples and their companions are
//! the first kN points of one Owen-scrambled Sobol sequence (many-emitters, 8 rays, 32 spp x 8:
//! sigma 0.311 -> 0.301 against `companion`'s shifts; 128 x 6: 0.284 -> 0.278); otherwise (rounds,
//! whose later passes take those points) `companion`.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::camera::RayCamera;
use super::integrator::Integrator;
use crate::geometry::Ray;
use crate::sample::ONE_MINUS_EPS;

/// How many camera rays carry a path's directly seen emission where emitters have edges.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum EmissionSplits {
    /// The path's own camera ray alone (no companions, no search for edges).
    #[value(name = "1")]
    One,
    #[value(name = "2")]
    Two,
    #[value(name = "4")]
    Four,
    #[default]
    #[value(name = "8")]
    Eight,
    #[value(name = "16")]
    Sixteen,
}

impl EmissionSplits {
    /// The most camera rays a path takes.
    pub const MOST: usize = 16;

    /// Camera rays a path takes in a pixel that splits.
    pub fn count(self) -> usize {
        match self {
            EmissionSplits::One => 1,
            EmissionSplits::Two => 2,
            EmissionSplits::Four => 4,
            EmissionSplits::Eight => 8,
            EmissionSplits::Sixteen => 16,
        }
    }
}

impl std::fmt::Display for EmissionSplits {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.count())
    }
}

/// The first sixteen points of the two-dimensional Sobol sequence (van der Corput, and direction
/// numbers 1/2, 3/4, 5/8, 15/16), in sixteenths, in index order (not Gray-code order).
const SOBOL_SIXTEENTHS: [(u32, u32); EmissionSplits::MOST] = [
    (0, 0),
    (8, 8),
    (4, 12),
    (12, 4),
    (2, 10),
    (10, 2),
    (6, 6),
    (14, 14),
    (1, 15),
    (9, 7),
    (5, 3),
    (13, 11),
    (3, 5),
    (11, 13),
    (7, 9),
    (15, 1),
];

/// Companion `j` (0: the point itself) of pixel sample `u` in [0, 1)^2: the leading four bits of
/// each coordinate XORed with those of Sobol point `j`. XOR with a constant permutes the
/// sixteenths, so a companion is uniform where `u` is; and since the first 2^m Sobol points are a
/// (0, m, 2)-net, so are the first 2^m companions of any point: one in each of the 2^m elementary
/// intervals of every shape (for eight: each eighth of the pixel across, each eighth down, each
/// cell of 4 x 2 and of 2 x 4).
pub fn companion(u: Vec2, j: usize) -> Vec2 {
    let (sx, sy) = SOBOL_SIXTEENTHS[j];
    // 32 fraction bits hold every bit of a float in [0, 1) down to 2^-32; the product of the
    // shifted integer and 2^-32 rounds up to 1 only from above 1 - 2^-25.
    let xor = |v: f32, s: u32| {
        let bits = (v as f64 * 4294967296.0) as u32 ^ (s << 28);
        ((bits as f64 / 4294967296.0) as f32).min(ONE_MINUS_EPS)
    };
    Vec2::new(xor(u.x, sx), xor(u.y, sy))
}

/// Steps of the edge search's lattice of camera rays per pixel, along each axis: a pixel is
/// searched at its (STEPS + 1)^2 lattice points, corners and sides included, which its neighbours
/// share.
const STEPS: usize = 2;

/// The pixels whose paths split their camera rays.
#[derive(Clone, Debug)]
pub struct SplitPixels {
    width: usize,
    split: Vec<bool>,
}

impl SplitPixels {
    /// Pixels where emitters have an edge: among the camera rays (through the lens's centre,
    /// mid-shutter) at the pixel's lattice points, the radiance seen from emitters differs by more
    /// than the environment's mean luminance in some channel; grown by `reach` pixels, as far as
    /// a pixel's filter takes its samples.
    ///
    /// Under an environment every surface reflects about its mean radiance, and the rest of a
    /// path's noise grows with that: an emitter's edge of less contrast is not most of its
    /// pixel's noise (DamagedHelmet's emissive texture under a sky with a sun: its companions cost
    /// a fifth more time for no measurable change in noise). An edge between the lattice's rays
    /// may go unseen: its pixel then does not split, which costs noise, not bias.
    pub fn find(
        integrator: &Integrator,
        cam: &RayCamera,
        (width, height): (usize, usize),
        reach: usize,
    ) -> Self {
        let floor = integrator.lights.environment_luminance();
        let edges: Vec<bool> = (0..height)
            .into_par_iter()
            .flat_map_iter(|y| edges_of_row(integrator, cam, (width, y), floor))
            .collect();
        let r = reach as isize;
        let split = (0..width * height)
            .into_par_iter()
            .map(|k| {
                let (x, y) = ((k % width) as isize, (k / width) as isize);
                (-r..=r).any(|dy| {
                    (-r..=r).any(|dx| {
                        let (nx, ny) = (x + dx, y + dy);
                        (0..width as isize).contains(&nx)
                            && (0..height as isize).contains(&ny)
                            && edges[ny as usize * width + nx as usize]
                    })
                })
            })
            .collect();
        Self { width, split }
    }

    /// Whether pixel (x, y) splits.
    pub fn at(&self, x: usize, y: usize) -> bool {
        self.split[y * self.width + x]
    }

    /// How many pixels split.
    pub fn count(&self) -> usize {
        self.split.iter().filter(|&&s| s).count()
    }
}

/// Which pixels of row `y` (`width` of them) see emitters' radiance differ by more than `floor`
/// across their lattice points.
fn edges_of_row(
    integrator: &Integrator,
    cam: &RayCamera,
    (width, y): (usize, usize),
    floor: f32,
) -> Vec<bool> {
    let across = width * STEPS + 1;
    // The emitters' radiance at the lattice points of the row's pixels: STEPS + 1 rows of
    // `across`, traced eight neighbours at a time.
    let mut seen = vec![Vec3::ZERO; (STEPS + 1) * across];
    let step = 1.0 / STEPS as f32;
    for (k, chunk) in seen.chunks_mut(8).enumerate() {
        let rays: [Ray; 8] = std::array::from_fn(|l| {
            let at = 8 * k + l;
            let (i, j) = (at % across, at / across);
            let film = Vec2::new(i as f32, (y * STEPS + j) as f32) * step;
            cam.ray_at(film, Vec2::splat(0.5), 0.5)
        });
        let n = chunk.len();
        let mut hits = [None; 8];
        integrator.accel.intersect_many(&rays[..n], &mut hits[..n]);
        for ((e, ray), hit) in chunk.iter_mut().zip(&rays).zip(&hits) {
            *e = integrator.seen(ray, hit.as_ref()).emitters;
        }
    }
    (0..width)
        .map(|x| {
            let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
            for j in 0..=STEPS {
                for e in &seen[j * across + x * STEPS..=j * across + (x + 1) * STEPS] {
                    (lo, hi) = (lo.min(*e), hi.max(*e));
                }
            }
            (hi - lo).max_element() > floor
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn companions_are_a_net_and_keep_their_point_below_the_shift() {
        for (m, k) in [(1u32, 2usize), (2, 4), (3, 8), (4, 16)] {
            for seed in 0..200u32 {
                let h = |s: u32| (s.wrapping_mul(0x9E37_79B9) >> 8) as f32 / (1u32 << 24) as f32;
                let u = Vec2::new(h(seed * 2 + 1), h(seed * 2 + 2));
                let pts: Vec<Vec2> = (0..k).map(|j| companion(u, j)).collect();
                assert_eq!(pts[0], u, "companion 0 is the point");
                // Every elementary interval of volume 2^-m (2^a by 2^(m-a) cells) holds one.
                for a in 0..=m {
                    let mut cells: Vec<(u32, u32)> = pts
                        .iter()
                        .map(|p| {
                            (
                                (p.x * (1 << a) as f32) as u32,
                                (p.y * (1 << (m - a)) as f32) as u32,
                            )
                        })
                        .collect();
                    cells.sort();
                    cells.dedup();
                    assert_eq!(cells.len(), k, "k {k}, shape {a}, u {u}");
                }
                // Below the shifted bits each companion keeps the point's position.
                for p in &pts {
                    let frac = |v: f32| (v * 16.0).fract();
                    assert!((frac(p.x) - frac(u.x)).abs() < 1e-5);
                    assert!((frac(p.y) - frac(u.y)).abs() < 1e-5);
                    assert!(p.x < 1.0 && p.y < 1.0);
                }
            }
        }
    }
}
