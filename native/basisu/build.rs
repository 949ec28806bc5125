//! Builds the vendored Basis Universal transcoder (v1.16, Apache-2.0) with glint's wrapper. Only the
//! RGBA32 output is used, so the GPU block formats are compiled out; KTX2 containers and Zstandard are
//! handled on the Rust side.
fn main() {
    println!("cargo:rerun-if-changed=wrapper.cpp");
    println!("cargo:rerun-if-changed=vendor/transcoder");
    let mut build = cc::Build::new();
    build
        .cpp(true)
        .flag_if_supported("-std=c++11")
        .flag_if_supported("-fno-strict-aliasing");
    for flag in [
        "-Wno-unused-parameter",
        "-Wno-unused-variable",
        "-Wno-unused-function",
        "-Wno-class-memaccess",
        "-Wno-unused-value",
        "-Wno-unused-but-set-variable",
        "-w",
    ] {
        build.flag_if_supported(flag);
    }
    for (name, value) in [
        ("BASISD_SUPPORT_KTX2", "0"),
        ("BASISD_SUPPORT_KTX2_ZSTD", "0"),
        ("BASISD_SUPPORT_DXT1", "0"),
        ("BASISD_SUPPORT_DXT5A", "0"),
        ("BASISD_SUPPORT_BC7", "0"),
        ("BASISD_SUPPORT_BC7_MODE5", "0"),
        ("BASISD_SUPPORT_PVRTC1", "0"),
        ("BASISD_SUPPORT_PVRTC2", "0"),
        ("BASISD_SUPPORT_ETC2_EAC_A8", "0"),
        ("BASISD_SUPPORT_ETC2_EAC_RG11", "0"),
        ("BASISD_SUPPORT_ATC", "0"),
        ("BASISD_SUPPORT_FXT1", "0"),
    ] {
        build.define(name, value);
    }
    // Basis's asserts are debugging aids that abort the process (a fuzzed ETC1S stream reaches
    // `assert(0)` in decode_vlc); without them the transcoder breaks off and reports failure,
    // which glint turns into an error naming the image. Its own release builds define it too.
    build.define("NDEBUG", None);
    build
        .include("vendor")
        .file("vendor/transcoder/basisu_transcoder.cpp")
        .file("wrapper.cpp")
        .compile("glint_basisu");
}
