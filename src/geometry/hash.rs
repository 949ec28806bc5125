//! Integer hashing for seeds and keys: every pseudo-random decision outside a sampler's dimensions
//! (test rays, scene-file jitter) and every sampler's scrambles derive from this one mix.

/// SplitMix64's finaliser: a bijective 64-bit mix with good avalanche.
pub const fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
