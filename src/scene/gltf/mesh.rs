//! glTF primitives to scene `Mesh`es: attributes read and checked against POSITION, strips and fans
//! made triangles, the mesh cleaned, and the skin and morph attributes of its kept vertices.

use glam::{Vec2, Vec3, Vec4};
use gltf::mesh::Mode;

use super::accessor::{read_indices, read_vec};
use super::error::GltfError;
use super::{Loader, MorphTarget, SkinAttrs};
use crate::scene::mesh::{Cleaned, UV_SETS};
use crate::scene::Mesh;

/// A primitive made a scene mesh, with the per-vertex data posing needs beside it.
struct Built {
    mesh: Mesh,
    skin: Option<SkinAttrs>,
    morph: Option<Vec<MorphTarget>>,
}

impl Loader<'_> {
    /// The scene mesh of a (mesh, primitive) pair, built on first use; None when skipped.
    pub(super) fn primitive(
        &mut self,
        mesh: &gltf::Mesh,
        prim: &gltf::Primitive,
    ) -> Result<Option<u32>, GltfError> {
        let key = (mesh.index(), prim.index());
        if let Some(m) = self.prims.get(&key) {
            return Ok(*m);
        }
        let label = match mesh.name() {
            Some(n) => format!("mesh {} ('{n}'), primitive {}", mesh.index(), prim.index()),
            None => format!("mesh {}, primitive {}", mesh.index(), prim.index()),
        };
        let built = self
            .build_primitive(mesh, prim, &label)
            .map_err(|e| e.at(label.as_str()))?;
        let out = built.map(|b| {
            self.scene.meshes.push(b.mesh);
            let index = (self.scene.meshes.len() - 1) as u32;
            self.variant_mappings(prim, index, &label);
            if let Some(attrs) = b.skin {
                self.skin_attrs.insert(index, attrs);
            }
            if let Some(targets) = b.morph {
                self.morph_attrs.insert(index, targets);
            }
            index
        });
        self.prims.insert(key, out);
        Ok(out)
    }

    fn build_primitive(
        &mut self,
        mesh: &gltf::Mesh,
        prim: &gltf::Primitive,
        label: &str,
    ) -> Result<Option<Built>, GltfError> {
        let mode = prim.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            self.scene
                .warnings
                .push(format!("{label}: mode {mode:?} is not triangles; skipped"));
            return Ok(None);
        }
        let Some(mut m) = self.read_mesh(mesh, prim)? else {
            self.scene
                .warnings
                .push(format!("{label}: no POSITION attribute; skipped"));
            return Ok(None);
        };
        let n = m.positions.len();
        let cleaned = m.clean_with_order();
        self.dropped += cleaned.dropped;
        let skin = self.skin_attrs(prim, n, &cleaned, m.positions.len())?;
        let morph = self.morph_targets(prim, n, &cleaned, m.positions.len())?;
        if m.indices.is_empty() {
            self.scene
                .warnings
                .push(format!("{label}: no valid triangles; skipped"));
            return Ok(None);
        }
        Ok(Some(Built {
            mesh: m,
            skin,
            morph,
        }))
    }

    /// The primitive's attributes and triangles, before cleaning; None without POSITION.
    fn read_mesh(
        &mut self,
        mesh: &gltf::Mesh,
        prim: &gltf::Primitive,
    ) -> Result<Option<Mesh>, GltfError> {
        let Some(pos_acc) = prim.get(&gltf::Semantic::Positions) else {
            return Ok(None);
        };
        let positions: Vec<Vec3> = read_vec::<3>(&pos_acc, self.buffers, "POSITION")?
            .into_iter()
            .map(Vec3::from)
            .collect();
        let n = positions.len();
        let normals = self.attribute::<3>(prim, gltf::Semantic::Normals, "NORMAL", n)?;
        let uvs = self.attribute::<2>(prim, gltf::Semantic::TexCoords(0), "TEXCOORD_0", n)?;
        let tangents = self.attribute::<4>(prim, gltf::Semantic::Tangents, "TANGENT", n)?;
        let uv_sets = (1..UV_SETS as u32)
            .map(|k| {
                let what = format!("TEXCOORD_{k}");
                let set = self.attribute::<2>(prim, gltf::Semantic::TexCoords(k), &what, n)?;
                Ok(set.into_iter().map(Vec2::from).collect())
            })
            .collect::<Result<Vec<Vec<Vec2>>, GltfError>>()?;
        let colors = self.colors(prim, n)?;
        let flat: Vec<u32> = match prim.indices() {
            Some(a) => {
                let idx = read_indices(&a, self.buffers)?;
                if let Some(&bad) = idx.iter().find(|&&i| i as usize >= n) {
                    return Err(GltfError::VertexIndex {
                        index: bad,
                        vertices: n,
                    });
                }
                idx
            }
            None => (0..n as u32).collect(),
        };
        let material = match prim.material().index() {
            Some(i) => i as u32,
            None => self.default_material(),
        };
        Ok(Some(Mesh {
            name: match mesh.name() {
                Some(name) if mesh.primitives().len() > 1 => format!("{name}/{}", prim.index()),
                Some(name) => name.to_owned(),
                None => format!("mesh {}/{}", mesh.index(), prim.index()),
            },
            positions,
            normals: normals.into_iter().map(Vec3::from).collect(),
            uvs: uvs.into_iter().map(Vec2::from).collect(),
            tangents: tangents.into_iter().map(Vec4::from).collect(),
            indices: triangles(prim.mode(), &flat),
            material,
            uv_sets,
            colors,
        }))
    }

    /// A float attribute of `N` components with one value per vertex; empty when absent.
    fn attribute<const N: usize>(
        &self,
        prim: &gltf::Primitive,
        semantic: gltf::Semantic,
        what: &str,
        vertices: usize,
    ) -> Result<Vec<[f32; N]>, GltfError> {
        match prim.get(&semantic) {
            Some(a) => {
                let v = read_vec::<N>(&a, self.buffers, what)?;
                check_len(what, v.len(), vertices)?;
                Ok(v)
            }
            None => Ok(Vec::new()),
        }
    }

    /// COLOR_0 as linear RGBA (RGB gets alpha 1); empty when absent.
    fn colors(&self, prim: &gltf::Primitive, vertices: usize) -> Result<Vec<Vec4>, GltfError> {
        let Some(a) = prim.get(&gltf::Semantic::Colors(0)) else {
            return Ok(Vec::new());
        };
        let colors: Vec<Vec4> = if a.dimensions() == gltf::accessor::Dimensions::Vec3 {
            read_vec::<3>(&a, self.buffers, "COLOR_0")?
                .into_iter()
                .map(|c| Vec3::from(c).extend(1.0))
                .collect()
        } else {
            read_vec::<4>(&a, self.buffers, "COLOR_0")?
                .into_iter()
                .map(Vec4::from)
                .collect()
        };
        check_len("COLOR_0", colors.len(), vertices)?;
        Ok(colors)
    }

    /// JOINTS_0 and WEIGHTS_0 of the kept vertices, when the primitive has both.
    fn skin_attrs(
        &self,
        prim: &gltf::Primitive,
        vertices: usize,
        cleaned: &Cleaned,
        kept: usize,
    ) -> Result<Option<SkinAttrs>, GltfError> {
        let (Some(j), Some(w)) = (
            prim.get(&gltf::Semantic::Joints(0)),
            prim.get(&gltf::Semantic::Weights(0)),
        ) else {
            return Ok(None);
        };
        let joints = read_vec::<4>(&j, self.buffers, "JOINTS_0")?;
        let weights = read_vec::<4>(&w, self.buffers, "WEIGHTS_0")?;
        check_len("JOINTS_0", joints.len(), vertices)?;
        check_len("WEIGHTS_0", weights.len(), vertices)?;
        let joints: Vec<[u16; 4]> = (0..kept)
            .map(|k| joints[cleaned.original(k)].map(|x| x.clamp(0.0, u16::MAX as f32) as u16))
            .collect();
        let weights: Vec<Vec4> = (0..kept)
            .map(|k| Vec4::from(weights[cleaned.original(k)]))
            .collect();
        Ok(Some((joints, weights)))
    }

    /// The position and normal displacements of every morph target, for the kept vertices.
    fn morph_targets(
        &self,
        prim: &gltf::Primitive,
        vertices: usize,
        cleaned: &Cleaned,
        kept: usize,
    ) -> Result<Option<Vec<MorphTarget>>, GltfError> {
        if prim.morph_targets().len() == 0 {
            return Ok(None);
        }
        let mut targets = Vec::new();
        for (ti, target) in prim.morph_targets().enumerate() {
            let what = format!("morph target {ti}");
            let read = |acc: Option<gltf::Accessor>| -> Result<Vec<Vec3>, GltfError> {
                match acc {
                    Some(a) => {
                        let v = read_vec::<3>(&a, self.buffers, &what)?;
                        check_len(&what, v.len(), vertices)?;
                        Ok((0..kept)
                            .map(|k| Vec3::from(v[cleaned.original(k)]))
                            .collect())
                    }
                    None => Ok(Vec::new()),
                }
            };
            let dp = read(target.positions())?;
            let dn = read(target.normals())?;
            let dp = if dp.is_empty() {
                vec![Vec3::ZERO; kept]
            } else {
                dp
            };
            if dp.iter().chain(&dn).any(|d| !d.is_finite()) {
                return Err(GltfError::MorphNotFinite(ti));
            }
            targets.push((dp, dn));
        }
        Ok(Some(targets))
    }
}

fn check_len(what: &str, len: usize, vertices: usize) -> Result<(), GltfError> {
    if len != vertices {
        Err(GltfError::AttributeLength {
            what: what.to_owned(),
            len,
            vertices,
        })
    } else {
        Ok(())
    }
}

/// The triangles of a list, strip or fan of vertex indices.
fn triangles(mode: Mode, flat: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::Triangles => flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
        Mode::TriangleStrip => (2..flat.len())
            .map(|i| {
                if i % 2 == 0 {
                    [flat[i - 2], flat[i - 1], flat[i]]
                } else {
                    [flat[i - 1], flat[i - 2], flat[i]]
                }
            })
            .collect(),
        _ => (2..flat.len())
            .map(|i| [flat[0], flat[i - 1], flat[i]])
            .collect(),
    }
}
