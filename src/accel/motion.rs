//! Moving instances for the Rust backends: each gets its own object-space BVH and bounds over the
//! shutter; a ray is moved into object space by the inverse of the instance's transform at its time.
//!
//! The transform at a time is the linear interpolation of the instance's `Motion` steps, exactly as
//! Embree interpolates an instance's time steps, so every backend sees an object in the same place.
//! Static instances never come here: they stay in the backends' flat world-space structures, and a
//! backend over a scene without motion holds no `MovingSet` at all. The backends call it after their
//! own traversal with the closest static hit so far (the same shape of call that CSG objects take).

use super::bvh::Bvh;
use super::flat::TriId;
use super::layered::Triangles;
use crate::geometry::{Aabb, Hit, Ray};
use crate::scene::Scene;

/// One moving instance: its bounds over the whole shutter and a bare BVH over its triangles in object
/// space.
struct Moving {
    inst: u32,
    bounds: Aabb,
    bvh: Bvh,
}

/// Every moving instance of a scene (a flat list tested box by box: scenes have few moving objects).
pub struct MovingSet {
    items: Vec<Moving>,
}

impl MovingSet {
    /// The moving instances of `scene`, or None when nothing moves.
    pub fn build(scene: &Scene) -> Option<Self> {
        let items: Vec<Moving> = scene
            .instances
            .iter()
            .enumerate()
            .filter_map(|(i, inst)| {
                let motion = inst.motion.as_ref()?;
                let mesh = &scene.meshes[inst.mesh as usize];
                let alpha = scene.mesh_needs_alpha_test(inst.mesh);
                let tris: Vec<_> = (0..mesh.indices.len() as u32)
                    .map(|p| mesh.triangle(p))
                    .collect();
                let ids = (0..mesh.indices.len() as u32)
                    .map(|p| TriId::new(i as u32, p, alpha))
                    .collect();
                Some(Moving {
                    inst: i as u32,
                    bounds: motion.bounds(&mesh.bounds()),
                    bvh: Bvh::new(tris, ids),
                })
            })
            .collect();
        (!items.is_empty()).then_some(Self { items })
    }

    /// Number of moving instances.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    /// Bytes held by the per-instance structures.
    pub fn memory_bytes(&self) -> usize {
        self.items.iter().map(|m| m.bvh.memory_bytes()).sum()
    }

    /// The closer of `best` (the backend's own hit) and the closest hit on a moving instance; with
    /// `any`, the first hit found.
    pub fn intersect(&self, scene: &Scene, ray: &Ray, best: Option<Hit>, any: bool) -> Option<Hit> {
        if any && best.is_some() {
            return best;
        }
        let mut best = best;
        let inv = ray.d.recip();
        for m in &self.items {
            let t_max = best.map_or(ray.t_max, |h| h.t);
            if m.bounds.clip(ray.o, inv, ray.t_min, t_max).is_none() {
                continue;
            }
            let to_world = scene.instances[m.inst as usize].to_world_at(ray.time);
            let inv = to_world.inverse();
            // Same parameter t in both spaces: the direction is transformed, not renormalised.
            let local = Ray {
                o: inv.transform_point3(ray.o),
                d: inv.transform_vector3(ray.d),
                t_max,
                ..*ray
            };
            if let Some(h) = m.bvh.query(scene, &local, any) {
                best = Some(h);
                if any {
                    break;
                }
            }
        }
        best
    }
}
