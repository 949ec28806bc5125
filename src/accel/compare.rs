//! Cross-checking backends: random rays aimed at a scene's triangles and a comparison of the hits two
//! accelerators report for them. Used by the tests (Embree vs BVH) and by benchmarks.

use glam::Vec3;
use rayon::prelude::*;

use super::Accel;
use crate::geometry::{Hit, Ray};
use crate::sample::mix64;
use crate::scene::Scene;

/// Relative distance tolerance under which two hits count as the same.
pub const T_TOLERANCE: f32 = 1e-4;

fn unit(h: u64) -> f32 {
    (h >> 40) as f32 / (1u64 << 24) as f32
}

/// `n` rays for a scene, deterministic in `seed`: three in four start on a sphere around the scene and
/// aim at a random point of a random triangle (so they mostly hit, from every side), one in four has a
/// random origin inside the bounds and a random direction.
pub fn random_rays(scene: &Scene, n: usize, seed: u64) -> Vec<Ray> {
    let bounds = scene.bounds();
    if bounds.is_empty() {
        return Vec::new();
    }
    let center = bounds.center();
    let radius = bounds.extent().length().max(1e-6);
    // Triangle table over instances, for choosing a target uniformly by index.
    let mut offsets = Vec::with_capacity(scene.instances.len());
    let mut total = 0usize;
    for inst in &scene.instances {
        offsets.push(total);
        total += scene.meshes[inst.mesh as usize].indices.len();
    }
    (0..n)
        .into_par_iter()
        .map(|i| {
            let h = |k: u64| unit(mix64(seed ^ mix64(i as u64 * 8 + k)));
            let dir = sphere_dir(h(0), h(1));
            if i % 4 == 3 || total == 0 {
                let o = bounds.min + bounds.extent() * Vec3::new(h(2), h(3), h(4));
                return Ray::new(o, dir);
            }
            let k = ((h(2) as f64 * total as f64) as usize).min(total - 1);
            let inst_idx = offsets.partition_point(|&o| o <= k) - 1;
            let inst = &scene.instances[inst_idx];
            let mesh = &scene.meshes[inst.mesh as usize];
            let tri = mesh
                .triangle((k - offsets[inst_idx]) as u32)
                .map(|p| inst.to_world.transform_point3(p));
            let (s, t) = (h(3).sqrt(), h(4));
            let target = tri[0] * (1.0 - s) + tri[1] * (s * (1.0 - t)) + tri[2] * (s * t);
            let o = center + dir * radius;
            Ray::new(o, (target - o).normalize())
        })
        .collect()
}

fn sphere_dir(u: f32, v: f32) -> Vec3 {
    let z = 1.0 - 2.0 * u;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * std::f32::consts::PI * v;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// How two backends' answers for the same rays compare.
#[derive(Clone, Debug, Default)]
pub struct Agreement {
    pub rays: usize,
    pub hits: usize,
    /// Same primitive and distance within `T_TOLERANCE`, or both missed.
    pub same: usize,
    /// Different primitives at the same distance (a ray through a shared edge or coincident faces).
    pub ties: usize,
    /// Everything else, with the ray and both answers (at most `MAX_KEPT` kept).
    pub mismatches: Vec<(Ray, Option<Hit>, Option<Hit>)>,
    pub mismatch_count: usize,
    /// Disagreements of `occluded` with `intersect(..).is_some()` across the two backends.
    pub occlusion_mismatches: usize,
}

const MAX_KEPT: usize = 16;

impl Agreement {
    pub fn fraction_same(&self) -> f64 {
        (self.same + self.ties) as f64 / self.rays.max(1) as f64
    }
}

/// Whether two hit distances along `ray` agree: within `T_TOLERANCE` relative, or within the rounding
/// error of the hit point itself (a few ulps of the largest coordinate involved), which is what bounds
/// the agreement of tiny distances from origins far from zero.
fn close(ray: &Ray, a: f32, b: f32) -> bool {
    let t = a.abs().max(b.abs());
    let magnitude = ray.o.abs().max_element() + t * ray.d.abs().max_element();
    (a - b).abs() <= T_TOLERANCE * t + 16.0 * f32::EPSILON * magnitude
}

/// Compares closest hits and occlusion answers of `a` and `b` for every ray.
pub fn compare(a: &dyn Accel, b: &dyn Accel, rays: &[Ray]) -> Agreement {
    rays.par_chunks(4096)
        .map(|chunk| {
            let mut g = Agreement::default();
            for ray in chunk {
                let (ha, hb) = (a.intersect(ray), b.intersect(ray));
                g.rays += 1;
                g.hits += ha.is_some() as usize;
                match (ha, hb) {
                    (None, None) => g.same += 1,
                    (Some(x), Some(y)) if close(ray, x.t, y.t) => {
                        if (x.inst, x.prim) == (y.inst, y.prim) {
                            g.same += 1
                        } else {
                            g.ties += 1
                        }
                    }
                    _ => {
                        g.mismatch_count += 1;
                        if g.mismatches.len() < MAX_KEPT {
                            g.mismatches.push((*ray, ha, hb));
                        }
                    }
                }
                if a.occluded(ray) != hb.is_some() || b.occluded(ray) != ha.is_some() {
                    g.occlusion_mismatches += 1;
                }
            }
            g
        })
        .reduce(Agreement::default, |mut x, y| {
            x.rays += y.rays;
            x.hits += y.hits;
            x.same += y.same;
            x.ties += y.ties;
            x.mismatch_count += y.mismatch_count;
            x.occlusion_mismatches += y.occlusion_mismatches;
            x.mismatches.extend(y.mismatches);
            x.mismatches.truncate(MAX_KEPT);
            x
        })
}
