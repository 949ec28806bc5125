//! EXT_meshopt_compression and KHR_meshopt_compression: compressed buffer views decoded (through the
//! vendored meshoptimizer) into fresh buffers before any accessor reads them.
//!
//! Each compressed view is decoded once, its bytes appended to the buffer list, and the view re-pointed
//! at them in the JSON, so the rest of the loader reads plain buffer views. Everything the C decoder
//! asserts (strides, counts) is checked here first, and the output size is checked against what the
//! compressed bytes can possibly expand to before it is allocated.

use gltf::json::validation::USize64;
use gltf::json::Index;
use serde::Deserialize;

use super::error::MeshoptError;

/// The extension names glint decodes (KHR is EXT plus the COLOR filter and codec version 1).
pub(super) const EXTENSIONS: [&str; 2] = ["EXT_meshopt_compression", "KHR_meshopt_compression"];

/// No decoded view larger than this, whatever the file says.
const MAX_DECODED: usize = 1 << 30;

/// The extension object of a compressed buffer view.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
struct Compressed {
    buffer: usize,
    #[serde(default)]
    byte_offset: usize,
    byte_length: usize,
    byte_stride: usize,
    count: usize,
    mode: Mode,
    #[serde(default)]
    filter: Filter,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "UPPERCASE")]
pub enum Mode {
    Attributes,
    Triangles,
    Indices,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "UPPERCASE")]
pub enum Filter {
    #[default]
    None,
    Octahedral,
    Quaternion,
    Exponential,
    Color,
}

impl Mode {
    /// The most output bytes one compressed byte can decode to (with headroom): the vertex codec
    /// spends at least one control byte per 256 vertices of a 4-byte channel, the index codec at
    /// least one byte per triangle, the sequence codec one byte per index.
    fn max_ratio(self) -> usize {
        match self {
            Mode::Attributes => 1024,
            Mode::Triangles => 12,
            Mode::Indices => 4,
        }
    }
}

/// Whether a buffer only stands in for compressed data (the extension's `fallback`): it has no
/// bytes of its own to read.
pub(super) fn is_fallback(buffer: &gltf::Buffer) -> bool {
    EXTENSIONS.iter().any(|name| {
        buffer
            .extension_value(name)
            .and_then(|v| v.get("fallback"))
            .and_then(|v| v.as_bool())
            .unwrap_or(false)
    })
}

/// Decodes every compressed buffer view of `doc` into a new buffer appended to `buffers`, and returns
/// the document with those views pointing at them (the same document when nothing is compressed).
pub(super) fn decode_views(
    doc: gltf::Document,
    buffers: &mut Vec<Vec<u8>>,
) -> Result<gltf::Document, MeshoptError> {
    let compressed = doc.views().any(|v| compressed_ext(&v).is_some());
    if !compressed {
        return Ok(doc);
    }
    let mut root = doc.into_json();
    for (i, view) in root.buffer_views.iter_mut().enumerate() {
        let Some(others) = view.extensions.as_mut().map(|e| &mut e.others) else {
            continue;
        };
        let Some((name, value)) = EXTENSIONS
            .iter()
            .find_map(|n| others.remove(*n).map(|v| (*n, v)))
        else {
            continue;
        };
        let ext: Compressed =
            serde_json::from_value(value).map_err(|e| MeshoptError::Json { view: i, source: e })?;
        if ext.filter == Filter::Color && name == EXTENSIONS[0] {
            return Err(MeshoptError::ColorFilterInExt(i));
        }
        let data = decode_view(i, &ext, buffers)?;
        let index = u32::try_from(root.buffers.len()).map_err(|_| MeshoptError::TooMany)?;
        root.buffers.push(gltf::json::Buffer {
            byte_length: USize64::from(data.len()),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
        view.buffer = Index::new(index);
        view.byte_offset = None;
        view.byte_length = USize64::from(data.len());
        buffers.push(data);
    }
    // Only buffers and views changed, and each decoded view now fits its buffer exactly.
    Ok(gltf::Document::from_json_without_validation(root))
}

fn compressed_ext<'a>(view: &'a gltf::buffer::View) -> Option<&'a serde_json::Value> {
    EXTENSIONS.iter().find_map(|n| view.extension_value(n))
}

/// The decoded bytes of buffer view `view`, compressed as `ext` says.
fn decode_view(
    view: usize,
    ext: &Compressed,
    buffers: &[Vec<u8>],
) -> Result<Vec<u8>, MeshoptError> {
    let src = buffers.get(ext.buffer).ok_or(MeshoptError::NoBuffer {
        view,
        buffer: ext.buffer,
    })?;
    let end = ext.byte_offset.checked_add(ext.byte_length);
    let encoded = match end {
        Some(end) if end <= src.len() => &src[ext.byte_offset..end],
        _ => {
            return Err(MeshoptError::OutOfBounds {
                view,
                buffer: ext.buffer,
                start: ext.byte_offset,
                len: ext.byte_length,
                have: src.len(),
            })
        }
    };
    decode(encoded, ext.count, ext.byte_stride, ext.mode, ext.filter)
        .map_err(|problem| MeshoptError::Stream { view, problem })
}

/// Decodes one stream of `count` elements of `stride` bytes; the heart of the extension, apart from
/// the JSON, so that tests and fuzzing reach it directly.
pub fn decode(
    encoded: &[u8],
    count: usize,
    stride: usize,
    mode: Mode,
    filter: Filter,
) -> Result<Vec<u8>, String> {
    check_shape(count, stride, mode, filter)?;
    let size = count
        .checked_mul(stride)
        .filter(|&s| s <= MAX_DECODED)
        .ok_or_else(|| format!("{count} elements of {stride} bytes are too many"))?;
    let limit = encoded
        .len()
        .saturating_mul(mode.max_ratio())
        .saturating_add(4096);
    if size > limit {
        return Err(format!(
            "{count} elements of {stride} bytes cannot come from {} compressed bytes",
            encoded.len()
        ));
    }
    // Words, so that the filters' 16- and 32-bit accesses are aligned.
    let mut words = vec![0u32; size.div_ceil(4)];
    let dst = words.as_mut_ptr().cast::<std::ffi::c_void>();
    // SAFETY: `words` holds `count * stride` bytes; the decoders write at most that many and read
    // only `encoded`; their preconditions (stride, count) were checked by `check_shape`.
    let rc = unsafe {
        match mode {
            Mode::Attributes => meshopt::ffi::meshopt_decodeVertexBuffer(
                dst,
                count,
                stride,
                encoded.as_ptr(),
                encoded.len(),
            ),
            Mode::Triangles => meshopt::ffi::meshopt_decodeIndexBuffer(
                dst,
                count,
                stride,
                encoded.as_ptr(),
                encoded.len(),
            ),
            Mode::Indices => meshopt::ffi::meshopt_decodeIndexSequence(
                dst,
                count,
                stride,
                encoded.as_ptr(),
                encoded.len(),
            ),
        }
    };
    if rc != 0 {
        return Err(format!("corrupt {mode:?} stream (decoder error {rc})"));
    }
    // SAFETY: as above; each filter's stride was checked against what it accepts.
    unsafe {
        match filter {
            Filter::None => {}
            Filter::Octahedral => meshopt::ffi::meshopt_decodeFilterOct(dst, count, stride),
            Filter::Quaternion => meshopt::ffi::meshopt_decodeFilterQuat(dst, count, stride),
            Filter::Exponential => meshopt::ffi::meshopt_decodeFilterExp(dst, count, stride),
            Filter::Color => meshopt::ffi::meshopt_decodeFilterColor(dst, count, stride),
        }
    }
    let mut bytes: Vec<u8> = words.iter().flat_map(|w| w.to_ne_bytes()).collect();
    bytes.truncate(size);
    Ok(bytes)
}

/// The strides and counts the extension (and the C decoder) allow for a mode and filter.
fn check_shape(count: usize, stride: usize, mode: Mode, filter: Filter) -> Result<(), String> {
    let stride_ok = match mode {
        Mode::Attributes => stride > 0 && stride <= 256 && stride.is_multiple_of(4),
        Mode::Triangles | Mode::Indices => stride == 2 || stride == 4,
    };
    if !stride_ok {
        return Err(format!(
            "byteStride {stride} is not allowed in {mode:?} mode"
        ));
    }
    if mode == Mode::Triangles && !count.is_multiple_of(3) {
        return Err(format!("TRIANGLES count {count} is not a multiple of 3"));
    }
    let filter_ok = match filter {
        Filter::None => true,
        _ if mode != Mode::Attributes => false,
        Filter::Octahedral | Filter::Color => stride == 4 || stride == 8,
        Filter::Quaternion => stride == 8,
        Filter::Exponential => true,
    };
    if !filter_ok {
        return Err(format!(
            "filter {filter:?} does not apply to byteStride {stride} in {mode:?} mode"
        ));
    }
    Ok(())
}

#[cfg(test)]
#[path = "meshopt_tests.rs"]
mod tests;
