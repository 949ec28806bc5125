//! OBJ + MTL loader, through `tobj` (triangulated, single index). Each tobj model (an `o`/`g` group,
//! split again at every `usemtl`) becomes one `Mesh` with one identity `Instance`. MTL materials map
//! onto the metallic-roughness `Material`: Kd -> base colour, Ns -> roughness, Ks -> specular strength,
//! Ke -> emission, d -> alpha, Ni -> ior, map_Kd / map_Bump -> textures. `d` (or `Tr`) stays alpha as
//! coverage (the surface is partly absent), as glTF's alpha is; glass is named by the illumination
//! model instead: `illum 6`/`7` (refraction on) give a thick refracting dielectric, `illum 4`/`9`
//! (glass on) a thin-walled one, both fully transmissive, tinted by `Tf` (default white) in place of
//! Kd, and then `d` does not also cut the surface away.
//!
//! The PBR extension of MTL (Exocortex's, which Blender writes) maps onto the same model: Pr
//! roughness, Pm metallic (each replaced by its map_Pr / map_Pm texture when given, as Blender's
//! importer does), Ps sheen, Pc / Pcr clearcoat and its roughness, aniso / anisor anisotropy and
//! its rotation (in turns), norm a tangent-space normal map. Pr, when given, beats Ns. Blender's
//! own conventions are followed where it writes its Principled BSDF (checked against Blender 5.0's
//! importer): Pc is four times the coat weight, and in a PBR material Ks is the "Specular IOR
//! Level", whose 0.5 is the plain dielectric (glTF specular factor 1).

use std::cell::RefCell;
use std::collections::HashMap;
use std::io::BufReader;
use std::path::{Path, PathBuf};

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::decode::Rgba8;
use super::{AlphaMode, Instance, LoadError, Material, Mesh, Scene, TexRef, Texture};

/// Reads a file an OBJ names (an MTL library, a texture), given its full path.
pub type Files<'a> = dyn Fn(&Path) -> std::io::Result<Vec<u8>> + 'a;

/// Loads an .obj file and the .mtl files it names. Never panics on malformed input.
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    let bytes =
        std::fs::read(path).map_err(|e| LoadError::new(path, format!("cannot read file: {e}")))?;
    load_bytes(path, &bytes, &|p: &Path| std::fs::read(p))
}

/// Loads an OBJ whose bytes are in hand; `path` names it in errors and the MTL libraries and
/// textures it names are read through `files` from beside it.
pub fn load_bytes(path: &Path, bytes: &[u8], files: &Files) -> Result<Scene, LoadError> {
    match super::quiet_panic::catch(|| load_inner(path, bytes, files)) {
        Some(r) => r,
        None => Err(LoadError::new(
            path,
            "malformed OBJ (the OBJ reader failed on an inconsistent file)",
        )),
    }
}

/// Roughness from a Phong exponent (the usual Blinn-Phong <-> Beckmann correspondence).
pub fn roughness_from_ns(ns: f32) -> f32 {
    (2.0 / (ns.max(0.0) + 2.0)).sqrt().clamp(0.0, 1.0)
}

/// The material of an OBJ without usable MTL: a grey dielectric.
pub fn default_obj_material() -> Material {
    Material {
        name: "default".into(),
        base_color: Vec4::new(0.8, 0.8, 0.8, 1.0),
        metallic: 0.0,
        roughness: 0.5,
        ..Material::default()
    }
}

fn load_inner(path: &Path, bytes: &[u8], files: &Files) -> Result<Scene, LoadError> {
    let (models, materials, search, warnings) = read_obj(path, bytes, files)?;
    let mut scene = Scene::default();
    scene.warnings.extend(warnings);
    let mut textures: HashMap<(PathBuf, bool), Option<u32>> = HashMap::new();
    for m in &materials {
        let mat = convert_material(m, &search, files, &mut scene, &mut textures);
        scene.materials.push(mat);
    }
    let mut default_material: Option<u32> = None;
    let mut dropped = 0;
    for model in &models {
        let material = match model.mesh.material_id {
            Some(id) if id < scene.materials.len() => id as u32,
            _ => *default_material.get_or_insert_with(|| {
                scene.materials.push(default_obj_material());
                (scene.materials.len() - 1) as u32
            }),
        };
        let mut mesh = convert_mesh(model, material).map_err(|e| LoadError::new(path, e))?;
        dropped += mesh.clean();
        if mesh.indices.is_empty() {
            continue;
        }
        scene.meshes.push(mesh);
        scene.instances.push(Instance::new(
            (scene.meshes.len() - 1) as u32,
            Mat4::IDENTITY,
        ));
    }
    if dropped > 0 {
        scene
            .warnings
            .push(format!("dropped {dropped} degenerate triangles"));
    }
    scene.stats.nodes = 0;
    scene.stats.meshes = models.len();
    scene.stats.primitives = scene.meshes.len();
    scene.stats.materials = scene.materials.len();
    scene.stats.textures = scene.textures.len();
    scene.stats.triangles = scene.triangle_count();
    Ok(scene)
}

/// What tobj reads from an OBJ: its models, its materials, the folders to search for textures
/// (each MTL's own folder, then the OBJ's) and one warning per MTL that could not be read.
type ObjContents = (
    Vec<tobj::Model>,
    Vec<tobj::Material>,
    Vec<PathBuf>,
    Vec<String>,
);

fn read_obj(path: &Path, bytes: &[u8], files: &Files) -> Result<ObjContents, LoadError> {
    let dir = path
        .parent()
        .unwrap_or_else(|| Path::new("."))
        .to_path_buf();
    let mtl_dirs: RefCell<Vec<PathBuf>> = RefCell::new(Vec::new());
    let mtl_errors: RefCell<Vec<String>> = RefCell::new(Vec::new());
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = BufReader::new(bytes);
    let (models, materials) = tobj::load_obj_buf(&mut reader, &opts, |mtl: &Path| {
        let full = dir.join(mtl);
        let r = match files(&full) {
            Ok(text) => tobj::load_mtl_buf(&mut BufReader::new(&text[..])),
            Err(_) => Err(tobj::LoadError::OpenFileFailed),
        };
        match &r {
            Ok(_) => mtl_dirs
                .borrow_mut()
                .push(full.parent().unwrap_or(&dir).to_path_buf()),
            Err(e) => mtl_errors.borrow_mut().push(format!(
                "material library '{}': {}; using a default material",
                mtl.display(),
                match e {
                    tobj::LoadError::OpenFileFailed => "cannot open the file".to_string(),
                    e => e.to_string(),
                }
            )),
        }
        r
    })
    .map_err(|e| LoadError::new(path, format!("malformed OBJ: {e}")))?;
    let mut search = mtl_dirs.into_inner();
    search.push(dir);
    Ok((
        models,
        materials.unwrap_or_default(),
        search,
        mtl_errors.into_inner(),
    ))
}

/// One tobj model as a `Mesh`; attributes whose count does not match the positions are dropped,
/// and an index past the last vertex is an error.
fn convert_mesh(model: &tobj::Model, material: u32) -> Result<Mesh, String> {
    let tm = &model.mesh;
    let vec3s = |v: &[f32]| -> Vec<Vec3> {
        v.chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]))
            .collect()
    };
    let positions = vec3s(&tm.positions);
    let n = positions.len();
    if let Some(&bad) = tm.indices.iter().find(|&&i| i as usize >= n) {
        return Err(format!(
            "object '{}': vertex index {bad} out of range ({n} vertices)",
            model.name
        ));
    }
    let normals = if tm.normals.len() == 3 * n {
        vec3s(&tm.normals)
    } else {
        Vec::new()
    };
    // OBJ puts v = 0 at the bottom of the image; glint's textures have v = 0 at the top row.
    let uvs: Vec<Vec2> = if tm.texcoords.len() == 2 * n {
        tm.texcoords
            .chunks_exact(2)
            .map(|t| Vec2::new(t[0], 1.0 - t[1]))
            .collect()
    } else {
        Vec::new()
    };
    let indices = tm
        .indices
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    Ok(Mesh {
        name: model.name.clone(),
        positions,
        normals,
        uvs,
        tangents: Vec::new(),
        indices,
        material,
        ..Default::default()
    })
}

fn parse3(s: &str) -> Option<Vec3> {
    let v: Vec<f32> = s
        .split_whitespace()
        .take(3)
        .map_while(|w| w.parse().ok())
        .collect();
    match v.len() {
        3 => Some(Vec3::new(v[0], v[1], v[2])),
        1 => Some(Vec3::splat(v[0])),
        _ => None,
    }
}

fn convert_material(
    m: &tobj::Material,
    search: &[PathBuf],
    files: &Files,
    scene: &mut Scene,
    textures: &mut HashMap<(PathBuf, bool), Option<u32>>,
) -> Material {
    let kd = m.diffuse.map(Vec3::from).unwrap_or(Vec3::splat(0.8));
    let alpha = match (m.dissolve, m.unknown_param.get("Tr")) {
        (Some(d), _) => d,
        (None, Some(tr)) => 1.0 - tr.trim().parse::<f32>().unwrap_or(0.0),
        _ => 1.0,
    }
    .clamp(0.0, 1.0);
    let emissive = m
        .emissive
        .map(Vec3::from)
        .or_else(|| m.unknown_param.get("Ke").and_then(|s| parse3(s)))
        .unwrap_or(Vec3::ZERO)
        .max(Vec3::ZERO);
    let mut mat = Material {
        name: m.name.clone(),
        base_color: kd.extend(alpha),
        metallic: 0.0,
        roughness: m.shininess.map(roughness_from_ns).unwrap_or(0.5),
        emissive: if emissive.is_finite() {
            emissive
        } else {
            Vec3::ZERO
        },
        alpha_mode: if alpha < 1.0 {
            AlphaMode::Blend
        } else {
            AlphaMode::Opaque
        },
        // A specular colour of zero means a purely diffuse surface.
        specular: m
            .specular
            .map(|ks| Vec3::from(ks).max_element().clamp(0.0, 1.0))
            .unwrap_or(1.0),
        ior: m
            .optical_density
            .filter(|n| n.is_finite() && *n >= 1.0)
            .unwrap_or(1.5),
        ..Material::default()
    };
    if let Some(illum @ (4 | 6 | 7 | 9)) = m.illumination_model {
        let tf = m
            .unknown_param
            .get("Tf")
            .and_then(|s| parse3(s))
            .filter(|c| c.is_finite())
            .unwrap_or(Vec3::ONE)
            .clamp(Vec3::ZERO, Vec3::ONE);
        mat.base_color = tf.extend(1.0);
        mat.alpha_mode = AlphaMode::Opaque;
        mat.transmission = 1.0;
        mat.specular = 1.0;
        mat.thickness = if matches!(illum, 6 | 7) { 1.0 } else { 0.0 };
    }
    apply_pbr(m, &mut mat);
    attach_textures(m, &mut mat, (search, files), scene, textures);
    mat
}

/// A scalar MTL statement of the PBR extension, when it is there and finite.
fn pbr_scalar(m: &tobj::Material, key: &str) -> Option<f32> {
    m.unknown_param
        .get(key)
        .and_then(|s| s.split_whitespace().next()?.parse::<f32>().ok())
        .filter(|v| v.is_finite())
}

/// The PBR extension's scalar statements on `mat`.
fn apply_pbr(m: &tobj::Material, mat: &mut Material) {
    use super::layers::{Anisotropy, Clearcoat, Sheen};
    let unit = |key| pbr_scalar(m, key).map(|v| v.clamp(0.0, 1.0));
    let pbr = ["Pr", "Pm", "Ps", "Pc", "map_Pr", "map_Pm"]
        .iter()
        .any(|k| m.unknown_param.contains_key(*k));
    if !pbr {
        return;
    }
    if let Some(level) = m.specular.map(|ks| Vec3::from(ks).max_element()) {
        mat.specular = (2.0 * level).clamp(0.0, 1.0);
    }
    if let Some(r) = unit("Pr") {
        mat.roughness = r;
    }
    if let Some(metal) = unit("Pm") {
        mat.metallic = metal;
    }
    if let Some(sheen) = m
        .unknown_param
        .get("Ps")
        .and_then(|s| parse3(s))
        .filter(|c| c.is_finite() && c.max_element() > 0.0)
    {
        mat.layers.sheen = Some(Sheen {
            color: sheen.clamp(Vec3::ZERO, Vec3::ONE),
            color_tex: None,
            // Blender's default sheen roughness; the extension has no statement for it.
            roughness: 0.5,
            roughness_tex: None,
        });
    }
    if let Some(coat) = pbr_scalar(m, "Pc")
        .map(|c| (c / 4.0).clamp(0.0, 1.0))
        .filter(|&c| c > 0.0)
    {
        mat.layers.clearcoat = Some(Clearcoat {
            factor: coat,
            factor_tex: None,
            roughness: unit("Pcr").unwrap_or(0.0),
            roughness_tex: None,
            normal_tex: None,
            normal_scale: 1.0,
        });
    }
    if let Some(strength) = unit("aniso").filter(|&a| a > 0.0) {
        mat.layers.anisotropy = Some(Anisotropy {
            strength,
            rotation: pbr_scalar(m, "anisor").unwrap_or(0.0) * std::f32::consts::TAU,
            texture: None,
        });
    }
}

/// The MTL's texture maps (map_Kd, a normal/bump map, map_Ke) on `mat`.
fn attach_textures(
    m: &tobj::Material,
    mat: &mut Material,
    (search, files): (&[PathBuf], &Files),
    scene: &mut Scene,
    textures: &mut HashMap<(PathBuf, bool), Option<u32>>,
) {
    let label = format!("material '{}'", m.name);
    if let Some(t) = &m.diffuse_texture {
        mat.base_color_tex =
            texture(t, true, (search, files), scene, textures, &label).map(TexRef::new);
    }
    let normal = m.normal_texture.clone().or_else(|| {
        ["norm", "map_bump", "map_Bump", "bump"]
            .iter()
            .find_map(|k| m.unknown_param.get(*k).cloned())
    });
    if let Some(t) = &normal {
        mat.normal_tex =
            texture(t, false, (search, files), scene, textures, &label).map(TexRef::new);
    }
    if let Some(t) = metal_rough_texture(m, (search, files), scene, &label) {
        mat.metallic_roughness_tex = Some(TexRef::new(t));
        if m.unknown_param.contains_key("map_Pr") {
            mat.roughness = 1.0;
        }
        if m.unknown_param.contains_key("map_Pm") {
            mat.metallic = 1.0;
        }
    }
    if let Some(t) = m.unknown_param.get("map_Ke") {
        mat.emissive_tex =
            texture(t, true, (search, files), scene, textures, &label).map(TexRef::new);
        if mat.emissive == Vec3::ZERO {
            mat.emissive = Vec3::ONE;
        }
    }
}

/// map_Pr and map_Pm (grey images) as one glTF-layout texture: roughness in G, metallic in B, the
/// channel of a missing map 1 (so its factor stands alone). At the larger map's size when they
/// differ, the other sampled nearest.
fn metal_rough_texture(
    m: &tobj::Material,
    (search, files): (&[PathBuf], &Files),
    scene: &mut Scene,
    label: &str,
) -> Option<u32> {
    let mut load = |key: &str| {
        let (file, bytes) = find(m.unknown_param.get(key)?, (search, files), scene, label)?;
        decode(&file, &bytes, scene, label)
    };
    let (rough, metal) = (load("map_Pr"), load("map_Pm"));
    let (width, height) = [&rough, &metal]
        .iter()
        .filter_map(|i| i.as_ref().map(|i| (i.width, i.height)))
        .max_by_key(|&(w, h)| w * h)?;
    let grey = |img: &Option<Rgba8>, x: usize, y: usize| match img {
        Some(i) => i.pixels[(y * i.height / height) * i.width + x * i.width / width][0],
        None => 255,
    };
    let pixels = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| [0, grey(&rough, x, y), grey(&metal, x, y), 255])
        .collect();
    scene.textures.push(Texture::repeating(
        format!("{} metallic-roughness", m.name),
        (width, height),
        pixels,
        false,
    ));
    Some((scene.textures.len() - 1) as u32)
}

/// Finds and reads a texture named in an MTL statement (which may carry options such as `-bm 1`
/// before the file name) next to the MTL or the OBJ.
fn resolve(spec: &str, search: &[PathBuf], files: &Files) -> Option<(PathBuf, Vec<u8>)> {
    let spec = spec.trim().replace('\\', "/");
    let last = spec.split_whitespace().last().unwrap_or("").to_string();
    for cand in [spec.as_str(), last.as_str()] {
        if cand.is_empty() {
            continue;
        }
        for d in search {
            let p = d.join(cand);
            if let Ok(bytes) = files(&p) {
                return Some((p, bytes));
            }
        }
    }
    None
}

/// The file an MTL statement names and its bytes; a warning naming it when it is not found.
fn find(
    spec: &str,
    (search, files): (&[PathBuf], &Files),
    scene: &mut Scene,
    label: &str,
) -> Option<(PathBuf, Vec<u8>)> {
    let found = resolve(spec, search, files);
    if found.is_none() {
        scene.warnings.push(format!(
            "{label}: texture '{}' not found; ignored",
            spec.trim()
        ));
    }
    found
}

/// A texture file decoded; a warning naming it when it cannot be.
fn decode(file: &Path, bytes: &[u8], scene: &mut Scene, label: &str) -> Option<Rgba8> {
    super::decode::decode_rgba8(bytes)
        .map_err(|e| {
            scene.warnings.push(format!(
                "{label}: cannot load texture '{}': {e}; ignored",
                file.display()
            ))
        })
        .ok()
}

fn texture(
    spec: &str,
    srgb: bool,
    (search, files): (&[PathBuf], &Files),
    scene: &mut Scene,
    textures: &mut HashMap<(PathBuf, bool), Option<u32>>,
    label: &str,
) -> Option<u32> {
    let (file, bytes) = find(spec, (search, files), scene, label)?;
    if let Some(t) = textures.get(&(file.clone(), srgb)) {
        return *t;
    }
    let out = decode(&file, &bytes, scene, label).map(|img| {
        let name = file
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default();
        scene.textures.push(Texture::repeating(
            name,
            (img.width, img.height),
            img.pixels,
            srgb,
        ));
        (scene.textures.len() - 1) as u32
    });
    textures.insert((file, srgb), out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Scene, Wrap};

    #[test]
    fn no_mtl_gives_grey_dielectric_and_computed_normals() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("q.obj");
        std::fs::write(&p, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
        let s = Scene::load(&p).unwrap();
        assert_eq!(s.meshes.len(), 1);
        assert_eq!(s.instances.len(), 1);
        assert!(s.instances[0].is_identity());
        assert_eq!(s.stats.triangles, 2);
        assert_eq!(s.stats.nodes, 0);
        let m = &s.materials[0];
        assert_eq!(m.base_color, Vec4::new(0.8, 0.8, 0.8, 1.0));
        assert_eq!((m.metallic, m.roughness), (0.0, 0.5));
        assert!(s.meshes[0]
            .normals
            .iter()
            .all(|n| (*n - Vec3::Z).length() < 1e-6));
        assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    }

    #[test]
    fn mtl_maps_onto_metallic_roughness_and_splits_by_material() {
        let dir = tempfile::tempdir().unwrap();
        // 2x2 texture: top row red, bottom row blue (v = 0 is the bottom in OBJ).
        let img = image::RgbaImage::from_raw(1, 2, vec![255, 0, 0, 255, 0, 0, 255, 255]).unwrap();
        img.save(dir.path().join("rb.png")).unwrap();
        std::fs::write(
            dir.path().join("m.mtl"),
            "newmtl lamp\nKd 0.5 0.25 1\nKs 0 0 0\nNs 98\nKe 17 12 4\nNi 1.33\n\
             newmtl glass\nKd 1 1 1\nKs 1 1 1\nd 0.5\nmap_Kd -bm 1 rb.png\nmap_Bump nothere.png\n",
        )
        .unwrap();
        let p = dir.path().join("m.obj");
        std::fs::write(
            &p,
            "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
             usemtl lamp\nf 1/1 2/2 3/3\nusemtl glass\nf 1/1 2/2 3/3\n",
        )
        .unwrap();
        let s = Scene::load(&p).unwrap();
        assert_eq!(s.meshes.len(), 2);
        assert_eq!(s.instances.len(), 2);
        let lamp = s.material_of_mesh(0);
        assert_eq!(lamp.name, "lamp");
        assert_eq!(lamp.base_color, Vec4::new(0.5, 0.25, 1.0, 1.0));
        assert_eq!(lamp.emissive, Vec3::new(17.0, 12.0, 4.0));
        assert!((lamp.roughness - 0.1414).abs() < 1e-3);
        assert_eq!(lamp.metallic, 0.0);
        assert_eq!(lamp.specular, 0.0);
        assert!((lamp.ior - 1.33).abs() < 1e-6);
        let glass = s.material_of_mesh(1);
        assert_eq!(glass.alpha_mode, AlphaMode::Blend);
        assert_eq!(glass.base_color.w, 0.5);
        let t = glass.base_color_tex.expect("map_Kd with options resolves");
        let tex = &s.textures[t.texture as usize];
        assert!(tex.srgb);
        assert_eq!(tex.wrap_s, Wrap::Repeat);
        assert!(glass.normal_tex.is_none());
        assert!(
            s.warnings.iter().any(|w| w.contains("nothere.png")),
            "{:?}",
            s.warnings
        );
        // OBJ vt (0, 0) is the bottom-left: it must sample the bottom (blue) row.
        let uv = s.meshes[1].uvs[0];
        assert_eq!(uv, Vec2::new(0.0, 1.0));
        let c = tex.sample(Vec2::new(0.5, 0.75));
        assert!(c.z > 0.9 && c.x < 0.1, "{c}");
        assert_eq!(s.stats.meshes, 2);
        assert_eq!(s.stats.materials, 2);
    }

    #[test]
    fn illum_names_glass_and_d_stays_coverage() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("g.mtl"),
            "newmtl thick\nKd 0 0 0\nNi 1.45\nd 0.2\nillum 7\nTf 0.9 1 0.8\n\
             newmtl thin\nillum 4\nNs 1000\n\
             newmtl veil\nKd 1 1 1\nd 0.3\nillum 2\n",
        )
        .unwrap();
        let p = dir.path().join("g.obj");
        std::fs::write(
            &p,
            "mtllib g.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n\
             usemtl thick\nf 1 2 3\nusemtl thin\nf 1 2 3\nusemtl veil\nf 1 2 3\n",
        )
        .unwrap();
        let s = Scene::load(&p).unwrap();
        let thick = s.material_of_mesh(0);
        assert_eq!(thick.transmission, 1.0);
        assert!(!thick.is_thin_walled() && thick.is_transmissive());
        assert!((thick.ior - 1.45).abs() < 1e-6);
        assert_eq!(thick.base_color, Vec4::new(0.9, 1.0, 0.8, 1.0));
        assert_eq!(thick.alpha_mode, AlphaMode::Opaque);
        let thin = s.material_of_mesh(1);
        assert!(thin.is_thin_walled() && thin.is_transmissive());
        assert_eq!(thin.base_color, Vec4::ONE);
        let veil = s.material_of_mesh(2);
        assert_eq!(veil.transmission, 0.0);
        assert_eq!(veil.alpha_mode, AlphaMode::Blend);
        assert_eq!(veil.base_color.w, 0.3);
    }

    #[test]
    fn mtl_pbr_extension_maps_onto_the_gltf_model() {
        let dir = tempfile::tempdir().unwrap();
        // map_Pr is 2x1 (grey 51 | 204), map_Pm 1x1 (grey 255): the texture takes the larger size.
        image::GrayImage::from_raw(2, 1, vec![51, 204])
            .unwrap()
            .save(dir.path().join("rough.png"))
            .unwrap();
        image::GrayImage::from_raw(1, 1, vec![255])
            .unwrap()
            .save(dir.path().join("metal.png"))
            .unwrap();
        std::fs::write(
            dir.path().join("p.mtl"),
            "newmtl scalars\nKd 0.8 0.1 0.1\nKs 0.25 0.25 0.25\nNs 900\nPr 0.3\nPm 1\nPs 0.2\nPc 2\nPcr 0.1\n\
             aniso 0.4\nanisor 0.25\n\
             newmtl maps\nKd 1 1 1\nPr 0.5\nPm 0.5\nmap_Pr rough.png\nmap_Pm metal.png\n\
             newmtl rough_only\nPm 0.25\nmap_Pr rough.png\n\
             newmtl plain\nNs 98\n",
        )
        .unwrap();
        let p = dir.path().join("p.obj");
        std::fs::write(
            &p,
            "mtllib p.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl scalars\nf 1 2 3\n\
             usemtl maps\nf 1 2 3\nusemtl rough_only\nf 1 2 3\nusemtl plain\nf 1 2 3\n",
        )
        .unwrap();
        let s = Scene::load(&p).unwrap();
        assert!(s.warnings.is_empty(), "{:?}", s.warnings);
        let m = s.material_of_mesh(0);
        assert_eq!((m.roughness, m.metallic), (0.3, 1.0), "Pr beats Ns");
        let sheen = m.layers.sheen.expect("Ps gives a sheen");
        assert_eq!(sheen.color, Vec3::splat(0.2));
        let coat = m.layers.clearcoat.expect("Pc gives a coat");
        assert_eq!(
            (coat.factor, coat.roughness),
            (0.5, 0.1),
            "Pc is 4x Blender's coat weight"
        );
        assert_eq!(
            m.specular, 0.5,
            "Ks 0.25 is Blender's IOR level 0.25: half the plain F0"
        );
        assert_eq!(
            s.material_of_mesh(1).specular,
            1.0,
            "no Ks: the plain dielectric"
        );
        let aniso = m.layers.anisotropy.expect("aniso gives anisotropy");
        assert_eq!(aniso.strength, 0.4);
        assert!((aniso.rotation - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
        let maps = s.material_of_mesh(1);
        assert_eq!(
            (maps.roughness, maps.metallic),
            (1.0, 1.0),
            "maps replace the scalars"
        );
        let t = &s.textures[maps.metallic_roughness_tex.unwrap().texture as usize];
        assert!(!t.srgb);
        assert_eq!((t.width, t.height), (2, 1));
        assert_eq!(t.pixels, vec![[0, 51, 255, 255], [0, 204, 255, 255]]);
        let rough_only = s.material_of_mesh(2);
        assert_eq!((rough_only.roughness, rough_only.metallic), (1.0, 0.25));
        let t = &s.textures[rough_only.metallic_roughness_tex.unwrap().texture as usize];
        assert_eq!(t.pixels[1], [0, 204, 255, 255], "no map_Pm: B = 1 keeps Pm");
        let plain = s.material_of_mesh(3);
        assert!(plain.layers.sheen.is_none() && plain.layers.clearcoat.is_none());
        assert!(plain.metallic_roughness_tex.is_none() && plain.metallic == 0.0);
    }
}
