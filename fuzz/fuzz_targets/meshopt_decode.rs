//! Fuzzes the meshopt decoder directly: the first bytes choose mode, filter, stride and count, the
//! rest is the compressed stream. Decoding must give bytes or an error, never a crash.
#![no_main]

use glint::scene::gltf::meshopt::{decode, Filter, Mode};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if data.len() < 4 {
        return;
    }
    let mode = [Mode::Attributes, Mode::Triangles, Mode::Indices][data[0] as usize % 3];
    let filter = [
        Filter::None,
        Filter::Octahedral,
        Filter::Quaternion,
        Filter::Exponential,
        Filter::Color,
    ][data[1] as usize % 5];
    let stride = data[2] as usize + 1;
    let count = u16::from_le_bytes([data[3], data.get(4).copied().unwrap_or(0)]) as usize;
    if let Ok(out) = decode(&data[5.min(data.len())..], count, stride, mode, filter) {
        assert_eq!(out.len(), count * stride);
    }
});
