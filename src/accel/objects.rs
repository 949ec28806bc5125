//! Non-triangle primitives (CSG objects) for the Rust backends: a binary BVH over their boxes that
//! the triangle BVH and the grid consult after their own traversal, with the distance of their
//! triangle hit as the limit, so the triangle hot loops stay as they are (instances use it too).

use crate::csg::CsgObject;
use crate::geometry::median::MedianBvh;
use crate::geometry::{Aabb, Hit, Ray};

/// A primitive the triangle accelerators do not know: bounds, closest hit and any hit in the ray's
/// `(t_min, t_max)`.
pub trait Primitive {
    fn bounds(&self) -> Aabb;
    /// Distance and surface id of the closest hit.
    fn intersect(&self, ray: &Ray) -> Option<(f32, u32)>;
    fn occluded(&self, ray: &Ray) -> bool;
}

impl Primitive for CsgObject {
    fn bounds(&self) -> Aabb {
        CsgObject::bounds(self)
    }
    fn intersect(&self, ray: &Ray) -> Option<(f32, u32)> {
        CsgObject::intersect(self, ray)
    }
    fn occluded(&self, ray: &Ray) -> bool {
        CsgObject::occluded(self, ray)
    }
}

/// A BVH over a few primitives, built by median splits (there are few, and each costs far more than a
/// box test), one primitive to a leaf.
#[derive(Clone, Debug, Default)]
pub struct ObjectBvh {
    tree: MedianBvh,
    /// The primitive of each leaf item (items are in the tree's leaf order).
    prims: Vec<u32>,
}

impl ObjectBvh {
    pub fn build<P: Primitive>(prims: &[P]) -> Self {
        Self::over(prims.iter().map(|p| p.bounds()))
    }

    /// The tree over items with these bounds (item `i` is the `i`th box; empty boxes are left out).
    pub fn over(bounds: impl Iterator<Item = Aabb>) -> Self {
        let mut items: Vec<(u32, Aabb)> = bounds
            .enumerate()
            .map(|(i, b)| (i as u32, b))
            .filter(|(_, b)| !b.is_empty())
            .collect();
        let tree = MedianBvh::build(
            &mut items,
            1,
            |run| run.iter().fold(Aabb::EMPTY, |b, i| b.union(i.1)),
            |i| i.1.center(),
        );
        Self {
            tree,
            prims: items.into_iter().map(|(i, _)| i).collect(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.tree.is_empty()
    }

    /// Bytes held by the tree.
    pub fn memory_bytes(&self) -> usize {
        self.tree.nodes.len() * std::mem::size_of::<crate::geometry::median::Node>()
            + self.prims.len() * std::mem::size_of::<u32>()
    }

    /// The closest hit on the primitives nearer than `best` (the caller's hit so far), else `best`.
    /// Hits name their primitive in `Hit::inst` as `tag | index`. (Kept out of line, so the callers'
    /// triangle loops stay as compact as without it.)
    #[inline(never)]
    pub fn intersect<P: Primitive>(
        &self,
        prims: &[P],
        ray: &Ray,
        best: Option<Hit>,
        tag: u32,
    ) -> Option<Hit> {
        let mut r = *ray;
        if let Some(h) = best {
            r.t_max = h.t;
        }
        let start = r;
        let mut best = best;
        self.walk(&start, |i| {
            if let Some((t, surface)) = prims[i as usize].intersect(&r) {
                if t < r.t_max {
                    r.t_max = t;
                    best = Some(Hit {
                        t,
                        u: 0.0,
                        v: 0.0,
                        inst: tag | i,
                        prim: surface,
                    });
                }
            }
            (false, r.t_max)
        });
        best
    }

    /// Whether any primitive is hit in the ray's window.
    #[inline(never)]
    pub fn occluded<P: Primitive>(&self, prims: &[P], ray: &Ray) -> bool {
        let mut hit = false;
        self.walk(ray, |i| {
            hit = prims[i as usize].occluded(ray);
            (hit, ray.t_max)
        });
        hit
    }

    /// Visits the primitives whose boxes the ray enters, nearest box first; `visit` returns whether
    /// to stop and the current far limit. Visits nothing when the tree is empty.
    pub fn walk(&self, ray: &Ray, mut visit: impl FnMut(u32) -> (bool, f32)) {
        if self.is_empty() {
            return;
        }
        let inv = ray.d.recip();
        let mut t_max = ray.t_max;
        let enter = |b: &Aabb, t_max: f32| b.clip(ray.o, inv, ray.t_min, t_max).map(|(t, _)| t);
        let nodes = &self.tree.nodes;
        let mut stack = [(0u32, 0.0f32); 64];
        let mut sp = 0;
        if let Some(t) = enter(&nodes[0].bounds, t_max) {
            stack[0] = (0, t);
            sp = 1;
        }
        while sp > 0 {
            sp -= 1;
            let (at, t_enter) = stack[sp];
            if t_enter > t_max {
                continue;
            }
            let n = nodes[at as usize];
            if n.count == 1 {
                let (stop, limit) = visit(self.prims[n.index as usize]);
                if stop {
                    return;
                }
                t_max = limit;
                continue;
            }
            let l = n.index as usize;
            let tl = enter(&nodes[l].bounds, t_max);
            let tr = enter(&nodes[l + 1].bounds, t_max);
            // Far child first on the stack, so the near one is visited first.
            let mut push = |i: usize, t: Option<f32>| {
                if let Some(t) = t {
                    stack[sp] = (i as u32, t);
                    sp += 1;
                }
            };
            if tl.unwrap_or(f32::INFINITY) <= tr.unwrap_or(f32::INFINITY) {
                push(l + 1, tr);
                push(l, tl);
            } else {
                push(l, tl);
                push(l + 1, tr);
            }
        }
    }
}
