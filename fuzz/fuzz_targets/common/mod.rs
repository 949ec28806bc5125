//! The fuzzed paths, one function per target, shared by the fuzz targets and by the test that
//! replays `fuzz/regressions/` (tests/fuzz_regressions.rs includes this file): bytes to a loaded
//! Scene, checked, and when small built (the Rust BVH) and rendered at 4x4 pixels.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::Vec3;
use glint::accel::Backend;
use glint::render::job::{Basics, JobOptions, Overrides, RenderJob};
use glint::scene::gltf::meshopt::{decode, Filter, Mode};
use glint::scene::{EnvMap, Light, TexRef, Texture, TextureFilter, Wrap};
use glint::Scene;

/// Scenes up to this many triangles (and CSG objects) are built and rendered; bigger ones only
/// loaded, so that one input never costs seconds.
const RENDER_TRIANGLES: usize = 20_000;

/// A fuzzed path: bytes in, no panic out.
pub type Target = fn(&[u8]);

/// Every target by name (its folder under fuzz/regressions and fuzz/corpus).
pub const TARGETS: &[(&str, Target)] = &[
    ("gltf_load", gltf),
    ("glb_load", glb),
    ("obj_load", obj),
    ("scene_toml", scene_toml),
    ("envmap_load", envmap),
    ("texture_decode", texture),
    ("meshopt_decode", meshopt),
    ("draco_decode", draco),
];

/// A path in a folder that holds nothing, to name in-memory inputs: relative references resolve
/// beside it and find no file.
fn nowhere(name: &str) -> PathBuf {
    std::env::temp_dir().join("glint-fuzz-nowhere").join(name)
}

/// The repository's assets folder, which scene-file inputs place their assets from (this file is
/// compiled both from the repository root and from fuzz/).
fn assets() -> PathBuf {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    if here.join("assets").is_dir() {
        here.join("assets")
    } else {
        here.join("../assets")
    }
}

/// A .gltf (JSON, with data-URI buffers and images).
pub fn gltf(data: &[u8]) {
    if let Ok(scene) =
        glint::scene::gltf::load_bytes(&nowhere("input.gltf"), data, &Default::default())
    {
        exercise(scene);
    }
}

/// A .glb (header, JSON and BIN chunks, embedded images, meshopt views).
pub fn glb(data: &[u8]) {
    if let Ok(scene) =
        glint::scene::gltf::load_bytes(&nowhere("input.glb"), data, &Default::default())
    {
        exercise(scene);
    }
}

/// Where the MTL part of an OBJ input starts.
const MTL_SPLIT: &[u8] = b"\n#MTL\n";

/// An OBJ, then (after a line `#MTL`) the text of `m.mtl`, which the OBJ reaches with
/// `mtllib m.mtl`; any other file it names does not exist.
pub fn obj(data: &[u8]) {
    let (obj, mtl) = match data.windows(MTL_SPLIT.len()).position(|w| w == MTL_SPLIT) {
        Some(i) => (&data[..i], &data[i + MTL_SPLIT.len()..]),
        None => (data, &[][..]),
    };
    let mtl_path = nowhere("m.mtl");
    let files = |p: &Path| {
        if p == mtl_path {
            Ok(mtl.to_vec())
        } else {
            Err(std::io::Error::from(std::io::ErrorKind::NotFound))
        }
    };
    if let Ok(scene) = glint::scene::obj::load_bytes(&nowhere("input.obj"), obj, &files) {
        exercise(scene);
    }
}

/// A scene file, read as if it were assets/scenes/input.toml: `path = "../demo/demo.glb"` loads a model.
pub fn scene_toml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(scene) = glint::scene::desc::load_str(&assets().join("scenes/input.toml"), text) {
        exercise(scene);
    }
}

/// An environment map, OpenEXR when the first byte is 0x76 (the magic's), Radiance HDR otherwise;
/// then a 4x4 render lit by it.
pub fn envmap(data: &[u8]) {
    let name = if data.first() == Some(&0x76) {
        "sky.exr"
    } else {
        "sky.hdr"
    };
    let Ok(map) = EnvMap::from_bytes(&nowhere(name), data) else {
        return;
    };
    let _ = map.lookup(Vec3::Y);
    let mut scene = quad_scene();
    scene.lights.push(Light::Environment {
        radiance: Vec3::ONE,
        map: Some(Arc::new(map)),
    });
    exercise(scene);
}

/// A texture image (PNG, JPEG, WebP, GIF, guessed from the bytes as glTF and OBJ images are)
/// through glint's capped decoder onto a quad, then a render that samples it.
pub fn texture(data: &[u8]) {
    let Ok(img) = glint::scene::decode::decode_rgba8(data) else {
        return;
    };
    assert_eq!(img.pixels.len(), img.width * img.height);
    let mut scene = quad_scene();
    scene.textures.push(Texture {
        name: "fuzzed".into(),
        width: img.width,
        height: img.height,
        pixels: img.pixels,
        srgb: true,
        wrap_s: Wrap::Repeat,
        wrap_t: Wrap::MirroredRepeat,
        // Both filters, by the input's length (its bytes are the image's).
        filter: if data.len().is_multiple_of(2) {
            TextureFilter::Nearest
        } else {
            TextureFilter::Linear
        },
    });
    scene.materials[0].base_color_tex = Some(TexRef::new(0));
    exercise(scene);
}

/// The meshopt decoder directly: the first 5 bytes choose mode, filter, stride and count, the rest
/// is the compressed stream.
pub fn meshopt(data: &[u8]) {
    if data.len() < 4 {
        return;
    }
    let mode = [Mode::Attributes, Mode::Triangles, Mode::Indices][data[0] as usize % 3];
    let filter = [
        Filter::None,
        Filter::Octahedral,
        Filter::Quaternion,
        Filter::Exponential,
        Filter::Color,
    ][data[1] as usize % 5];
    let stride = data[2] as usize + 1;
    let count = u16::from_le_bytes([data[3], data.get(4).copied().unwrap_or(0)]) as usize;
    if let Ok(out) = decode(&data[5.min(data.len())..], count, stride, mode, filter) {
        assert_eq!(out.len(), count * stride);
    }
}

/// The attribute layouts (semantic, glTF component type, type) by Draco id of the shared
/// glTF-Draco files: Box; Duck; CesiumMan; RiggedSimple; MorphPrimitivesTest's second primitive.
const DRACO_LAYOUTS: [&[(&str, u32, &str)]; 5] = [
    &[("NORMAL", 5126, "VEC3"), ("POSITION", 5126, "VEC3")],
    &[
        ("NORMAL", 5126, "VEC3"),
        ("POSITION", 5126, "VEC3"),
        ("TEXCOORD_0", 5126, "VEC2"),
    ],
    &[
        ("JOINTS_0", 5123, "VEC4"),
        ("NORMAL", 5126, "VEC3"),
        ("POSITION", 5126, "VEC3"),
        ("TEXCOORD_0", 5126, "VEC2"),
        ("WEIGHTS_0", 5126, "VEC4"),
    ],
    &[
        ("JOINTS_0", 5123, "VEC4"),
        ("NORMAL", 5126, "VEC3"),
        ("POSITION", 5126, "VEC3"),
        ("WEIGHTS_0", 5126, "VEC4"),
    ],
    &[
        ("POSITION", 5126, "VEC3"),
        ("NORMAL", 5126, "VEC3"),
        ("TEXCOORD_0", 5126, "VEC2"),
    ],
];

/// A KHR_draco_mesh_compression stream through the glTF loader: the first 5 bytes give the vertex
/// count (u16), the triangle count (u16) and the attribute layout its fallback accessors declare;
/// the rest is the Draco stream, the BIN chunk of a one-primitive .glb.
pub fn draco(data: &[u8]) {
    if let Some(file) = draco_glb(data) {
        glb(&file);
    }
}

/// The .glb that `draco` loads: a point count (u16), a face count (u16), an attribute layout (u8),
/// then the Draco stream; None when the input is shorter than its header.
pub fn draco_glb(data: &[u8]) -> Option<Vec<u8>> {
    if data.len() < 5 {
        return None;
    }
    let points = u16::from_le_bytes([data[0], data[1]]);
    let faces = u16::from_le_bytes([data[2], data[3]]) as u32;
    let layout = DRACO_LAYOUTS[data[4] as usize % DRACO_LAYOUTS.len()];
    let stream = &data[5..];
    let mut accessors = vec![format!(
        r#"{{"componentType": 5125, "count": {}, "type": "SCALAR"}}"#,
        faces * 3
    )];
    let (mut attributes, mut ids) = (Vec::new(), Vec::new());
    for (id, (name, ty, kind)) in layout.iter().enumerate() {
        accessors.push(format!(
            r#"{{"componentType": {ty}, "count": {points}, "type": "{kind}"}}"#
        ));
        attributes.push(format!(r#""{name}": {}"#, id + 1));
        ids.push(format!(r#""{name}": {id}"#));
    }
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}},
  "extensionsUsed": ["KHR_draco_mesh_compression"],
  "extensionsRequired": ["KHR_draco_mesh_compression"],
  "buffers": [{{"byteLength": {len}}}],
  "bufferViews": [{{"buffer": 0, "byteLength": {len}}}],
  "accessors": [{accessors}],
  "meshes": [{{"primitives": [{{"attributes": {{{attributes}}}, "indices": 0,
    "extensions": {{"KHR_draco_mesh_compression": {{"bufferView": 0, "attributes": {{{ids}}}}}}}}}]}}],
  "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#,
        len = stream.len(),
        accessors = accessors.join(", "),
        attributes = attributes.join(", "),
        ids = ids.join(", "),
    );
    Some(glb_bytes(json.as_bytes(), stream))
}

/// A .glb of a JSON chunk and a BIN chunk (each padded to 4 bytes).
pub fn glb_bytes(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |b: &[u8], with: u8| {
        let mut v = b.to_vec();
        v.resize(b.len().div_ceil(4) * 4, with);
        v
    };
    let (j, b) = (pad(json, b' '), pad(bin, 0));
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b);
    out
}

/// A 2x2 grid of quads facing +Z with UVs over [0, 2]^2, for the image targets.
fn quad_scene() -> Scene {
    let mut mesh = glint::scene::generate::quad_grid(2);
    mesh.uvs = mesh
        .positions
        .iter()
        .map(|p| glam::Vec2::new(p.x, p.y))
        .collect();
    glint::scene::generate::single_mesh_scene(mesh)
}

/// Checks a loaded scene and, when it is small, builds it and renders 4x4 pixels at 1 spp.
fn exercise(scene: Scene) {
    scene.validate().expect("a loaded scene is valid");
    let _ = scene.bounds();
    if scene.triangle_count() > RENDER_TRIANGLES || scene.csg.len() > 64 {
        return;
    }
    let defaults = Basics {
        width: 4,
        height: 4,
        spp: 1,
        max_depth: 2,
        backend: Backend::Bvh,
        ..Basics::default()
    };
    let opts = JobOptions {
        defaults,
        // The file's [render] settings may not enlarge the render.
        flags: Overrides::all(defaults),
        ..JobOptions::default()
    };
    // A scene the job refuses (a camera it cannot use) is a clean error, which is fine.
    if let Ok(job) = RenderJob::prepare(scene, &opts) {
        let out = job.render(&indicatif::ProgressBar::hidden());
        assert_eq!(out.image.pixels.len(), 16);
    }
}
