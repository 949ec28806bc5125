//! Fresnel reflectance: the exact unpolarised dielectric form the base uses, and Schlick's
//! approximation (the glTF spec's, for metals and the clearcoat).

use glam::Vec3;

/// Unpolarised Fresnel reflectance of a dielectric interface with relative index `eta` (far side over
/// near side) at incidence cosine `cos_i`; 1 under total internal reflection.
pub fn fresnel_exact(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

pub(super) fn schlick(f0: Vec3, cos: f32) -> Vec3 {
    f0 + (Vec3::ONE - f0) * (1.0 - cos).clamp(0.0, 1.0).powi(5)
}

/// Schlick's form for one channel.
pub(super) fn schlick1(f0: f32, cos: f32) -> f32 {
    f0 + (1.0 - f0) * (1.0 - cos).clamp(0.0, 1.0).powi(5)
}
