//! ACES, fitted: Stephen Hill's fit of the ACES RRT + sRGB ODT (BakingLab), the usual "ACES filmic"
//! of real-time engines: a matrix into a tone-scale space, a rational curve, a matrix back.

use glam::{Mat3, Vec3};

/// sRGB -> the ODT's working space, with the RRT's saturation folded in (rows as published).
const INPUT_ROWS: [[f32; 3]; 3] = [
    [0.597_19, 0.354_58, 0.048_23],
    [0.076_00, 0.908_34, 0.015_66],
    [0.028_40, 0.133_83, 0.837_77],
];

/// Back to linear sRGB (rows as published).
const OUTPUT_ROWS: [[f32; 3]; 3] = [
    [1.604_75, -0.531_08, -0.073_67],
    [-0.102_08, 1.108_13, -0.006_05],
    [-0.003_27, -0.072_76, 1.076_02],
];

fn rows(m: &[[f32; 3]; 3]) -> Mat3 {
    Mat3::from_cols_array_2d(m).transpose()
}

/// The rational fit of the RRT + ODT tone scale.
fn rrt_odt(v: f32) -> f32 {
    let a = v * (v + 0.024_578_6) - 0.000_090_537;
    let b = v * (0.983_729 * v + 0.432_951) + 0.238_081;
    a / b
}

/// Maps non-negative linear Rec. 709 to linear Rec. 709 in [0, 1].
pub fn map(c: Vec3) -> Vec3 {
    let v = rows(&INPUT_ROWS) * c;
    let v = Vec3::from_array(v.to_array().map(rrt_odt));
    (rows(&OUTPUT_ROWS) * v).clamp(Vec3::ZERO, Vec3::ONE)
}
