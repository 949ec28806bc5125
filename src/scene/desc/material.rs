//! The `[[material]]` tables of a scene file: named metallic-roughness materials with defaults for a
//! grey dielectric, checked against their physical ranges.

use glam::Vec3;
use serde::Deserialize;

use super::layers::{
    AnisotropyDesc, ClearcoatDesc, DiffuseTransmissionDesc, IridescenceDesc, SheenDesc,
};
use super::light::white;
use crate::scene::{AlphaMode, Material};

/// A material defined in the scene file; what is left out takes these defaults (a grey dielectric).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MaterialDesc {
    pub(super) name: String,
    #[serde(default = "grey")]
    base_color: [f32; 3],
    #[serde(default = "one")]
    alpha: f32,
    #[serde(default)]
    metallic: f32,
    #[serde(default = "half")]
    roughness: f32,
    #[serde(default)]
    emissive: [f32; 3],
    #[serde(default = "one")]
    emissive_strength: f32,
    #[serde(default = "one")]
    specular: f32,
    #[serde(default)]
    transmission: f32,
    #[serde(default = "ior")]
    ior: f32,
    /// Above 0 the transmissive material is a solid that refracts (KHR_materials_volume); 0 is a
    /// thin wall that light passes straight through.
    #[serde(default)]
    thickness: f32,
    #[serde(default = "white")]
    attenuation_color: [f32; 3],
    /// Distance at which light inside keeps `attenuation_color` of itself (default: no absorption).
    attenuation_distance: Option<f32>,
    #[serde(default)]
    double_sided: bool,
    /// KHR_materials_unlit: the base colour shown as it is.
    #[serde(default)]
    unlit: bool,
    // The extension layers (`layers.rs`).
    /// KHR_materials_specular's specularColorFactor: tints the dielectric F0.
    pub(super) specular_color: Option<[f32; 3]>,
    pub(super) clearcoat: Option<ClearcoatDesc>,
    pub(super) sheen: Option<SheenDesc>,
    pub(super) anisotropy: Option<AnisotropyDesc>,
    pub(super) iridescence: Option<IridescenceDesc>,
    pub(super) diffuse_transmission: Option<DiffuseTransmissionDesc>,
    /// KHR_materials_dispersion: 20 / Abbe number (0: none); for solids (`thickness` above 0).
    #[serde(default)]
    pub(super) dispersion: f32,
}

fn grey() -> [f32; 3] {
    [0.8; 3]
}
pub(super) fn one() -> f32 {
    1.0
}
pub(super) fn half() -> f32 {
    0.5
}
fn ior() -> f32 {
    1.5
}

impl MaterialDesc {
    pub(super) fn to_material(&self) -> Material {
        let [r, g, b] = self.base_color;
        Material {
            name: self.name.clone(),
            base_color: glam::Vec4::new(r, g, b, self.alpha),
            metallic: self.metallic,
            roughness: self.roughness,
            emissive: Vec3::from(self.emissive) * self.emissive_strength,
            alpha_mode: if self.alpha < 1.0 {
                AlphaMode::Blend
            } else {
                AlphaMode::Opaque
            },
            double_sided: self.double_sided,
            specular: self.specular,
            transmission: self.transmission,
            ior: self.ior,
            thickness: self.thickness,
            attenuation_color: self.attenuation_color.into(),
            attenuation_distance: self.attenuation_distance.unwrap_or(f32::INFINITY),
            unlit: self.unlit,
            layers: self.to_layers(),
            ..Material::default()
        }
    }

    /// The first field out of its physical range, as `(field, why)`.
    pub(super) fn range_error(&self) -> Option<(&'static str, &'static str)> {
        let unit = |v: f32| (0.0..=1.0).contains(&v);
        if !self.base_color.iter().all(|&c| unit(c)) || !unit(self.alpha) {
            return Some(("base_color/alpha", "must lie in [0, 1]"));
        }
        let out = out_of_range([
            ("metallic", self.metallic, Range::Unit),
            ("roughness", self.roughness, Range::Unit),
            ("specular", self.specular, Range::Unit),
            ("transmission", self.transmission, Range::Unit),
            ("ior", self.ior, Range::AtLeastOne),
            ("thickness", self.thickness, Range::NonNegative),
        ]);
        if out.is_some() {
            return out;
        }
        if !self.attenuation_color.iter().all(|&c| unit(c))
            || self
                .attenuation_distance
                .is_some_and(|d| d.is_nan() || d <= 0.0)
        {
            return Some((
                "attenuation_color/attenuation_distance",
                "must lie in [0, 1] / be positive",
            ));
        }
        let e = Vec3::from(self.emissive) * self.emissive_strength;
        if !(e.is_finite() && e.min_element() >= 0.0) {
            return Some(("emissive", "must be finite and not negative"));
        }
        self.layers_range_error()
    }
}

/// A physical range a scene-file value must lie in, with what its error says.
#[derive(Clone, Copy, Debug)]
pub(super) enum Range {
    Unit,
    AtLeastOne,
    NonNegative,
    Finite,
}

impl Range {
    fn holds(self, v: f32) -> bool {
        match self {
            Range::Unit => (0.0..=1.0).contains(&v),
            Range::AtLeastOne => v >= 1.0 && v.is_finite(),
            Range::NonNegative => v >= 0.0 && v.is_finite(),
            Range::Finite => v.is_finite(),
        }
    }

    fn why(self) -> &'static str {
        match self {
            Range::Unit => "must lie in [0, 1]",
            Range::AtLeastOne => "must be at least 1",
            Range::NonNegative => "must be finite and not negative",
            Range::Finite => "must be finite",
        }
    }
}

/// The first `(field, value, range)` whose value is out of its range, as `(field, why)`.
pub(super) fn out_of_range(
    values: impl IntoIterator<Item = (&'static str, f32, Range)>,
) -> Option<(&'static str, &'static str)> {
    values
        .into_iter()
        .find(|&(_, v, r)| !r.holds(v))
        .map(|(field, _, r)| (field, r.why()))
}
