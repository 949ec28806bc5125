//! Where every random number of a path comes from: a sampler addressed by named dimensions.
//! A value depends only on (seed, pixel, sample index, dimension), never on threads or tile order.
//!
//! Three samplers share the `Sampler` trait: independent `random` values, `stratified` (jittered
//! strata over the pixel's samples, every dimension stratified on its own and shuffled, padded as in
//! pbrt), and `sobol` (Owen-scrambled Sobol points, Burley 2020, padded per dimension pair).
//! `warp` maps the unit square onto the domains the renderer samples, and `mis` weighs two sampling
//! strategies against each other.

#[cfg(test)]
pub(crate) mod chi_square;
pub mod mis;
mod sobol;
mod stratified;
pub mod warp;

use glam::Vec2;

use crate::geometry::mix64;

/// The largest f32 below 1: where sample values (and numbers remapped from them) are clamped.
pub const ONE_MINUS_EPS: f32 = 1.0 - f32::EPSILON / 2.0;

pub use sobol::SobolSampler;
pub use stratified::{permutation_element, StratifiedSampler};

/// The named sampling dimensions of one path. Camera dimensions come once per path; the others once
/// per bounce, so that bounce `k` of every path draws from the same dimension (what stratified and
/// low-discrepancy samplers need to line dimensions up).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dim {
    /// Position on the pixel (2D).
    Pixel,
    /// Position on the lens (2D).
    Lens,
    /// Time within the shutter (1D).
    Time,
    /// Which light to sample (1D).
    LightChoice,
    /// Position on the chosen light (2D).
    Light,
    /// Which BSDF lobe to sample (1D).
    BsdfLobe,
    /// Direction from the chosen lobe (2D).
    Bsdf,
    /// Russian roulette (1D).
    Roulette,
    /// Seed for stochastic transparency of the rays leaving this bounce (1D, used as 32 bits).
    Alpha,
}

impl Dim {
    const CAMERA_DIMS: u32 = 5;
    const BOUNCE_DIMS: u32 = 8;

    /// The flat dimension index of this named dimension at a bounce (2D dimensions take two slots).
    pub fn index(self, bounce: u32) -> u32 {
        match self {
            Dim::Pixel => 0,
            Dim::Lens => 2,
            Dim::Time => 4,
            _ => {
                let k = match self {
                    Dim::LightChoice => 0,
                    Dim::Light => 1,
                    Dim::BsdfLobe => 3,
                    Dim::Bsdf => 4,
                    Dim::Roulette => 6,
                    Dim::Alpha => 7,
                    _ => unreachable!(),
                };
                Self::CAMERA_DIMS + bounce * Self::BOUNCE_DIMS + k
            }
        }
    }
}

/// A source of sample values in [0, 1) for named dimensions of one pixel sample at a time.
pub trait Sampler {
    /// Starts sample `index` of pixel `(x, y)`.
    fn start(&mut self, x: u32, y: u32, index: u32);
    fn get_1d(&mut self, dim: Dim, bounce: u32) -> f32;
    fn get_2d(&mut self, dim: Dim, bounce: u32) -> Vec2;

    /// Point `j` (from 1) of 2D dimension `dim`'s extension past the first pass, where the sampler
    /// has one: with a pass of N samples, the pass's points and their extensions 1..k are the
    /// first kN points of the dimension's sequence. For renders whose first pass is all their
    /// samples (a later pass would take the same points).
    fn get_2d_extension(&mut self, _dim: Dim, _bounce: u32, _j: u32) -> Option<Vec2> {
        None
    }

    /// 32 random bits for a ray seed (see `Ray::seed`).
    fn get_seed(&mut self, bounce: u32) -> u32 {
        (self.get_1d(Dim::Alpha, bounce) * 4_294_967_296.0) as u32
    }
}

/// Independent uniform samples, from a hash of (seed, pixel, sample, dimension).
#[derive(Clone, Debug)]
pub struct RandomSampler {
    seed: u64,
    key: u64,
}

impl RandomSampler {
    pub fn new(seed: u64) -> Self {
        Self { seed, key: 0 }
    }

    fn value(&self, dim: u32) -> f32 {
        let h = mix64(self.key ^ mix64(dim as u64 + 0x5851_F42D_4C95_7F2D));
        // 24 random bits give every float in [0, 1) a multiple of 2^-24, never 1.0.
        (h >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }
}

impl Sampler for RandomSampler {
    fn start(&mut self, x: u32, y: u32, index: u32) {
        self.key = mix64(
            self.seed
                ^ mix64(
                    ((x as u64) << 32 | y as u64) ^ mix64(index as u64 ^ 0xD1B5_4A32_D192_ED03),
                ),
        );
    }

    fn get_1d(&mut self, dim: Dim, bounce: u32) -> f32 {
        self.value(dim.index(bounce))
    }

    fn get_2d(&mut self, dim: Dim, bounce: u32) -> Vec2 {
        let i = dim.index(bounce);
        Vec2::new(self.value(i), self.value(i + 1))
    }
}

/// Which sampler a render draws from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum SamplerKind {
    /// Independent uniform values.
    Random,
    /// Jittered strata (N x M over the pixel, N*M in every other dimension), shuffled per dimension.
    Stratified,
    /// Owen-scrambled Sobol (0,2)-sequence points, shuffled per dimension pair.
    #[default]
    Sobol,
}

impl std::fmt::Display for SamplerKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            SamplerKind::Random => "random",
            SamplerKind::Stratified => "stratified",
            SamplerKind::Sobol => "sobol",
        })
    }
}

/// One of the samplers, chosen at run time (an enum, so calls dispatch without a box).
#[derive(Clone, Debug)]
// The Sobol sampler's kept seeds (1 KB) make it the large variant; one sampler is made a tile, and
// boxing it would put a pointer between every draw and its seeds.
#[allow(clippy::large_enum_variant)]
pub enum AnySampler {
    Random(RandomSampler),
    Stratified(StratifiedSampler),
    Sobol(SobolSampler),
}

impl AnySampler {
    /// `spp` is the number of samples a pixel takes per pass (what the stratified sampler divides
    /// into strata; later samples start new, independently shuffled passes).
    pub fn new(kind: SamplerKind, seed: u64, spp: u32) -> Self {
        match kind {
            SamplerKind::Random => AnySampler::Random(RandomSampler::new(seed)),
            SamplerKind::Stratified => AnySampler::Stratified(StratifiedSampler::new(seed, spp)),
            SamplerKind::Sobol => AnySampler::Sobol(SobolSampler::new(seed, spp)),
        }
    }
}

impl Sampler for AnySampler {
    fn start(&mut self, x: u32, y: u32, index: u32) {
        match self {
            AnySampler::Random(s) => s.start(x, y, index),
            AnySampler::Stratified(s) => s.start(x, y, index),
            AnySampler::Sobol(s) => s.start(x, y, index),
        }
    }
    fn get_1d(&mut self, dim: Dim, bounce: u32) -> f32 {
        match self {
            AnySampler::Random(s) => s.get_1d(dim, bounce),
            AnySampler::Stratified(s) => s.get_1d(dim, bounce),
            AnySampler::Sobol(s) => s.get_1d(dim, bounce),
        }
    }
    fn get_2d(&mut self, dim: Dim, bounce: u32) -> Vec2 {
        match self {
            AnySampler::Random(s) => s.get_2d(dim, bounce),
            AnySampler::Stratified(s) => s.get_2d(dim, bounce),
            AnySampler::Sobol(s) => s.get_2d(dim, bounce),
        }
    }
    fn get_2d_extension(&mut self, dim: Dim, bounce: u32, j: u32) -> Option<Vec2> {
        match self {
            AnySampler::Random(s) => s.get_2d_extension(dim, bounce, j),
            AnySampler::Stratified(s) => s.get_2d_extension(dim, bounce, j),
            AnySampler::Sobol(s) => s.get_2d_extension(dim, bounce, j),
        }
    }
}

/// A 64-bit key for (seed, pixel): what decorrelates pixels from each other.
fn pixel_key(seed: u64, x: u32, y: u32) -> u64 {
    mix64(seed ^ mix64(((x as u64) << 32 | y as u64) ^ 0x9E37_79B9_7F4A_7C15))
}

/// The key of the pixel a sampler is in, hashed when the sampler moves to another pixel rather
/// than at every restart (a render restarts it twice a sample, and the two hashes were a tenth of
/// a sample that meets only the environment).
#[derive(Clone, Debug, Default)]
pub(crate) struct PixelKey {
    at: Option<(u32, u32)>,
    key: u64,
}

impl PixelKey {
    /// The key of pixel (x, y) under `seed` (one sampler keeps one seed).
    pub fn of(&mut self, seed: u64, x: u32, y: u32) -> u64 {
        if self.at != Some((x, y)) {
            self.at = Some((x, y));
            self.key = pixel_key(seed, x, y);
        }
        self.key
    }
}

/// 24 random bits of a hash as a float in [0, 1).
pub(crate) fn unit_float(h: u64) -> f32 {
    (h >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dimensions_do_not_overlap() {
        let mut seen = std::collections::HashSet::new();
        for bounce in 0..4 {
            for (d, width) in [
                (Dim::LightChoice, 1),
                (Dim::Light, 2),
                (Dim::BsdfLobe, 1),
                (Dim::Bsdf, 2),
                (Dim::Roulette, 1),
                (Dim::Alpha, 1),
            ] {
                for k in 0..width {
                    assert!(seen.insert(d.index(bounce) + k), "{d:?} at bounce {bounce}");
                }
            }
        }
        for (d, width) in [(Dim::Pixel, 2), (Dim::Lens, 2), (Dim::Time, 1)] {
            for k in 0..width {
                assert!(seen.insert(d.index(0) + k), "{d:?}");
            }
        }
    }

    #[test]
    fn random_sampler_is_deterministic_and_uniform() {
        let mut a = RandomSampler::new(7);
        let mut b = RandomSampler::new(7);
        let mut sum = 0.0f64;
        let n = 100_000;
        for i in 0..n {
            a.start(i % 13, i / 13, i);
            b.start(i % 13, i / 13, i);
            let v = a.get_1d(Dim::Roulette, 2);
            assert_eq!(v, b.get_1d(Dim::Roulette, 2));
            assert!((0.0..1.0).contains(&v));
            sum += v as f64;
        }
        assert!((sum / n as f64 - 0.5).abs() < 0.005);
    }
}
