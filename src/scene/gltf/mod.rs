//! glTF 2.0 loader (.gltf with external or data-URI buffers, and .glb): the entry `load` and the walk
//! of the node hierarchy that places meshes, lights and cameras.
//!
//! The `gltf` crate parses and validates the JSON; buffers are read through it too, but every accessor
//! is read here (`accessor`), with its extent checked against its buffer view and buffer first, so that
//! a malformed file becomes a `LoadError` naming the element instead of a panic. Each (mesh, primitive)
//! pair becomes one `Mesh` (`mesh`); every node that uses it adds an `Instance`.

mod accessor;
mod animation;
mod buffers;
#[cfg(feature = "draco")]
mod draco;
pub mod error;
mod image;
mod instancing;
mod light;
mod lobes;
mod material;
mod mesh;
pub mod meshopt;
mod pointer;
mod spec_gloss;
#[cfg(test)]
mod tests;
mod variants;

use std::collections::HashMap;
use std::path::Path;
use std::rc::Rc;

use glam::{Mat4, Vec3, Vec4};

pub use error::GltfError;
#[cfg(test)]
pub(crate) use material::uv_transform;

use super::{Camera, Instance, LoadError, LoadOptions, Scene, SceneChoice};

/// Extensions glint implements: a file may require them, and using any other draws a warning.
const SUPPORTED: &[&str] = &[
    "KHR_animation_pointer",
    "KHR_lights_punctual",
    "KHR_materials_anisotropy",
    "KHR_materials_clearcoat",
    "KHR_materials_diffuse_transmission",
    "KHR_materials_dispersion",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_iridescence",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_unlit",
    "KHR_materials_variants",
    "KHR_materials_volume",
    "KHR_texture_transform",
    // Integer attributes (normalized or not) are what the accessor reader decodes anyway; the
    // dequantizing scale and offset live in node transforms and texture transforms.
    "KHR_mesh_quantization",
    "EXT_mesh_gpu_instancing",
    "EXT_meshopt_compression",
    "KHR_meshopt_compression",
    #[cfg(feature = "draco")]
    "KHR_draco_mesh_compression",
    "EXT_texture_webp",
    "KHR_texture_basisu",
];

/// One morph target's position and normal displacements.
type MorphTarget = (Vec<Vec3>, Vec<Vec3>);
/// Per-vertex joints and weights of a skinned mesh.
type SkinAttrs = (Vec<[u16; 4]>, Vec<Vec4>);

/// Loads a .gltf or .glb file keeping the scene and animation `opts` choose. Never panics on
/// malformed input: every problem is a `LoadError`.
pub fn load(path: &Path, opts: &LoadOptions) -> Result<Scene, LoadError> {
    let bytes =
        std::fs::read(path).map_err(|e| LoadError::new(path, GltfError::Read(e).to_string()))?;
    load_bytes(path, &bytes, opts)
}

/// Loads a .gltf or .glb file whose bytes are in hand; `path` names it in errors, and relative URIs
/// (external buffers and images) resolve beside it.
pub fn load_bytes(path: &Path, bytes: &[u8], opts: &LoadOptions) -> Result<Scene, LoadError> {
    match super::quiet_panic::catch(|| load_inner(path, bytes, opts)) {
        Some(r) => r.map_err(|e| LoadError::new(path, e.to_string())),
        None => Err(LoadError::new(
            path,
            "internal error in the glTF reader (the file is inconsistent in a way glint does not check)",
        )),
    }
}

fn load_inner(path: &Path, bytes: &[u8], opts: &LoadOptions) -> Result<Scene, GltfError> {
    let base = path.parent().unwrap_or_else(|| Path::new("."));
    let (json_bytes, blob) = if bytes.starts_with(b"glTF") {
        accessor::split_glb(bytes)?
    } else {
        let json = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
        (json, None)
    };
    let (json_bytes, pointers) = pointer::extract(json_bytes)?;
    let (doc, required) = document(&json_bytes)?;
    let mut buffers = accessor::read_buffers(&doc, base, blob)?;
    let doc = meshopt::decode_views(doc, &mut buffers)?;
    #[cfg_attr(not(feature = "draco"), allow(unused_mut))]
    let mut decode_warnings = Vec::new();
    #[cfg(feature = "draco")]
    let doc = draco::decode_primitives(doc, &mut buffers, &mut decode_warnings)?;
    let buffers = buffers::Buffers::new(buffers);
    Loader {
        doc: &doc,
        buffers: &buffers,
        base,
        scene: Scene {
            warnings: decode_warnings,
            ..Scene::default()
        },
        prims: HashMap::new(),
        textures: HashMap::new(),
        gloss_textures: HashMap::new(),
        images: HashMap::new(),
        default_material: None,
        dropped: 0,
        animation: opts.animation,
        scene_choice: &opts.scene,
        skin_attrs: HashMap::new(),
        morph_attrs: HashMap::new(),
        pointers,
    }
    .run(required)
}

/// Each scene of the file by index and name, for errors and `glint info`.
pub(super) fn scene_names(doc: &gltf::Document) -> Vec<String> {
    doc.scenes()
        .map(|s| match s.name() {
            Some(n) => format!("{} '{n}'", s.index()),
            None => s.index().to_string(),
        })
        .collect()
}

/// The validated document of a JSON chunk, its required extensions checked against glint's (and
/// returned, since the document no longer lists them).
fn document(json: &[u8]) -> Result<(gltf::Document, Vec<String>), GltfError> {
    let mut root: gltf::json::Root =
        gltf::json::deserialize::from_slice(json).map_err(GltfError::Json)?;
    if let Some(ext) = root
        .extensions_required
        .iter()
        .find(|e| !SUPPORTED.contains(&e.as_str()))
    {
        return Err(GltfError::UnsupportedExtension(ext.clone()));
    }
    // The crate's validation refuses required extensions it has no code for (KHR_materials_volume);
    // glint has checked them above.
    let required = std::mem::take(&mut root.extensions_required);
    image::prefer_extension_sources(&mut root);
    let fallback = root.clone();
    // Draco primitives' accessors have no data of their own: the decoder fills them in.
    #[cfg(feature = "draco")]
    let draco_views = draco::fallback_views(&root);
    #[cfg(not(feature = "draco"))]
    let draco_views: Vec<String> = Vec::new();
    let doc = match gltf::Document::from_json(root) {
        Ok(doc) => Ok(doc),
        // POSITION's min/max are required by the spec but unused here: tolerate files without them.
        Err(gltf::Error::Validation(errs))
            if errs.iter().all(|(p, e)| {
                matches!(e, gltf::json::validation::Error::Missing)
                    && (p.as_str().ends_with(".min")
                        || p.as_str().ends_with(".max")
                        || draco_views.iter().any(|v| v == p.as_str()))
            }) =>
        {
            Ok(gltf::Document::from_json_without_validation(fallback))
        }
        Err(gltf::Error::Validation(errs)) => Err(GltfError::Validation {
            first: errs
                .iter()
                .take(5)
                .map(|(p, e)| format!("{p}: {e}"))
                .collect(),
            total: errs.len(),
        }),
        Err(e) => Err(GltfError::Document(e)),
    }?;
    Ok((doc, required))
}

struct Loader<'a> {
    doc: &'a gltf::Document,
    buffers: &'a buffers::Buffers,
    base: &'a Path,
    scene: Scene,
    /// (mesh, primitive) -> index in `scene.meshes`, or None when the primitive was skipped.
    prims: HashMap<(usize, usize), Option<u32>>,
    /// (glTF texture, sRGB) -> index in `scene.textures`, or None when its image failed.
    textures: HashMap<(usize, bool), Option<u32>>,
    /// (scene texture, glossiness factor bits) -> the roughness texture derived from a spec-gloss
    /// texture.
    gloss_textures: HashMap<(u32, u32), u32>,
    images: HashMap<usize, Option<Rc<image::Pixels>>>,
    default_material: Option<u32>,
    dropped: usize,
    /// Which animation to keep.
    animation: usize,
    /// Which scene's nodes to place.
    scene_choice: &'a SceneChoice,
    /// Joints and weights of skinned scene meshes, by mesh index.
    skin_attrs: HashMap<u32, SkinAttrs>,
    /// Morph targets of scene meshes, by mesh index.
    morph_attrs: HashMap<u32, Vec<MorphTarget>>,
    /// KHR_animation_pointer channels of every animation.
    pointers: Vec<pointer::PointerChannel>,
}

/// What the node walk placed, for the animation: the hierarchy as reached from the roots, and what
/// hangs from which node.
#[derive(Default)]
struct Placed {
    parent_of: Vec<Option<u32>>,
    /// (instance, node) of every instance.
    instances: Vec<(u32, u32)>,
    /// (camera, node) of every camera, by position in the file's camera list.
    camera_nodes: Vec<(usize, u32)>,
    /// (instance, scene mesh, glTF skin) of every skinned primitive placed.
    skinned: Vec<(u32, u32, usize)>,
    /// (scene mesh, node, default weights) of every primitive with morph targets placed.
    morphed: Vec<(u32, u32, Vec<f32>)>,
    /// (glTF camera, camera) in the order met; sorted by glTF camera before the animation is read.
    cameras: Vec<(usize, Camera)>,
    /// Every punctual light placed, in the order of `Scene::lights`.
    lights: Vec<PlacedLight>,
}

/// A punctual light as placed: where it is in the scene, its node, the file's light, and its shape
/// in the node's frame.
struct PlacedLight {
    light: u32,
    node: u32,
    source: usize,
    local: crate::scene::Light,
    color: Vec3,
    intensity: f32,
}

impl Loader<'_> {
    fn run(mut self, required: Vec<String>) -> Result<Scene, GltfError> {
        let doc = self.doc;
        self.scene.stats.extensions_required = required;
        self.scene.stats.scenes = scene_names(doc);
        self.scene.variants.names = variants::names(doc);
        for ext in doc.extensions_used() {
            if !SUPPORTED.contains(&ext) {
                self.scene.warnings.push(format!(
                    "{ext} is used but not supported; rendered without it"
                ));
            }
        }
        for m in doc.materials() {
            let mat = self.material(&m);
            self.scene.materials.push(mat);
        }
        let mut placed = self.walk()?;
        placed.cameras.sort_by_key(|(i, _)| *i);
        // Camera nodes by position in the sorted list.
        let cam_nodes: Vec<(u32, u32)> = placed
            .cameras
            .iter()
            .enumerate()
            .filter_map(|(k, (ci, _))| {
                placed
                    .camera_nodes
                    .iter()
                    .find(|(c, _)| c == ci)
                    .map(|&(_, n)| (k as u32, n))
            })
            .collect();
        self.scene.cameras = placed.cameras.iter().map(|(_, c)| c.clone()).collect();
        self.scene.animation = self.file_animation(&placed, cam_nodes)?;
        if self.dropped > 0 {
            self.scene
                .warnings
                .push(format!("dropped {} degenerate triangles", self.dropped));
        }
        self.count_stats();
        Ok(self.scene)
    }

    /// The roots of the hierarchy: the chosen scene's; by default the default scene's, else scene
    /// 0's, else every node that is nobody's child.
    fn roots(&self) -> Result<Vec<usize>, GltfError> {
        let doc = self.doc;
        let chosen = match self.scene_choice {
            SceneChoice::Default => doc.default_scene().or_else(|| doc.scenes().next()),
            SceneChoice::Index(i) => Some(doc.scenes().nth(*i).ok_or(GltfError::NoScene {
                asked: self.scene_choice.to_string(),
                names: scene_names(doc),
            })?),
            SceneChoice::Name(n) => {
                Some(doc.scenes().find(|s| s.name() == Some(n.as_str())).ok_or(
                    GltfError::NoScene {
                        asked: self.scene_choice.to_string(),
                        names: scene_names(doc),
                    },
                )?)
            }
        };
        Ok(match chosen {
            Some(s) => s.nodes().map(|n| n.index()).collect(),
            None => {
                let mut is_child = vec![false; doc.nodes().len()];
                for n in doc.nodes() {
                    for c in n.children() {
                        is_child[c.index()] = true;
                    }
                }
                (0..is_child.len()).filter(|&i| !is_child[i]).collect()
            }
        })
    }

    /// Walks the hierarchy depth first from the roots, placing each node's meshes, light and camera
    /// at its world transform; a node reached twice is placed once.
    fn walk(&mut self) -> Result<Placed, GltfError> {
        let nodes: Vec<gltf::Node> = self.doc.nodes().collect();
        let mut visited = vec![false; nodes.len()];
        let mut placed = Placed {
            parent_of: vec![None; nodes.len()],
            ..Placed::default()
        };
        let mut stack: Vec<(usize, Mat4)> = self
            .roots()?
            .iter()
            .rev()
            .map(|&r| (r, Mat4::IDENTITY))
            .collect();
        while let Some((ni, parent)) = stack.pop() {
            if visited[ni] {
                self.scene.warnings.push(format!(
                    "node {ni} is reached twice in the hierarchy (a cycle or a shared child); skipped the second time"
                ));
                continue;
            }
            visited[ni] = true;
            let node = &nodes[ni];
            let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
            for c in node.children().collect::<Vec<_>>().into_iter().rev() {
                if !visited[c.index()] {
                    placed.parent_of[c.index()] = Some(ni as u32);
                }
                stack.push((c.index(), world));
            }
            self.place_node(node, world, &mut placed)?;
        }
        Ok(placed)
    }

    /// Places what hangs from one node at its world transform.
    fn place_node(
        &mut self,
        node: &gltf::Node,
        world: Mat4,
        placed: &mut Placed,
    ) -> Result<(), GltfError> {
        let ni = node.index();
        let label = node_label(node);
        if !world.is_finite() {
            self.scene.warnings.push(format!(
                "{label}: transform is not finite; its mesh, light and camera are skipped"
            ));
            return Ok(());
        }
        if let Some(mesh) = node.mesh() {
            if world.determinant() == 0.0 {
                self.scene.warnings.push(format!(
                    "{label}: transform has zero scale; its mesh is skipped"
                ));
            } else {
                self.place_mesh(node, &mesh, world, placed)?;
            }
        }
        if let Some(light) = node.light() {
            if let Some(local) = self.light(&light, world, &label) {
                placed.lights.push(PlacedLight {
                    light: (self.scene.lights.len() - 1) as u32,
                    node: ni as u32,
                    source: light.index(),
                    local,
                    color: Vec3::from(light.color()),
                    intensity: light.intensity(),
                });
            }
        }
        if let Some(cam) = node.camera() {
            placed.camera_nodes.push((cam.index(), ni as u32));
            placed
                .cameras
                .push((cam.index(), light::camera(&cam, node, world)));
        }
        Ok(())
    }

    /// One instance of each primitive of a node's mesh.
    fn place_mesh(
        &mut self,
        node: &gltf::Node,
        mesh: &gltf::Mesh,
        world: Mat4,
        placed: &mut Placed,
    ) -> Result<(), GltfError> {
        let ni = node.index() as u32;
        if let Some(locals) = self
            .gpu_instances(node)
            .map_err(|e| e.at(node_label(node)))?
        {
            return self.place_gpu_instances(node, mesh, world, &locals);
        }
        for prim in mesh.primitives() {
            let Some(m) = self.primitive(mesh, &prim)? else {
                continue;
            };
            if self.morph_attrs.contains_key(&m) {
                let weights = node
                    .weights()
                    .or(mesh.weights())
                    .map(<[f32]>::to_vec)
                    .unwrap_or_default();
                placed.morphed.push((m, ni, weights));
            }
            let instance = self.scene.instances.len() as u32;
            if let Some(skin) = node.skin() {
                placed.skinned.push((instance, m, skin.index()));
            }
            placed.instances.push((instance, ni));
            self.scene.instances.push(Instance::new(m, world));
        }
        Ok(())
    }

    /// One instance of each primitive per EXT_mesh_gpu_instancing transform (after the node's). They
    /// stay where the rest pose puts them: the animation moves whole nodes, not their instances.
    fn place_gpu_instances(
        &mut self,
        node: &gltf::Node,
        mesh: &gltf::Mesh,
        world: Mat4,
        locals: &[Mat4],
    ) -> Result<(), GltfError> {
        let placed = locals
            .len()
            .saturating_mul(mesh.primitives().len())
            .saturating_add(self.scene.instances.len());
        if placed > super::limits::MAX_INSTANCES {
            return Err(GltfError::TooManyInstances {
                node: node_label(node),
                count: placed,
            });
        }
        let worlds: Vec<Mat4> = locals.iter().map(|l| world * *l).collect();
        let bad = worlds
            .iter()
            .filter(|m| !m.is_finite() || m.determinant() == 0.0)
            .count();
        if bad > 0 {
            self.scene.warnings.push(format!(
                "{}: {bad} of {} EXT_mesh_gpu_instancing transforms are not finite or have zero scale; skipped",
                node_label(node),
                worlds.len()
            ));
        }
        for prim in mesh.primitives() {
            let Some(m) = self.primitive(mesh, &prim)? else {
                continue;
            };
            for w in &worlds {
                if w.is_finite() && w.determinant() != 0.0 {
                    self.scene.instances.push(Instance::new(m, *w));
                }
            }
        }
        Ok(())
    }

    /// What the file held, for `glint info`.
    fn count_stats(&mut self) {
        let doc = self.doc;
        let stats = &mut self.scene.stats;
        stats.nodes = doc.nodes().len();
        stats.meshes = doc.meshes().len();
        stats.primitives = doc.meshes().map(|m| m.primitives().len()).sum();
        stats.materials = doc.materials().len();
        stats.textures = doc.textures().len();
        stats.lights = doc.lights().map(|l| l.len()).unwrap_or(0);
        stats.cameras = doc.cameras().len();
        stats.animations = doc.animations().len();
        stats.extensions_used = doc.extensions_used().map(str::to_owned).collect();
        self.scene.stats.triangles = self.scene.triangle_count();
    }
}

/// Whether glint implements extension `name` (for `glint info`).
pub fn supports(name: &str) -> bool {
    SUPPORTED.contains(&name)
}

/// How messages name a node.
fn node_label(node: &gltf::Node) -> String {
    match node.name() {
        Some(n) => format!("node {} ('{n}')", node.index()),
        None => format!("node {}", node.index()),
    }
}
