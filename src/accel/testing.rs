//! Helpers for the accelerators' unit tests: a brute-force reference and a small deterministic RNG.
//! Compiled only for tests.

use crate::geometry::triangle::{self, RayShear};
use crate::geometry::{Hit, Ray};
use std::sync::Arc;

use glam::{Mat4, Vec3};

use super::Accel;
use crate::scene::{generate, Instance, Material, Mesh, Scene};

/// A shared scene of the meshes and instances, with the default material.
pub fn scene(meshes: Vec<Mesh>, instances: Vec<Instance>) -> Arc<Scene> {
    Arc::new(generate::scene_of(meshes, instances))
}

/// Brute force over every triangle of every instance (static, opaque): the closest hit, the
/// reference the Rust backends must match exactly (they use the same triangle test).
pub fn brute(s: &Scene, ray: &Ray) -> Option<Hit> {
    let sh = RayShear::new(ray.d);
    let mut best: Option<Hit> = None;
    for (i, inst) in s.instances.iter().enumerate() {
        for p in 0..s.meshes[inst.mesh as usize].indices.len() as u32 {
            let [a, b, c] = s.world_triangle(i as u32, p);
            let t_max = best.map_or(ray.t_max, |b| b.t);
            if let Some(h) = triangle::intersect(ray.o, &sh, a, b, c, ray.t_min, t_max) {
                best = Some(Hit {
                    t: h.t,
                    u: h.u,
                    v: h.v,
                    inst: i as u32,
                    prim: p,
                });
            }
        }
    }
    best
}

/// `brute` as an accelerator, for `compare::compare`.
pub struct Brute(pub Arc<Scene>);

impl Accel for Brute {
    fn name(&self) -> &'static str {
        "brute force"
    }

    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        brute(&self.0, ray)
    }

    fn occluded(&self, ray: &Ray) -> bool {
        brute(&self.0, ray).is_some()
    }
}

/// Uniform numbers in [0, 1) from a xorshift generator.
pub fn rng(seed: u64) -> impl FnMut() -> f32 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The unit quad [0,1]^2 at z = 0: triangle 0 = (0,1,2), triangle 1 = (0,2,3).
pub fn quad() -> Mesh {
    Mesh {
        name: "quad".into(),
        positions: vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ],
        normals: vec![Vec3::Z; 4],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Default::default()
    }
}

/// A validated shared scene of the meshes, instances and materials.
pub fn scene_with(
    meshes: Vec<Mesh>,
    instances: Vec<Instance>,
    materials: Vec<Material>,
) -> Arc<Scene> {
    let s = Scene {
        meshes,
        instances,
        materials,
        ..Default::default()
    };
    s.validate().expect("valid test scene");
    Arc::new(s)
}

/// A ray straight down (-z) from `o`.
pub fn down(o: Vec3) -> Ray {
    Ray::new(o, Vec3::NEG_Z)
}

/// A quad of material `mat` (material 1) placed once directly (inst 0, over an opaque quad at
/// z = -1, inst 3) and twice more at x = 10 and x = 20 as a second mesh (insts 1, 2).
pub fn alpha_quads(mat: Material) -> Arc<Scene> {
    let mut masked = quad();
    masked.material = 1;
    scene_with(
        vec![quad(), masked.clone(), masked],
        vec![
            Instance::new(1, Mat4::IDENTITY),
            Instance::new(2, Mat4::from_translation(Vec3::new(10.0, 0.0, 0.0))),
            Instance::new(2, Mat4::from_translation(Vec3::new(20.0, 0.0, 0.0))),
            Instance::new(0, Mat4::from_translation(Vec3::new(0.0, 0.0, -1.0))),
        ],
        vec![Material::default(), mat],
    )
}

/// Asserts that `a`'s batched queries (`intersect_many`, `occluded_many`) answer each of `rays`
/// as its single queries do; returns the batched closest hits.
pub fn assert_batches_match_single(a: &dyn Accel, rays: &[Ray], name: &str) -> Vec<Option<Hit>> {
    let mut hits = vec![None; rays.len()];
    let mut occluded = vec![false; rays.len()];
    a.intersect_many(rays, &mut hits);
    a.occluded_many(rays, &mut occluded);
    for (i, r) in rays.iter().enumerate() {
        assert_eq!(hits[i], a.intersect(r), "{name}: ray {i}");
        assert_eq!(occluded[i], a.occluded(r), "{name}: ray {i}");
    }
    hits
}
