//! A uniform voxel grid over world-space triangles (`--backend grid`): instances flattened as the BVH
//! flattens them, cells sized from the triangle count (about `lambda` triangles' worth of cells per
//! triangle, shaped by the bounds' aspect; coarser where large triangles would span too many of
//! them, `SPAN_BUDGET`), stored compactly (per-cell offsets into one flat array of
//! four-triangle packets, as the BVH's leaves) and built in parallel. Rays walk the cells with the
//! 3D-DDA of Amanatides and Woo, test each cell's packets with the four-wide watertight test the BVH
//! uses (lanes already tested by the ray are masked out by a small per-ray mailbox, and a packet with
//! no lane left is skipped), and stop as soon as the closest hit lies in the cell being walked, so
//! both backends return the same hits.
//!
//! Robustness: cell crossings are computed directly from the cell boundaries (never accumulated), the
//! start cell is chosen consistently with those crossings, and every triangle is inserted into the
//! cells its box overlaps after padding by a few float spacings of the scene's magnitude, which
//! covers the rounding of the crossings and of the hit points.

use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;

use glam::Vec3;
use rayon::prelude::*;

use super::flat::{take_lanes, TriId};
use super::layered::{Layered, Triangles};
use crate::geometry::triangle::{self, RayShear, Tri4};
use crate::geometry::{Aabb, Hit, Ray};
use crate::scene::Scene;

/// The `grid` backend: the grid over the static triangles, then moving instances and CSG objects.
pub type GridAccel = Layered<Grid>;

/// Cells per triangle the resolution aims at (measured: see `GridAccel::build_lambda`).
pub const DEFAULT_LAMBDA: f32 = 0.5;
/// Most cells along one axis.
pub const MAX_CELLS_PER_AXIS: u32 = 512;
/// Most cells in all (4 bytes of offsets each).
pub const MAX_CELLS: usize = 1 << 24;
/// Slots of the per-ray mailbox (a direct-mapped cache of recently tested triangles).
const MAILBOX: usize = 64;
/// Triangles whose box spans more cells than this are checked against each cell's box by their plane.
const PLANE_TEST_MIN_CELLS: usize = 2;
/// The most cells the triangles' boxes may span in all (each is visited once to insert, and its
/// cell entries are at most that many), or 8 a triangle where that is more: past it the resolution
/// halves until they fit. A triangle across the whole grid spans every cell, up to `MAX_CELLS`: a
/// thousand of them in a large scan's grid would mean 1.7e10 cell tests, and some 44,000 more
/// entries than the u32 offsets hold. Models span about two cells a triangle (ToyCar 0.21M for 109k
/// triangles, icosphere:8 2.0M for 1.3M, MetalRoughSpheresNoTextures 1.8M for 1.0M), far inside it.
const SPAN_BUDGET: u64 = 1 << 26;

/// The uniform grid over a set of triangles.
pub struct Grid {
    /// World-space vertices, by triangle index (build input only: emptied once the cells are packed).
    tris: Vec<[Vec3; 3]>,
    ids: Vec<TriId>,
    /// Grid bounds (the triangles' bounds, padded).
    min: Vec3,
    max: Vec3,
    res: [u32; 3],
    cell_size: Vec3,
    inv_cell_size: Vec3,
    /// Padding added to every triangle box before insertion.
    pad: f32,
    /// Per cell (x fastest), the range `offsets[c]..offsets[c + 1]` of `packets`; `cells + 1` entries.
    offsets: Vec<u32>,
    /// Every cell's triangles, ascending by index, four to a packet (a cell's last packet may have
    /// unused lanes, which never hit).
    packets: Vec<Tri4>,
    /// The triangle index of each packet lane (`u32::MAX` for unused lanes), for the mailbox and ids.
    lanes: Vec<[u32; 4]>,
    /// Triangle references over all cells.
    entries: usize,
}

impl GridAccel {
    /// Builds with `lambda` cells per triangle (before clamping). With cells tested four triangles
    /// at a time, 0.25 to 1 is the sweet spot (`examples/grid_bench`: 0.5 is 1.4x as fast as 3 on
    /// an icosphere and 1.3x on the bunny): fewer cells hold more triangles each, more cells cost
    /// more steps of the walk (mostly through empty cells) and memory.
    pub fn build_lambda(scene: Arc<Scene>, lambda: f32) -> Self {
        Self::build_with(scene, |_, tris, ids| Grid::new(tris, ids, lambda))
    }
}

impl Grid {
    /// The grid over these world-space triangles, with `lambda` cells per triangle.
    pub fn new(tris: Vec<[Vec3; 3]>, ids: Vec<TriId>, lambda: f32) -> Self {
        let bounds = tris
            .par_iter()
            .map(|t| Aabb::from_points(*t))
            .reduce(|| Aabb::EMPTY, Aabb::union);
        if tris.is_empty() || bounds.is_empty() {
            return Self {
                tris,
                ids,
                min: Vec3::ZERO,
                max: Vec3::ZERO,
                res: [1; 3],
                cell_size: Vec3::ZERO,
                inv_cell_size: Vec3::ZERO,
                pad: 0.0,
                offsets: vec![0, 0],
                packets: Vec::new(),
                lanes: Vec::new(),
                entries: 0,
            };
        }
        // Rounding of crossings and hit points is a few float spacings of the coordinates involved:
        // the scene's own, and ray origins up to a scene diagonal away from it.
        let magnitude =
            bounds.min.abs().max(bounds.max.abs()).max_element() + bounds.extent().length();
        let pad = 16.0 * f32::EPSILON * magnitude;
        let min = bounds.min - Vec3::splat(pad);
        let max = bounds.max + Vec3::splat(pad);
        let budget = SPAN_BUDGET.max(8 * tris.len() as u64).min(u32::MAX as u64);
        let mut grid = Self {
            tris,
            ids,
            min,
            max,
            res: [1; 3],
            cell_size: Vec3::ZERO,
            inv_cell_size: Vec3::ZERO,
            pad,
            offsets: Vec::new(),
            packets: Vec::new(),
            lanes: Vec::new(),
            entries: 0,
        };
        grid.set_resolution(resolution(max - min, grid.tris.len(), lambda));
        while grid.res != [1; 3] && grid.spanned_cells() > budget {
            grid.set_resolution(grid.res.map(|r| (r / 2).max(1)));
        }
        grid.fill();
        grid
    }

    fn set_resolution(&mut self, res: [u32; 3]) {
        let extent = self.max - self.min;
        let resf = Vec3::new(res[0] as f32, res[1] as f32, res[2] as f32);
        self.res = res;
        self.cell_size = extent / resf;
        self.inv_cell_size = Vec3::select(extent.cmpgt(Vec3::ZERO), resf / extent, Vec3::ZERO);
    }

    /// The cells the triangles' padded boxes span, summed: a bound on the insertion's work and on
    /// the entries it makes.
    fn spanned_cells(&self) -> u64 {
        self.tris
            .par_iter()
            .map(|t| self.box_cells(t).2 as u64)
            .sum()
    }

    /// The first and last cell (per axis) that the padded box of `t` overlaps, and how many cells
    /// that box spans.
    #[inline]
    fn box_cells(&self, t: &[Vec3; 3]) -> ([usize; 3], [usize; 3], usize) {
        let b = Aabb::from_points(*t);
        let pad = Vec3::splat(self.pad);
        let (lo, hi) = (self.cell_of(b.min - pad), self.cell_of(b.max + pad));
        (lo, hi, (0..3).map(|a| hi[a] - lo[a] + 1).product())
    }

    /// Count pass, prefix sum, fill pass, then each cell's list sorted (so the layout, and the order
    /// in which ties are met, never depends on thread scheduling) and packed four to a packet.
    fn fill(&mut self) {
        let cells = self.cell_count();
        let counts: Vec<AtomicU32> = (0..cells).map(|_| AtomicU32::new(0)).collect();
        self.tris.par_iter().for_each(|t| {
            self.for_each_cell(t, |c| {
                counts[c].fetch_add(1, Ordering::Relaxed);
            })
        });
        let mut offsets = Vec::with_capacity(cells + 1);
        let mut total = 0u64;
        offsets.push(0u32);
        for c in &counts {
            total += c.load(Ordering::Relaxed) as u64;
            // At most the spanned cells, which `new` keeps within a budget far below 2^32.
            offsets.push(u32::try_from(total).expect("cell entries within the span budget"));
        }
        drop(counts);
        let cursor: Vec<AtomicU32> = offsets[..cells]
            .iter()
            .map(|&o| AtomicU32::new(o))
            .collect();
        let refs: Vec<AtomicU32> = (0..total).map(|_| AtomicU32::new(0)).collect();
        self.tris.par_iter().enumerate().for_each(|(i, t)| {
            self.for_each_cell(t, |c| {
                let k = cursor[c].fetch_add(1, Ordering::Relaxed);
                refs[k as usize].store(i as u32, Ordering::Relaxed);
            })
        });
        drop(cursor);
        let mut refs: Vec<u32> = refs.into_iter().map(AtomicU32::into_inner).collect();
        // Sort every cell's list, in blocks of cells (each block's entries are one contiguous run).
        const BLOCK: usize = 4096;
        let mut blocks = Vec::with_capacity(cells / BLOCK + 1);
        let mut rest: &mut [u32] = &mut refs;
        for c0 in (0..cells).step_by(BLOCK) {
            let c1 = (c0 + BLOCK).min(cells);
            let len = (offsets[c1] - offsets[c0]) as usize;
            let (block, tail) = rest.split_at_mut(len);
            blocks.push((c0, c1, block));
            rest = tail;
        }
        blocks.into_par_iter().for_each(|(c0, c1, block)| {
            let base = offsets[c0];
            for c in c0..c1 {
                let (s, e) = (
                    (offsets[c] - base) as usize,
                    (offsets[c + 1] - base) as usize,
                );
                block[s..e].sort_unstable();
            }
        });
        // Pack every cell's list into packets of four, in blocks of cells.
        let pack = |c0: usize, c1: usize| {
            let mut out = Vec::new();
            for c in c0..c1 {
                let list = &refs[offsets[c] as usize..offsets[c + 1] as usize];
                out.extend(Tri4::packets(list, &self.tris));
            }
            out
        };
        let (packets, lanes): (Vec<Tri4>, Vec<[u32; 4]>) = (0..cells.div_ceil(BLOCK))
            .into_par_iter()
            .flat_map_iter(|b| pack(b * BLOCK, ((b + 1) * BLOCK).min(cells)))
            .unzip();
        let mut packet_offsets = Vec::with_capacity(cells + 1);
        let mut n = 0u32;
        packet_offsets.push(0);
        for c in 0..cells {
            n += (offsets[c + 1] - offsets[c]).div_ceil(4);
            packet_offsets.push(n);
        }
        debug_assert_eq!(n as usize, packets.len());
        self.entries = refs.len();
        self.offsets = packet_offsets;
        self.packets = packets;
        self.lanes = lanes;
        self.tris = Vec::new();
    }

    /// Calls `f` with every cell that the padded box of `t` overlaps and, for triangles spanning
    /// several cells, whose padded box the triangle's plane passes through.
    #[inline]
    fn for_each_cell(&self, t: &[Vec3; 3], mut f: impl FnMut(usize)) {
        let pad = Vec3::splat(self.pad);
        let (lo, hi, span) = self.box_cells(t);
        let [nx, ny, _] = self.res.map(|r| r as usize);
        // The plane test, conservative: a margin far above the rounding of the normal and distance.
        let e1 = t[1] - t[0];
        let e2 = t[2] - t[0];
        let n = e1.cross(e2);
        let n_abs = n.abs();
        let err = 1e-4 * e1.abs().max_element() * e2.abs().max_element();
        let plane = span > PLANE_TEST_MIN_CELLS;
        for z in lo[2]..=hi[2] {
            for y in lo[1]..=hi[1] {
                for x in lo[0]..=hi[0] {
                    if plane {
                        let cmin =
                            self.min + Vec3::new(x as f32, y as f32, z as f32) * self.cell_size;
                        let half = self.cell_size * 0.5 + pad;
                        let center = cmin + self.cell_size * 0.5;
                        let rel = center - t[0];
                        let dist = n.dot(rel).abs();
                        let reach = n_abs.dot(half);
                        let margin = err * (rel.abs().max_element() + half.max_element());
                        if dist > reach + margin {
                            continue;
                        }
                    }
                    f((z * ny + y) * nx + x);
                }
            }
        }
    }

    /// The cell holding a point, clamped to the grid.
    #[inline]
    fn cell_of(&self, p: Vec3) -> [usize; 3] {
        let q = ((p - self.min) * self.inv_cell_size).to_array();
        std::array::from_fn(|a| (q[a].floor().max(0.0) as usize).min(self.res[a] as usize - 1))
    }

    /// Cells per axis.
    pub fn resolution(&self) -> [u32; 3] {
        self.res
    }

    pub fn cell_count(&self) -> usize {
        self.res.iter().map(|&r| r as usize).product()
    }

    /// Triangle references over all cells (a triangle counts once per cell it is listed in).
    pub fn entry_count(&self) -> usize {
        self.entries
    }

    /// Cells holding at least one triangle.
    pub fn occupied_cells(&self) -> usize {
        self.offsets.windows(2).filter(|w| w[1] > w[0]).count()
    }

    /// Ray parameter where the ray crosses boundary `k` of `axis` (computed the same way everywhere).
    #[inline(always)]
    fn crossing(&self, axis: usize, k: i32, o: f32, inv: f32) -> f32 {
        (self.min[axis] + k as f32 * self.cell_size[axis] - o) * inv
    }

    /// Walks the cells along the ray, keeping the closest accepted hit; with `any`, returns the first.
    /// (Negated comparisons are deliberate: a NaN distance or limit ends the walk.)
    #[inline(always)]
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    fn query(&self, scene: &Scene, ray: &Ray, any: bool) -> Option<Hit> {
        if self.packets.is_empty() {
            return None;
        }
        let o = ray.o.to_array();
        let d = ray.d.to_array();
        let inv_d = ray.d.recip();
        let inv = inv_d.to_array();
        // Clip the segment to the grid box (conservative, as the BVH's slab test).
        let bounds = Aabb {
            min: self.min,
            max: self.max,
        };
        let (t0, t1) = bounds.clip(ray.o, inv_d, ray.t_min, ray.t_max)?;
        // The start cell, chosen consistently with the crossings that the walk computes.
        let mut cell = [0i32; 3];
        let mut step = [0i32; 3];
        let mut t_next = [f32::INFINITY; 3];
        for a in 0..3 {
            let n = self.res[a] as i32;
            let p = o[a] + t0 * d[a];
            let mut i = ((p - self.min[a]) * self.inv_cell_size[a])
                .floor()
                .clamp(0.0, (n - 1) as f32) as i32;
            if !inv[a].is_finite() || d[a] == 0.0 {
                // Parallel to this axis: the ray never leaves the slab it starts in.
                cell[a] = i;
                continue;
            }
            if d[a] > 0.0 {
                while i + 1 < n && self.crossing(a, i + 1, o[a], inv[a]) <= t0 {
                    i += 1;
                }
                while i > 0 && self.crossing(a, i, o[a], inv[a]) > t0 {
                    i -= 1;
                }
                step[a] = 1;
                t_next[a] = self.crossing(a, i + 1, o[a], inv[a]);
            } else {
                while i > 0 && self.crossing(a, i, o[a], inv[a]) <= t0 {
                    i -= 1;
                }
                while i + 1 < n && self.crossing(a, i + 1, o[a], inv[a]) > t0 {
                    i += 1;
                }
                step[a] = -1;
                t_next[a] = self.crossing(a, i, o[a], inv[a]);
            }
            cell[a] = i;
        }
        let [nx, ny, _] = self.res.map(|r| r as i32);
        let sh = RayShear::new(ray.d);
        let mut t_max = ray.t_max;
        let mut best: Option<Hit> = None;
        let mut mailbox = [u32::MAX; MAILBOX];
        loop {
            let c = ((cell[2] * ny + cell[1]) * nx + cell[0]) as usize;
            let (s, e) = (self.offsets[c] as usize, self.offsets[c + 1] as usize);
            for p in s..e {
                // Lanes whose triangle was tested already (or unused lanes) are left out.
                let lanes = self.lanes[p];
                let mut live = 0u32;
                for (l, &id) in lanes.iter().enumerate() {
                    let slot = id as usize % MAILBOX;
                    if id == u32::MAX || mailbox[slot] == id {
                        continue;
                    }
                    mailbox[slot] = id;
                    live |= 1 << l;
                }
                if live == 0 {
                    continue;
                }
                let h = triangle::intersect4(ray.o, &sh, &self.packets[p], ray.t_min, t_max);
                let ids = |lane| self.ids[lanes[lane] as usize];
                if take_lanes(
                    any,
                    &h,
                    h.mask & live,
                    ids,
                    scene,
                    ray,
                    &mut t_max,
                    &mut best,
                ) {
                    return best;
                }
            }
            // Leave through the nearest boundary; stop once no farther cell can hold a nearer hit.
            let axis = if t_next[0] < t_next[1] {
                if t_next[0] < t_next[2] {
                    0
                } else {
                    2
                }
            } else if t_next[1] < t_next[2] {
                1
            } else {
                2
            };
            let t_exit = t_next[axis];
            if !(t_exit < t_max) || !(t_exit <= t1) || step[axis] == 0 {
                return best;
            }
            cell[axis] += step[axis];
            if cell[axis] < 0 || cell[axis] >= self.res[axis] as i32 {
                return best;
            }
            let k = cell[axis] + (step[axis] > 0) as i32;
            t_next[axis] = self.crossing(axis, k, o[axis], inv[axis]);
        }
    }
}

/// Cells per axis for `n` triangles in a box of `extent`: `extent_axis * (lambda n / volume)^(1/3)`,
/// where axes too thin for one cell get one and the others share the density; clamped per axis and
/// in total.
fn resolution(extent: Vec3, n: usize, lambda: f32) -> [u32; 3] {
    let e = extent.to_array().map(|x| x as f64);
    let target = (lambda.max(1e-3) as f64 * n as f64).max(1.0);
    let mut thin = e.map(|x| !(x > 0.0 && x.is_finite()));
    let mut res = [1u32; 3];
    for _ in 0..3 {
        let dims = thin.iter().filter(|&&t| !t).count();
        if dims == 0 {
            break;
        }
        let volume: f64 = (0..3).filter(|&a| !thin[a]).map(|a| e[a]).product();
        let density = (target / volume).powf(1.0 / dims as f64);
        let mut changed = false;
        for a in 0..3 {
            if thin[a] {
                res[a] = 1;
                continue;
            }
            let cells = e[a] * density;
            if cells < 1.0 {
                thin[a] = true;
                changed = true;
            }
            res[a] = cells.round().clamp(1.0, MAX_CELLS_PER_AXIS as f64) as u32;
        }
        if !changed {
            break;
        }
    }
    let total: f64 = res.iter().map(|&r| r as f64).product();
    if total > MAX_CELLS as f64 {
        let s = (MAX_CELLS as f64 / total).cbrt();
        res = res.map(|r| ((r as f64 * s).floor() as u32).max(1));
    }
    res
}

impl Triangles for Grid {
    const NAME: &'static str = "grid";

    fn build(_: &Scene, tris: Vec<[Vec3; 3]>, ids: Vec<TriId>) -> Self {
        Self::new(tris, ids, DEFAULT_LAMBDA)
    }

    #[inline]
    fn traverse(&self, scene: &Scene, ray: &Ray, any: bool) -> Option<Hit> {
        Self::query(self, scene, ray, any)
    }

    fn memory_bytes(&self) -> usize {
        self.tris.len() * std::mem::size_of::<[Vec3; 3]>()
            + self.ids.len() * std::mem::size_of::<TriId>()
            + self.offsets.len() * 4
            + self.packets.len() * std::mem::size_of::<Tri4>()
            + self.lanes.len() * std::mem::size_of::<[u32; 4]>()
    }
}

#[cfg(test)]
mod tests {
    // Queries are tested with every backend's in `accel::conformance`.
    use super::*;
    use crate::accel::testing::{brute, scene};
    use crate::accel::Accel;
    use crate::scene::{generate, Instance, Mesh};
    use glam::Mat4;

    /// Triangles across the whole of a fine grid: the resolution halves until the cells their
    /// boxes span fit the budget, and the coarser grid still finds what brute force finds.
    #[test]
    fn huge_triangles_across_a_fine_grid_coarsen_it() {
        let mut r = crate::accel::testing::rng(7);
        let mut mesh = Mesh::default();
        let mut add = |t: [Vec3; 3]| {
            let k = mesh.positions.len() as u32;
            mesh.positions.extend(t);
            mesh.normals.extend([Vec3::Z; 3]);
            mesh.indices.push([k, k + 1, k + 2]);
        };
        // Enough small triangles in the unit cube to ask for about 46^3 cells...
        for _ in 0..200_000 {
            let c = Vec3::new(r(), r(), r());
            add([
                c,
                c + Vec3::new(1e-3, 0.0, 0.0),
                c + Vec3::new(0.0, 1e-3, 1e-3),
            ]);
        }
        // ...and a fan of a thousand about its diagonal, each box spanning every cell (97M in all).
        for i in 0..1000 {
            let a = i as f32 / 1000.0;
            add([Vec3::ZERO, Vec3::ONE, Vec3::new(1.0, a, 1.0 - a)]);
        }
        let s = scene(vec![mesh], vec![Instance::new(0, Mat4::IDENTITY)]);
        let g = GridAccel::build(s.clone());
        let grid = g.statics();
        let asked = resolution(Vec3::ONE, 201_000, DEFAULT_LAMBDA);
        assert!(asked.iter().all(|&a| a >= 40), "{asked:?}");
        assert!(
            grid.resolution()
                .iter()
                .zip(&asked)
                .all(|(&got, &a)| got <= a / 2),
            "{:?} against {asked:?}",
            grid.resolution()
        );
        assert!(grid.entry_count() as u64 <= SPAN_BUDGET);
        for i in 0..200 {
            let o = Vec3::new(r(), r(), 2.0);
            let d = (Vec3::new(r(), r(), 0.0) - o).normalize();
            let ray = Ray::new(o, d);
            assert_eq!(g.intersect(&ray), brute(&s, &ray), "ray {i}");
        }
    }

    #[test]
    fn empty_and_flat_scenes_get_degenerate_grids() {
        let g = GridAccel::build(scene(vec![], vec![]));
        assert_eq!(g.statics().entry_count(), 0);
        let s = scene(
            vec![generate::quad_grid(8)],
            vec![Instance::new(0, Mat4::IDENTITY)],
        );
        let g = GridAccel::build(s);
        assert_eq!(
            g.statics().resolution()[2],
            1,
            "a flat scene gets one cell across"
        );
        assert!(g.statics().cell_count() > 1);
        // Rays that are no rays: NaN and zero directions, NaN limits.
        for ray in [
            Ray::new(Vec3::new(1.0, 1.0, 1.0), Vec3::ZERO),
            Ray::new(Vec3::new(1.0, 1.0, 1.0), Vec3::NAN),
            Ray::segment(Vec3::new(1.0, 1.0, 1.0), -Vec3::Z, f32::NAN),
        ] {
            assert!(g.intersect(&ray).is_none());
        }
    }

    #[test]
    fn resolution_follows_count_and_aspect() {
        assert_eq!(resolution(Vec3::ZERO, 100, 3.0), [1, 1, 1]);
        let r = resolution(Vec3::new(4.0, 2.0, 1.0), 1000, 3.0);
        let total: u32 = r.iter().product();
        assert!(r[0] > r[1] && r[1] > r[2], "{r:?}");
        assert!((1500..6000).contains(&total), "{r:?}");
        // Flat and line-like boxes: the thin axes get one cell, the density goes to the others.
        let r = resolution(Vec3::new(1.0, 1.0, 0.0), 1000, 3.0);
        assert_eq!(r[2], 1);
        assert!(r[0] > 40 && r[0] == r[1], "{r:?}");
        let r = resolution(Vec3::new(10.0, 1e-7, 0.0), 1000, 3.0);
        assert_eq!(r, [MAX_CELLS_PER_AXIS, 1, 1]);
        // Caps: per axis and in total.
        let r = resolution(Vec3::ONE, 1 << 30, 8.0);
        assert!(r.iter().all(|&x| x <= MAX_CELLS_PER_AXIS));
        assert!(r.iter().map(|&x| x as usize).product::<usize>() <= MAX_CELLS);
    }
}
