//! The bytes of a glTF file: the .glb container split into JSON and BIN, buffers read (data URIs,
//! external files), and accessors read element by element with every extent checked first.

use std::path::Path;

use gltf::accessor::{DataType, Dimensions};

use super::buffers::Buffers;
use super::error::{AccessorError, BufferProblem, GlbError, GltfError, ViewError};

/// Splits a binary glTF into its JSON chunk and BIN chunk, checking every length.
pub(super) fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<Vec<u8>>), GlbError> {
    let u32_at =
        |o: usize| u32::from_le_bytes([bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]]);
    if bytes.len() < 12 {
        return Err(GlbError::NoHeader(bytes.len()));
    }
    let version = u32_at(4);
    if version != 2 {
        return Err(GlbError::Version(version));
    }
    let length = u32_at(8) as usize;
    if length > bytes.len() {
        return Err(GlbError::Length {
            length,
            file: bytes.len(),
        });
    }
    if length < 20 {
        return Err(GlbError::NoRoom(length));
    }
    let data = &bytes[..length];
    let mut at = 12;
    let mut json = None;
    let mut bin = None;
    let mut chunk = 0;
    while at < data.len() {
        if data.len() - at < 8 {
            return Err(GlbError::ChunkHeader(chunk));
        }
        let len = u32_at(at) as usize;
        let ty = &data[at + 4..at + 8];
        let start = at + 8;
        if len > data.len() - start {
            return Err(GlbError::Chunk {
                chunk,
                len,
                remain: data.len() - start,
            });
        }
        let body = &data[start..start + len];
        match (chunk, ty) {
            (0, b"JSON") => json = Some(body),
            (0, _) => return Err(GlbError::FirstNotJson),
            (1, b"BIN\0") => bin = Some(body.to_vec()),
            _ => {} // unknown chunks are to be ignored
        }
        at = start + len;
        chunk += 1;
    }
    let json = json.ok_or(GlbError::NoJson)?;
    Ok((json, bin))
}

/// Whether the importer's percent-decoding of a relative URI would succeed (it panics otherwise).
pub(super) fn uri_decodes(uri: &str) -> bool {
    if uri.contains(':') {
        return true;
    }
    let b = uri.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%' && i + 2 < b.len() {
            if let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8(out).is_ok()
}

/// The data of every buffer, each at least as long as it says.
pub(super) fn read_buffers(
    doc: &gltf::Document,
    base: &Path,
    blob: Option<Vec<u8>>,
) -> Result<Vec<Vec<u8>>, GltfError> {
    let mut blob = blob;
    let mut out = Vec::new();
    for buffer in doc.buffers() {
        let i = buffer.index();
        let what = match buffer.source() {
            gltf::buffer::Source::Bin => format!("buffer {i} (the .glb BIN chunk)"),
            gltf::buffer::Source::Uri(uri) if uri.starts_with("data:") => {
                format!("buffer {i} (data URI)")
            }
            gltf::buffer::Source::Uri(uri) => format!("buffer {i} ('{uri}')"),
        };
        let fail = |problem| GltfError::Buffer {
            what: what.clone(),
            problem,
        };
        // A meshopt fallback buffer is never read: its views are decoded from elsewhere.
        if super::meshopt::is_fallback(&buffer) {
            out.push(Vec::new());
            continue;
        }
        if let gltf::buffer::Source::Uri(uri) = buffer.source() {
            if !uri_decodes(uri) {
                return Err(fail(BufferProblem::MalformedUri));
            }
        }
        let data = gltf::buffer::Data::from_source_and_blob(buffer.source(), Some(base), &mut blob)
            .map_err(|e| {
                fail(match e {
                    gltf::Error::Io(e) => BufferProblem::Io(e),
                    gltf::Error::MissingBlob => BufferProblem::NoBin,
                    e => BufferProblem::Source(e),
                })
            })?;
        if data.len() < buffer.length() {
            return Err(fail(BufferProblem::Truncated {
                declared: buffer.length(),
                present: data.len(),
            }));
        }
        out.push(data.0);
    }
    Ok(out)
}

/// The bytes of a buffer view, checked against its buffer.
pub(super) fn view_bytes<'b>(
    view: &gltf::buffer::View,
    buffers: &'b [Vec<u8>],
) -> Result<&'b [u8], ViewError> {
    let buf = buffers
        .get(view.buffer().index())
        .ok_or(ViewError::BufferMissing(view.index()))?;
    let end = view.offset().checked_add(view.length());
    match end {
        Some(end) if end <= buf.len() => Ok(&buf[view.offset()..end]),
        _ => Err(ViewError::OutOfBounds {
            view: view.index(),
            start: view.offset(),
            end: view.offset().saturating_add(view.length()),
            len: buf.len(),
        }),
    }
}

/// Reads every element of an accessor (sparse included) through `conv`, which gets the element's bytes.
/// Extents are checked first: a short buffer is an error, never a panic.
pub(super) fn read_elements<T: Copy>(
    acc: &gltf::Accessor,
    buffers: &Buffers,
    conv: impl Fn(&[u8]) -> T,
) -> Result<Vec<T>, AccessorError> {
    let name = match acc.name() {
        Some(n) => format!("accessor {} ('{n}')", acc.index()),
        None => format!("accessor {}", acc.index()),
    };
    let elem = acc.data_type().size() * acc.dimensions().multiplicity();
    let count = acc.count();
    if count > (1 << 31) || (acc.view().is_none() && count > (1 << 26)) {
        return Err(AccessorError::TooLarge { name, count });
    }
    buffers.charge(&name, count, std::mem::size_of::<T>())?;
    // Allocated only once the extents are known to be inside the file's data.
    let mut out = match acc.view() {
        Some(view) => read_dense(acc, &view, buffers, &name, &conv)?,
        None => vec![conv(&vec![0u8; elem]); count],
    };
    if let Some(sparse) = acc.sparse() {
        apply_sparse(&sparse, elem, buffers, &name, &conv, &mut out)?;
    }
    Ok(out)
}

/// The elements of an accessor stored in `view`.
fn read_dense<T>(
    acc: &gltf::Accessor,
    view: &gltf::buffer::View,
    buffers: &[Vec<u8>],
    name: &str,
    conv: impl Fn(&[u8]) -> T,
) -> Result<Vec<T>, AccessorError> {
    let elem = acc.data_type().size() * acc.dimensions().multiplicity();
    let count = acc.count();
    let bytes = view_bytes(view, buffers).map_err(|source| AccessorError::View {
        name: name.to_owned(),
        source,
    })?;
    let stride = view.stride().unwrap_or(elem);
    if stride < elem {
        return Err(AccessorError::Stride {
            name: name.to_owned(),
            stride,
            elem,
        });
    }
    if count > 0 {
        let need = (count - 1)
            .checked_mul(stride)
            .and_then(|n| n.checked_add(elem))
            .and_then(|n| n.checked_add(acc.offset()));
        if !matches!(need, Some(need) if need <= bytes.len()) {
            return Err(AccessorError::OutOfBounds {
                name: name.to_owned(),
                count,
                elem,
                stride,
                offset: acc.offset(),
                len: bytes.len(),
                view: view.index(),
            });
        }
    }
    let base = acc.offset();
    let mut out = Vec::with_capacity(count);
    for i in 0..count {
        let o = base + i * stride;
        out.push(conv(&bytes[o..o + elem]));
    }
    Ok(out)
}

/// Overwrites the elements a sparse accessor names with its values.
fn apply_sparse<T>(
    sparse: &gltf::accessor::sparse::Sparse,
    elem: usize,
    buffers: &[Vec<u8>],
    name: &str,
    conv: impl Fn(&[u8]) -> T,
    out: &mut [T],
) -> Result<(), AccessorError> {
    let view_err = |source| AccessorError::SparseView {
        name: name.to_owned(),
        source,
    };
    let count = out.len();
    let n = sparse.count();
    let ind = sparse.indices();
    let isize = ind.index_type().size();
    let ibytes = view_bytes(&ind.view(), buffers).map_err(view_err)?;
    let vals = sparse.values();
    let vbytes = view_bytes(&vals.view(), buffers).map_err(view_err)?;
    let ineed = n
        .checked_mul(isize)
        .and_then(|x| x.checked_add(ind.offset()));
    let vneed = n
        .checked_mul(elem)
        .and_then(|x| x.checked_add(vals.offset()));
    if !matches!(ineed, Some(k) if k <= ibytes.len())
        || !matches!(vneed, Some(k) if k <= vbytes.len())
    {
        return Err(AccessorError::SparseOutOfBounds {
            name: name.to_owned(),
        });
    }
    for k in 0..n {
        let o = ind.offset() + k * isize;
        let idx = match isize {
            1 => ibytes[o] as usize,
            2 => u16::from_le_bytes([ibytes[o], ibytes[o + 1]]) as usize,
            _ => u32::from_le_bytes([ibytes[o], ibytes[o + 1], ibytes[o + 2], ibytes[o + 3]])
                as usize,
        };
        if idx >= count {
            return Err(AccessorError::SparseIndex {
                name: name.to_owned(),
                index: idx,
                count,
            });
        }
        let vo = vals.offset() + k * elem;
        out[idx] = conv(&vbytes[vo..vo + elem]);
    }
    Ok(())
}

/// One component as f32, normalised per the glTF rules when `normalized`.
pub(super) fn component(dt: DataType, b: &[u8], normalized: bool) -> f32 {
    let scaled = |v: f32, max: f32, signed: bool| match (normalized, signed) {
        (false, _) => v,
        (true, false) => v / max,
        (true, true) => (v / max).max(-1.0),
    };
    match dt {
        DataType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        DataType::U8 => scaled(b[0] as f32, 255.0, false),
        DataType::I8 => scaled(b[0] as i8 as f32, 127.0, true),
        DataType::U16 => scaled(u16::from_le_bytes([b[0], b[1]]) as f32, 65535.0, false),
        DataType::I16 => scaled(i16::from_le_bytes([b[0], b[1]]) as f32, 32767.0, true),
        DataType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
    }
}

/// Reads a float attribute of `N` components (SCALAR for 1; any component type, normalised as
/// declared).
pub(super) fn read_vec<const N: usize>(
    acc: &gltf::Accessor,
    buffers: &Buffers,
    what: &str,
) -> Result<Vec<[f32; N]>, AccessorError> {
    let want = match N {
        1 => Dimensions::Scalar,
        2 => Dimensions::Vec2,
        3 => Dimensions::Vec3,
        _ => Dimensions::Vec4,
    };
    if acc.dimensions() != want {
        return Err(AccessorError::Type {
            what: what.to_owned(),
            index: acc.index(),
            found: acc.dimensions(),
            want,
        });
    }
    let dt = acc.data_type();
    let cs = dt.size();
    let norm = acc.normalized();
    read_elements(acc, buffers, |b| {
        let mut v = [0.0; N];
        for (k, c) in v.iter_mut().enumerate() {
            *c = component(dt, &b[k * cs..], norm);
        }
        v
    })
}

/// Reads a float SCALAR accessor.
pub(super) fn read_f32s(
    acc: &gltf::Accessor,
    buffers: &Buffers,
) -> Result<Vec<f32>, AccessorError> {
    read_elements(acc, buffers, |b| {
        f32::from_le_bytes([b[0], b[1], b[2], b[3]])
    })
}

/// Reads an index accessor (unsigned integer SCALAR).
pub(super) fn read_indices(
    acc: &gltf::Accessor,
    buffers: &Buffers,
) -> Result<Vec<u32>, AccessorError> {
    if acc.dimensions() != Dimensions::Scalar {
        return Err(AccessorError::IndexNotScalar(acc.index()));
    }
    let dt = acc.data_type();
    if !matches!(dt, DataType::U8 | DataType::U16 | DataType::U32) {
        return Err(AccessorError::IndexType {
            index: acc.index(),
            found: dt,
        });
    }
    read_elements(acc, buffers, |b| match dt {
        DataType::U8 => b[0] as u32,
        DataType::U16 => u16::from_le_bytes([b[0], b[1]]) as u32,
        _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
    })
}
