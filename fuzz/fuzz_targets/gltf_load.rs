//! Fuzzes the glTF/GLB reader from bytes to a loaded Scene: any input must give a Scene or an error,
//! never a panic, a hang or a huge allocation. Seed it with the files of assets/ and ../shared/assets.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // The loader reads paths; each process writes its input beside itself under the temp folder.
    let ext = if data.starts_with(b"glTF") {
        "glb"
    } else {
        "gltf"
    };
    let path = std::env::temp_dir().join(format!("glint-fuzz-{}.{ext}", std::process::id()));
    if std::fs::write(&path, data).is_err() {
        return;
    }
    if let Ok(scene) = glint::Scene::load(&path) {
        // Touch what the loader produced, so that inconsistent meshes show up here too.
        let _ = scene.triangle_count();
    }
});
