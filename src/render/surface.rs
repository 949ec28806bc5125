//! What the integrator knows about a hit point: position, normals, texture coordinates and the material
//! evaluated there (textures, normal map), all in world space. Built from a `Hit` and the `Scene`.

use glam::{Vec2, Vec3, Vec4Swizzles};

use super::bsdf::{Bsdf, Coat, DiffuseTransmission, Iridescence, Sheen};
use crate::geometry::Frame;
use crate::geometry::{Hit, Ray};
use crate::scene::layers::Anisotropy;
use crate::scene::{Material, MaterialLayers, Scene, TexRef, VertexAttrs};

#[derive(Clone, Copy, Debug)]
pub struct SurfaceInteraction {
    pub p: Vec3,
    /// Geometric normal, turned to face the incoming ray.
    pub ng: Vec3,
    pub uv: Vec2,
    pub bsdf: Bsdf,
    /// Emitted radiance towards the incoming ray.
    pub emission: Vec3,
    /// KHR_materials_unlit: `emission` is the base colour and nothing scatters off the surface.
    pub unlit: bool,
    pub inst: u32,
    pub prim: u32,
    /// Index of the material in `Scene::materials` (the material id feature image).
    pub material: u32,
}

/// A texture at the coordinates of the set it reads.
fn tex(scene: &Scene, t: Option<TexRef>, uv: VertexAttrs) -> Option<glam::Vec4> {
    t.map(|t| scene.textures[t.texture as usize].sample(t.uv_of(&uv)))
}

/// What a surface sends towards the viewer by itself: an unlit material's base colour, or emission.
fn radiance(scene: &Scene, mat: &Material, uv: VertexAttrs) -> Vec3 {
    if mat.unlit {
        scene.base_color(mat, uv).xyz()
    } else {
        emission(scene, mat, uv)
    }
}

/// Emitted radiance of a material at a point's texture coordinates.
pub fn emission(scene: &Scene, mat: &Material, uv: VertexAttrs) -> Vec3 {
    match tex(scene, mat.emissive_tex, uv) {
        Some(t) => mat.emissive * t.xyz(),
        None => mat.emissive,
    }
}

/// What the surface at `hit` sends back along `ray` by itself (`SurfaceInteraction::emission`),
/// without building the interaction: camera rays that only look at emitters need nothing else.
pub fn radiance_at(scene: &Scene, hit: &Hit, ray: &Ray) -> Vec3 {
    if !SurfaceInteraction::can_emit(scene, hit) {
        return Vec3::ZERO;
    }
    if hit.csg().is_some() {
        return SurfaceInteraction::new(scene, hit, ray).emission;
    }
    let mesh = &scene.meshes[scene.instances[hit.inst as usize].mesh as usize];
    let mat = &scene.materials[mesh.material as usize];
    radiance(scene, mat, mesh.uv_at(hit.prim, hit.u, hit.v))
}

impl SurfaceInteraction {
    /// Whether the surface `hit` can have any emitted radiance (an emissive factor, or unlit): where
    /// not, a path's last vertex adds nothing and needs no interaction. CSG hits say yes.
    pub fn can_emit(scene: &Scene, hit: &Hit) -> bool {
        hit.csg().is_some() || {
            let mat = scene.material_of(hit.inst);
            mat.unlit || mat.is_emissive()
        }
    }

    pub fn new(scene: &Scene, hit: &Hit, ray: &Ray) -> Self {
        if let Some((object, surface)) = hit.csg() {
            return Self::from_csg(scene, hit, ray, object, surface);
        }
        let inst = &scene.instances[hit.inst as usize];
        let mesh = &scene.meshes[inst.mesh as usize];
        let mat = &scene.materials[mesh.material as usize];
        let [i0, i1, i2] = mesh.indices[hit.prim as usize].map(|i| i as usize);
        let (u, v, w) = (hit.u, hit.v, 1.0 - hit.u - hit.v);
        // A moving instance is where it was at the ray's time.
        let (to_world, normal_to_world) = match &inst.motion {
            Some(m) => {
                let t = m.at(ray.time);
                (t, glam::Mat3::from_mat4(t).inverse().transpose())
            }
            None => (inst.to_world, inst.normal_to_world),
        };
        let [p0, p1, p2] = [i0, i1, i2].map(|i| to_world.transform_point3(mesh.positions[i]));
        // Interpolated from the vertices rather than o + t d: the error stays within the triangle's
        // own rounding, which the ray-offset bounds expect.
        let p = p0 * w + p1 * u + p2 * v;
        let mut ng = (p1 - p0).cross(p2 - p0).normalize_or_zero();
        if ng == Vec3::ZERO {
            ng = -ray.d;
        }
        let interp_n = (normal_to_world
            * (mesh.normals[i0] * w + mesh.normals[i1] * u + mesh.normals[i2] * v))
            .normalize_or_zero();
        // The outside is where the vertex normals point (robust to mirrored instances and to
        // either winding); a ray arriving from there enters a transmissive object.
        let outward = if ng.dot(interp_n) < 0.0 { -ng } else { ng };
        let entering = outward.dot(ray.d) < 0.0;
        let mut n = if interp_n == Vec3::ZERO { ng } else { interp_n };
        // Two-sided shading: both normals face where the ray came from.
        if ng.dot(ray.d) > 0.0 {
            ng = -ng;
        }
        if n.dot(ng) < 0.0 {
            n = -n;
        }
        let uv = mesh.uv_at(hit.prim, u, v);

        let mapped = |nm: Option<TexRef>, scale: f32| {
            let m = mapped_normal(scene, hit, (nm, scale), n, ng, &to_world, uv);
            valid_reflection_normal(m, ng, -ray.d)
        };
        // The clearcoat has its own normal map, else follows the interpolated normal.
        let coat_n = match &mat.layers.clearcoat {
            Some(c) => mapped(c.normal_tex, c.normal_scale),
            None => n,
        };
        let n = mapped(mat.normal_tex, mat.normal_scale);

        let mut bsdf = material_bsdf(scene, mat, uv, (n, coat_n), entering);
        // Only anisotropic materials pay for a tangent frame.
        if let Some(a) = &mat.layers.anisotropy {
            let set = a
                .texture
                .or(mat.normal_tex)
                .map_or(0, |t| t.tex_coord as usize);
            if let Some(tb) = tangent_frame(scene, hit, n, &to_world, set) {
                let (strength, dir) = anisotropy_direction(scene, a, uv, tb);
                bsdf = bsdf.with_anisotropy(strength, dir);
            }
        }
        Self {
            p,
            ng,
            uv: uv.sets[0],
            bsdf,
            emission: radiance(scene, mat, uv),
            unlit: mat.unlit,
            inst: hit.inst,
            prim: hit.prim,
            material: mesh.material,
        }
    }
}

impl SurfaceInteraction {
    /// A hit on a CSG object: the point projected back onto its primitive (so offsetting it is as
    /// safe as for a triangle's interpolated point), the primitive's normal (flipped where it was
    /// subtracted) as both geometric and shading normal, and the material of that surface; no UVs.
    pub fn from_csg(scene: &Scene, hit: &Hit, ray: &Ray, object: u32, surface: u32) -> Self {
        let s = scene.csg[object as usize].surface(surface, ray.at(hit.t), ray.time);
        let mat = &scene.materials[s.material as usize];
        let ng = if s.n.dot(ray.d) > 0.0 { -s.n } else { s.n };
        let uv = VertexAttrs::from_uv(Vec2::ZERO);
        // The primitive's normal points out of the solid (subtracted surfaces flipped).
        let entering = s.n.dot(ray.d) < 0.0;
        Self {
            p: s.p,
            ng,
            uv: uv.sets[0],
            bsdf: material_bsdf(scene, mat, uv, (ng, ng), entering),
            emission: radiance(scene, mat, uv),
            unlit: mat.unlit,
            inst: hit.inst,
            prim: hit.prim,
            material: s.material,
        }
    }
}

/// A normal-mapped shading normal (`map`: texture and scale), or `n` where the map is missing or
/// points below the geometric normal `ng`.
fn mapped_normal(
    scene: &Scene,
    hit: &Hit,
    map: (Option<TexRef>, f32),
    n: Vec3,
    ng: Vec3,
    to_world: &glam::Mat4,
    uv: VertexAttrs,
) -> Vec3 {
    let Some(nm) = tex(scene, map.0, uv) else {
        return n;
    };
    let set = map.0.map_or(0, |t| t.tex_coord as usize);
    let Some((t, b)) = tangent_frame(scene, hit, n, to_world, set) else {
        return n;
    };
    let m = nm.xyz() * 2.0 - Vec3::ONE;
    let m = Vec3::new(m.x * map.1, m.y * map.1, m.z);
    let mapped = (t * m.x + b * m.y + n * m.z).normalize_or_zero();
    if mapped.dot(ng) > 0.0 {
        mapped
    } else {
        n
    }
}

/// The material's BSDF at a texture coordinate around shading normals `(n, coat_n)` (the base's and
/// the clearcoat's); `entering` says whether the ray arrives from outside (for the IOR ratio and
/// absorption of transmissive solids).
fn material_bsdf(
    scene: &Scene,
    mat: &Material,
    uv: VertexAttrs,
    (n, coat_n): (Vec3, Vec3),
    entering: bool,
) -> Bsdf {
    let base = scene.base_color(mat, uv);
    let (mut metallic, mut roughness) = (mat.metallic, mat.roughness);
    if let Some(mr) = tex(scene, mat.metallic_roughness_tex, uv) {
        roughness *= mr.y;
        metallic *= mr.z;
    }
    let transmission = match tex(scene, mat.transmission_tex, uv) {
        Some(t) => mat.transmission * t.x,
        None => mat.transmission,
    };
    let specular = match tex(scene, mat.layers.specular_tex, uv) {
        Some(t) => mat.specular * t.w,
        None => mat.specular,
    };
    let mut bsdf = Bsdf::new(
        Frame::from_normal(n),
        base.xyz(),
        metallic,
        roughness,
        specular,
    );
    bsdf.diffuse_transmission = diffuse_transmission(scene, &mat.layers, uv);
    let mut bsdf = bsdf
        .with_dielectric(transmission, mat.ior, mat.is_thin_walled(), entering)
        .with_dispersion(mat.layers.dispersion);
    bsdf.absorption = mat.absorption();
    bsdf.model = scene.shading;
    add_layers(scene, &mat.layers, uv, coat_n, &mut bsdf);
    bsdf
}

/// KHR_materials_diffuse_transmission's factor and colour at a point, textures applied; None where
/// the factor comes to 0.
fn diffuse_transmission(
    scene: &Scene,
    l: &MaterialLayers,
    uv: VertexAttrs,
) -> Option<DiffuseTransmission> {
    let d = l.diffuse_transmission.as_ref()?;
    let factor = d.factor * tex(scene, d.factor_tex, uv).map_or(1.0, |t| t.w);
    let color = d.color * tex(scene, d.color_tex, uv).map_or(Vec3::ONE, |t| t.xyz());
    (factor > 0.0).then(|| DiffuseTransmission::new(factor, color))
}

/// KHR_materials_specular's colour, the clearcoat, the sheen and the iridescent film, textures applied; a layer whose
/// weight comes to 0 here is left off (and costs nothing).
fn add_layers(scene: &Scene, l: &MaterialLayers, uv: VertexAttrs, coat_n: Vec3, bsdf: &mut Bsdf) {
    bsdf.specular_color = match tex(scene, l.specular_color_tex, uv) {
        Some(t) => l.specular_color * t.xyz(),
        None => l.specular_color,
    };
    if let Some(c) = &l.clearcoat {
        let weight = c.factor * tex(scene, c.factor_tex, uv).map_or(1.0, |t| t.x);
        let rough = c.roughness * tex(scene, c.roughness_tex, uv).map_or(1.0, |t| t.y);
        if weight > 0.0 {
            bsdf.coat = Some(Coat::new(Frame::from_normal(coat_n), weight, rough));
        }
    }
    if let Some(s) = &l.sheen {
        let color = s.color * tex(scene, s.color_tex, uv).map_or(Vec3::ONE, |t| t.xyz());
        let rough = s.roughness * tex(scene, s.roughness_tex, uv).map_or(1.0, |t| t.w);
        if color.max_element() > 0.0 {
            bsdf.sheen = Some(Sheen::new(color, rough));
        }
    }
    // The film lies on the outside: a ray leaving a transmissive solid meets the bare base.
    if let (Some(f), true) = (&l.iridescence, bsdf.outside) {
        let factor = f.factor * tex(scene, f.factor_tex, uv).map_or(1.0, |t| t.x);
        let thickness = match tex(scene, f.thickness_tex, uv) {
            Some(t) => f.thickness_min + (f.thickness_max - f.thickness_min) * t.y,
            None => f.thickness_max,
        };
        if factor > 0.0 && thickness > 0.0 {
            bsdf.iridescence = Some(Iridescence {
                factor,
                ior: f.ior,
                thickness,
                // Under a clearcoat the film's outside is the coat (IOR 1.5).
                outside_ior: if bsdf.coat.is_some() { 1.5 } else { 1.0 },
            });
        }
    }
}

/// KHR_materials_anisotropy's strength and world direction at a point, from the tangent frame
/// `(t, b)`: the texture's RG direction (or the tangent) turned by anisotropyRotation.
fn anisotropy_direction(
    scene: &Scene,
    a: &Anisotropy,
    uv: VertexAttrs,
    (t, b): (Vec3, Vec3),
) -> (f32, Vec3) {
    let (sin, cos) = a.rotation.sin_cos();
    let (strength, d) = match tex(scene, a.texture, uv) {
        Some(x) => {
            let d = Vec2::new(2.0 * x.x - 1.0, 2.0 * x.y - 1.0).normalize_or_zero();
            let d = Vec2::new(cos * d.x - sin * d.y, sin * d.x + cos * d.y);
            (a.strength * x.z, d)
        }
        None => (a.strength, Vec2::new(cos, sin)),
    };
    (strength, t * d.x + b * d.y)
}

/// Smallest margin above the geometric surface for the mirror direction of `wo` about the shading normal.
const MIN_REFLECTION_COS: f32 = 0.01;

/// Bends a shading normal towards the geometric one until the mirror reflection of `wo` stays above
/// the geometric surface. Interpolated and normal-mapped normals can tilt so far from the true surface
/// that glossy reflections point into it; those paths would die and leave black rims (as on the
/// NormalTangentMirrorTest cells). The bend is the smallest found by bisection, so surfaces seen
/// head-on keep their normals unchanged.
fn valid_reflection_normal(n: Vec3, ng: Vec3, wo: Vec3) -> Vec3 {
    let reflects_above = |m: Vec3| (2.0 * m.dot(wo) * m - wo).dot(ng) >= MIN_REFLECTION_COS;
    if reflects_above(n) || !reflects_above(ng) {
        return n;
    }
    let (mut lo, mut hi) = (0.0f32, 1.0f32);
    for _ in 0..10 {
        let mid = 0.5 * (lo + hi);
        if reflects_above(n.lerp(ng, mid).normalize()) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    n.lerp(ng, hi).normalize()
}

/// Tangent and bitangent for normal mapping, orthogonalised against `n`: from the mesh's tangents when
/// it has them, otherwise from the parameterisation of UV set `set` (the normal texture's) over the
/// triangle.
fn tangent_frame(
    scene: &Scene,
    hit: &Hit,
    n: Vec3,
    to_world: &glam::Mat4,
    set: usize,
) -> Option<(Vec3, Vec3)> {
    let inst = &scene.instances[hit.inst as usize];
    let mesh = &scene.meshes[inst.mesh as usize];
    let [i0, i1, i2] = mesh.indices[hit.prim as usize].map(|i| i as usize);
    let (u, v, w) = (hit.u, hit.v, 1.0 - hit.u - hit.v);
    let (t, sign) = if !mesh.tangents.is_empty() {
        let t4 = mesh.tangents[i0] * w + mesh.tangents[i1] * u + mesh.tangents[i2] * v;
        let t = to_world.transform_vector3(t4.xyz());
        (t, if mesh.tangents[i0].w < 0.0 { -1.0 } else { 1.0 })
    } else {
        let uvs = mesh.uv_set(set);
        if uvs.is_empty() {
            return None;
        }
        let [p0, p1, p2] = [i0, i1, i2].map(|i| to_world.transform_point3(mesh.positions[i]));
        let [t0, t1, t2] = [i0, i1, i2].map(|i| uvs[i]);
        let (e1, e2) = (p1 - p0, p2 - p0);
        let (d1, d2) = (t1 - t0, t2 - t0);
        let det = d1.x * d2.y - d1.y * d2.x;
        if det.abs() < 1e-20 {
            return None;
        }
        let t = (e1 * d2.y - e2 * d1.y) / det;
        let b = (e2 * d1.x - e1 * d2.x) / det;
        // glTF's v runs down the image while a normal map's green points up, so an unmirrored
        // parameterisation has dp/dv opposite to n x t; mirrored UVs flip that.
        let sign = if n.cross(t).dot(b) > 0.0 { -1.0 } else { 1.0 };
        (t, sign)
    };
    let t = (t - n * n.dot(t)).normalize_or_zero();
    if t == Vec3::ZERO {
        return None;
    }
    Some((t, n.cross(t) * sign))
}

#[cfg(test)]
mod tests {
    use std::f32::consts::{FRAC_1_SQRT_2, FRAC_PI_2, FRAC_PI_4};

    use super::*;
    use crate::scene::texture::Texture;

    /// KHR_materials_anisotropy's convention: the direction lies in tangent space, turned
    /// counter-clockwise by anisotropyRotation from the tangent towards the bitangent; the
    /// texture's RG is a direction in [-1, 1] (turned the same way), its B scales the strength; and
    /// the lobe is rougher along that direction (a point light's highlight stretches along it).
    #[test]
    fn anisotropy_direction_follows_the_spec_convention() {
        let mut scene = Scene::default();
        // RG (128, 255): the direction (0.004, 1), about the bitangent; B 128: strength x 0.5.
        scene.textures.push(Texture::repeating(
            "direction".into(),
            (1, 1),
            vec![[128, 255, 128, 255]],
            false,
        ));
        let uv = VertexAttrs::from_uv(Vec2::splat(0.5));
        let (t, b) = (Vec3::X, Vec3::Y);
        let dir = |rotation: f32, texture: Option<TexRef>| {
            let a = Anisotropy {
                strength: 0.8,
                rotation,
                texture,
            };
            anisotropy_direction(&scene, &a, uv, (t, b))
        };
        let close = |a: Vec3, b: Vec3| (a.normalize() - b).length() < 1e-2;
        let tex = Some(TexRef::new(0));
        assert!(close(dir(0.0, None).1, Vec3::X));
        assert!(close(dir(FRAC_PI_2, None).1, Vec3::Y));
        let diagonal = Vec3::new(FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0);
        assert!(close(dir(FRAC_PI_4, None).1, diagonal));
        assert!(close(dir(-FRAC_PI_2, None).1, -Vec3::Y));
        let (s, d) = dir(0.0, tex);
        assert!(close(d, Vec3::Y) && (s - 0.8 * 128.0 / 255.0).abs() < 1e-6);
        assert!(close(dir(FRAC_PI_2, tex).1, -Vec3::X));
        // The lobe at normal view: wider along the direction than across it.
        let tilt = |a: Vec3| Vec3::Z * 0.35f32.cos() + a * 0.35f32.sin();
        for (rotation, texture, axis) in [
            (0.0, None, Vec3::X),
            (FRAC_PI_2, None, Vec3::Y),
            (0.0, tex, Vec3::Y),
            (FRAC_PI_2, tex, -Vec3::X),
        ] {
            let (s, d) = dir(rotation, texture);
            let bsdf = Bsdf::new(Frame::from_normal(Vec3::Z), Vec3::ONE, 1.0, 0.3, 1.0)
                .with_anisotropy(s, d);
            let along = bsdf.eval(Vec3::Z, tilt(axis)).0.x;
            let across = bsdf.eval(Vec3::Z, tilt(Vec3::Z.cross(axis))).0.x;
            assert!(
                along > 2.0 * across,
                "rotation {rotation} texture {}: along {along}, across {across}",
                texture.is_some()
            );
        }
    }

    /// KHR_materials_diffuse_transmission's textures: the factor times the factor texture's A, the
    /// colour times the colour texture's RGB (decoded as the texture says); a factor of 0 at the
    /// texel leaves the lobe off.
    #[test]
    fn diffuse_transmission_reads_its_texture_channels() {
        let mut scene = Scene::default();
        for (pixel, srgb) in [([10, 20, 30, 128], false), ([255, 128, 0, 7], true)] {
            scene
                .textures
                .push(Texture::repeating("dt".into(), (1, 1), vec![pixel], srgb));
        }
        let uv = VertexAttrs::from_uv(Vec2::splat(0.5));
        let mut layers = MaterialLayers {
            diffuse_transmission: Some(crate::scene::layers::DiffuseTransmission {
                factor: 0.8,
                factor_tex: Some(TexRef::new(0)),
                color: Vec3::new(1.0, 0.5, 1.0),
                color_tex: Some(TexRef::new(1)),
            }),
            ..Default::default()
        };
        let dt = diffuse_transmission(&scene, &layers, uv).expect("on");
        assert!((dt.factor - 0.8 * 128.0 / 255.0).abs() < 1e-6);
        let green = crate::geometry::colour::srgb_to_linear(128.0 / 255.0);
        assert!(
            (dt.color - Vec3::new(1.0, 0.5 * green, 0.0))
                .abs()
                .max_element()
                < 1e-5
        );
        layers.diffuse_transmission.as_mut().unwrap().factor = 0.0;
        assert!(diffuse_transmission(&scene, &layers, uv).is_none());
    }

    #[test]
    fn tilted_normals_are_bent_just_enough() {
        let ng = Vec3::Z;
        let wo = Vec3::new(0.8, 0.0, 0.6).normalize();
        // A normal tilted far away from the viewer reflects wo into the surface.
        let tilted = Vec3::new(-0.7, 0.0, 0.714).normalize();
        assert!((2.0 * tilted.dot(wo) * tilted - wo).dot(ng) < 0.0);
        let fixed = valid_reflection_normal(tilted, ng, wo);
        let r = 2.0 * fixed.dot(wo) * fixed - wo;
        assert!(r.dot(ng) >= MIN_REFLECTION_COS);
        // ... and not much more than needed.
        assert!(r.dot(ng) < 0.05, "bent too far: {}", r.dot(ng));
        // A normal that already reflects above the surface is kept as it is.
        let mild = Vec3::new(0.1, 0.05, 1.0).normalize();
        assert_eq!(valid_reflection_normal(mild, ng, wo), mild);
    }
}
