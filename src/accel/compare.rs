//! Cross-checking backends: random rays aimed at a scene's triangles and a comparison of the hits two
//! accelerators report for them. Used by the tests (Embree vs BVH) and by benchmarks.

use glam::Vec3;
use rayon::prelude::*;

use super::Accel;
use crate::geometry::mix64;
use crate::geometry::{Hit, Ray};
use crate::scene::{AlphaMode, Scene};

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
                // The box grown by 1% of the diagonal: in a flat scene (MeshPrimitiveModes) the bounds
                // themselves are a plane, and an origin on a triangle's plane is a tie at t = 0 that
                // Embree's closed interval counts and the Rust backends' open one does not.
                let pad = Vec3::splat(0.01 * radius);
                let o =
                    bounds.min - pad + (bounds.extent() + 2.0 * pad) * Vec3::new(h(2), h(3), h(4));
                return Ray::new(o, dir);
            }
            let k = ((h(2) as f64 * total as f64) as usize).min(total - 1);
            let inst = offsets.partition_point(|&o| o <= k) - 1;
            let tri = scene.world_triangle(inst as u32, (k - offsets[inst]) as u32);
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
    /// Disagreements where a hit grazes its triangle (the ray within `GRAZING_COS` of parallel to it):
    /// there t, u, v are ill-conditioned and no two float implementations agree.
    pub grazing: usize,
    /// Disagreements where one backend's nearer hit lies within `EDGE_BARYCENTRIC` of its triangle's
    /// edge and the other passed by: a silhouette edge, where instanced (object-space, Embree) and
    /// flattened (world-space, BVH) vertices round differently.
    pub edges: usize,
    /// Disagreements where the nearer hit's alpha is within `ALPHA_MARGIN` of its material's cutoff:
    /// the backends' barycentrics differ in the last bits, and so may the texture lookup.
    pub alpha_edges: usize,
    /// Disagreements where the nearer hit lies within the rounding error of the hit point (the
    /// tolerance of `close`) of the ray's origin: an origin within a few ulps of a triangle's plane,
    /// where whether the ray leaving it touches it is decided by rounding.
    pub at_origin: usize,
    /// Everything else, with the ray and both answers (at most `MAX_KEPT` kept).
    pub mismatches: Vec<(Ray, Option<Hit>, Option<Hit>)>,
    pub mismatch_count: usize,
    /// Rays whose closest hits agree but whose `occluded` answers do not match them.
    pub occlusion_mismatches: usize,
}

const MAX_KEPT: usize = 16;

/// |cos| between ray and triangle plane below which a hit counts as grazing (about 0.6 degrees).
pub const GRAZING_COS: f32 = 0.01;

/// Barycentric distance from an edge under which a hit counts as on the edge.
pub const EDGE_BARYCENTRIC: f32 = 1e-3;
/// Distance from an edge, relative to the scene's size, under which a hit counts as on the edge
/// (for slivers, whose barycentrics say little).
pub const EDGE_RELATIVE: f32 = 1e-5;

/// Alpha distance from a mask cutoff under which a cutout decision counts as on the edge.
pub const ALPHA_MARGIN: f32 = 0.02;

fn on_alpha_edge(scene: &Scene, hit: &Option<Hit>) -> bool {
    hit.is_some_and(|h| {
        if h.csg().is_some() {
            return false;
        }
        let mesh = scene.mesh_of(h.inst);
        let mat = &scene.materials[mesh.material as usize];
        match mat.alpha_mode {
            AlphaMode::Mask(cutoff)
                if scene.mesh_needs_alpha_test(scene.instances[h.inst as usize].mesh) =>
            {
                let alpha = scene.base_color(mat, mesh.uv_at(h.prim, h.u, h.v)).w;
                (alpha - cutoff).abs() < ALPHA_MARGIN
            }
            _ => false,
        }
    })
}

/// World-space distance from a hit to the nearest edge of its triangle.
fn edge_distance(scene: &Scene, h: &Hit) -> f32 {
    let [a, b, c] = scene.world_triangle(h.inst, h.prim);
    let twice_area = (b - a).cross(c - a).length();
    // Barycentric weight of a vertex times the height over the opposite edge.
    let (wa, wb, wc) = (1.0 - h.u - h.v, h.u, h.v);
    let height = |e: glam::Vec3| twice_area / e.length().max(f32::MIN_POSITIVE);
    (wa * height(c - b))
        .min(wb * height(a - c))
        .min(wc * height(b - a))
}

fn on_edge(scene: &Scene, hit: &Option<Hit>) -> bool {
    let size = scene.bounds().extent().length();
    hit.is_some_and(|h| {
        // CSG surfaces have no triangle edges (their own edges are where faces meet at an angle,
        // which `grazes` and the distance tolerance cover).
        h.csg().is_none() && h.u.min(h.v).min(1.0 - h.u - h.v) < EDGE_BARYCENTRIC
            || edge_distance(scene, &h) < EDGE_RELATIVE * size
    })
}

fn grazes(scene: &Scene, ray: &Ray, hit: &Option<Hit>) -> bool {
    hit.is_some_and(|h| incidence(scene, ray, &h) < GRAZING_COS)
}

impl Agreement {
    pub fn fraction_same(&self) -> f64 {
        (self.same + self.ties) as f64 / self.rays.max(1) as f64
    }
}

/// Whether two hit distances along `ray` agree: within `T_TOLERANCE` relative, or within the rounding
/// error of the hit point (64 ulps of the largest coordinate involved, in world space or, for
/// Embree's instanced meshes, in object space scaled to world units), divided by the cosine of
/// incidence, since a point error of e moves a hit by e / cos along the ray.
fn close(scene: &Scene, magnitudes: &[f32], ray: &Ray, x: &Hit, y: &Hit) -> bool {
    let t = x.t.abs().max(y.t.abs());
    let diff = (x.t - y.t).abs();
    let world = ray.o.abs().max_element() + t * ray.d.abs().max_element();
    if diff <= T_TOLERANCE * t + 64.0 * f32::EPSILON * world {
        return true;
    }
    diff <= T_TOLERANCE * t + point_error(scene, magnitudes, ray, &[*x, *y], world)
}

/// The rounding error of the hit points `hits` along `ray`, as a distance in `t`: 64 ulps of the
/// largest coordinate involved (at least `world`) over the smallest cosine of incidence (for unit
/// directions, as the compared rays have).
fn point_error(scene: &Scene, magnitudes: &[f32], ray: &Ray, hits: &[Hit], world: f32) -> f32 {
    let of = |h: &Hit| match h.csg() {
        Some((object, _)) => {
            let b = scene.csg[object as usize].bounds();
            b.min.abs().max(b.max.abs()).max_element()
        }
        None => magnitudes[h.inst as usize],
    };
    let magnitude = hits.iter().map(of).fold(world, f32::max);
    let cos = hits
        .iter()
        .map(|h| incidence(scene, ray, h))
        .fold(1.0f32, f32::min)
        .max(GRAZING_COS);
    64.0 * f32::EPSILON * magnitude / cos
}

/// Whether `hit` is within the rounding error of its point of the ray's origin.
fn at_origin(scene: &Scene, magnitudes: &[f32], ray: &Ray, hit: &Option<Hit>) -> bool {
    hit.is_some_and(|h| h.t <= point_error(scene, magnitudes, ray, &[h], ray.o.abs().max_element()))
}

/// Per instance: the largest object-space coordinate of its mesh, in world units.
fn object_magnitudes(scene: &Scene) -> Vec<f32> {
    let per_mesh: Vec<f32> = scene
        .meshes
        .iter()
        .map(|m| {
            let b = m.bounds();
            b.min.abs().max(b.max.abs()).max_element()
        })
        .collect();
    scene
        .instances
        .iter()
        .map(|inst| {
            let m = glam::Mat3::from_mat4(inst.to_world);
            let scale = m
                .x_axis
                .length()
                .max(m.y_axis.length())
                .max(m.z_axis.length());
            per_mesh[inst.mesh as usize] * scale
        })
        .collect()
}

/// |cos| of the angle between the ray and the hit surface's geometric normal.
fn incidence(scene: &Scene, ray: &Ray, h: &Hit) -> f32 {
    let (_, n) = scene.hit_geometry(h, ray);
    n.dot(ray.d.normalize()).abs()
}

fn nearer(a: Option<Hit>, b: Option<Hit>) -> Option<Hit> {
    match (a, b) {
        (Some(x), Some(y)) => Some(if x.t <= y.t { x } else { y }),
        (x, y) => x.or(y),
    }
}

/// Compares closest hits and occlusion answers of `a` and `b` (both built over `scene`) for every ray.
pub fn compare(scene: &Scene, a: &dyn Accel, b: &dyn Accel, rays: &[Ray]) -> Agreement {
    let magnitudes = object_magnitudes(scene);
    let close = |ray: &Ray, x: &Hit, y: &Hit| close(scene, &magnitudes, ray, x, y);
    rays.par_chunks(4096)
        .map(|chunk| {
            let mut g = Agreement::default();
            for ray in chunk {
                let (ha, hb) = (a.intersect(ray), b.intersect(ray));
                g.rays += 1;
                g.hits += ha.is_some() as usize;
                match (ha, hb) {
                    (None, None) => g.same += 1,
                    (Some(x), Some(y)) if close(ray, &x, &y) => {
                        if (x.inst, x.prim) == (y.inst, y.prim) {
                            g.same += 1
                        } else {
                            g.ties += 1
                        }
                    }
                    _ if grazes(scene, ray, &ha) || grazes(scene, ray, &hb) => g.grazing += 1,
                    _ if on_edge(scene, &nearer(ha, hb)) => g.edges += 1,
                    _ if on_alpha_edge(scene, &nearer(ha, hb)) => g.alpha_edges += 1,
                    _ if at_origin(scene, &magnitudes, ray, &nearer(ha, hb)) => g.at_origin += 1,
                    _ => {
                        g.mismatch_count += 1;
                        if g.mismatches.len() < MAX_KEPT {
                            g.mismatches.push((*ray, ha, hb));
                        }
                    }
                }
                // Where the closest hits agree, any-hit queries must give the same answer too.
                let agreed = ha.is_some() == hb.is_some()
                    && (ha.is_none() || close(ray, &ha.unwrap(), &hb.unwrap()));
                if agreed && (a.occluded(ray) != ha.is_some() || b.occluded(ray) != hb.is_some()) {
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
            x.grazing += y.grazing;
            x.at_origin += y.at_origin;
            x.edges += y.edges;
            x.alpha_edges += y.alpha_edges;
            x.mismatch_count += y.mismatch_count;
            x.occlusion_mismatches += y.occlusion_mismatches;
            x.mismatches.extend(y.mismatches);
            x.mismatches.truncate(MAX_KEPT);
            x
        })
}
