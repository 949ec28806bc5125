//! Non-triangle primitives (CSG objects) for the Rust backends: a small binary BVH over their boxes
//! that the triangle BVH and the grid consult after their own traversal, with the distance of their
//! triangle hit as the limit, so the triangle hot loops stay as they are.

use glam::Vec3;

use crate::csg::CsgObject;
use crate::geometry::{gamma, Aabb, Hit, Ray};

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

/// A node: bounds, and two children (`count == 0`, left at `index`, right at `index + 1`) or one
/// primitive (`count == 1`, its index in `index`).
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    index: u32,
    count: u32,
}

/// A BVH over a few primitives, built by median splits (there are few, and each costs far more than a
/// box test).
#[derive(Clone, Debug, Default)]
pub struct ObjectBvh {
    nodes: Vec<Node>,
}

impl ObjectBvh {
    pub fn build<P: Primitive>(prims: &[P]) -> Self {
        let mut items: Vec<(u32, Aabb)> = prims
            .iter()
            .enumerate()
            .map(|(i, p)| (i as u32, p.bounds()))
            .filter(|(_, b)| !b.is_empty())
            .collect();
        let mut nodes = Vec::new();
        if !items.is_empty() {
            nodes.push(Node {
                bounds: Aabb::EMPTY,
                index: 0,
                count: 0,
            });
            build(&mut items, 0, &mut nodes);
        }
        Self { nodes }
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
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
        if self.nodes.is_empty() {
            return best;
        }
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
        if self.nodes.is_empty() {
            return false;
        }
        let mut hit = false;
        self.walk(ray, |i| {
            hit = prims[i as usize].occluded(ray);
            (hit, ray.t_max)
        });
        hit
    }

    /// Visits the primitives whose boxes the ray enters, nearest box first; `visit` returns whether
    /// to stop and the current far limit.
    fn walk(&self, ray: &Ray, mut visit: impl FnMut(u32) -> (bool, f32)) {
        let inv = ray.d.recip();
        let mut t_max = ray.t_max;
        let mut stack = [(0u32, 0.0f32); 64];
        let mut sp = 0;
        if let Some(t) = enter(&self.nodes[0].bounds, ray.o, inv, ray.t_min, t_max) {
            stack[0] = (0, t);
            sp = 1;
        }
        while sp > 0 {
            sp -= 1;
            let (at, t_enter) = stack[sp];
            if t_enter > t_max {
                continue;
            }
            let n = self.nodes[at as usize];
            if n.count == 1 {
                let (stop, limit) = visit(n.index);
                if stop {
                    return;
                }
                t_max = limit;
                continue;
            }
            let l = n.index as usize;
            let tl = enter(&self.nodes[l].bounds, ray.o, inv, ray.t_min, t_max);
            let tr = enter(&self.nodes[l + 1].bounds, ray.o, inv, ray.t_min, t_max);
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

/// Where the ray enters `b` within `[t_min, t_max]` (conservative slab test, Ize 2013).
#[inline(always)]
fn enter(b: &Aabb, o: Vec3, inv: Vec3, t_min: f32, t_max: f32) -> Option<f32> {
    let far_scale = 1.0 + 2.0 * gamma(3);
    let (mut t0, mut t1) = (t_min, t_max);
    for a in 0..3 {
        let (lo, hi) = ((b.min[a] - o[a]) * inv[a], (b.max[a] - o[a]) * inv[a]);
        let (near, far) = if inv[a] < 0.0 { (hi, lo) } else { (lo, hi) };
        let far = far * far_scale;
        t0 = if near > t0 { near } else { t0 };
        t1 = if far < t1 { far } else { t1 };
    }
    (t0 <= t1).then_some(t0)
}

fn build(items: &mut [(u32, Aabb)], at: usize, nodes: &mut Vec<Node>) {
    let bounds = items.iter().fold(Aabb::EMPTY, |b, i| b.union(i.1));
    if items.len() == 1 {
        nodes[at] = Node {
            bounds,
            index: items[0].0,
            count: 1,
        };
        return;
    }
    let axis = items
        .iter()
        .fold(Aabb::EMPTY, |b, i| b.grow(i.1.center()))
        .extent()
        .max_position();
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| {
        a.1.center()[axis].total_cmp(&b.1.center()[axis])
    });
    let l = nodes.len();
    let blank = Node {
        bounds: Aabb::EMPTY,
        index: 0,
        count: 0,
    };
    nodes.push(blank);
    nodes.push(blank);
    nodes[at] = Node {
        bounds,
        index: l as u32,
        count: 0,
    };
    let (left, right) = items.split_at_mut(mid);
    build(left, l, nodes);
    build(right, l + 1, nodes);
}
