//! Compressed glTF variants (meshopt geometry, WebP textures) made from shared models render like
//! their originals in every backend, and corrupt compressed files are clean errors naming the file.

mod common;

use std::path::{Path, PathBuf};

use glint::render::RenderSettings;
use glint::Scene;

fn asset(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets")
        .join(rel)
}

/// Renders `variant` and `original` at the same seed in every backend and checks the relative mean
/// absolute difference; returns the largest one.
fn assert_renders_like(variant: &Path, original: &Path, limit: f64) -> f64 {
    let settings = RenderSettings {
        width: 96,
        height: 72,
        spp: 16,
        max_depth: 4,
        seed: 3,
        ..Default::default()
    };
    let (sa, ca) = common::load_for_render(original, settings.width, settings.height);
    let (sb, cb) = common::load_for_render(variant, settings.width, settings.height);
    let mut worst: f64 = 0.0;
    for b in common::render_backends() {
        let a = common::render_with(&sa, &ca, b, &settings);
        let v = common::render_with(&sb, &cb, b, &settings);
        assert!(!v.has_non_finite(), "{}: {b} left a NaN", variant.display());
        let rel = a.mean_abs_diff(&v) / a.mean_rgb().max(1e-6);
        eprintln!(
            "{} vs original, {b}: relative MAD {rel:.3e}",
            variant.display()
        );
        assert!(
            rel <= limit,
            "{}: {b}: relative MAD {rel} > {limit}",
            variant.display()
        );
        worst = worst.max(rel);
    }
    worst
}

/// (compressed variant under assets/, original under the shared assets)
const VARIANTS: [(&str, &str); 4] = [
    ("meshopt/duck-ext.glb", "gltf/Duck/glTF-Binary/Duck.glb"),
    (
        "meshopt/boxanimated-khr.glb",
        "gltf/BoxAnimated/glTF-Binary/BoxAnimated.glb",
    ),
    (
        "meshopt/meshprimitivemodes-khr.glb",
        "gltf/MeshPrimitiveModes/glTF/MeshPrimitiveModes.gltf",
    ),
    (
        "webp/boxtextured-webp.glb",
        "gltf/BoxTextured/glTF-Binary/BoxTextured.glb",
    ),
];

#[test]
fn compressed_variants_render_like_their_originals() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    for (variant, original) in VARIANTS {
        assert_renders_like(&asset(variant), &shared.join(original), 0.005);
    }
}

/// A variant warns about nothing its original does not (MeshPrimitiveModes skips its lines in both).
#[test]
fn compressed_variants_load_without_new_warnings() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    for (variant, original) in VARIANTS {
        let s = Scene::load(&asset(variant)).unwrap_or_else(|e| panic!("{e}"));
        let o = Scene::load(&shared.join(original)).unwrap();
        assert!(s.triangle_count() > 0, "{variant}: no triangles");
        assert_eq!(s.triangle_count(), o.triangle_count(), "{variant}");
        // gltfpack renumbers meshes: compare what the warnings say, not where.
        let what = |w: &String| w.rsplit(": ").next().unwrap_or(w).to_owned();
        let known: Vec<String> = o.warnings.iter().map(what).collect();
        for w in &s.warnings {
            assert!(known.contains(&what(w)), "{variant}: new warning {w}");
        }
    }
    let s = Scene::load(&asset("webp/boxtextured-webp.glb")).unwrap();
    assert_eq!(s.textures.len(), 1, "the WebP texture was not decoded");
}

/// A GLB split into its JSON (parsed) and BIN chunk.
fn glb_parts(path: &Path) -> (serde_json::Value, Vec<u8>) {
    let b = std::fs::read(path).unwrap();
    let u32_at = |o: usize| u32::from_le_bytes(b[o..o + 4].try_into().unwrap()) as usize;
    let jl = u32_at(12);
    let json = serde_json::from_slice(&b[20..20 + jl]).unwrap();
    let bo = 20 + jl;
    let bl = u32_at(bo);
    (json, b[bo + 8..bo + 8 + bl].to_vec())
}

fn glb(json: &serde_json::Value, bin: &[u8]) -> Vec<u8> {
    let mut j = serde_json::to_vec(json).unwrap();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut bin = bin.to_vec();
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + bin.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// Loads a GLB written to a temporary file; the error text, which must name the file.
fn load_err(name: &str, bytes: &[u8]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join(name);
    std::fs::write(&p, bytes).unwrap();
    let Err(e) = Scene::load(&p) else {
        panic!("a corrupt file loaded");
    };
    let e = e.to_string();
    assert!(e.contains(name), "error does not name the file: {e}");
    e
}

#[test]
fn corrupt_meshopt_files_are_errors_naming_the_buffer_view() {
    let (json, bin) = glb_parts(&asset("meshopt/duck-ext.glb"));
    let ext = "/extensions/EXT_meshopt_compression";
    let edit = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut j = json.clone();
        f(&mut j);
        j
    };
    let cases: Vec<(serde_json::Value, Vec<u8>, &str)> = vec![
        (
            edit(&|j| {
                *j.pointer_mut(&format!("/bufferViews/1{ext}/byteLength"))
                    .unwrap() = 1_000_000_000u64.into()
            }),
            bin.clone(),
            "buffer view 1: meshopt data",
        ),
        (
            edit(&|j| {
                *j.pointer_mut(&format!("/bufferViews/2{ext}/count"))
                    .unwrap() = 4_000_000_000u64.into()
            }),
            bin.clone(),
            "buffer view 2: meshopt",
        ),
        (
            edit(&|j| {
                *j.pointer_mut(&format!("/bufferViews/4{ext}/mode")).unwrap() = "STRIPS".into()
            }),
            bin.clone(),
            "buffer view 4: invalid meshopt compression object",
        ),
        (
            edit(&|j| {
                *j.pointer_mut(&format!("/bufferViews/3{ext}/byteStride"))
                    .unwrap() = 6.into()
            }),
            bin.clone(),
            "buffer view 3: meshopt: byteStride 6",
        ),
        (
            json.clone(),
            vec![0xFF; bin.len()],
            "buffer view 1: meshopt: corrupt",
        ),
    ];
    for (j, b, want) in cases {
        let e = load_err("corrupt-meshopt.glb", &glb(&j, &b));
        assert!(e.contains(want), "{e} (wanted {want})");
    }
}

/// The `gltf` crate unwraps the MIME type of an image in a buffer view: the file gets a warning,
/// the texture is left out, and nothing panics.
#[test]
fn embedded_image_without_mime_type_is_a_warning() {
    let (mut json, bin) = glb_parts(&asset("webp/boxtextured-webp.glb"));
    json["images"][0]
        .as_object_mut()
        .unwrap()
        .remove("mimeType");
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("no-mime.glb");
    std::fs::write(&p, glb(&json, &bin)).unwrap();
    let s = Scene::load(&p).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.textures.is_empty());
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    assert!(s.warnings[0].contains("image 0") && s.warnings[0].contains("mimeType"));
}
