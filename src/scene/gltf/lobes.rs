//! The KHR material extensions that add lobes or change the base's microfacets and Fresnel:
//! anisotropy, iridescence, diffuse transmission and dispersion, read from the material's JSON.

use gltf::json::Value;

use super::material::num;
use super::Loader;
use crate::scene::layers::Anisotropy;
use crate::scene::Material;

impl Loader<'_> {
    /// Reads the extensions of this file onto `mat`.
    pub(super) fn lobe_extensions(&mut self, m: &gltf::Material, mat: &mut Material, label: &str) {
        if let Some(a) = m.extension_value("KHR_materials_anisotropy") {
            mat.layers.anisotropy = self.anisotropy(a, label);
        }
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
}
