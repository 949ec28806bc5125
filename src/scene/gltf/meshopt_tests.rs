//! Tests of the meshopt decoder: streams made by meshoptimizer's own encoders decode back, and
//! handmade corrupt streams and lying counts are errors, never panics or huge allocations.

use super::{decode, Filter, Mode};

fn bytes_of<T: Copy, const N: usize>(v: &[[T; N]]) -> Vec<u8> {
    let n = std::mem::size_of_val(v);
    // SAFETY: plain integer arrays, read as bytes.
    unsafe { std::slice::from_raw_parts(v.as_ptr().cast::<u8>(), n) }.to_vec()
}

fn vertices() -> Vec<[u32; 3]> {
    (0..1000u32)
        .map(|i| [i, i * 7 % 13, u32::MAX - i])
        .collect()
}

#[test]
fn attributes_round_trip() {
    let v = vertices();
    let enc = meshopt::encode_vertex_buffer(&v).unwrap();
    let out = decode(&enc, v.len(), 12, Mode::Attributes, Filter::None).unwrap();
    assert_eq!(out, bytes_of(&v));
}

#[test]
fn triangles_and_indices_round_trip() {
    let idx: Vec<u32> = (0..300u32).map(|i| (i * 37) % 101).collect();
    let enc = meshopt::encode_index_buffer(&idx, 101).unwrap();
    let out = decode(&enc, idx.len(), 4, Mode::Triangles, Filter::None).unwrap();
    // The triangle codec keeps triangle order but may rotate the corners of each triangle.
    let got: Vec<u32> = out
        .chunks(4)
        .map(|b| u32::from_le_bytes(b.try_into().unwrap()))
        .collect();
    for (t, (g, w)) in got.chunks(3).zip(idx.chunks(3)).enumerate() {
        let rotations = [[w[0], w[1], w[2]], [w[1], w[2], w[0]], [w[2], w[0], w[1]]];
        assert!(
            rotations.contains(&[g[0], g[1], g[2]]),
            "triangle {t}: {g:?} vs {w:?}"
        );
    }
    let enc = meshopt::encode_index_sequence(&idx, 101).unwrap();
    let out = decode(&enc, idx.len(), 2, Mode::Indices, Filter::None).unwrap();
    let want: Vec<[u16; 1]> = idx.iter().map(|&i| [i as u16]).collect();
    assert_eq!(out, bytes_of(&want));
}

/// Unit vectors through the octahedral filter come back within the 8-bit encoding's error.
#[test]
fn octahedral_filter_decodes_unit_vectors() {
    let n: Vec<[f32; 4]> = (0..64)
        .map(|i| {
            let (t, p) = (i as f32 * 0.37, i as f32 * 0.11);
            [t.sin() * p.cos(), t.sin() * p.sin(), t.cos(), 0.0]
        })
        .collect();
    let filtered = meshopt::encode_filter_oct::<i8>(&n, 8);
    let enc = meshopt::encode_vertex_buffer(&filtered).unwrap();
    let out = decode(&enc, n.len(), 4, Mode::Attributes, Filter::Octahedral).unwrap();
    for (k, want) in n.iter().enumerate() {
        for c in 0..3 {
            let got = out[4 * k + c] as i8 as f32 / 127.0;
            assert!(
                (got - want[c]).abs() < 0.03,
                "vector {k} component {c}: {got} vs {want:?}"
            );
        }
    }
}

#[test]
fn quaternion_and_exponential_filters_decode() {
    let q: Vec<[f32; 4]> = (0..32)
        .map(|i| {
            let a = i as f32 * 0.2;
            [0.0, (a / 2.0).sin(), 0.0, (a / 2.0).cos()]
        })
        .collect();
    let enc = meshopt::encode_vertex_buffer(&meshopt::encode_filter_quat(&q, 12)).unwrap();
    let out = decode(&enc, q.len(), 8, Mode::Attributes, Filter::Quaternion).unwrap();
    for (k, want) in q.iter().enumerate() {
        let got: Vec<f32> = (0..4)
            .map(|c| {
                i16::from_le_bytes([out[8 * k + 2 * c], out[8 * k + 2 * c + 1]]) as f32 / 32767.0
            })
            .collect();
        // q and -q are the same rotation; the filter may give either.
        let sign = if got[3] * want[3] + got[1] * want[1] < 0.0 {
            -1.0
        } else {
            1.0
        };
        for c in 0..4 {
            let got = sign * got[c];
            assert!(
                (got - want[c]).abs() < 0.01,
                "quat {k}.{c}: {got} vs {}",
                want[c]
            );
        }
    }
    let p: Vec<[f32; 3]> = (0..50)
        .map(|i| [i as f32 * 0.5, -3.25, 1e-3 * i as f32])
        .collect();
    let filtered = meshopt::encode_filter_exp(&p, 23, meshopt::EncodeExpMode::Separate);
    let enc = meshopt::encode_vertex_buffer(&filtered).unwrap();
    let out = decode(&enc, p.len(), 12, Mode::Attributes, Filter::Exponential).unwrap();
    for (k, want) in p.iter().enumerate() {
        for c in 0..3 {
            let b = &out[12 * k + 4 * c..];
            let got = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            assert!(
                (got - want[c]).abs() <= (want[c].abs() * 1e-6).max(1e-9),
                "{got} vs {}",
                want[c]
            );
        }
    }
}

/// Every truncation and a flipped header of a valid stream is an error or decodes (garbage in,
/// garbage out is allowed), never a panic.
#[test]
fn truncated_and_corrupt_streams_are_errors() {
    let v = vertices();
    let enc = meshopt::encode_vertex_buffer(&v).unwrap();
    for cut in 0..enc.len() {
        assert!(decode(&enc[..cut], v.len(), 12, Mode::Attributes, Filter::None).is_err());
    }
    let mut bad = enc.clone();
    bad[0] = 0x00;
    let e = decode(&bad, v.len(), 12, Mode::Attributes, Filter::None).unwrap_err();
    assert!(e.contains("corrupt"), "{e}");
    let idx: Vec<u32> = (0..300u32).collect();
    let enc = meshopt::encode_index_buffer(&idx, 300).unwrap();
    for cut in 0..enc.len() {
        assert!(decode(&enc[..cut], 300, 4, Mode::Triangles, Filter::None).is_err());
    }
    // Flipping bytes anywhere: errors or garbage, never a crash.
    for k in 0..enc.len() {
        let mut b = enc.clone();
        b[k] ^= 0xA5;
        let _ = decode(&b, 300, 4, Mode::Triangles, Filter::None);
    }
}

#[test]
fn lying_counts_fail_before_allocating() {
    let e = decode(
        &[0xA0; 40],
        usize::MAX / 2,
        4,
        Mode::Attributes,
        Filter::None,
    )
    .unwrap_err();
    assert!(e.contains("too many"), "{e}");
    let e = decode(&[0xA0; 40], 100_000_000, 4, Mode::Attributes, Filter::None).unwrap_err();
    assert!(e.contains("cannot come from 40 compressed bytes"), "{e}");
    let e = decode(&[0xE1; 40], 3_000, 4, Mode::Triangles, Filter::None).unwrap_err();
    assert!(e.contains("cannot come from"), "{e}");
}

#[test]
fn shapes_the_decoder_asserts_are_refused() {
    let cases = [
        (3, 6, Mode::Attributes, Filter::None, "byteStride 6"),
        (3, 260, Mode::Attributes, Filter::None, "byteStride 260"),
        (3, 8, Mode::Triangles, Filter::None, "byteStride 8"),
        (4, 2, Mode::Triangles, Filter::None, "multiple of 3"),
        (
            3,
            12,
            Mode::Attributes,
            Filter::Octahedral,
            "filter Octahedral",
        ),
        (
            3,
            4,
            Mode::Attributes,
            Filter::Quaternion,
            "filter Quaternion",
        ),
        (
            3,
            4,
            Mode::Indices,
            Filter::Exponential,
            "filter Exponential",
        ),
    ];
    for (count, stride, mode, filter, want) in cases {
        let e = decode(&[0; 64], count, stride, mode, filter).unwrap_err();
        assert!(e.contains(want), "{e} (wanted {want})");
    }
}
