//! Constructive solid geometry by ray casting (Roth 1982): analytic primitives give the spans of a ray
//! inside them, and union, intersection and difference combine those interval lists up a tree.
//!
//! A `CsgObject` is one tree placed in the world. The Rust accelerators treat it as a leaf (through
//! `accel::objects`), Embree as a user geometry; both call `CsgObject::intersect`/`occluded`.
//! Interval lists live on the stack (`Intervals`, fixed capacity); nothing is allocated per ray.

pub mod mesh;
pub mod shape;

use std::sync::Arc;

use glam::{Affine3A, Mat3, Mat4, Vec3};

use crate::geometry::Motion;
use crate::geometry::{Aabb, Ray};
pub use mesh::SolidMesh;
pub use shape::Shape;

/// Most intervals a list holds. A list that would grow past it keeps its nearest `CAPACITY`
/// intervals and records where the first dropped one began as its `limit`: it is exact before the
/// limit and says nothing beyond, and queries report no surface there.
pub const CAPACITY: usize = 16;

/// A surface id: which leaf primitive (the low `CsgObject::leaf_bits` bits, as few as the object's
/// leaves need), which of its faces above them (see `Shape::normal`; a mesh operand's triangle) and
/// whether its normal is flipped (bit 31, toggled by each difference that subtracts it).
/// `Hit::prim` of a CSG hit is such an id; `CsgObject::split_surface` takes it apart.
pub const FLIP: u32 = 1 << 31;
/// The "surface" at an infinite end of an interval (half-spaces): never reported.
pub const NO_SURFACE: u32 = !FLIP;
/// Most leaves in one object.
pub const MAX_LEAVES: usize = 1 << 16;
/// Most operands an operation node evaluates directly; larger unions and intersections are
/// regrouped into subtrees of this fan-out (they are associative).
const MAX_FANOUT: usize = 8;
/// Boundaries of different operands closer than `COINCIDENT * (|t| + object size / |d|)` count as
/// one (coincident faces, e.g. A minus B sharing a face, give no speckles), and result intervals or
/// gaps shorter than that vanish (tangent rays give no one-point hits).
pub const COINCIDENT: f32 = 1e-5;

/// Where the ray is inside a solid: from `t0` (entering surface `s0`) to `t1` (leaving surface `s1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub t0: f32,
    pub t1: f32,
    pub s0: u32,
    pub s1: u32,
}

/// A Roth diagram: sorted, disjoint intervals, so its boundaries alternate entering and leaving.
#[derive(Clone, Copy, Debug)]
pub struct Intervals {
    len: usize,
    limit: f32,
    items: [Interval; CAPACITY],
}

impl Default for Intervals {
    fn default() -> Self {
        Self::EMPTY
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    Union,
    Intersection,
    Difference,
}

impl Op {
    fn inside(self, a: bool, b: bool) -> bool {
        match self {
            Op::Union => a || b,
            Op::Intersection => a && b,
            Op::Difference => a && !b,
        }
    }
}

impl Intervals {
    pub const EMPTY: Intervals = Intervals {
        len: 0,
        limit: f32::INFINITY,
        items: [Interval {
            t0: 0.0,
            t1: 0.0,
            s0: NO_SURFACE,
            s1: NO_SURFACE,
        }; CAPACITY],
    };

    /// A list from sorted, disjoint intervals (for tests and callers building their own).
    pub fn from_slice(items: &[Interval]) -> Self {
        let mut l = Self::EMPTY;
        for &i in items {
            l.push(i);
        }
        l
    }

    pub fn as_slice(&self) -> &[Interval] {
        &self.items[..self.len]
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Beyond this distance the list is incomplete (after an overflow or an early stop).
    pub fn limit(&self) -> f32 {
        self.limit
    }

    fn push(&mut self, i: Interval) {
        if self.len == CAPACITY {
            self.limit = self.limit.min(i.t0);
        } else if i.t0 < self.limit {
            self.items[self.len] = i;
            self.len += 1;
        }
    }

    /// Sorted and alternating: every interval non-empty, each starting after the previous ended.
    pub fn is_well_formed(&self) -> bool {
        let s = self.as_slice();
        s.iter().all(|i| i.t0 < i.t1) && s.windows(2).all(|w| w[0].t1 < w[1].t0)
    }

    /// The boundary `t` of `k`: entering boundaries at even `k`, leaving ones at odd.
    #[inline(always)]
    fn boundary(&self, k: usize) -> (f32, u32) {
        let i = &self.items[k / 2];
        if k.is_multiple_of(2) {
            (i.t0, i.s0)
        } else {
            (i.t1, i.s1)
        }
    }

    /// The first boundary in `(t_min, t_max)`: distance and surface.
    pub fn first_in(&self, t_min: f32, t_max: f32) -> Option<(f32, u32)> {
        let t_max = t_max.min(self.limit);
        for k in 0..2 * self.len {
            let (t, s) = self.boundary(k);
            if t > t_min {
                return (t < t_max && s != NO_SURFACE).then_some((t, s));
            }
        }
        None
    }

    /// `op` applied pointwise along the ray: a sweep over both lists' boundaries in order. Boundaries
    /// within `tol(t)` of the first of a group are applied together (coincident faces), and the
    /// result's surface at a change is the one whose own crossing causes that change; subtracted
    /// surfaces are flipped. Intervals and gaps within `tol` are dropped and merged.
    pub fn combine(op: Op, a: &Intervals, b: &Intervals, tol: impl Fn(f32) -> f32) -> Intervals {
        let mut out = Intervals::EMPTY;
        out.limit = a.limit.min(b.limit);
        let flip_b = if op == Op::Difference { FLIP } else { 0 };
        let (na, nb) = (2 * a.len, 2 * b.len);
        let (mut i, mut j) = (0, 0);
        let (mut in_a, mut in_b, mut cur) = (false, false, false);
        let mut open = (0.0f32, NO_SURFACE);
        loop {
            let ta = if i < na {
                a.boundary(i).0
            } else {
                f32::INFINITY
            };
            let tb = if j < nb {
                b.boundary(j).0
            } else {
                f32::INFINITY
            };
            let t = ta.min(tb);
            // (NaN ends the sweep too.)
            if t.partial_cmp(&out.limit) != Some(std::cmp::Ordering::Less) {
                break;
            }
            let end = t + tol(t);
            let (a0, b0) = (in_a, in_b);
            // The first crossing of the group that would change the result on its own.
            let mut cause: Option<(f32, u32)> = None;
            let mut first = (t, NO_SURFACE);
            while i < na && a.boundary(i).0 <= end {
                let (te, s) = a.boundary(i);
                if first.1 == NO_SURFACE {
                    first = (te, s);
                }
                if cause.is_none() && op.inside(!a0, b0) != cur {
                    cause = Some((te, s));
                }
                in_a = !in_a;
                i += 1;
            }
            while j < nb && b.boundary(j).0 <= end {
                let (te, s) = b.boundary(j);
                let s = if s == NO_SURFACE { s } else { s ^ flip_b };
                if first.1 == NO_SURFACE {
                    first = (te, s);
                }
                if op.inside(a0, !b0) != cur && cause.is_none_or(|c| te < c.0) {
                    cause = Some((te, s));
                }
                in_b = !in_b;
                j += 1;
            }
            let next = op.inside(in_a, in_b);
            if next == cur {
                continue;
            }
            let (te, s) = cause.unwrap_or(first);
            if next {
                // A gap narrower than the tolerance closes: reopen the previous interval.
                match out.as_slice().last() {
                    Some(last) if te - last.t1 <= tol(te) => {
                        open = (last.t0, last.s0);
                        out.len -= 1;
                    }
                    _ => open = (te, s),
                }
            } else if te - open.0 > tol(te) {
                out.push(Interval {
                    t0: open.0,
                    t1: te,
                    s0: open.1,
                    s1: s,
                });
            }
            cur = next;
        }
        if cur {
            // Inside up to infinity, or up to the limit where knowledge ends.
            out.push(Interval {
                t0: open.0,
                t1: f32::INFINITY,
                s0: open.1,
                s1: NO_SURFACE,
            });
        }
        out
    }
}

/// The runtime CSG tree, as the scene description gives it (see `scene::desc::csg::NodeSpec`): primitives and n-ary
/// operations, each with its own transform (object to parent).
#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    Primitive {
        shape: Shape,
        transform: Mat4,
        material: u32,
    },
    Operation {
        op: Op,
        children: Vec<Node>,
        transform: Mat4,
    },
    /// A closed triangle mesh as an operand (inside by crossing parity).
    Mesh {
        mesh: Arc<SolidMesh>,
        transform: Mat4,
        material: u32,
    },
}

impl Node {
    pub fn primitive(shape: Shape, material: u32) -> Node {
        Node::Primitive {
            shape,
            transform: Mat4::IDENTITY,
            material,
        }
    }

    pub fn op(op: Op, children: Vec<Node>) -> Node {
        Node::Operation {
            op,
            children,
            transform: Mat4::IDENTITY,
        }
    }

    /// This node moved by `m` (applied after its own transform).
    pub fn transformed(mut self, m: Mat4) -> Node {
        match &mut self {
            Node::Primitive { transform, .. }
            | Node::Operation { transform, .. }
            | Node::Mesh { transform, .. } => *transform = m * *transform,
        }
        self
    }

    pub fn union(children: Vec<Node>) -> Node {
        Node::op(Op::Union, children)
    }

    pub fn intersection(children: Vec<Node>) -> Node {
        Node::op(Op::Intersection, children)
    }

    pub fn difference(children: Vec<Node>) -> Node {
        Node::op(Op::Difference, children)
    }
}

/// What a leaf is: an analytic shape or a closed mesh.
#[derive(Clone, Debug)]
enum LeafShape {
    Analytic(Shape),
    Mesh(Arc<SolidMesh>),
}

impl LeafShape {
    fn faces(&self) -> usize {
        match self {
            LeafShape::Analytic(_) => 6,
            LeafShape::Mesh(m) => m.triangle_count(),
        }
    }

    fn bounds(&self) -> Aabb {
        match self {
            LeafShape::Analytic(s) => s.bounds(),
            LeafShape::Mesh(m) => m.bounds(),
        }
    }

    fn project(&self, face: u32, p: Vec3) -> Vec3 {
        match self {
            LeafShape::Analytic(s) => s.project(face, p),
            LeafShape::Mesh(m) => m.project(face, p),
        }
    }

    fn normal(&self, face: u32, p: Vec3) -> Vec3 {
        match self {
            LeafShape::Analytic(s) => s.normal(face, p),
            LeafShape::Mesh(m) => m.normal(face),
        }
    }
}

/// A primitive with its whole transform baked in (leaf to world, and back).
#[derive(Clone, Debug)]
struct Leaf {
    shape: LeafShape,
    to_local: Affine3A,
    to_world: Affine3A,
    normal_to_world: Mat3,
    material: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Leaf,
    Op(Op),
}

/// A flattened node: its world bounds, and a leaf index or a run of children in `CsgObject::kids`.
#[derive(Clone, Copy, Debug)]
struct Flat {
    kind: Kind,
    bounds: Aabb,
    first: u32,
    count: u32,
}

/// One CSG tree placed in the world.
#[derive(Clone, Debug)]
pub struct CsgObject {
    pub root: Node,
    pub to_world: Mat4,
    leaves: Vec<Leaf>,
    nodes: Vec<Flat>,
    kids: Vec<u32>,
    /// Bits of a surface id that name the leaf.
    leaf_bits: u32,
    /// Placements over the shutter when the object moves (absent for a still one).
    motion: Option<Box<ObjectMotion>>,
}

/// A moving object is evaluated where it rests (at `to_world`): a ray at time `t` is carried there
/// by `to_world * placement(t)^-1`, which keeps its parameter `t`, and the surface found is carried back.
#[derive(Clone, Debug)]
struct ObjectMotion {
    placement: Motion,
    /// `to_world^-1`: with the placement at `t`, where the rest pose goes at `t`.
    from_rest: Mat4,
    /// Bounds over the whole shutter, and at each time step (for Embree's motion blur).
    bounds: Aabb,
    step_bounds: Vec<Aabb>,
}

/// The surface at a hit: world position (projected onto the primitive), unit normal (outward of
/// the result: flipped on subtracted surfaces), and material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CsgSurface {
    pub p: Vec3,
    pub n: Vec3,
    pub material: u32,
}

/// One ray's constants for an evaluation.
struct Query {
    o: Vec3,
    d: Vec3,
    inv: Vec3,
    t_min: f32,
    t_max: f32,
    /// Object size in units of `t`.
    scale: f32,
    /// Closest-hit mode: unions stop once their first surface is known.
    closest: bool,
}

impl Query {
    #[inline(always)]
    fn tol(&self, t: f32) -> f32 {
        if t.is_finite() {
            COINCIDENT * (t.abs() + self.scale)
        } else {
            0.0
        }
    }

    /// Entry and exit of `b` within the ray's window (conservative, as the BVH's slab test).
    #[inline(always)]
    fn enters(&self, b: &Aabb) -> Option<f32> {
        let far_scale = 1.0 + 2.0 * crate::geometry::gamma(3);
        let (mut t0, mut t1) = (self.t_min, self.t_max);
        for a in 0..3 {
            let (lo, hi) = (
                (b.min[a] - self.o[a]) * self.inv[a],
                (b.max[a] - self.o[a]) * self.inv[a],
            );
            let (near, far) = if self.inv[a] < 0.0 {
                (hi, lo)
            } else {
                (lo, hi)
            };
            let far = far * far_scale;
            t0 = if near > t0 { near } else { t0 };
            t1 = if far < t1 { far } else { t1 };
        }
        (t0 <= t1).then_some(t0)
    }
}

fn overlap(a: Aabb, b: Aabb) -> Aabb {
    let o = Aabb {
        min: a.min.max(b.min),
        max: a.max.min(b.max),
    };
    if o.is_empty() {
        Aabb::EMPTY
    } else {
        o
    }
}

impl CsgObject {
    /// Flattens `root` placed by `to_world`. Fails on an unbounded solid (a half-space not cut by a
    /// bounded one), an empty operation, too many leaves or a transform that cannot be inverted.
    pub fn new(root: Node, to_world: Mat4) -> Result<Self, String> {
        let mut obj = Self {
            root: root.clone(),
            to_world,
            leaves: Vec::new(),
            nodes: Vec::new(),
            kids: Vec::new(),
            leaf_bits: 0,
            motion: None,
        };
        obj.flatten(&root, to_world)?;
        obj.leaf_bits = (usize::BITS - (obj.leaves.len().max(2) - 1).leading_zeros()).max(1);
        let faces = obj
            .leaves
            .iter()
            .map(|l| l.shape.faces())
            .max()
            .unwrap_or(0);
        if faces >= (1usize << (31 - obj.leaf_bits)) - 1 {
            return Err(format!(
                "a CSG object of {} primitives can hold meshes of at most {} triangles",
                obj.leaves.len(),
                (1usize << (31 - obj.leaf_bits)) - 2
            ));
        }
        let b = obj.bounds();
        if !(b.is_empty() || b.min.is_finite() && b.max.is_finite()) {
            return Err("unbounded CSG solid (intersect half-spaces with a bounded solid)".into());
        }
        Ok(obj)
    }

    /// Appends the flattened subtree of `node` (parent-to-world `m`); returns its index.
    fn flatten(&mut self, node: &Node, m: Mat4) -> Result<u32, String> {
        match node {
            Node::Primitive {
                shape,
                transform,
                material,
            } => self.leaf(LeafShape::Analytic(*shape), m * *transform, *material),
            Node::Mesh {
                mesh,
                transform,
                material,
            } => self.leaf(LeafShape::Mesh(mesh.clone()), m * *transform, *material),
            Node::Operation {
                op,
                children,
                transform,
            } => {
                if children.is_empty() {
                    return Err(format!("{op:?} without operands"));
                }
                let w = m * *transform;
                let mut ids = Vec::with_capacity(children.len());
                for c in children {
                    ids.push(self.flatten(c, w)?);
                }
                Ok(self.group(*op, ids))
            }
        }
    }

    /// Appends a leaf placed by `w` (leaf to world); returns its node index.
    fn leaf(&mut self, shape: LeafShape, w: Mat4, material: u32) -> Result<u32, String> {
        if !w.is_finite() || w.determinant().abs() < 1e-30 || !w.determinant().is_finite() {
            return Err("a CSG primitive's transform is degenerate or not finite".into());
        }
        if self.leaves.len() >= MAX_LEAVES {
            return Err(format!("more than {MAX_LEAVES} primitives"));
        }
        let to_world = Affine3A::from_mat4(w);
        let local = shape.bounds();
        let bounds = if local.min.is_finite() && local.max.is_finite() {
            local.transformed(&w)
        } else {
            local
        };
        self.leaves.push(Leaf {
            shape,
            to_local: to_world.inverse(),
            to_world,
            normal_to_world: Mat3::from_mat4(w).inverse().transpose(),
            material,
        });
        self.nodes.push(Flat {
            kind: Kind::Leaf,
            bounds,
            first: self.leaves.len() as u32 - 1,
            count: 0,
        });
        Ok(self.nodes.len() as u32 - 1)
    }

    /// An operation node over already flattened children, regrouped to `MAX_FANOUT`.
    fn group(&mut self, op: Op, mut ids: Vec<u32>) -> u32 {
        if op == Op::Difference && ids.len() > MAX_FANOUT {
            // A - B1 - ... - Bn = A - (B1 u ... u Bn).
            let rest = self.group(Op::Union, ids.split_off(1));
            ids.push(rest);
        }
        while ids.len() > MAX_FANOUT {
            ids = ids
                .chunks(MAX_FANOUT)
                .map(|c| {
                    if c.len() == 1 {
                        c[0]
                    } else {
                        self.group(op, c.to_vec())
                    }
                })
                .collect();
        }
        let boxes: Vec<Aabb> = ids.iter().map(|&i| self.nodes[i as usize].bounds).collect();
        let bounds = match op {
            Op::Union => boxes.iter().fold(Aabb::EMPTY, |a, &b| a.union(b)),
            Op::Intersection => boxes[1..].iter().fold(boxes[0], |a, &b| overlap(a, b)),
            Op::Difference => boxes[0],
        };
        let first = self.kids.len() as u32;
        self.kids.extend(&ids);
        self.nodes.push(Flat {
            kind: Kind::Op(op),
            bounds,
            first,
            count: ids.len() as u32,
        });
        self.nodes.len() as u32 - 1
    }

    fn root_index(&self) -> usize {
        self.nodes.len() - 1
    }

    /// The object moving through `placement` (world placements over the normalised shutter, in
    /// place of `to_world`); a placement that never differs from `to_world` leaves it still.
    pub fn with_motion(mut self, placement: Motion) -> Self {
        if placement.steps.iter().all(|m| *m == self.to_world) {
            self.motion = None;
            return self;
        }
        let rest = self.rest_bounds();
        let from_rest = self.to_world.inverse();
        let step_bounds: Vec<Aabb> = placement
            .steps
            .iter()
            .map(|m| rest.transformed(&(*m * from_rest)))
            .collect();
        let bounds = step_bounds.iter().fold(Aabb::EMPTY, |b, s| b.union(*s));
        self.motion = Some(Box::new(ObjectMotion {
            placement,
            from_rest,
            bounds,
            step_bounds,
        }));
        self
    }

    /// Whether the object moves during the shutter.
    pub fn moves(&self) -> bool {
        self.motion.is_some()
    }

    /// Evenly spaced time steps of the motion over the shutter (1 for a still object).
    pub fn time_steps(&self) -> usize {
        self.motion.as_ref().map_or(1, |m| m.step_bounds.len())
    }

    /// Bounds at time step `k` of `time_steps()`; between steps the object stays inside the linear
    /// blend of its neighbours' bounds, as its placement is the linear blend of theirs.
    pub fn step_bounds(&self, k: usize) -> Aabb {
        match &self.motion {
            Some(m) => m.step_bounds[k.min(m.step_bounds.len() - 1)],
            None => self.bounds(),
        }
    }

    /// World-space bounds (over the whole shutter for a moving object).
    pub fn bounds(&self) -> Aabb {
        match &self.motion {
            Some(m) => m.bounds,
            None => self.rest_bounds(),
        }
    }

    /// Bounds where the object rests, at `to_world`.
    fn rest_bounds(&self) -> Aabb {
        self.nodes.last().map_or(Aabb::EMPTY, |n| n.bounds)
    }

    /// From where the object rests to where it is at normalised shutter time `time` (None: still).
    fn rest_to_world(&self, time: f32) -> Option<Mat4> {
        let m = self.motion.as_ref()?;
        Some(m.placement.at(time) * m.from_rest)
    }

    /// The ray carried to where the object rests (the same ray for a still object).
    fn rest_ray(&self, ray: &Ray) -> Ray {
        match self.rest_to_world(ray.time).map(|m| m.inverse()) {
            None => *ray,
            Some(m) => Ray {
                o: m.transform_point3(ray.o),
                d: m.transform_vector3(ray.d),
                ..*ray
            },
        }
    }

    /// Materials of every primitive.
    pub fn materials(&self) -> impl Iterator<Item = u32> + '_ {
        self.leaves.iter().map(|l| l.material)
    }

    fn query(&self, ray: &Ray, closest: bool) -> Query {
        let dl = ray.d.length();
        Query {
            o: ray.o,
            d: ray.d,
            inv: ray.d.recip(),
            t_min: ray.t_min,
            t_max: ray.t_max,
            scale: self.rest_bounds().extent().length() / dl,
            closest,
        }
    }

    /// The ray's full interval list within its window (for tests and tools).
    pub fn intervals(&self, ray: &Ray) -> Intervals {
        let q = self.query(&self.rest_ray(ray), false);
        let mut out = Intervals::EMPTY;
        if q.enters(&self.rest_bounds()).is_some() {
            self.eval(self.root_index() as u32, &q, &mut out);
        }
        out
    }

    /// The closest surface in `(ray.t_min, ray.t_max)`: distance and surface id.
    pub fn intersect(&self, ray: &Ray) -> Option<(f32, u32)> {
        let ray = &self.rest_ray(ray);
        let q = self.query(ray, true);
        q.enters(&self.rest_bounds())?;
        let mut l = Intervals::EMPTY;
        self.eval(self.root_index() as u32, &q, &mut l);
        if let Some(h) = l.first_in(ray.t_min, ray.t_max) {
            return Some(h);
        }
        if l.limit() < ray.t_max {
            // An early stop left the answer open beyond its limit: evaluate in full.
            let q = Query {
                closest: false,
                ..q
            };
            let mut l = Intervals::EMPTY;
            self.eval(self.root_index() as u32, &q, &mut l);
            return l.first_in(ray.t_min, ray.t_max);
        }
        None
    }

    /// Whether any surface lies in `(ray.t_min, ray.t_max)` (the closest-hit path, which stops early).
    pub fn occluded(&self, ray: &Ray) -> bool {
        self.intersect(ray).is_some()
    }

    fn eval(&self, node: u32, q: &Query, out: &mut Intervals) {
        let n = &self.nodes[node as usize];
        match n.kind {
            Kind::Leaf => {
                let leaf = &self.leaves[n.first as usize];
                let o = leaf.to_local.transform_point3(q.o);
                let d = leaf.to_local.transform_vector3(q.d);
                let id = |t: f32, face: u32, flipped: bool| {
                    if t.is_finite() {
                        self.surface_id(n.first, face, flipped)
                    } else {
                        NO_SURFACE
                    }
                };
                match &leaf.shape {
                    LeafShape::Analytic(shape) => {
                        for s in shape.spans(o, d).iter() {
                            if s.t1 < q.t_min - q.tol(q.t_min) || s.t0 > q.t_max {
                                continue;
                            }
                            out.push(Interval {
                                t0: s.t0,
                                t1: s.t1,
                                s0: id(s.t0, s.f0, false),
                                s1: id(s.t1, s.f1, false),
                            });
                        }
                    }
                    LeafShape::Mesh(mesh) => {
                        let mut c = [mesh::Crossing::default(); mesh::MAX_CROSSINGS];
                        let (k, overflow) = mesh.crossings(o, d, |t| q.tol(t), &mut c);
                        // Outside at minus infinity: crossings alternate entering and leaving. A
                        // surface's normal faces out where the line enters through a triangle that
                        // faces against it (and leaves through one that faces along it).
                        for pair in c[..k].chunks_exact(2) {
                            let (a, b) = (pair[0], pair[1]);
                            if b.t < q.t_min - q.tol(q.t_min) || a.t > q.t_max || a.t >= b.t {
                                continue;
                            }
                            out.push(Interval {
                                t0: a.t,
                                t1: b.t,
                                s0: id(a.t, a.tri, !a.facing),
                                s1: id(b.t, b.tri, b.facing),
                            });
                        }
                        if overflow || k % 2 == 1 {
                            // Crossings dropped (or an odd count from a grazing ray): nothing is
                            // known beyond the last kept one.
                            out.limit = out
                                .limit
                                .min(c[..k].last().map_or(f32::NEG_INFINITY, |x| x.t));
                        }
                    }
                }
            }
            Kind::Op(op) => {
                let kids = &self.kids[n.first as usize..(n.first + n.count) as usize];
                let tol = |t| q.tol(t);
                match op {
                    Op::Union => {
                        // Operands in the order the ray enters their boxes; an operand entered after
                        // the result's first surface cannot change that surface.
                        let mut order = [(0.0f32, 0u32); MAX_FANOUT];
                        let mut k = 0;
                        for &c in kids {
                            if let Some(t) = q.enters(&self.nodes[c as usize].bounds) {
                                let mut at = k;
                                while at > 0 && order[at - 1].0 > t {
                                    order[at] = order[at - 1];
                                    at -= 1;
                                }
                                order[at] = (t, c);
                                k += 1;
                            }
                        }
                        for (idx, &(t_enter, c)) in order[..k].iter().enumerate() {
                            if q.closest && idx > 0 {
                                if let Some((first, _)) = out.first_in(q.t_min, q.t_max) {
                                    if first + tol(first) < t_enter {
                                        out.limit = out.limit.min(t_enter);
                                        break;
                                    }
                                }
                            }
                            let mut child = Intervals::EMPTY;
                            self.eval(c, q, &mut child);
                            *out = if idx == 0 {
                                child
                            } else {
                                Intervals::combine(op, out, &child, tol)
                            };
                        }
                    }
                    Op::Intersection => {
                        if kids
                            .iter()
                            .any(|&c| q.enters(&self.nodes[c as usize].bounds).is_none())
                        {
                            return;
                        }
                        self.eval(kids[0], q, out);
                        for &c in &kids[1..] {
                            if out.is_empty() && out.limit == f32::INFINITY {
                                return;
                            }
                            let mut child = Intervals::EMPTY;
                            self.eval(c, q, &mut child);
                            *out = Intervals::combine(op, out, &child, tol);
                        }
                    }
                    Op::Difference => {
                        self.eval(kids[0], q, out);
                        for &c in &kids[1..] {
                            if out.is_empty() && out.limit == f32::INFINITY {
                                return;
                            }
                            if q.enters(&self.nodes[c as usize].bounds).is_none() {
                                continue;
                            }
                            let mut child = Intervals::EMPTY;
                            self.eval(c, q, &mut child);
                            *out = Intervals::combine(op, out, &child, tol);
                        }
                    }
                }
            }
        }
    }

    /// The surface `id` at (about) world point `p`: `p` projected onto it, its world normal and its
    /// material.
    /// The surface id of face `face` of leaf `leaf` (see `FLIP`).
    pub fn surface_id(&self, leaf: u32, face: u32, flipped: bool) -> u32 {
        leaf | face << self.leaf_bits | if flipped { FLIP } else { 0 }
    }

    /// The leaf, face and flip of a surface id.
    pub fn split_surface(&self, id: u32) -> (u32, u32, bool) {
        let id_ = id & !FLIP;
        (
            id_ & ((1 << self.leaf_bits) - 1),
            id_ >> self.leaf_bits,
            id & FLIP != 0,
        )
    }

    /// The surface `id` at world point `p`, where the object is at normalised shutter time `time`.
    pub fn surface(&self, id: u32, p: Vec3, time: f32) -> CsgSurface {
        let Some(from_rest) = self.rest_to_world(time) else {
            return self.rest_surface(id, p);
        };
        let to_rest = from_rest.inverse();
        let s = self.rest_surface(id, to_rest.transform_point3(p));
        // Back from rest: points by `from_rest`, normals by its inverse transpose.
        CsgSurface {
            p: from_rest.transform_point3(s.p),
            n: Mat3::from_mat4(to_rest)
                .transpose()
                .mul_vec3(s.n)
                .normalize_or(s.n),
            material: s.material,
        }
    }

    fn rest_surface(&self, id: u32, p: Vec3) -> CsgSurface {
        let (leaf, face, flipped) = self.split_surface(id);
        let Some(l) = self.leaves.get(leaf as usize) else {
            return CsgSurface {
                p,
                n: Vec3::Z,
                material: 0,
            };
        };
        let local = l.shape.project(face, l.to_local.transform_point3(p));
        let n = (l.normal_to_world * l.shape.normal(face, local)).normalize_or(Vec3::Z);
        CsgSurface {
            p: l.to_world.transform_point3(local),
            n: if flipped { -n } else { n },
            material: l.material,
        }
    }
}

#[cfg(test)]
mod tests;
