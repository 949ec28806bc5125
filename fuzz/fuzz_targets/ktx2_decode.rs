//! Fuzzes the KTX2 decoder (container, Zstandard, BasisLZ global data, ETC1S and UASTC transcoding):
//! any input must give an image of the size it reports or an error, never a panic, a hang or an
//! allocation beyond the decoder's limits. Seed it with assets/ktx2/*.ktx2.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(img) = glint::scene::ktx2::decode(data) {
        assert_eq!(img.pixels.len(), img.width * img.height);
    }
});
