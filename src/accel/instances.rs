//! The instances the Rust backends trace in object space rather than flatten: moving ones, and the
//! static copies of meshes placed many times (a forest of one tree, EXT_mesh_gpu_instancing).
//!
//! Each such mesh gets one object-space BVH that all its instances share (its hits name instance 0,
//! and each instance asks with its own index as the base), and a median-split tree over the
//! instances' world bounds (over the shutter for moving ones) orders them front to back. A ray is
//! moved into object space by the inverse of the instance's transform: precomputed for a static
//! instance, and for a moving one the inverse of the linear interpolation of its `Motion` steps at
//! the ray's time, exactly as Embree interpolates an instance's time steps. The parameter t is the
//! same in both spaces (the direction is transformed, not renormalised), and so are barycentrics.

use glam::Mat4;
use rayon::prelude::*;

use super::bvh::Bvh;
use super::flat::TriId;
use super::layered::Triangles;
use super::objects::ObjectBvh;
use crate::geometry::{Aabb, Hit, Ray};
use crate::scene::Scene;

/// A mesh placed more than once is traced through its instances, rather than copied into the
/// flat world-space structure, when its copies would hold more than this many triangles. Below it,
/// copying keeps the one-level walk, faster per ray (100k tetrahedra as instances traced at 0.30x
/// the rays per second of the same triangles flattened, `benches/scenes/instances.py`); above it,
/// the copies' memory (some 40 bytes a triangle) outweighs that.
pub const FLATTEN_LIMIT: usize = 1 << 22;

/// For each instance of `scene`, whether the Rust backends trace it here (true) or flatten it: the
/// moving ones, and those of meshes placed more than once whose copies hold more than `limit`
/// triangles (`FLATTEN_LIMIT` in the backends).
pub fn traced_as_instances(scene: &Scene, limit: usize) -> Vec<bool> {
    let mut uses = vec![0usize; scene.meshes.len()];
    for inst in &scene.instances {
        uses[inst.mesh as usize] += 1;
    }
    let copied = |m: usize| uses[m].saturating_mul(scene.meshes[m].indices.len());
    scene
        .instances
        .iter()
        .map(|inst| {
            let m = inst.mesh as usize;
            inst.motion.is_some() || (uses[m] > 1 && copied(m) > limit)
        })
        .collect()
}

/// One instance traced here.
struct Placed {
    /// Index in `Scene::instances`.
    inst: u32,
    /// Its mesh's structure in `InstanceSet::meshes`.
    bvh: u32,
    /// World to object for a static instance; None for a moving one (inverted at the ray's time).
    from_world: Option<Mat4>,
}

/// The instances of a scene traced in object space.
pub struct InstanceSet {
    /// Over the world bounds of `placed` (its items are indices into it).
    tree: ObjectBvh,
    placed: Vec<Placed>,
    /// One object-space BVH per mesh with an instance here.
    meshes: Vec<Bvh>,
}

impl InstanceSet {
    /// The instances of `scene` marked in `traced` (see `traced_as_instances`), or None for none.
    pub fn build(scene: &Scene, traced: &[bool]) -> Option<Self> {
        let mut slot = vec![u32::MAX; scene.meshes.len()];
        let mut mesh_ids = Vec::new();
        let mut placed = Vec::new();
        for (i, inst) in scene.instances.iter().enumerate() {
            if !traced[i] {
                continue;
            }
            let m = inst.mesh as usize;
            if slot[m] == u32::MAX {
                slot[m] = mesh_ids.len() as u32;
                mesh_ids.push(inst.mesh);
            }
            placed.push(Placed {
                inst: i as u32,
                bvh: slot[m],
                from_world: inst.motion.is_none().then(|| inst.to_world.inverse()),
            });
        }
        if placed.is_empty() {
            return None;
        }
        let meshes = mesh_ids
            .par_iter()
            .map(|&m| {
                let mesh = &scene.meshes[m as usize];
                let alpha = scene.mesh_needs_alpha_test(m);
                let n = mesh.indices.len() as u32;
                let tris = (0..n).map(|p| mesh.triangle(p)).collect();
                Bvh::new(tris, (0..n).map(|p| TriId::new(0, p, alpha)).collect())
            })
            .collect();
        let object_bounds: Vec<Aabb> = mesh_ids
            .iter()
            .map(|&m| scene.meshes[m as usize].bounds())
            .collect();
        let bounds: Vec<Aabb> = placed
            .par_iter()
            .map(|p| {
                let inst = &scene.instances[p.inst as usize];
                let object = &object_bounds[p.bvh as usize];
                match &inst.motion {
                    Some(motion) => motion.bounds(object),
                    None => object.transformed(&inst.to_world),
                }
                .padded()
            })
            .collect();
        Some(Self {
            tree: ObjectBvh::over(bounds.into_iter()),
            placed,
            meshes,
        })
    }

    /// Number of instances traced here.
    pub fn len(&self) -> usize {
        self.placed.len()
    }

    pub fn is_empty(&self) -> bool {
        self.placed.is_empty()
    }

    /// Bytes held by the shared mesh structures and the per-instance records.
    pub fn memory_bytes(&self) -> usize {
        self.meshes.iter().map(|b| b.memory_bytes()).sum::<usize>()
            + self.placed.len() * std::mem::size_of::<Placed>()
            + self.tree.memory_bytes()
    }

    /// The closer of `best` (the backend's own hit) and the closest hit on these instances; with
    /// `any`, the first hit found.
    pub fn intersect(&self, scene: &Scene, ray: &Ray, best: Option<Hit>, any: bool) -> Option<Hit> {
        if any && best.is_some() {
            return best;
        }
        let mut best = best;
        let mut t_max = best.map_or(ray.t_max, |h| h.t);
        let start = Ray { t_max, ..*ray };
        self.tree.walk(&start, |i| {
            let p = &self.placed[i as usize];
            let from_world = p.from_world.unwrap_or_else(|| {
                scene.instances[p.inst as usize]
                    .to_world_at(ray.time)
                    .inverse()
            });
            let local = Ray {
                o: from_world.transform_point3(ray.o),
                d: from_world.transform_vector3(ray.d),
                t_max,
                ..*ray
            };
            if let Some(h) = self.meshes[p.bvh as usize].query(scene, &local, any, p.inst) {
                t_max = h.t;
                best = Some(h);
                return (any, t_max);
            }
            (false, t_max)
        });
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{generate, Instance};
    use glam::Vec3;

    /// A box placed `n` times along x, 3 apart.
    fn row(n: usize) -> Scene {
        let instances = (0..n)
            .map(|k| {
                Instance::new(
                    0,
                    Mat4::from_translation(Vec3::new(3.0 * k as f32, 0.0, 0.0)),
                )
            })
            .collect();
        generate::scene_of(
            vec![generate::box_mesh(Vec3::splat(-1.0), Vec3::splat(1.0))],
            instances,
        )
    }

    /// Twelve triangles a box: four boxes hold 48, a single one is never instanced.
    #[test]
    fn a_mesh_is_traced_as_instances_once_its_copies_pass_the_limit() {
        assert!(traced_as_instances(&row(4), 48).iter().all(|t| !t));
        assert!(traced_as_instances(&row(4), 47).iter().all(|t| *t));
        assert!(traced_as_instances(&row(1), 0).iter().all(|t| !t));
    }

    /// A ray along the row from the far end hits the last box first and names it; one that starts
    /// between boxes k and k+1 heading back names box k; both in world units.
    #[test]
    fn hits_name_their_instance_and_world_distance() {
        let n = 16;
        let scene = row(n);
        let set = InstanceSet::build(&scene, &traced_as_instances(&scene, 0)).unwrap();
        assert_eq!(set.len(), n);
        let far = 3.0 * n as f32 + 10.0;
        let h = set
            .intersect(
                &scene,
                &Ray::new(Vec3::new(far, 0.2, 0.3), -Vec3::X),
                None,
                false,
            )
            .unwrap();
        assert_eq!(h.inst as usize, n - 1);
        assert!(
            (h.t - (far - (3.0 * (n - 1) as f32 + 1.0))).abs() < 1e-4,
            "{}",
            h.t
        );
        for k in 0..n - 1 {
            let o = Vec3::new(3.0 * k as f32 + 1.5, 0.2, 0.3);
            let h = set
                .intersect(&scene, &Ray::new(o, -Vec3::X), None, false)
                .unwrap();
            assert_eq!(h.inst as usize, k);
            assert!((h.t - 0.5).abs() < 1e-5, "{}", h.t);
            // A nearer hit already in hand wins; a farther one loses.
            let near = Hit {
                t: 0.25,
                u: 0.0,
                v: 0.0,
                inst: 99,
                prim: 0,
            };
            assert_eq!(
                set.intersect(&scene, &Ray::new(o, -Vec3::X), Some(near), false)
                    .unwrap()
                    .inst,
                99
            );
            assert!(set
                .intersect(&scene, &Ray::new(o, Vec3::Y), None, true)
                .is_none());
        }
    }
}
