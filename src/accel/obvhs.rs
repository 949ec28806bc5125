//! A peer backend that nobody here wrote: the pure-Rust [`obvhs`](https://crates.io/crates/obvhs)
//! crate's compressed wide BVH8 (CWBVH, Ylitie et al. 2017: PLOC build, parallel reinsertion,
//! spatial pre-splits), for `glint bench rays` (`obvhs` cargo feature, off by default).
//!
//! It is fed what the Rust BVH is fed: instances flattened to world-space triangles with the same
//! vertex transform and the same (instance, primitive) identity, and it sits in the same `Layered`
//! composition (moving instances and CSG objects after it). The build uses obvhs's
//! `very_slow_build` preset ("vsb", the best-traversing preset in its published Tray Racing CPU
//! benchmark; `GLINT_OBVHS_PRESET` picks another) and traversal is obvhs's own closest-hit and
//! early-exit walks (`CwBvh::ray_traverse`, `CwBvh::ray_traverse_miss`, its SSE node test) with its
//! `RtTriangle` Möller-Trumbore test, as its benchmark runs them. Triangles are stored in the BVH's
//! primitive order, as its examples recommend, so a leaf indexes them directly.
//!
//! obvhs calls back for every candidate triangle, so alpha-tested materials are honoured as in the
//! other backends: a candidate on such a mesh counts only where `Scene::alpha_passes` says so.
//! Barycentrics are those of vertices 1 and 2 (glint's convention, which is also obvhs's), recomputed
//! from the closest hit after traversal (and per candidate only for alpha-tested triangles).
//!
//! Its triangle test is not watertight, unlike glint's: rays through shared edges can slip through
//! or pick the neighbour, which `accel::compare` classifies as edges and ties.

use std::sync::Arc;
use std::time::Duration;

use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::cwbvh::node::CwBvhNode;
use obvhs::cwbvh::CwBvh;
use obvhs::ray::{Ray as ORay, RayHit};
use obvhs::rt_triangle::RtTriangle;
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;

use super::flat::TriId;
use super::layered::{Layered, Triangles};
use crate::geometry::{Hit, Ray};
use crate::scene::Scene;

/// The `obvhs` backend: obvhs's BVH over the static triangles, then moving instances and CSG objects.
pub type ObvhsAccel = Layered<Obvhs>;

/// obvhs's CWBVH over a set of triangles.
pub struct Obvhs {
    bvh: CwBvh,
    /// World-space triangles in the BVH's primitive order (a pre-split triangle appears once per
    /// leaf that references it).
    tris: Vec<RtTriangle>,
    /// Identity of each entry of `tris`.
    ids: Vec<TriId>,
    /// A power of two by which world space (triangles, ray origins and distances) is scaled for
    /// obvhs; see `world_scale`.
    scale: f32,
    preset: &'static str,
}

/// A power of two that brings the scene's largest coordinate to at least 2^10 (never below 1).
///
/// obvhs 0.4's node test clamps each box's entry distance to an absolute 1e-4
/// (`cwbvh::node::EPSILON`), so a box whose exit lies nearer than that is culled: on a small model
/// (ToyCar is 3 cm across) shadow and bounce rays leaving a surface lose their nearby hits. Scaling
/// by a power of two is exact, so obvhs traces the same triangles and rays with the same rounding,
/// only with that cutoff moved far below anything the scene can resolve.
fn world_scale(scene: &Scene) -> f32 {
    let b = scene.bounds();
    let m = b.min.abs().max(b.max.abs()).max_element();
    if !(m.is_finite() && m > 0.0) {
        return 1.0;
    }
    let k = (10 - m.log2().ceil() as i32).clamp(0, 100);
    2f32.powi(k)
}

/// The obvhs build preset by name (as in its Tray Racing benchmark's `--preset`).
pub fn preset(name: &str) -> Option<BvhBuildParams> {
    Some(match name {
        "fastest_build" => BvhBuildParams::fastest_build(),
        "very_fast_build" => BvhBuildParams::very_fast_build(),
        "fast_build" => BvhBuildParams::fast_build(),
        "medium_build" => BvhBuildParams::medium_build(),
        "slow_build" => BvhBuildParams::slow_build(),
        "very_slow_build" => BvhBuildParams::very_slow_build(),
        _ => return None,
    })
}

/// The preset used by `build`: `very_slow_build`, or `GLINT_OBVHS_PRESET` when it names another.
fn chosen_preset() -> (&'static str, BvhBuildParams) {
    const NAMES: [&str; 6] = [
        "fastest_build",
        "very_fast_build",
        "fast_build",
        "medium_build",
        "slow_build",
        "very_slow_build",
    ];
    let wanted = std::env::var("GLINT_OBVHS_PRESET").unwrap_or_default();
    let name = NAMES
        .into_iter()
        .find(|n| *n == wanted)
        .unwrap_or("very_slow_build");
    (name, preset(name).expect("known preset"))
}

impl ObvhsAccel {
    /// Builds with the obvhs build preset `params` (named `preset`).
    pub fn build_preset(scene: Arc<Scene>, preset: &'static str, params: BvhBuildParams) -> Self {
        Self::build_with(scene, |scene, tris, ids| {
            Obvhs::new(world_scale(scene), tris, ids, preset, params)
        })
    }
}

impl Obvhs {
    /// The BVH over these world-space triangles, scaled by `scale` for obvhs (see `world_scale`).
    pub fn new(
        scale: f32,
        world: Vec<[glam::Vec3; 3]>,
        ids: Vec<TriId>,
        preset: &'static str,
        params: BvhBuildParams,
    ) -> Self {
        let tris: Vec<Triangle> = world
            .iter()
            .map(|t| {
                // obvhs has its own glam: hand the coordinates over as arrays.
                let [a, b, c] = t.map(|v| (v * scale).to_array());
                Triangle {
                    v0: a.into(),
                    v1: b.into(),
                    v2: c.into(),
                }
            })
            .collect();
        if tris.is_empty() {
            return Self {
                bvh: CwBvh::default(),
                tris: Vec::new(),
                ids: Vec::new(),
                scale,
                preset,
            };
        }
        let bvh = build_cwbvh_from_tris(&tris, params, &mut Duration::default());
        let (tris, ids) = bvh
            .primitive_indices
            .iter()
            .map(|&i| (RtTriangle::from(&tris[i as usize]), ids[i as usize]))
            .unzip();
        Self {
            bvh,
            tris,
            ids,
            scale,
            preset,
        }
    }

    /// The obvhs build preset this structure was built with.
    pub fn preset(&self) -> &'static str {
        self.preset
    }

    pub fn node_count(&self) -> usize {
        self.bvh.nodes.len()
    }

    /// obvhs's view of a glint ray. Adding +0.0 turns a -0.0 direction component into +0.0: obvhs
    /// 0.4's node test picks the near slab by `direction < 0.0` but inverts -0.0 to a large negative
    /// number, so an axis-parallel ray with a -0.0 component (e.g. `-Vec3::Z`) would miss every box.
    /// Origins and distances are scaled by `self.scale` (directions are not).
    #[inline(always)]
    fn ray(&self, ray: &Ray) -> ORay {
        ORay::new(
            (ray.o * self.scale).to_array().into(),
            (ray.d + glam::Vec3::ZERO).to_array().into(),
            ray.t_min * self.scale,
            ray.t_max * self.scale,
        )
    }

    /// The triangle test for candidate `i`: obvhs's distance, or infinity where the candidate misses
    /// (or lies in a cutout of an alpha-tested material).
    #[inline(always)]
    fn candidate(&self, scene: &Scene, r: &ORay, i: usize, ray: &Ray) -> f32 {
        let tri = &self.tris[i];
        let t = tri.intersect(r);
        let id = self.ids[i];
        if t < r.tmax && id.alpha_tested() {
            let uv = tri.compute_barycentric(r);
            if !id.accepts(scene, uv.x, uv.y, ray) {
                return f32::INFINITY;
            }
        }
        t
    }
}

impl Triangles for Obvhs {
    const NAME: &'static str = "obvhs";

    /// With obvhs's `very_slow_build` preset (see the module notes).
    fn build(scene: &Scene, tris: Vec<[glam::Vec3; 3]>, ids: Vec<TriId>) -> Self {
        let (name, params) = chosen_preset();
        Self::new(world_scale(scene), tris, ids, name, params)
    }

    /// The closest hit whatever `any` says: `occluded` has its own traversal, which stops at the
    /// first candidate.
    fn traverse(&self, scene: &Scene, ray: &Ray, _any: bool) -> Option<Hit> {
        if self.tris.is_empty() {
            return None;
        }
        let r = self.ray(ray);
        let mut hit = RayHit::none();
        // `ray_traverse` accepts t < the current tmax only, so a hit is in [t_min, t_max).
        if !self
            .bvh
            .ray_traverse(r, &mut hit, |r, i| self.candidate(scene, r, i, ray))
        {
            return None;
        }
        let i = hit.primitive_id as usize;
        let uv = self.tris[i].compute_barycentric(&r);
        let id = self.ids[i];
        Some(Hit {
            t: hit.t / self.scale,
            u: uv.x,
            v: uv.y,
            inst: id.inst(),
            prim: id.prim,
        })
    }

    fn occluded(&self, scene: &Scene, ray: &Ray) -> bool {
        if self.tris.is_empty() {
            return false;
        }
        let r = self.ray(ray);
        // Stops at the first candidate with t < t_max.
        !self
            .bvh
            .ray_traverse_miss(r, |r, i| self.candidate(scene, r, i, ray))
    }

    fn memory_bytes(&self) -> usize {
        self.bvh.nodes.len() * std::mem::size_of::<CwBvhNode>()
            + self.bvh.primitive_indices.len() * std::mem::size_of::<u32>()
            + self.tris.len() * std::mem::size_of::<RtTriangle>()
            + self.ids.len() * std::mem::size_of::<TriId>()
    }
}

#[cfg(test)]
mod tests {
    // Queries are tested with every backend's in `accel::conformance`.
    use super::*;

    #[test]
    fn small_scenes_are_scaled_up_by_powers_of_two() {
        use crate::scene::generate;
        let mut s = generate::single_mesh_scene(generate::icosphere(2, 0.0));
        for (scale, scaled) in [(1e-3f32, true), (1.0, true), (1e4, false)] {
            s.instances[0].to_world = glam::Mat4::from_scale(glam::Vec3::splat(scale));
            let b = s.bounds();
            let m = b.min.abs().max(b.max.abs()).max_element();
            let k = world_scale(&s);
            assert_eq!(k.log2().fract(), 0.0, "{k}");
            if scaled {
                assert!((512.0..=1024.0).contains(&(k * m)), "{scale}: {k} * {m}");
            } else {
                assert_eq!(k, 1.0);
            }
        }
        assert!(preset("very_slow_build").is_some() && preset("no_such").is_none());
    }
}
