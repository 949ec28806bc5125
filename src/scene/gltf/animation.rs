//! glTF animations, skins and morph targets into `scene::animation`: channels on node TRS and on morph
//! weights, each skin's joints and inverse bind matrices, and the rest shapes that posing deforms.

use glam::{Mat4, Quat, Vec3, Vec4};
use gltf::accessor::{DataType, Dimensions};

use super::accessor::{component, read_elements, read_f32s, read_vec};
use super::error::GltfError;
use super::{Loader, Placed};
use crate::scene::animated_properties::AnimatedLight;
use crate::scene::animation::{
    Channel, Curve, Interpolation, Morph, Node, Property, Skin, WeightChannel,
};
use crate::scene::Animation;

pub(super) fn interpolation_of(i: gltf::animation::Interpolation) -> Interpolation {
    match i {
        gltf::animation::Interpolation::Linear => Interpolation::Linear,
        gltf::animation::Interpolation::Step => Interpolation::Step,
        gltf::animation::Interpolation::CubicSpline => Interpolation::CubicSpline,
    }
}

impl Loader<'_> {
    /// The file's animation `self.animation` with the skins and morphs placed, or None when nothing
    /// moves; an error when the file has animations but not that one.
    pub(super) fn file_animation(
        &mut self,
        placed: &Placed,
        cameras: Vec<(u32, u32)>,
    ) -> Result<Option<Animation>, GltfError> {
        let doc = self.doc;
        let skins = self.skins(&placed.skinned)?;
        let morphs = self.morphs(&placed.morphed);
        if doc.animations().len() == 0 && skins.is_empty() && morphs.is_empty() {
            return Ok(None);
        }
        let mut a = match doc.animations().nth(self.animation) {
            Some(anim) => {
                let mut a = self.animation(&anim)?;
                a.properties.lights = placed
                    .lights
                    .iter()
                    .map(|l| AnimatedLight {
                        light: l.light,
                        node: l.node,
                        local: l.local.clone(),
                        color: l.color,
                        intensity: l.intensity,
                        color_curve: None,
                        intensity_curve: None,
                    })
                    .collect();
                self.pointer_channels(&anim, placed, &mut a)?;
                a
            }
            None if doc.animations().len() == 0 => Animation::default(),
            None => {
                return Err(GltfError::NoAnimation {
                    index: self.animation,
                    count: doc.animations().len(),
                })
            }
        };
        a.skins = skins;
        a.morphs = morphs;
        a.nodes = doc
            .nodes()
            .map(|n| {
                let (t, r, s) = n.transform().decomposed();
                Node {
                    parent: placed.parent_of[n.index()],
                    translation: Vec3::from(t),
                    rotation: Quat::from_array(r).normalize(),
                    scale: Vec3::from(s),
                }
            })
            .collect();
        a.instances = placed.instances.clone();
        a.cameras = cameras;
        let lights = std::mem::take(&mut a.properties.lights);
        a.properties.lights = lights
            .into_iter()
            .filter(|l| l.color_curve.is_some() || l.intensity_curve.is_some() || a.moves(l.node))
            .collect();
        let moves = !a.channels.is_empty()
            || !a.skins.is_empty()
            || !a.morphs.is_empty()
            || !a.properties.is_empty();
        Ok(moves.then_some(a))
    }

    /// A morph-target weights channel: key times and, per key element, one weight per target.
    pub(super) fn weight_channel(
        &self,
        sampler: &gltf::animation::Sampler,
        node: u32,
    ) -> Result<Option<WeightChannel>, GltfError> {
        let interpolation = interpolation_of(sampler.interpolation());
        let times = self.key_times(&sampler.input())?;
        let output = sampler.output();
        if output.dimensions() != Dimensions::Scalar {
            return Err(GltfError::WeightsNotScalar(output.index()));
        }
        let (dt, norm) = (output.data_type(), output.normalized());
        let values: Vec<f32> = read_elements(&output, self.buffers, |b| component(dt, b, norm))?;
        let elements = times.len() * interpolation.per_key();
        if elements == 0 {
            return Ok(None);
        }
        if !values.len().is_multiple_of(elements) || values.iter().any(|v| !v.is_finite()) {
            return Err(GltfError::WeightsShape {
                weights: values.len(),
                elements,
            });
        }
        Ok(Some(WeightChannel {
            node,
            interpolation,
            width: values.len() / elements,
            times,
            values,
        }))
    }

    /// A sampler's keys as a curve of `width`-component values (1, 3 or 4; floats or normalized
    /// integers), three elements a key for cubic splines, all finite.
    pub(super) fn curve(
        &self,
        sampler: &gltf::animation::Sampler,
        width: usize,
    ) -> Result<Curve, GltfError> {
        let interpolation = interpolation_of(sampler.interpolation());
        let times = self.key_times(&sampler.input())?;
        let output = sampler.output();
        let values = match width {
            1 => padded(read_vec::<1>(&output, self.buffers, "output")?),
            3 => padded(read_vec::<3>(&output, self.buffers, "output")?),
            _ => padded(read_vec::<4>(&output, self.buffers, "output")?),
        };
        let expected = interpolation.per_key() * times.len();
        if values.len() != expected {
            return Err(GltfError::OutputCount {
                values: values.len(),
                keys: times.len(),
                expected,
            });
        }
        if values.iter().any(|v| !v.is_finite()) {
            return Err(GltfError::OutputNotFinite);
        }
        Ok(Curve {
            interpolation,
            times,
            values,
        })
    }

    /// Key times of a sampler input: float SCALAR, finite and increasing.
    pub(super) fn key_times(&self, input: &gltf::Accessor) -> Result<Vec<f32>, GltfError> {
        if input.dimensions() != Dimensions::Scalar || input.data_type() != DataType::F32 {
            return Err(GltfError::KeyTimesType(input.index()));
        }
        let times = read_f32s(input, self.buffers)?;
        if times.iter().any(|t| !t.is_finite()) || times.windows(2).any(|w| w[1] < w[0]) {
            return Err(GltfError::KeyTimesOrder);
        }
        Ok(times)
    }

    /// Meshes with morph targets, with the rest shape to displace; a mesh placed by several nodes
    /// takes the first node's weights.
    fn morphs(&mut self, morphed: &[(u32, u32, Vec<f32>)]) -> Vec<Morph> {
        let mut out: Vec<Morph> = Vec::new();
        for (mesh, node, weights) in morphed {
            if out.iter().any(|m| m.mesh == *mesh) {
                self.scene.warnings.push(format!(
                    "mesh {mesh} with morph targets is placed by several nodes; it takes the first node's weights"
                ));
                continue;
            }
            let Some(targets) = self.morph_attrs.get(mesh) else {
                continue;
            };
            let m = &self.scene.meshes[*mesh as usize];
            let mut default_weights = weights.clone();
            default_weights.resize(targets.len(), 0.0);
            out.push(Morph {
                mesh: *mesh,
                node: *node,
                default_weights,
                targets: targets.clone(),
                rest_positions: m.positions.clone(),
                rest_normals: m.normals.clone(),
            });
        }
        out
    }

    /// Skins of the skinned instances: joints, inverse bind matrices, and the mesh's rest shape with
    /// its per-vertex joints and weights. A mesh skinned by two nodes is posed for the first only.
    fn skins(&mut self, skinned: &[(u32, u32, usize)]) -> Result<Vec<Skin>, GltfError> {
        let mut out: Vec<Skin> = Vec::new();
        for &(instance, mesh, skin_index) in skinned {
            let Some((joints_v, weights)) = self.skin_attrs.get(&mesh) else {
                self.scene.warnings.push(format!(
                    "mesh {mesh}: node has a skin but the primitive has no JOINTS_0/WEIGHTS_0; drawn unskinned"
                ));
                continue;
            };
            if out.iter().any(|s| s.mesh == mesh) {
                self.scene.warnings.push(format!(
                    "mesh {mesh} is skinned by several nodes; posed for the first only"
                ));
                continue;
            }
            let skin = self
                .doc
                .skins()
                .nth(skin_index)
                .ok_or(GltfError::SkinOutOfRange)?;
            let joints: Vec<u32> = skin.joints().map(|n| n.index() as u32).collect();
            let inverse_bind: Vec<Mat4> = match skin.inverse_bind_matrices() {
                Some(acc) => {
                    if acc.dimensions() != Dimensions::Mat4 || acc.data_type() != DataType::F32 {
                        return Err(GltfError::InverseBindType {
                            skin: skin_index,
                            accessor: acc.index(),
                        });
                    }
                    read_elements(&acc, self.buffers, |b| {
                        Mat4::from_cols_array(&std::array::from_fn(|k| {
                            f32::from_le_bytes([b[4 * k], b[4 * k + 1], b[4 * k + 2], b[4 * k + 3]])
                        }))
                    })
                    .map_err(|e| GltfError::from(e).at(format!("skin {skin_index}")))?
                }
                None => vec![Mat4::IDENTITY; joints.len()],
            };
            if inverse_bind.len() < joints.len() {
                return Err(GltfError::InverseBindCount {
                    skin: skin_index,
                    matrices: inverse_bind.len(),
                    joints: joints.len(),
                });
            }
            if let Some(bad) = joints_v
                .iter()
                .flatten()
                .find(|&&j| j as usize >= joints.len())
            {
                return Err(GltfError::JointOutOfRange {
                    mesh,
                    joint: *bad,
                    skin: skin_index,
                    joints: joints.len(),
                });
            }
            let m = &self.scene.meshes[mesh as usize];
            out.push(Skin {
                instance,
                mesh,
                joints,
                inverse_bind,
                vertex_joints: joints_v.clone(),
                vertex_weights: weights.clone(),
                rest_positions: m.positions.clone(),
                rest_normals: m.normals.clone(),
            });
        }
        Ok(out)
    }

    /// The channels of one animation on node translation, rotation and scale (morph weights are
    /// skipped with a warning); the caller adds the node hierarchy.
    fn animation(&mut self, anim: &gltf::Animation) -> Result<Animation, GltfError> {
        let label = match anim.name() {
            Some(n) => format!("animation {} ('{n}')", anim.index()),
            None => format!("animation {}", anim.index()),
        };
        let mut out = Animation {
            name: anim.name().unwrap_or("").to_owned(),
            ..Default::default()
        };
        for (ci, ch) in anim.channels().enumerate() {
            let property = match ch.target().property() {
                gltf::animation::Property::Translation => Property::Translation,
                gltf::animation::Property::Rotation => Property::Rotation,
                gltf::animation::Property::Scale => Property::Scale,
                gltf::animation::Property::MorphTargetWeights => {
                    let c = self
                        .weight_channel(&ch.sampler(), ch.target().node().index() as u32)
                        .map_err(|e| e.at(format!("{label}, channel {ci}")))?;
                    out.weights.extend(c);
                    continue;
                }
            };
            let at = |e: GltfError| e.at(format!("{label}, channel {ci}"));
            let width = if property == Property::Rotation { 4 } else { 3 };
            let curve = self.curve(&ch.sampler(), width).map_err(at)?;
            if curve.times.is_empty() {
                continue;
            }
            out.channels.push(Channel {
                node: ch.target().node().index() as u32,
                property,
                curve,
            });
        }
        Ok(out)
    }
}

/// `N`-component values in `Vec4`s, the rest zero.
fn padded<const N: usize>(values: Vec<[f32; N]>) -> Vec<Vec4> {
    values
        .into_iter()
        .map(|a| {
            let mut v = Vec4::ZERO;
            v.as_mut()[..N].copy_from_slice(&a);
            v
        })
        .collect()
}
