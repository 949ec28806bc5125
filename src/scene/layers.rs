//! The glTF material extensions layered over the metallic-roughness base: KHR_materials_specular's
//! colour and textures, clearcoat, sheen, anisotropy, iridescence, diffuse transmission, dispersion.

use glam::Vec3;

use super::TexRef;

/// KHR_materials_clearcoat: a dielectric GGX coat (IOR 1.5) over the whole material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clearcoat {
    /// clearcoatFactor, times the R channel of `factor_tex`.
    pub factor: f32,
    pub factor_tex: Option<TexRef>,
    /// clearcoatRoughnessFactor (perceptual), times the G channel of `roughness_tex`.
    pub roughness: f32,
    pub roughness_tex: Option<TexRef>,
    /// The coat's own normal map; without one the coat follows the interpolated normal.
    pub normal_tex: Option<TexRef>,
    pub normal_scale: f32,
}

/// KHR_materials_sheen: a Charlie sheen (Estevez and Kulla 2017) over the base.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sheen {
    /// sheenColorFactor (linear), times the RGB of `color_tex` (sRGB).
    pub color: Vec3,
    pub color_tex: Option<TexRef>,
    /// sheenRoughnessFactor (perceptual), times the A channel of `roughness_tex`.
    pub roughness: f32,
    pub roughness_tex: Option<TexRef>,
}

/// KHR_materials_anisotropy: the base's specular roughness raised along a direction in the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Anisotropy {
    /// anisotropyStrength, times the B channel of `texture`.
    pub strength: f32,
    /// anisotropyRotation (radians, counter-clockwise from the tangent).
    pub rotation: f32,
    /// Direction in tangent space in RG (mapped from [0, 1] to [-1, 1]), strength in B; linear.
    pub texture: Option<TexRef>,
}

/// KHR_materials_iridescence: a thin dielectric film over the base.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iridescence {
    /// iridescenceFactor, times the R channel of `factor_tex`.
    pub factor: f32,
    pub factor_tex: Option<TexRef>,
    /// iridescenceIor: the film's index of refraction.
    pub ior: f32,
    /// Film thickness in nanometres: `thickness_max`, or mix(min, max, G of `thickness_tex`).
    pub thickness_min: f32,
    pub thickness_max: f32,
    pub thickness_tex: Option<TexRef>,
}

/// KHR_materials_diffuse_transmission: a Lambertian BTDF taking part of the base's diffuse light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiffuseTransmission {
    /// diffuseTransmissionFactor, times the A channel of `factor_tex`.
    pub factor: f32,
    pub factor_tex: Option<TexRef>,
    /// diffuseTransmissionColorFactor (linear), times the RGB of `color_tex` (sRGB).
    pub color: Vec3,
    pub color_tex: Option<TexRef>,
}

/// Everything of a material beyond the metallic-roughness base; the default adds nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialLayers {
    /// KHR_materials_specular's A-channel texture, multiplying the specular factor.
    pub specular_tex: Option<TexRef>,
    /// specularColorFactor: tints the dielectric F0 (clamped to 1 where it is used).
    pub specular_color: Vec3,
    /// specularColorTexture (sRGB RGB), multiplying `specular_color`.
    pub specular_color_tex: Option<TexRef>,
    pub clearcoat: Option<Clearcoat>,
    pub sheen: Option<Sheen>,
    pub anisotropy: Option<Anisotropy>,
    pub iridescence: Option<Iridescence>,
    pub diffuse_transmission: Option<DiffuseTransmission>,
    /// KHR_materials_dispersion's `dispersion` (20 / Abbe number; 0: none), for thick transmission.
    pub dispersion: f32,
}

impl Default for MaterialLayers {
    fn default() -> Self {
        Self {
            specular_tex: None,
            specular_color: Vec3::ONE,
            specular_color_tex: None,
            clearcoat: None,
            sheen: None,
            anisotropy: None,
            iridescence: None,
            diffuse_transmission: None,
            dispersion: 0.0,
        }
    }
}

impl MaterialLayers {
    /// Every texture slot (bound or not) of the layers.
    pub fn textures_mut(&mut self) -> impl Iterator<Item = &mut Option<TexRef>> {
        let mut v = vec![&mut self.specular_tex, &mut self.specular_color_tex];
        if let Some(c) = &mut self.clearcoat {
            v.extend([&mut c.factor_tex, &mut c.roughness_tex, &mut c.normal_tex]);
        }
        if let Some(s) = &mut self.sheen {
            v.extend([&mut s.color_tex, &mut s.roughness_tex]);
        }
        if let Some(a) = &mut self.anisotropy {
            v.push(&mut a.texture);
        }
        if let Some(i) = &mut self.iridescence {
            v.extend([&mut i.factor_tex, &mut i.thickness_tex]);
        }
        if let Some(d) = &mut self.diffuse_transmission {
            v.extend([&mut d.factor_tex, &mut d.color_tex]);
        }
        v.into_iter()
    }
}
