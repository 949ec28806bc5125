//! Tests of the Draco primitive decoder on the committed Box (assets/draco): it decodes to the
//! original's geometry, and handmade corruptions are errors naming the primitive, never panics.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::scene::Scene;

fn box_files() -> (Value, Vec<u8>) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/draco");
    let json = serde_json::from_slice(&std::fs::read(dir.join("Box.gltf")).unwrap()).unwrap();
    (json, std::fs::read(dir.join("Box.bin")).unwrap())
}

/// Writes the document (its buffer renamed to `Box.bin`) and buffer to a temp dir.
fn write(dir: &tempfile::TempDir, json: &Value, bin: &[u8]) -> PathBuf {
    std::fs::write(dir.path().join("Box.bin"), bin).unwrap();
    let p = dir.path().join("draco-box.gltf");
    std::fs::write(&p, serde_json::to_vec(json).unwrap()).unwrap();
    p
}

/// Runs the decoder itself on the document (no panic catching in between): Ok, or the error text.
fn decode(json: &Value, bin: &[u8]) -> Result<gltf::Document, String> {
    let root: gltf::json::Root = serde_json::from_value(json.clone()).unwrap();
    let doc = gltf::Document::from_json_without_validation(root);
    let mut buffers = vec![bin.to_vec()];
    super::decode_primitives(doc, &mut buffers, &mut Vec::new()).map_err(|e| e.to_string())
}

#[test]
fn the_box_decodes_to_twelve_triangles_on_the_unit_cube() {
    let (json, bin) = box_files();
    let dir = tempfile::tempdir().unwrap();
    let scene = Scene::load(&write(&dir, &json, &bin)).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    assert_eq!(scene.triangle_count(), 12);
    let mesh = &scene.meshes[0];
    assert_eq!(mesh.positions.len(), 24);
    // Quantized to 11 bits by the encoder: within 1e-3 of the cube's corners at +-0.5.
    for p in &mesh.positions {
        for c in p.to_array() {
            assert!((c.abs() - 0.5).abs() < 1e-3, "{p}");
        }
    }
    assert_eq!(mesh.normals.len(), 24, "decoded normals");
    assert!(mesh.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-2));
}

#[test]
fn truncated_and_bit_flipped_streams_are_errors_or_bounded_meshes() {
    let (json, bin) = box_files();
    let len = json["bufferViews"][0]["byteLength"].as_u64().unwrap() as usize;
    let mut refused = 0;
    for cut in 0..len {
        let mut j = json.clone();
        j["bufferViews"][0]["byteLength"] = cut.into();
        let Err(e) = decode(&j, &bin) else {
            panic!("a stream cut to {cut} bytes decoded");
        };
        assert!(
            e.contains("mesh 0 ('Mesh') primitive 0: KHR_draco_mesh_compression"),
            "{e}"
        );
        refused += 1;
    }
    assert_eq!(refused, len);
    // Every single-bit flip: an error, or a mesh that still fits the accessors' counts (Draco has
    // no checksum; a flipped quantized value is a valid, different mesh).
    let mut errors = 0;
    for bit in 0..len * 8 {
        let mut b = bin.clone();
        b[bit / 8] ^= 1 << (bit % 8);
        if decode(&json, &b).is_err() {
            errors += 1;
        }
    }
    assert!(errors > 0, "no bit flip was detected");
    // Through the loader, a corrupt stream names the file, mesh and primitive.
    let dir = tempfile::tempdir().unwrap();
    let mut j = json.clone();
    j["bufferViews"][0]["byteLength"] = 40.into();
    let e = Scene::load(&write(&dir, &j, &bin)).unwrap_err().to_string();
    assert!(e.contains("draco-box.gltf"), "{e}");
    assert!(e.contains("mesh 0 ('Mesh') primitive 0"), "{e}");
}

#[test]
fn wrong_attribute_ids_and_lying_counts_are_errors() {
    let (json, bin) = box_files();
    let ext = "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression";
    let edit = |path: &str, v: Value| {
        let mut j = json.clone();
        *j.pointer_mut(path).unwrap() = v;
        j
    };
    let cases = [
        (
            edit(&format!("{ext}/attributes/POSITION"), 9.into()),
            "POSITION: the Draco stream has no attribute with id 9",
        ),
        (
            edit("/accessors/2/count", 23.into()),
            "the accessor has 23 elements but the Draco stream 24",
        ),
        (
            edit("/accessors/0/count", 33.into()),
            "corrupt Draco stream",
        ),
        (
            edit(&format!("{ext}/bufferView"), 5.into()),
            "buffer view 5 does not exist",
        ),
        (
            edit("/bufferViews/0/byteOffset", 100.into()),
            "out of bounds of buffer 0's 120 bytes",
        ),
        (
            edit(
                &format!("{ext}/attributes"),
                serde_json::json!({"TEXCOORD_0": 0}),
            ),
            "maps attribute TEXCOORD_0, which the primitive does not have",
        ),
        (
            edit(&format!("{ext}/attributes"), serde_json::json!([1, 2])),
            "invalid extension object",
        ),
        (
            edit("/accessors/2/componentType", 5121.into()),
            "do not fit the accessor's component type",
        ),
        (
            edit("/accessors/2/count", 4_000_000_000u64.into()),
            "more than the",
        ),
    ];
    for (j, want) in cases {
        let e = decode(&j, &bin)
            .err()
            .unwrap_or_else(|| panic!("{want}: decoded"));
        assert!(e.contains(want), "{e} (wanted {want})");
        assert!(e.contains("mesh 0 ('Mesh') primitive 0"), "{e}");
    }
}

#[test]
fn morph_targets_outside_an_edgebreaker_stream_are_a_warning() {
    // The Box is edgebreaker-coded; give it a morph target of 24 zero displacements.
    let (mut json, bin) = box_files();
    let zeros = format!("data:application/octet-stream;base64,{}", "A".repeat(384));
    json["buffers"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!({"byteLength": 288, "uri": zeros}));
    json["bufferViews"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!({"buffer": 1, "byteLength": 288}));
    json["accessors"].as_array_mut().unwrap().push(
        serde_json::json!({"bufferView": 1, "componentType": 5126, "count": 24, "type": "VEC3"}),
    );
    json["meshes"][0]["primitives"][0]["targets"] = serde_json::json!([{"POSITION": 3}]);
    let dir = tempfile::tempdir().unwrap();
    let scene = Scene::load(&write(&dir, &json, &bin)).unwrap();
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("edgebreaker") && w.contains("mesh 0")),
        "{:?}",
        scene.warnings
    );
}
