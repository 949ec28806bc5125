//! Safe calls into the vendored Draco decoder: one Draco mesh stream to its indices and attributes.
//! Buffer sizes are checked here before the C++ code sees a pointer; corrupt streams are errors.

use std::ffi::CStr;
use std::os::raw::{c_char, c_int, c_void};

extern "C" {
    fn glint_draco_decode(
        data: *const u8,
        len: usize,
        max_faces: u32,
        max_points: u32,
        out: *mut *mut c_void,
        err: *mut c_char,
        err_len: usize,
    ) -> c_int;
    fn glint_draco_free(handle: *mut c_void);
    fn glint_draco_counts(handle: *const c_void, faces: *mut u32, points: *mut u32);
    fn glint_draco_indices(handle: *const c_void, out: *mut u32, out_len: usize) -> c_int;
    fn glint_draco_attribute_components(handle: *const c_void, id: u32) -> c_int;
    fn glint_draco_attribute(
        handle: *const c_void,
        id: u32,
        component_type: c_int,
        components: c_int,
        out: *mut c_void,
        out_bytes: usize,
    ) -> c_int;
}

/// Why a Draco stream or one of its attributes could not be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DracoError {
    /// The decoder refused the stream (corrupt, not a mesh, or larger than the limits), with
    /// Draco's own message.
    Stream(String),
    /// The decoder ran out of memory.
    OutOfMemory,
    /// No attribute has this unique id.
    NoAttribute(u32),
    /// An attribute's values do not convert to the requested type (out of range or NaN).
    Convert(u32),
    /// The requested layout is not one this binding writes (component type or count).
    Layout,
    /// The decoded data is inconsistent (an index or value index out of range).
    Corrupt,
}

impl std::fmt::Display for DracoError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DracoError::Stream(m) if m.is_empty() => f.write_str("corrupt Draco stream"),
            DracoError::Stream(m) => write!(f, "corrupt Draco stream: {m}"),
            DracoError::OutOfMemory => f.write_str("out of memory while decoding"),
            DracoError::NoAttribute(id) => write!(f, "no Draco attribute with id {id}"),
            DracoError::Convert(id) => write!(
                f,
                "Draco attribute {id} has values that do not fit the accessor's component type"
            ),
            DracoError::Layout => f.write_str("unsupported component type or count"),
            DracoError::Corrupt => f.write_str("decoded indices or values out of range"),
        }
    }
}

impl std::error::Error for DracoError {}

/// glTF component types the attribute copy writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ComponentType {
    I8,
    U8,
    I16,
    U16,
    U32,
    F32,
}

impl ComponentType {
    /// The glTF `componentType` code.
    fn code(self) -> c_int {
        match self {
            ComponentType::I8 => 5120,
            ComponentType::U8 => 5121,
            ComponentType::I16 => 5122,
            ComponentType::U16 => 5123,
            ComponentType::U32 => 5125,
            ComponentType::F32 => 5126,
        }
    }

    /// Bytes per component.
    pub fn size(self) -> usize {
        match self {
            ComponentType::I8 | ComponentType::U8 => 1,
            ComponentType::I16 | ComponentType::U16 => 2,
            ComponentType::U32 | ComponentType::F32 => 4,
        }
    }
}

/// Upper bounds on what a stream may declare, checked by the decoder before it allocates.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    pub max_faces: u32,
    pub max_points: u32,
}

/// A decoded Draco mesh (owned by the C++ side until dropped).
pub struct Mesh {
    handle: *mut c_void,
    faces: u32,
    points: u32,
}

impl Drop for Mesh {
    fn drop(&mut self) {
        // SAFETY: `handle` came from a successful glint_draco_decode and is freed once.
        unsafe { glint_draco_free(self.handle) }
    }
}

/// Decodes one Draco mesh stream.
pub fn decode(data: &[u8], limits: Limits) -> Result<Mesh, DracoError> {
    let mut handle = std::ptr::null_mut();
    let mut msg = [0 as c_char; 256];
    // SAFETY: `data` is valid for `data.len()` bytes, `msg` for its length; the wrapper catches
    // every C++ exception and writes a NUL-terminated message.
    let rc = unsafe {
        glint_draco_decode(
            data.as_ptr(),
            data.len(),
            limits.max_faces,
            limits.max_points,
            &mut handle,
            msg.as_mut_ptr(),
            msg.len(),
        )
    };
    if rc != 0 || handle.is_null() {
        // SAFETY: the wrapper NUL-terminates within `msg` (or leaves it zeroed).
        let text = unsafe { CStr::from_ptr(msg.as_ptr()) }
            .to_string_lossy()
            .into_owned();
        return Err(if rc == 2 {
            DracoError::OutOfMemory
        } else {
            DracoError::Stream(text)
        });
    }
    let (mut faces, mut points) = (0, 0);
    // SAFETY: `handle` is a live mesh.
    unsafe { glint_draco_counts(handle, &mut faces, &mut points) };
    Ok(Mesh {
        handle,
        faces,
        points,
    })
}

fn status(rc: c_int, id: u32) -> Result<(), DracoError> {
    match rc {
        0 => Ok(()),
        2 => Err(DracoError::OutOfMemory),
        5 => Err(DracoError::Convert(id)),
        7 => Err(DracoError::NoAttribute(id)),
        6 | 8 => Err(DracoError::Layout),
        _ => Err(DracoError::Corrupt),
    }
}

impl Mesh {
    /// Triangles.
    pub fn faces(&self) -> u32 {
        self.faces
    }

    /// Vertices (Draco "points"), the count of every attribute.
    pub fn points(&self) -> u32 {
        self.points
    }

    /// The 3 * faces vertex indices, each below `points()`.
    pub fn indices(&self) -> Result<Vec<u32>, DracoError> {
        let mut out = vec![0u32; self.faces as usize * 3];
        // SAFETY: `out` holds exactly the `out.len()` indices written.
        status(
            unsafe { glint_draco_indices(self.handle, out.as_mut_ptr(), out.len()) },
            0,
        )?;
        Ok(out)
    }

    /// The component count of attribute `id`, or None when the stream has no such attribute.
    pub fn components(&self, id: u32) -> Option<usize> {
        // SAFETY: `handle` is a live mesh.
        let n = unsafe { glint_draco_attribute_components(self.handle, id) };
        (n > 0).then_some(n as usize)
    }

    /// Attribute `id` as `components` values of type `ty` per vertex, tightly packed
    /// (little-endian bytes, as a glTF buffer holds them).
    pub fn attribute(
        &self,
        id: u32,
        ty: ComponentType,
        components: usize,
    ) -> Result<Vec<u8>, DracoError> {
        if !(1..=16).contains(&components) {
            return Err(DracoError::Layout);
        }
        let bytes = self.points as usize * components * ty.size();
        // 4-byte aligned storage, so the C++ side may write floats and u32s in place.
        let mut words = vec![0u32; bytes.div_ceil(4)];
        // SAFETY: `words` holds at least `bytes` bytes, 4-byte aligned.
        let rc = unsafe {
            glint_draco_attribute(
                self.handle,
                id,
                ty.code(),
                components as c_int,
                words.as_mut_ptr().cast(),
                bytes,
            )
        };
        status(rc, id)?;
        let mut out: Vec<u8> = words.iter().flat_map(|w| w.to_ne_bytes()).collect();
        out.truncate(bytes);
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIMITS: Limits = Limits {
        max_faces: 1 << 20,
        max_points: 1 << 20,
    };

    #[test]
    fn garbage_and_empty_streams_are_errors() {
        assert!(matches!(decode(&[], LIMITS), Err(DracoError::Stream(_))));
        let e = decode(b"DRACO\x02\x02\x01\x01\x00\x00\xff\xff\xff\xff\x0f", LIMITS)
            .err()
            .unwrap();
        assert!(matches!(e, DracoError::Stream(_)), "{e}");
        assert!(decode(&[0x55; 64], LIMITS).is_err());
    }

    /// The shared Box's Draco stream (118 bytes), when the shared assets are present.
    fn shared_box() -> Option<Vec<u8>> {
        let bin = std::fs::read("/work/shared/assets/gltf/Box/glTF-Draco/Box.bin").ok()?;
        Some(bin[..118].to_vec())
    }

    #[test]
    fn the_shared_box_decodes_and_its_corruptions_are_errors() {
        let Some(stream) = shared_box() else {
            eprintln!("skipped: /work/shared/assets is absent");
            return;
        };
        let mesh = decode(&stream, LIMITS).unwrap();
        assert_eq!((mesh.faces(), mesh.points()), (12, 24));
        let idx = mesh.indices().unwrap();
        assert!(idx.iter().all(|&i| i < 24));
        assert_eq!(mesh.components(1), Some(3));
        let pos = mesh.attribute(1, ComponentType::F32, 3).unwrap();
        let p: Vec<f32> = pos
            .chunks(4)
            .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
            .collect();
        assert!(p.iter().all(|v| (v.abs() - 0.5).abs() < 1e-3), "{p:?}");
        assert_eq!(mesh.components(7), None);
        assert_eq!(
            mesh.attribute(7, ComponentType::F32, 3).err(),
            Some(DracoError::NoAttribute(7))
        );
        let tight = Limits {
            max_faces: 11,
            max_points: 24,
        };
        assert!(decode(&stream, tight).is_err());
        for cut in 0..stream.len() {
            let _ = decode(&stream[..cut], LIMITS).map(|m| m.indices());
        }
        for at in 0..stream.len() * 8 {
            let mut s = stream.clone();
            s[at / 8] ^= 1 << (at % 8);
            if let Ok(m) = decode(&s, LIMITS) {
                assert!(m.faces() <= LIMITS.max_faces);
                let _ = m.indices();
                let _ = m.attribute(0, ComponentType::F32, 3);
            }
        }
    }
}
