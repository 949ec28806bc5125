//! KTX2 textures in glTF files: KHR_texture_basisu sources preferred over the fallback, KTX2 images
//! named without the extension (the shared AnisotropyBarnLamp), and a corrupt KTX2 image that is one
//! warning naming it while the model still loads.

mod common;

use std::path::{Path, PathBuf};

use glint::Scene;

fn ktx2_asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/ktx2")
        .join(name)
}

/// A one-quad glTF in `dir` whose base colour texture has a PNG source and, when `ktx2` is given,
/// a KHR_texture_basisu source naming that file (copied beside it).
fn quad_gltf(dir: &Path, ktx2: Option<&str>) -> PathBuf {
    let png = std::fs::read(ktx2_asset("gradient.png")).unwrap();
    std::fs::write(dir.join("fallback.png"), png).unwrap();
    let mut images = vec![serde_json::json!({"uri": "fallback.png"})];
    let mut texture = serde_json::json!({"source": 0});
    if let Some(k) = ktx2 {
        std::fs::copy(ktx2_asset(k), dir.join(k)).unwrap();
        images.push(serde_json::json!({"uri": k, "mimeType": "image/ktx2"}));
        texture["extensions"] = serde_json::json!({"KHR_texture_basisu": {"source": 1}});
    }
    let pos: Vec<u8> = [[0f32, 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]]
        .iter()
        .flatten()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let uv: Vec<u8> = [[0f32, 1.], [1., 1.], [1., 0.], [0., 0.]]
        .iter()
        .flatten()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let idx: Vec<u8> = [0u16, 1, 2, 0, 2, 3]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let blob = [pos.clone(), uv.clone(), idx.clone()].concat();
    use base64_free::encode;
    let doc = serde_json::json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": if ktx2.is_some() { vec!["KHR_texture_basisu"] } else { vec![] },
        "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [texture], "images": images,
        "buffers": [{"byteLength": blob.len(), "uri": format!("data:application/octet-stream;base64,{}", encode(&blob))}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": pos.len()},
            {"buffer": 0, "byteOffset": pos.len(), "byteLength": uv.len()},
            {"buffer": 0, "byteOffset": pos.len() + uv.len(), "byteLength": idx.len()}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    });
    let path = dir.join("quad.gltf");
    std::fs::write(&path, doc.to_string()).unwrap();
    path
}

/// Standard base64 without a dependency (the test writes data URIs).
mod base64_free {
    pub fn encode(b: &[u8]) -> String {
        const T: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut s = String::new();
        for c in b.chunks(3) {
            let n = (c[0] as u32) << 16
                | (*c.get(1).unwrap_or(&0) as u32) << 8
                | *c.get(2).unwrap_or(&0) as u32;
            for k in 0..4 {
                if k <= c.len() {
                    s.push(T[(n >> (18 - 6 * k) & 63) as usize] as char);
                } else {
                    s.push('=');
                }
            }
        }
        s
    }
}

#[test]
fn the_basisu_source_wins_over_the_fallback() {
    let dir = tempfile::tempdir().unwrap();
    for k in ["uastc-zstd.ktx2", "etc1s.ktx2"] {
        let scene = Scene::load(&quad_gltf(dir.path(), Some(k))).unwrap();
        assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
        let tex = &scene.textures[0];
        let want = glint::scene::ktx2::decode(&std::fs::read(ktx2_asset(k)).unwrap()).unwrap();
        assert_eq!((tex.width, tex.height), (want.width, want.height));
        assert_eq!(tex.pixels, want.pixels, "{k}: the KTX2 image, not the PNG");
        assert!(tex.srgb, "a base colour texture is sRGB");
    }
}

#[test]
fn a_corrupt_ktx2_image_is_one_warning_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    for k in ["corrupt-etc1s.ktx2", "truncated.ktx2"] {
        let scene = Scene::load(&quad_gltf(dir.path(), Some(k))).unwrap();
        assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
        let w = &scene.warnings[0];
        assert!(
            w.contains(&format!("image 1 ('{k}')")) && w.contains("KTX2"),
            "{w}"
        );
        assert!(scene.textures.is_empty() && scene.materials[0].base_color_tex.is_none());
    }
}

#[test]
fn the_barn_lamp_loads_its_uastc_textures() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let path = shared.join("gltf/AnisotropyBarnLamp/glTF-KTX2-Basisu/AnisotropyBarnLamp.gltf");
    let scene = Scene::load(&path).unwrap();
    let image_warnings: Vec<_> = scene
        .warnings
        .iter()
        .filter(|w| w.contains("image"))
        .collect();
    assert!(image_warnings.is_empty(), "{image_warnings:?}");
    assert!(scene.textures.len() >= 3, "{}", scene.textures.len());
    assert!(scene
        .textures
        .iter()
        .all(|t| (t.width, t.height) == (2048, 2048)));
    let (s, c) = common::load_for_render(&path, 48, 48);
    let settings = glint::render::RenderSettings {
        width: 48,
        height: 48,
        spp: 4,
        max_depth: 3,
        ..Default::default()
    };
    let img = common::render_with(&s, &c, common::render_backends()[0], &settings);
    assert!(!img.has_non_finite());
}
