//! The shared glTF-Draco variants (KHR_draco_mesh_compression) load, render without NaN, and render
//! like their uncompressed originals at the same seed (BVH backend; the CLI compares the others).

#![cfg(feature = "draco")]

mod common;

use std::path::Path;

use glint::accel::Backend;
use glint::render::RenderSettings;
use glint::Scene;

fn settings() -> RenderSettings {
    RenderSettings {
        width: 80,
        height: 60,
        spp: 8,
        max_depth: 4,
        seed: 5,
        ..Default::default()
    }
}

/// Relative mean absolute difference between renders of `variant` and `original` (BVH backend).
fn rmad(variant: &Path, original: &Path) -> f64 {
    let s = settings();
    let (sa, ca) = common::load_for_render(original, s.width, s.height);
    let (sb, cb) = common::load_for_render(variant, s.width, s.height);
    let a = common::render_with(&sa, &ca, Backend::Bvh, &s);
    let v = common::render_with(&sb, &cb, Backend::Bvh, &s);
    assert!(
        !v.has_non_finite(),
        "{}: NaN in the render",
        variant.display()
    );
    a.mean_abs_diff(&v) / a.mean_rgb().max(1e-6)
}

/// (Draco variant, original), under the shared gltf folder.
const PAIRS: [(&str, &str); 3] = [
    ("Box/glTF-Draco/Box.gltf", "Box/glTF-Binary/Box.glb"),
    ("Duck/glTF-Draco/Duck.gltf", "Duck/glTF-Binary/Duck.glb"),
    (
        "CesiumMan/glTF-Draco/CesiumMan.gltf",
        "CesiumMan/glTF-Binary/CesiumMan.glb",
    ),
];

#[test]
fn draco_variants_render_like_their_originals() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let gltf = shared.join("gltf");
    for (variant, original) in PAIRS {
        let (v, o) = (gltf.join(variant), gltf.join(original));
        let (sv, so) = (Scene::load(&v).unwrap(), Scene::load(&o).unwrap());
        assert_eq!(sv.triangle_count(), so.triangle_count(), "{variant}");
        let rel = rmad(&v, &o);
        eprintln!("{variant}: relative MAD {rel:.3e}");
        assert!(rel <= 0.005, "{variant}: relative MAD {rel} > 0.005");
    }
}

/// Skinned and morphed Draco files without a shared uncompressed twin: load with their skin or
/// morph targets and render without NaN.
#[test]
fn skinned_and_morphed_draco_files_load_and_render() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    for rel in [
        "RiggedSimple/glTF-Draco/RiggedSimple.gltf",
        "MorphPrimitivesTest/glTF-Draco/MorphPrimitivesTest.gltf",
    ] {
        let p = shared.join("gltf").join(rel);
        let scene = Scene::load(&p).unwrap_or_else(|e| panic!("{e}"));
        assert!(scene.triangle_count() > 0, "{rel}");
        assert!(scene
            .meshes
            .iter()
            .all(|m| m.positions.iter().all(|p| p.is_finite())));
        let s = settings();
        let (sc, cam) = common::load_for_render(&p, s.width, s.height);
        let img = common::render_with(&sc, &cam, Backend::Bvh, &s);
        assert!(!img.has_non_finite(), "{rel}: NaN in the render");
        assert!(img.mean_rgb() > 0.0, "{rel}: black render");
    }
}
