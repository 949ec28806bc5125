//! The light BVH (Conty Estevez & Kulla 2018; pbrt-v4's `BVHLightSampler`): lights with bounds in
//! a tree, one chosen per shading point by descending it in proportion to each child's
//! `LightBounds::importance` there; lights at infinity are chosen beside it by power.
//!
//! The tree is built binary (the surface-area-orientation split) and then collapsed three levels at
//! a time into eight-wide nodes, whose eight children's bounds two four-wide SIMD evaluations give
//! side by side: a third of the levels of the binary descent, whose steps wait on one another. The
//! probability of a choice is the product of the child probabilities along the light's path, which
//! every light keeps as a trail of 3-bit lane numbers, so `pmf` repeats `choose`'s arithmetic
//! exactly.

use glam::Vec3;

use super::alias::AliasTable;
use super::bounds::{Bounds4, LightBounds, PackedBounds};
use crate::geometry::Aabb;
use crate::sample::ONE_MINUS_EPS;

/// Most lights in a leaf, chosen among by power. One: every choice is made by importance. With
/// leaves of four (a blind choice among neighbours, a level fewer) many-emitters had 1.11x the
/// variance per sample for 0.98x the time a sample, 1.11x the time to RMSE 0.01 (two: 1.07x;
/// benches/peers/README.md, with four-wide nodes).
const LEAF_LIGHTS: usize = 1;
/// Buckets per axis of the split search.
const BUCKETS: usize = 12;
/// From this depth on, nodes split in the middle, so no trail outgrows its 64 bits: 21 wide levels
/// hold 63 binary ones, 31 of them for 2^32 lights.
const BALANCED_FROM_DEPTH: u32 = 31;
/// Children of a wide node, and the bits of a trail that name one. Sixteen (four evaluations)
/// took many-emitters' sigma from 0.405 to 0.393 but cost 15% more a sample: 1.09x the time to
/// RMSE 0.01.
const LANES: usize = 8;
const LANE_BITS: u32 = 3;

#[derive(Clone, Debug)]
struct Node {
    bounds: PackedBounds,
    /// A leaf's first light in `LightBvh::leaf_lights`, or an interior node's second child (its
    /// first follows it).
    index: u32,
    /// A leaf's number of lights; 0 for interior nodes.
    lights: u32,
}

/// A light of a leaf: its entry, and its share of the leaf's power with the running sum of the
/// shares up to it (the choice within the leaf).
#[derive(Clone, Copy, Debug)]
struct LeafLight {
    entry: u32,
    share: f32,
    cdf: f32,
}

/// A node of the eight-wide tree that the choice descends: up to eight children side by side.
#[derive(Clone, Copy)]
struct WideNode {
    bounds: [Bounds4; LANES / 4],
    /// Per lane: an interior child's index in `LightBvh::wide`, or a leaf's first light in
    /// `LightBvh::leaf_lights`.
    index: [u32; LANES],
    /// Per lane: a leaf's number of lights; 0 for an interior child (and an empty lane, whose
    /// importance is zero, so it is never taken).
    lights: [u32; LANES],
}

impl WideNode {
    /// The importance bounds of the lanes (independent four-wide evaluations).
    #[inline(always)]
    fn importance(&self, p: Vec3, n: Vec3) -> [f32; LANES] {
        // A plain loop: through `map` or `from_fn` the evaluations were copied or not inlined.
        let mut out = [0.0; LANES];
        for (q, b) in self.bounds.iter().enumerate() {
            out[4 * q..4 * q + 4].copy_from_slice(&b.importance(p, n));
        }
        out
    }
}

/// Where a light sits: its trail from the root (bits 3k to 3k + 2: the lane taken at wide depth
/// k) and its share of its leaf.
#[derive(Clone, Copy, Debug)]
enum Place {
    Tree(u64, f32),
    /// Chosen by power among the lights at infinity, at this index of their table.
    Infinite(u32),
    /// Never chosen (no power, or no bounds and not at infinity).
    Nowhere,
}

#[derive(Clone)]
pub(super) struct LightBvh {
    wide: Vec<WideNode>,
    leaf_lights: Vec<LeafLight>,
    places: Vec<Place>,
    infinite: Vec<u32>,
    infinite_table: AliasTable,
    /// The probability of choosing among the lights at infinity rather than in the tree: their
    /// share of the total power.
    p_infinite: f32,
}

impl LightBvh {
    /// The BVH over `n` lights: `bounds(i)` for each light in the tree (`None` for lights at
    /// infinity, whose weights come from `weights`).
    pub fn new(weights: &[f32], bounds: impl Fn(usize) -> Option<LightBounds>) -> Self {
        let n = weights.len();
        let mut places = vec![Place::Nowhere; n];
        let (mut items, mut infinite) = (Vec::new(), Vec::new());
        let (mut tree_power, mut infinite_power) = (0.0f64, 0.0f64);
        for (i, &w) in weights.iter().enumerate() {
            if w.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) || !w.is_finite() {
                continue;
            }
            match bounds(i) {
                Some(b) => {
                    tree_power += b.phi as f64;
                    items.push((i as u32, b));
                }
                None => {
                    places[i] = Place::Infinite(infinite.len() as u32);
                    infinite_power += w as f64;
                    infinite.push(i as u32);
                }
            }
        }
        let infinite_weights: Vec<f32> = infinite.iter().map(|&i| weights[i as usize]).collect();
        let total = tree_power + infinite_power;
        let p_infinite = if total > 0.0 {
            (infinite_power / total) as f32
        } else {
            0.0
        };
        let mut tree = Tree {
            nodes: Vec::with_capacity(2 * items.len()),
            leaf_lights: Vec::with_capacity(items.len()),
            places: &mut places,
        };
        if !items.is_empty() {
            tree.build(&mut items, 0, 0);
        }
        let (nodes, leaf_lights) = (tree.nodes, tree.leaf_lights);
        let mut wide = Vec::with_capacity(nodes.len() / 2 + 1);
        if !nodes.is_empty() {
            collapse(&nodes, 0, (0, 0), &mut wide, &leaf_lights, &mut places);
        }
        Self {
            wide,
            leaf_lights,
            places,
            infinite,
            infinite_table: AliasTable::new(&infinite_weights),
            p_infinite,
        }
    }

    /// A light for the point `p` with unit normal `n` (zero: none) and `u` in [0, 1), with its
    /// probability.
    pub fn choose(&self, p: Vec3, n: Vec3, u: f32) -> Option<(usize, f32)> {
        if u < self.p_infinite || self.wide.is_empty() {
            let u = (u / self.p_infinite).min(ONE_MINUS_EPS);
            let (k, pk) = self.infinite_table.sample(u)?;
            return Some((self.infinite[k] as usize, pk * self.p_infinite));
        }
        let mut u = ((u - self.p_infinite) / (1.0 - self.p_infinite)).min(ONE_MINUS_EPS);
        let mut pmf = 1.0 - self.p_infinite;
        let mut at = 0;
        loop {
            let node = &self.wide[at];
            let shares = shares(node.importance(p, n))?;
            // The lane whose interval of [0, 1) holds u; past the last (rounding), the last taken.
            let (mut lane, mut below, mut sum) = (0, 0.0, 0.0);
            for (l, &s) in shares.iter().enumerate() {
                if s > 0.0 {
                    (lane, below) = (l, sum);
                    if u < sum + s {
                        break;
                    }
                }
                sum += s;
            }
            let share = shares[lane];
            u = ((u - below) / share).min(ONE_MINUS_EPS);
            pmf *= share;
            if node.lights[lane] > 0 {
                let leaf =
                    &self.leaf_lights[node.index[lane] as usize..][..node.lights[lane] as usize];
                let l = leaf
                    .iter()
                    .find(|l| u < l.cdf)
                    .unwrap_or(&leaf[leaf.len() - 1]);
                return Some((l.entry as usize, pmf * l.share));
            }
            at = node.index[lane] as usize;
        }
    }

    /// The probability that `choose` picks light `i` for `p` and `n`.
    pub fn pmf(&self, p: Vec3, n: Vec3, i: usize) -> f32 {
        let (mut trail, share) = match self.places[i] {
            Place::Tree(t, share) => (t, share),
            Place::Infinite(k) => return self.p_infinite * self.infinite_table.pmf(k as usize),
            Place::Nowhere => return 0.0,
        };
        let mut pmf = 1.0 - self.p_infinite;
        let mut at = 0;
        loop {
            let node = &self.wide[at];
            let Some(shares) = shares(node.importance(p, n)) else {
                return 0.0;
            };
            let lane = (trail & (LANES as u64 - 1)) as usize;
            pmf *= shares[lane];
            if node.lights[lane] > 0 {
                return pmf * share;
            }
            at = node.index[lane] as usize;
            trail >>= LANE_BITS;
        }
    }
}

/// Each lane's share of the importances, `None` when none can light the point (the ratios in
/// f64, an infinite bound taken as the largest finite one, so that huge bounds near a point light
/// still divide).
#[inline(always)]
fn shares(importance: [f32; LANES]) -> Option<[f32; LANES]> {
    let imp = importance.map(|x| x.min(f32::MAX) as f64);
    let sum: f64 = imp.iter().sum();
    (sum > 0.0).then(|| imp.map(|x| (x / sum) as f32))
}

/// Makes the wide node for binary node `at` (interior, or the root leaf): its lanes are `at`'s
/// descendants three levels down, or nearer ones where those are leaves. Each lane at wide `depth` is numbered into
/// the trails of the lights below it; returns the node's index in `wide`.
fn collapse(
    binary: &[Node],
    at: usize,
    (depth, trail): (u32, u64),
    wide: &mut Vec<WideNode>,
    leaf_lights: &[LeafLight],
    places: &mut [Place],
) -> u32 {
    let node = &binary[at];
    let mut lanes = vec![at];
    if node.lights == 0 {
        for _ in 0..LANE_BITS {
            lanes = lanes
                .into_iter()
                .flat_map(|c| {
                    let child = &binary[c];
                    if child.lights > 0 {
                        vec![c]
                    } else {
                        vec![c + 1, child.index as usize]
                    }
                })
                .collect();
        }
    }
    let bounds: Vec<PackedBounds> = lanes.iter().map(|&b| binary[b].bounds).collect();
    let mut quads = bounds.chunks(4);
    let me = wide.len();
    wide.push(WideNode {
        bounds: std::array::from_fn(|_| Bounds4::new(quads.next().unwrap_or(&[]))),
        index: [0; LANES],
        lights: [0; LANES],
    });
    for (l, &b) in lanes.iter().enumerate() {
        let lane_trail = trail | (l as u64) << (LANE_BITS * depth);
        let child = &binary[b];
        if child.lights > 0 {
            let first = child.index as usize;
            for ll in &leaf_lights[first..first + child.lights as usize] {
                places[ll.entry as usize] = Place::Tree(lane_trail, ll.share);
            }
            wide[me].index[l] = child.index;
            wide[me].lights[l] = child.lights;
        } else {
            let k = collapse(
                binary,
                b,
                (depth + 1, lane_trail),
                wide,
                leaf_lights,
                places,
            );
            wide[me].index[l] = k;
        }
    }
    me as u32
}

/// The tree while it is built.
struct Tree<'a> {
    nodes: Vec<Node>,
    leaf_lights: Vec<LeafLight>,
    places: &'a mut [Place],
}

impl Tree<'_> {
    /// Builds the subtree of `items` at `depth` with bit trail `trail`, appending its nodes (the
    /// node first, then its left subtree, then its right) and recording each light's place.
    fn build(&mut self, items: &mut [(u32, LightBounds)], depth: u32, trail: u64) -> LightBounds {
        if items.len() <= LEAF_LIGHTS {
            return self.leaf(items, trail);
        }
        let mid = split(items, depth).unwrap_or_else(|| middle_split(items));
        let at = self.nodes.len();
        self.nodes.push(Node {
            bounds: items[0].1.packed(),
            index: 0,
            lights: 0,
        });
        let (left, right) = items.split_at_mut(mid);
        let lb = self.build(left, depth + 1, trail);
        self.nodes[at].index = self.nodes.len() as u32;
        let rb = self.build(right, depth + 1, trail | (1 << depth));
        let b = LightBounds::union(&lb, &rb);
        self.nodes[at].bounds = b.packed();
        b
    }

    fn leaf(&mut self, items: &[(u32, LightBounds)], trail: u64) -> LightBounds {
        let b = items
            .iter()
            .map(|(_, b)| *b)
            .reduce(|a, b| LightBounds::union(&a, &b))
            .expect("a leaf has lights");
        self.nodes.push(Node {
            bounds: b.packed(),
            index: self.leaf_lights.len() as u32,
            lights: items.len() as u32,
        });
        let total: f64 = items.iter().map(|(_, l)| l.phi as f64).sum();
        let mut cdf = 0.0f64;
        for &(entry, l) in items {
            let share = (l.phi as f64 / total) as f32;
            cdf += l.phi as f64 / total;
            self.places[entry as usize] = Place::Tree(trail, share);
            self.leaf_lights.push(LeafLight {
                entry,
                share,
                cdf: cdf as f32,
            });
        }
        b
    }
}

/// The split of `items` (sorted in place into two groups) of least surface-area-orientation
/// cost over `BUCKETS` buckets of centroids along each axis; `None` where every centroid is the
/// same or the depth calls for balance.
fn split(items: &mut [(u32, LightBounds)], depth: u32) -> Option<usize> {
    if depth >= BALANCED_FROM_DEPTH {
        return None;
    }
    let total = items
        .iter()
        .fold(Aabb::EMPTY, |b, (_, l)| b.union(l.bounds));
    let centroids = Aabb::from_points(items.iter().map(|(_, l)| l.centroid()));
    let extent = total.extent();
    let c_extent = centroids.extent();
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in 0..3 {
        // Also skips NaN extents.
        if c_extent[axis].partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            continue;
        }
        let mut buckets: [Option<LightBounds>; BUCKETS] = [None; BUCKETS];
        for (_, l) in items.iter() {
            let b = &mut buckets[bucket_of(l, axis, &centroids)];
            *b = Some(b.map_or(*l, |b| LightBounds::union(&b, l)));
        }
        // Boxes thin along the split axis are cheap to split across it.
        let regularity = extent.max_element() / extent[axis].max(f32::MIN_POSITIVE);
        let cost = |group: &[Option<LightBounds>]| {
            group
                .iter()
                .flatten()
                .copied()
                .reduce(|a, b| LightBounds::union(&a, &b))
                .map_or(0.0, |b| b.cost(regularity))
        };
        for s in 1..BUCKETS {
            let c = cost(&buckets[..s]) + cost(&buckets[s..]);
            if c.is_finite() && best.is_none_or(|(bc, _, _)| c < bc) {
                best = Some((c, axis, s));
            }
        }
    }
    let (_, axis, s) = best?;
    let mut mid = 0;
    for i in 0..items.len() {
        if bucket_of(&items[i].1, axis, &centroids) < s {
            items.swap(i, mid);
            mid += 1;
        }
    }
    (mid > 0 && mid < items.len()).then_some(mid)
}

/// The bucket along `axis` of `l`'s centroid among `centroids` (of positive extent on `axis`).
fn bucket_of(l: &LightBounds, axis: usize, centroids: &Aabb) -> usize {
    let t = (l.centroid()[axis] - centroids.min[axis]) / centroids.extent()[axis];
    ((t * BUCKETS as f32) as usize).min(BUCKETS - 1)
}

/// Halves `items` by centroid along the axis where the centroids spread most.
fn middle_split(items: &mut [(u32, LightBounds)]) -> usize {
    let centroids = Aabb::from_points(items.iter().map(|(_, l)| l.centroid()));
    let e = centroids.extent();
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |a, b| {
        a.1.centroid()[axis].total_cmp(&b.1.centroid()[axis])
    });
    mid
}

#[cfg(test)]
mod tests {
    use super::super::bounds::Cone;
    use super::*;

    fn unit(k: u64) -> f32 {
        (crate::geometry::mix64(k) >> 40) as f32 / (1u64 << 24) as f32
    }

    fn point(k: u64) -> Vec3 {
        Vec3::new(unit(3 * k), unit(3 * k + 1), unit(3 * k + 2)) * 4.0 - 2.0
    }

    /// `n` small lights of assorted power and facing, with one light at infinity when `sky`.
    fn lights(n: usize, sky: bool) -> (Vec<f32>, Vec<Option<LightBounds>>) {
        let mut weights = Vec::new();
        let mut bounds = Vec::new();
        for i in 0..n as u64 {
            let c = point(i + 100);
            let w = 0.1 + unit(7 * i + 5) * 3.0;
            let normal = (point(i + 5000) + Vec3::splat(1e-3)).normalize();
            weights.push(w);
            bounds.push(Some(LightBounds {
                bounds: Aabb::from_points([c - Vec3::splat(0.02), c + Vec3::splat(0.02)]),
                phi: w,
                normals: Cone {
                    w: normal,
                    cos_theta: 1.0,
                },
                cos_theta_e: 0.0,
                two_sided: i % 3 == 0,
            }));
        }
        // A light of no power is never chosen.
        weights.push(0.0);
        bounds.push(bounds[0].map(|b| LightBounds { phi: 0.0, ..b }));
        if sky {
            weights.push(5.0);
            bounds.push(None);
        }
        (weights, bounds)
    }

    #[test]
    fn choices_follow_the_pmf_and_only_lights_that_reach_are_chosen() {
        for (n, sky) in [(1, false), (2, true), (37, false), (300, true)] {
            let (weights, bounds) = lights(n, sky);
            let bvh = LightBvh::new(&weights, |i| bounds[i]);
            for k in 0..20u64 {
                let p = point(k) * 1.5;
                let nrm = if k % 2 == 0 {
                    Vec3::ZERO
                } else {
                    point(k + 77).normalize()
                };
                let pmf: Vec<f32> = (0..weights.len()).map(|i| bvh.pmf(p, nrm, i)).collect();
                assert_eq!(pmf[n], 0.0, "the powerless light");
                // Unbiased: every light whose own bounds say it reaches the point can be chosen
                // (its ancestors' bounds are looser). What leads only to lights that cannot is
                // lost, or spent on them within a leaf.
                for (i, b) in bounds.iter().enumerate().take(n) {
                    if b.unwrap().importance(p, nrm) > 0.0 {
                        assert!(pmf[i] > 0.0, "light {i} of {n}");
                    }
                }
                let total: f32 = pmf.iter().sum();
                assert!(total <= 1.0 + 1e-4, "{n} lights: pmf sums to {total}");
                // A stratified sweep of u: each light's share of the strata is its pmf, and
                // the probability returned with a choice is the pmf.
                let m = 20_000;
                let mut counts = vec![0u32; weights.len()];
                let mut none = 0;
                for j in 0..m {
                    if let Some((i, pi)) = bvh.choose(p, nrm, (j as f32 + 0.5) / m as f32) {
                        assert!((pi - pmf[i]).abs() <= 1e-5 * pmf[i].max(1e-3), "{i}");
                        counts[i] += 1;
                    } else {
                        none += 1;
                    }
                }
                let lost = none as f32 / m as f32;
                assert!(
                    (lost - (1.0 - total)).abs() <= 40.0 / m as f32,
                    "{lost} vs {total}"
                );
                for (i, &c) in counts.iter().enumerate() {
                    let f = c as f32 / m as f32;
                    // The strata quantise the pmf's intervals: one stratum per tree level.
                    assert!(
                        (f - pmf[i]).abs() <= 40.0 / m as f32,
                        "{n} lights, light {i}: chosen {f}, pmf {}",
                        pmf[i]
                    );
                }
            }
        }
    }

    /// Lights that no split can tell apart (one box, one power) are halved by the middle split
    /// down to leaves of one, several wide levels deep, and each is as likely as the others.
    #[test]
    fn coincident_lights_are_chosen_alike_through_middle_splits() {
        let n = 1000;
        let (mut weights, bounds) = lights(1, false);
        let one = bounds[0].unwrap();
        weights.truncate(1);
        let bvh = LightBvh::new(&vec![weights[0]; n], |_| Some(one));
        let p = one.centroid() + one.normals.w * 0.5;
        let total: f32 = (0..n).map(|i| bvh.pmf(p, Vec3::ZERO, i)).sum();
        assert!((total - 1.0).abs() < 1e-4, "{total}");
        let mut counts = vec![0u32; n];
        let m = 100 * n;
        for j in 0..m {
            let (i, pi) = bvh
                .choose(p, Vec3::ZERO, (j as f32 + 0.5) / m as f32)
                .unwrap();
            assert!((pi * n as f32 - 1.0).abs() < 1e-3, "light {i}: {pi}");
            counts[i] += 1;
        }
        // Stratified u over equal shares: each light takes its 100 strata, give or take the
        // rounding at each of the levels.
        assert!(
            counts.iter().all(|&c| (96..=104).contains(&c)),
            "{:?}",
            &counts[..20]
        );
    }

    #[test]
    fn far_from_all_lights_the_choice_is_by_power() {
        let (weights, bounds) = lights(50, false);
        let bvh = LightBvh::new(&weights, |i| bounds[i]);
        let total: f32 = weights.iter().sum();
        // Two-sided, isotropic lights seen from afar: the bounds' orientation terms all near 1.
        let iso: Vec<Option<LightBounds>> = bounds
            .iter()
            .map(|b| {
                b.map(|b| LightBounds {
                    normals: Cone::SPHERE,
                    ..b
                })
            })
            .collect();
        let far = LightBvh::new(&weights, |i| iso[i]);
        let p = Vec3::new(1e6, 0.0, 0.0);
        for (i, w) in weights.iter().enumerate().take(50) {
            let expected = w / total;
            assert!((far.pmf(p, Vec3::ZERO, i) - expected).abs() < 1e-3 * expected);
        }
        // Near a light, in front of it, its share rises above its power's share.
        let b = bounds[7].unwrap();
        let near = b.centroid() + b.normals.w * 0.05;
        assert!(bvh.pmf(near, Vec3::ZERO, 7) > 2.0 * weights[7] / total);
    }
}
