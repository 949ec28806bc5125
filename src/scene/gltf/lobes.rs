//! The KHR material extensions that add lobes or change the base's microfacets and Fresnel:
//! anisotropy, iridescence, diffuse transmission and dispersion, read from the material's JSON.

use glam::Vec3;
use gltf::json::Value;

use super::material::{num, rgb};
use super::Loader;
use crate::scene::layers::{Anisotropy, DiffuseTransmission, Iridescence};
use crate::scene::Material;

impl Loader<'_> {
    /// Reads the extensions of this file onto `mat`.
    pub(super) fn lobe_extensions(&mut self, m: &gltf::Material, mat: &mut Material, label: &str) {
        if let Some(a) = m.extension_value("KHR_materials_anisotropy") {
            mat.layers.anisotropy = self.anisotropy(a, label);
        }
        if let Some(i) = m.extension_value("KHR_materials_iridescence") {
            mat.layers.iridescence = self.iridescence(i, label);
        }
        if let Some(d) = m.extension_value("KHR_materials_diffuse_transmission") {
            mat.layers.diffuse_transmission = self.diffuse_transmission(d, label);
        }
        if let Some(d) = m.extension_value("KHR_materials_dispersion") {
            mat.layers.dispersion = num(d, "dispersion", 0.0).max(0.0);
        }
    }

    /// KHR_materials_diffuse_transmission's factors and textures; None when the factor is 0.
    fn diffuse_transmission(&mut self, v: &Value, label: &str) -> Option<DiffuseTransmission> {
        let factor = num(v, "diffuseTransmissionFactor", 0.0).clamp(0.0, 1.0);
        if factor == 0.0 {
            return None;
        }
        Some(DiffuseTransmission {
            factor,
            factor_tex: self.json_tex(v, "diffuseTransmissionTexture", false, label),
            color: rgb(v, "diffuseTransmissionColorFactor", Vec3::ONE).clamp(Vec3::ZERO, Vec3::ONE),
            color_tex: self.json_tex(v, "diffuseTransmissionColorTexture", true, label),
        })
    }

    /// KHR_materials_anisotropy's strength, rotation and direction texture; None when the
    /// strength is 0 (the material renders as without the extension).
    fn anisotropy(&mut self, a: &Value, label: &str) -> Option<Anisotropy> {
        let strength = num(a, "anisotropyStrength", 0.0).clamp(0.0, 1.0);
        if strength == 0.0 {
            return None;
        }
        Some(Anisotropy {
            strength,
            rotation: num(a, "anisotropyRotation", 0.0),
            texture: self.json_tex(a, "anisotropyTexture", false, label),
        })
    }

    /// KHR_materials_iridescence's factors and textures; None when the factor is 0.
    fn iridescence(&mut self, v: &Value, label: &str) -> Option<Iridescence> {
        let factor = num(v, "iridescenceFactor", 0.0).clamp(0.0, 1.0);
        if factor == 0.0 {
            return None;
        }
        let ior = num(v, "iridescenceIor", 1.3);
        Some(Iridescence {
            factor,
            factor_tex: self.json_tex(v, "iridescenceTexture", false, label),
            ior: if ior >= 1.0 { ior } else { 1.3 },
            thickness_min: num(v, "iridescenceThicknessMinimum", 100.0).max(0.0),
            thickness_max: num(v, "iridescenceThicknessMaximum", 400.0).max(0.0),
            thickness_tex: self.json_tex(v, "iridescenceThicknessTexture", false, label),
        })
    }
}
