//! Resource limits a user can trust: images over the pixel cap, accessors beyond what their buffers
//! hold, a mesh instanced a billion times, CSG and JSON nested ten thousand deep. Each is refused (an
//! image: left out with a warning) with a message naming the file and the element, quickly and
//! without the allocation (or the recursion) it asks for.

use std::io::Cursor;
use std::time::Instant;

use glint::Scene;

/// What a bufferless accessor needs to pass validation: one sparse element (from the positions).
const SPARSE: &str = r#","sparse":{"count":1,"indices":{"bufferView":0,"componentType":5125},"values":{"bufferView":0}}"#;

/// A one-triangle glTF whose node also carries `node_extra` (JSON members) and whose document adds
/// `extra` (members: more accessors after accessor 0, images, extensions).
fn gltf(node_extra: &str, accessors_extra: &str, extra: &str) -> String {
    // Three float VEC3 positions in a 36-byte data-URI buffer.
    let mut bin = Vec::new();
    for v in [[0f32, 0., 0.], [1., 0., 0.], [0., 1., 0.]] {
        for c in v {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    let b64 = base64(&bin);
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],
        "nodes":[{{"mesh":0{node_extra}}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
        "buffers":[{{"byteLength":36,"uri":"data:application/octet-stream;base64,{b64}"}}],
        "bufferViews":[{{"buffer":0,"byteLength":36}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}}{accessors_extra}]{extra}}}"#
    )
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Loads `text` as `name` in a fresh folder, expecting a refusal; returns its message and checks that
/// it came quickly (no allocation of the size asked for was attempted).
fn refused(name: &str, text: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    let t = Instant::now();
    let e = Scene::load(&path).expect_err("must be refused").to_string();
    assert!(t.elapsed().as_secs_f64() < 5.0, "took {:?}", t.elapsed());
    assert!(e.contains(name), "{e}");
    e
}

#[test]
fn the_one_triangle_file_loads() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ok.gltf");
    std::fs::write(&path, gltf("", "", "")).unwrap();
    assert_eq!(Scene::load(&path).unwrap().triangle_count(), 1);
}

#[test]
fn an_accessor_beyond_its_buffer_is_refused_naming_it() {
    let text = gltf("", "", "").replace(r#""count":3,"#, r#""count":1000000000,"#);
    let e = refused("long.gltf", &text);
    assert!(e.contains("accessor 0"), "{e}");
}

#[test]
fn a_mesh_instanced_a_billion_times_is_refused_naming_the_node_and_accessor() {
    let inst = r#","extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":1}}}"#;
    let extensions = r#","extensionsUsed":["EXT_mesh_gpu_instancing"]"#;
    // A billion: over the count a bufferless (all-zero) accessor may have.
    let billion = &format!(r#",{{"componentType":5126,"count":1000000000,"type":"VEC3"{SPARSE}}}"#);
    let e = refused("billion.gltf", &gltf(inst, billion, extensions));
    assert!(e.contains("node 0") && e.contains("accessor 1"), "{e}");
    // 67 million: allowed for a bufferless accessor, but far more than the file's data can stand for.
    let many = &format!(r#",{{"componentType":5126,"count":67108864,"type":"VEC3"{SPARSE}}}"#);
    let e = refused("many.gltf", &gltf(inst, many, extensions));
    assert!(
        e.contains("node 0") && e.contains("accessor 1") && e.contains("exceeds"),
        "{e}"
    );
    // The same asset through a scene file: the error names the scene file's line and the asset.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("many.gltf"), gltf(inst, many, extensions)).unwrap();
    let scene = dir.path().join("forest.toml");
    std::fs::write(&scene, "# a forest\n[[asset]]\npath = \"many.gltf\"\n").unwrap();
    let e = Scene::load(&scene).unwrap_err().to_string();
    assert!(
        e.contains("forest.toml") && e.contains("line 3") && e.contains("many.gltf"),
        "{e}"
    );
}

#[test]
fn one_accessor_read_by_thousands_of_primitives_is_refused() {
    // 40 primitives over one bufferless accessor of a million vertices: each read alone fits, all of
    // them do not come from a file of 36 bytes of data.
    let big = &format!(r#",{{"componentType":5126,"count":1000000,"type":"VEC3"{SPARSE}}}"#);
    let prims = vec![r#"{"attributes":{"POSITION":1}}"#; 40].join(",");
    let text =
        gltf("", big, "").replace(r#"[{"attributes":{"POSITION":0}}]"#, &format!("[{prims}]"));
    let e = refused("reused.gltf", &text);
    assert!(e.contains("accessor 1") && e.contains("exceeds"), "{e}");
}

/// A PNG of 1 x 1 pixels whose header claims `w` x `h` (CRC fixed up).
fn lying_png(w: u32, h: u32) -> Vec<u8> {
    let mut bytes = Vec::new();
    image::RgbaImage::new(1, 1)
        .write_to(&mut Cursor::new(&mut bytes), image::ImageFormat::Png)
        .unwrap();
    bytes[16..20].copy_from_slice(&w.to_be_bytes());
    bytes[20..24].copy_from_slice(&h.to_be_bytes());
    let crc = crc32fast::hash(&bytes[12..29]);
    bytes[29..33].copy_from_slice(&crc.to_be_bytes());
    bytes
}

#[test]
fn a_texture_over_the_pixel_cap_is_left_out_with_a_warning_naming_the_image() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("huge.png"), lying_png(100_000, 100_000)).unwrap();
    let images = r#","images":[{"uri":"huge.png"}],"textures":[{"source":0}],
        "materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}]"#;
    let text = gltf("", "", images).replace(
        r#"{"attributes":{"POSITION":0}}"#,
        r#"{"attributes":{"POSITION":0},"material":0}"#,
    );
    let path = dir.path().join("textured.gltf");
    std::fs::write(&path, text).unwrap();
    let t = Instant::now();
    let scene = Scene::load(&path).unwrap();
    assert!(t.elapsed().as_secs_f64() < 5.0);
    assert!(scene.textures.is_empty());
    let w = scene.warnings.join("\n");
    assert!(
        w.contains("huge.png") && w.contains("100000 x 100000") && w.contains("limit"),
        "{w}"
    );
}

#[test]
fn an_environment_map_over_the_pixel_cap_is_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let hdr = dir.path().join("sky.hdr");
    std::fs::write(
        &hdr,
        b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 200000\n",
    )
    .unwrap();
    let e = glint::scene::EnvMap::load(&hdr).unwrap_err().to_string();
    assert!(
        e.contains("sky.hdr") && e.contains("200000 x 100000"),
        "{e}"
    );
    // An OpenEXR header claiming as much (written small by glint, then its data window enlarged).
    let exr = dir.path().join("sky.exr");
    glint::film::write(&glint::film::Image::new(2, 1), &exr, 0.0).unwrap();
    let mut bytes = std::fs::read(&exr).unwrap();
    let at = find(&bytes, b"dataWindow\0box2i\0").unwrap() + 17 + 4;
    // box2i: min x, min y, max x, max y; a 100000 x 100000 window.
    bytes[at..at + 16].copy_from_slice(&[0i32, 0, 99_999, 99_999].map(i32::to_le_bytes).concat());
    std::fs::write(&exr, bytes).unwrap();
    let t = Instant::now();
    let e = glint::scene::EnvMap::load(&exr).unwrap_err().to_string();
    assert!(t.elapsed().as_secs_f64() < 5.0);
    assert!(
        e.contains("sky.exr") && e.contains("100000 x 100000"),
        "{e}"
    );
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

#[test]
fn csg_nested_ten_thousand_deep_is_refused_without_a_stack_overflow() {
    let nest = |depth: usize| {
        let mut s = String::from("{ sphere = { radius = 1.0 } }");
        for _ in 1..depth {
            s = format!("{{ union = [ {s} ] }}");
        }
        format!("[[object]]\ncsg = {s}\n")
    };
    let e = refused("deep.toml", &nest(10_000));
    assert!(
        e.contains("line 2") && e.contains("nested more than"),
        "{e}"
    );
    let e = refused("deepish.toml", &nest(30));
    assert!(e.contains("CSG tree is 30 levels deep"), "{e}");
    // Within the limit it loads.
    let dir = tempfile::tempdir().unwrap();
    let ok = dir.path().join("ok.toml");
    std::fs::write(&ok, nest(20)).unwrap();
    assert_eq!(Scene::load(&ok).unwrap().csg.len(), 1);
}

#[test]
fn json_nested_ten_thousand_deep_is_refused_without_a_stack_overflow() {
    let deep = format!(
        r#"{{"asset":{{"version":"2.0"}},"extensions":{{"EXT_deep":{}{}}}}}"#,
        "[".repeat(10_000),
        "]".repeat(10_000)
    );
    let e = refused("deep.gltf", &deep);
    assert!(e.contains("JSON"), "{e}");
}
