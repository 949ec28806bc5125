//! What can be wrong with a glTF file, as typed errors whose text names the element concerned.
//! `load` turns the one that stops loading into a `LoadError`; image problems only become warnings.

use gltf::accessor::{DataType, Dimensions};
use thiserror::Error;

/// A problem that stops a glTF file from loading.
#[derive(Debug, Error)]
pub enum GltfError {
    #[error("cannot read file: {0}")]
    Read(std::io::Error),
    #[error(transparent)]
    Glb(#[from] GlbError),
    #[error("invalid JSON: {0}")]
    Json(gltf::json::Error),
    #[error("requires unsupported extension {0}")]
    UnsupportedExtension(String),
    /// The first validation problems (`path: problem`), and how many there are in all.
    #[error("invalid glTF: {}{}", .first.join("; "), more(.first.len(), *.total))]
    Validation { first: Vec<String>, total: usize },
    #[error("invalid glTF: {0}")]
    Document(gltf::Error),
    /// `what` names the buffer, its source included.
    #[error("{what}: {problem}")]
    Buffer {
        what: String,
        problem: BufferProblem,
    },
    #[error(transparent)]
    Accessor(#[from] AccessorError),
    #[error(transparent)]
    Meshopt(#[from] MeshoptError),
    #[error(transparent)]
    Draco(#[from] DracoError),
    /// A problem inside the element `at` (a primitive, a skin, an animation channel).
    #[error("{at}: {source}")]
    At { at: String, source: Box<GltfError> },
    #[error("{at}: no sampler {sampler} in the animation")]
    PointerSampler { at: String, sampler: usize },
    #[error("no {asked} (the file's scenes: {})", if .names.is_empty() { "none".to_string() } else { .names.join(", ") })]
    NoScene { asked: String, names: Vec<String> },
    #[error("no animation {index} (the file has {count})")]
    NoAnimation { index: usize, count: usize },
    #[error("{what} has {len} elements but POSITION has {vertices}")]
    AttributeLength {
        what: String,
        len: usize,
        vertices: usize,
    },
    #[error("vertex index {index} out of range (the primitive has {vertices} vertices)")]
    VertexIndex { index: u32, vertices: usize },
    #[error("morph target {0}: displacements are not finite")]
    MorphNotFinite(usize),
    #[error("weights accessor {0} is not SCALAR")]
    WeightsNotScalar(usize),
    #[error("{weights} weights do not divide into {elements} key elements (or are not finite)")]
    WeightsShape { weights: usize, elements: usize },
    #[error("input accessor {0} is not a float SCALAR")]
    KeyTimesType(usize),
    #[error("key times are not finite and increasing")]
    KeyTimesOrder,
    #[error("{values} output values for {keys} keys (expected {expected})")]
    OutputCount {
        values: usize,
        keys: usize,
        expected: usize,
    },
    #[error("output values are not finite")]
    OutputNotFinite,
    #[error("skin out of range")]
    SkinOutOfRange,
    #[error("skin {skin}: inverse bind matrices accessor {accessor} is not a float MAT4")]
    InverseBindType { skin: usize, accessor: usize },
    #[error("skin {skin}: {matrices} inverse bind matrices for {joints} joints")]
    InverseBindCount {
        skin: usize,
        matrices: usize,
        joints: usize,
    },
    #[error(
        "{node}: EXT_mesh_gpu_instancing places {count} instances, more than the {} glint accepts",
        crate::scene::limits::MAX_INSTANCES
    )]
    TooManyInstances { node: String, count: usize },
    #[error("EXT_mesh_gpu_instancing: {attribute} names accessor {index}, which does not exist")]
    InstancingAccessor { attribute: String, index: usize },
    #[error("EXT_mesh_gpu_instancing: {first} has {count} instances but {other} has {len}")]
    InstancingCount {
        first: String,
        count: usize,
        other: String,
        len: usize,
    },
    #[error("mesh {mesh}: JOINTS_0 names joint {joint} but skin {skin} has {joints}")]
    JointOutOfRange {
        mesh: u32,
        joint: u16,
        skin: usize,
        joints: usize,
    },
}

impl GltfError {
    /// This error, as met inside the element `at`.
    pub fn at(self, at: impl Into<String>) -> Self {
        GltfError::At {
            at: at.into(),
            source: Box::new(self),
        }
    }
}

fn more(shown: usize, total: usize) -> String {
    if total > shown {
        format!(" (and {} more)", total - shown)
    } else {
        String::new()
    }
}

/// A binary glTF whose framing (header, chunks) is wrong.
#[derive(Debug, Error)]
pub enum GlbError {
    #[error("truncated .glb: {0} bytes, shorter than the 12-byte header")]
    NoHeader(usize),
    #[error("unsupported .glb version {0} (only glTF 2.0 is supported)")]
    Version(u32),
    #[error("truncated .glb: header says {length} bytes but the file has {file}")]
    Length { length: usize, file: usize },
    #[error("corrupt .glb: total length {0} leaves no room for a JSON chunk")]
    NoRoom(usize),
    #[error("truncated .glb: incomplete header of chunk {0}")]
    ChunkHeader(usize),
    #[error("truncated .glb: chunk {chunk} says {len} bytes but only {remain} remain")]
    Chunk {
        chunk: usize,
        len: usize,
        remain: usize,
    },
    #[error("corrupt .glb: the first chunk is not JSON")]
    FirstNotJson,
    #[error("truncated .glb: no JSON chunk")]
    NoJson,
}

/// Why a buffer's data cannot be had.
#[derive(Debug, Error)]
pub enum BufferProblem {
    #[error("malformed URI")]
    MalformedUri,
    #[error("cannot read external buffer file: {0}")]
    Io(std::io::Error),
    #[error("the .glb has no BIN chunk")]
    NoBin,
    #[error("{0}")]
    Source(gltf::Error),
    #[error("truncated: byteLength is {declared} but only {present} bytes are present")]
    Truncated { declared: usize, present: usize },
}

/// A buffer view that does not fit its buffer.
#[derive(Debug, Error)]
pub enum ViewError {
    #[error("buffer view {0}: buffer missing")]
    BufferMissing(usize),
    #[error("buffer view {view} out of bounds: bytes {start}..{end} of a {len}-byte buffer")]
    OutOfBounds {
        view: usize,
        start: usize,
        end: usize,
        len: usize,
    },
}

/// An accessor that cannot be read as the attribute it serves; `name` is `accessor N ('name')`.
#[derive(Debug, Error)]
pub enum AccessorError {
    #[error("{name}: count {count} is too large")]
    TooLarge { name: String, count: usize },
    /// The file reads more out of its buffers than they can reasonably hold (see `buffers.rs`).
    #[error("{name}: reading {count} more elements exceeds what the file's buffers can hold (a file that reuses or invents data on this scale is refused)")]
    Budget { name: String, count: usize },
    #[error("{name}: {source}")]
    View { name: String, source: ViewError },
    #[error("{name}: byteStride {stride} is smaller than the element size {elem}")]
    Stride {
        name: String,
        stride: usize,
        elem: usize,
    },
    #[error(
        "{name} out of bounds: {count} elements of {elem} bytes (stride {stride}) from offset \
         {offset} need more than the {len} bytes of buffer view {view}"
    )]
    OutOfBounds {
        name: String,
        count: usize,
        elem: usize,
        stride: usize,
        offset: usize,
        len: usize,
        view: usize,
    },
    #[error("{name} sparse: {source}")]
    SparseView { name: String, source: ViewError },
    #[error("{name}: sparse data out of bounds")]
    SparseOutOfBounds { name: String },
    #[error("{name}: sparse index {index} out of range (count {count})")]
    SparseIndex {
        name: String,
        index: usize,
        count: usize,
    },
    #[error("{what} accessor {index} has type {found:?}, expected {want:?}")]
    Type {
        what: String,
        index: usize,
        found: Dimensions,
        want: Dimensions,
    },
    #[error("index accessor {0} is not SCALAR")]
    IndexNotScalar(usize),
    #[error("index accessor {index} has component type {found:?}, expected an unsigned integer")]
    IndexType { index: usize, found: DataType },
}

/// A meshopt-compressed buffer view that cannot be decoded.
#[derive(Debug, Error)]
pub enum MeshoptError {
    #[error("buffer view {view}: invalid meshopt compression object: {source}")]
    Json {
        view: usize,
        source: serde_json::Error,
    },
    #[error("buffer view {0}: the COLOR filter needs KHR_meshopt_compression, not EXT_")]
    ColorFilterInExt(usize),
    #[error("buffer view {view}: meshopt data in buffer {buffer}, which does not exist")]
    NoBuffer { view: usize, buffer: usize },
    #[error(
        "buffer view {view}: meshopt data (bytes {start}..+{len} of buffer {buffer}) out of \
         bounds of its {have} bytes"
    )]
    OutOfBounds {
        view: usize,
        buffer: usize,
        start: usize,
        len: usize,
        have: usize,
    },
    #[error("buffer view {view}: meshopt: {problem}")]
    Stream { view: usize, problem: String },
    #[error("too many buffers")]
    TooMany,
}

/// A KHR_draco_mesh_compression primitive that cannot be decoded; `at` names the mesh and
/// primitive.
#[derive(Debug, Error)]
#[error("{at}: KHR_draco_mesh_compression: {problem}")]
pub struct DracoError {
    pub at: String,
    pub problem: String,
}

/// Why an image is ignored (a warning, not an error: the texture is left out).
#[derive(Debug, Error)]
pub enum ImageError {
    #[error(transparent)]
    View(#[from] ViewError),
    #[error(transparent)]
    Decode(#[from] crate::scene::decode::DecodeError),
    #[error("malformed URI")]
    MalformedUri,
    #[error("cannot read image file: {0}")]
    Io(std::io::Error),
    #[error("cannot decode image: {0}")]
    Source(gltf::Error),
    #[error("embedded in a buffer view without the mimeType the spec requires")]
    NoMimeType,
    #[error("neither a uri nor a buffer view")]
    NoSource,
}
