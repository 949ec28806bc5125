//! glTF 2.0 loader (.gltf with external or data-URI buffers, and .glb).
//!
//! The `gltf` crate parses and validates the JSON; buffers are read through it too, but every accessor
//! is read here, with its extent checked against its buffer view and buffer first, so that a malformed
//! file becomes a `LoadError` naming the element instead of a panic. Each (mesh, primitive) pair becomes
//! one `Mesh`; every node that uses it adds an `Instance`.
//!
//! The mesh clean-up shared with the OBJ loader (dropping degenerate triangles, computing normals) lives
//! here too: `clean_mesh`.

use std::collections::HashMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::rc::Rc;

use glam::{Mat4, Quat, Vec2, Vec3, Vec4};
use gltf::accessor::{DataType, Dimensions};
use gltf::json::Value;
use gltf::mesh::Mode;

use super::animation::{Channel, Interpolation, Morph, Property, Skin, WeightChannel};
use super::{
    AlphaMode, Animation, Camera, Light, LoadError, Material, Mesh, Projection, Scene, TexRef,
    Texture, Wrap,
};

/// Extensions glint understands well enough that a file may require them.
const SUPPORTED_REQUIRED: &[&str] = &[
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_transmission",
    "KHR_materials_ior",
    "KHR_materials_volume",
    "KHR_texture_transform",
];

/// Loads a .gltf or .glb file. Never panics on malformed input: every problem is a `LoadError`.
/// Loads a glTF file keeping its animation number `animation` (when it has animations).
pub fn load(path: &Path, animation: usize) -> Result<Scene, LoadError> {
    match catch_unwind(AssertUnwindSafe(|| load_inner(path, animation))) {
        Ok(r) => r,
        Err(_) => Err(LoadError::new(
            path,
            "malformed glTF (the glTF reader failed on an inconsistent file)",
        )),
    }
}

fn load_inner(path: &Path, animation: usize) -> Result<Scene, LoadError> {
    let err = |m: String| LoadError::new(path, m);
    let bytes = std::fs::read(path).map_err(|e| err(format!("cannot read file: {e}")))?;
    let base = path.parent().unwrap_or_else(|| Path::new("."));

    let (json_bytes, blob) = if bytes.starts_with(b"glTF") {
        split_glb(&bytes).map_err(err)?
    } else {
        let json = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes);
        (json, None)
    };
    let mut root: gltf::json::Root = gltf::json::deserialize::from_slice(json_bytes)
        .map_err(|e| err(format!("invalid JSON: {e}")))?;

    if let Some(ext) = root
        .extensions_required
        .iter()
        .find(|e| !SUPPORTED_REQUIRED.contains(&e.as_str()))
    {
        return Err(err(format!("requires unsupported extension {ext}")));
    }
    // The crate's validation refuses required extensions it has no code for (KHR_materials_volume);
    // glint has checked them above.
    root.extensions_required.clear();
    let fallback = root.clone();
    let doc = match gltf::Document::from_json(root) {
        Ok(doc) => Ok(doc),
        // POSITION's min/max are required by the spec but unused here: tolerate files without them.
        Err(gltf::Error::Validation(errs))
            if errs.iter().all(|(p, e)| {
                matches!(e, gltf::json::validation::Error::Missing)
                    && (p.as_str().ends_with(".min") || p.as_str().ends_with(".max"))
            }) =>
        {
            Ok(gltf::Document::from_json_without_validation(fallback))
        }
        Err(e) => Err(e),
    }
    .map_err(|e| match e {
        gltf::Error::Validation(errs) => {
            let list: Vec<String> = errs
                .iter()
                .take(5)
                .map(|(p, e)| format!("{p}: {e}"))
                .collect();
            let more = if errs.len() > 5 {
                format!(" (and {} more)", errs.len() - 5)
            } else {
                String::new()
            };
            err(format!("invalid glTF: {}{more}", list.join("; ")))
        }
        e => err(format!("invalid glTF: {e}")),
    })?;

    let buffers = read_buffers(&doc, base, blob).map_err(err)?;
    Loader {
        doc: &doc,
        buffers: &buffers,
        base,
        scene: Scene::default(),
        prims: HashMap::new(),
        textures: HashMap::new(),
        images: HashMap::new(),
        default_material: None,
        dropped: 0,
        animation,
        pending_skin: None,
        skin_attrs: HashMap::new(),
        pending_morph: None,
        morph_attrs: HashMap::new(),
    }
    .run()
    .map_err(err)
}

/// One morph target's position and normal displacements.
type MorphTarget = (Vec<Vec3>, Vec<Vec3>);

fn interpolation_of(i: gltf::animation::Interpolation) -> Interpolation {
    match i {
        gltf::animation::Interpolation::Linear => Interpolation::Linear,
        gltf::animation::Interpolation::Step => Interpolation::Step,
        gltf::animation::Interpolation::CubicSpline => Interpolation::CubicSpline,
    }
}

/// Splits a binary glTF into its JSON chunk and BIN chunk, checking every length.
fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<Vec<u8>>), String> {
    let u32_at =
        |o: usize| u32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]);
    if bytes.len() < 12 {
        return Err(format!(
            "truncated .glb: {} bytes, shorter than the 12-byte header",
            bytes.len()
        ));
    }
    let version = u32_at(4);
    if version != 2 {
        return Err(format!(
            "unsupported .glb version {version} (only glTF 2.0 is supported)"
        ));
    }
    let length = u32_at(8) as usize;
    if length > bytes.len() {
        return Err(format!(
            "truncated .glb: header says {length} bytes but the file has {}",
            bytes.len()
        ));
    }
    if length < 20 {
        return Err(format!(
            "corrupt .glb: total length {length} leaves no room for a JSON chunk"
        ));
    }
    let data = &bytes[..length];
    let mut at = 12;
    let mut json = None;
    let mut bin = None;
    let mut chunk = 0;
    while at < data.len() {
        if data.len() - at < 8 {
            return Err(format!(
                "truncated .glb: incomplete header of chunk {chunk}"
            ));
        }
        let len = u32_at(at) as usize;
        let ty = &data[at + 4..at + 8];
        let start = at + 8;
        if len > data.len() - start {
            return Err(format!(
                "truncated .glb: chunk {chunk} says {len} bytes but only {} remain",
                data.len() - start
            ));
        }
        let body = &data[start..start + len];
        match (chunk, ty) {
            (0, b"JSON") => json = Some(body),
            (0, _) => return Err("corrupt .glb: the first chunk is not JSON".into()),
            (1, b"BIN\0") => bin = Some(body.to_vec()),
            _ => {} // unknown chunks are to be ignored
        }
        at = start + len;
        chunk += 1;
    }
    let json = json.ok_or("truncated .glb: no JSON chunk")?;
    Ok((json, bin))
}

/// Whether the importer's percent-decoding of a relative URI would succeed (it panics otherwise).
fn uri_decodes(uri: &str) -> bool {
    if uri.contains(':') {
        return true;
    }
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%' && i + 2 < b.len() {
            if let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8(out).is_ok()
}

fn read_buffers(
    doc: &gltf::Document,
    base: &Path,
    blob: Option<Vec<u8>>,
) -> Result<Vec<Vec<u8>>, String> {
    let mut blob = blob;
    let mut out = Vec::new();
    for buffer in doc.buffers() {
        let i = buffer.index();
        let what = match buffer.source() {
            gltf::buffer::Source::Bin => format!("buffer {i} (the .glb BIN chunk)"),
            gltf::buffer::Source::Uri(uri) => {
                if uri.starts_with("data:") {
                    format!("buffer {i} (data URI)")
                } else {
                    format!("buffer {i} ('{uri}')")
                }
            }
        };
        if let gltf::buffer::Source::Uri(uri) = buffer.source() {
            if !uri_decodes(uri) {
                return Err(format!("{what}: malformed URI"));
            }
        }
        let data = gltf::buffer::Data::from_source_and_blob(buffer.source(), Some(base), &mut blob)
            .map_err(|e| match e {
                gltf::Error::Io(e) => format!("{what}: cannot read external buffer file: {e}"),
                gltf::Error::MissingBlob => format!("{what}: the .glb has no BIN chunk"),
                e => format!("{what}: {e}"),
            })?;
        if data.len() < buffer.length() {
            return Err(format!(
                "{what}: truncated: byteLength is {} but only {} bytes are present",
                buffer.length(),
                data.len()
            ));
        }
        out.push(data.0);
    }
    Ok(out)
}

/// The bytes of a buffer view, checked against its buffer.
fn view_bytes<'b>(view: &gltf::buffer::View, buffers: &'b [Vec<u8>]) -> Result<&'b [u8], String> {
    let buf = buffers
        .get(view.buffer().index())
        .ok_or_else(|| format!("buffer view {}: buffer missing", view.index()))?;
    let end = view.offset().checked_add(view.length());
    match end {
        Some(end) if end <= buf.len() => Ok(&buf[view.offset()..end]),
        _ => Err(format!(
            "buffer view {} out of bounds: bytes {}..{} of a {}-byte buffer",
            view.index(),
            view.offset(),
            view.offset().saturating_add(view.length()),
            buf.len()
        )),
    }
}

/// Reads every element of an accessor (sparse included) through `conv`, which gets the element's bytes.
/// Extents are checked first: a short buffer is an error, never a panic.
fn read_elements<T: Copy>(
    acc: &gltf::Accessor,
    buffers: &[Vec<u8>],
    conv: impl Fn(&[u8]) -> T,
) -> Result<Vec<T>, String> {
    let name = match acc.name() {
        Some(n) => format!("accessor {} ('{n}')", acc.index()),
        None => format!("accessor {}", acc.index()),
    };
    let csize = acc.data_type().size();
    let elem = csize * acc.dimensions().multiplicity();
    let count = acc.count();
    if count > (1 << 31) || (acc.view().is_none() && count > (1 << 26)) {
        return Err(format!("{name}: count {count} is too large"));
    }
    // Allocated only once the extents are known to be inside the file's data.
    let mut out = Vec::new();
    match acc.view() {
        Some(view) => {
            let bytes = view_bytes(&view, buffers).map_err(|e| format!("{name}: {e}"))?;
            let stride = view.stride().unwrap_or(elem);
            if stride < elem {
                return Err(format!(
                    "{name}: byteStride {stride} is smaller than the element size {elem}"
                ));
            }
            if count > 0 {
                let need = (count - 1)
                    .checked_mul(stride)
                    .and_then(|n| n.checked_add(elem))
                    .and_then(|n| n.checked_add(acc.offset()));
                match need {
                    Some(need) if need <= bytes.len() => {}
                    _ => {
                        return Err(format!(
                            "{name} out of bounds: {count} elements of {elem} bytes (stride {stride}) from \
                             offset {} need more than the {} bytes of buffer view {}",
                            acc.offset(),
                            bytes.len(),
                            view.index()
                        ))
                    }
                }
            }
            let base = acc.offset();
            out.reserve_exact(count);
            for i in 0..count {
                let o = base + i * stride;
                out.push(conv(&bytes[o..o + elem]));
            }
        }
        None => {
            let zero = vec![0u8; elem];
            out.resize(count, conv(&zero));
        }
    }
    if let Some(sparse) = acc.sparse() {
        let n = sparse.count();
        let ind = sparse.indices();
        let isize = ind.index_type().size();
        let ibytes = view_bytes(&ind.view(), buffers).map_err(|e| format!("{name} sparse: {e}"))?;
        let vals = sparse.values();
        let vbytes =
            view_bytes(&vals.view(), buffers).map_err(|e| format!("{name} sparse: {e}"))?;
        let ineed = n
            .checked_mul(isize)
            .and_then(|x| x.checked_add(ind.offset()));
        let vneed = n
            .checked_mul(elem)
            .and_then(|x| x.checked_add(vals.offset()));
        if !matches!(ineed, Some(k) if k <= ibytes.len())
            || !matches!(vneed, Some(k) if k <= vbytes.len())
        {
            return Err(format!("{name}: sparse data out of bounds"));
        }
        for k in 0..n {
            let o = ind.offset() + k * isize;
            let idx = match isize {
                1 => ibytes[o] as usize,
                2 => u16::from_le_bytes([ibytes[o], ibytes[o + 1]]) as usize,
                _ => u32::from_le_bytes([ibytes[o], ibytes[o + 1], ibytes[o + 2], ibytes[o + 3]])
                    as usize,
            };
            if idx >= count {
                return Err(format!(
                    "{name}: sparse index {idx} out of range (count {count})"
                ));
            }
            let vo = vals.offset() + k * elem;
            out[idx] = conv(&vbytes[vo..vo + elem]);
        }
    }
    Ok(out)
}

/// One component as f32, normalised per the glTF rules when `normalized`.
fn component(dt: DataType, b: &[u8], normalized: bool) -> f32 {
    match dt {
        DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        DataType::U8 => {
            let v = b[0] as f32;
            if normalized {
                v / 255.0
            } else {
                v
            }
        }
        DataType::I8 => {
            let v = b[0] as i8 as f32;
            if normalized {
                (v / 127.0).max(-1.0)
            } else {
                v
            }
        }
        DataType::U16 => {
            let v = u16::from_le_bytes([b[0], b[1]]) as f32;
            if normalized {
                v / 65535.0
            } else {
                v
            }
        }
        DataType::I16 => {
            let v = i16::from_le_bytes([b[0], b[1]]) as f32;
            if normalized {
                (v / 32767.0).max(-1.0)
            } else {
                v
            }
        }
        DataType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
    }
}

/// Reads a float vector attribute of `N` components (any component type, normalised as declared).
fn read_vec<const N: usize>(
    acc: &gltf::Accessor,
    buffers: &[Vec<u8>],
    what: &str,
) -> Result<Vec<[f32; N]>, String> {
    let want = match N {
        2 => Dimensions::Vec2,
        3 => Dimensions::Vec3,
        _ => Dimensions::Vec4,
    };
    if acc.dimensions() != want {
        return Err(format!(
            "{what} accessor {} has type {:?}, expected {want:?}",
            acc.index(),
            acc.dimensions()
        ));
    }
    let dt = acc.data_type();
    let cs = dt.size();
    let norm = acc.normalized();
    read_elements(acc, buffers, |b| {
        let mut v = [0.0; N];
        for (k, c) in v.iter_mut().enumerate() {
            *c = component(dt, &b[k * cs..], norm);
        }
        v
    })
}

fn read_indices(acc: &gltf::Accessor, buffers: &[Vec<u8>]) -> Result<Vec<u32>, String> {
    if acc.dimensions() != Dimensions::Scalar {
        return Err(format!("index accessor {} is not SCALAR", acc.index()));
    }
    let dt = acc.data_type();
    if !matches!(dt, DataType::U8 | DataType::U16 | DataType::U32) {
        return Err(format!(
            "index accessor {} has component type {dt:?}, expected an unsigned integer",
            acc.index()
        ));
    }
    read_elements(acc, buffers, |b| match dt {
        DataType::U8 => b[0] as u32,
        DataType::U16 => u16::from_le_bytes([b[0], b[1]]) as u32,
        _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
    })
}

/// Decoded image pixels, shared by the sRGB and linear variants of a texture.
struct Pixels {
    width: usize,
    height: usize,
    rgba: Vec<[u8; 4]>,
}

/// Converts any decoded glTF image into RGBA8 (grey formats replicate into RGB).
fn to_rgba8(img: &gltf::image::Data) -> Result<Vec<[u8; 4]>, String> {
    use gltf::image::Format::*;
    let n = img.width as usize * img.height as usize;
    let p = &img.pixels;
    let (ch, bytes_per) = match img.format {
        R8 => (1, 1),
        R8G8 => (2, 1),
        R8G8B8 => (3, 1),
        R8G8B8A8 => (4, 1),
        R16 => (1, 2),
        R16G16 => (2, 2),
        R16G16B16 => (3, 2),
        R16G16B16A16 => (4, 2),
        R32G32B32FLOAT => (3, 4),
        R32G32B32A32FLOAT => (4, 4),
    };
    if p.len() < n * ch * bytes_per {
        return Err("decoded image is shorter than its size".into());
    }
    let get = |i: usize| -> u8 {
        match bytes_per {
            1 => p[i],
            2 => (u16::from_ne_bytes([p[2 * i], p[2 * i + 1]]) as u32 * 255 / 65535) as u8,
            _ => {
                let f = f32::from_ne_bytes([p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]]);
                (f.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
            }
        }
    };
    Ok((0..n)
        .map(|k| {
            let i = k * ch;
            match ch {
                1 => {
                    let g = get(i);
                    [g, g, g, 255]
                }
                2 => {
                    let g = get(i);
                    [g, g, g, get(i + 1)]
                }
                3 => [get(i), get(i + 1), get(i + 2), 255],
                _ => [get(i), get(i + 1), get(i + 2), get(i + 3)],
            }
        })
        .collect())
}

fn wrap(w: gltf::texture::WrappingMode) -> Wrap {
    match w {
        gltf::texture::WrappingMode::ClampToEdge => Wrap::ClampToEdge,
        gltf::texture::WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
        gltf::texture::WrappingMode::Repeat => Wrap::Repeat,
    }
}

/// KHR_texture_transform as a row-major 2x3 matrix: T * R * S.
pub(crate) fn uv_transform(offset: [f32; 2], rotation: f32, scale: [f32; 2]) -> [[f32; 3]; 2] {
    let (s, c) = rotation.sin_cos();
    [
        [c * scale[0], s * scale[1], offset[0]],
        [-s * scale[0], c * scale[1], offset[1]],
    ]
}

/// A texture binding before it is resolved: texture index, texCoord set, UV transform.
struct TexInfo {
    texture: usize,
    tex_coord: u32,
    transform: [[f32; 3]; 2],
}

impl TexInfo {
    fn from_info(info: &gltf::texture::Info) -> Self {
        let mut tex_coord = info.tex_coord();
        let transform = match info.texture_transform() {
            Some(t) => {
                if let Some(tc) = t.tex_coord() {
                    tex_coord = tc;
                }
                uv_transform(t.offset(), t.rotation(), t.scale())
            }
            None => TexRef::IDENTITY_UV,
        };
        Self {
            texture: info.texture().index(),
            tex_coord,
            transform,
        }
    }

    /// For texture infos the crate does not type (normal textures): read the extension JSON.
    fn from_parts(texture: usize, tex_coord: u32, ext: Option<&Value>) -> Self {
        let mut tc = tex_coord;
        let transform = match ext {
            Some(v) => {
                let pair = |k: &str, d: [f32; 2]| match v.get(k).and_then(|a| a.as_array()) {
                    Some(a) if a.len() == 2 => [
                        a[0].as_f64().unwrap_or(d[0] as f64) as f32,
                        a[1].as_f64().unwrap_or(d[1] as f64) as f32,
                    ],
                    _ => d,
                };
                if let Some(t) = v.get("texCoord").and_then(|t| t.as_u64()) {
                    tc = t as u32;
                }
                let rot = v.get("rotation").and_then(|r| r.as_f64()).unwrap_or(0.0) as f32;
                uv_transform(pair("offset", [0.0, 0.0]), rot, pair("scale", [1.0, 1.0]))
            }
            None => TexRef::IDENTITY_UV,
        };
        Self {
            texture,
            tex_coord: tc,
            transform,
        }
    }
}

struct Loader<'a> {
    doc: &'a gltf::Document,
    buffers: &'a [Vec<u8>],
    base: &'a Path,
    scene: Scene,
    /// (mesh, primitive) -> index in `scene.meshes`, or None when the primitive was skipped.
    prims: HashMap<(usize, usize), Option<u32>>,
    /// (glTF texture, sRGB) -> index in `scene.textures`, or None when its image failed.
    textures: HashMap<(usize, bool), Option<u32>>,
    images: HashMap<usize, Option<Rc<Pixels>>>,
    default_material: Option<u32>,
    dropped: usize,
    /// Which animation to keep.
    animation: usize,
    /// Per-vertex joints and weights of the last primitive built, when skinned.
    pending_skin: Option<(Vec<[u16; 4]>, Vec<Vec4>)>,
    /// Joints and weights of skinned scene meshes, by mesh index.
    skin_attrs: HashMap<u32, (Vec<[u16; 4]>, Vec<Vec4>)>,
    /// Morph targets (position and normal displacements) of the last primitive built.
    pending_morph: Option<Vec<MorphTarget>>,
    /// Morph targets of scene meshes, by mesh index.
    morph_attrs: HashMap<u32, Vec<MorphTarget>>,
}

impl Loader<'_> {
    fn run(mut self) -> Result<Scene, String> {
        let doc = self.doc;
        for m in doc.materials() {
            let mat = self.material(&m);
            self.scene.materials.push(mat);
        }

        // Roots: the default scene, else scene 0, else every node that is nobody's child.
        let roots: Vec<usize> = match doc.default_scene().or_else(|| doc.scenes().next()) {
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
        };

        let nodes: Vec<gltf::Node> = doc.nodes().collect();
        let mut visited = vec![false; nodes.len()];
        // The hierarchy as reached from the roots, for animation: parents, and what hangs from nodes.
        let mut parent_of: Vec<Option<u32>> = vec![None; nodes.len()];
        let mut inst_nodes: Vec<(u32, u32)> = Vec::new();
        let mut cam_nodes: Vec<(usize, u32)> = Vec::new();
        // (instance, scene mesh, glTF skin) of every skinned primitive placed.
        let mut skinned: Vec<(u32, u32, usize)> = Vec::new();
        // (scene mesh, node, default weights) of every primitive with morph targets placed.
        let mut morphed: Vec<(u32, u32, Vec<f32>)> = Vec::new();
        let mut cameras: Vec<(usize, Camera)> = Vec::new();
        let mut stack: Vec<(usize, Mat4)> =
            roots.iter().rev().map(|&r| (r, Mat4::IDENTITY)).collect();
        while let Some((ni, parent)) = stack.pop() {
            if visited[ni] {
                self.scene.warnings.push(format!(
                    "node {ni} is reached twice in the hierarchy (a cycle or a shared child); skipped the second time"
                ));
                continue;
            }
            visited[ni] = true;
            let node = &nodes[ni];
            let local = Mat4::from_cols_array_2d(&node.transform().matrix());
            let world = parent * local;
            for c in node.children().collect::<Vec<_>>().into_iter().rev() {
                if !visited[c.index()] {
                    parent_of[c.index()] = Some(ni as u32);
                }
                stack.push((c.index(), world));
            }
            let label = match node.name() {
                Some(n) => format!("node {ni} ('{n}')"),
                None => format!("node {ni}"),
            };
            if !world.is_finite() {
                self.scene.warnings.push(format!(
                    "{label}: transform is not finite; its mesh, light and camera are skipped"
                ));
                continue;
            }
            if let Some(mesh) = node.mesh() {
                if world.determinant() == 0.0 {
                    self.scene.warnings.push(format!(
                        "{label}: transform has zero scale; its mesh is skipped"
                    ));
                } else {
                    for prim in mesh.primitives() {
                        if let Some(m) = self.primitive(&mesh, &prim)? {
                            if self.morph_attrs.contains_key(&m) {
                                let weights = node
                                    .weights()
                                    .or(mesh.weights())
                                    .map(<[f32]>::to_vec)
                                    .unwrap_or_default();
                                morphed.push((m, ni as u32, weights));
                            }
                            if let Some(skin) = node.skin() {
                                skinned.push((self.scene.instances.len() as u32, m, skin.index()));
                            }
                            inst_nodes.push((self.scene.instances.len() as u32, ni as u32));
                            self.scene.instances.push(super::Instance::new(m, world));
                        }
                    }
                }
            }
            if let Some(light) = node.light() {
                self.light(&light, world, &label);
            }
            if let Some(cam) = node.camera() {
                let (_, rot, trans) = world.to_scale_rotation_translation();
                let rot = if rot.is_finite() && rot.length() > 0.0 {
                    rot.normalize()
                } else {
                    Quat::IDENTITY
                };
                let projection = match cam.projection() {
                    gltf::camera::Projection::Perspective(p) => Projection::Perspective {
                        yfov: p.yfov(),
                        aspect: p.aspect_ratio(),
                    },
                    gltf::camera::Projection::Orthographic(o) => Projection::Orthographic {
                        xmag: o.xmag(),
                        ymag: o.ymag(),
                    },
                };
                let name = cam
                    .name()
                    .or(node.name())
                    .map(str::to_owned)
                    .unwrap_or_else(|| format!("camera {}", cam.index()));
                cam_nodes.push((cam.index(), ni as u32));
                cameras.push((
                    cam.index(),
                    Camera {
                        name,
                        to_world: Mat4::from_rotation_translation(rot, trans),
                        projection,
                        lens: None,
                        motion: None,
                    },
                ));
            }
        }
        cameras.sort_by_key(|(i, _)| *i);
        // Camera nodes by position in the sorted list.
        let cam_nodes: Vec<(u32, u32)> = cameras
            .iter()
            .enumerate()
            .filter_map(|(k, (ci, _))| {
                cam_nodes
                    .iter()
                    .find(|(c, _)| c == ci)
                    .map(|&(_, n)| (k as u32, n))
            })
            .collect();
        self.scene.cameras = cameras.into_iter().map(|(_, c)| c).collect();
        let skins = self.skins(&skinned)?;
        let morphs = self.morphs(&morphed);
        if doc.animations().len() > 0 || !skins.is_empty() || !morphs.is_empty() {
            let mut a = match doc.animations().nth(self.animation) {
                Some(anim) => self.animation(&anim)?,
                None if doc.animations().len() == 0 => Animation::default(),
                None => {
                    return Err(format!(
                        "no animation {} (the file has {})",
                        self.animation,
                        doc.animations().len()
                    ))
                }
            };
            a.skins = skins;
            a.morphs = morphs;
            a.nodes = nodes
                .iter()
                .map(|n| {
                    let (t, r, s) = n.transform().decomposed();
                    super::animation::Node {
                        parent: parent_of[n.index()],
                        translation: Vec3::from(t),
                        rotation: Quat::from_array(r).normalize(),
                        scale: Vec3::from(s),
                    }
                })
                .collect();
            a.instances = inst_nodes;
            a.cameras = cam_nodes;
            if !a.channels.is_empty() || !a.skins.is_empty() || !a.morphs.is_empty() {
                self.scene.animation = Some(a);
            }
        }

        if self.dropped > 0 {
            self.scene
                .warnings
                .push(format!("dropped {} degenerate triangles", self.dropped));
        }
        let stats = &mut self.scene.stats;
        stats.nodes = doc.nodes().len();
        stats.meshes = doc.meshes().len();
        stats.primitives = doc.meshes().map(|m| m.primitives().len()).sum();
        stats.materials = doc.materials().len();
        stats.textures = doc.textures().len();
        stats.lights = doc.lights().map(|l| l.len()).unwrap_or(0);
        stats.cameras = doc.cameras().len();
        stats.animations = doc.animations().len();
        self.scene.stats.triangles = self.scene.triangle_count();
        Ok(self.scene)
    }

    /// A morph-target weights channel: key times and, per key element, one weight per target.
    fn weight_channel(
        &self,
        ch: &gltf::animation::Channel,
    ) -> Result<Option<WeightChannel>, String> {
        let sampler = ch.sampler();
        let interpolation = interpolation_of(sampler.interpolation());
        let times = self.key_times(&sampler.input())?;
        let output = sampler.output();
        if output.dimensions() != Dimensions::Scalar {
            return Err(format!("weights accessor {} is not SCALAR", output.index()));
        }
        let (dt, norm) = (output.data_type(), output.normalized());
        let values: Vec<f32> = read_elements(&output, self.buffers, |b| component(dt, b, norm))?;
        let elements = times.len() * interpolation.per_key();
        if elements == 0 {
            return Ok(None);
        }
        if !values.len().is_multiple_of(elements) || values.iter().any(|v| !v.is_finite()) {
            return Err(format!(
                "{} weights do not divide into {} key elements (or are not finite)",
                values.len(),
                elements
            ));
        }
        Ok(Some(WeightChannel {
            node: ch.target().node().index() as u32,
            interpolation,
            width: values.len() / elements,
            times,
            values,
        }))
    }

    /// Key times of a sampler input: float SCALAR, finite and increasing.
    fn key_times(&self, input: &gltf::Accessor) -> Result<Vec<f32>, String> {
        if input.dimensions() != Dimensions::Scalar || input.data_type() != DataType::F32 {
            return Err(format!(
                "input accessor {} is not a float SCALAR",
                input.index()
            ));
        }
        let times: Vec<f32> = read_elements(input, self.buffers, |b| {
            f32::from_le_bytes([b[0], b[1], b[2], b[3]])
        })?;
        if times.iter().any(|t| !t.is_finite()) || times.windows(2).any(|w| w[1] < w[0]) {
            return Err("key times are not finite and increasing".into());
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
    fn skins(&mut self, skinned: &[(u32, u32, usize)]) -> Result<Vec<Skin>, String> {
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
                .ok_or("skin out of range")?;
            let label = format!("skin {skin_index}");
            let joints: Vec<u32> = skin.joints().map(|n| n.index() as u32).collect();
            let inverse_bind: Vec<Mat4> = match skin.inverse_bind_matrices() {
                Some(acc) => {
                    if acc.dimensions() != Dimensions::Mat4 || acc.data_type() != DataType::F32 {
                        return Err(format!(
                            "{label}: inverse bind matrices accessor {} is not a float MAT4",
                            acc.index()
                        ));
                    }
                    read_elements(&acc, self.buffers, |b| {
                        Mat4::from_cols_array(&std::array::from_fn(|k| {
                            f32::from_le_bytes([b[4 * k], b[4 * k + 1], b[4 * k + 2], b[4 * k + 3]])
                        }))
                    })
                    .map_err(|e| format!("{label}: {e}"))?
                }
                None => vec![Mat4::IDENTITY; joints.len()],
            };
            if inverse_bind.len() < joints.len() {
                return Err(format!(
                    "{label}: {} inverse bind matrices for {} joints",
                    inverse_bind.len(),
                    joints.len()
                ));
            }
            if let Some(bad) = joints_v
                .iter()
                .flatten()
                .find(|&&j| j as usize >= joints.len())
            {
                return Err(format!(
                    "mesh {mesh}: JOINTS_0 names joint {bad} but {label} has {}",
                    joints.len()
                ));
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
    fn animation(&mut self, anim: &gltf::Animation) -> Result<Animation, String> {
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
                        .weight_channel(&ch)
                        .map_err(|e| format!("{label}, channel {ci}: {e}"))?;
                    out.weights.extend(c);
                    continue;
                }
            };
            let at = |e: String| format!("{label}, channel {ci}: {e}");
            let sampler = ch.sampler();
            let interpolation = interpolation_of(sampler.interpolation());
            let times = self.key_times(&sampler.input()).map_err(at)?;
            let output = sampler.output();
            let values: Vec<Vec4> = match property {
                Property::Rotation => read_vec::<4>(&output, self.buffers, "rotation output")
                    .map_err(at)?
                    .into_iter()
                    .map(Vec4::from)
                    .collect(),
                _ => read_vec::<3>(&output, self.buffers, "output")
                    .map_err(at)?
                    .into_iter()
                    .map(|v| Vec3::from(v).extend(0.0))
                    .collect(),
            };
            let per_key = if interpolation == Interpolation::CubicSpline {
                3
            } else {
                1
            };
            if values.len() != per_key * times.len() {
                return Err(at(format!(
                    "{} output values for {} keys (expected {})",
                    values.len(),
                    times.len(),
                    per_key * times.len()
                )));
            }
            if values.iter().any(|v| !v.is_finite()) {
                return Err(at("output values are not finite".into()));
            }
            if times.is_empty() {
                continue;
            }
            out.channels.push(Channel {
                node: ch.target().node().index() as u32,
                property,
                interpolation,
                times,
                values,
            });
        }
        Ok(out)
    }

    fn light(&mut self, light: &gltf::khr_lights_punctual::Light, world: Mat4, label: &str) {
        use gltf::khr_lights_punctual::Kind;
        let color = Vec3::from(light.color()) * light.intensity();
        let position = world.w_axis.truncate();
        let direction = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
        let needs_dir = !matches!(light.kind(), Kind::Point);
        if !color.is_finite() || (needs_dir && direction == Vec3::ZERO) {
            self.scene.warnings.push(format!(
                "{label}: light {} has no usable colour or direction; skipped",
                light.index()
            ));
            return;
        }
        self.scene.lights.push(match light.kind() {
            Kind::Point => Light::Point {
                position,
                intensity: color,
            },
            Kind::Spot {
                inner_cone_angle,
                outer_cone_angle,
            } => Light::Spot {
                position,
                direction,
                intensity: color,
                cos_inner: inner_cone_angle.cos(),
                cos_outer: outer_cone_angle.cos(),
            },
            Kind::Directional => Light::Directional {
                direction,
                irradiance: color,
            },
        });
    }

    fn material(&mut self, m: &gltf::Material) -> Material {
        let label = match m.name() {
            Some(n) => format!("material {} ('{n}')", m.index().unwrap_or(0)),
            None => format!("material {}", m.index().unwrap_or(0)),
        };
        let pbr = m.pbr_metallic_roughness();
        let mut mat = Material {
            name: m
                .name()
                .map(str::to_owned)
                .unwrap_or_else(|| format!("material {}", m.index().unwrap_or(0))),
            base_color: Vec4::from(pbr.base_color_factor()),
            metallic: pbr.metallic_factor(),
            roughness: pbr.roughness_factor(),
            emissive: Vec3::from(m.emissive_factor()) * m.emissive_strength().unwrap_or(1.0),
            alpha_mode: match m.alpha_mode() {
                gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
                gltf::material::AlphaMode::Mask => AlphaMode::Mask(m.alpha_cutoff().unwrap_or(0.5)),
                gltf::material::AlphaMode::Blend => AlphaMode::Blend,
            },
            double_sided: m.double_sided(),
            transmission: m
                .transmission()
                .map(|t| t.transmission_factor())
                .unwrap_or(0.0),
            ior: m.ior().unwrap_or(1.5),
            ..Material::default()
        };
        if let Some(spec) = m.extension_value("KHR_materials_specular") {
            if let Some(f) = spec.get("specularFactor").and_then(|f| f.as_f64()) {
                mat.specular = f as f32;
            }
        }
        if let Some(t) = pbr.base_color_texture() {
            mat.base_color_tex = self.tex_ref(TexInfo::from_info(&t), true, &label);
        }
        if let Some(t) = pbr.metallic_roughness_texture() {
            mat.metallic_roughness_tex = self.tex_ref(TexInfo::from_info(&t), false, &label);
        }
        if let Some(t) = m.normal_texture() {
            let info = TexInfo::from_parts(
                t.texture().index(),
                t.tex_coord(),
                t.extension_value("KHR_texture_transform"),
            );
            mat.normal_tex = self.tex_ref(info, false, &label);
            mat.normal_scale = t.scale();
        }
        if let Some(t) = m.emissive_texture() {
            mat.emissive_tex = self.tex_ref(TexInfo::from_info(&t), true, &label);
        }
        if let Some(t) = m.transmission().and_then(|t| t.transmission_texture()) {
            mat.transmission_tex = self.tex_ref(TexInfo::from_info(&t), false, &label);
        }
        // Without KHR_materials_volume a transmissive surface is thin-walled (thickness 0). The
        // thickness texture only serves rasterisers; a path tracer measures the real thickness.
        if let Some(v) = m.volume() {
            mat.thickness = v.thickness_factor().max(0.0);
            mat.attenuation_color = Vec3::from(v.attenuation_color()).clamp(Vec3::ZERO, Vec3::ONE);
            let d = v.attenuation_distance();
            mat.attenuation_distance = if d > 0.0 { d } else { f32::INFINITY };
        }
        mat
    }

    fn tex_ref(&mut self, info: TexInfo, srgb: bool, label: &str) -> Option<TexRef> {
        if info.tex_coord != 0 {
            self.scene.warnings.push(format!(
                "{label}: texture {} uses TEXCOORD_{}; glint reads only TEXCOORD_0",
                info.texture, info.tex_coord
            ));
        }
        let t = self.texture(info.texture, srgb)?;
        Some(TexRef {
            texture: t,
            uv_transform: info.transform,
        })
    }

    fn texture(&mut self, index: usize, srgb: bool) -> Option<u32> {
        if let Some(t) = self.textures.get(&(index, srgb)) {
            return *t;
        }
        let tex = self.doc.textures().nth(index)?;
        let image = tex.source();
        let pixels = self.image(&image);
        let out = pixels.map(|p| {
            let sampler = tex.sampler();
            let name = tex
                .name()
                .or(image.name())
                .map(str::to_owned)
                .or_else(|| match image.source() {
                    gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
                        Some(uri.to_owned())
                    }
                    _ => None,
                })
                .unwrap_or_else(|| format!("texture {index}"));
            self.scene.textures.push(Texture {
                name,
                width: p.width,
                height: p.height,
                pixels: p.rgba.clone(),
                srgb,
                wrap_s: wrap(sampler.wrap_s()),
                wrap_t: wrap(sampler.wrap_t()),
            });
            (self.scene.textures.len() - 1) as u32
        });
        self.textures.insert((index, srgb), out);
        out
    }

    fn image(&mut self, image: &gltf::Image) -> Option<Rc<Pixels>> {
        let i = image.index();
        if let Some(p) = self.images.get(&i) {
            return p.clone();
        }
        let label = match image.source() {
            gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
                format!("image {i} ('{uri}')")
            }
            _ => format!("image {i}"),
        };
        let result = self.decode_image(image);
        let out = match result {
            Ok(p) => Some(Rc::new(p)),
            Err(e) => {
                self.scene
                    .warnings
                    .push(format!("{label}: {e}; the texture is ignored"));
                None
            }
        };
        self.images.insert(i, out.clone());
        out
    }

    fn decode_image(&self, image: &gltf::Image) -> Result<Pixels, String> {
        match image.source() {
            gltf::image::Source::View { view, .. } => {
                let bytes = view_bytes(&view, self.buffers)?;
                let img = image::load_from_memory(bytes)
                    .map_err(|e| format!("cannot decode image: {e}"))?
                    .to_rgba8();
                Ok(Pixels {
                    width: img.width() as usize,
                    height: img.height() as usize,
                    rgba: img.pixels().map(|p| p.0).collect(),
                })
            }
            gltf::image::Source::Uri { uri, .. } => {
                if !uri_decodes(uri) {
                    return Err("malformed URI".into());
                }
                let d = gltf::image::Data::from_source(image.source(), Some(self.base), &[])
                    .map_err(|e| match e {
                        gltf::Error::Io(e) => format!("cannot read image file: {e}"),
                        e => format!("cannot decode image: {e}"),
                    })?;
                Ok(Pixels {
                    width: d.width as usize,
                    height: d.height as usize,
                    rgba: to_rgba8(&d)?,
                })
            }
        }
    }

    fn default_material(&mut self) -> u32 {
        if let Some(m) = self.default_material {
            return m;
        }
        self.scene.materials.push(Material::default());
        let m = (self.scene.materials.len() - 1) as u32;
        self.default_material = Some(m);
        m
    }

    /// The scene mesh of a (mesh, primitive) pair, built on first use; None when skipped.
    fn primitive(
        &mut self,
        mesh: &gltf::Mesh,
        prim: &gltf::Primitive,
    ) -> Result<Option<u32>, String> {
        let key = (mesh.index(), prim.index());
        if let Some(m) = self.prims.get(&key) {
            return Ok(*m);
        }
        let label = match mesh.name() {
            Some(n) => format!("mesh {} ('{n}'), primitive {}", mesh.index(), prim.index()),
            None => format!("mesh {}, primitive {}", mesh.index(), prim.index()),
        };
        let built = self
            .build_primitive(mesh, prim, &label)
            .map_err(|e| format!("{label}: {e}"))?;
        let out = match built {
            Some(m) => {
                self.scene.meshes.push(m);
                let index = (self.scene.meshes.len() - 1) as u32;
                if let Some(attrs) = self.pending_skin.take() {
                    self.skin_attrs.insert(index, attrs);
                }
                if let Some(targets) = self.pending_morph.take() {
                    self.morph_attrs.insert(index, targets);
                }
                Some(index)
            }
            None => None,
        };
        self.prims.insert(key, out);
        Ok(out)
    }

    fn build_primitive(
        &mut self,
        mesh: &gltf::Mesh,
        prim: &gltf::Primitive,
        label: &str,
    ) -> Result<Option<Mesh>, String> {
        let mode = prim.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            self.scene
                .warnings
                .push(format!("{label}: mode {mode:?} is not triangles; skipped"));
            return Ok(None);
        }
        let Some(pos_acc) = prim.get(&gltf::Semantic::Positions) else {
            self.scene
                .warnings
                .push(format!("{label}: no POSITION attribute; skipped"));
            return Ok(None);
        };
        let positions: Vec<Vec3> = read_vec::<3>(&pos_acc, self.buffers, "POSITION")?
            .into_iter()
            .map(Vec3::from)
            .collect();
        let n = positions.len();
        let check_len = |what: &str, len: usize| {
            if len != n {
                Err(format!("{what} has {len} elements but POSITION has {n}"))
            } else {
                Ok(())
            }
        };
        let normals: Vec<Vec3> = match prim.get(&gltf::Semantic::Normals) {
            Some(a) => {
                let v = read_vec::<3>(&a, self.buffers, "NORMAL")?;
                check_len("NORMAL", v.len())?;
                v.into_iter().map(Vec3::from).collect()
            }
            None => Vec::new(),
        };
        let uvs: Vec<Vec2> = match prim.get(&gltf::Semantic::TexCoords(0)) {
            Some(a) => {
                let v = read_vec::<2>(&a, self.buffers, "TEXCOORD_0")?;
                check_len("TEXCOORD_0", v.len())?;
                v.into_iter().map(Vec2::from).collect()
            }
            None => Vec::new(),
        };
        let tangents: Vec<Vec4> = match prim.get(&gltf::Semantic::Tangents) {
            Some(a) => {
                let v = read_vec::<4>(&a, self.buffers, "TANGENT")?;
                check_len("TANGENT", v.len())?;
                v.into_iter().map(Vec4::from).collect()
            }
            None => Vec::new(),
        };
        let flat: Vec<u32> = match prim.indices() {
            Some(a) => {
                let idx = read_indices(&a, self.buffers)?;
                if let Some(&bad) = idx.iter().find(|&&i| i as usize >= n) {
                    return Err(format!(
                        "vertex index {bad} out of range (the primitive has {n} vertices)"
                    ));
                }
                idx
            }
            None => (0..n as u32).collect(),
        };
        let indices: Vec<[u32; 3]> = match mode {
            Mode::Triangles => flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
            Mode::TriangleStrip => (2..flat.len())
                .map(|i| {
                    if i % 2 == 0 {
                        [flat[i - 2], flat[i - 1], flat[i]]
                    } else {
                        [flat[i - 1], flat[i - 2], flat[i]]
                    }
                })
                .collect(),
            _ => (2..flat.len())
                .map(|i| [flat[0], flat[i - 1], flat[i]])
                .collect(),
        };
        let material = match prim.material().index() {
            Some(i) => i as u32,
            None => self.default_material(),
        };
        let mut m = Mesh {
            name: match mesh.name() {
                Some(name) if mesh.primitives().len() > 1 => format!("{name}/{}", prim.index()),
                Some(name) => name.to_owned(),
                None => format!("mesh {}/{}", mesh.index(), prim.index()),
            },
            positions,
            normals,
            uvs,
            tangents,
            indices,
            material,
        };
        let (dropped, kept) = clean_mesh_order(&mut m);
        self.dropped += dropped;
        self.pending_skin = None;
        if let (Some(j), Some(w)) = (
            prim.get(&gltf::Semantic::Joints(0)),
            prim.get(&gltf::Semantic::Weights(0)),
        ) {
            let joints = read_vec::<4>(&j, self.buffers, "JOINTS_0")?;
            let weights = read_vec::<4>(&w, self.buffers, "WEIGHTS_0")?;
            check_len("JOINTS_0", joints.len())?;
            check_len("WEIGHTS_0", weights.len())?;
            let pick = |k: usize| kept.as_ref().map_or(k, |o| o[k]);
            let joints: Vec<[u16; 4]> = (0..m.positions.len())
                .map(|k| joints[pick(k)].map(|x| x.clamp(0.0, u16::MAX as f32) as u16))
                .collect();
            let weights: Vec<Vec4> = (0..m.positions.len())
                .map(|k| Vec4::from(weights[pick(k)]))
                .collect();
            self.pending_skin = Some((joints, weights));
        }
        self.pending_morph = None;
        if prim.morph_targets().len() > 0 {
            let pick = |k: usize| kept.as_ref().map_or(k, |o| o[k]);
            let mut targets = Vec::new();
            for (ti, target) in prim.morph_targets().enumerate() {
                let what = format!("morph target {ti}");
                let read = |acc: Option<gltf::Accessor>| -> Result<Vec<Vec3>, String> {
                    match acc {
                        Some(a) => {
                            let v = read_vec::<3>(&a, self.buffers, &what)?;
                            check_len(&what, v.len())?;
                            Ok((0..m.positions.len())
                                .map(|k| Vec3::from(v[pick(k)]))
                                .collect())
                        }
                        None => Ok(Vec::new()),
                    }
                };
                let dp = read(target.positions())?;
                let dn = read(target.normals())?;
                let dp = if dp.is_empty() {
                    vec![Vec3::ZERO; m.positions.len()]
                } else {
                    dp
                };
                if dp.iter().chain(&dn).any(|d| !d.is_finite()) {
                    return Err(format!("{what}: displacements are not finite"));
                }
                targets.push((dp, dn));
            }
            self.pending_morph = Some(targets);
        }
        if m.indices.is_empty() {
            self.scene
                .warnings
                .push(format!("{label}: no valid triangles; skipped"));
            return Ok(None);
        }
        Ok(Some(m))
    }
}

/// Makes a mesh safe for the accelerators: drops degenerate triangles (repeated indices, zero area, a
/// non-finite corner), keeps only referenced vertices (so no NaN/Inf position survives), repairs
/// attributes, and computes area-weighted normals where the file has none (or unusable ones).
/// Returns the number of triangles dropped.
pub(crate) fn clean_mesh(m: &mut Mesh) -> usize {
    clean_mesh_order(m).0
}

/// `clean_mesh`, also returning which original vertex each kept vertex is (None when all are kept in
/// place), so that attributes the mesh does not hold (skin weights) can follow.
fn clean_mesh_order(m: &mut Mesh) -> (usize, Option<Vec<usize>>) {
    let mut kept = None;
    let before = m.indices.len();
    let nv = m.positions.len();
    let pos = &m.positions;
    m.indices.retain(|&[a, b, c]| {
        if a == b || b == c || a == c || a as usize >= nv || b as usize >= nv || c as usize >= nv {
            return false;
        }
        let (pa, pb, pc) = (pos[a as usize], pos[b as usize], pos[c as usize]);
        if !(pa.is_finite() && pb.is_finite() && pc.is_finite()) {
            return false;
        }
        let n = (pb - pa).cross(pc - pa);
        n.is_finite() && n.length_squared() > 0.0
    });
    let dropped = before - m.indices.len();

    // Compact to the referenced vertices when some are unreferenced.
    let mut remap = vec![u32::MAX; nv];
    let mut used = 0u32;
    for t in &m.indices {
        for &k in t {
            if remap[k as usize] == u32::MAX {
                remap[k as usize] = used;
                used += 1;
            }
        }
    }
    if (used as usize) < nv {
        let mut order = vec![0usize; used as usize];
        for (old, &new) in remap.iter().enumerate() {
            if new != u32::MAX {
                order[new as usize] = old;
            }
        }
        m.positions = order.iter().map(|&o| m.positions[o]).collect();
        if m.normals.len() == nv {
            m.normals = order.iter().map(|&o| m.normals[o]).collect();
        } else {
            m.normals.clear();
        }
        if m.uvs.len() == nv {
            m.uvs = order.iter().map(|&o| m.uvs[o]).collect();
        } else {
            m.uvs.clear();
        }
        if m.tangents.len() == nv {
            m.tangents = order.iter().map(|&o| m.tangents[o]).collect();
        } else {
            m.tangents.clear();
        }
        for t in &mut m.indices {
            for k in t.iter_mut() {
                *k = remap[*k as usize];
            }
        }
        kept = Some(order);
    }

    let n = m.positions.len();
    if m.uvs.len() != n {
        m.uvs.clear();
    }
    for uv in &mut m.uvs {
        if !uv.is_finite() {
            *uv = Vec2::ZERO;
        }
    }
    if m.tangents.len() != n || m.tangents.iter().any(|t| !t.is_finite()) {
        m.tangents.clear();
    }
    let bad_normal = |v: &Vec3| !v.is_finite() || v.length_squared() < 1e-20;
    if m.normals.len() != n || m.normals.iter().any(bad_normal) {
        let mut acc = vec![Vec3::ZERO; n];
        for &[a, b, c] in &m.indices {
            let (pa, pb, pc) = (
                m.positions[a as usize],
                m.positions[b as usize],
                m.positions[c as usize],
            );
            let f = (pb - pa).cross(pc - pa); // length = 2 * area: area weighting
            acc[a as usize] += f;
            acc[b as usize] += f;
            acc[c as usize] += f;
        }
        let computed = acc.into_iter().map(|v| {
            let u = v.normalize_or_zero();
            if u == Vec3::ZERO {
                Vec3::Z
            } else {
                u
            }
        });
        if m.normals.len() != n {
            m.normals = computed.collect();
        } else {
            for (given, c) in m.normals.iter_mut().zip(computed) {
                if bad_normal(given) {
                    *given = c;
                }
            }
        }
    }
    (dropped, kept)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Light, Projection, Scene};
    use std::path::PathBuf;

    fn base64(bytes: &[u8]) -> String {
        const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut s = String::new();
        for c in bytes.chunks(3) {
            let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
            let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
            for k in 0..4 {
                if k <= c.len() {
                    s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
                } else {
                    s.push('=');
                }
            }
        }
        s
    }

    /// Little-endian bytes of positions then (optionally) u16 indices, padded to 4.
    fn geometry(pos: &[[f32; 3]], idx: &[u16]) -> Vec<u8> {
        let mut b: Vec<u8> = pos.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
        b.extend(idx.iter().flat_map(|i| i.to_le_bytes()));
        while !b.len().is_multiple_of(4) {
            b.push(0);
        }
        b
    }

    /// A document whose mesh 0 is one primitive over `pos` (and `idx` when not empty), plus `extra`
    /// top-level members (nodes, scenes, ...), written to a temp dir.
    fn write(dir: &tempfile::TempDir, pos: &[[f32; 3]], idx: &[u16], extra: &str) -> PathBuf {
        let data = geometry(pos, idx);
        let pos_len = pos.len() * 12;
        let indices = if idx.is_empty() {
            String::new()
        } else {
            r#", "indices": 1"#.to_string()
        };
        let json = format!(
            r#"{{
  "asset": {{"version": "2.0"}},
  "buffers": [{{"byteLength": {len}, "uri": "data:application/octet-stream;base64,{b64}"}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": {pos_len}}},
    {{"buffer": 0, "byteOffset": {pos_len}, "byteLength": {idx_len}}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": {np}, "type": "VEC3"}},
    {{"bufferView": 1, "componentType": 5123, "count": {ni}, "type": "SCALAR"}}
  ],
  "meshes": [{{"name": "tri", "primitives": [{{"attributes": {{"POSITION": 0}}{indices}}}]}}],
  {extra}
}}"#,
            len = data.len(),
            b64 = base64(&data),
            idx_len = (idx.len() * 2).max(2),
            np = pos.len(),
            ni = idx.len().max(1),
        );
        let p = dir.path().join("t.gltf");
        std::fs::write(&p, json).unwrap();
        p
    }

    const TRI: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

    #[test]
    fn morph_target_weights_are_animated_and_posed() {
        // A triangle, one target lifting it by z = 1, weights keyed 0 -> 1 over a second.
        let floats: Vec<f32> = TRI
            .iter()
            .flatten()
            .copied()
            .chain([0.0, 0.0, 1.0].repeat(3))
            .chain([0.0, 1.0, 0.0, 1.0])
            .collect();
        let data: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
        let json = format!(
            r#"{{
  "asset": {{"version": "2.0"}},
  "buffers": [{{"byteLength": {len}, "uri": "data:application/octet-stream;base64,{b64}"}}],
  "bufferViews": [{{"buffer": 0, "byteLength": {len}}}],
  "accessors": [
    {{"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3"}},
    {{"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"}},
    {{"bufferView": 0, "byteOffset": 72, "componentType": 5126, "count": 2, "type": "SCALAR"}},
    {{"bufferView": 0, "byteOffset": 80, "componentType": 5126, "count": 2, "type": "SCALAR"}}
  ],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "targets": [{{"POSITION": 1}}]}}],
              "weights": [0.25]}}],
  "nodes": [{{"mesh": 0}}],
  "scenes": [{{"nodes": [0]}}],
  "animations": [{{"channels": [{{"sampler": 0, "target": {{"node": 0, "path": "weights"}}}}],
                   "samplers": [{{"input": 2, "output": 3}}]}}]
}}"#,
            len = data.len(),
            b64 = base64(&data),
        );
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("m.gltf");
        std::fs::write(&p, json).unwrap();
        let scene = Scene::load(&p).unwrap();
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
        let z_at = |t: f32| {
            let mut s = scene.clone();
            super::super::animation::pose(&mut s, t, [0.0, 0.0]);
            s.meshes[0]
                .positions
                .iter()
                .map(|p| p.z)
                .collect::<Vec<_>>()
        };
        assert_eq!(z_at(0.5), vec![0.5; 3]);
        assert_eq!(z_at(7.0), vec![1.0; 3]);
        // Unposed, the mesh is the file's base shape.
        assert!(scene.meshes[0].positions.iter().all(|p| p.z == 0.0));
        let a = scene.animation.as_ref().unwrap();
        assert_eq!(a.morphs[0].default_weights, vec![0.25]);
    }

    #[test]
    fn one_mesh_two_nodes_is_one_mesh_two_instances() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(
            &dir,
            &TRI,
            &[0, 1, 2],
            r#""nodes": [{"mesh": 0, "translation": [5, 0, 0]}, {"mesh": 0}],
               "scenes": [{"nodes": [0, 1]}], "scene": 0"#,
        );
        let s = Scene::load(&p).unwrap();
        assert_eq!(s.meshes.len(), 1);
        assert_eq!(s.instances.len(), 2);
        assert_eq!(s.stats.triangles, 2);
        assert_eq!(s.stats.nodes, 2);
        assert_eq!(s.stats.meshes, 1);
        assert_eq!(s.stats.primitives, 1);
        assert_eq!(
            s.instances[0].to_world.w_axis.truncate(),
            Vec3::new(5.0, 0.0, 0.0)
        );
        assert!(s.instances[1].is_identity());
        // No material in the file: one default material, exactly the spec default.
        assert_eq!(s.materials.len(), 1);
        assert_eq!(s.materials[0].metallic, 1.0);
        assert_eq!(s.materials[0].roughness, 1.0);
    }

    #[test]
    fn hierarchy_composes_parent_then_child() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(
            &dir,
            &TRI,
            &[0, 1, 2],
            r#""nodes": [{"translation": [1, 0, 0], "scale": [2, 2, 2], "children": [1]},
                         {"mesh": 0, "translation": [0, 1, 0]}],
               "scenes": [{"nodes": [0]}]"#,
        );
        let s = Scene::load(&p).unwrap();
        assert_eq!(s.instances.len(), 1);
        let m = s.instances[0].to_world;
        assert!((m.transform_point3(Vec3::ZERO) - Vec3::new(1.0, 2.0, 0.0)).length() < 1e-6);
        assert!((m.transform_point3(Vec3::X) - Vec3::new(3.0, 2.0, 0.0)).length() < 1e-6);
    }

    #[test]
    fn no_scenes_uses_root_nodes() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(
            &dir,
            &TRI,
            &[0, 1, 2],
            r#""nodes": [{"children": [1]}, {"mesh": 0}, {"mesh": 0}]"#,
        );
        let s = Scene::load(&p).unwrap();
        assert_eq!(s.instances.len(), 2);
    }

    #[test]
    fn non_indexed_primitive_and_computed_normals() {
        let dir = tempfile::tempdir().unwrap();
        let quad = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let p = write(
            &dir,
            &quad,
            &[],
            r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#,
        );
        let s = Scene::load(&p).unwrap();
        assert_eq!(s.meshes[0].indices.len(), 2);
        assert_eq!(s.stats.triangles, 2);
        assert_eq!(s.meshes[0].normals.len(), 6);
        for n in &s.meshes[0].normals {
            assert!((*n - Vec3::Z).length() < 1e-6, "{n}");
        }
        assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    }

    #[test]
    fn nan_and_degenerate_triangles_are_dropped_with_one_warning() {
        let dir = tempfile::tempdir().unwrap();
        let pos = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [f32::NAN, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [f32::INFINITY, 1.0, 1.0],
        ];
        // valid, NaN corner, repeated index, collinear (zero area), infinite corner
        let idx = [0, 1, 2, 0, 3, 1, 0, 0, 1, 0, 1, 4, 5, 1, 2];
        let p = write(
            &dir,
            &pos,
            &idx,
            r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#,
        );
        let s = Scene::load(&p).unwrap();
        assert_eq!(s.meshes[0].indices.len(), 1);
        assert!(s.meshes[0].positions.iter().all(|p| p.is_finite()));
        assert_eq!(s.meshes[0].positions.len(), 3);
        let w: Vec<_> = s
            .warnings
            .iter()
            .filter(|w| w.contains("degenerate"))
            .collect();
        assert_eq!(w.len(), 1, "{:?}", s.warnings);
        assert!(w[0].contains("dropped 4 degenerate triangles"), "{}", w[0]);
    }

    #[test]
    fn unsupported_required_extension_is_a_clear_error() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(
            &dir,
            &TRI,
            &[0, 1, 2],
            r#""nodes": [{"mesh": 0}],
               "extensionsUsed": ["KHR_draco_mesh_compression", "KHR_materials_volume"],
               "extensionsRequired": ["KHR_materials_volume", "KHR_draco_mesh_compression"]"#,
        );
        let e = Scene::load(&p).unwrap_err().to_string();
        assert!(
            e.contains("requires unsupported extension KHR_draco_mesh_compression"),
            "{e}"
        );
        assert!(e.contains("t.gltf"), "{e}");
        // A supported one that the gltf crate itself does not know is accepted.
        let p = write(
            &dir,
            &TRI,
            &[0, 1, 2],
            r#""nodes": [{"mesh": 0}], "extensionsUsed": ["KHR_materials_volume"],
               "extensionsRequired": ["KHR_materials_volume"]"#,
        );
        Scene::load(&p).unwrap();
    }

    #[test]
    fn spot_and_point_lights() {
        let dir = tempfile::tempdir().unwrap();
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let extra = format!(
            r#""extensionsUsed": ["KHR_lights_punctual"],
               "extensions": {{"KHR_lights_punctual": {{"lights": [
                  {{"type": "spot", "color": [1, 0.5, 0.25], "intensity": 4,
                    "spot": {{"innerConeAngle": 0.2, "outerConeAngle": 0.5}}}},
                  {{"type": "point", "intensity": 2}},
                  {{"type": "directional", "intensity": 3}}]}}}},
               "nodes": [
                  {{"translation": [0, 5, 0], "rotation": [{nx}, 0, 0, {h}],
                    "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}},
                  {{"translation": [1, 2, 3], "extensions": {{"KHR_lights_punctual": {{"light": 1}}}}}},
                  {{"extensions": {{"KHR_lights_punctual": {{"light": 2}}}}}}],
               "scenes": [{{"nodes": [0, 1, 2]}}]"#,
            nx = -h
        );
        let p = write(&dir, &TRI, &[0, 1, 2], &extra);
        let s = Scene::load(&p).unwrap();
        assert_eq!(s.lights.len(), 3);
        assert_eq!(s.stats.lights, 3);
        match &s.lights[0] {
            Light::Spot {
                position,
                direction,
                intensity,
                cos_inner,
                cos_outer,
            } => {
                assert!((*position - Vec3::new(0.0, 5.0, 0.0)).length() < 1e-6);
                assert!((*direction - Vec3::NEG_Y).length() < 1e-5, "{direction}");
                assert!((*intensity - Vec3::new(4.0, 2.0, 1.0)).length() < 1e-6);
                assert!((cos_inner - 0.2f32.cos()).abs() < 1e-6);
                assert!((cos_outer - 0.5f32.cos()).abs() < 1e-6);
            }
            l => panic!("expected a spot light, got {l:?}"),
        }
        assert_eq!(
            s.lights[1],
            Light::Point {
                position: Vec3::new(1.0, 2.0, 3.0),
                intensity: Vec3::splat(2.0)
            }
        );
        assert_eq!(
            s.lights[2],
            Light::Directional {
                direction: Vec3::NEG_Z,
                irradiance: Vec3::splat(3.0)
            }
        );
    }

    #[test]
    fn cameras_in_document_order_without_scale() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(
            &dir,
            &TRI,
            &[0, 1, 2],
            r#""cameras": [
                 {"name": "persp", "type": "perspective",
                  "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.1}},
                 {"type": "orthographic",
                  "orthographic": {"xmag": 2, "ymag": 1, "znear": 0.1, "zfar": 10}}],
               "nodes": [{"name": "orthoNode", "camera": 1, "translation": [0, 0, 9]},
                         {"camera": 0, "translation": [1, 2, 3], "scale": [2, 2, 2]}],
               "scenes": [{"nodes": [0, 1]}]"#,
        );
        let s = Scene::load(&p).unwrap();
        assert_eq!(s.cameras.len(), 2);
        assert_eq!(s.stats.cameras, 2);
        let c0 = &s.cameras[0];
        assert_eq!(c0.name, "persp");
        assert_eq!(
            c0.projection,
            Projection::Perspective {
                yfov: 0.7,
                aspect: Some(1.5)
            }
        );
        assert!((c0.position() - Vec3::new(1.0, 2.0, 3.0)).length() < 1e-6);
        assert!((c0.to_world.x_axis.truncate().length() - 1.0).abs() < 1e-6);
        let c1 = &s.cameras[1];
        assert_eq!(c1.name, "orthoNode");
        assert_eq!(
            c1.projection,
            Projection::Orthographic {
                xmag: 2.0,
                ymag: 1.0
            }
        );
    }

    #[test]
    fn materials_textures_and_transform() {
        let dir = tempfile::tempdir().unwrap();
        // A 2x1 PNG written next to the file.
        let img = image::RgbaImage::from_raw(2, 1, vec![255, 0, 0, 255, 0, 0, 255, 128]).unwrap();
        img.save(dir.path().join("tex.png")).unwrap();
        let p = write(
            &dir,
            &TRI,
            &[0, 1, 2],
            r#""images": [{"uri": "tex.png"}],
               "samplers": [{"wrapS": 33071, "wrapT": 33648}],
               "textures": [{"source": 0, "sampler": 0}],
               "extensionsUsed": ["KHR_texture_transform", "KHR_materials_emissive_strength",
                                  "KHR_materials_transmission", "KHR_materials_ior"],
               "materials": [{"name": "m",
                  "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                     "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":
                        {"offset": [0.5, 0.25], "scale": [2, 3]}}},
                     "metallicFactor": 0.25, "roughnessFactor": 0.75,
                     "metallicRoughnessTexture": {"index": 0}},
                  "normalTexture": {"index": 0, "scale": 0.5},
                  "emissiveFactor": [1, 0.5, 0], "emissiveTexture": {"index": 0},
                  "alphaMode": "MASK", "doubleSided": true,
                  "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4},
                                 "KHR_materials_transmission": {"transmissionFactor": 0.9},
                                 "KHR_materials_ior": {"ior": 1.33}}}],
               "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#,
        );
        let s = Scene::load(&p).unwrap();
        // The helper's mesh names no material: the spec default is appended after the file's one.
        assert_eq!(s.materials.len(), 2);
        assert_eq!(s.meshes[0].material, 1);
        assert_eq!(s.materials[1].metallic, 1.0);
        let m = &s.materials[0];
        assert_eq!(m.name, "m");
        assert_eq!(m.metallic, 0.25);
        assert_eq!(m.roughness, 0.75);
        assert_eq!(m.emissive, Vec3::new(4.0, 2.0, 0.0));
        assert_eq!(m.alpha_mode, AlphaMode::Mask(0.5));
        assert!(m.double_sided);
        assert!((m.transmission - 0.9).abs() < 1e-6);
        assert!((m.ior - 1.33).abs() < 1e-6);
        assert_eq!(m.normal_scale, 0.5);
        // sRGB and linear variants of texture 0.
        assert_eq!(s.textures.len(), 2);
        let bc = m.base_color_tex.unwrap();
        let t = &s.textures[bc.texture as usize];
        assert!(t.srgb);
        assert_eq!((t.width, t.height), (2, 1));
        assert_eq!(t.pixels[1], [0, 0, 255, 128]);
        assert_eq!(t.wrap_s, Wrap::ClampToEdge);
        assert_eq!(t.wrap_t, Wrap::MirroredRepeat);
        assert_eq!(bc.apply(Vec2::new(1.0, 1.0)), Vec2::new(2.5, 3.25));
        let mr = m.metallic_roughness_tex.unwrap();
        assert!(!s.textures[mr.texture as usize].srgb);
        assert_eq!(m.normal_tex.unwrap().texture, mr.texture);
        assert_eq!(m.emissive_tex.unwrap().texture, bc.texture);
        assert_eq!(s.stats.textures, 1);
    }

    #[test]
    fn texture_transform_rotation_matches_spec() {
        let m = uv_transform([0.0, 0.0], std::f32::consts::FRAC_PI_2, [1.0, 1.0]);
        let t = TexRef {
            texture: 0,
            uv_transform: m,
        };
        // The spec's rotation matrix [cos sin; -sin cos] takes (1, 0) to (0, -1).
        let r = t.apply(Vec2::new(1.0, 0.0));
        assert!((r - Vec2::new(0.0, -1.0)).length() < 1e-6, "{r}");
    }

    #[test]
    fn accessor_past_its_buffer_is_an_error_naming_the_mesh() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(&dir, &TRI, &[0, 1, 2], r#""nodes": [{"mesh": 0}]"#);
        let text = std::fs::read_to_string(&p).unwrap().replace(
            r#""count": 3, "type": "VEC3""#,
            r#""count": 300, "type": "VEC3""#,
        );
        std::fs::write(&p, text).unwrap();
        let e = Scene::load(&p).unwrap_err().to_string();
        assert!(e.contains("mesh 0 ('tri'), primitive 0"), "{e}");
        assert!(e.contains("out of bounds"), "{e}");
    }

    #[test]
    fn index_out_of_range_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(&dir, &TRI, &[0, 1, 7], r#""nodes": [{"mesh": 0}]"#);
        let e = Scene::load(&p).unwrap_err().to_string();
        assert!(e.contains("index 7 out of range"), "{e}");
    }

    #[test]
    fn points_are_skipped_with_a_warning() {
        let dir = tempfile::tempdir().unwrap();
        let p = write(&dir, &TRI, &[0, 1, 2], r#""nodes": [{"mesh": 0}]"#);
        let text = std::fs::read_to_string(&p)
            .unwrap()
            .replace(r#""indices": 1"#, r#""indices": 1, "mode": 0"#);
        std::fs::write(&p, text).unwrap();
        let s = Scene::load(&p).unwrap();
        assert!(s.meshes.is_empty());
        assert!(s
            .warnings
            .iter()
            .any(|w| w.contains("mesh 0 ('tri'), primitive 0")));
    }

    #[test]
    fn strips_and_fans_become_triangles() {
        let dir = tempfile::tempdir().unwrap();
        let quad = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        ];
        for (mode, idx) in [(5, [0u16, 1, 2, 3]), (6, [0, 1, 3, 2])] {
            let p = write(&dir, &quad, &idx, r#""nodes": [{"mesh": 0}]"#);
            let text = std::fs::read_to_string(&p).unwrap().replace(
                r#""indices": 1"#,
                &format!(r#""indices": 1, "mode": {mode}"#),
            );
            std::fs::write(&p, text).unwrap();
            let s = Scene::load(&p).unwrap();
            assert_eq!(s.meshes[0].indices.len(), 2);
            // Both triangles keep the same facing (+Z).
            for n in &s.meshes[0].normals {
                assert!((*n - Vec3::Z).length() < 1e-6, "mode {mode}: {n}");
            }
        }
    }

    /// Loads every asset of the shared set, when it is present, and checks known counts.
    #[test]
    fn shared_assets_load_with_sane_counts() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/assets");
        if !root.is_dir() {
            println!("shared assets not found at {}; skipped", root.display());
            return;
        }
        let mut files = Vec::new();
        let mut dirs = vec![root];
        while let Some(d) = dirs.pop() {
            for e in std::fs::read_dir(&d).unwrap().flatten() {
                let p = e.path();
                if p.is_dir() {
                    dirs.push(p);
                } else if matches!(
                    p.extension().and_then(|e| e.to_str()),
                    Some("glb" | "gltf" | "obj")
                ) {
                    files.push(p);
                }
            }
        }
        files.sort();
        assert!(!files.is_empty());
        let expect: &[(&str, usize)] = &[
            ("Box.glb", 12),
            ("BoxTextured.glb", 12),
            ("Duck.glb", 4212),
            ("DamagedHelmet.glb", 15452),
            ("ToyCar.gltf", 108936),
            ("CornellBox-Original.obj", 36),
            ("TransmissionTest.glb", 128775),
            ("AttenuationTest.glb", 292),
            ("GlassVaseFlowers.glb", 14036),
            ("Cameras.gltf", 2),
            ("LightsPunctualLamp.gltf", 6000),
            ("spot.obj", 5856),
        ];
        for f in &files {
            let name = f.file_name().unwrap().to_str().unwrap();
            let s = match Scene::load(f) {
                Ok(s) => s,
                // Files that need an extension glint does not read yet are refused by design.
                Err(e) if e.to_string().contains("requires unsupported extension") => {
                    println!("{name}: refused: {e}");
                    continue;
                }
                Err(e) => panic!("{e}"),
            };
            println!(
                "{name}: {:?} meshes={} instances={} warnings={:?}",
                s.stats,
                s.meshes.len(),
                s.instances.len(),
                s.warnings
            );
            assert!(s.stats.triangles > 0, "{name}");
            assert_eq!(s.stats.triangles, s.triangle_count());
            for m in &s.meshes {
                assert!(m.positions.iter().all(|p| p.is_finite()), "{name}");
                assert!(m.normals.iter().all(|n| n.is_finite()), "{name}");
            }
            if let Some((_, n)) = expect.iter().find(|(f, _)| *f == name) {
                assert_eq!(s.stats.triangles, *n, "{name}");
            }
            match name {
                "stanford-bunny.obj" => {
                    assert!(s.stats.triangles <= 69451 && s.stats.triangles > 69000)
                }
                "CornellBox-Original.obj" => {
                    assert!(s.materials.iter().any(|m| m.is_emissive()));
                }
                "DamagedHelmet.glb" => {
                    let m = &s.materials[0];
                    assert!(m.base_color_tex.is_some() && m.normal_tex.is_some());
                    assert!(m.emissive_tex.is_some() && m.metallic_roughness_tex.is_some());
                }
                "ToyCar.gltf" => assert_eq!(s.cameras.len(), 8),
                "Cameras.gltf" => assert_eq!(s.cameras.len(), 2),
                "LightsPunctualLamp.gltf" => assert_eq!(s.lights.len(), 5),
                "MetalRoughSpheresNoTextures.glb" => {
                    // 1,040,409 in the file; each of the 98 sphere instances has 2 zero-area triangles.
                    assert_eq!(s.stats.triangles, 1040409 - 98 * 2);
                    assert_eq!(s.stats.materials, 98);
                }
                _ => {}
            }
        }
    }
}
