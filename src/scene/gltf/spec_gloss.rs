//! KHR_materials_pbrSpecularGlossiness (archived, common in older files) converted onto glint's
//! metallic-roughness material with KHR_materials_specular's colour, exactly where the spec is exact.
//!
//! The extension defines its BRDF inputs as `c_diff = diffuse * (1 - max(specular))`,
//! `F0 = specular` and `alpha = (1 - glossiness)^2`, over the core spec's BRDF. glint's dielectric
//! (metallic 0) with KHR_materials_specular has `F0 = min(F0(ior) * specularColor, 1)` and scales the
//! diffuse by `1 - max(F)`, so taking metallic 0, roughness `1 - glossiness`, base colour `diffuse`
//! and specular colour `specular / F0(ior)` gives the same F0 per channel, the same roughness and, at
//! normal incidence, the same `c_diff`; towards grazing incidence the diffuse gives way to the
//! Fresnel rise as in every glTF material, which keeps the sum within 1. This is what the Khronos
//! Sample Viewer does (f0 = specular, c_diff as above, metallic 0). The other known route, solving
//! for a metalness that reproduces diffuse and specular (the spec's conversion example), cannot show
//! a coloured specular over a differently coloured diffuse, so glint does not take it.
//!
//! Textures: `diffuseTexture` becomes the base colour texture (sRGB, alpha linear);
//! `specularGlossinessTexture`'s RGB (sRGB) becomes the specular colour texture, and its linear A the
//! roughness through a derived metallic-roughness texture holding `1 - glossinessFactor * A` in G
//! (so bilinear filtering gives the same as filtering A, then converting).

use glam::{Vec3, Vec4};
use gltf::json::Value;

use super::Loader;
use crate::scene::{Material, TexRef, Texture};

/// F0 of a dielectric of index `ior` in air.
fn dielectric_f0(ior: f32) -> f32 {
    ((ior - 1.0) / (ior + 1.0)).powi(2)
}

/// The numbers of a JSON array of `N` components, or `default`.
fn array<const N: usize>(v: &Value, key: &str, default: [f32; N]) -> [f32; N] {
    let mut out = default;
    if let Some(a) = v
        .get(key)
        .and_then(Value::as_array)
        .filter(|a| a.len() == N)
    {
        for (o, x) in out.iter_mut().zip(a) {
            if let Some(f) = x.as_f64() {
                *o = f as f32;
            }
        }
    }
    out
}

impl Loader<'_> {
    /// Replaces the metallic-roughness parameters of `mat` by those of the spec-gloss object `sg`.
    pub(super) fn spec_gloss(&mut self, sg: &Value, mat: &mut Material, label: &str) {
        let diffuse = Vec4::from(array(sg, "diffuseFactor", [1.0; 4])).clamp(Vec4::ZERO, Vec4::ONE);
        let specular =
            Vec3::from(array(sg, "specularFactor", [1.0; 3])).clamp(Vec3::ZERO, Vec3::ONE);
        let gloss = sg
            .get("glossinessFactor")
            .and_then(Value::as_f64)
            .map_or(1.0, |g| g as f32)
            .clamp(0.0, 1.0);
        let f0 = dielectric_f0(mat.ior);
        mat.base_color = diffuse;
        mat.metallic = 0.0;
        mat.roughness = 1.0 - gloss;
        mat.specular = 1.0;
        mat.metallic_roughness_tex = None;
        mat.base_color_tex = self.json_tex(sg, "diffuseTexture", true, label);
        if f0 > 0.0 {
            mat.layers.specular_color = specular / f0;
            mat.layers.specular_tex = None;
            mat.layers.specular_color_tex =
                self.json_tex(sg, "specularGlossinessTexture", true, label);
        } else {
            // An index-matched material (IOR 1) reflects nothing whatever its specular colour.
            self.scene.warnings.push(format!(
                "{label}: KHR_materials_pbrSpecularGlossiness with IOR 1 has no specular reflection"
            ));
        }
        if let Some(t) = self.json_tex(sg, "specularGlossinessTexture", true, label) {
            if let Some(rough) = self.roughness_from_gloss(t, gloss) {
                mat.roughness = 1.0;
                mat.metallic_roughness_tex = Some(rough);
            }
        }
    }

    /// A metallic-roughness texture (G = `1 - gloss * A`, B = 0) derived from the spec-gloss texture
    /// bound as `t`, made once per (texture, glossiness factor).
    fn roughness_from_gloss(&mut self, t: TexRef, gloss: f32) -> Option<TexRef> {
        let key = (t.texture, gloss.to_bits());
        let texture = match self.gloss_textures.get(&key) {
            Some(&k) => k,
            None => {
                let src = self.scene.textures.get(t.texture as usize)?;
                let pixels = src
                    .pixels
                    .iter()
                    .map(|p| {
                        let r = 1.0 - gloss * (p[3] as f32 / 255.0);
                        [0, (r * 255.0).round() as u8, 0, 255]
                    })
                    .collect();
                let derived = Texture {
                    name: format!("{} (roughness = 1 - {gloss} * A)", src.name),
                    pixels,
                    srgb: false,
                    ..src.clone()
                };
                self.scene.textures.push(derived);
                let k = (self.scene.textures.len() - 1) as u32;
                self.gloss_textures.insert(key, k);
                k
            }
        };
        Some(TexRef { texture, ..t })
    }
}
