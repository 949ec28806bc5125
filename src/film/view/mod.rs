//! View transforms: how linear scene light becomes display light for PNG output. Exposure scales
//! first, a transform maps into [0, 1], the sRGB curve encodes; EXR output never passes here.

mod aces;
mod agx;
mod pbr_neutral;

use glam::Vec3;

use crate::geometry::colour::linear_to_srgb;

/// The display rendering of linear light (PNG output, turntable previews and contact sheets).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum ViewTransform {
    /// Khronos PBR Neutral: colours below 0.76 stay as they are (base colours read true), highlights
    /// roll off keeping their hue and bleach towards white.
    #[default]
    KhronosPbrNeutral,
    /// AgX (Blender's default): a filmic log curve with gamut inset; bright colours bleach smoothly.
    Agx,
    /// ACES filmic, Stephen Hill's fit of the RRT and sRGB ODT: more contrast, warmer highlights.
    Aces,
    /// Plain sRGB: each channel clamped to [0, 1], no tone curve.
    Standard,
}

impl ViewTransform {
    /// Linear display light in [0, 1] for linear scene light (already exposed); negative and
    /// non-finite channels count as 0.
    pub fn apply(self, c: Vec3) -> Vec3 {
        let c = Vec3::from_array(
            c.to_array()
                .map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 }),
        );
        let out = match self {
            ViewTransform::KhronosPbrNeutral => pbr_neutral::map(c),
            ViewTransform::Agx => agx::map(c),
            ViewTransform::Aces => aces::map(c),
            ViewTransform::Standard => c,
        };
        out.clamp(Vec3::ZERO, Vec3::ONE)
    }
}

/// How an image is shown: exposure in stops, then the view transform, then sRGB in 8 bits.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Display {
    pub exposure: f32,
    pub view: ViewTransform,
}

impl Display {
    pub fn new(exposure: f32, view: ViewTransform) -> Self {
        Self { exposure, view }
    }

    /// The 8-bit sRGB pixel for linear RGB `c`.
    pub fn encode(&self, c: Vec3) -> [u8; 3] {
        let d = self.view.apply(c * self.exposure.exp2());
        d.to_array()
            .map(|v| (linear_to_srgb(v) * 255.0 + 0.5) as u8)
    }
}

#[cfg(test)]
mod tests;
