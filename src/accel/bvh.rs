//! The pure-Rust backend: an 8-wide BVH over world-space triangles, built by binned SAH in parallel
//! (packet-aware costs) and collapsed from the binary tree. Traversal tests a node's eight boxes at
//! once (structure-of-arrays nodes; AVX where the CPU has it, two SSE halves otherwise), front to back
//! for closest hits, with conservative slab tests (Ize 2013), and leaves' triangles with the
//! watertight test (Woop 2013), eight at a time where the CPU has AVX and four otherwise. The
//! backend is this structure in a `Layered` composition (moving instances and CSG objects after
//! it); moving instances each hold a bare one of their own.

use std::mem::MaybeUninit;

use glam::Vec3;
use rayon::prelude::*;

use super::flat::{take_lanes, TriId};
use super::layered::{Layered, Triangles};
use crate::geometry::f4::F4;
use crate::geometry::lanes::Lanes;
#[cfg(target_arch = "x86_64")]
use crate::geometry::lanes::F8;
use crate::geometry::triangle::{self, PacketLanes, RayShear, Tri4};
use crate::geometry::{Aabb, Hit, Ray, SLAB_WIDEN};
use crate::scene::Scene;

/// The `bvh` backend: the BVH over the static triangles, then moving instances and CSG objects.
pub type BvhAccel = Layered<Bvh>;

/// Number of SAH bins per axis. 32 against 16 (best of three alternated runs, one thread): ToyCar
/// 1.5-2.5% more rays a second of each kind, icosphere:8 the same, build time the same.
const BINS: usize = 32;
/// Leaves never hold more than this many triangles (two packets: eight measured 7-9% faster than
/// four on icosphere:8 and the same on ToyCar, with 20% less memory).
const MAX_LEAF: usize = 8;
/// Cost of testing two packets of four triangles at once (eight AVX lanes), in tests of one. Costing
/// the pair as two packets instead, the ratio to robust Embree (best of four runs, one thread) was
/// 0.954 / 1.101 / 1.024 on icosphere:8's primary / shadow / diffuse rays against 0.962 / 1.146 /
/// 1.083, and 1.051 / 1.020 / 0.966 on ToyCar's against 1.091 / 1.042 / 1.019; 1.5 measured the same.
const PAIR_COST: f32 = 1.25;
/// Relative cost of a ray/box test against a ray/triangle-packet test, for the SAH.
const TRAVERSAL_COST: f32 = 1.0;
/// Subtrees smaller than this are built on the current thread.
const PARALLEL_THRESHOLD: usize = 4096;

/// A node of the binary tree: bounds and either two children (`count == 0`, left child right after
/// it, right child at `index`) or a leaf of `count` triangles starting at `index`. 32 bytes, two per cache line.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
struct Node {
    min: [f32; 3],
    index: u32,
    max: [f32; 3],
    count: u32,
}

/// Children per node of the traversed tree (a multiple of four).
const W: usize = 8;

impl Node {
    /// `n` all-zero nodes, in memory that the allocator hands out zeroed (fresh pages from the
    /// system for large trees): clearing the 2n - 1 slots of a big tree with stores took longer
    /// than binning its top levels.
    fn zeroed(n: usize) -> Vec<Node> {
        if n == 0 {
            return Vec::new();
        }
        let layout = std::alloc::Layout::array::<Node>(n).expect("node count fits in memory");
        // SAFETY: the layout has a non-zero size; a `Node` is f32s and u32s only, for which all-zero
        // bytes are a valid value; and the buffer comes from the global allocator with the layout of
        // `n` nodes, as `Vec::from_raw_parts` requires for length and capacity `n`.
        unsafe {
            let p = std::alloc::alloc_zeroed(layout).cast::<Node>();
            if p.is_null() {
                std::alloc::handle_alloc_error(layout);
            }
            Vec::from_raw_parts(p, n, n)
        }
    }
}

/// A `W`-wide node: the boxes of up to `W` children side by side (one array per bound), and for each
/// child either an inner node index (`count == 0`) or a leaf of `count` triangles from `child`.
/// Unused lanes hold an empty box, which no ray enters, and child 0. 32 W bytes.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct NodeW {
    /// Rows of `W` lanes: lower x, y, z, then upper x, y, z.
    b: [[f32; W]; 6],
    child: [u32; W],
    count: [u32; W],
}

impl NodeW {
    /// The box around the node's children (lower and upper corner, exact minima and maxima of
    /// theirs; empty lanes drop out), with a fourth lane of -inf and inf: all of space.
    fn enclosure(&self) -> [[f32; 4]; 2] {
        let (mut lo, mut hi) = ([f32::NEG_INFINITY; 4], [f32::INFINITY; 4]);
        for (a, (lo, hi)) in lo.iter_mut().zip(&mut hi).take(3).enumerate() {
            *lo = self.b[a].iter().copied().fold(f32::INFINITY, f32::min);
            *hi = self.b[3 + a]
                .iter()
                .copied()
                .fold(f32::NEG_INFINITY, f32::max);
        }
        [lo, hi]
    }
}

/// The 8-wide BVH over a set of triangles.
pub struct Bvh {
    /// Root at index 0 (absent for an empty scene).
    nodes: Vec<NodeW>,
    /// World-space triangles in packets of four, with their identities; a leaf is a run of packets.
    packets: Vec<Packet>,
    /// The box around the root's children (lower, upper corner), tested before a walk; a fourth
    /// lane of -inf and inf for `box_entered`.
    bounds: [[f32; 4]; 2],
    /// Whether the CPU has AVX, for the 8-lane box test.
    #[cfg(target_arch = "x86_64")]
    avx: bool,
}

impl Bvh {
    /// A BVH over exactly these triangles (hits report `ids`), in whatever space they are given.
    pub fn new(tris: Vec<[Vec3; 3]>, ids: Vec<TriId>) -> Self {
        let mut refs: Vec<PrimRef> = if tris.len() > PARALLEL_THRESHOLD {
            tris.par_iter()
                .enumerate()
                .map(|(i, t)| PrimRef::new(t, i as u32))
                .collect()
        } else {
            tris.iter()
                .enumerate()
                .map(|(i, t)| PrimRef::new(t, i as u32))
                .collect()
        };
        let mut bin = Node::zeroed((2 * refs.len()).max(1) - 1);
        if !refs.is_empty() {
            let bounds = bounds_of(&refs);
            build_node(&mut refs, 0, bounds, &mut bin, 0);
        }
        let order: Vec<u32> = refs.iter().map(|r| r.index()).collect();
        let mut out = Collapsed::with_capacity(tris.len());
        if !order.is_empty() {
            let source = Source {
                bin: &bin,
                order: &order,
                tris: &tris,
                ids: &ids,
            };
            collapse(
                &source,
                0,
                order.len(),
                order.len() >= PARALLEL_COLLAPSE,
                &mut out,
            );
        }
        let bounds = out.nodes.first().map_or([[0.0; 4]; 2], NodeW::enclosure);
        Self {
            nodes: out.nodes,
            packets: out.packets,
            bounds,
            #[cfg(target_arch = "x86_64")]
            avx: W == 8 && std::arch::is_x86_feature_detected!("avx"),
        }
    }

    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// This BVH walking with SSE box tests only (the walk of CPUs without AVX), for the tests.
    #[cfg(test)]
    pub(super) fn without_avx(self) -> Self {
        Self {
            #[cfg(target_arch = "x86_64")]
            avx: false,
            ..self
        }
    }

    /// Walks the tree front to back, keeping the closest accepted hit; with `any`, returns the first.
    /// Hits name instance `base + ` the instance of their `TriId` (a mesh's BVH shared by its
    /// instances holds instance 0, and each instance asks with its own index as `base`).
    #[inline(always)]
    pub(super) fn query(&self, scene: &Scene, ray: &Ray, any: bool, base: u32) -> Option<Hit> {
        if self.nodes.is_empty() || !self.box_entered(ray) {
            return None;
        }
        #[cfg(target_arch = "x86_64")]
        if self.avx {
            // SAFETY: `avx` is set only where the CPU has AVX.
            return unsafe {
                if any {
                    self.walk_avx::<true>(scene, ray, base)
                } else {
                    self.walk_avx::<false>(scene, ray, base)
                }
            };
        }
        if any {
            self.walk::<true, F4>(scene, ray, base)
        } else {
            self.walk::<false, F4>(scene, ray, base)
        }
    }

    /// Whether the ray enters the box around the whole tree, by the walk's own slab test (the same
    /// operations on each plane, so a ray that enters any of the root's children enters this box:
    /// each distance to its planes is at most, or at least, theirs, and rounding keeps order).
    /// A camera ray that misses the model is then spared the walk's setup: on icosphere:8, whose
    /// camera rays miss it six times in seven, that setup was the BVH's deficit against Embree.
    #[inline(always)]
    fn box_entered(&self, ray: &Ray) -> bool {
        // Four lanes: x, y, z and one whose box is all of space (its distances are -inf and inf,
        // which the running bounds ignore). Each bound is a minimum or maximum over a set, so
        // taking it across lanes gives the walk's sequential answer.
        let [lo, hi] = self.bounds.map(|r| F4::load(&r));
        let o = F4::load(&[ray.o.x, ray.o.y, ray.o.z, 0.0]);
        let inv = F4::splat(1.0) / F4::load(&[ray.d.x, ray.d.y, ray.d.z, 1.0]);
        let (t_lo, t_hi) = ((lo - o) * inv, (hi - o) * inv);
        let backwards = inv.lt(F4::splat(0.0));
        // As in the walk, a NaN distance (0 * inf on a plane) keeps the running bound.
        let tn = backwards
            .select(t_hi, t_lo)
            .max(F4::splat(ray.t_min))
            .to_array();
        let tf = backwards
            .select(t_lo, t_hi)
            .min(F4::splat(f32::INFINITY))
            .to_array();
        let tn = tn[0].max(tn[1]).max(tn[2]).max(tn[3]);
        let tf = tf[0].min(tf[1]).min(tf[2]).min(tf[3]) * FAR_SCALE;
        tn <= if tf < ray.t_max { tf } else { ray.t_max }
    }

    /// `walk` with 8-lane AVX box tests (and the rest VEX-encoded). Rust never fuses a multiply and
    /// an add on its own, so the hits are bit-identical to the SSE walk's.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    unsafe fn walk_avx<const ANY: bool>(&self, scene: &Scene, ray: &Ray, base: u32) -> Option<Hit> {
        self.walk::<ANY, F8>(scene, ray, base)
    }

    /// Asks for the cache lines of child `child` (of `count` triangles) when it is an inner node
    /// pushed for later: by the time the walk pops it they are often in (icosphere:8, 88 MB of
    /// nodes: 2-4% more rays a second). Leaves are not prefetched: their packets are another array.
    #[inline(always)]
    fn prefetch(&self, child: u32, count: u32) {
        if count == 0 {
            crate::geometry::prefetch(&self.nodes[child as usize]);
        }
    }

    /// The walk proper. The nearest child hit goes on without a trip through the stack; the others
    /// are pushed farthest first (in lane order for `ANY`).
    #[inline(always)]
    fn walk<const ANY: bool, L: PacketLanes>(
        &self,
        scene: &Scene,
        ray: &Ray,
        base: u32,
    ) -> Option<Hit> {
        let any = ANY;
        let sh = RayShear::new(ray.d);
        let slabs = Slabs::<L>::new(ray);
        let mut t_max = ray.t_max;
        let mut best: Option<Hit> = None;
        // Entries: (child, count, entry distance); inner nodes have count 0.
        // Left uninitialised (clearing it cost more than some whole walks): only entries below `sp`,
        // all written, are read.
        let mut stack = [const { MaybeUninit::<(u32, u32, f32)>::uninit() }; 16 * W];
        let mut sp = 0;
        let (mut child, mut count) = (0u32, 0u32);
        loop {
            if count > 0 {
                // The leaf's packets `L::PACKETS` at a time while they last, then one by one.
                let (mut packet, end) = (
                    child as usize,
                    child as usize + (count as usize).div_ceil(4),
                );
                while packet < end {
                    let group = &self.packets[packet..end];
                    let (h, n) = if group.len() >= L::PACKETS {
                        let h = triangle::intersect_packets::<L, _>(
                            ray.o, &sh, group, ray.t_min, t_max,
                        );
                        (h, L::PACKETS)
                    } else {
                        (
                            triangle::intersect4(ray.o, &sh, &group[0].tri, ray.t_min, t_max),
                            1,
                        )
                    };
                    let ids = |lane: usize| group[lane / 4].ids[lane % 4].rebased(base);
                    if take_lanes(any, &h, h.mask, ids, scene, ray, &mut t_max, &mut best) {
                        return best;
                    }
                    packet += n;
                }
            } else {
                let node = &self.nodes[child as usize];
                let (mut mask, t0) = slabs.test(node, t_max);
                if mask != 0 {
                    let first = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    if mask == 0 {
                        // One child: go straight on.
                        child = node.child[first];
                        count = node.count[first];
                        continue;
                    }
                    if any {
                        // Any hit will do: skip the sort (10% faster on shadow rays), go on with the
                        // first child.
                        while mask != 0 {
                            let l = mask.trailing_zeros() as usize;
                            mask &= mask - 1;
                            self.prefetch(node.child[l], node.count[l]);
                            stack[sp].write((node.child[l], node.count[l], 0.0));
                            sp += 1;
                        }
                        child = node.child[first];
                        count = node.count[first];
                        continue;
                    }
                    // Sort the hit children nearest first (insertion into at most W).
                    // Lane numbers only: sorting (distance, lane) pairs cleared sixteen words a node.
                    let mut order = [0u32; W];
                    order[0] = first as u32;
                    let mut n = 1;
                    while mask != 0 {
                        let l = mask.trailing_zeros();
                        mask &= mask - 1;
                        let t = t0[l as usize];
                        let mut k = n;
                        while k > 0 && t0[order[k - 1] as usize] > t {
                            order[k] = order[k - 1];
                            k -= 1;
                        }
                        order[k] = l;
                        n += 1;
                    }
                    for &l in order[1..n].iter().rev() {
                        let l = l as usize;
                        self.prefetch(node.child[l], node.count[l]);
                        stack[sp].write((node.child[l], node.count[l], t0[l]));
                        sp += 1;
                    }
                    let l = order[0] as usize;
                    child = node.child[l];
                    count = node.count[l];
                    continue;
                }
            }
            // Pop the nearest pending child that can still hold a closer hit.
            loop {
                if sp == 0 {
                    return best;
                }
                sp -= 1;
                // SAFETY: entry `sp` was written by the push that last raised `sp` past it.
                let (c, n, t_enter) = unsafe { stack[sp].assume_init() };
                if t_enter <= t_max {
                    (child, count) = (c, n);
                    break;
                }
            }
        }
    }
}

/// The ray/box test of a node's children, with its per-ray constants, in `L`-wide groups of the
/// node's lanes (four-wide twice, or eight-wide once where the walk is compiled for AVX): for each
/// child, the distance at which the ray enters its box, and a bit if it does within
/// `(t_min, t_max)`. Both widths give the same bits.
///
/// Ize 2013: the far slab distance is widened by 1 + 2 gamma(3) so that rounding never culls a box
/// that the ray touches. Scaling the smallest far distance is the same as scaling each (the rounded
/// product is monotonic in its operand). Minima and maxima are selects (minps/maxps) that keep the
/// running bound when a distance is NaN (0 * inf on a slab face).
struct Slabs<L: Lanes> {
    o: [L; 3],
    inv: [L; 3],
    t_min: L,
    /// Per axis, the bound rows entered first and last (`NodeW::b`: lo x y z, hi x y z).
    near: [usize; 3],
    far: [usize; 3],
}

const FAR_SCALE: f32 = SLAB_WIDEN;

impl<L: Lanes> Slabs<L> {
    #[inline(always)]
    fn new(ray: &Ray) -> Self {
        let inv = ray.d.recip().to_array();
        Self {
            o: ray.o.to_array().map(L::splat),
            inv: inv.map(L::splat),
            t_min: L::splat(ray.t_min),
            near: std::array::from_fn(|a| a + 3 * (inv[a] < 0.0) as usize),
            far: std::array::from_fn(|a| a + 3 * (inv[a] >= 0.0) as usize),
        }
    }

    #[inline(always)]
    fn test(&self, node: &NodeW, t_max: f32) -> (u32, [f32; W]) {
        const { assert!(W.is_multiple_of(L::N)) };
        let (near, far) = (&self.near, &self.far);
        let mut t0 = [0.0f32; W];
        let mut mask = 0;
        for q in 0..W / L::N {
            // No closures here: one that LLVM leaves out of line is not compiled for AVX, and
            // the AVX instructions inside become calls (six times slower).
            let tn = self.slab(node, near[0], 0, q).max(self.t_min);
            let tn = self.slab(node, near[1], 1, q).max(tn);
            let tn = self.slab(node, near[2], 2, q).max(tn);
            let tf = self.slab(node, far[0], 0, q).min(L::splat(f32::INFINITY));
            let tf = self.slab(node, far[1], 1, q).min(tf);
            let tf = self.slab(node, far[2], 2, q).min(tf);
            let tf = (tf * L::splat(FAR_SCALE)).min(L::splat(t_max));
            mask |= L::bits(tn.le(tf)) << (q * L::N);
            tn.store(&mut t0[q * L::N..]);
        }
        (mask, t0)
    }

    /// The distances to the planes of bound row `row` (along `axis`) of lane group `q`.
    #[inline(always)]
    fn slab(&self, node: &NodeW, row: usize, axis: usize, q: usize) -> L {
        (L::load(&node.b[row][q * L::N..]) - self.o[axis]) * self.inv[axis]
    }
}

/// The binary tree and the triangles it orders, as input to `collapse`.
struct Source<'a> {
    bin: &'a [Node],
    order: &'a [u32],
    tris: &'a [[Vec3; 3]],
    ids: &'a [TriId],
}

/// The `W`-wide tree being built, with its triangle packets.
struct Collapsed {
    nodes: Vec<NodeW>,
    packets: Vec<Packet>,
}

/// Four triangles and their identities side by side: a hit finds its identity in the lines that
/// the test has just read (from an array of their own, reading it missed the cache at most leaves
/// hit: 10% of the walk on icosphere:8's primary rays).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
struct Packet {
    tri: Tri4,
    ids: [TriId; 4],
}

impl AsRef<Tri4> for Packet {
    #[inline(always)]
    fn as_ref(&self) -> &Tri4 {
        &self.tri
    }
}

/// Packs a binary leaf's triangles into packets of four; returns the first packet's index.
fn pack_leaf(src: &Source, leaf: &Node, out: &mut Collapsed) -> u32 {
    let first = out.packets.len() as u32;
    let refs = &src.order[leaf.index as usize..(leaf.index + leaf.count) as usize];
    for (tri, lanes) in Tri4::packets(refs, src.tris) {
        let ids = lanes.map(|i| {
            if i == u32::MAX {
                TriId::NONE
            } else {
                src.ids[i as usize]
            }
        });
        out.packets.push(Packet { tri, ids });
    }
    first
}

/// Trees over at least this many references have the subtrees of their root collapsed in parallel.
const PARALLEL_COLLAPSE: usize = 1 << 14;

impl Collapsed {
    /// Empty, with room for the tree over `n` references.
    fn with_capacity(n: usize) -> Self {
        Self {
            nodes: Vec::with_capacity(n / 4 + 1),
            packets: Vec::with_capacity(n / 2 + 1),
        }
    }

    /// Appends a separately collapsed subtree; returns the index of its root.
    fn append(&mut self, sub: Collapsed) -> u32 {
        let (node_base, packet_base) = (self.nodes.len() as u32, self.packets.len() as u32);
        self.nodes.extend(sub.nodes.into_iter().map(|mut n| {
            for lane in 0..W {
                if n.count[lane] > 0 {
                    n.child[lane] += packet_base;
                } else if n.child[lane] != 0 {
                    // (Child 0, the subtree's root, is nobody's child: 0 marks an unused lane.)
                    n.child[lane] += node_base;
                }
            }
            n
        }));
        self.packets.extend(sub.packets);
        node_base
    }
}

/// Turns the binary tree below `at` (over `size` references) into `W`-wide nodes appended to `out`;
/// returns the new node's index. With `parallel`, the subtrees of the new node are collapsed in
/// parallel (each into its own arrays, then appended).
/// The up to W children of a wide node over binary node `at` (of `size` references): the binary
/// node's own children, then the largest inner child opened until there are W (or only leaves).
fn widest_children(bin: &[Node], at: usize, size: usize) -> ([(usize, usize); W], usize) {
    let inner = |i: usize| bin[i].count == 0;
    // Children of binary inner node `i` over `n` references: the left one follows it, the right one
    // is at `index`, and the left one's slots (twice its references) lie in between.
    let children = |(i, n): (usize, usize)| {
        let r = bin[i].index as usize;
        let left = (r - i) / 2;
        [(i + 1, left), (r, n - left)]
    };
    let area = |i: usize| {
        let n = &bin[i];
        Aabb {
            min: Vec3::from_array(n.min),
            max: Vec3::from_array(n.max),
        }
        .surface_area()
    };
    let mut kids = [(0usize, 0usize); W];
    let mut n = if inner(at) {
        kids[..2].copy_from_slice(&children((at, size)));
        2
    } else {
        kids[0] = (at, size);
        1
    };
    while n < W {
        let Some(pos) = (0..n)
            .filter(|&k| inner(kids[k].0))
            .max_by(|&a, &b| area(kids[a].0).total_cmp(&area(kids[b].0)))
        else {
            break;
        };
        let [l, r] = children(kids[pos]);
        kids[pos] = l;
        kids[n] = r;
        n += 1;
    }
    (kids, n)
}

fn collapse(src: &Source, at: usize, size: usize, parallel: bool, out: &mut Collapsed) -> u32 {
    let bin = src.bin;
    let inner = |i: usize| bin[i].count == 0;
    let (kids, n) = widest_children(bin, at, size);
    let index = out.nodes.len();
    out.nodes.push(NodeW {
        b: [
            [f32::INFINITY; W],
            [f32::INFINITY; W],
            [f32::INFINITY; W],
            [f32::NEG_INFINITY; W],
            [f32::NEG_INFINITY; W],
            [f32::NEG_INFINITY; W],
        ],
        child: [0; W],
        count: [0; W],
    });
    let kids = &kids[..n];
    let mut subs: Vec<Option<Collapsed>> = if parallel {
        kids.par_iter()
            .map(|&(k, kn)| {
                inner(k).then(|| {
                    let mut sub = Collapsed::with_capacity(kn);
                    collapse(src, k, kn, false, &mut sub);
                    sub
                })
            })
            .collect()
    } else {
        Vec::new()
    };
    for (lane, &(k, kn)) in kids.iter().enumerate() {
        let c = bin[k];
        let (child, count) = if c.count > 0 {
            (pack_leaf(src, &c, out), c.count)
        } else if let Some(sub) = subs.get_mut(lane).and_then(Option::take) {
            (out.append(sub), 0)
        } else {
            (collapse(src, k, kn, false, out), 0)
        };
        let node = &mut out.nodes[index];
        for axis in 0..3 {
            node.b[axis][lane] = c.min[axis];
            node.b[3 + axis][lane] = c.max[axis];
        }
        node.child[lane] = child;
        node.count[lane] = count;
    }
    index as u32
}

/// Build-time reference to one triangle: its bounds, with the triangle's index in the spare lane of
/// `lo` (as bits xored with those of 1.0, so the lane holds a normal float and never slows the
/// arithmetic on whole rows down; the lane is ignored).
#[derive(Clone, Copy)]
#[repr(C, align(16))]
struct PrimRef {
    lo: [f32; 4],
    hi: [f32; 4],
}

const INDEX_BITS: u32 = 0x3F80_0000;

impl PrimRef {
    fn new(t: &[Vec3; 3], index: u32) -> Self {
        let b = Aabb::from_points(*t);
        let [x, y, z] = b.min.to_array();
        let [u, v, w] = b.max.to_array();
        Self {
            lo: [x, y, z, f32::from_bits(index ^ INDEX_BITS)],
            hi: [u, v, w, 0.0],
        }
    }

    fn index(&self) -> u32 {
        self.lo[3].to_bits() ^ INDEX_BITS
    }

    fn bounds(&self) -> Box3 {
        Box3 {
            lo: F4::load(&self.lo),
            hi: F4::load(&self.hi),
        }
    }

    /// Twice the centroid (lanes x, y, z).
    fn c2(&self) -> F4 {
        F4::load(&self.lo) + F4::load(&self.hi)
    }
}

/// A box as two rows (lanes x, y, z; the fourth is ignored).
#[derive(Clone, Copy)]
struct Box3 {
    lo: F4,
    hi: F4,
}

impl Box3 {
    fn empty() -> Self {
        Self {
            lo: F4::splat(f32::INFINITY),
            hi: F4::splat(f32::NEG_INFINITY),
        }
    }

    /// The union with `o`; a NaN lane of `o` leaves this box's lane as it was.
    #[inline(always)]
    fn union(self, o: Box3) -> Self {
        Self {
            lo: o.lo.min(self.lo),
            hi: o.hi.max(self.hi),
        }
    }

    #[inline(always)]
    fn grow(self, p: F4) -> Self {
        Self {
            lo: p.min(self.lo),
            hi: p.max(self.hi),
        }
    }

    /// Half the surface area (of a non-empty box).
    #[inline(always)]
    fn half_area(&self) -> f32 {
        let [x, y, z, _] = (self.hi - self.lo).to_array();
        x * y + y * z + z * x
    }

    fn store(&self, node: &mut Node) {
        let (lo, hi) = (self.lo.to_array(), self.hi.to_array());
        node.min = [lo[0], lo[1], lo[2]];
        node.max = [hi[0], hi[1], hi[2]];
    }
}

/// Sets with more references than this are binned in parallel.
const PARALLEL_BINNING: usize = 1 << 16;

/// Bounds of the references and of their doubled centroids.
fn bounds_of(refs: &[PrimRef]) -> (Box3, Box3) {
    let fold = |(b, c): (Box3, Box3), r: &PrimRef| (b.union(r.bounds()), c.grow(r.c2()));
    let merge = |(b0, c0): (Box3, Box3), (b1, c1): (Box3, Box3)| (b0.union(b1), c0.union(c1));
    let empty = (Box3::empty(), Box3::empty());
    if refs.len() > PARALLEL_BINNING {
        refs.par_chunks(8192)
            .map(|c| c.iter().fold(empty, fold))
            .reduce(|| empty, merge)
    } else {
        refs.iter().fold(empty, fold)
    }
}

/// Builds the binary tree over `refs` into `slots`, reordering `refs` into leaf order. The tree
/// over `n` references takes at most `2n - 1` nodes, so each subtree gets that many slots (some
/// stay unused): the node itself, its left subtree right after it, then its right subtree (whose
/// index the node keeps). `slot0` is the global index of `slots[0]`, `base` that of `refs[0]`.
fn build_node(
    refs: &mut [PrimRef],
    base: u32,
    (bounds, centroids): (Box3, Box3),
    slots: &mut [Node],
    slot0: u32,
) {
    bounds.store(&mut slots[0]);
    let split = if refs.len() <= 1 {
        None
    } else {
        find_split(refs, &bounds, &centroids)
    };
    let (mid, left, right) = match split {
        Some(s) => partition(refs, &s),
        // No split beats a leaf, or the centroids coincide: still split large sets so leaves stay small.
        None if refs.len() > MAX_LEAF => {
            let [x, y, z, _] = (centroids.hi - centroids.lo).to_array();
            let axis = if x >= y && x >= z {
                0
            } else if y >= z {
                1
            } else {
                2
            };
            let mid = refs.len() / 2;
            refs.select_nth_unstable_by(mid, |a, b| {
                a.c2().to_array()[axis].total_cmp(&b.c2().to_array()[axis])
            });
            (mid, bounds_of(&refs[..mid]), bounds_of(&refs[mid..]))
        }
        None => {
            slots[0].index = base;
            slots[0].count = refs.len() as u32;
            return;
        }
    };
    let (head, rest) = slots.split_at_mut(1);
    let (left_slots, right_slots) = rest.split_at_mut(2 * mid - 1);
    let right_slot = slot0 + 2 * mid as u32;
    head[0].index = right_slot;
    head[0].count = 0;
    let parallel = refs.len() >= PARALLEL_THRESHOLD;
    let (lrefs, rrefs) = refs.split_at_mut(mid);
    let right_base = base + mid as u32;
    if parallel {
        rayon::join(
            || build_node(lrefs, base, left, left_slots, slot0 + 1),
            || build_node(rrefs, right_base, right, right_slots, right_slot),
        );
    } else {
        build_node(lrefs, base, left, left_slots, slot0 + 1);
        build_node(rrefs, right_base, right, right_slots, right_slot);
    }
}

/// Moves the references left of the split to the front, gathering the bounds and doubled-centroid
/// bounds of both sides on the way; returns how many go left, and the two sides' bounds.
fn partition(refs: &mut [PrimRef], s: &Split) -> (usize, (Box3, Box3), (Box3, Box3)) {
    let goes_left = |r: &PrimRef| s.bins_of(r.c2())[s.axis] < s.bin;
    let (mut lb, mut lc, mut rb, mut rc) =
        (Box3::empty(), Box3::empty(), Box3::empty(), Box3::empty());
    let (mut i, mut j) = (0, refs.len());
    loop {
        while i < j && goes_left(&refs[i]) {
            lb = lb.union(refs[i].bounds());
            lc = lc.grow(refs[i].c2());
            i += 1;
        }
        while i < j && !goes_left(&refs[j - 1]) {
            rb = rb.union(refs[j - 1].bounds());
            rc = rc.grow(refs[j - 1].c2());
            j -= 1;
        }
        if i >= j {
            break;
        }
        refs.swap(i, j - 1);
    }
    (i, (lb, lc), (rb, rc))
}

#[derive(Clone, Copy)]
struct Split {
    axis: usize,
    /// Bins `0..bin` go left.
    bin: usize,
    /// Bins in use (fewer for small sets, where evaluating 16 would cost more than it finds).
    bins: usize,
    /// Per axis, the doubled-centroid bound and the scale that map onto bin numbers.
    lo: F4,
    scale: F4,
}

impl Split {
    /// Bin of a doubled centroid along each axis (the same arithmetic for binning and partitioning,
    /// so both always agree).
    #[inline(always)]
    fn bins_of(&self, c2: F4) -> [usize; 4] {
        // Clamped before the conversion (a NaN becomes 0: `max` keeps its second operand).
        ((c2 - self.lo) * self.scale)
            .max(F4::splat(0.0))
            .min(F4::splat((self.bins - 1) as f32))
            .to_i32()
            .map(|b| b as usize)
    }
}

/// Per-axis bins of references: box and count.
#[derive(Clone, Copy)]
struct Bins {
    boxes: [[Box3; BINS]; 3],
    counts: [[u32; BINS]; 3],
}

impl Bins {
    fn empty() -> Self {
        Bins {
            boxes: [[Box3::empty(); BINS]; 3],
            counts: [[0; BINS]; 3],
        }
    }

    /// Bins of a run of references.
    fn of(s: &Split, refs: &[PrimRef]) -> Self {
        let mut bins = Bins::empty();
        for r in refs {
            let b = s.bins_of(r.c2());
            let bounds = r.bounds();
            for (axis, &k) in b[..3].iter().enumerate() {
                bins.boxes[axis][k] = bins.boxes[axis][k].union(bounds);
                bins.counts[axis][k] += 1;
            }
        }
        bins
    }

    fn merge(mut self, o: Bins) -> Self {
        for axis in 0..3 {
            for b in 0..BINS {
                self.boxes[axis][b] = self.boxes[axis][b].union(o.boxes[axis][b]);
                self.counts[axis][b] += o.counts[axis][b];
            }
        }
        self
    }
}

/// The SAH cost of intersecting `n` triangles, in tests of one packet of four: the walk tests a
/// leaf's packets two at a time (one eight-lane test, `PAIR_COST`) and a last lone packet alone.
fn packets(n: u32) -> f32 {
    let (pairs, rest) = (n / 8, n % 8);
    let last = match rest {
        0 => 0.0,
        1..=4 => 1.0,
        _ => PAIR_COST,
    };
    pairs as f32 * PAIR_COST + last
}

/// The binned-SAH split with the lowest cost, if it beats making a leaf.
fn find_split(refs: &[PrimRef], bounds: &Box3, cb: &Box3) -> Option<Split> {
    let nb = (refs.len() / 2).clamp(4, BINS);
    let (lo, hi) = (cb.lo.to_array(), cb.hi.to_array());
    // Axes along which the centroids do not spread (or NaN) get scale 0: one bin, no split.
    let scale: [f32; 4] = std::array::from_fn(|axis| {
        let extent = hi[axis] - lo[axis];
        if axis < 3 && extent > 0.0 {
            nb as f32 / extent
        } else {
            0.0
        }
    });
    let split0 = Split {
        axis: 0,
        bin: 0,
        bins: nb,
        lo: cb.lo,
        scale: F4::load(&scale),
    };
    let bins = if refs.len() > PARALLEL_BINNING {
        refs.par_chunks(8192)
            .map(|c| Bins::of(&split0, c))
            .reduce(Bins::empty, Bins::merge)
    } else {
        Bins::of(&split0, refs)
    };
    let leaf_cost = packets(refs.len() as u32);
    let parent_area = bounds.half_area().max(f32::MIN_POSITIVE);
    let mut best: Option<(f32, Split)> = None;
    for (axis, &s) in scale[..3].iter().enumerate() {
        if s == 0.0 {
            continue;
        }
        let (boxes, counts) = (&bins.boxes[axis], &bins.counts[axis]);
        let mut right_area = [0.0f32; BINS];
        let mut right_count = [0u32; BINS];
        let (mut acc, mut n) = (Box3::empty(), 0);
        for b in (1..nb).rev() {
            acc = acc.union(boxes[b]);
            n += counts[b];
            right_area[b] = acc.half_area();
            right_count[b] = n;
        }
        let (mut acc, mut n) = (Box3::empty(), 0);
        for b in 1..nb {
            acc = acc.union(boxes[b - 1]);
            n += counts[b - 1];
            if n == 0 || right_count[b] == 0 {
                continue;
            }
            let cost = TRAVERSAL_COST
                + (acc.half_area() * packets(n) + right_area[b] * packets(right_count[b]))
                    / parent_area;
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((
                    cost,
                    Split {
                        axis,
                        bin: b,
                        ..split0
                    },
                ));
            }
        }
    }
    best.filter(|(c, _)| *c < leaf_cost || refs.len() > MAX_LEAF)
        .map(|(_, s)| s)
}

impl Triangles for Bvh {
    const NAME: &'static str = "bvh";

    fn build(_: &Scene, tris: Vec<[Vec3; 3]>, ids: Vec<TriId>) -> Self {
        Self::new(tris, ids)
    }

    #[inline]
    fn traverse(&self, scene: &Scene, ray: &Ray, any: bool) -> Option<Hit> {
        Self::query(self, scene, ray, any, 0)
    }

    fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<NodeW>()
            + self.packets.len() * std::mem::size_of::<Packet>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::testing::rng;

    /// The box test never turns away a ray that the walk would find a hit for: rays from the box's
    /// faces, edges and corners exactly, along and across its planes (with +0 and -0 direction
    /// components, whose slab distances are infinite or NaN), rays in its rim through the
    /// triangles that make its faces, and random rays; and it does turn away rays that miss the
    /// box (else it would save nothing).
    #[test]
    fn box_test_keeps_every_ray_the_walk_hits() {
        let mut next = rng(17);
        let tris: Vec<[Vec3; 3]> = (0..300)
            .map(|_| {
                let c = Vec3::new(next(), next(), next()) * 4.0 - 2.0;
                [(); 3].map(|_| c + (Vec3::new(next(), next(), next()) - 0.5) * 0.8)
            })
            .collect();
        let ids = (0..tris.len() as u32)
            .map(|i| TriId::new(0, i, false))
            .collect();
        let bvh = Bvh::new(tris.clone(), ids);
        let scene = Scene::default();
        let [lo, hi] = bvh.bounds.map(|r| Vec3::from_slice(&r));
        let mut origins = Vec::new();
        for k in 0..27u32 {
            // Each axis at the lower face, the middle or the upper face.
            let pick = |a: usize| match k / 3u32.pow(a as u32) % 3 {
                0 => lo[a],
                1 => 0.5 * (lo[a] + hi[a]),
                _ => hi[a],
            };
            origins.push(Vec3::new(pick(0), pick(1), pick(2)));
        }
        let axis_dirs = [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z];
        let signed_zero = [Vec3::new(-0.0, 1.0, 0.0), Vec3::new(0.0, -0.0, -1.0)];
        let mut rays = Vec::new();
        for &o in &origins {
            for &d in axis_dirs.iter().chain(&signed_zero) {
                rays.push(Ray::new(o, d));
            }
        }
        for _ in 0..3000 {
            let o = Vec3::new(next(), next(), next()) * 12.0 - 6.0;
            let target = Vec3::new(next(), next(), next()) * 5.0 - 2.5;
            rays.push(Ray::new(o, (target - o).normalize()));
            let d = Vec3::new(next(), next(), next()) - 0.5;
            rays.push(Ray::new(o, d.normalize()));
        }
        // Aimed at every vertex and at points inside every triangle from outside the box: the
        // triangles that make the box's faces are hit where only the box's rim is crossed.
        for t in &tris {
            for target in [
                t[0],
                t[1],
                t[2],
                (t[0] + t[1] + t[2]) / 3.0,
                0.8 * t[0] + 0.2 * t[1],
            ] {
                let o = target + (Vec3::new(next(), next(), next()) - 0.5).normalize() * 10.0;
                rays.push(Ray::new(o, (target - o).normalize()));
            }
        }
        // Through points of every triangle near its vertices, across one axis each (a +0 or -0
        // component there): where the vertex makes a face of the box, the ray stays in its rim.
        for t in &tris {
            let c = (t[0] + t[1] + t[2]) / 3.0;
            for &v in t {
                let q = v + 0.001 * (c - v);
                for a in 0..3 {
                    let mut d = Vec3::new(next(), next(), next()) - 0.5;
                    d[a] = if next() < 0.5 { 0.0 } else { -0.0 };
                    let d = d.normalize();
                    rays.push(Ray::new(q - d * 10.0, d));
                }
            }
        }
        // Along each face, just inside it and exactly on it (with a +0 or -0 component across it):
        // they cross the box's rim only.
        let size = hi - lo;
        for a in 0..3 {
            for (face, inward) in [(lo[a], 1.0), (hi[a], -1.0)] {
                for depth in [0.0, 0.002, 0.01] {
                    for k in 0..40 {
                        let mut d = Vec3::new(next(), next(), next()) - 0.5;
                        d[a] = if k % 2 == 0 { 0.0 } else { -0.0 };
                        let d = d.normalize();
                        let mut p = lo + Vec3::new(next(), next(), next()) * size;
                        p[a] = face + inward * depth * size[a];
                        rays.push(Ray::new(p - d * 10.0, d));
                    }
                }
            }
        }
        let (mut hits, mut turned_away) = (0, 0);
        for ray in &rays {
            let walked = bvh.walk::<false, F4>(&scene, ray, 0);
            let entered = bvh.box_entered(ray);
            assert!(walked.is_none() || entered, "{ray:?} hits {walked:?}");
            hits += walked.is_some() as u32;
            turned_away += !entered as u32;
        }
        assert!(hits > 500, "only {hits} hits");
        assert!(turned_away > 500, "only {turned_away} rays turned away");
    }
}
