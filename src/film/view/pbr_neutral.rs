//! Khronos PBR Neutral (the glTF product-rendering tone mapper): linear below 0.76, a hue-keeping
//! shoulder above it that desaturates towards white. From the Khronos ToneMapping/PBR_Neutral spec.

use glam::Vec3;

/// F90 of an IoR 1.5 dielectric: the black-level offset removed from every channel.
const F90: f32 = 0.04;
/// Where highlight compression starts (K_s).
const START: f32 = 0.8 - F90;
/// How fast compressed highlights desaturate (K_d).
const DESATURATION: f32 = 0.15;

/// Maps non-negative linear Rec. 709 to linear Rec. 709 in [0, 1].
pub fn map(c: Vec3) -> Vec3 {
    let x = c.min_element();
    // A smooth toe: subtracting F90 outright would crush near-blacks.
    let offset = if x < 2.0 * F90 {
        x - x * x / (4.0 * F90)
    } else {
        F90
    };
    let c = c - Vec3::splat(offset);
    let peak = c.max_element();
    if peak < START {
        return c;
    }
    let d = 1.0 - START;
    let new_peak = 1.0 - d * d / (peak + d - START);
    let c = c * (new_peak / peak);
    // Scaling and mixing with grey keep the hue; only saturation goes.
    let g = 1.0 - 1.0 / (DESATURATION * (peak - new_peak) + 1.0);
    c.lerp(Vec3::splat(new_peak), g)
}
