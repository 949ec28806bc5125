//! Spawning secondary rays without self-intersection: the origin is pushed off the surface along the
//! geometric normal by an amount that scales with the coordinates' magnitude (Waechter and Binder,
//! Ray Tracing Gems ch. 6), so it works for huge and tiny scenes alike.

use glam::Vec3;

/// Below this magnitude a fixed absolute offset is used (integer ulps vanish near zero).
const ORIGIN: f32 = 1.0 / 32.0;
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
const INT_SCALE: f32 = 256.0;

/// Offsets `p` (a hit point) away from the surface, to the side that `n` points to.
pub fn offset_ray_origin(p: Vec3, n: Vec3) -> Vec3 {
    let of_i = [
        (INT_SCALE * n.x) as i32,
        (INT_SCALE * n.y) as i32,
        (INT_SCALE * n.z) as i32,
    ];
    let mut out = [0.0f32; 3];
    for a in 0..3 {
        let bits = p[a].to_bits() as i32;
        // Wrapping, as release builds do anyway: -0.0's bits are i32::MIN, and near zero the
        // result is not used.
        let moved = f32::from_bits(if p[a] < 0.0 {
            bits.wrapping_sub(of_i[a])
        } else {
            bits.wrapping_add(of_i[a])
        } as u32);
        out[a] = if p[a].abs() < ORIGIN {
            p[a] + FLOAT_SCALE * n[a]
        } else {
            moved
        };
    }
    Vec3::from_array(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moves_to_the_normal_side_at_every_scale() {
        let n = Vec3::new(0.3, 0.8, -0.52).normalize();
        for scale in [1e-6f32, 1e-3, 1.0, 1e3, 1e5, 1e7] {
            let p = Vec3::new(1.7, -2.3, 0.9) * scale;
            let q = offset_ray_origin(p, n);
            assert!((q - p).dot(n) > 0.0, "scale {scale}");
            // Small relative to the coordinates (or to the absolute floor near zero).
            assert!((q - p).length() <= (p.abs().max_element() * 1e-4).max(1e-4));
        }
    }

    #[test]
    fn negative_zero_and_the_smallest_negatives_move_like_zero() {
        // Their bits sit at i32::MIN, where the integer offset overflowed (a fuzzed GLB).
        let n = Vec3::new(0.6, -0.8, 0.0);
        for x in [-0.0f32, -f32::from_bits(1), 0.0] {
            let p = Vec3::new(x, x, x);
            let q = offset_ray_origin(p, n);
            assert!((q - p).dot(n) > 0.0 && q.is_finite(), "{x}: {q}");
        }
    }
}
