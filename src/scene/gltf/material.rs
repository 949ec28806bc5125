//! glTF materials onto the metallic-roughness `Material`: factors, the KHR material extensions glint
//! reads, and texture bindings with their KHR_texture_transform.

use glam::{Vec3, Vec4};
use gltf::json::Value;

use super::Loader;
use crate::scene::layers::{Clearcoat, Sheen};
use crate::scene::mesh::UV_SETS;
use crate::scene::{AlphaMode, Material, TexRef};

/// A number of an extension's JSON object, or its default.
pub(super) fn num(v: &Value, key: &str, default: f32) -> f32 {
    v.get(key)
        .and_then(Value::as_f64)
        .map_or(default, |f| f as f32)
}

/// An RGB triple of an extension's JSON object, or its default.
pub(super) fn rgb(v: &Value, key: &str, default: Vec3) -> Vec3 {
    match v.get(key).and_then(Value::as_array) {
        Some(a) if a.len() == 3 => Vec3::new(
            a[0].as_f64().unwrap_or(default.x as f64) as f32,
            a[1].as_f64().unwrap_or(default.y as f64) as f32,
            a[2].as_f64().unwrap_or(default.z as f64) as f32,
        ),
        _ => default,
    }
}

/// KHR_texture_transform as a row-major 2x3 matrix: T * R * S.
pub(crate) fn uv_transform(offset: [f32; 2], rotation: f32, scale: [f32; 2]) -> [[f32; 3]; 2] {
    let (s, c) = rotation.sin_cos();
    [
        [c * scale[0], s * scale[1], offset[0]],
        [-s * scale[0], c * scale[1], offset[1]],
    ]
}

/// A texture binding before it is resolved: texture index, texCoord set, UV transform.
struct TexInfo {
    texture: usize,
    tex_coord: u32,
    transform: [[f32; 3]; 2],
}

impl TexInfo {
    fn from_info(info: &gltf::texture::Info) -> Self {
        let mut tex_coord = info.tex_coord();
        let transform = match info.texture_transform() {
            Some(t) => {
                if let Some(tc) = t.tex_coord() {
                    tex_coord = tc;
                }
                uv_transform(t.offset(), t.rotation(), t.scale())
            }
            None => TexRef::IDENTITY_UV,
        };
        Self {
            texture: info.texture().index(),
            tex_coord,
            transform,
        }
    }

    /// For texture infos the crate does not type (normal textures): read the extension JSON.
    fn from_parts(texture: usize, tex_coord: u32, ext: Option<&Value>) -> Self {
        let mut tc = tex_coord;
        let transform = match ext {
            Some(v) => {
                let pair = |k: &str, d: [f32; 2]| match v.get(k).and_then(|a| a.as_array()) {
                    Some(a) if a.len() == 2 => [
                        a[0].as_f64().unwrap_or(d[0] as f64) as f32,
                        a[1].as_f64().unwrap_or(d[1] as f64) as f32,
                    ],
                    _ => d,
                };
                if let Some(t) = v.get("texCoord").and_then(|t| t.as_u64()) {
                    tc = t as u32;
                }
                let rot = v.get("rotation").and_then(|r| r.as_f64()).unwrap_or(0.0) as f32;
                uv_transform(pair("offset", [0.0, 0.0]), rot, pair("scale", [1.0, 1.0]))
            }
            None => TexRef::IDENTITY_UV,
        };
        Self {
            texture,
            tex_coord: tc,
            transform,
        }
    }
}

impl Loader<'_> {
    pub(super) fn material(&mut self, m: &gltf::Material) -> Material {
        let label = match m.name() {
            Some(n) => format!("material {} ('{n}')", m.index().unwrap_or(0)),
            None => format!("material {}", m.index().unwrap_or(0)),
        };
        let pbr = m.pbr_metallic_roughness();
        let mut mat = Material {
            name: m
                .name()
                .map(str::to_owned)
                .unwrap_or_else(|| format!("material {}", m.index().unwrap_or(0))),
            base_color: Vec4::from(pbr.base_color_factor()),
            metallic: pbr.metallic_factor(),
            roughness: pbr.roughness_factor(),
            emissive: Vec3::from(m.emissive_factor()) * m.emissive_strength().unwrap_or(1.0),
            alpha_mode: match m.alpha_mode() {
                gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
                gltf::material::AlphaMode::Mask => AlphaMode::Mask(m.alpha_cutoff().unwrap_or(0.5)),
                gltf::material::AlphaMode::Blend => AlphaMode::Blend,
            },
            double_sided: m.double_sided(),
            transmission: m
                .transmission()
                .map(|t| t.transmission_factor())
                .unwrap_or(0.0),
            ior: m.ior().unwrap_or(1.5),
            ..Material::default()
        };
        // An unlit material shows its base colour and nothing else (its emission is not a light).
        mat.unlit = m.extension_value("KHR_materials_unlit").is_some();
        if mat.unlit {
            mat.emissive = Vec3::ZERO;
        }
        if let Some(spec) = m.extension_value("KHR_materials_specular") {
            mat.specular = num(spec, "specularFactor", 1.0);
            mat.layers.specular_color = rgb(spec, "specularColorFactor", Vec3::ONE).max(Vec3::ZERO);
            mat.layers.specular_tex = self.json_tex(spec, "specularTexture", false, &label);
            mat.layers.specular_color_tex =
                self.json_tex(spec, "specularColorTexture", true, &label);
        }
        if let Some(cc) = m.extension_value("KHR_materials_clearcoat") {
            mat.layers.clearcoat = self.clearcoat(cc, &label);
        }
        if let Some(sh) = m.extension_value("KHR_materials_sheen") {
            mat.layers.sheen = self.sheen(sh, &label);
        }
        self.lobe_extensions(m, &mut mat, &label);
        self.core_textures(m, &mut mat, &label);
        if let Some(sg) = m.extension_value("KHR_materials_pbrSpecularGlossiness") {
            self.spec_gloss(sg, &mut mat, &label);
        }
        // Without KHR_materials_volume a transmissive surface is thin-walled (thickness 0). The
        // thickness texture only serves rasterisers; a path tracer measures the real thickness.
        if let Some(v) = m.volume() {
            mat.thickness = v.thickness_factor().max(0.0);
            mat.attenuation_color = Vec3::from(v.attenuation_color()).clamp(Vec3::ZERO, Vec3::ONE);
            let d = v.attenuation_distance();
            mat.attenuation_distance = if d > 0.0 { d } else { f32::INFINITY };
        }
        mat
    }

    /// The core model's textures (base colour, metallic-roughness, normal, emissive) and
    /// KHR_materials_transmission's.
    fn core_textures(&mut self, m: &gltf::Material, mat: &mut Material, label: &str) {
        let pbr = m.pbr_metallic_roughness();
        if let Some(t) = pbr.base_color_texture() {
            mat.base_color_tex = self.tex_ref(TexInfo::from_info(&t), true, label);
        }
        if let Some(t) = pbr.metallic_roughness_texture() {
            mat.metallic_roughness_tex = self.tex_ref(TexInfo::from_info(&t), false, label);
        }
        if let Some(t) = m.normal_texture() {
            let info = TexInfo::from_parts(
                t.texture().index(),
                t.tex_coord(),
                t.extension_value("KHR_texture_transform"),
            );
            mat.normal_tex = self.tex_ref(info, false, label);
            mat.normal_scale = t.scale();
        }
        if let Some(t) = m.emissive_texture() {
            mat.emissive_tex = self.tex_ref(TexInfo::from_info(&t), true, label);
        }
        if let Some(t) = m.transmission().and_then(|t| t.transmission_texture()) {
            mat.transmission_tex = self.tex_ref(TexInfo::from_info(&t), false, label);
        }
    }

    /// KHR_materials_clearcoat's factors and textures; None when the coat is off (factor 0).
    fn clearcoat(&mut self, cc: &Value, label: &str) -> Option<Clearcoat> {
        let factor = num(cc, "clearcoatFactor", 0.0).clamp(0.0, 1.0);
        if factor == 0.0 {
            return None;
        }
        let normal = cc.get("clearcoatNormalTexture");
        Some(Clearcoat {
            factor,
            factor_tex: self.json_tex(cc, "clearcoatTexture", false, label),
            roughness: num(cc, "clearcoatRoughnessFactor", 0.0).clamp(0.0, 1.0),
            roughness_tex: self.json_tex(cc, "clearcoatRoughnessTexture", false, label),
            normal_tex: self.json_tex(cc, "clearcoatNormalTexture", false, label),
            normal_scale: normal.map_or(1.0, |n| num(n, "scale", 1.0)),
        })
    }

    /// KHR_materials_sheen's factors and textures; None when the sheen is off (colour black).
    fn sheen(&mut self, sh: &Value, label: &str) -> Option<Sheen> {
        let color = rgb(sh, "sheenColorFactor", Vec3::ZERO).clamp(Vec3::ZERO, Vec3::ONE);
        if color == Vec3::ZERO {
            return None;
        }
        Some(Sheen {
            color,
            color_tex: self.json_tex(sh, "sheenColorTexture", true, label),
            roughness: num(sh, "sheenRoughnessFactor", 0.0).clamp(0.0, 1.0),
            roughness_tex: self.json_tex(sh, "sheenRoughnessTexture", false, label),
        })
    }

    /// A textureInfo inside an extension's JSON (`index`, `texCoord`, KHR_texture_transform).
    pub(super) fn json_tex(
        &mut self,
        v: &Value,
        key: &str,
        srgb: bool,
        label: &str,
    ) -> Option<TexRef> {
        let t = v.get(key)?;
        let Some(index) = t.get("index").and_then(Value::as_u64) else {
            self.scene
                .warnings
                .push(format!("{label}: {key} has no texture index; ignored"));
            return None;
        };
        if index as usize >= self.doc.textures().len() {
            self.scene.warnings.push(format!(
                "{label}: {key} names texture {index}, which does not exist; ignored"
            ));
            return None;
        }
        let tc = t.get("texCoord").and_then(Value::as_u64).unwrap_or(0) as u32;
        let ext = t
            .get("extensions")
            .and_then(|e| e.get("KHR_texture_transform"));
        self.tex_ref(TexInfo::from_parts(index as usize, tc, ext), srgb, label)
    }

    fn tex_ref(&mut self, info: TexInfo, srgb: bool, label: &str) -> Option<TexRef> {
        let mut tex_coord = info.tex_coord;
        if tex_coord as usize >= UV_SETS {
            self.scene.warnings.push(format!(
                "{label}: texture {} uses TEXCOORD_{tex_coord}; glint reads sets 0 to {}, so it reads set 0",
                info.texture,
                UV_SETS - 1
            ));
            tex_coord = 0;
        }
        let t = self.texture(info.texture, srgb)?;
        Some(TexRef {
            texture: t,
            uv_transform: info.transform,
            tex_coord,
        })
    }

    /// The spec's default material, added to the scene the first time a primitive names none.
    pub(super) fn default_material(&mut self) -> u32 {
        if let Some(m) = self.default_material {
            return m;
        }
        self.scene.materials.push(Material::default());
        let m = (self.scene.materials.len() - 1) as u32;
        self.default_material = Some(m);
        m
    }
}
