//! KHR_draco_mesh_compression: each compressed primitive's Draco stream decoded (through the vendored
//! Draco decoder) into fresh buffers, and its attributes and indices re-pointed at them.
//!
//! Runs on the JSON before the loader, like meshopt: for each attribute the extension maps, a copy of
//! the primitive's fallback accessor (which gives count, type, componentType and normalized) is
//! pointed at the decoded values, and the primitive at the copy, so the rest of the loader reads
//! plain accessors. The counts those accessors declare bound the decoder before it allocates.

use std::collections::BTreeMap;

use glint_draco::{ComponentType, Limits};
use gltf::json::validation::{Checked, USize64};
use gltf::json::{self, Index};
use serde::Deserialize;

use super::error::DracoError;
use crate::scene::limits::MAX_WORLD_TRIANGLES;

pub(super) const EXTENSION: &str = "KHR_draco_mesh_compression";

/// Most vertices one compressed primitive may declare (three per triangle of the world's limit).
const MAX_POINTS: usize = 3 * MAX_WORLD_TRIANGLES;

/// The extension object of a compressed primitive.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "camelCase")]
struct Compressed {
    buffer_view: usize,
    attributes: BTreeMap<String, u32>,
}

/// How messages name a primitive.
fn label(mesh: &json::Mesh, mi: usize, pi: usize) -> String {
    match &mesh.name {
        Some(n) => format!("mesh {mi} ('{n}') primitive {pi}"),
        None => format!("mesh {mi} primitive {pi}"),
    }
}

/// Decodes every Draco-compressed primitive of `doc` into new buffers appended to `buffers`, and
/// returns the document with those primitives reading them (the same document when none is).
pub(super) fn decode_primitives(
    doc: gltf::Document,
    buffers: &mut Vec<Vec<u8>>,
    warnings: &mut Vec<String>,
) -> Result<gltf::Document, DracoError> {
    let compressed = doc
        .meshes()
        .flat_map(|m| m.primitives())
        .any(|p| p.extension_value(EXTENSION).is_some());
    if !compressed {
        return Ok(doc);
    }
    let mut root = doc.into_json();
    for mi in 0..root.meshes.len() {
        for pi in 0..root.meshes[mi].primitives.len() {
            let Some(value) = root.meshes[mi].primitives[pi]
                .extensions
                .as_mut()
                .and_then(|e| e.others.remove(EXTENSION))
            else {
                continue;
            };
            let at = label(&root.meshes[mi], mi, pi);
            let ext: Compressed = serde_json::from_value(value).map_err(|e| DracoError {
                at: at.clone(),
                problem: format!("invalid extension object: {e}"),
            })?;
            let reordered =
                decode_primitive(&mut root, buffers, (mi, pi), &ext).map_err(|problem| {
                    DracoError {
                        at: at.clone(),
                        problem,
                    }
                })?;
            let has_targets = root.meshes[mi].primitives[pi]
                .targets
                .as_ref()
                .is_some_and(|t| !t.is_empty());
            if reordered && has_targets {
                warnings.push(format!(
                    "{at}: the Draco stream is edgebreaker-coded, which reorders vertices, but the morph targets are not in it; they may not line up"
                ));
            }
        }
    }
    // Only accessors, views, buffers and primitives changed; each new view fits its buffer exactly.
    Ok(gltf::Document::from_json_without_validation(root))
}

/// The validation paths (`accessors[N].bufferView`) of the accessors Draco primitives read, whose
/// missing buffer views the loader tolerates: the decoded data replaces them.
pub(super) fn fallback_views(root: &json::Root) -> Vec<String> {
    let mut out = Vec::new();
    for prim in root.meshes.iter().flat_map(|m| &m.primitives) {
        let compressed = prim
            .extensions
            .as_ref()
            .is_some_and(|e| e.others.contains_key(EXTENSION));
        if compressed {
            let accessors = prim.attributes.values().chain(prim.indices.as_ref());
            out.extend(accessors.map(|a| format!("accessors[{}].bufferView", a.value())));
        }
    }
    out
}

/// The bytes of buffer view `view`, checked against its buffer.
fn view_bytes<'a>(
    root: &json::Root,
    buffers: &'a [Vec<u8>],
    view: usize,
) -> Result<&'a [u8], String> {
    let v = root
        .buffer_views
        .get(view)
        .ok_or_else(|| format!("buffer view {view} does not exist"))?;
    let b = v.buffer.value();
    let data = buffers
        .get(b)
        .ok_or_else(|| format!("buffer view {view}: buffer {b} does not exist"))?;
    let start = v.byte_offset.map_or(0, |o| o.0) as usize;
    let len = v.byte_length.0 as usize;
    start
        .checked_add(len)
        .filter(|&end| end <= data.len())
        .map(|end| &data[start..end])
        .ok_or_else(|| {
            format!(
                "buffer view {view} (bytes {start}..+{len}) out of bounds of buffer {b}'s {} bytes",
                data.len()
            )
        })
}

/// The accessor `index` of the primitive, with its count (bounded by glint's limits).
fn accessor(root: &json::Root, index: usize, what: &str) -> Result<(json::Accessor, u32), String> {
    let a = root
        .accessors
        .get(index)
        .ok_or_else(|| format!("{what} accessor {index} does not exist"))?;
    let count = a.count.0 as usize;
    if count > MAX_POINTS {
        return Err(format!(
            "{what} accessor {index} declares {count} elements, more than the {MAX_POINTS} glint accepts"
        ));
    }
    Ok((a.clone(), count as u32))
}

fn component_type(a: &json::Accessor) -> Option<ComponentType> {
    use json::accessor::ComponentType as C;
    match a.component_type {
        Checked::Valid(json::accessor::GenericComponentType(t)) => Some(match t {
            C::I8 => ComponentType::I8,
            C::U8 => ComponentType::U8,
            C::I16 => ComponentType::I16,
            C::U16 => ComponentType::U16,
            C::U32 => ComponentType::U32,
            C::F32 => ComponentType::F32,
        }),
        Checked::Invalid => None,
    }
}

/// Appends `data` as a new buffer with one view over all of it, and a copy of `template` reading
/// it; returns the new accessor's index.
fn push_accessor(
    root: &mut json::Root,
    buffers: &mut Vec<Vec<u8>>,
    mut template: json::Accessor,
    data: Vec<u8>,
) -> Result<Index<json::Accessor>, String> {
    let too_many = || "too many buffers".to_string();
    let buffer = u32::try_from(root.buffers.len()).map_err(|_| too_many())?;
    let view = u32::try_from(root.buffer_views.len()).map_err(|_| too_many())?;
    let accessor = u32::try_from(root.accessors.len()).map_err(|_| too_many())?;
    root.buffers.push(json::Buffer {
        byte_length: USize64::from(data.len()),
        name: None,
        uri: None,
        extensions: None,
        extras: Default::default(),
    });
    root.buffer_views.push(json::buffer::View {
        buffer: Index::new(buffer),
        byte_length: USize64::from(data.len()),
        byte_offset: None,
        byte_stride: None,
        name: None,
        target: None,
        extensions: None,
        extras: Default::default(),
    });
    buffers.push(data);
    template.buffer_view = Some(Index::new(view));
    template.byte_offset = None;
    template.sparse = None;
    root.accessors.push(template);
    Ok(Index::new(accessor))
}

/// An attribute the extension maps: semantic, name, Draco id, fallback accessor, its count.
type Mapped = (
    Checked<json::mesh::Semantic>,
    String,
    u32,
    json::Accessor,
    u32,
);

/// The primitive's attributes that the extension maps, each with its fallback accessor; an error
/// when the extension maps one the primitive lacks.
fn mapped_attributes(
    root: &json::Root,
    prim: &json::mesh::Primitive,
    ext: &Compressed,
) -> Result<Vec<Mapped>, String> {
    let mut mapped = Vec::new();
    for (semantic, index) in &prim.attributes {
        let name = semantic.to_string();
        if let Some(&id) = ext.attributes.get(&name) {
            let (a, count) = accessor(root, index.value(), &name)?;
            mapped.push((semantic.clone(), name, id, a, count));
        }
    }
    if let Some(name) = ext
        .attributes
        .keys()
        .find(|n| !mapped.iter().any(|m| &m.1 == *n))
    {
        return Err(format!(
            "the extension maps attribute {name}, which the primitive does not have"
        ));
    }
    Ok(mapped)
}

/// Decodes one primitive's stream and re-points its attributes and indices at the decoded data.
fn decode_primitive(
    root: &mut json::Root,
    buffers: &mut Vec<Vec<u8>>,
    (mi, pi): (usize, usize),
    ext: &Compressed,
) -> Result<bool, String> {
    let prim = root.meshes[mi].primitives[pi].clone();
    let mapped = mapped_attributes(root, &prim, ext)?;
    let indices = match prim.indices {
        Some(i) => Some(accessor(root, i.value(), "indices")?),
        None => None,
    };
    let limits = Limits {
        max_faces: indices
            .as_ref()
            .map_or(MAX_WORLD_TRIANGLES as u32, |(_, count)| *count / 3),
        max_points: mapped.iter().map(|m| m.4).max().unwrap_or(0),
    };
    let stream = view_bytes(root, buffers, ext.buffer_view)?;
    // Header: "DRACO", version major and minor, encoder type, method (0 sequential, which keeps
    // the vertex order; 1 edgebreaker, which does not).
    let reorders = stream.get(8) == Some(&1);
    let mesh = glint_draco::decode(stream, limits).map_err(|e| e.to_string())?;
    let mut fresh = Vec::with_capacity(mapped.len());
    for (semantic, name, id, a, count) in mapped {
        let data = attribute(&mesh, &name, id, &a, count)?;
        fresh.push((semantic, push_accessor(root, buffers, a, data)?));
    }
    let idx = mesh.indices().map_err(|e| e.to_string())?;
    let (mut template, count) =
        indices.unwrap_or_else(|| (index_template(idx.len()), idx.len() as u32));
    if count as usize != idx.len() {
        return Err(format!(
            "the indices accessor has {count} elements but the Draco stream {} ({} triangles)",
            idx.len(),
            mesh.faces()
        ));
    }
    template.component_type = Checked::Valid(json::accessor::GenericComponentType(
        json::accessor::ComponentType::U32,
    ));
    let bytes = idx.iter().flat_map(|i| i.to_le_bytes()).collect();
    let indices = push_accessor(root, buffers, template, bytes)?;
    let prim = &mut root.meshes[mi].primitives[pi];
    for (semantic, index) in fresh {
        prim.attributes.insert(semantic, index);
    }
    prim.indices = Some(indices);
    Ok(reorders)
}

/// The decoded values of Draco attribute `id` in the layout of fallback accessor `a` (`count`
/// elements, which must be the stream's vertex count).
fn attribute(
    mesh: &glint_draco::Mesh,
    name: &str,
    id: u32,
    a: &json::Accessor,
    count: u32,
) -> Result<Vec<u8>, String> {
    if count != mesh.points() {
        return Err(format!(
            "{name}: the accessor has {count} elements but the Draco stream {} vertices",
            mesh.points()
        ));
    }
    let ty = component_type(a).ok_or_else(|| format!("{name}: invalid component type"))?;
    let components = match a.type_ {
        Checked::Valid(t) => t.multiplicity(),
        Checked::Invalid => return Err(format!("{name}: invalid accessor type")),
    };
    if mesh.components(id).is_none() {
        return Err(format!(
            "{name}: the Draco stream has no attribute with id {id}"
        ));
    }
    mesh.attribute(id, ty, components)
        .map_err(|e| format!("{name}: {e}"))
}

/// An index accessor for a compressed primitive that has none in the file (the stream always has).
fn index_template(count: usize) -> json::Accessor {
    json::Accessor {
        buffer_view: None,
        byte_offset: None,
        count: USize64::from(count),
        component_type: Checked::Valid(json::accessor::GenericComponentType(
            json::accessor::ComponentType::U32,
        )),
        extensions: None,
        extras: Default::default(),
        type_: Checked::Valid(json::accessor::Type::Scalar),
        min: None,
        max: None,
        name: None,
        normalized: false,
        sparse: None,
    }
}

#[cfg(test)]
#[path = "draco_tests.rs"]
mod tests;
