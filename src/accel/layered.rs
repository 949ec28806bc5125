//! The composition every Rust backend shares: a structure over the flattened instances' world-space
//! triangles, then the instances traced in object space (`instances::InstanceSet`: moving ones and
//! copies of meshes placed many times), then the CSG objects (`ObjectBvh`).
//!
//! Each later layer is asked with the closest hit so far as its limit, so the triangle structure's hot
//! loop stays as it is. `Layered<S>` is generic over the structure (no `dyn`): every backend's walk is
//! inlined into its own `intersect` and `occluded`.

use std::sync::Arc;

use glam::Vec3;

use super::flat::{flatten, TriId};
use super::instances::{traced_as_instances, InstanceSet, FLATTEN_LIMIT};
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

/// A backend: flattened triangles in `S`, then instances traced in object space, then CSG objects.
pub struct Layered<S> {
    scene: Arc<Scene>,
    statics: S,
    /// Instances traced in object space (absent when every instance is flattened).
    instances: Option<Box<InstanceSet>>,
    /// The scene's CSG objects, tested after the triangles.
    objects: ObjectBvh,
}

impl<S: Triangles> Layered<S> {
    /// Builds over the scene's flattened instances (world space, `S::build`), the others and its CSG
    /// objects.
    pub fn build(scene: Arc<Scene>) -> Self {
        Self::build_with(scene, S::build)
    }

    /// As `build`, with the static structure made by `build`.
    pub fn build_with(
        scene: Arc<Scene>,
        build: impl FnOnce(&Scene, Vec<[Vec3; 3]>, Vec<TriId>) -> S,
    ) -> Self {
        Self::build_limited(scene, build, FLATTEN_LIMIT)
    }

    /// As `build_with`, flattening shared meshes only while their copies hold at most `limit`
    /// triangles (`instances::traced_as_instances`).
    pub fn build_limited(
        scene: Arc<Scene>,
        build: impl FnOnce(&Scene, Vec<[Vec3; 3]>, Vec<TriId>) -> S,
        limit: usize,
    ) -> Self {
        let traced = traced_as_instances(&scene, limit);
        let (tris, ids) = flatten(&scene, &traced);
        let statics = build(&scene, tris, ids);
        Self {
            instances: InstanceSet::build(&scene, &traced).map(Box::new),
            objects: ObjectBvh::build(&scene.csg),
            statics,
            scene,
        }
    }

    /// The structure over the flattened triangles.
    pub fn statics(&self) -> &S {
        &self.statics
    }

    /// The flattened triangles, then the instances.
    #[inline]
    fn triangles_hit(&self, ray: &Ray) -> Option<Hit> {
        let hit = self.statics.intersect(&self.scene, ray);
        match &self.instances {
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
                    .instances
                    .as_ref()
                    .is_some_and(|m| m.intersect(&self.scene, ray, None, true).is_some())
                || (!self.objects.is_empty() && self.objects.occluded(&self.scene.csg, ray)))
    }

    fn memory_bytes(&self) -> usize {
        self.statics.memory_bytes() + self.instances.as_ref().map_or(0, |m| m.memory_bytes())
    }
}
