//! The KTX2 decoder against the Basis Universal encoder's own unpacking of the same files, the PNGs
//! they were made from, and corrupt inputs made by hand and by mutation (errors, never panics).

use std::path::PathBuf;

use super::*;

fn asset(name: &str) -> Vec<u8> {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("assets/ktx2")
        .join(name);
    std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn png(name: &str) -> Rgba8 {
    let img = image::load_from_memory(&asset(name)).unwrap().to_rgba8();
    Rgba8 {
        width: img.width() as usize,
        height: img.height() as usize,
        pixels: img.pixels().map(|p| p.0).collect(),
    }
}

/// Largest and mean absolute channel difference over channels `ch`.
fn diff(a: &Rgba8, b: &Rgba8, ch: std::ops::Range<usize>) -> (u8, f64) {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let (mut worst, mut sum, mut n) = (0u8, 0u64, 0u64);
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        for c in ch.clone() {
            let d = p[c].abs_diff(q[c]);
            worst = worst.max(d);
            sum += d as u64;
            n += 1;
        }
    }
    (worst, sum as f64 / n as f64)
}

#[test]
fn etc1s_and_uastc_decode_as_the_encoder_unpacks_them() {
    // ETC1S colour decodes exactly as its ETC1 transcode; UASTC exactly as its ASTC transcode.
    for (file, reference, channels) in [
        ("etc1s.ktx2", "etc1s.ref.png", 0..3),
        ("etc1s-alpha.ktx2", "etc1s-alpha.ref.png", 0..3),
        ("uastc-zstd.ktx2", "uastc-zstd.ref.png", 0..4),
        ("uastc-alpha.ktx2", "uastc-alpha.ref.png", 0..4),
    ] {
        let got = decode(&asset(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        let (worst, _) = diff(&got, &png(reference), channels);
        assert_eq!(worst, 0, "{file} differs from {reference}");
    }
}

#[test]
fn decoded_images_are_close_to_their_sources() {
    // ETC1S at the encoder's default quality is lossy on a checker off the 4x4 block grid (mean
    // 16.5 of 255 on gradient.png, 8.1 on alpha.png); UASTC is near-lossless (3.1).
    for (file, source, limit) in [
        ("etc1s.ktx2", "gradient.png", 20.0),
        ("etc1s-alpha.ktx2", "alpha.png", 20.0),
        ("uastc-zstd.ktx2", "gradient.png", 5.0),
        ("uastc-alpha.ktx2", "alpha.png", 5.0),
    ] {
        let got = decode(&asset(file)).unwrap();
        let (worst, mean) = diff(&got, &png(source), 0..4);
        eprintln!("{file} vs {source}: mean |d| {mean:.2}, worst {worst}");
        assert!(mean < limit, "{file}: mean {mean}");
    }
    // Alpha survives: the right half of alpha.png is 64, the left 255.
    let a = decode(&asset("etc1s-alpha.ktx2")).unwrap();
    assert!(
        a.pixels[0][3] > 240 && a.pixels[11][3] < 90,
        "{:?}",
        (a.pixels[0], a.pixels[11])
    );
}

#[test]
fn corrupt_files_are_errors() {
    let e = decode(&asset("truncated.ktx2")).unwrap_err();
    assert!(matches!(e, Ktx2Error::Container(_)), "{e}");
    let e = decode(&asset("corrupt-etc1s.ktx2")).unwrap_err();
    assert!(
        matches!(e, Ktx2Error::Transcode(_) | Ktx2Error::BasisLz(_)),
        "{e}"
    );
    assert!(decode(b"not a texture").is_err());
    assert!(decode(&[]).is_err());
}

/// Offsets of the header fields patched below.
const WIDTH: usize = 20;
const HEIGHT: usize = 24;
const SGD_LENGTH: usize = 72;
/// The first level index entry: byte offset, byte length, uncompressed byte length.
const LEVEL0: usize = 80;

fn patched(file: &str, at: usize, bytes: &[u8]) -> Vec<u8> {
    let mut d = asset(file);
    d[at..at + bytes.len()].copy_from_slice(bytes);
    d
}

#[test]
fn lying_sizes_are_refused_before_allocating() {
    // A huge image in a small file: refused by size, nothing allocated for it.
    let d = patched("uastc-zstd.ktx2", WIDTH, &100_000u32.to_le_bytes());
    assert!(matches!(decode(&d), Err(Ktx2Error::TooLarge(100_000, _))));
    let d = patched("etc1s.ktx2", HEIGHT, &16384u32.to_le_bytes());
    let d = {
        let mut d = d;
        d[WIDTH..WIDTH + 4].copy_from_slice(&16384u32.to_le_bytes());
        d
    };
    assert!(matches!(decode(&d), Err(Ktx2Error::TooLarge(..))));
    // A level that claims to inflate to more than its image needs.
    let d = patched("uastc-zstd.ktx2", LEVEL0 + 16, &(1u64 << 40).to_le_bytes());
    assert!(
        matches!(decode(&d), Err(Ktx2Error::LevelSize { .. })),
        "{:?}",
        decode(&d)
    );
    // An uncompressed level shorter than its image.
    let d = patched("uastc-alpha.ktx2", LEVEL0 + 8, &10u64.to_le_bytes());
    assert!(decode(&d).is_err());
    // Global data claiming codebooks longer than itself.
    let mut d = asset("etc1s.ktx2");
    let sgd = u64::from_le_bytes(d[64..72].try_into().unwrap()) as usize;
    d[sgd + 4..sgd + 8].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(
        matches!(decode(&d), Err(Ktx2Error::BasisLz(_))),
        "{:?}",
        decode(&d)
    );
    // Global data shorter than its header.
    let d = patched("etc1s.ktx2", SGD_LENGTH, &4u64.to_le_bytes());
    assert!(decode(&d).is_err());
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
    #[test]
    fn mutated_files_never_panic(
        file in 0usize..4,
        flips in proptest::collection::vec((0usize..4096, 0u8..=255), 1..8),
        cut in 0usize..4096,
    ) {
        let name = ["etc1s.ktx2", "etc1s-alpha.ktx2", "uastc-zstd.ktx2", "uastc-alpha.ktx2"][file];
        let mut d = asset(name);
        for (at, x) in flips {
            let n = d.len();
            d[at % n] ^= x;
        }
        if cut < d.len() && cut % 3 == 0 {
            d.truncate(cut);
        }
        if let Ok(img) = decode(&d) {
            proptest::prop_assert_eq!(img.pixels.len(), img.width * img.height);
        }
    }
}

#[test]
fn a_descriptor_the_ktx2_reader_panics_on_is_an_error() {
    // A fuzzer's file: a texel block dimension of 255, which `ktx2` turns into 255 + 1.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/regressions/texture_decode/ktx2-dfd-texel-dimension-255.ktx2");
    let e = decode(&std::fs::read(path).unwrap()).unwrap_err();
    assert!(
        matches!(&e, Ktx2Error::Container(m) if m.contains("descriptor")),
        "{e}"
    );
}

#[test]
fn an_overlong_code_in_an_etc1s_stream_is_an_error_not_an_abort() {
    // A fuzzer's file: Basis's decode_vlc reached `assert(0)`, which aborted the whole process
    // before the transcoder was built with NDEBUG.
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/regressions/texture_decode/ktx2-etc1s-vlc-overlong-assert.ktx2");
    assert!(decode(&std::fs::read(path).unwrap()).is_err());
}
