//! Scene files (`scene.toml`): glTF/OBJ assets placed with transforms, named materials and overrides,
//! lights, a camera with lens and shutter, and render settings, gathered into one `Scene`.

use std::collections::HashMap;
use std::ops::Range;
use std::path::{Path, PathBuf};

use glam::Vec3;
use serde::Deserialize;
use toml::Spanned;

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
    light: Vec<LightDesc>,
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
    Environment(EnvironmentDesc),
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
        let to_world = a.transform.to_mat4();
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
        scene.append(asset, to_world, &remap);
    }

    for l in &desc.light {
        scene.lights.push(l.to_light());
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

impl LightDesc {
    fn to_light(&self) -> super::Light {
        use super::Light;
        match self {
            LightDesc::Point(p) => Light::Point {
                position: p.position.into(),
                intensity: Vec3::from(p.color) * p.intensity,
            },
            LightDesc::Spot(s) => Light::Spot {
                position: s.position.into(),
                direction: (Vec3::from(s.look_at) - Vec3::from(s.position)).normalize_or_zero(),
                intensity: Vec3::from(s.color) * s.intensity,
                cos_inner: s.inner_angle.to_radians().cos(),
                cos_outer: s.outer_angle.to_radians().cos(),
            },
            LightDesc::Directional(d) => Light::Directional {
                direction: Vec3::from(d.direction).normalize_or_zero(),
                irradiance: Vec3::from(d.color) * d.irradiance,
            },
            LightDesc::Environment(e) => Light::Environment {
                radiance: Vec3::from(e.color) * e.strength,
            },
        }
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
}
