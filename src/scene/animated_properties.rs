//! Animated properties beyond node transforms (what glTF's KHR_animation_pointer reaches): material
//! factors, light colour and intensity (lights also follow their node), and camera field of view.
//!
//! They are applied once per frame, at the middle of the shutter, as morphs are: a factor does not
//! blur. Each animated object keeps the rest values of what is stored combined in the scene
//! (emissive factor x strength, light colour x intensity), so animating one part keeps the other.

use glam::{Mat4, Vec3, Vec4};

use super::animation::{Animation, Curve};
use super::{AlphaMode, DirectionalLight, Light, PointLight, Projection, Scene, SpotLight};

/// A material factor glint renders, by its glTF name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MaterialProperty {
    BaseColor,
    Metallic,
    Roughness,
    EmissiveFactor,
    EmissiveStrength,
    AlphaCutoff,
    NormalScale,
    Transmission,
    Ior,
    Thickness,
    AttenuationDistance,
    AttenuationColor,
}

impl MaterialProperty {
    /// The property at a glTF material path (after `/materials/N/`), or None for one glint does
    /// not animate.
    pub fn at(path: &str) -> Option<Self> {
        Some(match path {
            "pbrMetallicRoughness/baseColorFactor" => Self::BaseColor,
            "pbrMetallicRoughness/metallicFactor" => Self::Metallic,
            "pbrMetallicRoughness/roughnessFactor" => Self::Roughness,
            "emissiveFactor" => Self::EmissiveFactor,
            "extensions/KHR_materials_emissive_strength/emissiveStrength" => Self::EmissiveStrength,
            "alphaCutoff" => Self::AlphaCutoff,
            "normalTexture/scale" => Self::NormalScale,
            "extensions/KHR_materials_transmission/transmissionFactor" => Self::Transmission,
            "extensions/KHR_materials_ior/ior" => Self::Ior,
            "extensions/KHR_materials_volume/thicknessFactor" => Self::Thickness,
            "extensions/KHR_materials_volume/attenuationDistance" => Self::AttenuationDistance,
            "extensions/KHR_materials_volume/attenuationColor" => Self::AttenuationColor,
            _ => return None,
        })
    }

    /// Components per value (glTF's accessor type for it).
    pub fn width(self) -> usize {
        match self {
            Self::BaseColor => 4,
            Self::EmissiveFactor | Self::AttenuationColor => 3,
            _ => 1,
        }
    }
}

/// One material's animated factors, with the rest values of the emissive product.
#[derive(Clone, Debug)]
pub struct AnimatedMaterial {
    pub material: u32,
    pub emissive_factor: Vec3,
    pub emissive_strength: f32,
    pub curves: Vec<(MaterialProperty, Curve)>,
}

/// A punctual light of the file as placed in the scene: its node, its shape in the node's frame at
/// unit colour and intensity, and the curves (if any) of its colour and intensity.
#[derive(Clone, Debug)]
pub struct AnimatedLight {
    /// Index in `Scene::lights`.
    pub light: u32,
    pub node: u32,
    /// The light in its node's frame, its intensity 1.
    pub local: Light,
    pub color: Vec3,
    pub intensity: f32,
    pub color_curve: Option<Curve>,
    pub intensity_curve: Option<Curve>,
}

/// A camera's animated vertical field of view (radians).
#[derive(Clone, Debug)]
pub struct AnimatedCamera {
    /// Index in `Scene::cameras`.
    pub camera: u32,
    pub yfov: Curve,
}

/// Everything of a scene animated besides node transforms and morph weights.
#[derive(Clone, Debug, Default)]
pub struct AnimatedProperties {
    pub materials: Vec<AnimatedMaterial>,
    /// Every placed punctual light that moves with its node or has a curve.
    pub lights: Vec<AnimatedLight>,
    pub cameras: Vec<AnimatedCamera>,
}

impl AnimatedProperties {
    pub fn is_empty(&self) -> bool {
        self.materials.is_empty() && self.lights.is_empty() && self.cameras.is_empty()
    }

    /// Time of the last key of any curve.
    pub fn duration(&self) -> f32 {
        let materials = self
            .materials
            .iter()
            .flat_map(|m| m.curves.iter().map(|c| &c.1));
        let lights = self
            .lights
            .iter()
            .flat_map(|l| l.color_curve.iter().chain(&l.intensity_curve));
        let cameras = self.cameras.iter().map(|c| &c.yfov);
        materials
            .chain(lights)
            .chain(cameras)
            .map(Curve::last_time)
            .fold(0.0, f32::max)
    }
}

/// Sets the scene's animated properties to their values at animation time `t` (lights also to
/// their node's place then).
pub fn apply(scene: &mut Scene, anim: &Animation, t: f32) {
    let props = &anim.properties;
    for m in &props.materials {
        if let Some(mat) = scene.materials.get_mut(m.material as usize) {
            apply_material(mat, m, t);
        }
    }
    for l in &props.lights {
        let color = l
            .color_curve
            .as_ref()
            .map_or(l.color, |c| c.sample(t).truncate());
        let intensity = l
            .intensity_curve
            .as_ref()
            .map_or(l.intensity, |c| c.sample(t).x);
        let power = (color * intensity).max(Vec3::ZERO);
        let world: Mat4 = anim.world(l.node, t);
        let placed = with_power(l.local.clone(), power).transformed(&world);
        if let Some(slot) = scene.lights.get_mut(l.light as usize) {
            if power.is_finite() && world.is_finite() && world.determinant() != 0.0 {
                *slot = placed;
            }
        }
    }
    for c in &props.cameras {
        if let Some(cam) = scene.cameras.get_mut(c.camera as usize) {
            if let Projection::Perspective { yfov, .. } = &mut cam.projection {
                let v = c.yfov.sample(t).x;
                if v.is_finite() {
                    *yfov = v.clamp(1e-4, std::f32::consts::PI - 1e-4);
                }
            }
        }
    }
}

fn apply_material(mat: &mut super::Material, m: &AnimatedMaterial, t: f32) {
    let (mut factor, mut strength, mut emissive) = (m.emissive_factor, m.emissive_strength, false);
    for (property, curve) in &m.curves {
        let v = curve.sample(t);
        if !v.is_finite() {
            continue;
        }
        let unit = v.x.clamp(0.0, 1.0);
        match property {
            MaterialProperty::BaseColor => mat.base_color = v.clamp(Vec4::ZERO, Vec4::ONE),
            MaterialProperty::Metallic => mat.metallic = unit,
            MaterialProperty::Roughness => mat.roughness = unit,
            MaterialProperty::EmissiveFactor => (factor, emissive) = (v.truncate(), true),
            MaterialProperty::EmissiveStrength => (strength, emissive) = (v.x, true),
            MaterialProperty::AlphaCutoff => {
                if let AlphaMode::Mask(c) = &mut mat.alpha_mode {
                    *c = v.x;
                }
            }
            MaterialProperty::NormalScale => mat.normal_scale = v.x,
            MaterialProperty::Transmission => mat.transmission = unit,
            MaterialProperty::Ior => mat.ior = v.x.max(1.0),
            MaterialProperty::Thickness => mat.thickness = v.x.max(0.0),
            MaterialProperty::AttenuationDistance => {
                mat.attenuation_distance = if v.x > 0.0 { v.x } else { f32::INFINITY }
            }
            MaterialProperty::AttenuationColor => {
                mat.attenuation_color = v.truncate().clamp(Vec3::ZERO, Vec3::ONE)
            }
        }
    }
    if emissive {
        mat.emissive = (factor.clamp(Vec3::ZERO, Vec3::ONE) * strength.max(0.0)).max(Vec3::ZERO);
    }
}

/// A punctual light with its intensity (W/sr, or irradiance for a directional light) set.
fn with_power(light: Light, power: Vec3) -> Light {
    match light {
        Light::Point(l) => Light::Point(PointLight {
            intensity: power,
            ..l
        }),
        Light::Spot(l) => Light::Spot(SpotLight {
            intensity: power,
            ..l
        }),
        Light::Directional(l) => Light::Directional(DirectionalLight {
            irradiance: power,
            ..l
        }),
        other => other,
    }
}
