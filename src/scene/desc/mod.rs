//! Scene files (`scene.toml`): glTF/OBJ assets placed with transforms, named materials and overrides,
//! lights, a camera with lens and shutter, and render settings, gathered into one `Scene`.

use std::collections::HashMap;
use std::ops::Range;
use std::path::{Path, PathBuf};

use glam::Vec3;
use serde::Deserialize;
use toml::Spanned;

pub mod csg;
mod layers;
mod light;
mod material;
mod settings;

use light::LightDesc;
use material::MaterialDesc;
pub use settings::FileSettings;

use super::transform::TransformSpec;
use super::{Camera, LoadError, Material, Scene};

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
    /// KHR_materials_variants: the asset's material variant to dress it in (before `materials`
    /// re-dresses by name).
    variant: Option<Spanned<String>>,
}

/// A message about the byte range `span` of the file's text, as an error naming its line.
type At<'a> = dyn Fn(Range<usize>, String) -> LoadError + 'a;

/// Loads a scene file and every asset it names.
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| LoadError::new(path, format!("cannot read: {e}")))?;
    load_str(path, &text)
}

/// Reads a scene file whose text is in hand; `path` names it in errors, and its assets are read
/// from beside it.
pub fn load_str(path: &Path, text: &str) -> Result<Scene, LoadError> {
    if let Some(line) = super::limits::toml_too_deep(text) {
        return Err(LoadError::new(
            path,
            format!(
                "line {line}: arrays and tables nested more than {} deep",
                super::limits::MAX_TOML_NESTING
            ),
        ));
    }
    let desc: Desc = toml::from_str(text).map_err(|e| LoadError::new(path, e.to_string()))?;
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
    let named = add_materials(&mut scene, &desc.material, &at)?;
    let lookup = |name: &Spanned<String>| {
        named.get(name.get_ref()).copied().ok_or_else(|| {
            at(
                name.span(),
                format!("no material named '{}'", name.get_ref()),
            )
        })
    };
    let mut loaded = AssetFiles::new(desc.asset.iter().map(|a| dir.join(a.path.get_ref())));
    for a in &desc.asset {
        let t = (frame_time, shutter);
        add_asset(&mut scene, a, dir, t, &mut loaded, &lookup, &at)?;
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
        scene.cameras.insert(0, camera(path, c)?);
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

/// Adds the file's materials to the scene, by name; a name given twice is an error.
fn add_materials(
    scene: &mut Scene,
    materials: &[Spanned<MaterialDesc>],
    at: &At,
) -> Result<HashMap<String, u32>, LoadError> {
    let mut named: HashMap<String, u32> = HashMap::new();
    for m in materials {
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
    Ok(named)
}

/// Loads one asset, posed at `frame_time` over `shutter`, and appends it placed by its transforms with
/// its materials overridden as the file says.
/// The asset files of a scene file, each read once however many assets name it: a copy of the
/// loaded scene is far cheaper than parsing and decoding its textures again.
struct AssetFiles {
    /// Uses still to come, per file.
    uses: HashMap<PathBuf, usize>,
    /// Files read and named again later.
    kept: HashMap<PathBuf, Scene>,
}

impl AssetFiles {
    fn new(files: impl Iterator<Item = PathBuf>) -> Self {
        let mut uses = HashMap::new();
        for f in files {
            *uses.entry(f).or_insert(0) += 1;
        }
        Self {
            uses,
            kept: HashMap::new(),
        }
    }

    /// The scene of `file` for its next use: read at its first, kept while more follow (the load
    /// warnings come with the first only).
    fn take(&mut self, file: &Path) -> Result<Scene, LoadError> {
        let scene = match self.kept.remove(file) {
            Some(s) => s,
            None => Scene::load(file)?,
        };
        let left = self.uses.get_mut(file).map_or(0, |n| {
            *n = n.saturating_sub(1);
            *n
        });
        if left > 0 {
            let copy = Scene {
                warnings: Vec::new(),
                ..scene.clone()
            };
            self.kept.insert(file.to_path_buf(), copy);
        }
        Ok(scene)
    }
}

fn add_asset(
    scene: &mut Scene,
    a: &AssetDesc,
    dir: &Path,
    (frame_time, shutter): (f32, [f32; 2]),
    loaded: &mut AssetFiles,
    lookup: &dyn Fn(&Spanned<String>) -> Result<u32, LoadError>,
    at: &At,
) -> Result<(), LoadError> {
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
    let mut asset = loaded
        .take(&file)
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
    if let Some(v) = &a.variant {
        asset.select_variant(v.get_ref()).map_err(|e| {
            at(
                v.span(),
                format!("asset '{}': {}", rel.display(), e.message),
            )
        })?;
    }
    // Overrides replace the asset's materials before they join the scene's list.
    let remap = material_overrides(a, &asset, lookup, at)?;
    for w in asset.warnings.drain(..) {
        scene.warnings.push(format!("{}: {w}", rel.display()));
    }
    scene.append(asset, &remap, |u| blend(start, end, u));
    // Checked as the scene grows, so that a file naming one asset a million times stops early.
    if let Some(why) = scene.too_large() {
        return Err(at(
            a.path.span(),
            format!("asset '{}': {why}", rel.display()),
        ));
    }
    Ok(())
}

/// The asset's material indices that the scene file replaces (`material` for all of them, or
/// `materials` by name), with the scene-file materials replacing them.
fn material_overrides(
    a: &AssetDesc,
    asset: &Scene,
    lookup: &dyn Fn(&Spanned<String>) -> Result<u32, LoadError>,
    at: &At,
) -> Result<HashMap<usize, u32>, LoadError> {
    let rel = a.path.get_ref();
    let all = a.material.as_ref().map(lookup).transpose()?;
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
    Ok(remap)
}

/// The file's camera, with its thin lens when it has an aperture or f-number.
fn camera(path: &Path, c: &CameraDesc) -> Result<Camera, LoadError> {
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
    Ok(cam)
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
        let depth = desc.csg.depth();
        if depth > super::limits::MAX_CSG_DEPTH {
            return Err(fail(format!(
                "the CSG tree is {depth} levels deep, more than the {} glint accepts",
                super::limits::MAX_CSG_DEPTH
            )));
        }
        // Meshes are looked up (and made solid) before resolving, which only reads them.
        solid_operands(scene, &desc.csg, &mut solids, &mut used).map_err(fail)?;
        let root = desc
            .csg
            .resolve_with(
                &|n| named.get(n).copied(),
                &|n| solids.get(n).cloned(),
                default,
            )
            .map_err(|e| fail(e.to_string()))?;
        let start = desc.transform.to_mat4();
        let mut object =
            crate::csg::CsgObject::new(root, start).map_err(|e| fail(e.to_string()))?;
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

/// The meshes a CSG tree names as operands, made solid where their asset placed them (once per
/// name); their mesh indices go into `used`.
fn solid_operands(
    scene: &Scene,
    csg: &csg::NodeSpec,
    solids: &mut HashMap<String, std::sync::Arc<crate::csg::SolidMesh>>,
    used: &mut Vec<u32>,
) -> Result<(), String> {
    for name in mesh_names(csg) {
        if solids.contains_key(&name) {
            continue;
        }
        let Some(k) = scene.meshes.iter().position(|m| m.name == name) else {
            return Err(format!("no mesh named '{name}' in the assets"));
        };
        let mut mesh = scene.meshes[k].clone();
        if let Some(inst) = scene.instances.iter().find(|i| i.mesh as usize == k) {
            for p in &mut mesh.positions {
                *p = inst.to_world.transform_point3(*p);
            }
        }
        let solid = mesh.to_solid().map_err(|e| format!("mesh '{name}': {e}"))?;
        solids.insert(name, std::sync::Arc::new(solid));
        used.push(k as u32);
    }
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

#[cfg(test)]
mod tests;
