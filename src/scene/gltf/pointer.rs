//! KHR_animation_pointer: channels that target a JSON pointer instead of a node, taken out of the
//! JSON before the gltf crate parses it (it requires a node on every channel) and turned into curves.
//!
//! Node TRS and weights pointers become ordinary node channels; material factors, light colour and
//! intensity, and camera yfov become `AnimatedProperties`; any other pointer is held at its rest
//! value with one warning naming it.

use std::borrow::Cow;

use glam::Vec3;

use super::error::GltfError;
use super::Loader;
use crate::scene::animated_properties::{AnimatedMaterial, MaterialProperty};
use crate::scene::animation::{Channel, Curve, Property};

/// One pointer channel as the file gives it.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct PointerChannel {
    pub animation: usize,
    pub sampler: usize,
    pub pointer: String,
}

/// What a pointer reaches, of what glint renders.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Target {
    Node(u32, Property),
    Weights(u32),
    Material(u32, MaterialProperty),
    LightColor(u32),
    LightIntensity(u32),
    CameraYfov(u32),
}

impl Target {
    /// The target of a JSON pointer (RFC 6901 escapes undone), or None for one glint does not
    /// animate.
    pub fn parse(pointer: &str) -> Option<Target> {
        let rest = pointer.strip_prefix('/')?;
        let parts: Vec<String> = rest
            .split('/')
            .map(|p| p.replace("~1", "/").replace("~0", "~"))
            .collect();
        let index = |s: &str| s.parse::<u32>().ok();
        let parts: Vec<&str> = parts.iter().map(String::as_str).collect();
        Some(match parts.as_slice() {
            ["nodes", n, "translation"] => Target::Node(index(n)?, Property::Translation),
            ["nodes", n, "rotation"] => Target::Node(index(n)?, Property::Rotation),
            ["nodes", n, "scale"] => Target::Node(index(n)?, Property::Scale),
            ["nodes", n, "weights"] => Target::Weights(index(n)?),
            ["materials", m, path @ ..] => {
                Target::Material(index(m)?, MaterialProperty::at(&path.join("/"))?)
            }
            ["extensions", "KHR_lights_punctual", "lights", l, "color"] => {
                Target::LightColor(index(l)?)
            }
            ["extensions", "KHR_lights_punctual", "lights", l, "intensity"] => {
                Target::LightIntensity(index(l)?)
            }
            ["cameras", c, "perspective", "yfov"] => Target::CameraYfov(index(c)?),
            _ => return None,
        })
    }

    /// Components per key value.
    fn width(self) -> usize {
        match self {
            Target::Node(_, Property::Rotation) => 4,
            Target::Node(..) | Target::LightColor(_) => 3,
            Target::Material(_, p) => p.width(),
            Target::Weights(_) | Target::LightIntensity(_) | Target::CameraYfov(_) => 1,
        }
    }
}

/// The JSON without its pointer channels, and those channels. Files that never name the extension
/// are passed through untouched (and unparsed).
pub(super) fn extract(json: &[u8]) -> Result<(Cow<'_, [u8]>, Vec<PointerChannel>), GltfError> {
    const NAME: &[u8] = b"KHR_animation_pointer";
    if !json.windows(NAME.len()).any(|w| w == NAME) {
        return Ok((Cow::Borrowed(json), Vec::new()));
    }
    let mut root: serde_json::Value = serde_json::from_slice(json).map_err(GltfError::Json)?;
    let mut out = Vec::new();
    if let Some(anims) = root.get_mut("animations").and_then(|a| a.as_array_mut()) {
        for (ai, anim) in anims.iter_mut().enumerate() {
            let Some(channels) = anim.get_mut("channels").and_then(|c| c.as_array_mut()) else {
                continue;
            };
            channels.retain(|ch| {
                let target = &ch["target"];
                if target["path"] != "pointer" {
                    return true;
                }
                let pointer = target["extensions"]["KHR_animation_pointer"]["pointer"].as_str();
                if let (Some(sampler), Some(pointer)) = (ch["sampler"].as_u64(), pointer) {
                    out.push(PointerChannel {
                        animation: ai,
                        sampler: sampler as usize,
                        pointer: pointer.to_owned(),
                    });
                }
                false
            });
        }
    }
    let bytes = serde_json::to_vec(&root).map_err(GltfError::Json)?;
    Ok((Cow::Owned(bytes), out))
}

impl Loader<'_> {
    /// Adds animation `anim`'s pointer channels to `out`: node ones as node channels, the rest as
    /// animated properties (lights and cameras through `placed`).
    pub(super) fn pointer_channels(
        &mut self,
        anim: &gltf::Animation,
        placed: &super::Placed,
        out: &mut crate::scene::Animation,
    ) -> Result<(), GltfError> {
        let doc = self.doc;
        let mine: Vec<PointerChannel> = self
            .pointers
            .iter()
            .filter(|p| p.animation == anim.index())
            .cloned()
            .collect();
        for (k, ch) in mine.into_iter().enumerate() {
            let label = format!(
                "animation {}, pointer channel {k} ('{}')",
                anim.index(),
                ch.pointer
            );
            let target = Target::parse(&ch.pointer).filter(|t| self.target_exists(*t));
            let Some(target) = target else {
                self.scene.warnings.push(format!(
                    "{label}: glint does not animate what it points at; held at its rest value"
                ));
                continue;
            };
            let Some(sampler) = anim.samplers().nth(ch.sampler) else {
                return Err(GltfError::PointerSampler {
                    at: label,
                    sampler: ch.sampler,
                });
            };
            if let Target::Weights(node) = target {
                let w = self
                    .weight_channel(&sampler, node)
                    .map_err(|e| e.at(label.clone()))?;
                out.weights.extend(w);
                continue;
            }
            let curve = self
                .curve(&sampler, target.width())
                .map_err(|e| e.at(label.clone()))?;
            if curve.times.is_empty() {
                continue;
            }
            attach_curve(doc, out, placed, target, curve);
        }
        Ok(())
    }

    /// Whether the element a target names is in the file.
    fn target_exists(&self, t: Target) -> bool {
        let doc = self.doc;
        match t {
            Target::Node(n, _) | Target::Weights(n) => (n as usize) < doc.nodes().len(),
            Target::Material(m, _) => (m as usize) < doc.materials().len(),
            Target::LightColor(l) | Target::LightIntensity(l) => doc
                .lights()
                .is_some_and(|mut ls| ls.nth(l as usize).is_some()),
            Target::CameraYfov(c) => doc.cameras().nth(c as usize).is_some_and(|c| {
                matches!(c.projection(), gltf::camera::Projection::Perspective(_))
            }),
        }
    }
}

/// The animated entry of material `m`, made (with its rest emissive factor and strength) on first use.
fn material_entry<'a>(
    doc: &gltf::Document,
    out: &'a mut crate::scene::Animation,
    m: u32,
) -> &'a mut AnimatedMaterial {
    let list = &mut out.properties.materials;
    let at = match list.iter().position(|e| e.material == m) {
        Some(i) => i,
        None => {
            let mat = doc.materials().nth(m as usize);
            list.push(AnimatedMaterial {
                material: m,
                emissive_factor: mat
                    .as_ref()
                    .map_or(Vec3::ZERO, |m| Vec3::from(m.emissive_factor())),
                emissive_strength: mat
                    .as_ref()
                    .and_then(|m| m.emissive_strength())
                    .unwrap_or(1.0),
                curves: Vec::new(),
            });
            list.len() - 1
        }
    };
    &mut list[at]
}

/// Puts an animation pointer's curve where its target's property is animated: a node channel, a
/// material's curves, the lights and cameras placed from the animated glTF light or camera.
fn attach_curve(
    doc: &gltf::Document,
    out: &mut crate::scene::Animation,
    placed: &super::Placed,
    target: Target,
    curve: Curve,
) {
    match target {
        Target::Node(node, property) => out.channels.push(Channel {
            node,
            property,
            curve,
        }),
        Target::Material(m, property) => material_entry(doc, out, m).curves.push((property, curve)),
        Target::LightColor(l) | Target::LightIntensity(l) => {
            // Before the caller filters them, the animated lights are `placed.lights`.
            for (light, p) in out.properties.lights.iter_mut().zip(&placed.lights) {
                if p.source != l as usize {
                    continue;
                }
                if matches!(target, Target::LightColor(_)) {
                    light.color_curve = Some(curve.clone());
                } else {
                    light.intensity_curve = Some(curve.clone());
                }
            }
        }
        Target::CameraYfov(c) => {
            for (scene_camera, (gltf_camera, _)) in placed.cameras.iter().enumerate() {
                if *gltf_camera == c as usize {
                    out.properties.cameras.push(
                        crate::scene::animated_properties::AnimatedCamera {
                            camera: scene_camera as u32,
                            yfov: curve.clone(),
                        },
                    );
                }
            }
        }
        Target::Weights(_) => unreachable!("weights are handled above"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pointers_parse_to_their_targets() {
        let cases = [
            (
                "/nodes/3/translation",
                Some(Target::Node(3, Property::Translation)),
            ),
            (
                "/nodes/0/rotation",
                Some(Target::Node(0, Property::Rotation)),
            ),
            ("/nodes/12/weights", Some(Target::Weights(12))),
            (
                "/materials/2/pbrMetallicRoughness/baseColorFactor",
                Some(Target::Material(2, MaterialProperty::BaseColor)),
            ),
            (
                "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength",
                Some(Target::Material(0, MaterialProperty::EmissiveStrength)),
            ),
            (
                "/extensions/KHR_lights_punctual/lights/1/color",
                Some(Target::LightColor(1)),
            ),
            (
                "/extensions/KHR_lights_punctual/lights/1/intensity",
                Some(Target::LightIntensity(1)),
            ),
            ("/cameras/4/perspective/yfov", Some(Target::CameraYfov(4))),
            ("/materials/0/occlusionTexture/strength", None),
            ("/nodes/x/translation", None),
            ("/nodes/-1/scale", None),
            ("nodes/0/scale", None),
            ("", None),
        ];
        for (p, want) in cases {
            assert_eq!(Target::parse(p), want, "{p}");
        }
    }

    #[test]
    fn extract_takes_pointer_channels_only() {
        let json = br#"{"asset":{"version":"2.0"},"animations":[{"channels":[
            {"sampler":0,"target":{"node":0,"path":"translation"}},
            {"sampler":1,"target":{"path":"pointer","extensions":{"KHR_animation_pointer":{"pointer":"/materials/0/emissiveFactor"}}}},
            {"sampler":2,"target":{"path":"pointer"}}],"samplers":[]}],
            "extensionsUsed":["KHR_animation_pointer"]}"#;
        let (rest, ptrs) = extract(json).unwrap();
        assert_eq!(
            ptrs,
            vec![PointerChannel {
                animation: 0,
                sampler: 1,
                pointer: "/materials/0/emissiveFactor".into()
            }]
        );
        let v: serde_json::Value = serde_json::from_slice(&rest).unwrap();
        assert_eq!(v["animations"][0]["channels"].as_array().unwrap().len(), 1);
        // Without the extension's name the bytes pass through as they are.
        let plain = br#"{"asset":{"version":"2.0"}}"#;
        assert!(matches!(extract(plain).unwrap().0, Cow::Borrowed(b) if b == plain));
        assert!(extract(b"{\"KHR_animation_pointer\": [").is_err());
    }
}
