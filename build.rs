//! Build script: finds or fetches the Embree 4 shared library and tells rustc how to link and load it.
//! Only active with the `embree` feature; a `--no-default-features` build needs nothing from here.
//!
//! Order of preference:
//!  * `EMBREE_DIR` — any directory holding `libembree4.so` (a real Embree 4 install, or an offline copy);
//!  * otherwise Embree 4.4.0 from the PyPI wheel `embreex==4.4.0.post1`, downloaded once with
//!    `python3 -m pip download` into `<target-dir>/embree4/` (override with `EMBREE_CACHE_DIR`).
//!
//! The library directory goes into an rpath, so `cargo run`, `cargo test` and the built binary load it
//! with no `LD_LIBRARY_PATH`. See ../shared/EMBREE.md, section 2.
use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

const WHEEL: &str = "embreex==4.4.0.post1";
const SUBDIR: &str = "embree-4.4.0-embreex-4.4.0.post1";

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=EMBREE_DIR");
    println!("cargo:rerun-if-env-changed=EMBREE_CACHE_DIR");
    if env::var_os("CARGO_FEATURE_EMBREE").is_none() {
        return;
    }
    let dir = match env::var_os("EMBREE_DIR") {
        Some(d) => PathBuf::from(d),
        None => fetch_wheel(),
    };
    if !dir.join("libembree4.so").exists() {
        panic!(
            "{}: no libembree4.so there (set EMBREE_DIR to a directory holding libembree4.so)",
            dir.display()
        );
    }
    // Re-run (and re-fetch) if somebody deletes the cached library.
    println!(
        "cargo:rerun-if-changed={}",
        dir.join("libembree4.so").display()
    );
    println!("cargo:rustc-link-search=native={}", dir.display());
    // Reaches the bins, tests, examples and benches of this package: keep glint one package.
    println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
    println!("cargo:rustc-env=GLINT_EMBREE_LIB_DIR={}", dir.display());
}

fn cache_root() -> PathBuf {
    if let Some(d) = env::var_os("EMBREE_CACHE_DIR") {
        return PathBuf::from(d);
    }
    // OUT_DIR = <target-dir>/[<triple>/]<profile>/build/<pkg>-<hash>/out
    let out = PathBuf::from(env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    out.ancestors()
        .nth(4)
        .expect("OUT_DIR is deep enough")
        .join("embree4")
}

fn fetch_wheel() -> PathBuf {
    let root = cache_root();
    let dest = root.join(SUBDIR);
    if dest.join("libembree4.so").exists() {
        return dest;
    }
    fs::create_dir_all(&root).expect("create the Embree cache directory");
    let tmp = root.join(format!(".tmp-{}", std::process::id()));
    let _ = fs::remove_dir_all(&tmp);
    fs::create_dir_all(&tmp).expect("create a temporary directory");
    let python = env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    // Pin platform and ABI so the file fetched does not depend on the local Python.
    let status = Command::new(&python)
        .args([
            "-m",
            "pip",
            "download",
            "--no-deps",
            "--only-binary=:all:",
            "--platform",
            "manylinux_2_28_x86_64",
            "--python-version",
            "3.11",
            "--implementation",
            "cp",
            "--abi",
            "cp311",
            "--disable-pip-version-check",
            "-q",
            "-d",
        ])
        .arg(&tmp)
        .arg(WHEEL)
        .status()
        .unwrap_or_else(|e| panic!("cannot run {python}: {e}; set EMBREE_DIR"));
    if !status.success() {
        let _ = fs::remove_dir_all(&tmp);
        panic!("pip download {WHEEL} failed (offline?); set EMBREE_DIR to a directory with libembree4.so");
    }
    // Unpack only <pkg>.libs/*.so* with Python's zipfile, so no `unzip` is needed.
    let script = r#"
import sys, zipfile, glob, os
whl = glob.glob(os.path.join(sys.argv[1], '*.whl'))[0]
with zipfile.ZipFile(whl) as z:
    for n in z.namelist():
        if '.libs/' in n and '.so' in n:
            with open(os.path.join(sys.argv[1], os.path.basename(n)), 'wb') as f:
                f.write(z.read(n))
os.remove(whl)
"#;
    let status = Command::new(&python)
        .arg("-c")
        .arg(script)
        .arg(&tmp)
        .status()
        .expect("run python to unpack the wheel");
    assert!(status.success(), "unpacking the wheel failed");
    // `-lembree4` needs libembree4.so; the wheel has libembree4-<hash>.so.4 (its SONAME).
    let real = fs::read_dir(&tmp)
        .expect("read the unpacked wheel")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .find(|n| n.starts_with("libembree4-") && n.ends_with(".so.4"))
        .expect("no libembree4-*.so.4 in the wheel");
    std::os::unix::fs::symlink(&real, tmp.join("libembree4.so")).expect("symlink libembree4.so");
    // Atomic publish; a concurrent build may have won the race, which is fine.
    if fs::rename(&tmp, &dest).is_err() {
        let _ = fs::remove_dir_all(&tmp);
    }
    assert!(Path::new(&dest).join("libembree4.so").exists());
    dest
}
