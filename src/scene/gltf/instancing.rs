//! EXT_mesh_gpu_instancing: a node's per-instance TRANSLATION, ROTATION and SCALE accessors read into
//! local transforms, each of which places the node's mesh once more (as a shared mesh is placed).

use glam::{Mat4, Quat, Vec3};

use super::accessor::read_vec;
use super::error::GltfError;
use super::Loader;

const EXT: &str = "EXT_mesh_gpu_instancing";

impl Loader<'_> {
    /// The node's instance transforms (relative to the node), or None when it does not use the
    /// extension. Every attribute must have the same count; a missing one is the identity.
    pub(super) fn gpu_instances(&self, node: &gltf::Node) -> Result<Option<Vec<Mat4>>, GltfError> {
        let Some(attrs) = node
            .extension_value(EXT)
            .and_then(|e| e.get("attributes"))
            .and_then(|a| a.as_object())
        else {
            return Ok(None);
        };
        let accessor = |name: &str| -> Result<Option<gltf::Accessor>, GltfError> {
            let Some(v) = attrs.get(name) else {
                return Ok(None);
            };
            let index = v.as_u64().unwrap_or(u64::MAX) as usize;
            match self.doc.accessors().nth(index) {
                Some(a) => Ok(Some(a)),
                None => Err(GltfError::InstancingAccessor {
                    attribute: name.to_owned(),
                    index,
                }),
            }
        };
        let vec3 = |name: &str| -> Result<Option<Vec<Vec3>>, GltfError> {
            let Some(a) = accessor(name)? else {
                return Ok(None);
            };
            let what = format!("{EXT} {name}");
            Ok(Some(
                read_vec::<3>(&a, self.buffers, &what)?
                    .into_iter()
                    .map(Vec3::from)
                    .collect(),
            ))
        };
        let t = vec3("TRANSLATION")?;
        let s = vec3("SCALE")?;
        let r: Option<Vec<Quat>> = match accessor("ROTATION")? {
            Some(a) => Some(
                read_vec::<4>(&a, self.buffers, &format!("{EXT} ROTATION"))?
                    .into_iter()
                    .map(|q| Quat::from_array(q).normalize())
                    .collect(),
            ),
            None => None,
        };
        let counts = [
            ("TRANSLATION", t.as_ref().map(Vec::len)),
            ("ROTATION", r.as_ref().map(Vec::len)),
            ("SCALE", s.as_ref().map(Vec::len)),
        ];
        let present: Vec<(&str, usize)> = counts
            .iter()
            .filter_map(|&(n, c)| c.map(|c| (n, c)))
            .collect();
        let Some(&(first, count)) = present.first() else {
            return Ok(Some(Vec::new()));
        };
        if let Some(&(other, len)) = present.iter().find(|(_, c)| *c != count) {
            return Err(GltfError::InstancingCount {
                first: first.to_owned(),
                count,
                other: other.to_owned(),
                len,
            });
        }
        Ok(Some(
            (0..count)
                .map(|i| {
                    Mat4::from_scale_rotation_translation(
                        s.as_ref().map_or(Vec3::ONE, |s| s[i]),
                        r.as_ref().map_or(Quat::IDENTITY, |r| r[i]),
                        t.as_ref().map_or(Vec3::ZERO, |t| t[i]),
                    )
                })
                .collect(),
        ))
    }
}
