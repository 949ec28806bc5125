//! KHR_materials_iridescence's thin film: the Fresnel reflectance of a dielectric film over the base
//! (Belcour and Barla 2017, in the approximation the extension's implementation notes give: Schlick
//! at both interfaces, phase shifts of 0 or pi, the spectral integral in closed form to second order).

use std::f32::consts::PI;

use glam::{Mat3, Vec3};

/// A thin film over the base's specular layer.
#[derive(Clone, Copy, Debug)]
pub struct Iridescence {
    /// iridescenceFactor (times its texture's R): how much the film's Fresnel replaces the plain one.
    pub factor: f32,
    /// The film's index of refraction.
    pub ior: f32,
    /// Film thickness in nanometres.
    pub thickness: f32,
    /// The index above the film: 1 (air), or the clearcoat's 1.5 under a coat.
    pub outside_ior: f32,
}

/// CIE XYZ to linear Rec. 709 (the extension's XYZ_TO_REC709), by columns as GLSL lists them.
const XYZ_TO_REC709: Mat3 = Mat3::from_cols_array(&[
    3.2404542, -0.969_266, 0.0556434, -1.5371385, 1.8760108, -0.2040259, -0.4985314, 0.041_556,
    1.0572252,
]);

/// Normal-incidence reflectance between indices `t` (transmitted side) and `i` (incident side).
fn ior_to_f0(t: f32, i: f32) -> f32 {
    let r = (t - i) / (t + i);
    r * r
}

fn f0_to_ior(f0: f32) -> f32 {
    let s = f0.clamp(0.0, 0.9999).sqrt();
    (1.0 + s) / (1.0 - s)
}

fn schlick(f0: f32, cos: f32) -> f32 {
    f0 + (1.0 - f0) * (1.0 - cos).clamp(0.0, 1.0).powi(5)
}

/// The colour-matching functions' Fourier transform at optical path difference `opd` (nm) with
/// phase `shift` per channel, fitted by Gaussians (Belcour and Barla's evalSensitivity), in RGB.
fn sensitivity(opd: f32, shift: Vec3) -> Vec3 {
    let phase = 2.0 * PI * opd * 1.0e-9;
    let val = Vec3::new(5.4856e-13, 4.4201e-13, 5.2481e-13);
    let pos = Vec3::new(1.6810e+06, 1.7953e+06, 2.2084e+06);
    let var = Vec3::new(4.3278e+09, 9.3046e+09, 6.6121e+09);
    let p2 = phase * phase;
    let mut xyz = Vec3::new(
        val.x * (2.0 * PI * var.x).sqrt() * (pos.x * phase + shift.x).cos() * (-p2 * var.x).exp(),
        val.y * (2.0 * PI * var.y).sqrt() * (pos.y * phase + shift.y).cos() * (-p2 * var.y).exp(),
        val.z * (2.0 * PI * var.z).sqrt() * (pos.z * phase + shift.z).cos() * (-p2 * var.z).exp(),
    );
    xyz.x += 9.7470e-14
        * (2.0 * PI * 4.5282e+09f32).sqrt()
        * (2.2399e+06 * phase + shift.x).cos()
        * (-4.5282e+09 * p2).exp();
    XYZ_TO_REC709 * (xyz / 1.0685e-7)
}

impl Iridescence {
    /// The film's reflectance at incidence cosine `cos1` over a base of normal-incidence
    /// reflectance `f0` (per channel), clamped to [0, 1] (the RGB projection can leave the gamut).
    pub fn fresnel(&self, cos1: f32, f0: Vec3) -> Vec3 {
        let outside = self.outside_ior;
        // The film fades into the outside medium as it vanishes.
        let s = (self.thickness / 0.03).clamp(0.0, 1.0);
        let film = outside + (self.ior - outside) * s * s * (3.0 - 2.0 * s);
        let sin2 = (outside / film).powi(2) * (1.0 - cos1 * cos1);
        let cos2_sq = 1.0 - sin2;
        if cos2_sq < 0.0 {
            return Vec3::ONE;
        }
        let cos2 = cos2_sq.sqrt();
        // Outside -> film.
        let r12 = schlick(ior_to_f0(film, outside), cos1);
        let t121 = 1.0 - r12;
        let phi12 = if film < outside { PI } else { 0.0 };
        let phi21 = PI - phi12;
        // Film -> base.
        let base_ior = f0.to_array().map(f0_to_ior);
        let r23 = Vec3::from(base_ior.map(|b| schlick(ior_to_f0(b, film), cos2)));
        let phi23 = Vec3::from(base_ior.map(|b| if b < film { PI } else { 0.0 }));
        let opd = 2.0 * film * self.thickness * cos2;
        let phi = Vec3::splat(phi21) + phi23;
        let r123 = (r12 * r23).clamp(Vec3::splat(1e-5), Vec3::splat(0.9999));
        let r123_sqrt = Vec3::new(r123.x.sqrt(), r123.y.sqrt(), r123.z.sqrt());
        let rs = t121 * t121 * r23 / (Vec3::ONE - r123);
        let mut i = Vec3::splat(r12) + rs;
        let mut cm = rs - Vec3::splat(t121);
        for m in 1..=2 {
            cm *= r123_sqrt;
            i += cm * 2.0 * sensitivity(m as f32 * opd, m as f32 * phi);
        }
        i.clamp(Vec3::ZERO, Vec3::ONE)
    }
}
