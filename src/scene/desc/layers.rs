//! The glTF extension layers of a scene file's `[[material]]`: tables for clearcoat, sheen,
//! anisotropy, iridescence and diffuse transmission, plus specular colour and dispersion.
//!
//! A table that is present turns its layer on; its defaults make the bare table a visible layer
//! (a full smooth coat, a white sheen, ...). Values mean what the glTF extensions' factors mean,
//! except that angles are in degrees, as everywhere in scene files. No textures: scene-file
//! materials have none. A layer whose strength is 0 is off, as the glTF loader has it.

use glam::Vec3;
use serde::Deserialize;

use super::light::white;
use super::material::{out_of_range, MaterialDesc, Range};
use crate::scene::layers::{
    Anisotropy, Clearcoat, DiffuseTransmission, Iridescence, MaterialLayers, Sheen,
};

/// `clearcoat = { factor, roughness }`: a dielectric GGX coat (IOR 1.5).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ClearcoatDesc {
    #[serde(default = "super::material::one")]
    factor: f32,
    /// Perceptual, as glTF's clearcoatRoughnessFactor.
    #[serde(default)]
    roughness: f32,
}

/// `sheen = { color, roughness }`: the Charlie sheen.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SheenDesc {
    #[serde(default = "white")]
    color: [f32; 3],
    #[serde(default = "super::material::half")]
    roughness: f32,
}

/// `anisotropy = { strength, rotation }`: rotation in degrees, counter-clockwise from the tangent.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct AnisotropyDesc {
    strength: f32,
    #[serde(default)]
    rotation: f32,
}

/// `iridescence = { factor, ior, thickness }`: a thin film, `thickness` in nanometres.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct IridescenceDesc {
    #[serde(default = "super::material::one")]
    factor: f32,
    #[serde(default = "film_ior")]
    ior: f32,
    #[serde(default = "film_thickness")]
    thickness: f32,
}

/// `diffuse_transmission = { factor, color }`: a Lambertian BTDF taking part of the diffuse light.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DiffuseTransmissionDesc {
    #[serde(default = "super::material::one")]
    factor: f32,
    #[serde(default = "white")]
    color: [f32; 3],
}

/// KHR_materials_iridescence's defaults.
fn film_ior() -> f32 {
    1.3
}
fn film_thickness() -> f32 {
    400.0
}

impl MaterialDesc {
    pub(super) fn to_layers(&self) -> MaterialLayers {
        MaterialLayers {
            specular_color: self.specular_color.map_or(Vec3::ONE, Vec3::from),
            clearcoat: layer(&self.clearcoat),
            sheen: layer(&self.sheen),
            anisotropy: layer(&self.anisotropy),
            iridescence: layer(&self.iridescence),
            diffuse_transmission: layer(&self.diffuse_transmission),
            dispersion: self.dispersion,
            ..MaterialLayers::default()
        }
    }

    /// The first layer field out of its physical range, as `(field, why)`.
    pub(super) fn layers_range_error(&self) -> Option<(&'static str, &'static str)> {
        use Range::{AtLeastOne, Finite, NonNegative, Unit};
        let colour = |field, c: [f32; 3]| c.map(|v| (field, v, Unit));
        let mut checks = vec![("dispersion", self.dispersion, NonNegative)];
        if let Some(c) = self.specular_color {
            checks.extend(colour("specular_color", c));
        }
        if let Some(c) = &self.clearcoat {
            checks.extend([
                ("clearcoat.factor", c.factor, Unit),
                ("clearcoat.roughness", c.roughness, Unit),
            ]);
        }
        if let Some(s) = &self.sheen {
            checks.extend(colour("sheen.color", s.color));
            checks.push(("sheen.roughness", s.roughness, Unit));
        }
        if let Some(a) = &self.anisotropy {
            checks.extend([
                ("anisotropy.strength", a.strength, Unit),
                ("anisotropy.rotation", a.rotation, Finite),
            ]);
        }
        if let Some(i) = &self.iridescence {
            checks.extend([
                ("iridescence.factor", i.factor, Unit),
                ("iridescence.ior", i.ior, AtLeastOne),
                ("iridescence.thickness", i.thickness, NonNegative),
            ]);
        }
        if let Some(d) = &self.diffuse_transmission {
            checks.push(("diffuse_transmission.factor", d.factor, Unit));
            checks.extend(colour("diffuse_transmission.color", d.color));
        }
        out_of_range(checks)
    }
}

/// A layer's table: the layer it turns on, none at strength 0 (as the glTF loader has it).
trait LayerDesc {
    type Layer;
    fn layer(&self) -> Option<Self::Layer>;
}

fn layer<D: LayerDesc>(desc: &Option<D>) -> Option<D::Layer> {
    desc.as_ref().and_then(D::layer)
}

impl LayerDesc for ClearcoatDesc {
    type Layer = Clearcoat;
    fn layer(&self) -> Option<Clearcoat> {
        (self.factor > 0.0).then_some(Clearcoat {
            factor: self.factor,
            factor_tex: None,
            roughness: self.roughness,
            roughness_tex: None,
            normal_tex: None,
            normal_scale: 1.0,
        })
    }
}

impl LayerDesc for SheenDesc {
    type Layer = Sheen;
    fn layer(&self) -> Option<Sheen> {
        (self.color != [0.0; 3]).then_some(Sheen {
            color: self.color.into(),
            color_tex: None,
            roughness: self.roughness,
            roughness_tex: None,
        })
    }
}

impl LayerDesc for AnisotropyDesc {
    type Layer = Anisotropy;
    fn layer(&self) -> Option<Anisotropy> {
        (self.strength > 0.0).then_some(Anisotropy {
            strength: self.strength,
            rotation: self.rotation.to_radians(),
            texture: None,
        })
    }
}

impl LayerDesc for IridescenceDesc {
    type Layer = Iridescence;
    fn layer(&self) -> Option<Iridescence> {
        (self.factor > 0.0).then_some(Iridescence {
            factor: self.factor,
            factor_tex: None,
            ior: self.ior,
            // Without a thickness texture the film is `thickness_max` thick.
            thickness_min: self.thickness,
            thickness_max: self.thickness,
            thickness_tex: None,
        })
    }
}

impl LayerDesc for DiffuseTransmissionDesc {
    type Layer = DiffuseTransmission;
    fn layer(&self) -> Option<DiffuseTransmission> {
        (self.factor > 0.0).then_some(DiffuseTransmission {
            factor: self.factor,
            factor_tex: None,
            color: self.color.into(),
            color_tex: None,
        })
    }
}
