//! The composition every Rust backend shares: a structure over the static instances' world-space
//! triangles, then the moving instances (`motion::MovingSet`), then the CSG objects (`ObjectBvh`).
//!
//! Each later layer is asked with the closest hit so far as its limit, so the triangle structure's hot
//! loop stays as it is. `Layered<S>` is generic over the structure (no `dyn`): every backend's walk is
//! inlined into its own `intersect` and `occluded`.

use std::sync::Arc;

use glam::Vec3;

use super::flat::{flatten, TriId};
use super::motion::MovingSet;
use super::objects::ObjectBvh;
use super::Accel;
use crate::geometry::{Hit, Ray, CSG_BIT};
use crate::scene::Scene;

/// A ray-query structure over a set of triangles (the static layer of a `Layered` backend). Hits
/// report the given `TriId`s, and honour alpha-tested materials through `TriId::accepts`.
pub trait Triangles: Send + Sync + Sized {
    /// The backend's name (`Accel::name`).
    const NAME: &'static str;
    /// The structure over `tris` (world space), with `ids` their identities.
    fn build(scene: &Scene, tris: Vec<[Vec3; 3]>, ids: Vec<TriId>) -> Self;
    /// The closest accepted hit in the ray's `(t_min, t_max)`; with `any`, may return the first
    /// found instead.
    fn traverse(&self, scene: &Scene, ray: &Ray, any: bool) -> Option<Hit>;
    /// The closest accepted hit in the ray's `(t_min, t_max)`.
    #[inline]
    fn intersect(&self, scene: &Scene, ray: &Ray) -> Option<Hit> {
        self.traverse(scene, ray, false)
    }
    /// Whether any accepted hit lies in the ray's `(t_min, t_max)`.
    #[inline]
    fn occluded(&self, scene: &Scene, ray: &Ray) -> bool {
        self.traverse(scene, ray, true).is_some()
    }
    /// Bytes held by the structure.
    fn memory_bytes(&self) -> usize;
}

/// A backend: static triangles in `S`, then moving instances, then CSG objects.
pub struct Layered<S> {
    scene: Arc<Scene>,
    statics: S,
    /// Instances that move during the shutter (absent for static scenes).
    moving: Option<Box<MovingSet>>,
    /// The scene's CSG objects, tested after the triangles.
    objects: ObjectBvh,
}

impl<S: Triangles> Layered<S> {
    /// Builds over the scene's static instances (world space, `S::build`), its moving ones and its
    /// CSG objects.
    pub fn build(scene: Arc<Scene>) -> Self {
        Self::build_with(scene, S::build)
    }

    /// As `build`, with the static structure made by `build`.
    pub fn build_with(
        scene: Arc<Scene>,
        build: impl FnOnce(&Scene, Vec<[Vec3; 3]>, Vec<TriId>) -> S,
    ) -> Self {
        let (tris, ids) = flatten(&scene);
        let statics = build(&scene, tris, ids);
        Self {
            moving: MovingSet::build(&scene).map(Box::new),
            objects: ObjectBvh::build(&scene.csg),
            statics,
            scene,
        }
    }

    /// The structure over the static triangles.
    pub fn statics(&self) -> &S {
        &self.statics
    }

    /// The static triangles, then the moving instances.
    #[inline]
    fn triangles_hit(&self, ray: &Ray) -> Option<Hit> {
        let hit = self.statics.intersect(&self.scene, ray);
        match &self.moving {
            None => hit,
            Some(m) => m.intersect(&self.scene, ray, hit, false),
        }
    }
}

impl<S: Triangles> Accel for Layered<S> {
    fn name(&self) -> &'static str {
        S::NAME
    }

    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        // A NaN or zero direction would make every slab test pass and overflow the walk's stack.
        if !ray.is_valid() {
            return None;
        }
        // Decided before the walk, so the walk of a scene without CSG compiles as it did before
        // (testing after it cost 5% on coherent rays).
        if self.objects.is_empty() {
            return self.triangles_hit(ray);
        }
        let best = self.triangles_hit(ray);
        self.objects.intersect(&self.scene.csg, ray, best, CSG_BIT)
    }

    fn occluded(&self, ray: &Ray) -> bool {
        ray.is_valid()
            && (self.statics.occluded(&self.scene, ray)
                || self
                    .moving
                    .as_ref()
                    .is_some_and(|m| m.intersect(&self.scene, ray, None, true).is_some())
                || (!self.objects.is_empty() && self.objects.occluded(&self.scene.csg, ray)))
    }

    fn memory_bytes(&self) -> usize {
        self.statics.memory_bytes() + self.moving.as_ref().map_or(0, |m| m.memory_bytes())
    }
}
