//! Builds the vendored decoder half of Google Draco (v1.5.7, Apache-2.0) with glint's wrapper. The
//! configuration cmake would generate is the hand-written vendor/src/draco/draco_features.h.
use std::path::Path;

fn main() {
    println!("cargo:rerun-if-changed=wrapper.cpp");
    println!("cargo:rerun-if-changed=vendor/src");
    let mut build = cc::Build::new();
    build
        .cpp(true)
        .flag_if_supported("-std=c++17")
        .flag_if_supported("-fno-strict-aliasing")
        // Draco's assert()s are debugging aids, not input checks; the fuzz target runs it as built.
        .define("NDEBUG", None)
        .flag_if_supported("-w");
    build.include("vendor/src").file("wrapper.cpp");
    let mut files = Vec::new();
    collect(Path::new("vendor/src"), &mut files);
    files.sort();
    build.files(files).compile("glint_draco");
}

/// Every .cc file under `dir`.
fn collect(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("vendor/src is readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            collect(&path, out);
        } else if path.extension().is_some_and(|e| e == "cc") {
            out.push(path);
        }
    }
}
