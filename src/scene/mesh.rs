//! `Mesh`, a triangle mesh in object space, and the clean-up every loader runs on what it read:
//! degenerate and non-finite triangles dropped, unreferenced vertices compacted, missing normals computed.

use glam::{Vec2, Vec3, Vec4};

use crate::geometry::Aabb;

/// A triangle mesh in its own object space, with one material (a glTF primitive, or an OBJ model).
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub name: String,
    pub positions: Vec<Vec3>,
    /// Per-vertex shading normals; always present (computed from the faces when the file has none).
    pub normals: Vec<Vec3>,
    /// Texture coordinates of set 0; empty when the file has none.
    pub uvs: Vec<Vec2>,
    /// Per-vertex tangents (xyz, w = bitangent sign); empty when the file has none.
    pub tangents: Vec<Vec4>,
    pub indices: Vec<[u32; 3]>,
    pub material: u32,
    /// Texture coordinates of sets 1.. (`uv_sets[k]` is set k + 1, below `UV_SETS`); each empty when
    /// the file has no such set.
    pub uv_sets: Vec<Vec<Vec2>>,
    /// Linear RGBA vertex colours (glTF COLOR_0, alpha 1 for RGB), multiplying the base colour; empty
    /// when the file has none.
    pub colors: Vec<Vec4>,
}

/// Texture coordinate sets a mesh can hold (TEXCOORD_0 to TEXCOORD_3).
pub const UV_SETS: usize = 4;

/// What textures read at a point of a mesh: the coordinates of every set and the vertex colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexAttrs {
    pub sets: [Vec2; UV_SETS],
    pub color: Vec4,
}

impl VertexAttrs {
    /// Set 0 at `uv`, the other sets zero, white: a surface without vertex attributes (CSG).
    pub fn from_uv(uv: Vec2) -> Self {
        let mut sets = [Vec2::ZERO; UV_SETS];
        sets[0] = uv;
        Self {
            sets,
            color: Vec4::ONE,
        }
    }
}

impl Mesh {
    /// The solid this closed mesh bounds, as a CSG operand.
    pub fn to_solid(&self) -> Result<crate::csg::SolidMesh, crate::csg::mesh::NotClosed> {
        crate::csg::SolidMesh::new(&self.name, &self.positions, &self.indices)
    }

    pub fn triangle(&self, prim: u32) -> [Vec3; 3] {
        let [a, b, c] = self.indices[prim as usize];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(self.positions.iter().copied())
    }

    /// Texture coordinate set `k` (empty when the mesh has none).
    pub fn uv_set(&self, k: usize) -> &[Vec2] {
        match k {
            0 => &self.uvs,
            _ => self.uv_sets.get(k - 1).map_or(&[], Vec::as_slice),
        }
    }

    /// Texture coordinates of every set (zero where the mesh has none) and the vertex colour (white
    /// without one) at barycentrics `(u, v)` of a triangle.
    pub fn uv_at(&self, prim: u32, u: f32, v: f32) -> VertexAttrs {
        let [a, b, c] = self.indices[prim as usize].map(|i| i as usize);
        let w = 1.0 - u - v;
        let mut out = VertexAttrs::from_uv(Vec2::ZERO);
        for (k, set) in out.sets.iter_mut().enumerate() {
            let t = self.uv_set(k);
            if !t.is_empty() {
                *set = t[a] * w + t[b] * u + t[c] * v;
            }
        }
        if !self.colors.is_empty() {
            out.color = self.colors[a] * w + self.colors[b] * u + self.colors[c] * v;
        }
        out
    }
}

impl Mesh {
    /// Makes the mesh safe for the accelerators: drops degenerate triangles (repeated indices, zero
    /// area, a non-finite corner), keeps only referenced vertices (so no NaN/Inf position survives),
    /// repairs attributes, and computes area-weighted normals where the file has none (or unusable
    /// ones). Returns the number of triangles dropped.
    pub fn clean(&mut self) -> usize {
        self.clean_with_order().dropped
    }

    /// `clean`, also telling which original vertex each kept vertex is, so that attributes the mesh
    /// does not hold (skin weights, morph targets) can follow.
    pub(crate) fn clean_with_order(&mut self) -> Cleaned {
        let dropped = self.drop_degenerate();
        let kept = self.compact();
        self.repair_attributes();
        self.repair_normals();
        Cleaned { dropped, kept }
    }

    /// Drops triangles with a repeated or out-of-range index, a non-finite corner or no area.
    fn drop_degenerate(&mut self) -> usize {
        let before = self.indices.len();
        let nv = self.positions.len();
        let pos = &self.positions;
        self.indices.retain(|&[a, b, c]| {
            if a == b
                || b == c
                || a == c
                || a as usize >= nv
                || b as usize >= nv
                || c as usize >= nv
            {
                return false;
            }
            let (pa, pb, pc) = (pos[a as usize], pos[b as usize], pos[c as usize]);
            if !(pa.is_finite() && pb.is_finite() && pc.is_finite()) {
                return false;
            }
            let n = (pb - pa).cross(pc - pa);
            n.is_finite() && n.length_squared() > 0.0
        });
        before - self.indices.len()
    }

    /// Keeps only the referenced vertices, in order of first use; returns the original index of each
    /// kept vertex, or None when every vertex is referenced (then nothing moves).
    fn compact(&mut self) -> Option<Vec<usize>> {
        let nv = self.positions.len();
        let mut remap = vec![u32::MAX; nv];
        let mut used = 0u32;
        for t in &self.indices {
            for &k in t {
                if remap[k as usize] == u32::MAX {
                    remap[k as usize] = used;
                    used += 1;
                }
            }
        }
        if used as usize >= nv {
            return None;
        }
        let mut order = vec![0usize; used as usize];
        for (old, &new) in remap.iter().enumerate() {
            if new != u32::MAX {
                order[new as usize] = old;
            }
        }
        self.positions = pick(&self.positions, &order);
        self.normals = pick_or_clear(&self.normals, &order, nv);
        self.uvs = pick_or_clear(&self.uvs, &order, nv);
        self.tangents = pick_or_clear(&self.tangents, &order, nv);
        self.colors = pick_or_clear(&self.colors, &order, nv);
        for set in &mut self.uv_sets {
            *set = pick_or_clear(set, &order, nv);
        }
        for t in &mut self.indices {
            for k in t.iter_mut() {
                *k = remap[*k as usize];
            }
        }
        Some(order)
    }

    /// Clears UVs, colours and tangents that do not match the vertices; non-finite UVs become zero
    /// and non-finite colours white.
    fn repair_attributes(&mut self) {
        let n = self.positions.len();
        for set in std::iter::once(&mut self.uvs).chain(&mut self.uv_sets) {
            if set.len() != n {
                set.clear();
            }
            for uv in set.iter_mut() {
                if !uv.is_finite() {
                    *uv = Vec2::ZERO;
                }
            }
        }
        if self.colors.len() != n {
            self.colors.clear();
        }
        for c in &mut self.colors {
            if !c.is_finite() {
                *c = Vec4::ONE;
            }
        }
        if self.tangents.len() != n || self.tangents.iter().any(|t| !t.is_finite()) {
            self.tangents.clear();
        }
    }

    /// Computes area-weighted normals for every vertex when the file has none, or for the unusable
    /// ones (not finite, or zero) when it has some.
    fn repair_normals(&mut self) {
        let n = self.positions.len();
        let bad_normal = |v: &Vec3| !v.is_finite() || v.length_squared() < 1e-20;
        if self.normals.len() == n && !self.normals.iter().any(bad_normal) {
            return;
        }
        let computed = self.face_normals();
        if self.normals.len() != n {
            self.normals = computed.collect();
        } else {
            for (given, c) in self.normals.iter_mut().zip(computed) {
                if bad_normal(given) {
                    *given = c;
                }
            }
        }
    }

    /// Per vertex, the unit sum of its faces' area-weighted normals (+Z where they cancel).
    fn face_normals(&self) -> impl Iterator<Item = Vec3> {
        let mut acc = vec![Vec3::ZERO; self.positions.len()];
        for &[a, b, c] in &self.indices {
            let (pa, pb, pc) = (
                self.positions[a as usize],
                self.positions[b as usize],
                self.positions[c as usize],
            );
            let f = (pb - pa).cross(pc - pa); // length = 2 * area: area weighting
            acc[a as usize] += f;
            acc[b as usize] += f;
            acc[c as usize] += f;
        }
        acc.into_iter().map(|v| {
            let u = v.normalize_or_zero();
            if u == Vec3::ZERO {
                Vec3::Z
            } else {
                u
            }
        })
    }
}

/// What `Mesh::clean_with_order` did.
pub(crate) struct Cleaned {
    /// Triangles dropped.
    pub dropped: usize,
    /// The original vertex of each kept vertex; None when all are kept in place.
    pub kept: Option<Vec<usize>>,
}

impl Cleaned {
    /// The original index of kept vertex `k`.
    pub fn original(&self, k: usize) -> usize {
        self.kept.as_ref().map_or(k, |o| o[k])
    }
}

fn pick<T: Copy>(v: &[T], order: &[usize]) -> Vec<T> {
    order.iter().map(|&o| v[o]).collect()
}

/// `pick` for a per-vertex attribute, which is dropped when it does not have one value a vertex.
fn pick_or_clear<T: Copy>(v: &[T], order: &[usize], nv: usize) -> Vec<T> {
    if v.len() == nv {
        pick(v, order)
    } else {
        Vec::new()
    }
}
