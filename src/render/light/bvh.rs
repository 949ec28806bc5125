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
use super::bounds::{Bounds4, BoundsLanes, LightBounds, PackedBounds};
use crate::geometry::Aabb;
use crate::sample::ONE_MINUS_EPS;

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

/// A node of the binary tree. Every leaf is one light, so every choice is made by importance:
/// with leaves of up to four chosen among by power (a blind choice among neighbours, a level
/// fewer), many-emitters had 1.11x the variance per sample for 0.98x the time a sample, 1.11x the
/// time to RMSE 0.01 (two: 1.07x; benches/peers/README.md, with four-wide nodes).
#[derive(Clone, Debug)]
struct Node {
    bounds: PackedBounds,
    /// A leaf's light (its entry), or an interior node's second child (its first follows it).
    index: u32,
    leaf: bool,
}

/// A node of the eight-wide tree that the choice descends: up to eight children side by side.
#[derive(Clone, Copy)]
struct WideNode {
    bounds: [Bounds4; LANES / 4],
    /// Per lane: an interior child's index in `LightBvh::wide`, or a leaf's light.
    index: [u32; LANES],
    /// Per lane: whether it is a leaf (not for an empty lane, whose importance is zero, so it is
    /// never taken).
    leaf: [bool; LANES],
}

impl WideNode {
    /// The importance bounds of the lanes: one eight-wide evaluation where the CPU has AVX, else
    /// two independent four-wide ones; the same bits either way.
    #[inline(always)]
    fn importance(&self, p: Vec3, n: Vec3) -> [f32; LANES] {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: the CPU has AVX (checked just above; std caches the answer).
            return unsafe { self.importance_avx(p, n) };
        }
        // A plain loop: through `map` or `from_fn` the evaluations were copied or not inlined.
        let mut out = [0.0; LANES];
        for (q, b) in self.bounds.iter().enumerate() {
            out[4 * q..4 * q + 4].copy_from_slice(&b.importance(p, n).to_array());
        }
        out
    }

    /// `importance` in one eight-lane evaluation.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    fn importance_avx(&self, p: Vec3, n: Vec3) -> [f32; LANES] {
        const { assert!(LANES == 8) };
        BoundsLanes::halves(&self.bounds[0], &self.bounds[1])
            .importance(p, n)
            .to_array()
    }
}

/// Where a light sits: its trail from the root (bits 3k to 3k + 2: the lane taken at wide depth
/// k).
#[derive(Clone, Copy, Debug)]
enum Place {
    Tree(u64),
    /// Chosen by power among the lights at infinity, at this index of their table.
    Infinite(u32),
    /// Never chosen (no power, or no bounds and not at infinity).
    Nowhere,
}

#[derive(Clone)]
pub(super) struct LightBvh {
    wide: Vec<WideNode>,
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
                // The tree's share against the lights at infinity is by the lights' weights (a
                // spot's bound is not its flux).
                Some(b) => {
                    tree_power += w as f64;
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
        let mut nodes = Vec::with_capacity(2 * items.len());
        if !items.is_empty() {
            build(&mut nodes, &mut items, 0);
        }
        let mut wide = Vec::with_capacity(nodes.len() / 2 + 1);
        if !nodes.is_empty() {
            collapse(&nodes, 0, (0, 0), &mut wide, &mut places);
        }
        Self {
            wide,
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
            let w = Weights::of(node.importance(p, n))?;
            // The first lane whose running sum passes u's share of the total (never an empty one:
            // its running sum is its predecessor's); past the last (rounding), the last nonempty.
            let target = u as f64 * w.sum;
            let passed = w.cum.iter().filter(|&&c| c <= target).count();
            let lane = if passed < LANES {
                passed
            } else {
                w.imp.iter().rposition(|&x| x > 0.0).unwrap_or(LANES - 1)
            };
            let below = w.cum[lane] - w.imp[lane];
            u = (((target - below) / w.imp[lane]) as f32).min(ONE_MINUS_EPS);
            pmf *= w.share(lane);
            if node.leaf[lane] {
                return Some((node.index[lane] as usize, pmf));
            }
            at = node.index[lane] as usize;
        }
    }

    /// The probability that `choose` picks light `i` for `p` and `n`.
    pub fn pmf(&self, p: Vec3, n: Vec3, i: usize) -> f32 {
        let mut trail = match self.places[i] {
            Place::Tree(t) => t,
            Place::Infinite(k) => return self.p_infinite * self.infinite_table.pmf(k as usize),
            Place::Nowhere => return 0.0,
        };
        let mut pmf = 1.0 - self.p_infinite;
        let mut at = 0;
        loop {
            let node = &self.wide[at];
            let Some(w) = Weights::of(node.importance(p, n)) else {
                return 0.0;
            };
            let lane = (trail & (LANES as u64 - 1)) as usize;
            pmf *= w.share(lane);
            if node.leaf[lane] {
                return pmf;
            }
            at = node.index[lane] as usize;
            trail >>= LANE_BITS;
        }
    }
}

/// A wide node's lane importances as `choose` and `pmf` weigh them: in f64, an infinite bound
/// taken as the largest finite one (so that huge bounds near a point light still divide), with
/// their running sums; one division per level, for the lane taken, rather than one per lane.
struct Weights {
    imp: [f64; LANES],
    /// `cum[l]`: the sum of lanes `0..=l`, added in lane order.
    cum: [f64; LANES],
    sum: f64,
}

impl Weights {
    /// `None` when no lane can light the point.
    #[inline(always)]
    fn of(importance: [f32; LANES]) -> Option<Self> {
        let imp = importance.map(|x| x.min(f32::MAX) as f64);
        let mut cum = [0.0; LANES];
        let mut sum = 0.0;
        for (c, &x) in cum.iter_mut().zip(&imp) {
            sum += x;
            *c = sum;
        }
        (sum > 0.0).then_some(Self { imp, cum, sum })
    }

    /// Lane `l`'s probability, the same in `choose` and `pmf`.
    #[inline(always)]
    fn share(&self, l: usize) -> f32 {
        (self.imp[l] / self.sum) as f32
    }
}

/// Makes the wide node for binary node `at` (interior, or the root leaf): its lanes are `at`'s
/// descendants three levels down, or nearer ones where those are leaves. Each lane at wide
/// `depth` is numbered into the trails of the lights below it; returns the node's index in `wide`.
fn collapse(
    binary: &[Node],
    at: usize,
    (depth, trail): (u32, u64),
    wide: &mut Vec<WideNode>,
    places: &mut [Place],
) -> u32 {
    let mut lanes = vec![at];
    if !binary[at].leaf {
        for _ in 0..LANE_BITS {
            lanes = lanes
                .into_iter()
                .flat_map(|c| {
                    let child = &binary[c];
                    if child.leaf {
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
        leaf: [false; LANES],
    });
    for (l, &b) in lanes.iter().enumerate() {
        let lane_trail = trail | (l as u64) << (LANE_BITS * depth);
        let child = &binary[b];
        if child.leaf {
            places[child.index as usize] = Place::Tree(lane_trail);
            wide[me].index[l] = child.index;
            wide[me].leaf[l] = true;
        } else {
            wide[me].index[l] = collapse(binary, b, (depth + 1, lane_trail), wide, places);
        }
    }
    me as u32
}

/// Builds the binary subtree of `items` at `depth` into `nodes` (the node first, then its left
/// subtree, then its right); `collapse` then numbers each light's trail.
fn build(nodes: &mut Vec<Node>, items: &mut [(u32, LightBounds)], depth: u32) -> LightBounds {
    if let [(entry, b)] = items {
        nodes.push(Node {
            bounds: b.packed(),
            index: *entry,
            leaf: true,
        });
        return *b;
    }
    let mid = split(items, depth).unwrap_or_else(|| middle_split(items));
    let at = nodes.len();
    nodes.push(Node {
        bounds: items[0].1.packed(),
        index: 0,
        leaf: false,
    });
    let (left, right) = items.split_at_mut(mid);
    let lb = build(nodes, left, depth + 1);
    nodes[at].index = nodes.len() as u32;
    let rb = build(nodes, right, depth + 1);
    let b = LightBounds::union(&lb, &rb);
    nodes[at].bounds = b.packed();
    b
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
        let (weights, bounds) = lights(1, false);
        let one = bounds[0].unwrap();
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
