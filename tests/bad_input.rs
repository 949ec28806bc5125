//! Malformed and hostile input: every case is an error naming the file and the problem, or a load
//! with a warning; never a panic.

use std::path::{Path, PathBuf};

use glint::Scene;

/// A binary glTF with one triangle (positions + u16 indices) in its BIN chunk.
fn glb_bytes(extra_json: &str, positions: &[[f32; 3]]) -> Vec<u8> {
    let mut bin: Vec<u8> = positions
        .iter()
        .flatten()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let pos_len = bin.len();
    for i in [0u16, 1, 2] {
        bin.extend(i.to_le_bytes());
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let mut json = format!(
        r#"{{"asset": {{"version": "2.0"}},
  "buffers": [{{"byteLength": {bl}}}],
  "bufferViews": [{{"buffer": 0, "byteLength": {pos_len}}},
                  {{"buffer": 0, "byteOffset": {pos_len}, "byteLength": 6}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": {n}, "type": "VEC3",
                  "min": [0, 0, 0], "max": [1, 1, 1]}},
                {{"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}}],
  "meshes": [{{"name": "tri", "primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0 {extra_json}}}"#,
        bl = bin.len(),
        n = positions.len()
    )
    .into_bytes();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::new();
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(&bin);
    out
}

const TRI: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    p
}

/// The error of loading `p`, checked to name the file and to contain every word of `words`.
fn load_err(p: &Path, words: &[&str]) -> String {
    let e = match Scene::load(p) {
        Ok(_) => panic!("{} loaded but should not have", p.display()),
        Err(e) => e.to_string(),
    };
    println!("{e}");
    let name = p.file_name().unwrap().to_str().unwrap();
    assert!(e.contains(name), "error does not name the file: {e}");
    for w in words {
        assert!(e.contains(w), "error lacks '{w}': {e}");
    }
    e
}

#[test]
fn well_formed_glb_loads() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "ok.glb", &glb_bytes("", &TRI));
    let s = Scene::load(&p).unwrap();
    assert_eq!(s.stats.triangles, 1);
}

#[test]
fn missing_file() {
    let dir = tempfile::tempdir().unwrap();
    load_err(&dir.path().join("nothing-here.glb"), &["no such file"]);
    load_err(&dir.path().join("nothing-here.obj"), &["no such file"]);
}

#[test]
fn truncated_glb() {
    let dir = tempfile::tempdir().unwrap();
    let full = glb_bytes("", &TRI);
    for cut in [5, 12, 19, 40, full.len() / 2, full.len() - 4] {
        let p = write(dir.path(), "cut.glb", &full[..cut]);
        load_err(&p, &["truncated"]);
    }
}

#[test]
fn glb_with_garbage_body() {
    let dir = tempfile::tempdir().unwrap();
    let mut bytes = glb_bytes("", &TRI);
    bytes[16..20].copy_from_slice(b"XXXX"); // the JSON chunk's type
    let p = write(dir.path(), "garbage.glb", &bytes);
    load_err(&p, &["JSON"]);
}

#[test]
fn accessor_longer_than_its_buffer() {
    let dir = tempfile::tempdir().unwrap();
    // JSON .gltf with a data URI holding 36 bytes of positions, but an accessor of 1000 vertices.
    let json = r#"{"asset": {"version": "2.0"},
      "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 1000, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 1]}],
      "meshes": [{"name": "broken", "primitives": [{"attributes": {"POSITION": 0}}]}],
      "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]}"#;
    let p = write(dir.path(), "short.gltf", json.as_bytes());
    load_err(&p, &["mesh 0 ('broken'), primitive 0", "out of bounds"]);

    // A count far beyond anything in memory: an error, not an allocation failure.
    let huge = json.replace(r#""count": 1000"#, r#""count": 3000000000"#);
    let p = write(dir.path(), "huge.gltf", huge.as_bytes());
    load_err(&p, &["mesh 0 ('broken'), primitive 0"]);

    // A buffer view past the end of its buffer.
    let json = json
        .replace(r#""count": 1000"#, r#""count": 3"#)
        .replace(r#""byteLength": 36}],"#, r#""byteLength": 3600}],"#);
    let p = write(dir.path(), "view.gltf", json.as_bytes());
    load_err(&p, &["out of bounds"]);
}

#[test]
fn missing_external_buffer() {
    let dir = tempfile::tempdir().unwrap();
    let json = r#"{"asset": {"version": "2.0"},
      "buffers": [{"byteLength": 36, "uri": "gone.bin"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 1]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]}"#;
    let p = write(dir.path(), "ext.gltf", json.as_bytes());
    load_err(&p, &["gone.bin", "cannot read"]);
}

#[test]
fn index_out_of_range() {
    let dir = tempfile::tempdir().unwrap();
    let mut bytes = glb_bytes("", &TRI);
    // The indices are the last 6 bytes before the 2 padding bytes: make the third one 9.
    let n = bytes.len();
    bytes[n - 4..n - 2].copy_from_slice(&9u16.to_le_bytes());
    let p = write(dir.path(), "idx.glb", &bytes);
    load_err(&p, &["mesh 0 ('tri'), primitive 0", "out of range"]);
}

#[test]
fn json_index_to_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        dir.path(),
        "dangling.glb",
        &glb_bytes(r#", "materials": [], "textures": [{"source": 7}]"#, &TRI),
    );
    load_err(&p, &["invalid glTF"]);
}

#[test]
fn nan_vertex_is_dropped_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let pos = [[0.0, 0.0, 0.0], [f32::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let p = write(dir.path(), "nan.glb", &glb_bytes("", &pos));
    let s = Scene::load(&p).unwrap();
    assert_eq!(s.stats.triangles, 0);
    assert!(s
        .meshes
        .iter()
        .all(|m| m.positions.iter().all(|p| p.is_finite())));
    assert!(
        s.warnings
            .iter()
            .any(|w| w.contains("dropped 1 degenerate triangles")),
        "{:?}",
        s.warnings
    );
}

#[test]
fn unsupported_required_extension() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        dir.path(),
        "ibl.glb",
        &glb_bytes(
            r#", "extensionsUsed": ["EXT_lights_image_based"],
                 "extensionsRequired": ["EXT_lights_image_based"]"#,
            &TRI,
        ),
    );
    load_err(
        &p,
        &["requires unsupported extension EXT_lights_image_based"],
    );
}

#[test]
fn malformed_json() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        dir.path(),
        "bad.gltf",
        br#"{"asset": {"version": "2.0"}, "nodes": [ "#,
    );
    load_err(&p, &["invalid JSON"]);
    let p = write(dir.path(), "empty.gltf", b"");
    load_err(&p, &["invalid JSON"]);
    let p = write(
        dir.path(),
        "wrongtype.gltf",
        br#"{"asset": {"version": "2.0"}, "nodes": 3}"#,
    );
    load_err(&p, &["invalid JSON"]);
}

#[test]
fn malformed_obj() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        dir.path(),
        "faces.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
    );
    load_err(&p, &["malformed OBJ", "index"]);
    let p = write(
        dir.path(),
        "zero.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
    );
    load_err(&p, &["malformed OBJ"]);
    let p = write(
        dir.path(),
        "rel.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -9/-9 -1/-9 -2/-9\n",
    );
    load_err(&p, &["malformed OBJ"]);
    let p = write(dir.path(), "text.obj", b"v 0 zero 0\n");
    load_err(&p, &["malformed OBJ"]);
}

#[test]
fn obj_with_missing_mtl_and_nan_vertex_loads_with_warnings() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        dir.path(),
        "warn.obj",
        b"mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nusemtl x\nf 1 2 3\nf 1 2 4\n",
    );
    let s = Scene::load(&p).unwrap();
    assert_eq!(s.stats.triangles, 1);
    assert!(
        s.warnings.iter().any(|w| w.contains("missing.mtl")),
        "{:?}",
        s.warnings
    );
    assert!(
        s.warnings
            .iter()
            .any(|w| w.contains("dropped 1 degenerate")),
        "{:?}",
        s.warnings
    );
    assert!(s
        .meshes
        .iter()
        .all(|m| m.positions.iter().all(|p| p.is_finite())));
}

#[test]
fn unknown_extension() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "model.ply", b"ply\n");
    load_err(&p, &["unsupported file type"]);
}

#[test]
fn scene_file_errors_name_file_and_line() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "t.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let cases: [(&str, &[&str]); 6] = [
        (
            "[[asset]]\npath = \"missing.glb\"\n",
            &["line 2", "missing.glb", "no such file"],
        ),
        (
            "[[asset]]\npath = \"t.obj\"\ncolour = 1\n",
            &["line 3", "colour"],
        ),
        ("[render]\nspp = -4\n", &["line 2", "spp"]),
        ("[[light]]\ntype = \"laser\"\n", &["line 2", "laser"]),
        (
            "[[asset]]\npath = \"t.obj\"\ntransform = { scale = 0 }\n",
            &["line 2", "singular"],
        ),
        (
            "[[material]]\nname = \"m\"\nroughness = 2\n",
            &["line 1", "roughness"],
        ),
    ];
    for (i, (text, words)) in cases.iter().enumerate() {
        let p = write(dir.path(), &format!("s{i}.toml"), text.as_bytes());
        load_err(&p, words);
    }
}
