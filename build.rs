//! Build script: finds or fetches the Embree 4 and Open Image Denoise 2 shared libraries and tells
//! rustc how to link and load them. Each is only wanted by its cargo feature (`embree`, `denoise`).
//!
//! Order of preference, for each library:
//!  * `EMBREE_DIR` (a directory holding `libembree4.so`) / `OIDN_DIR` (one holding
//!    `libOpenImageDenoise.so`): a real install, or an offline copy;
//!  * otherwise the library from a PyPI wheel, downloaded once with `python3 -m pip download` into
//!    `<target-dir>/embree4/` (`embreex==4.4.0.post1`, override with `EMBREE_CACHE_DIR`) or
//!    `<target-dir>/oidn2/` (`pyoidn==2.5.1.0`, override with `OIDN_CACHE_DIR`).
//!
//! The library directories go into an rpath, so `cargo run`, `cargo test` and the built binary load
//! them with no `LD_LIBRARY_PATH`. See ../shared/EMBREE.md, section 2, and ../shared/OIDN.md.
use std::env;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

/// One shared library glint links, fetched from a wheel when its `*_DIR` variable is unset.
struct Lib {
    feature: &'static str,
    dir_var: &'static str,
    cache_var: &'static str,
    cache_name: &'static str,
    /// The `-l` name: `lib{link}.so` must be in the directory.
    link: &'static str,
    wheel: &'static str,
    platform: &'static str,
    /// Folder under the cache for this wheel's files.
    subdir: &'static str,
    /// Python: unpack what is needed from the wheel (argv[1]) into the folder argv[2].
    unpack: &'static str,
}

const EMBREE: Lib = Lib {
    feature: "EMBREE",
    dir_var: "EMBREE_DIR",
    cache_var: "EMBREE_CACHE_DIR",
    cache_name: "embree4",
    link: "embree4",
    wheel: "embreex==4.4.0.post1",
    platform: "manylinux_2_28_x86_64",
    subdir: "embree-4.4.0-embreex-4.4.0.post1",
    // Only <pkg>.libs/*.so*; `-lembree4` needs libembree4.so, the wheel has libembree4-<hash>.so.4
    // (its SONAME).
    unpack: r#"
import sys, zipfile, os
with zipfile.ZipFile(sys.argv[1]) as z:
    for n in z.namelist():
        if '.libs/' in n and '.so' in n:
            with open(os.path.join(sys.argv[2], os.path.basename(n)), 'wb') as f:
                f.write(z.read(n))
real = [n for n in os.listdir(sys.argv[2]) if n.startswith('libembree4-') and n.endswith('.so.4')]
os.symlink(real[0], os.path.join(sys.argv[2], 'libembree4.so'))
"#,
};

const OIDN: Lib = Lib {
    feature: "DENOISE",
    dir_var: "OIDN_DIR",
    cache_var: "OIDN_CACHE_DIR",
    cache_name: "oidn2",
    link: "OpenImageDenoise",
    wheel: "pyoidn==2.5.1.0",
    platform: "manylinux2014_x86_64",
    // The folder must be named `lib`: the libraries' RPATH is $ORIGIN/../lib, and the API library
    // loads the core and the CPU device through it.
    subdir: "oidn-2.5.1-pyoidn-2.5.1.0/lib",
    // The four files a CPU build needs (the GPU devices, SYCL and Unified Runtime are left out).
    unpack: r#"
import sys, zipfile, os
d = sys.argv[2]
with zipfile.ZipFile(sys.argv[1]) as z:
    for n in ['libOpenImageDenoise.so.2.5.1', 'libOpenImageDenoise_core.so.2.5.1',
              'libOpenImageDenoise_device_cpu.so.2.5.1', 'libtbb.so.12']:
        with open(os.path.join(d, n), 'wb') as f:
            f.write(z.read('pyoidn/oidn/lib/' + n))
for alias in ['libOpenImageDenoise.so.2', 'libOpenImageDenoise.so']:
    os.symlink('libOpenImageDenoise.so.2.5.1', os.path.join(d, alias))
"#,
};

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    for lib in [EMBREE, OIDN] {
        println!("cargo:rerun-if-env-changed={}", lib.dir_var);
        println!("cargo:rerun-if-env-changed={}", lib.cache_var);
        if env::var_os(format!("CARGO_FEATURE_{}", lib.feature)).is_some() {
            let dir = find(&lib);
            println!(
                "cargo:rustc-env=GLINT_{}_LIB_DIR={}",
                lib.feature,
                dir.display()
            );
        }
    }
}

/// The library's directory (from its variable or the wheel), with link and rpath arguments printed.
fn find(lib: &Lib) -> PathBuf {
    let dir = match env::var_os(lib.dir_var) {
        Some(d) => PathBuf::from(d),
        None => fetch_wheel(lib),
    };
    let so = dir.join(format!("lib{}.so", lib.link));
    if !so.exists() {
        panic!(
            "{}: no lib{}.so there (set {} to a directory holding lib{}.so)",
            dir.display(),
            lib.link,
            lib.dir_var,
            lib.link
        );
    }
    // Re-run (and re-fetch) if somebody deletes the cached library.
    println!("cargo:rerun-if-changed={}", so.display());
    println!("cargo:rustc-link-search=native={}", dir.display());
    // Reaches the bins, tests, examples and benches of this package: keep glint one package.
    println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
    dir
}

fn cache_root(lib: &Lib) -> PathBuf {
    if let Some(d) = env::var_os(lib.cache_var) {
        return PathBuf::from(d);
    }
    // OUT_DIR = <target-dir>/[<triple>/]<profile>/build/<pkg>-<hash>/out
    let out = PathBuf::from(env::var("OUT_DIR").expect("cargo sets OUT_DIR"));
    out.ancestors()
        .nth(4)
        .expect("OUT_DIR is deep enough")
        .join(lib.cache_name)
}

fn fetch_wheel(lib: &Lib) -> PathBuf {
    let root = cache_root(lib);
    let dest = root.join(lib.subdir);
    let so = format!("lib{}.so", lib.link);
    if dest.join(&so).exists() {
        return dest;
    }
    let hint = format!("set {} to a directory with {so}", lib.dir_var);
    let parent = dest.parent().expect("subdir has a parent");
    fs::create_dir_all(parent).unwrap_or_else(|e| panic!("create {}: {e}", parent.display()));
    let tmp = parent.join(format!(".tmp-{}", std::process::id()));
    let _ = fs::remove_dir_all(&tmp);
    fs::create_dir_all(&tmp).expect("create a temporary directory");
    let python = env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    // Pin platform and ABI so the file fetched does not depend on the local Python.
    let status = Command::new(&python)
        .args(["-m", "pip", "download", "--no-deps", "--only-binary=:all:"])
        .args(["--platform", lib.platform, "--python-version", "3.11"])
        .args(["--implementation", "cp", "--abi", "cp311"])
        .args(["--disable-pip-version-check", "-q", "-d"])
        .arg(&tmp)
        .arg(lib.wheel)
        .status()
        .unwrap_or_else(|e| panic!("cannot run {python}: {e}; {hint}"));
    let wheel = fs::read_dir(&tmp)
        .ok()
        .and_then(|d| d.filter_map(|e| e.ok()).map(|e| e.path()).next());
    let (true, Some(wheel)) = (status.success(), wheel) else {
        let _ = fs::remove_dir_all(&tmp);
        panic!("pip download {} failed (offline?); {hint}", lib.wheel);
    };
    // Unpack with Python's zipfile, so no `unzip` is needed.
    let files = tmp.join("files");
    fs::create_dir_all(&files).expect("create the unpack directory");
    let status = Command::new(&python)
        .arg("-c")
        .arg(lib.unpack)
        .arg(&wheel)
        .arg(&files)
        .status()
        .expect("run python to unpack the wheel");
    assert!(status.success(), "unpacking {} failed; {hint}", lib.wheel);
    // Atomic publish; a concurrent build may have won the race, which is fine.
    if fs::rename(&files, &dest).is_err() {
        assert!(
            dest.join(&so).exists(),
            "{}: could not publish; {hint}",
            dest.display()
        );
    }
    let _ = fs::remove_dir_all(&tmp);
    assert!(Path::new(&dest).join(&so).exists());
    dest
}
