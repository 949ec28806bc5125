//! A closed triangle mesh as a CSG operand: the inside of the line is read from the parity of its
//! crossings with the surface (sorted; the duplicate crossings of a ray through a shared edge merged),
//! found with a small BVH over the mesh's triangles in its own space.

use glam::Vec3;

use crate::geometry::median::{MedianBvh, Node};
use crate::geometry::triangle::{self, RayShear};
use crate::geometry::Aabb;

/// Most crossings of one line with one mesh that are kept; a list that would need more keeps the
/// nearest and reports the rest as unknown (see `Intervals::limit`).
pub const MAX_CROSSINGS: usize = 2 * super::CAPACITY;
const LEAF_SIZE: usize = 4;

/// A closed (every edge shared by exactly two triangles) triangle mesh in object space.
#[derive(Debug)]
pub struct SolidMesh {
    pub name: String,
    /// The triangles, reordered into the BVH's leaf order (surface ids name them by this order).
    tris: Vec<[Vec3; 3]>,
    nodes: Vec<Node>,
    bounds: Aabb,
}

/// Meshes are compared by identity (they are shared through `Arc`s).
impl PartialEq for SolidMesh {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self, other)
    }
}

/// A mesh that cannot bound a solid.
#[derive(Debug, thiserror::Error)]
#[error("mesh '{0}' is not closed (every edge must join exactly two triangles) and cannot be a CSG operand")]
pub struct NotClosed(pub String);

/// One crossing: distance, triangle and whether the triangle's normal faces against the line.
#[derive(Clone, Copy, Debug, Default)]
pub struct Crossing {
    pub t: f32,
    pub tri: u32,
    pub facing: bool,
}

impl SolidMesh {
    /// The solid bounded by the triangles `indices` over `positions`; fails when they are not closed
    /// (its inside would be undefined).
    pub fn new(name: &str, positions: &[Vec3], indices: &[[u32; 3]]) -> Result<Self, NotClosed> {
        let mut edges = std::collections::HashMap::<(u32, u32), u32>::new();
        for t in indices {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        if indices.is_empty() || edges.values().any(|&n| n != 2) {
            return Err(NotClosed(name.to_string()));
        }
        let mut tris: Vec<[Vec3; 3]> = indices
            .iter()
            .map(|t| t.map(|i| positions[i as usize]))
            .collect();
        let nodes = MedianBvh::build(
            &mut tris,
            LEAF_SIZE,
            |run| Aabb::from_points(run.iter().flatten().copied()),
            |t| (t[0] + t[1] + t[2]) / 3.0,
        )
        .nodes;
        Ok(Self {
            name: name.to_string(),
            bounds: nodes[0].bounds,
            tris,
            nodes,
        })
    }

    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    pub fn triangle_count(&self) -> usize {
        self.tris.len()
    }

    /// Unit normal of triangle `tri` (by its winding).
    pub fn normal(&self, tri: u32) -> Vec3 {
        let [a, b, c] = self
            .tris
            .get(tri as usize)
            .copied()
            .unwrap_or([Vec3::ZERO; 3]);
        (b - a).cross(c - a).normalize_or(Vec3::Z)
    }

    /// `p` moved onto the plane of triangle `tri`.
    pub fn project(&self, tri: u32, p: Vec3) -> Vec3 {
        let Some(&[a, ..]) = self.tris.get(tri as usize) else {
            return p;
        };
        let n = self.normal(tri);
        p - n * n.dot(p - a)
    }

    /// Every crossing of the whole line `o + t d` with the surface, sorted, duplicates through shared
    /// edges merged (same facing within `tol`); returns how many, and whether some were dropped.
    pub fn crossings(
        &self,
        o: Vec3,
        d: Vec3,
        tol: impl Fn(f32) -> f32,
        out: &mut [Crossing; MAX_CROSSINGS],
    ) -> (usize, bool) {
        let sh = RayShear::new(d);
        let inv = d.recip();
        let mut n = 0;
        let mut overflow = false;
        let mut stack = [0u32; 64];
        let mut sp = 1;
        while sp > 0 {
            sp -= 1;
            let node = self.nodes[stack[sp] as usize];
            if node
                .bounds
                .clip(o, inv, f32::NEG_INFINITY, f32::INFINITY)
                .is_none()
            {
                continue;
            }
            if node.count == 0 {
                stack[sp] = node.index;
                stack[sp + 1] = node.index + 1;
                sp += 2;
                continue;
            }
            for i in node.index..node.index + node.count {
                let [a, b, c] = self.tris[i as usize];
                if let Some(h) =
                    triangle::intersect(o, &sh, a, b, c, f32::NEG_INFINITY, f32::INFINITY)
                {
                    let facing = (b - a).cross(c - a).dot(d) < 0.0;
                    if n < MAX_CROSSINGS {
                        out[n] = Crossing {
                            t: h.t,
                            tri: i,
                            facing,
                        };
                        n += 1;
                    } else {
                        overflow = true;
                    }
                }
            }
        }
        let list = &mut out[..n];
        list.sort_unstable_by(|x, y| x.t.total_cmp(&y.t));
        // Merge a crossing into the previous one when it is the same crossing seen through a shared
        // edge or vertex.
        let mut m = 0;
        for k in 0..n {
            let c = list[k];
            if m > 0 && list[m - 1].facing == c.facing && c.t - list[m - 1].t <= tol(c.t) {
                continue;
            }
            list[m] = c;
            m += 1;
        }
        (m, overflow)
    }
}
