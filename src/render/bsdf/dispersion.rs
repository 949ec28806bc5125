//! KHR_materials_dispersion: the index of refraction per RGB channel, from the Abbe number by the
//! extension's two-term Cauchy formula at one representative wavelength per channel.

use glam::Vec3;

use super::Bsdf;

/// The wavelengths (nm) standing for R, G and B: the Fraunhofer C, d and F lines that define the
/// Abbe number, so green keeps the material's IOR (n_d) and red to blue spans n_F - n_C = (n_d - 1) / V_d.
pub const CHANNEL_WAVELENGTHS: [f32; 3] = [656.27, 587.56, 486.13];

/// The extension's n(lambda) = max(n_d + (n_d - 1) / V_d (523655 / lambda^2 - 1.5168), 1), for IOR
/// `ior` (n_d) and `dispersion` (20 / V_d), lambda in nm.
pub fn ior_at(ior: f32, dispersion: f32, lambda: f32) -> f32 {
    let inv_abbe = dispersion / 20.0;
    (ior + (ior - 1.0) * inv_abbe * (523_655.0 / (lambda * lambda) - 1.5168)).max(1.0)
}

/// The IOR of each RGB channel at its representative wavelength.
pub fn channel_iors(ior: f32, dispersion: f32) -> Vec3 {
    Vec3::from_array(CHANNEL_WAVELENGTHS.map(|l| ior_at(ior, dispersion, l)))
}

impl Bsdf {
    /// KHR_materials_dispersion on a thick transmissive surface (call after `with_dielectric`):
    /// its IOR per channel. Thin walls do not refract, so they have none; neither has a dispersion of 0.
    pub fn with_dispersion(mut self, dispersion: f32) -> Self {
        if dispersion > 0.0 && !self.thin && self.transmission > 0.0 {
            let ior = if self.outside {
                self.eta
            } else {
                1.0 / self.eta
            };
            self.dispersion = Some(channel_iors(ior, dispersion));
        }
        self
    }

    /// The surface as the light of channel `c` (0 red, 1 green, 2 blue) sees it: that channel's
    /// IOR everywhere (Fresnel and refraction). A path following one channel carries zero in the
    /// others, so the other channels' values do not matter.
    pub fn for_channel(mut self, c: usize) -> Self {
        if let Some(iors) = self.dispersion {
            let n = iors[c];
            self.eta = if self.outside { n } else { 1.0 / n };
        }
        self
    }
}
