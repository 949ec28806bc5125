//! Keyframe animation (glTF): samplers (step, linear with slerp, cubic spline) on node translation,
//! rotation and scale, and the node hierarchy that turns them into world transforms at any time, from
//! which `pose` gives moving instances and cameras their `Motion` over the shutter.

use glam::{Mat4, Quat, Vec3, Vec4};

use super::animated_properties::AnimatedProperties;
use super::{Aabb, Scene};
use crate::geometry::motion::{Motion, MOTION_TOLERANCE};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    Step,
    /// Linear; spherical linear for rotations.
    Linear,
    /// Cubic Hermite spline; each key holds (in-tangent, value, out-tangent).
    CubicSpline,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Property {
    Translation,
    Rotation,
    Scale,
}

/// Keyed values of one property: key times (seconds, increasing) and values (three per key for
/// cubic splines), each in a `Vec4` (xyz, a quaternion's xyzw, or a factor in x, the rest zero).
#[derive(Clone, Debug)]
pub struct Curve {
    pub interpolation: Interpolation,
    pub times: Vec<f32>,
    pub values: Vec<Vec4>,
}

impl Curve {
    /// The curve at time `t` (clamped to the first and last keys, as glTF says), between keys by
    /// `lerp`.
    fn sample_by(&self, t: f32, lerp: impl Fn(Vec4, Vec4, f32) -> Vec4) -> Vec4 {
        interpolate(
            &self.times,
            self.interpolation,
            t,
            |k, part| self.values[k * self.interpolation.per_key() + part],
            lerp,
        )
    }

    /// The curve at time `t`, components interpolated linearly.
    pub fn sample(&self, t: f32) -> Vec4 {
        self.sample_by(t, |a, b, s| a.lerp(b, s))
    }

    /// The curve of a rotation at time `t`: a unit quaternion, spherically interpolated.
    pub fn sample_rotation(&self, t: f32) -> Vec4 {
        let v = self.sample_by(t, |a, b, s| {
            Vec4::from(
                Quat::from_vec4(a)
                    .normalize()
                    .slerp(Quat::from_vec4(b).normalize(), s),
            )
        });
        Vec4::from(Quat::from_vec4(v).normalize())
    }

    pub fn last_time(&self) -> f32 {
        self.times.last().copied().unwrap_or(0.0)
    }
}

/// One animated property of one node.
#[derive(Clone, Debug)]
pub struct Channel {
    pub node: u32,
    pub property: Property,
    pub curve: Curve,
}

impl Channel {
    /// The channel's value at time `t`.
    pub fn sample(&self, t: f32) -> Vec4 {
        if self.property == Property::Rotation {
            self.curve.sample_rotation(t)
        } else {
            self.curve.sample(t)
        }
    }
}

impl Interpolation {
    /// Output elements per key: (in-tangent, value, out-tangent) for cubic splines.
    pub fn per_key(self) -> usize {
        match self {
            Interpolation::CubicSpline => 3,
            _ => 1,
        }
    }
}

/// The glTF sampler formulas over keys at `times`: `part(k, p)` is element `p` of key `k` (0 for
/// step and linear; 0 in-tangent, 1 value, 2 out-tangent for cubic splines). Clamped outside the keys.
fn interpolate<T>(
    times: &[f32],
    interpolation: Interpolation,
    t: f32,
    part: impl Fn(usize, usize) -> T,
    lerp: impl Fn(T, T, f32) -> T,
) -> T
where
    T: Copy + std::ops::Add<Output = T> + std::ops::Mul<f32, Output = T>,
{
    let n = times.len();
    let value = if interpolation == Interpolation::CubicSpline {
        1
    } else {
        0
    };
    let key = |k: usize| part(k, value);
    if n <= 1 || t <= times[0] || t.is_nan() {
        return key(0);
    }
    if t >= times[n - 1] {
        return key(n - 1);
    }
    // The last key at or before t.
    let k = times.partition_point(|&x| x <= t) - 1;
    let dt = times[k + 1] - times[k];
    let s = if dt > 0.0 { (t - times[k]) / dt } else { 0.0 };
    match interpolation {
        Interpolation::Step => key(k),
        Interpolation::Linear => lerp(key(k), key(k + 1), s),
        Interpolation::CubicSpline => {
            let (s2, s3) = (s * s, s * s * s);
            key(k) * (2.0 * s3 - 3.0 * s2 + 1.0)
                + part(k, 2) * (dt * (s3 - 2.0 * s2 + s))
                + key(k + 1) * (-2.0 * s3 + 3.0 * s2)
                + part(k + 1, 0) * (dt * (s3 - s2))
        }
    }
}

/// Morph-target weights of one node over time: `width` weights per key element.
#[derive(Clone, Debug)]
pub struct WeightChannel {
    pub node: u32,
    pub interpolation: Interpolation,
    pub times: Vec<f32>,
    pub width: usize,
    pub values: Vec<f32>,
}

impl WeightChannel {
    pub fn sample(&self, t: f32) -> Vec<f32> {
        let per = self.interpolation.per_key();
        (0..self.width)
            .map(|i| {
                interpolate(
                    &self.times,
                    self.interpolation,
                    t,
                    |k, part| self.values[(k * per + part) * self.width + i],
                    |a: f32, b: f32, s| a + (b - a) * s,
                )
            })
            .collect()
    }
}

/// A mesh with morph targets: rest shape plus the weighted sum of the targets' displacements.
#[derive(Clone, Debug)]
pub struct Morph {
    pub mesh: u32,
    /// The node whose weights drive it (animated through `Animation::weights`).
    pub node: u32,
    /// Weights when no channel animates them (the node's, else the mesh's, else zero).
    pub default_weights: Vec<f32>,
    /// Per target: position and normal displacements (normals empty when the file has none).
    pub targets: Vec<(Vec<Vec3>, Vec<Vec3>)>,
    pub rest_positions: Vec<Vec3>,
    pub rest_normals: Vec<Vec3>,
}

impl Morph {
    /// Positions and normals with the weights at animation time `t`.
    pub fn posed(&self, anim: &Animation, t: f32) -> (Vec<Vec3>, Vec<Vec3>) {
        let weights = anim
            .weights
            .iter()
            .find(|w| w.node == self.node)
            .map_or_else(|| self.default_weights.clone(), |w| w.sample(t));
        let mut pos = self.rest_positions.clone();
        let mut nrm = self.rest_normals.clone();
        for ((dp, dn), &w) in self.targets.iter().zip(&weights) {
            if w == 0.0 {
                continue;
            }
            for (p, d) in pos.iter_mut().zip(dp) {
                *p += *d * w;
            }
            for (n, d) in nrm.iter_mut().zip(dn) {
                *n += *d * w;
            }
        }
        for (n, r) in nrm.iter_mut().zip(&self.rest_normals) {
            let u = n.normalize_or_zero();
            *n = if u == Vec3::ZERO { *r } else { u };
        }
        (pos, nrm)
    }
}

/// A node of the file's hierarchy: its parent and rest transform (TRS; a node given by a matrix is
/// decomposed, which glTF allows only for nodes that are not animated).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    pub parent: Option<u32>,
    pub translation: Vec3,
    pub rotation: Quat,
    pub scale: Vec3,
}

/// One animation of a file, with what it moves: instances and cameras by the node they hang from.
#[derive(Clone, Debug, Default)]
pub struct Animation {
    pub name: String,
    pub nodes: Vec<Node>,
    pub channels: Vec<Channel>,
    /// (instance index, node index) of every instance below a node.
    pub instances: Vec<(u32, u32)>,
    /// (camera index, node index) of every camera.
    pub cameras: Vec<(u32, u32)>,
    /// Skinned meshes, posed by `pose` from their joints' world transforms.
    pub skins: Vec<Skin>,
    /// Morph-target weight channels.
    pub weights: Vec<WeightChannel>,
    /// Meshes with morph targets, posed by `pose` (before skinning).
    pub morphs: Vec<Morph>,
    /// Material factors, punctual lights and camera fields of view that change over time.
    pub properties: AnimatedProperties,
}

/// A mesh deformed by a skeleton: vertex = sum of weight_k (joint_k world x inverse bind_k) x rest.
/// The instance's own node transform is ignored, as glTF says for skinned meshes.
#[derive(Clone, Debug)]
pub struct Skin {
    pub instance: u32,
    pub mesh: u32,
    /// Joint nodes, indexed by the vertices' joint numbers.
    pub joints: Vec<u32>,
    pub inverse_bind: Vec<Mat4>,
    pub vertex_joints: Vec<[u16; 4]>,
    pub vertex_weights: Vec<Vec4>,
    /// The mesh as the file gives it (bind shape).
    pub rest_positions: Vec<Vec3>,
    pub rest_normals: Vec<Vec3>,
}

impl Skin {
    /// Positions and normals posed at animation time `t`, from the rest shape `rest` (positions,
    /// normals: the file's, or morphed).
    pub fn posed(
        &self,
        anim: &Animation,
        t: f32,
        rest: (&[Vec3], &[Vec3]),
    ) -> (Vec<Vec3>, Vec<Vec3>) {
        let mats: Vec<Mat4> = self
            .joints
            .iter()
            .zip(&self.inverse_bind)
            .map(|(&j, ib)| anim.world(j, t) * *ib)
            .collect();
        let mut pos = Vec::with_capacity(rest.0.len());
        let mut nrm = Vec::with_capacity(rest.0.len());
        for (k, (&p, &n)) in rest.0.iter().zip(rest.1).enumerate() {
            let w = self.vertex_weights[k];
            let total = w.x + w.y + w.z + w.w;
            let m = if total > 0.0 {
                let j = self.vertex_joints[k];
                (mats[j[0] as usize] * w.x
                    + mats[j[1] as usize] * w.y
                    + mats[j[2] as usize] * w.z
                    + mats[j[3] as usize] * w.w)
                    * (1.0 / total)
            } else {
                Mat4::IDENTITY
            };
            pos.push(m.transform_point3(p));
            let nm = glam::Mat3::from_mat4(m).inverse().transpose();
            let n2 = (nm * n).normalize_or_zero();
            nrm.push(if n2 == Vec3::ZERO || !n2.is_finite() {
                n
            } else {
                n2
            });
        }
        (pos, nrm)
    }
}

impl Animation {
    /// The node's transform relative to its parent at time `t`.
    pub fn local(&self, node: u32, t: f32) -> Mat4 {
        let n = &self.nodes[node as usize];
        let (mut tr, mut rot, mut sc) = (n.translation, n.rotation, n.scale);
        for c in self.channels.iter().filter(|c| c.node == node) {
            let v = c.sample(t);
            match c.property {
                Property::Translation => tr = v.truncate(),
                Property::Rotation => rot = Quat::from_vec4(v),
                Property::Scale => sc = v.truncate(),
            }
        }
        Mat4::from_scale_rotation_translation(sc, rot, tr)
    }

    /// The node's world transform at time `t`.
    pub fn world(&self, node: u32, t: f32) -> Mat4 {
        let mut m = self.local(node, t);
        let mut p = self.nodes[node as usize].parent;
        // Bounded by the node count, so a malformed parent cycle cannot hang.
        for _ in 0..self.nodes.len() {
            let Some(q) = p else { break };
            m = self.local(q, t) * m;
            p = self.nodes[q as usize].parent;
        }
        m
    }

    /// Whether the node or one of its ancestors is animated.
    pub fn moves(&self, node: u32) -> bool {
        let mut p = Some(node);
        for _ in 0..=self.nodes.len() {
            let Some(q) = p else { return false };
            if self.channels.iter().any(|c| c.node == q) {
                return true;
            }
            p = self.nodes[q as usize].parent;
        }
        false
    }

    /// Time of the last key (the animation's length in seconds).
    pub fn duration(&self) -> f32 {
        self.channels
            .iter()
            .map(|c| c.curve.last_time())
            .chain(self.weights.iter().filter_map(|w| w.times.last().copied()))
            .fold(self.properties.duration(), f32::max)
    }
}

/// Poses the scene's animation at `frame_time` seconds and gives every instance and camera that moves
/// during `shutter` (seconds relative to the frame time) its `Motion`. Ray time `u` in [0, 1] is
/// animation time `frame_time + shutter[0] + u (shutter[1] - shutter[0])`. Without an animation
/// nothing changes; with a closed shutter (`open == close`) the scene is posed and nothing moves.
pub fn pose(scene: &mut Scene, frame_time: f32, shutter: [f32; 2]) {
    let Some(anim) = scene.animation.take() else {
        return;
    };
    let t_of = |u: f32| frame_time + shutter[0] + u * (shutter[1] - shutter[0]);
    let open = shutter[1] > shutter[0];
    pose_instances(scene, &anim, t_of, open);
    // Morphs, then skins, are posed once per frame, in the middle of the shutter (no per-vertex
    // motion blur).
    deform_meshes(scene, &anim, t_of(0.5));
    pose_cameras(scene, &anim, t_of, open);
    // Factors, lights and fields of view too: once, mid-shutter.
    super::animated_properties::apply(scene, &anim, t_of(0.5));
    scene.animation = Some(anim);
}

/// Places every moving rigid instance at ray time 0, with its motion when the shutter is `open`
/// (skinned instances are left to `deform_meshes`). `t_of` maps ray time to animation time.
fn pose_instances(scene: &mut Scene, anim: &Animation, t_of: impl Fn(f32) -> f32, open: bool) {
    for &(i, node) in &anim.instances {
        if !anim.moves(node) || anim.skins.iter().any(|s| s.instance == i) {
            continue;
        }
        let Some(inst) = scene.instances.get_mut(i as usize) else {
            continue;
        };
        let object = scene.meshes[inst.mesh as usize].bounds();
        let world = |u: f32| anim.world(node, t_of(u));
        let to_world = world(0.0);
        if to_world.is_finite() && to_world.determinant() != 0.0 {
            *inst = super::Instance::new(inst.mesh, to_world);
        }
        if open {
            inst.motion = Motion::of_object(world, &object).filter(|m| {
                m.steps
                    .iter()
                    .all(|s| s.is_finite() && s.determinant() != 0.0)
            });
        }
    }
}

/// Replaces the vertices of morphed and skinned meshes by their pose at animation time `t`
/// (a skin deforms its mesh's morphed pose where it has one); skinned instances lose their node
/// transform.
fn deform_meshes(scene: &mut Scene, anim: &Animation, t: f32) {
    let mut deformed: Vec<(u32, Vec<Vec3>, Vec<Vec3>)> = anim
        .morphs
        .iter()
        .map(|m| {
            let (p, n) = m.posed(anim, t);
            (m.mesh, p, n)
        })
        .collect();
    for skin in &anim.skins {
        let (pos, nrm) = match deformed.iter().position(|d| d.0 == skin.mesh) {
            Some(i) => {
                let (_, p, n) = deformed.swap_remove(i);
                skin.posed(anim, t, (&p, &n))
            }
            None => skin.posed(anim, t, (&skin.rest_positions, &skin.rest_normals)),
        };
        deformed.push((skin.mesh, pos, nrm));
        if let Some(inst) = scene.instances.get_mut(skin.instance as usize) {
            *inst = super::Instance::new(inst.mesh, Mat4::IDENTITY);
        }
    }
    for (mesh, pos, nrm) in deformed {
        if pos.iter().any(|p| !p.is_finite()) {
            continue;
        }
        let mesh = &mut scene.meshes[mesh as usize];
        mesh.positions = pos;
        mesh.normals = nrm;
        // Tangents follow poorly under blending; the surface falls back to UV-derived ones.
        mesh.tangents.clear();
    }
}

/// Places every moving camera (rigidly) at ray time 0, with its motion when the shutter is
/// `open`.
fn pose_cameras(scene: &mut Scene, anim: &Animation, t_of: impl Fn(f32) -> f32, open: bool) {
    let unit = Aabb {
        min: Vec3::splat(-1.0),
        max: Vec3::splat(1.0),
    };
    for &(i, node) in &anim.cameras {
        if !anim.moves(node) {
            continue;
        }
        let Some(cam) = scene.cameras.get_mut(i as usize) else {
            continue;
        };
        cam.to_world = rigid(anim.world(node, t_of(0.0)));
        if open {
            cam.motion = Motion::sample(
                |u| rigid(anim.world(node, t_of(u))),
                &unit,
                MOTION_TOLERANCE,
            );
        }
    }
}

/// A camera's transform keeps rotation and translation only (as the loader does): scale would
/// change the field of view.
pub fn rigid(m: Mat4) -> Mat4 {
    let (_, rot, trans) = m.to_scale_rotation_translation();
    let rot = if rot.is_finite() && rot.length() > 0.0 {
        rot.normalize()
    } else {
        Quat::IDENTITY
    };
    Mat4::from_rotation_translation(rot, trans)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn channel(property: Property, interpolation: Interpolation, values: Vec<Vec4>) -> Channel {
        Channel {
            node: 0,
            property,
            curve: Curve {
                interpolation,
                times: vec![1.0, 3.0],
                values,
            },
        }
    }

    #[test]
    fn samplers_follow_the_gltf_formulas() {
        let (a, b) = (Vec4::new(0.0, 2.0, 0.0, 0.0), Vec4::new(4.0, 2.0, 8.0, 0.0));
        let lin = channel(Property::Translation, Interpolation::Linear, vec![a, b]);
        assert_eq!(lin.sample(0.0), a);
        assert_eq!(lin.sample(2.5), a.lerp(b, 0.75));
        assert_eq!(lin.sample(9.0), b);
        let step = channel(Property::Translation, Interpolation::Step, vec![a, b]);
        assert_eq!(step.sample(2.99), a);
        assert_eq!(step.sample(3.0), b);
        // Cubic Hermite with zero tangents is smoothstep between the keys.
        let z = Vec4::ZERO;
        let cub = channel(
            Property::Translation,
            Interpolation::CubicSpline,
            vec![z, a, z, z, b, z],
        );
        let s: f32 = 0.25;
        let h = 3.0 * s * s - 2.0 * s * s * s;
        assert!((cub.sample(1.5) - a.lerp(b, h)).length() < 1e-6);
        // With tangents: the derivative at the start key is the out-tangent.
        let d = Vec4::new(1.0, 0.0, 0.0, 0.0);
        let cub = channel(
            Property::Translation,
            Interpolation::CubicSpline,
            vec![z, a, d, z, a, z],
        );
        let slope = (cub.sample(1.0 + 1e-3) - cub.sample(1.0)).x / 1e-3;
        assert!((slope - 1.0).abs() < 1e-2, "{slope}");
        // Slerp keeps the rotation at constant angular speed.
        let q0 = Quat::IDENTITY;
        let q1 = Quat::from_rotation_y(1.5);
        let rot = channel(
            Property::Rotation,
            Interpolation::Linear,
            vec![Vec4::from(q0), Vec4::from(q1)],
        );
        let q = Quat::from_vec4(rot.sample(1.5));
        assert!(q.angle_between(Quat::from_rotation_y(0.375)) < 1e-5);
    }

    #[test]
    fn motion_steps_grow_with_rotation_and_interpolate_linearly() {
        let object = Aabb {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        };
        // A pure translation is exact with two steps.
        let tr =
            Motion::sample(|u| Mat4::from_translation(Vec3::X * 3.0 * u), &object, 1e-3).unwrap();
        assert_eq!(tr.steps.len(), 2);
        assert!((tr.at(0.25).transform_point3(Vec3::ZERO) - Vec3::X * 0.75).length() < 1e-6);
        // A half turn needs many; the interpolated corners stay within the tolerance.
        let rot = Motion::sample(|u| Mat4::from_rotation_y(3.0 * u), &object, 1e-3).unwrap();
        assert!(rot.steps.len() > 9, "{}", rot.steps.len());
        for k in 0..100 {
            let u = k as f32 / 99.0;
            let p = Vec3::ONE;
            let err =
                rot.at(u).transform_point3(p) - Mat4::from_rotation_y(3.0 * u).transform_point3(p);
            assert!(err.length() < 2e-3, "{u}: {err}");
        }
        assert!(Motion::sample(|_| Mat4::IDENTITY, &object, 1e-3).is_none());
        // Bounds over the steps hold every interpolated position.
        let b = rot.bounds(&object);
        for k in 0..50 {
            let p = rot.at(k as f32 / 49.0).transform_point3(Vec3::ONE);
            assert!(b.min.cmple(p).all() && p.cmple(b.max).all());
        }
    }

    #[test]
    fn skins_blend_joint_transforms_by_weight() {
        let node = |translation: Vec3| Node {
            parent: None,
            translation,
            rotation: Quat::IDENTITY,
            scale: Vec3::ONE,
        };
        // Joint 1 moves along +y from 0 to 2 over a second; joint 0 stays at the origin.
        let anim = Animation {
            nodes: vec![node(Vec3::ZERO), node(Vec3::ZERO)],
            channels: vec![Channel {
                node: 1,
                property: Property::Translation,
                curve: Curve {
                    interpolation: Interpolation::Linear,
                    times: vec![0.0, 1.0],
                    values: vec![Vec4::ZERO, Vec4::new(0.0, 2.0, 0.0, 0.0)],
                },
            }],
            ..Default::default()
        };
        let skin = Skin {
            instance: 0,
            mesh: 0,
            joints: vec![0, 1],
            // Joint 1's bind pose is at x = 1: its inverse moves the vertex back before posing.
            inverse_bind: vec![Mat4::IDENTITY, Mat4::from_translation(-Vec3::X)],
            vertex_joints: vec![[0, 1, 0, 0], [1, 0, 0, 0]],
            vertex_weights: vec![
                Vec4::new(0.25, 0.75, 0.0, 0.0),
                Vec4::new(1.0, 0.0, 0.0, 0.0),
            ],
            rest_positions: vec![Vec3::new(1.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.0)],
            rest_normals: vec![Vec3::Z, Vec3::Z],
        };
        let (p, n) = skin.posed(&anim, 0.5, (&skin.rest_positions, &skin.rest_normals));
        // 0.25 * (1, 0, 0) + 0.75 * ((1, 0, 0) - (1, 0, 0) + (0, 1, 0)).
        assert!(
            (p[0] - Vec3::new(0.25, 0.75, 0.0)).length() < 1e-6,
            "{}",
            p[0]
        );
        assert!(
            (p[1] - Vec3::new(0.0, 2.0, 0.0)).length() < 1e-6,
            "{}",
            p[1]
        );
        assert_eq!(n[0], Vec3::Z);
    }
}
