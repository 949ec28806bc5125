//! AgX (Troy Sobotka's view transform, Blender 4's default), in the widely used minimal form: an
//! inset matrix, a log2 encoding over [-12.47, 4.03] EV, a polynomial fit of the default contrast.

use glam::{Mat3, Vec3};

/// Lowest and highest stops the log encoding covers (relative to 0.18 grey).
const MIN_EV: f32 = -12.473_93;
const MAX_EV: f32 = 4.026_069;

/// Rec. 709 into the AgX working space: pulls primaries inwards so that bright saturated colours
/// bleach towards white instead of clipping per channel (columns as in the reference GLSL).
fn inset() -> Mat3 {
    Mat3::from_cols(
        Vec3::new(0.842_479_1, 0.042_328_24, 0.042_375_655),
        Vec3::new(0.078_433_6, 0.878_468_6, 0.078_433_6),
        Vec3::new(0.079_223_745, 0.079_166_13, 0.879_143),
    )
}

/// The inverse of `inset`, back to Rec. 709.
fn outset() -> Mat3 {
    Mat3::from_cols(
        Vec3::new(1.196_879, -0.052_896_85, -0.052_971_635),
        Vec3::new(-0.098_020_88, 1.151_903_1, -0.098_043_45),
        Vec3::new(-0.099_029_74, -0.098_961_18, 1.151_073_7),
    )
}

/// The sixth-order fit of AgX's default sigmoid on the normalised log value.
fn contrast(x: f32) -> f32 {
    let x2 = x * x;
    let x4 = x2 * x2;
    15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x
        - 0.002_32
}

/// Maps non-negative linear Rec. 709 to linear Rec. 709 in [0, 1].
pub fn map(c: Vec3) -> Vec3 {
    let v = inset() * c;
    let encoded = v.to_array().map(|v| {
        let ev = v.log2().clamp(MIN_EV, MAX_EV);
        contrast((ev - MIN_EV) / (MAX_EV - MIN_EV))
    });
    // The curve's output is display-encoded for a 2.2 power display; undo that to linear light
    // so that the one sRGB encoding after every view applies.
    let display = (outset() * Vec3::from_array(encoded)).clamp(Vec3::ZERO, Vec3::ONE);
    display.powf(2.2)
}
