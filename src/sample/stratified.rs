//! The stratified sampler: jittered N x M strata over the pixel, and every other dimension padded as
//! pbrt does: each (1D or 2D) dimension is stratified on its own over the pixel's N*M samples and
//! shuffled by a permutation hashed from (seed, pixel, dimension, pass), so dimensions do not line up.

use glam::Vec2;

use super::{unit_float, Dim, PixelKey, Sampler, ONE_MINUS_EPS};
use crate::geometry::mix64;

#[derive(Clone, Debug)]
pub struct StratifiedSampler {
    seed: u64,
    /// Strata per pass: `nx * ny` samples.
    nx: u32,
    ny: u32,
    keys: PixelKey,
    pixel: u64,
    /// The sample's stratum slot within its pass, and the pass.
    slot: u32,
    pass: u32,
    index: u32,
}

impl StratifiedSampler {
    /// `spp` samples per pass, split into the most square N x M grid with N * M = spp.
    pub fn new(seed: u64, spp: u32) -> Self {
        let n = spp.max(1);
        let mut nx = (n as f64).sqrt() as u32;
        while !n.is_multiple_of(nx) {
            nx -= 1;
        }
        Self {
            seed,
            nx,
            ny: n / nx,
            keys: PixelKey::default(),
            pixel: 0,
            slot: 0,
            pass: 0,
            index: 0,
        }
    }

    pub fn strata(&self) -> (u32, u32) {
        (self.nx, self.ny)
    }

    fn n(&self) -> u32 {
        self.nx * self.ny
    }

    /// The stratum this sample takes in flat dimension `d`, and a hash for its jitter.
    fn stratum(&self, d: u32) -> (u32, u64) {
        let dim_key = mix64(self.pixel ^ mix64(d as u64 + 0x2545_F491_4F6C_DD1D));
        let perm_seed = mix64(dim_key ^ self.pass as u64) as u32;
        let j = permutation_element(self.slot, self.n(), perm_seed);
        (
            j,
            mix64(dim_key ^ mix64(self.index as u64 ^ 0xA076_1D64_78BD_642F)),
        )
    }
}

impl Sampler for StratifiedSampler {
    fn start(&mut self, x: u32, y: u32, index: u32) {
        self.pixel = self.keys.of(self.seed, x, y);
        self.slot = index % self.n();
        self.pass = index / self.n();
        self.index = index;
    }

    fn get_1d(&mut self, dim: Dim, bounce: u32) -> f32 {
        let (j, h) = self.stratum(dim.index(bounce));
        ((j as f32 + unit_float(h)) / self.n() as f32).min(ONE_MINUS_EPS)
    }

    fn get_2d(&mut self, dim: Dim, bounce: u32) -> Vec2 {
        let (j, h) = self.stratum(dim.index(bounce));
        let (sx, sy) = (j % self.nx, j / self.nx);
        let (jx, jy) = (unit_float(h), unit_float(mix64(h)));
        Vec2::new(
            ((sx as f32 + jx) / self.nx as f32).min(ONE_MINUS_EPS),
            ((sy as f32 + jy) / self.ny as f32).min(ONE_MINUS_EPS),
        )
    }
}

/// Element `i` of a pseudo-random permutation of `0..n` chosen by `seed` (Kensler 2013, as in pbrt's
/// `PermutationElement`): a bijection without storing the permutation.
pub fn permutation_element(i: u32, n: u32, seed: u32) -> u32 {
    Permutation::new(n).element(i, seed)
}

/// The permutations of `0..n` that `permutation_element` draws, with the bit mask their walk
/// needs worked out once (a sampler draws from one `n` a few dozen times a sample).
#[derive(Clone, Copy, Debug)]
pub struct Permutation {
    n: u32,
    /// All bits up to `n - 1`'s highest.
    mask: u32,
}

impl Permutation {
    pub fn new(n: u32) -> Self {
        let mut w = n.wrapping_sub(1);
        w |= w >> 1;
        w |= w >> 2;
        w |= w >> 4;
        w |= w >> 8;
        w |= w >> 16;
        Self { n, mask: w }
    }

    /// The number of elements, `n`.
    pub fn len(&self) -> u32 {
        self.n
    }

    /// Element `i` (below `n`) of the permutation chosen by `seed`.
    #[inline]
    pub fn element(&self, mut i: u32, seed: u32) -> u32 {
        let (p, w, n) = (seed, self.mask, self.n);
        loop {
            i ^= p;
            i = i.wrapping_mul(0xe170_893d);
            i ^= p >> 16;
            i ^= (i & w) >> 4;
            i ^= p >> 8;
            i = i.wrapping_mul(0x0929_eb3f);
            i ^= p >> 23;
            i ^= (i & w) >> 1;
            i = i.wrapping_mul(1 | p >> 27);
            i = i.wrapping_mul(0x6935_fa69);
            i ^= (i & w) >> 11;
            i = i.wrapping_mul(0x74dc_b303);
            i ^= (i & w) >> 2;
            i = i.wrapping_mul(0x9e50_1cc3);
            i ^= (i & w) >> 2;
            i = i.wrapping_mul(0xc860_a3df);
            i &= w;
            i ^= i >> 5;
            if i < n {
                break;
            }
        }
        rem(i as u64 + p as u64, n)
    }
}

/// `x % n`, by a mask where `n` is a power of two (every pass size a user is likely to pick): the
/// same value, without the division's latency on each of a sample's few dozen dimensions.
#[inline(always)]
pub fn rem(x: u64, n: u32) -> u32 {
    if n.is_power_of_two() {
        (x & (n as u64 - 1)) as u32
    } else {
        (x % n as u64) as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rem_is_the_remainder() {
        for n in [1u32, 2, 3, 7, 64, 100, 128, 1 << 31, u32::MAX] {
            for x in [0u64, 1, 63, 64, 65, 99, 1 << 40, u64::MAX - 5, u64::MAX] {
                assert_eq!(rem(x, n) as u64, x % n as u64, "{x} % {n}");
            }
        }
    }

    #[test]
    fn permutation_is_a_bijection() {
        for n in [1u32, 2, 7, 16, 100] {
            for seed in [0u32, 1, 0xdead_beef] {
                let mut seen = vec![false; n as usize];
                for i in 0..n {
                    let j = permutation_element(i, n, seed) as usize;
                    assert!(!seen[j]);
                    seen[j] = true;
                }
            }
        }
    }

    /// Exactly one sample per stratum: in the pixel dimension (N x M), and in padded higher
    /// dimensions (2D and 1D), for every pass.
    #[test]
    fn one_sample_per_stratum_in_pixel_and_padded_dimensions() {
        for spp in [16u32, 12, 9] {
            let mut s = StratifiedSampler::new(5, spp);
            let (nx, ny) = s.strata();
            assert_eq!(nx * ny, spp);
            for (x, y) in [(0, 0), (3, 7)] {
                for pass in 0..2 {
                    let mut hit_pixel = vec![0; spp as usize];
                    let mut hit_bsdf = vec![0; spp as usize];
                    let mut hit_1d = vec![0; spp as usize];
                    for i in 0..spp {
                        s.start(x, y, pass * spp + i);
                        for (v, hits) in [
                            (s.get_2d(Dim::Pixel, 0), &mut hit_pixel),
                            (s.get_2d(Dim::Bsdf, 3), &mut hit_bsdf),
                        ] {
                            let (sx, sy) = ((v.x * nx as f32) as u32, (v.y * ny as f32) as u32);
                            hits[(sy * nx + sx) as usize] += 1;
                        }
                        let u = s.get_1d(Dim::Roulette, 2);
                        hit_1d[(u * spp as f32) as usize] += 1;
                    }
                    assert!(hit_pixel.iter().all(|&c| c == 1), "{spp}: {hit_pixel:?}");
                    assert!(hit_bsdf.iter().all(|&c| c == 1), "{spp}: {hit_bsdf:?}");
                    assert!(hit_1d.iter().all(|&c| c == 1), "{spp}: {hit_1d:?}");
                }
            }
        }
    }

    #[test]
    fn dimensions_are_shuffled_independently() {
        // The stratum a sample takes in one dimension must not predict its stratum in another.
        let mut s = StratifiedSampler::new(1, 16);
        let mut same = 0;
        for i in 0..16 {
            s.start(2, 2, i);
            let a = s.get_1d(Dim::LightChoice, 0);
            let b = s.get_1d(Dim::LightChoice, 1);
            same += ((a * 16.0) as u32 == (b * 16.0) as u32) as u32;
        }
        assert!(same < 6);
    }
}
