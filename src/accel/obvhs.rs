//! A peer backend that nobody here wrote: the pure-Rust [`obvhs`](https://crates.io/crates/obvhs)
//! crate's compressed wide BVH8 (CWBVH, Ylitie et al. 2017: PLOC build, parallel reinsertion,
//! spatial pre-splits), for `glint bench rays` (`obvhs` cargo feature, off by default).
//!
//! It is fed what the Rust BVH is fed: instances flattened to world-space triangles with the same
//! vertex transform and the same (instance, primitive) identity. The build uses obvhs's
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

use super::flat::{flatten, TriId};
use super::motion::MovingSet;
use super::Accel;
use crate::geometry::{Hit, Ray};
use crate::scene::Scene;

pub struct ObvhsAccel {
    scene: Arc<Scene>,
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
    /// Instances that move during the shutter (absent for static scenes).
    moving: Option<Box<MovingSet>>,
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
    /// Builds with obvhs's `very_slow_build` preset (see the module notes).
    pub fn build(scene: Arc<Scene>) -> Self {
        let (name, params) = chosen_preset();
        Self::build_with(scene, name, params)
    }

    pub fn build_with(scene: Arc<Scene>, preset: &'static str, params: BvhBuildParams) -> Self {
        let scale = world_scale(&scene);
        let (world, ids) = flatten(&scene);
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
                moving: MovingSet::build(&scene).map(Box::new),
                scene,
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
            moving: MovingSet::build(&scene).map(Box::new),
            scene,
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
    fn candidate(&self, r: &ORay, i: usize, ray: &Ray) -> f32 {
        let tri = &self.tris[i];
        let t = tri.intersect(r);
        let id = self.ids[i];
        if t < r.tmax && id.alpha_tested() {
            let uv = tri.compute_barycentric(r);
            if !id.accepts(&self.scene, uv.x, uv.y, ray) {
                return f32::INFINITY;
            }
        }
        t
    }
}

impl ObvhsAccel {
    fn own_intersect(&self, ray: &Ray) -> Option<Hit> {
        if self.tris.is_empty() {
            return None;
        }
        let r = self.ray(ray);
        let mut hit = RayHit::none();
        // `ray_traverse` accepts t < the current tmax only, so a hit is in [t_min, t_max).
        if !self
            .bvh
            .ray_traverse(r, &mut hit, |r, i| self.candidate(r, i, ray))
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

    fn own_occluded(&self, ray: &Ray) -> bool {
        if self.tris.is_empty() {
            return false;
        }
        let r = self.ray(ray);
        // Stops at the first candidate with t < t_max.
        !self
            .bvh
            .ray_traverse_miss(r, |r, i| self.candidate(r, i, ray))
    }
}

impl Accel for ObvhsAccel {
    fn name(&self) -> &'static str {
        "obvhs"
    }

    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let hit = self.own_intersect(ray);
        match &self.moving {
            None => hit,
            Some(m) => m.intersect(&self.scene, ray, hit, false),
        }
    }

    fn occluded(&self, ray: &Ray) -> bool {
        self.own_occluded(ray)
            || self
                .moving
                .as_ref()
                .is_some_and(|m| m.intersect(&self.scene, ray, None, true).is_some())
    }

    fn memory_bytes(&self) -> usize {
        self.moving.as_ref().map_or(0, |m| m.memory_bytes())
            + self.bvh.nodes.len() * std::mem::size_of::<CwBvhNode>()
            + self.bvh.primitive_indices.len() * std::mem::size_of::<u32>()
            + self.tris.len() * std::mem::size_of::<RtTriangle>()
            + self.ids.len() * std::mem::size_of::<TriId>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::bvh::Bvh;
    use crate::accel::compare;
    use crate::accel::testing::scene;
    use crate::scene::{generate, AlphaMode, Instance, Material, Mesh};
    use glam::{Mat4, Vec3, Vec4};

    /// Two displaced icospheres (one flattened from a rotated, scaled instance) and a grid behind.
    fn test_scene() -> Arc<Scene> {
        scene(
            vec![generate::icosphere(4, 0.05), generate::quad_grid(30)],
            vec![
                Instance::new(0, Mat4::IDENTITY),
                Instance::new(
                    0,
                    Mat4::from_translation(Vec3::new(2.5, 0.3, -0.5))
                        * Mat4::from_rotation_y(0.6)
                        * Mat4::from_scale(Vec3::splat(0.7)),
                ),
                Instance::new(
                    1,
                    Mat4::from_translation(Vec3::new(-3.0, -3.0, -2.0))
                        * Mat4::from_scale(Vec3::splat(0.25)),
                ),
            ],
        )
    }

    #[test]
    fn agrees_with_bvh_on_random_rays() {
        let s = test_scene();
        let bvh = Bvh::build(s.clone());
        let rays = compare::random_rays(&s, 200_000, 7);
        for (name, params) in [
            ("very_slow_build", BvhBuildParams::very_slow_build()),
            ("medium_build", BvhBuildParams::medium_build()),
            ("fastest_build", BvhBuildParams::fastest_build()),
        ] {
            let ob = ObvhsAccel::build_with(s.clone(), name, params);
            let g = compare::compare(&s, &ob, &bvh, &rays);
            assert_eq!(g.mismatch_count, 0, "{name}: {:?}", g.mismatches);
            assert_eq!(g.occlusion_mismatches, 0, "{name}");
            assert!(g.hits > rays.len() / 2, "{name}: {} hits", g.hits);
            assert!(g.fraction_same() > 0.999, "{name}: {g:?}");
        }
    }

    /// A 3 mm model, with rays leaving its surfaces: hits nearer than obvhs's absolute 1e-4 box cutoff
    /// must still be found (see `world_scale`).
    #[test]
    fn small_scenes_keep_near_hits() {
        let s = scene(
            vec![generate::icosphere(4, 0.05)],
            vec![Instance::new(0, Mat4::from_scale(Vec3::splat(1e-3)))],
        );
        let bvh = Bvh::build(s.clone());
        let ob = ObvhsAccel::build(s.clone());
        let mut rays = compare::random_rays(&s, 50_000, 11);
        // Start just inside the sphere: the nearest hit is within micrometres.
        for r in &mut rays {
            if let Some(h) = bvh.intersect(r) {
                r.o += r.d * (h.t - 2e-6);
            }
        }
        let g = compare::compare(&s, &ob, &bvh, &rays);
        assert_eq!(g.mismatch_count, 0, "{:?}", g.mismatches);
        assert_eq!(g.occlusion_mismatches, 0);
    }

    #[test]
    fn barycentrics_weight_vertices_1_and_2() {
        let s = test_scene();
        let ob = ObvhsAccel::build(s.clone());
        let bvh = Bvh::build(s.clone());
        let (mut checked, mut close) = (0, 0);
        for ray in compare::random_rays(&s, 20_000, 3) {
            let (Some(h), Some(b)) = (ob.intersect(&ray), bvh.intersect(&ray)) else {
                continue;
            };
            if (h.inst, h.prim) != (b.inst, b.prim) {
                continue;
            }
            let [p0, p1, p2] = s.world_triangle(h.inst, h.prim);
            // Skip grazing hits, where t, u, v are ill-conditioned.
            let n = (p1 - p0).cross(p2 - p0).normalize();
            if n.dot(ray.d.normalize()).abs() < 0.1 {
                continue;
            }
            let p = p0 * (1.0 - h.u - h.v) + p1 * h.u + p2 * h.v;
            let q = ray.o + ray.d * h.t;
            assert!((p - q).length() < 1e-4 * (1.0 + q.length()), "{p} vs {q}");
            // The two triangle tests round differently; far from grazing they agree closely.
            close += ((h.u - b.u).abs() < 1e-4 && (h.v - b.v).abs() < 1e-4) as usize;
            checked += 1;
        }
        assert!(checked > 10_000, "{checked}");
        assert!(close as f64 > 0.99 * checked as f64, "{close} of {checked}");
    }

    #[test]
    fn empty_scene_and_segment_limits() {
        let ob = ObvhsAccel::build(scene(vec![], vec![]));
        assert!(ob.intersect(&Ray::new(Vec3::ZERO, Vec3::Z)).is_none());
        assert!(!ob.occluded(&Ray::new(Vec3::ZERO, Vec3::Z)));
        let ob = ObvhsAccel::build(scene(
            vec![generate::quad_grid(2)],
            vec![Instance::new(0, Mat4::IDENTITY)],
        ));
        let down = Ray::new(Vec3::new(0.5, 0.3, 1.0), -Vec3::Z);
        assert!((ob.intersect(&down).unwrap().t - 1.0).abs() < 1e-6);
        assert!(ob.occluded(&down));
        assert!(!ob.occluded(&Ray::segment(down.o, down.d, 0.99)));
        assert!(ob.occluded(&Ray::segment(down.o, down.d, 1.01)));
        assert!(ob.intersect(&Ray::segment(down.o, down.d, 0.99)).is_none());
        let beyond = Ray {
            t_min: 1.01,
            ..down
        };
        assert!(ob.intersect(&beyond).is_none());
        assert!(!ob.occluded(&beyond));
        assert!(ob.memory_bytes() > 0);
    }

    #[test]
    fn alpha_mask_cuts_out() {
        let quad = || {
            let mut m: Mesh = generate::quad_grid(1);
            m.material = 0;
            m
        };
        for (alpha, visible) in [(0.2, false), (0.8, true)] {
            let mat = Material {
                alpha_mode: AlphaMode::Mask(0.5),
                base_color: Vec4::new(1.0, 1.0, 1.0, alpha),
                ..Default::default()
            };
            assert!(mat.needs_alpha_test());
            let mut masked = quad();
            masked.material = 1;
            let s = Arc::new(Scene {
                meshes: vec![quad(), masked],
                instances: vec![
                    Instance::new(1, Mat4::IDENTITY),
                    Instance::new(0, Mat4::from_translation(Vec3::new(0.0, 0.0, -1.0))),
                ],
                materials: vec![Material::default(), mat],
                ..Default::default()
            });
            let ob = ObvhsAccel::build(s.clone());
            let down = Ray::new(Vec3::new(0.5, 0.25, 1.0), -Vec3::Z);
            let h = ob.intersect(&down).unwrap();
            assert_eq!(h.inst, if visible { 0 } else { 1 }, "alpha {alpha}");
            let shadow = Ray::segment(down.o, down.d, 1.5);
            assert_eq!(ob.occluded(&shadow), visible, "alpha {alpha}");
        }
    }
}
