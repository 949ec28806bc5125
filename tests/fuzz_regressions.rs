//! Replays every input kept under fuzz/regressions/<target>/ (what the fuzzers found, once fixed)
//! through the same code the fuzz target runs: each must load or fail cleanly, never panic.

#[path = "../fuzz/fuzz_targets/common/mod.rs"]
mod harness;

use std::path::Path;

#[test]
fn every_kept_fuzz_finding_loads_or_fails_cleanly() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions");
    let mut replayed = 0;
    let mut panicked = Vec::new();
    for (target, run) in harness::TARGETS {
        let Ok(entries) = std::fs::read_dir(root.join(target)) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            let data = std::fs::read(&path).unwrap();
            if std::panic::catch_unwind(|| run(&data)).is_err() {
                panicked.push(path.display().to_string());
            }
            replayed += 1;
        }
    }
    assert!(panicked.is_empty(), "panicked on {panicked:?}");
    // The folder is part of the repository: an empty replay means it was not found.
    assert!(
        replayed > 0,
        "no regression inputs under {}",
        root.display()
    );
}

#[test]
fn every_fuzz_target_has_a_regression_folder_name_of_its_own() {
    let mut names: Vec<&str> = harness::TARGETS.iter().map(|(n, _)| *n).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), harness::TARGETS.len());
    let fuzz = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/fuzz_targets");
    for n in names {
        assert!(
            fuzz.join(format!("{n}.rs")).is_file(),
            "no fuzz target {n}.rs"
        );
    }
}

#[test]
fn draco_streams_declaring_more_texcoord_orientations_than_corners_are_refused() {
    // Two fuzzed streams whose portable texture-coordinate predictor declared up to 2^31
    // orientations: Draco allocated 296 MB and decoded bits for 6-10 s before failing. Now the
    // count is checked against the mesh's corners first (the replay above would pass either way,
    // only slowly; here the stream must be refused).
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/draco_decode");
    for name in [
        "texcoord-orientations-2e31-48k.bin",
        "texcoord-orientations-296mb-30k.bin",
    ] {
        let data = std::fs::read(dir.join(name)).unwrap();
        let file = harness::draco_glb(&data).unwrap();
        let e = glint::scene::gltf::load_bytes(Path::new(name), &file, &Default::default())
            .err()
            .unwrap_or_else(|| panic!("{name} loaded"))
            .to_string();
        assert!(e.contains("Draco"), "{name}: {e}");
    }
}
