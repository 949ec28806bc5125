//! One in-memory `Scene` that every loader fills: meshes, instances, materials, textures, lights, cameras.
//! Loaders (`gltf`, `obj`) produce it; accelerators and the integrator only read it.

pub mod animated_properties;
pub mod animation;
pub mod decode;
pub mod defaults;
pub mod desc;
pub mod envmap;
pub mod error;
pub mod features;
pub mod generate;
pub mod gltf;
pub mod ktx2;
pub mod layers;
pub mod limits;
pub mod load_options;
pub mod mesh;
pub mod obj;
mod quiet_panic;
pub mod shading;
pub mod texture;
pub mod transform;
pub mod up_axis;
pub mod variants;

use std::path::{Path, PathBuf};

use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

use crate::csg::CsgObject;
use crate::geometry::Motion;
use crate::geometry::{Aabb, Hit, Ray};
pub use animation::Animation;
pub use envmap::EnvMap;
pub use error::LoadError;
pub use layers::MaterialLayers;
pub use load_options::{LoadOptions, SceneChoice};
pub use mesh::{Mesh, VertexAttrs};
pub use shading::{GgxScattering, Layering, ShadingModel};
pub use texture::{Texture, TextureFilter, Wrap};
pub use up_axis::UpAxis;
pub use variants::MaterialVariants;

/// One placement of a mesh in the world.
#[derive(Clone, Debug)]
pub struct Instance {
    pub mesh: u32,
    pub to_world: Mat4,
    /// Transforms normals to world space (inverse transpose of the linear part).
    pub normal_to_world: Mat3,
    /// Transforms over the shutter when the instance moves (then `to_world` is the one at time 0);
    /// moving instances are traced apart from the static world-space triangles.
    pub motion: Option<Motion>,
}

impl Instance {
    pub fn new(mesh: u32, to_world: Mat4) -> Self {
        let normal_to_world = Mat3::from_mat4(to_world).inverse().transpose();
        Self {
            mesh,
            to_world,
            normal_to_world,
            motion: None,
        }
    }

    /// Object to world at normalised shutter time `time`.
    #[inline]
    pub fn to_world_at(&self, time: f32) -> Mat4 {
        match &self.motion {
            Some(m) => m.at(time),
            None => self.to_world,
        }
    }

    pub fn is_identity(&self) -> bool {
        self.to_world == Mat4::IDENTITY
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AlphaMode {
    Opaque,
    /// Cut out where alpha < cutoff.
    Mask(f32),
    /// Partly transparent: a surface of alpha `a` stops a ray with probability `a`.
    Blend,
}

/// A texture binding: which texture, the texture coordinate set it reads, and the
/// KHR_texture_transform applied to the UVs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexRef {
    pub texture: u32,
    /// Row-major 2x3 affine UV transform (identity when the file has none).
    pub uv_transform: [[f32; 3]; 2],
    /// Texture coordinate set (below `mesh::UV_SETS`).
    pub tex_coord: u32,
}

impl TexRef {
    pub const IDENTITY_UV: [[f32; 3]; 2] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

    pub fn new(texture: u32) -> Self {
        Self {
            texture,
            uv_transform: Self::IDENTITY_UV,
            tex_coord: 0,
        }
    }

    /// Where this binding samples its texture at a point with these vertex attributes.
    pub fn uv_of(&self, attrs: &VertexAttrs) -> Vec2 {
        self.apply(attrs.sets[(self.tex_coord as usize).min(mesh::UV_SETS - 1)])
    }

    pub fn apply(&self, uv: Vec2) -> Vec2 {
        let m = &self.uv_transform;
        Vec2::new(
            m[0][0] * uv.x + m[0][1] * uv.y + m[0][2],
            m[1][0] * uv.x + m[1][1] * uv.y + m[1][2],
        )
    }
}

/// glTF's metallic-roughness material; OBJ/MTL materials are mapped onto it.
#[derive(Clone, Debug)]
pub struct Material {
    pub name: String,
    /// Linear RGB and alpha.
    pub base_color: Vec4,
    pub base_color_tex: Option<TexRef>,
    pub metallic: f32,
    pub roughness: f32,
    /// Roughness in G, metalness in B (glTF layout).
    pub metallic_roughness_tex: Option<TexRef>,
    pub normal_tex: Option<TexRef>,
    pub normal_scale: f32,
    /// Linear RGB radiance, emissive strength included.
    pub emissive: Vec3,
    pub emissive_tex: Option<TexRef>,
    pub alpha_mode: AlphaMode,
    pub double_sided: bool,
    /// Strength of the dielectric specular layer (KHR_materials_specular's factor; 0 = pure Lambert).
    pub specular: f32,
    /// KHR_materials_transmission factor: the fraction of the light entering the dielectric base
    /// that passes through the surface (0 = opaque).
    pub transmission: f32,
    /// Multiplies `transmission` by its R channel.
    pub transmission_tex: Option<TexRef>,
    /// Index of refraction of the dielectric (KHR_materials_ior; sets F0 and the refraction).
    pub ior: f32,
    /// KHR_materials_volume's thicknessFactor: 0 means thin-walled (light passes straight through
    /// the surface unbent, as glTF treats transmission without a volume); above 0 the mesh bounds
    /// a refracting medium whose real thickness the path tracer measures along each ray.
    pub thickness: f32,
    /// Beer-Lambert absorption of the medium: light keeps `attenuation_color` after travelling
    /// `attenuation_distance` inside it (infinite: no absorption).
    pub attenuation_color: Vec3,
    pub attenuation_distance: f32,
    /// KHR_materials_unlit: the base colour is emitted as it is, unlit, and nothing bounces off it.
    pub unlit: bool,
    /// KHR_materials_specular's colour (F0 tint) and textures, and the clearcoat and sheen layers.
    pub layers: MaterialLayers,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            name: "default".into(),
            base_color: Vec4::ONE,
            base_color_tex: None,
            metallic: 1.0,
            roughness: 1.0,
            metallic_roughness_tex: None,
            normal_tex: None,
            normal_scale: 1.0,
            emissive: Vec3::ZERO,
            emissive_tex: None,
            alpha_mode: AlphaMode::Opaque,
            double_sided: false,
            specular: 1.0,
            transmission: 0.0,
            transmission_tex: None,
            ior: 1.5,
            thickness: 0.0,
            attenuation_color: Vec3::ONE,
            attenuation_distance: f32::INFINITY,
            unlit: false,
            layers: MaterialLayers::default(),
        }
    }
}

impl Material {
    /// Every texture binding of the material (for renumbering when scenes are combined).
    pub fn textures_mut(&mut self) -> impl Iterator<Item = &mut TexRef> {
        [
            &mut self.base_color_tex,
            &mut self.metallic_roughness_tex,
            &mut self.normal_tex,
            &mut self.emissive_tex,
            &mut self.transmission_tex,
        ]
        .into_iter()
        .chain(self.layers.textures_mut())
        .flatten()
    }

    /// Whether some texel emits. Features are derived from what the material can do at any texel: a
    /// texture multiplies its factor by a value in [0, 1], so a factor with a texture may take any
    /// value between 0 and the factor.
    pub fn is_emissive(&self) -> bool {
        self.emissive.max_element() > 0.0
    }

    /// Whether light can pass through the surface somewhere (KHR_materials_transmission or
    /// KHR_materials_diffuse_transmission where it is not a metal): metalness below 1 at some
    /// texel, which a metallic texture can give whatever the factor.
    pub fn is_transmissive(&self) -> bool {
        (self.transmission > 0.0 || self.layers.diffuse_transmission.is_some())
            && self.can_be_dielectric()
    }

    /// Whether a smooth part of the surface can pass light straight through (specular
    /// transmission; diffuse transmission scatters, so shadow rays never see through it).
    pub fn is_specular_transmissive(&self) -> bool {
        self.transmission > 0.0 && self.can_be_dielectric()
    }

    /// Whether the metalness is below 1 at some texel.
    pub fn can_be_dielectric(&self) -> bool {
        self.metallic < 1.0 || self.metallic_roughness_tex.is_some()
    }

    /// Transmissive without a volume: the surface is a thin wall with no inside.
    pub fn is_thin_walled(&self) -> bool {
        self.thickness <= 0.0
    }

    /// The medium's absorption coefficient per unit length (zero when it does not absorb).
    pub fn absorption(&self) -> Vec3 {
        if !(self.attenuation_distance.is_finite() && self.attenuation_distance > 0.0) {
            return Vec3::ZERO;
        }
        let c = self.attenuation_color.clamp(Vec3::splat(1e-6), Vec3::ONE);
        -Vec3::new(c.x.ln(), c.y.ln(), c.z.ln()) / self.attenuation_distance
    }

    /// Whether hits on this material need an alpha test (cutouts or blending) on any mesh; a mesh's
    /// vertex colours can lower the alpha too (`Scene::mesh_needs_alpha_test`).
    pub fn needs_alpha_test(&self) -> bool {
        match self.alpha_mode {
            AlphaMode::Opaque => false,
            AlphaMode::Mask(_) | AlphaMode::Blend => {
                self.base_color_tex.is_some() || self.base_color.w < 1.0
            }
        }
    }
}

/// Lights given by the file (KHR_lights_punctual, scene files) or added by the default rig. Emissive
/// triangles are lights too, but they live in the materials; the integrator collects them. The
/// analytic area lights (sphere, disk, rectangle) are not geometry: they emit and are seen, but cast
/// no shadow on each other or on the scene. Radiance is linear RGB in W/(m^2 sr).
#[derive(Clone, Debug, PartialEq)]
pub enum Light {
    Point(PointLight),
    Spot(SpotLight),
    Directional(DirectionalLight),
    Sphere(SphereLight),
    Disk(DiskLight),
    Rect(RectLight),
    /// Radiance from every direction not blocked by the scene: `radiance` times the map's value in
    /// that direction, or constant `radiance` without a map.
    Environment {
        radiance: Vec3,
        map: Option<std::sync::Arc<EnvMap>>,
    },
}

/// A point emitting `intensity` in W/sr (glTF candela, linear RGB) in every direction. Every light
/// but the environment is a struct, so that the renderer holds the scene's value rather than a copy
/// of its fields.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLight {
    pub position: Vec3,
    pub intensity: Vec3,
}

/// A point light limited to a cone about its unit `direction` (where it points to), fading from
/// full at `cos_inner` to nothing at `cos_outer`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpotLight {
    pub position: Vec3,
    pub direction: Vec3,
    pub intensity: Vec3,
    pub cos_inner: f32,
    pub cos_outer: f32,
}

/// Light from infinitely far: `irradiance` (glTF lux) on a surface facing it, travelling along the
/// unit `direction`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionalLight {
    pub direction: Vec3,
    pub irradiance: Vec3,
}

/// A sphere emitting `radiance` outwards from every point of its surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereLight {
    pub center: Vec3,
    pub radius: f32,
    pub radiance: Vec3,
}

/// A disk emitting on the side its unit `normal` faces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiskLight {
    pub center: Vec3,
    pub normal: Vec3,
    pub radius: f32,
    pub radiance: Vec3,
}

/// The parallelogram `corner + s * edge_u + t * edge_v` (s, t in [0, 1]), emitting towards
/// `edge_u x edge_v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RectLight {
    pub corner: Vec3,
    pub edge_u: Vec3,
    pub edge_v: Vec3,
    pub radiance: Vec3,
}

impl Light {
    /// For an analytic area light, the point light at its centre with the intensity it has along
    /// its axis (radiance times projected area), so it lights what faces it about as brightly but
    /// casts hard shadows; None for other lights.
    pub fn as_point_light(&self) -> Option<Light> {
        let (position, area, radiance) = match *self {
            Light::Sphere(SphereLight {
                center,
                radius,
                radiance,
            })
            | Light::Disk(DiskLight {
                center,
                radius,
                radiance,
                ..
            }) => (center, std::f32::consts::PI * radius * radius, radiance),
            Light::Rect(r) => (
                r.corner + 0.5 * (r.edge_u + r.edge_v),
                r.edge_u.cross(r.edge_v).length(),
                r.radiance,
            ),
            _ => return None,
        };
        Some(Light::Point(PointLight {
            position,
            intensity: radiance * area,
        }))
    }

    /// The light moved by an affine transform: positions as points, directions as vectors (renormalised),
    /// normals by the inverse transpose, radii by the transform's mean scale, environment maps by its
    /// rotation (a constant environment is unchanged).
    pub fn transformed(&self, m: &Mat4) -> Light {
        let dir = |d: Vec3| m.transform_vector3(d).normalize_or_zero();
        let scale = m.determinant().abs().cbrt();
        match *self {
            Light::Sphere(s) => Light::Sphere(SphereLight {
                center: m.transform_point3(s.center),
                radius: s.radius * scale,
                ..s
            }),
            Light::Disk(d) => Light::Disk(DiskLight {
                center: m.transform_point3(d.center),
                normal: m
                    .inverse()
                    .transpose()
                    .transform_vector3(d.normal)
                    .normalize_or_zero(),
                radius: d.radius * scale,
                ..d
            }),
            Light::Rect(r) => Light::Rect(RectLight {
                corner: m.transform_point3(r.corner),
                edge_u: m.transform_vector3(r.edge_u),
                edge_v: m.transform_vector3(r.edge_v),
                ..r
            }),
            Light::Environment { radiance, ref map } => Light::Environment {
                radiance,
                map: map.as_ref().map(|e| {
                    // Only the rotation part turns a map; the columns are renormalised so that a
                    // scale or translation does not distort it.
                    let r = Mat3::from_mat4(*m);
                    let r = Mat3::from_cols(
                        r.x_axis.normalize_or_zero(),
                        r.y_axis.normalize_or_zero(),
                        r.z_axis.normalize_or_zero(),
                    );
                    let mut e = EnvMap::clone(e);
                    e.rotation = r * e.rotation;
                    std::sync::Arc::new(e)
                }),
            },
            Light::Point(l) => Light::Point(PointLight {
                position: m.transform_point3(l.position),
                ..l
            }),
            Light::Spot(l) => Light::Spot(SpotLight {
                position: m.transform_point3(l.position),
                direction: dir(l.direction),
                ..l
            }),
            Light::Directional(l) => Light::Directional(DirectionalLight {
                direction: dir(l.direction),
                ..l
            }),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Vertical field of view in radians; aspect ratio from the file, or from the image when absent.
    Perspective { yfov: f32, aspect: Option<f32> },
    /// Half extents of the view.
    Orthographic { xmag: f32, ymag: f32 },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub name: String,
    /// Camera to world; the camera looks down its -Z with +Y up (glTF convention).
    pub to_world: Mat4,
    pub projection: Projection,
    /// A thin lens for depth of field; None is a pinhole.
    pub lens: Option<Lens>,
    /// Camera to world over the shutter when the camera moves (`to_world` is the one at time 0).
    pub motion: Option<Motion>,
}

/// A thin lens: rays leave a disk of `radius` (scene units) and meet on the plane `focus_distance`
/// in front of the camera, where everything is sharp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lens {
    pub radius: f32,
    pub focus_distance: f32,
}

/// Sensor height that `--fstop` assumes to turn the vertical field of view into a focal length:
/// 24 mm (full frame), with scene units in metres.
pub const SENSOR_HEIGHT_M: f32 = 0.024;

impl Lens {
    /// The lens of f-number `fstop` for a camera of vertical field of view `yfov` on a full-frame
    /// sensor: focal length f = (h / 2) / tan(yfov / 2), aperture radius f / (2 N).
    pub fn from_fstop(fstop: f32, yfov: f32, focus_distance: f32) -> Self {
        let focal = 0.5 * SENSOR_HEIGHT_M / (0.5 * yfov).tan();
        Self {
            radius: focal / (2.0 * fstop),
            focus_distance,
        }
    }
}

impl Camera {
    pub fn look_at(eye: Vec3, target: Vec3, up: Vec3, yfov: f32) -> Self {
        Self {
            name: "look-at".into(),
            to_world: Mat4::look_at_rh(eye, target, up).inverse(),
            projection: Projection::Perspective { yfov, aspect: None },
            lens: None,
            motion: None,
        }
    }

    pub fn position(&self) -> Vec3 {
        self.to_world.w_axis.truncate()
    }
}

/// What the file held, for `glint info` (counts from the file, not after flattening).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneStats {
    pub nodes: usize,
    pub meshes: usize,
    pub primitives: usize,
    /// Triangles over all instances (a mesh used twice counts twice).
    pub triangles: usize,
    pub materials: usize,
    pub textures: usize,
    pub lights: usize,
    pub cameras: usize,
    pub animations: usize,
    /// The file's `extensionsUsed` and `extensionsRequired` (glTF files only).
    pub extensions_used: Vec<String>,
    pub extensions_required: Vec<String>,
    /// A glTF file's scenes by index and name (`--scene` chooses one).
    pub scenes: Vec<String>,
}

#[derive(Clone, Debug, Default)]
pub struct Scene {
    pub source: PathBuf,
    pub meshes: Vec<Mesh>,
    pub instances: Vec<Instance>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub lights: Vec<Light>,
    pub cameras: Vec<Camera>,
    /// Constructive-solid-geometry objects, hit as `Hit::csg` (see `geometry::Hit`).
    pub csg: Vec<CsgObject>,
    pub stats: SceneStats,
    /// The file's animation (the first, or the one chosen when loading); `animation::pose` applies it.
    pub animation: Option<Animation>,
    /// Non-fatal problems met while loading (skipped primitives, dropped triangles), one line each.
    pub warnings: Vec<String>,
    /// Render settings from a scene file (empty for model files).
    pub settings: desc::FileSettings,
    /// KHR_materials_variants: the material sets the meshes can be dressed in.
    pub variants: MaterialVariants,
    /// The shading model the render uses (the glTF specification's unless a scene file or the
    /// command line chooses otherwise; set when a render is set up).
    pub shading: ShadingModel,
}

impl Scene {
    /// Loads a .gltf, .glb, .obj or .toml (scene) file, chosen by extension (with a glTF file's first
    /// animation).
    pub fn load(path: &Path) -> Result<Scene, LoadError> {
        Self::load_with(path, &LoadOptions::default())
    }

    /// Loads a file keeping the scene and animation `opts` choose of a glTF file (an error when the
    /// file lacks that one; for other files, any scene but the default is an error).
    pub fn load_with(path: &Path, opts: &LoadOptions) -> Result<Scene, LoadError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .unwrap_or_default();
        if !path.exists() {
            return Err(LoadError::new(path, "no such file"));
        }
        let mut scene = match ext.as_str() {
            "gltf" | "glb" => gltf::load(path, opts)?,
            _ if opts.scene != SceneChoice::Default => {
                return Err(LoadError::new(
                    path,
                    format!(
                        "{} asked for, but only glTF files hold several scenes",
                        opts.scene
                    ),
                ))
            }
            "obj" => obj::load(path)?,
            "toml" => desc::load(path)?,
            _ => {
                return Err(LoadError::new(
                    path,
                    format!("unsupported file type '.{ext}' (expected .gltf, .glb, .obj or .toml)"),
                ))
            }
        };
        scene.source = path.to_path_buf();
        scene.validate()?;
        Ok(scene)
    }

    /// Checks the invariants the accelerators rely on; a loader bug or odd file becomes an error here.
    pub fn validate(&self) -> Result<(), LoadError> {
        let err = |m: String| Err(LoadError::new(&self.source, m));
        if let Some(why) = self.too_large() {
            return err(why);
        }
        for (i, m) in self.meshes.iter().enumerate() {
            let n = m.positions.len() as u32;
            if m.indices.iter().flatten().any(|&k| k >= n) {
                return err(format!(
                    "mesh {i} ('{}'): vertex index out of range",
                    m.name
                ));
            }
            if m.normals.len() != m.positions.len() {
                return err(format!("mesh {i} ('{}'): normals missing", m.name));
            }
            if m.material as usize >= self.materials.len() {
                return err(format!("mesh {i} ('{}'): material out of range", m.name));
            }
        }
        for (i, inst) in self.instances.iter().enumerate() {
            if inst.mesh as usize >= self.meshes.len() {
                return err(format!("instance {i}: mesh out of range"));
            }
            if !inst.to_world.is_finite() {
                return err(format!("instance {i}: transform is not finite"));
            }
        }
        for (i, c) in self.csg.iter().enumerate() {
            if let Some(m) = c.materials().find(|&m| m as usize >= self.materials.len()) {
                return err(format!("CSG object {i}: material {m} out of range"));
            }
        }
        Ok(())
    }

    /// Moves everything of `other` into this scene, placed by `placement` (normalised shutter time
    /// to transform; lights and cameras where it is at time 0); its material `i` becomes this
    /// scene's `remap[i]` where given, and a copy otherwise.
    pub fn append(
        &mut self,
        other: Scene,
        remap: &std::collections::HashMap<usize, u32>,
        placement: impl Fn(f32) -> Mat4,
    ) {
        let to_world = placement(0.0);
        let (mesh0, tex0) = (self.meshes.len() as u32, self.textures.len() as u32);
        self.append_instances(&other, mesh0, &placement);
        let mut material_index = Vec::with_capacity(other.materials.len());
        for (i, mut m) in other.materials.into_iter().enumerate() {
            if let Some(&k) = remap.get(&i) {
                material_index.push(k);
                continue;
            }
            for t in m.textures_mut() {
                t.texture += tex0;
            }
            material_index.push(self.materials.len() as u32);
            self.materials.push(m);
        }
        self.textures.extend(other.textures);
        self.variants
            .append(&other.variants, mesh0, &material_index);
        self.meshes.extend(other.meshes.into_iter().map(|mut m| {
            m.material = material_index[m.material as usize];
            m
        }));
        self.lights
            .extend(other.lights.iter().map(|l| l.transformed(&to_world)));
        self.cameras.extend(other.cameras.into_iter().map(|mut c| {
            c.to_world = to_world * c.to_world;
            c
        }));
        let (s, o) = (&mut self.stats, &other.stats);
        s.nodes += o.nodes;
        s.meshes += o.meshes;
        s.primitives += o.primitives;
        s.textures += o.textures;
        s.animations += o.animations;
    }

    /// Adds `other`'s instances (meshes numbered from `mesh0`) placed by `placement` (normalised
    /// shutter time to transform); an instance moves when it or its placement does.
    pub fn append_instances(&mut self, other: &Scene, mesh0: u32, placement: impl Fn(f32) -> Mat4) {
        let placement_moves = placement(0.0) != placement(1.0);
        for i in &other.instances {
            let mut inst = Instance::new(i.mesh + mesh0, placement(0.0) * i.to_world_at(0.0));
            if placement_moves || i.motion.is_some() {
                let object = other.meshes[i.mesh as usize].bounds();
                inst.motion = Motion::of_object(|u| placement(u) * i.to_world_at(u), &object);
            }
            self.instances.push(inst);
        }
    }

    /// Dresses the meshes in material variant `name` (KHR_materials_variants); an unknown name is an
    /// error listing the known ones.
    pub fn select_variant(&mut self, name: &str) -> Result<(), LoadError> {
        let mut materials: Vec<u32> = self.meshes.iter().map(|m| m.material).collect();
        self.variants
            .apply(name, &mut materials)
            .map_err(|e| LoadError::new(&self.source, e.to_string()))?;
        for (m, k) in self.meshes.iter_mut().zip(materials) {
            m.material = k;
        }
        Ok(())
    }

    pub fn mesh_of(&self, inst: u32) -> &Mesh {
        &self.meshes[self.instances[inst as usize].mesh as usize]
    }

    /// The world-space vertices of triangle `prim` of instance `inst`.
    pub fn world_triangle(&self, inst: u32, prim: u32) -> [Vec3; 3] {
        let instance = &self.instances[inst as usize];
        self.meshes[instance.mesh as usize]
            .triangle(prim)
            .map(|p| instance.to_world.transform_point3(p))
    }

    pub fn material_of_mesh(&self, mesh: u32) -> &Material {
        &self.materials[self.meshes[mesh as usize].material as usize]
    }

    pub fn material_of(&self, inst: u32) -> &Material {
        &self.materials[self.mesh_of(inst).material as usize]
    }

    /// World-space bounds of every instance and CSG object.
    pub fn bounds(&self) -> Aabb {
        let meshes = self.instances.iter().fold(Aabb::EMPTY, |b, inst| {
            let object = self.meshes[inst.mesh as usize].bounds();
            b.union(match &inst.motion {
                Some(m) => m.bounds(&object),
                None => object.transformed(&inst.to_world),
            })
        });
        self.csg.iter().fold(meshes, |b, c| b.union(c.bounds()))
    }

    /// Asks the cache for the vertex indices of the triangle `hit` names (a hint: shading reads them
    /// next, and on a large mesh they are rarely in the cache after the ray query).
    #[inline]
    pub fn prefetch_triangle(&self, hit: &Hit) {
        if hit.csg().is_none() {
            if let Some(tri) = self.mesh_of(hit.inst).indices.get(hit.prim as usize) {
                crate::geometry::prefetch(tri);
            }
        }
    }

    /// The hit point and (unit, unoriented) geometric normal of a hit on a triangle or a CSG surface.
    pub fn hit_geometry(&self, hit: &Hit, ray: &Ray) -> (Vec3, Vec3) {
        if let Some((object, surface)) = hit.csg() {
            let s = self.csg[object as usize].surface(surface, ray.at(hit.t), ray.time);
            return (s.p, s.n);
        }
        // Where the instance is at the ray's time (moving instances differ from `world_triangle`).
        let m = self.instances[hit.inst as usize].to_world_at(ray.time);
        let [a, b, c] = self
            .mesh_of(hit.inst)
            .triangle(hit.prim)
            .map(|p| m.transform_point3(p));
        let p = a * (1.0 - hit.u - hit.v) + b * hit.u + c * hit.v;
        (p, (b - a).cross(c - a).normalize_or_zero())
    }

    /// Whether anything moves during the shutter (instances or cameras with `Motion`).
    pub fn has_motion(&self) -> bool {
        self.instances.iter().any(|i| i.motion.is_some())
            || self.cameras.iter().any(|c| c.motion.is_some())
            || self.csg.iter().any(|c| c.moves())
    }

    pub fn triangle_count(&self) -> usize {
        self.instances
            .iter()
            .map(|i| self.meshes[i.mesh as usize].indices.len())
            .sum()
    }

    /// Why the scene is more than glint accepts (`limits`), or None; meshes out of range count as
    /// empty here (`validate` reports them).
    pub fn too_large(&self) -> Option<String> {
        let triangles = self
            .instances
            .iter()
            .map(|i| {
                self.meshes
                    .get(i.mesh as usize)
                    .map_or(0, |m| m.indices.len())
            })
            .fold(0usize, usize::saturating_add);
        limits::too_large(self.instances.len(), triangles)
    }

    /// Whether hits on mesh `mesh` need an alpha test: its material cuts out or blends, and its alpha
    /// can fall below 1 somewhere (the factor, a base colour texture, or COLOR_0's alpha).
    pub fn mesh_needs_alpha_test(&self, mesh: u32) -> bool {
        let m = &self.meshes[mesh as usize];
        let mat = &self.materials[m.material as usize];
        mat.needs_alpha_test()
            || (mat.alpha_mode != AlphaMode::Opaque && m.colors.iter().any(|c| c.w < 1.0))
    }

    /// Whether a candidate hit counts, for materials with alpha cutouts or blending. Accelerators call
    /// this for meshes whose material `needs_alpha_test`. Blending is stochastic but deterministic per
    /// ray and triangle, so every backend makes the same choice.
    pub fn alpha_passes(&self, inst: u32, prim: u32, u: f32, v: f32, ray: &Ray) -> bool {
        let mesh = self.mesh_of(inst);
        let mat = &self.materials[mesh.material as usize];
        let alpha = self.base_color(mat, mesh.uv_at(prim, u, v)).w;
        match mat.alpha_mode {
            AlphaMode::Opaque => true,
            AlphaMode::Mask(cutoff) => alpha >= cutoff,
            AlphaMode::Blend => blend_hash(ray, inst, prim) < alpha,
        }
    }

    /// Base colour (linear RGB, alpha) of a material at a texture coordinate.
    pub fn base_color(&self, mat: &Material, uv: VertexAttrs) -> Vec4 {
        let c = mat.base_color * uv.color;
        match mat.base_color_tex {
            Some(t) => c * self.textures[t.texture as usize].sample(t.uv_of(&uv)),
            None => c,
        }
    }
}

/// A uniform number in [0, 1) from the ray's seed and the triangle: the same in every backend and run.
fn blend_hash(ray: &Ray, inst: u32, prim: u32) -> f32 {
    let key = (ray.seed as u64) << 32 ^ (inst as u64) << 24 ^ prim as u64;
    (crate::geometry::mix64(key ^ 0x9E37_79B9_7F4A_7C15) >> 40) as f32 / (1u64 << 24) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    #[test]
    fn area_and_environment_lights_move_with_a_transform() {
        let m = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0))
            * Mat4::from_rotation_y(0.8)
            * Mat4::from_scale(Vec3::splat(2.0));
        let r = Mat3::from_rotation_y(0.8);
        let radiance = Vec3::ONE;
        let moved = |l: Light| l.transformed(&m);
        let Light::Sphere(SphereLight { center, radius, .. }) = moved(Light::Sphere(SphereLight {
            center: Vec3::X,
            radius: 0.5,
            radiance,
        })) else {
            unreachable!()
        };
        assert!(
            (center - m.transform_point3(Vec3::X)).length() < 1e-5 && (radius - 1.0).abs() < 1e-5
        );
        let Light::Disk(DiskLight { normal, radius, .. }) = moved(Light::Disk(DiskLight {
            center: Vec3::ZERO,
            normal: Vec3::X,
            radius: 1.0,
            radiance,
        })) else {
            unreachable!()
        };
        assert!((normal - r * Vec3::X).length() < 1e-5 && (radius - 2.0).abs() < 1e-5);
        let Light::Rect(RectLight { edge_u, edge_v, .. }) = moved(Light::Rect(RectLight {
            corner: Vec3::ZERO,
            edge_u: Vec3::X,
            edge_v: Vec3::Z,
            radiance,
        })) else {
            unreachable!()
        };
        assert!((edge_u.cross(edge_v).normalize() - r * -Vec3::Y).length() < 1e-5);
        // A turned map shows the turned world the same radiance: lookup(R d) after = lookup(d) before.
        let px = (0..32).map(|i| Vec3::splat(i as f32)).collect();
        let map = Arc::new(EnvMap::new(8, 4, px).unwrap());
        let Light::Environment {
            map: Some(turned), ..
        } = moved(Light::Environment {
            radiance,
            map: Some(map.clone()),
        })
        else {
            unreachable!()
        };
        for d in [
            Vec3::new(0.3, 0.4, -0.8),
            Vec3::new(-0.7, -0.1, 0.2),
            Vec3::X,
        ] {
            let d = d.normalize();
            assert_eq!(turned.lookup(r * d), map.lookup(d));
        }
        let constant = Light::Environment {
            radiance,
            map: None,
        };
        assert_eq!(moved(constant.clone()), constant);
    }
}
