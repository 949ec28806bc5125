//! Scene files (`scene.toml`): glTF/OBJ assets placed with transforms, named materials and overrides,
//! lights, a camera with lens and shutter, and render settings, gathered into one `Scene`.

use std::collections::HashMap;
use std::ops::Range;
use std::path::{Path, PathBuf};

use glam::Vec3;
use serde::Deserialize;
use toml::Spanned;

pub mod csg;

use super::transform::TransformSpec;
use super::{AlphaMode, Camera, LoadError, Material, Scene};
use crate::film::filter::FilterKind;
use crate::sample::SamplerKind;

/// Render settings a scene file may carry; command-line flags given explicitly win over them.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FileSettings {
    pub width: Option<usize>,
    pub height: Option<usize>,
    pub spp: Option<u32>,
    pub max_depth: Option<u32>,
    pub seed: Option<u64>,
    #[serde(default, deserialize_with = "value_enum")]
    pub sampler: Option<SamplerKind>,
    #[serde(default, deserialize_with = "value_enum")]
    pub filter: Option<FilterKind>,
    pub backend: Option<String>,
}

/// A `clap::ValueEnum` read from its command-line name, so the file and the flags spell values alike.
fn value_enum<'de, D, T>(d: D) -> Result<Option<T>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: clap::ValueEnum,
{
    let s = String::deserialize(d)?;
    T::from_str(&s, true)
        .map(Some)
        .map_err(|_| serde::de::Error::custom(format!("unknown value '{s}'")))
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Desc {
    #[serde(default)]
    render: FileSettings,
    camera: Option<CameraDesc>,
    #[serde(default)]
    asset: Vec<AssetDesc>,
    #[serde(default)]
    material: Vec<Spanned<MaterialDesc>>,
    #[serde(default)]
    light: Vec<Spanned<LightDesc>>,
    #[serde(default)]
    object: Vec<Spanned<ObjectDesc>>,
}

/// A CSG object: a tree of analytic primitives (and closed meshes of the assets, by name).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectDesc {
    csg: csg::NodeSpec,
    material: Option<String>,
    #[serde(default)]
    transform: TransformSpec,
    /// Where the object is when the shutter closes (it moves linearly from `transform`).
    transform_end: Option<TransformSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraDesc {
    position: [f32; 3],
    look_at: [f32; 3],
    #[serde(default = "up")]
    up: [f32; 3],
    /// Vertical field of view, degrees.
    #[serde(default = "fov")]
    fov: f32,
    /// Thin lens: aperture radius (scene units) or f-number (24 mm sensor), focused at
    /// `focus_distance` (default: the distance to `look_at`).
    aperture: Option<f32>,
    fstop: Option<f32>,
    focus_distance: Option<f32>,
    /// Shutter interval in seconds relative to `frame_time` (seconds into the assets' animations).
    shutter: Option<[f32; 2]>,
    #[serde(default)]
    frame_time: f32,
}

fn up() -> [f32; 3] {
    [0.0, 1.0, 0.0]
}
fn fov() -> f32 {
    super::defaults::DEFAULT_FOV_DEG
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct AssetDesc {
    /// A .gltf, .glb or .obj file, relative to the scene file.
    path: Spanned<PathBuf>,
    #[serde(default)]
    transform: TransformSpec,
    /// Where the asset is when the shutter closes (it moves linearly from `transform`).
    transform_end: Option<TransformSpec>,
    /// One scene-file material for every mesh of the asset.
    material: Option<Spanned<String>>,
    /// The asset's own material names mapped to scene-file materials.
    #[serde(default)]
    materials: HashMap<String, Spanned<String>>,
}

/// A material defined in the scene file; what is left out takes these defaults (a grey dielectric).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialDesc {
    name: String,
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
}

fn grey() -> [f32; 3] {
    [0.8; 3]
}
fn one() -> f32 {
    1.0
}
fn half() -> f32 {
    0.5
}
fn ior() -> f32 {
    1.5
}

impl MaterialDesc {
    fn to_material(&self) -> Material {
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
            ..Material::default()
        }
    }

    /// The first field out of its physical range, as `(field, why)`.
    fn range_error(&self) -> Option<(&'static str, &'static str)> {
        let unit = |v: f32| (0.0..=1.0).contains(&v);
        if !self.base_color.iter().all(|&c| unit(c)) || !unit(self.alpha) {
            return Some(("base_color/alpha", "must lie in [0, 1]"));
        }
        for (name, v) in [
            ("metallic", self.metallic),
            ("roughness", self.roughness),
            ("specular", self.specular),
            ("transmission", self.transmission),
        ] {
            if !unit(v) {
                return Some((name, "must lie in [0, 1]"));
            }
        }
        if !(self.ior >= 1.0 && self.ior.is_finite()) {
            return Some(("ior", "must be at least 1"));
        }
        if !(self.thickness >= 0.0 && self.thickness.is_finite()) {
            return Some(("thickness", "must be finite and not negative"));
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
        None
    }
}

/// A light of the scene file; `color` is linear RGB, scaled by the strength field of its kind.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase")]
enum LightDesc {
    Point(PointDesc),
    Spot(SpotDesc),
    Directional(DirectionalDesc),
    Sphere(SphereDesc),
    Disk(DiskDesc),
    Rect(RectDesc),
    Environment(EnvironmentDesc),
}

/// An emitting sphere: `radiance` (W/sr/m^2) is `color * strength`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SphereDesc {
    center: [f32; 3],
    radius: f32,
    #[serde(default = "white")]
    color: [f32; 3],
    strength: f32,
}

/// A one-sided disk facing `look_at` (or along `normal`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct DiskDesc {
    center: [f32; 3],
    radius: f32,
    normal: Option<[f32; 3]>,
    look_at: Option<[f32; 3]>,
    #[serde(default = "white")]
    color: [f32; 3],
    strength: f32,
}

/// A one-sided rectangle: `center` and `size = [w, h]` facing `look_at` (or along `normal`), or the
/// parallelogram `corner + s edge_u + t edge_v` emitting towards `edge_u x edge_v`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RectDesc {
    center: Option<[f32; 3]>,
    size: Option<[f32; 2]>,
    normal: Option<[f32; 3]>,
    look_at: Option<[f32; 3]>,
    corner: Option<[f32; 3]>,
    edge_u: Option<[f32; 3]>,
    edge_v: Option<[f32; 3]>,
    #[serde(default = "white")]
    color: [f32; 3],
    strength: f32,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PointDesc {
    position: [f32; 3],
    #[serde(default = "white")]
    color: [f32; 3],
    /// W/sr.
    intensity: f32,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct SpotDesc {
    position: [f32; 3],
    look_at: [f32; 3],
    #[serde(default = "white")]
    color: [f32; 3],
    intensity: f32,
    /// Full-intensity half angle and cut-off half angle, degrees.
    #[serde(default)]
    inner_angle: f32,
    #[serde(default = "outer")]
    outer_angle: f32,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct DirectionalDesc {
    /// Where the light travels to.
    direction: [f32; 3],
    #[serde(default = "white")]
    color: [f32; 3],
    /// Irradiance on a surface facing the light.
    irradiance: f32,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct EnvironmentDesc {
    #[serde(default = "white")]
    color: [f32; 3],
    #[serde(default = "one")]
    strength: f32,
    /// A lat-long (equirectangular) .exr or .hdr map, relative to the scene file.
    map: Option<PathBuf>,
    /// Turns the map about +Y, degrees.
    #[serde(default)]
    rotate_y: f32,
}

fn white() -> [f32; 3] {
    [1.0; 3]
}
fn outer() -> f32 {
    45.0
}

/// Loads a scene file and every asset it names.
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| LoadError::new(path, format!("cannot read: {e}")))?;
    let desc: Desc = toml::from_str(&text).map_err(|e| LoadError::new(path, e.to_string()))?;
    let at = |span: Range<usize>, msg: String| {
        let line = text[..span.start.min(text.len())].lines().count().max(1);
        LoadError::new(path, format!("line {line}: {msg}"))
    };
    let dir = path.parent().unwrap_or(Path::new(""));
    let (shutter, frame_time) = desc.camera.as_ref().map_or(([0.0; 2], 0.0), |c| {
        (c.shutter.unwrap_or([0.0; 2]), c.frame_time)
    });
    let valid = shutter[0] <= shutter[1]
        && shutter[0].is_finite()
        && shutter[1].is_finite()
        && frame_time.is_finite();
    if !valid {
        return Err(LoadError::new(
            path,
            "[camera]: shutter must be [open, close] with open <= close, frame_time finite",
        ));
    }

    let mut scene = Scene::default();
    let mut named: HashMap<String, u32> = HashMap::new();
    for m in &desc.material {
        if let Some((field, why)) = m.get_ref().range_error() {
            return Err(at(
                m.span(),
                format!("material '{}': {field} {why}", m.get_ref().name),
            ));
        }
        let index = scene.materials.len() as u32;
        if named.insert(m.get_ref().name.clone(), index).is_some() {
            return Err(at(
                m.span(),
                format!("material '{}' is defined twice", m.get_ref().name),
            ));
        }
        scene.materials.push(m.get_ref().to_material());
    }
    let lookup = |name: &Spanned<String>| {
        named.get(name.get_ref()).copied().ok_or_else(|| {
            at(
                name.span(),
                format!("no material named '{}'", name.get_ref()),
            )
        })
    };

    for a in &desc.asset {
        let rel = a.path.get_ref();
        let file = dir.join(rel);
        if file
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
        {
            return Err(at(
                a.path.span(),
                format!(
                    "asset '{}': scene files cannot include scene files",
                    rel.display()
                ),
            ));
        }
        let mut asset = Scene::load(&file)
            .map_err(|e| at(a.path.span(), format!("asset '{}': {e}", rel.display())))?;
        if let Some(why) = a.transform.problem() {
            return Err(at(
                a.path.span(),
                format!("asset '{}': transform {why}", rel.display()),
            ));
        }
        let start = a.transform.to_mat4();
        let end = match &a.transform_end {
            Some(t) => match t.problem() {
                Some(why) => {
                    return Err(at(
                        a.path.span(),
                        format!("asset '{}': transform_end {why}", rel.display()),
                    ))
                }
                None => t.to_mat4(),
            },
            None => start,
        };
        super::animation::pose(&mut asset, frame_time, shutter);
        // Overrides replace the asset's materials before they join the scene's list.
        let all = a.material.as_ref().map(&lookup).transpose()?;
        let mut remap: HashMap<usize, u32> = HashMap::new();
        for (i, m) in asset.materials.iter().enumerate() {
            if let Some(k) = all {
                remap.insert(i, k);
            } else if let Some(name) = a.materials.get(&m.name) {
                remap.insert(i, lookup(name)?);
            }
        }
        for (from, name) in &a.materials {
            if !asset.materials.iter().any(|m| &m.name == from) {
                return Err(at(
                    name.span(),
                    format!("asset '{}' has no material named '{from}'", rel.display()),
                ));
            }
        }
        for w in asset.warnings.drain(..) {
            scene.warnings.push(format!("{}: {w}", rel.display()));
        }
        scene.append(asset, &remap, |u| blend(start, end, u));
    }

    add_objects(&mut scene, &desc.object, &named, &at)?;
    for l in &desc.light {
        let light = l
            .get_ref()
            .to_light(dir)
            .map_err(|e| at(l.span(), format!("light: {e}")))?;
        scene.lights.push(light);
    }
    if let Some(c) = &desc.camera {
        let (eye, target) = (Vec3::from(c.position), Vec3::from(c.look_at));
        if eye == target || !(c.fov > 0.0 && c.fov < 180.0) {
            return Err(LoadError::new(
                path,
                "[camera]: position equals look_at, or fov is not in (0, 180) degrees",
            ));
        }
        let mut cam = Camera::look_at(eye, target, Vec3::from(c.up), c.fov.to_radians());
        cam.name = "scene file".into();
        let focus = c.focus_distance.unwrap_or((target - eye).length());
        let radius = match (c.aperture, c.fstop) {
            (Some(_), Some(_)) => Some(Err("give aperture or fstop, not both")),
            (Some(a), None) => Some(Ok(a)),
            (None, Some(n)) if n > 0.0 => {
                Some(Ok(
                    super::Lens::from_fstop(n, c.fov.to_radians(), focus).radius
                ))
            }
            (None, Some(_)) => Some(Err("fstop must be positive")),
            (None, None) => None,
        };
        match radius {
            Some(Err(e)) => return Err(LoadError::new(path, format!("[camera]: {e}"))),
            Some(Ok(r)) if !(r >= 0.0 && r.is_finite() && focus > 0.0 && focus.is_finite()) => {
                return Err(LoadError::new(
                    path,
                    "[camera]: aperture and focus_distance must be positive and finite",
                ))
            }
            Some(Ok(r)) if r > 0.0 => {
                cam.lens = Some(super::Lens {
                    radius: r,
                    focus_distance: focus,
                })
            }
            _ => {}
        }
        scene.cameras.insert(0, cam);
    }
    scene.settings = desc.render;
    scene.stats.lights = scene.lights.len();
    scene.stats.cameras = scene.cameras.len();
    scene.stats.materials = scene.materials.len();
    scene.stats.triangles = scene.triangle_count();
    if scene.materials.is_empty() {
        scene.materials.push(Material::default());
    }
    Ok(scene)
}

/// The placement a fraction `u` of the way from `a` to `b`: scale, rotation (slerp) and translation
/// interpolated apart, so a turning asset keeps its size.
fn blend(a: glam::Mat4, b: glam::Mat4, u: f32) -> glam::Mat4 {
    if a == b {
        return a;
    }
    let (sa, ra, ta) = a.to_scale_rotation_translation();
    let (sb, rb, tb) = b.to_scale_rotation_translation();
    glam::Mat4::from_scale_rotation_translation(sa.lerp(sb, u), ra.slerp(rb, u), ta.lerp(tb, u))
}

/// Resolves the CSG objects into the scene. A mesh named as an operand (`mesh = "name"`) is taken where
/// its asset placed it, and its instances leave the scene: the object shows it, cut.
fn add_objects(
    scene: &mut Scene,
    objects: &[Spanned<ObjectDesc>],
    named: &HashMap<String, u32>,
    at: &dyn Fn(Range<usize>, String) -> LoadError,
) -> Result<(), LoadError> {
    use std::sync::Arc;
    let mut used: Vec<u32> = Vec::new();
    let mut solids: HashMap<String, Arc<crate::csg::SolidMesh>> = HashMap::new();
    for o in objects {
        let desc = o.get_ref();
        let fail = |e: String| at(o.span(), format!("object: {e}"));
        if let Some(why) = desc.transform.problem() {
            return Err(fail(format!("transform {why}")));
        }
        let default = match &desc.material {
            Some(m) => *named
                .get(m)
                .ok_or_else(|| fail(format!("no material named '{m}'")))?,
            None => {
                if scene.materials.is_empty() {
                    scene.materials.push(Material::default());
                }
                0
            }
        };
        // Meshes are looked up (and made solid) before resolving, which only reads them.
        for name in mesh_names(&desc.csg) {
            if solids.contains_key(&name) {
                continue;
            }
            let Some(k) = scene.meshes.iter().position(|m| m.name == name) else {
                return Err(fail(format!("no mesh named '{name}' in the assets")));
            };
            let mut mesh = scene.meshes[k].clone();
            if let Some(inst) = scene.instances.iter().find(|i| i.mesh as usize == k) {
                for p in &mut mesh.positions {
                    *p = inst.to_world.transform_point3(*p);
                }
            }
            let solid = mesh
                .to_solid()
                .map_err(|e| fail(format!("mesh '{name}': {e}")))?;
            solids.insert(name, Arc::new(solid));
            used.push(k as u32);
        }
        let root = desc
            .csg
            .resolve_with(
                &|n| named.get(n).copied(),
                &|n| solids.get(n).cloned(),
                default,
            )
            .map_err(fail)?;
        let start = desc.transform.to_mat4();
        let mut object = crate::csg::CsgObject::new(root, start).map_err(fail)?;
        if let Some(end) = &desc.transform_end {
            if let Some(why) = end.problem() {
                return Err(fail(format!("transform_end {why}")));
            }
            // As assets move: scale, rotation and translation blended apart, at as many time steps
            // as keep the linear interpolation within the motion tolerance.
            let end = end.to_mat4();
            let local = object.bounds().transformed(&start.inverse());
            if let Some(m) = crate::geometry::Motion::of_object(|u| blend(start, end, u), &local) {
                object = object.with_motion(m);
            }
        }
        scene.csg.push(object);
    }
    scene.instances.retain(|i| !used.contains(&i.mesh));
    Ok(())
}

/// The names of the meshes a CSG tree uses as operands.
fn mesh_names(node: &csg::NodeSpec) -> Vec<String> {
    use csg::KindSpec;
    match &node.kind {
        KindSpec::Mesh(name) => vec![name.clone()],
        KindSpec::Union(k) | KindSpec::Intersection(k) | KindSpec::Difference(k) => {
            k.iter().flat_map(mesh_names).collect()
        }
        _ => Vec::new(),
    }
}

impl LightDesc {
    fn to_light(&self, dir: &Path) -> Result<super::Light, String> {
        use super::{DiskLight, Light, RectLight, SphereLight};
        let rgb = |c: [f32; 3], k: f32| -> Result<Vec3, String> {
            let v = Vec3::from(c) * k;
            if v.is_finite() && v.min_element() >= 0.0 {
                Ok(v)
            } else {
                Err("color and strength must be finite and not negative".into())
            }
        };
        let positive = |name: &str, v: f32| {
            if v > 0.0 && v.is_finite() {
                Ok(v)
            } else {
                Err(format!("{name} must be positive"))
            }
        };
        // The unit normal of an area light: given, or towards `look_at`.
        let facing = |center: Vec3, normal: Option<[f32; 3]>, look_at: Option<[f32; 3]>| {
            let n = match (normal, look_at) {
                (Some(n), None) => Vec3::from(n),
                (None, Some(t)) => Vec3::from(t) - center,
                _ => return Err("give exactly one of normal and look_at".to_string()),
            };
            let n = n.normalize_or_zero();
            if n == Vec3::ZERO || !n.is_finite() {
                return Err("the facing direction is zero".into());
            }
            Ok(n)
        };
        Ok(match self {
            LightDesc::Point(p) => Light::Point {
                position: p.position.into(),
                intensity: rgb(p.color, p.intensity)?,
            },
            LightDesc::Spot(s) => Light::Spot {
                position: s.position.into(),
                direction: facing(s.position.into(), None, Some(s.look_at))?,
                intensity: rgb(s.color, s.intensity)?,
                cos_inner: s.inner_angle.to_radians().cos(),
                cos_outer: s.outer_angle.to_radians().cos(),
            },
            LightDesc::Directional(d) => Light::Directional {
                direction: facing(Vec3::ZERO, Some(d.direction), None)?,
                irradiance: rgb(d.color, d.irradiance)?,
            },
            LightDesc::Sphere(s) => Light::Sphere(SphereLight {
                center: s.center.into(),
                radius: positive("radius", s.radius)?,
                radiance: rgb(s.color, s.strength)?,
            }),
            LightDesc::Disk(d) => Light::Disk(DiskLight {
                center: d.center.into(),
                normal: facing(d.center.into(), d.normal, d.look_at)?,
                radius: positive("radius", d.radius)?,
                radiance: rgb(d.color, d.strength)?,
            }),
            LightDesc::Rect(r) => {
                let (corner, edge_u, edge_v) =
                    match (r.center, r.size, r.corner, r.edge_u, r.edge_v) {
                        (Some(c), Some([w, h]), None, None, None) => {
                            let c = Vec3::from(c);
                            let n = facing(c, r.normal, r.look_at)?;
                            positive("size", w.min(h))?;
                            // Width along the horizontal most across the normal, height up.
                            let frame = crate::geometry::Frame::from_normal(n);
                            let across = if n.cross(Vec3::Y).length() > 1e-3 {
                                Vec3::Y.cross(n).normalize()
                            } else {
                                frame.t
                            };
                            let up = n.cross(across);
                            let (eu, ev) = (across * w, up * h);
                            (c - 0.5 * (eu + ev), eu, ev)
                        }
                        (None, None, Some(c), Some(u), Some(v)) => {
                            if r.normal.is_some() || r.look_at.is_some() {
                                return Err("a corner rectangle faces edge_u x edge_v".into());
                            }
                            (Vec3::from(c), Vec3::from(u), Vec3::from(v))
                        }
                        _ => {
                            return Err(
                                "a rect light takes center and size, or corner, edge_u and edge_v"
                                    .into(),
                            )
                        }
                    };
                if edge_u.cross(edge_v).length() <= 0.0 {
                    return Err("the rectangle has no area".into());
                }
                Light::Rect(RectLight {
                    corner,
                    edge_u,
                    edge_v,
                    radiance: rgb(r.color, r.strength)?,
                })
            }
            LightDesc::Environment(e) => {
                let map = match &e.map {
                    Some(p) => Some(std::sync::Arc::new(
                        super::EnvMap::load(&dir.join(p))
                            .map_err(|e| e.to_string())?
                            .rotated_y(e.rotate_y.to_radians()),
                    )),
                    None => None,
                };
                Light::Environment {
                    radiance: rgb(e.color, e.strength)?,
                    map,
                }
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn unknown_key_names_its_line() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(
            dir.path(),
            "s.toml",
            "[render]\nspp = 4\n\n[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfvo = 30\n",
        );
        let e = load(&p).unwrap_err().to_string();
        assert!(
            e.contains("s.toml") && e.contains("line 7") && e.contains("fvo"),
            "{e}"
        );
    }

    #[test]
    fn wrong_type_names_its_line() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(dir.path(), "s.toml", "[render]\nwidth = \"wide\"\n");
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains("line 2"), "{e}");
    }

    #[test]
    fn unknown_material_names_its_line() {
        let dir = tempfile::tempdir().unwrap();
        let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        write(dir.path(), "t.obj", obj);
        let p = write(
            dir.path(),
            "s.toml",
            "[[material]]\nname = \"red\"\nbase_color = [1, 0, 0]\n\n[[asset]]\npath = \"t.obj\"\nmaterial = \"blue\"\n",
        );
        let e = load(&p).unwrap_err().to_string();
        assert!(e.contains("line 7") && e.contains("blue"), "{e}");
    }

    #[test]
    fn assets_are_placed_and_overridden() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        let p = write(
            dir.path(),
            "s.toml",
            r#"
[render]
spp = 8
sampler = "stratified"

[[material]]
name = "gold"
base_color = [1, 0.8, 0.3]
metallic = 1
roughness = 0.2

[[asset]]
path = "t.obj"
transform = { translate = [10, 0, 0] }

[[asset]]
path = "t.obj"
material = "gold"
transform = { scale = 2, rotate_z = 90 }

[[light]]
type = "point"
position = [0, 0, 3]
intensity = 5

[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
fov = 30
"#,
        );
        let s = load(&p).unwrap();
        assert_eq!(s.instances.len(), 2);
        assert_eq!(s.settings.spp, Some(8));
        assert_eq!(s.settings.sampler, Some(SamplerKind::Stratified));
        let t0 = s.world_triangle(0, 0);
        assert!((t0[1] - Vec3::new(11.0, 0.0, 0.0)).length() < 1e-5);
        // Scaled by 2, then turned 90 degrees about z: (1,0,0) -> (0,2,0).
        let t1 = s.world_triangle(1, 0);
        assert!((t1[1] - Vec3::new(0.0, 2.0, 0.0)).length() < 1e-5, "{t1:?}");
        assert_eq!(s.material_of(1).name, "gold");
        assert_ne!(s.material_of(0).name, "gold");
        assert_eq!(s.lights.len(), 1);
        assert_eq!(s.cameras[0].name, "scene file");
    }

    #[test]
    fn area_lights_face_where_they_are_told() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(
            dir.path(),
            "s.toml",
            r#"
[[light]]
type = "rect"
center = [0, 2, 0]
size = [2, 1]
look_at = [0, 0, 0]
strength = 3

[[light]]
type = "disk"
center = [1, 1, 1]
radius = 0.5
normal = [0, 0, 1]
strength = 1

[[light]]
type = "sphere"
center = [0, 1, 0]
radius = 0.1
color = [1, 0.5, 0.25]
strength = 4
"#,
        );
        let s = load(&p).unwrap();
        match s.lights[0] {
            super::super::Light::Rect(super::super::RectLight {
                corner,
                edge_u,
                edge_v,
                radiance,
            }) => {
                let n = edge_u.cross(edge_v).normalize();
                assert!((n - Vec3::NEG_Y).length() < 1e-6, "{n}");
                assert!(
                    (corner + 0.5 * (edge_u + edge_v) - Vec3::new(0.0, 2.0, 0.0)).length() < 1e-6
                );
                assert!((edge_u.length() * edge_v.length() - 2.0).abs() < 1e-5);
                assert_eq!(radiance, Vec3::splat(3.0));
            }
            ref l => panic!("{l:?}"),
        }
        assert!(matches!(s.lights[1], super::super::Light::Disk(d) if d.normal == Vec3::Z));
        assert!(
            matches!(s.lights[2], super::super::Light::Sphere(l) if l.radiance == Vec3::new(4.0, 2.0, 1.0))
        );
        let bad = write(
            dir.path(),
            "b.toml",
            "[[light]]\ntype = \"disk\"\ncenter = [0, 0, 0]\nradius = 1\nstrength = 1\n",
        );
        let e = load(&bad).unwrap_err().to_string();
        assert!(e.contains("line 1") && e.contains("normal"), "{e}");
    }

    #[test]
    fn moving_assets_lens_and_csg_objects() {
        let dir = tempfile::tempdir().unwrap();
        // A closed tetrahedron, to be cut by a box.
        write(
            dir.path(),
            "tet.obj",
            "o tet\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
        );
        write(
            dir.path(),
            "t.obj",
            "o tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        );
        let p = write(
            dir.path(),
            "s.toml",
            r#"
[[material]]
name = "red"
base_color = [1, 0, 0]

[[asset]]
path = "t.obj"
transform = { translate = [0, 0, 0] }
transform_end = { translate = [2, 0, 0] }

[[asset]]
path = "tet.obj"

[[object]]
csg = { difference = [ { mesh = "tet" }, { box = { min = [0.5, -1, -1], max = [2, 2, 2] } } ] }
material = "red"

[[object]]
csg = { sphere = { center = [0, 0, 0], radius = 0.5 } }
transform = { translate = [0, 3, 0] }
transform_end = { translate = [1, 3, 0], rotate_y = 90 }

[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
aperture = 0.1
shutter = [0, 0.5]
"#,
        );
        let s = load(&p).unwrap();
        // The moving triangle: at shutter close it has moved by (2, 0, 0).
        let m = s.instances[0].motion.as_ref().expect("the asset moves");
        let end = m.at(1.0).transform_point3(Vec3::ZERO);
        assert!((end - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-4, "{end}");
        // The tetrahedron became a CSG operand: its own instance left the scene.
        assert_eq!(s.instances.len(), 1);
        assert_eq!(s.csg.len(), 2);
        // The moving sphere turns as it goes: more than two time steps; the cut tetrahedron stays.
        assert!(!s.csg[0].moves() && s.csg[1].moves() && s.csg[1].time_steps() > 2);
        let moved = crate::geometry::Ray::new(Vec3::new(1.0, 3.0, 5.0), -Vec3::Z).with_time(1.0);
        assert!(s.csg[1].intersect(&moved).is_some());
        assert!(s.csg[1].intersect(&moved.with_time(0.0)).is_none());
        let lens = s.cameras[0].lens.expect("aperture gives a lens");
        assert!((lens.radius - 0.1).abs() < 1e-6 && (lens.focus_distance - 5.0).abs() < 1e-5);
        // A ray along x at y = z = 0.1 enters the cut tetrahedron at x = 0 and leaves at the cut.
        let ray = crate::geometry::Ray::new(Vec3::new(-1.0, 0.1, 0.1), Vec3::X);
        let (t, _) = s.csg[0].intersect(&ray).expect("hits the cut tetrahedron");
        assert!((t - 1.0).abs() < 1e-4, "{t}");
        let back = crate::geometry::Ray::new(Vec3::new(3.0, 0.1, 0.1), -Vec3::X);
        let (t, _) = s.csg[0].intersect(&back).expect("hits the cut face");
        assert!((t - 2.5).abs() < 1e-4, "{t}");
        let bad = write(
            dir.path(),
            "b.toml",
            "[[object]]\ncsg = { mesh = \"nothing\" }\n",
        );
        let e = load(&bad).unwrap_err().to_string();
        assert!(e.contains("line 1") && e.contains("nothing"), "{e}");
    }
}
