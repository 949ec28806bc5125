//! The lights the integrator samples: punctual lights, every emissive triangle, analytic sphere, disk
//! and rectangle lights and environments, chosen in proportion to power through an alias table.
//!
//! Each kind lives in its own file with its sampling, pdf, hit and power; this file holds the set and
//! the thin dispatch over the kinds. Analytic lights are not in the accelerators: rays find them
//! through `emitted` (up to the scene hit) and environments through `escaped`, both returning
//! radiance already weighted by multiple importance sampling against the BSDF sample that made the
//! ray. They do not occlude anything.

mod alias;
mod area;
mod directional;
mod disk;
mod distribution;
mod environment;
mod point;
mod rect;
mod sphere;
mod spot;
mod triangle;

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

pub use alias::AliasTable;
pub use distribution::{Distribution1D, Distribution2D};

use crate::geometry::Ray;
use crate::sample::mis::power_heuristic;
use crate::scene::{Light, Scene};
use area::AreaLight;
use disk::Disk;
use environment::Environment;
use rect::Rect;
use triangle::Triangle;

#[derive(Clone, Debug)]
enum Entry {
    /// Point, spot and directional lights, as the scene gives them.
    Punctual(Light),
    Triangle(Triangle),
    Sphere(crate::scene::SphereLight),
    Disk(Disk),
    Rect(Rect),
    Environment(Environment),
}

impl Entry {
    /// The entry of a scene light and its weight (power) among the lights; `far_disk` is the area of
    /// the scene's bounding disk, through which lights at infinity send their flux.
    fn of_light(l: &Light, far_disk: f32) -> (Self, f32) {
        let punctual = || Entry::Punctual(l.clone());
        match l {
            Light::Point { intensity, .. } => (punctual(), point::power(*intensity)),
            Light::Spot {
                intensity,
                cos_outer,
                ..
            } => (punctual(), spot::power(*intensity, *cos_outer)),
            Light::Directional { irradiance, .. } => {
                (punctual(), directional::power(*irradiance, far_disk))
            }
            Light::Sphere(s) => (Entry::Sphere(*s), s.power()),
            Light::Disk(d) => {
                let d = Disk::new(*d);
                (Entry::Disk(d.clone()), d.power())
            }
            Light::Rect(r) => {
                let r = Rect::new(*r);
                (Entry::Rect(r.clone()), r.power())
            }
            Light::Environment { radiance, map } => {
                let e = Environment::new(*radiance, map.as_ref());
                let w = e.power(far_disk);
                (Entry::Environment(e), w)
            }
        }
    }

    /// The analytic area light this entry is, if it is one.
    fn area(&self) -> Option<&dyn AreaLight> {
        match self {
            Entry::Sphere(s) => Some(s),
            Entry::Disk(d) => Some(d),
            Entry::Rect(r) => Some(r),
            _ => None,
        }
    }
}

/// A sampled light contribution at a shading point.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction towards the light.
    pub wi: Vec3,
    /// Distance to the light along `wi` (infinite for directional lights and environments).
    pub dist: f32,
    /// Incident radiance (area lights) or irradiance-like quantity (delta lights), not divided by pdf.
    pub li: Vec3,
    /// Solid-angle pdf including the choice probability; for delta lights only the choice probability.
    pub pdf: f32,
    pub is_delta: bool,
}

pub struct LightSet {
    entries: Vec<Entry>,
    /// Power-proportional choice among `entries`.
    table: AliasTable,
    /// For each instance, the index of its first triangle entry, or `u32::MAX` when not emissive.
    first_triangle: Vec<u32>,
    /// Entries that rays can hit (spheres, disks, rectangles) and entries that escaping rays see.
    hittable: Vec<u32>,
    environments: Vec<u32>,
}

/// The multiple-importance weight of a BSDF-sampled emitter hit (`None`: no competing light
/// sample, as for camera rays, so weight 1).
fn mis_weight(pdf_bsdf: Option<f32>, pdf_light: f32) -> f32 {
    pdf_bsdf.map_or(1.0, |b| power_heuristic(b, pdf_light))
}

impl LightSet {
    pub fn new(scene: &Scene) -> Self {
        let mut entries = Vec::new();
        let mut weights = Vec::new();
        let (mut hittable, mut environments) = (Vec::new(), Vec::new());
        let (_, radius) = crate::scene::defaults::bounding_sphere(&scene.bounds());
        let far_disk = PI * radius * radius;
        for l in &scene.lights {
            let (entry, w) = Entry::of_light(l, far_disk);
            let w = if w.is_finite() { w.max(0.0) } else { 0.0 };
            match entry {
                // A punctual light of no power can never be seen: leave it out.
                Entry::Punctual(_) if w <= 0.0 => continue,
                Entry::Environment(_) => environments.push(entries.len() as u32),
                _ if entry.area().is_some() => hittable.push(entries.len() as u32),
                _ => {}
            }
            entries.push(entry);
            weights.push(w);
        }
        let mut first_triangle = vec![u32::MAX; scene.instances.len()];
        for (i, inst) in scene.instances.iter().enumerate() {
            let mesh = &scene.meshes[inst.mesh as usize];
            let mat = &scene.materials[mesh.material as usize];
            // A moving emitter is reached by BSDF sampling only: light samples on it would be
            // taken where it is at time 0, not at the ray's time.
            if !mat.is_emissive() || inst.motion.is_some() {
                continue;
            }
            first_triangle[i] = entries.len() as u32;
            for p in 0..mesh.indices.len() as u32 {
                let t = Triangle::new(scene, i as u32, p);
                weights.push(t.power(scene, mat, mesh));
                entries.push(Entry::Triangle(t));
            }
        }
        Self {
            table: AliasTable::new(&weights),
            entries,
            first_triangle,
            hittable,
            environments,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Picks a light with `u_choice` and a point on it with `u`, as seen from `p`.
    pub fn sample(&self, scene: &Scene, p: Vec3, u_choice: f32, u: Vec2) -> Option<LightSample> {
        let (i, choice) = self.table.sample(u_choice)?;
        match &self.entries[i] {
            Entry::Punctual(light) => sample_punctual(light, p).map(|(wi, dist, li)| LightSample {
                wi,
                dist,
                li,
                pdf: choice,
                is_delta: true,
            }),
            Entry::Triangle(t) => t.sample(scene, p, u, choice),
            Entry::Sphere(s) => s.sample(p, u, choice),
            Entry::Disk(d) => d.sample(p, u, choice),
            Entry::Rect(r) => r.sample(p, u, choice),
            Entry::Environment(e) => e.sample(u, choice),
        }
    }

    /// The solid-angle pdf with which `sample` would have chosen the point `q` (normal `nq`) on emissive
    /// triangle `(inst, prim)` from `p`: what multiple importance sampling needs for BSDF-sampled hits.
    pub fn pdf_triangle(&self, inst: u32, prim: u32, p: Vec3, q: Vec3, nq: Vec3) -> f32 {
        // CSG surfaces (`Hit::csg`) and unlit instances are never sampled as lights.
        let first = self
            .first_triangle
            .get(inst as usize)
            .copied()
            .unwrap_or(u32::MAX);
        if first == u32::MAX {
            return 0.0;
        }
        let i = (first + prim) as usize;
        let Entry::Triangle(t) = &self.entries[i] else {
            return 0.0;
        };
        t.pdf(self.table.pmf(i), p, q, nq)
    }

    /// Radiance that `ray` receives from analytic area lights in front of `t_max` (the scene hit),
    /// each weighted against the BSDF sample of solid-angle pdf `pdf_bsdf` that made the ray (`None`
    /// for camera rays and after specular bounces: weight 1). Lights do not stop the ray.
    pub fn emitted(&self, ray: &Ray, t_max: f32, pdf_bsdf: Option<f32>) -> Vec3 {
        let mut l = Vec3::ZERO;
        let len = ray.d.length();
        if len <= 0.0 {
            return l;
        }
        let (o, d) = (ray.o, ray.d / len);
        // Distances below along the unit direction; `t_max` is in units of the ray's own direction.
        let t_max = t_max * len;
        for &i in &self.hittable {
            let i = i as usize;
            let Some(light) = self.entries[i].area() else {
                continue;
            };
            if let Some((t, pdf)) = light.hit(o, d) {
                if t < t_max {
                    l += light.radiance() * mis_weight(pdf_bsdf, self.table.pmf(i) * pdf);
                }
            }
        }
        l
    }

    /// Radiance from the environments in direction `d` of a ray that left the scene, weighted as in
    /// `emitted`.
    pub fn escaped(&self, d: Vec3, pdf_bsdf: Option<f32>) -> Vec3 {
        let d = d.normalize_or_zero();
        let mut l = Vec3::ZERO;
        for &i in &self.environments {
            let i = i as usize;
            let (li, pdf) = self.environment_radiance(i, d);
            l += li * mis_weight(pdf_bsdf, self.table.pmf(i) * pdf);
        }
        l
    }

    /// Radiance of environment entry `i` from unit direction `d` and the pdf of `sample` picking
    /// `d` (before the choice probability).
    fn environment_radiance(&self, i: usize, d: Vec3) -> (Vec3, f32) {
        match &self.entries[i] {
            Entry::Environment(e) => e.radiance(d),
            _ => (Vec3::ZERO, 0.0),
        }
    }
}

/// Direction, distance and arriving intensity (already divided by distance squared) of a delta light.
fn sample_punctual(light: &Light, p: Vec3) -> Option<(Vec3, f32, Vec3)> {
    match *light {
        Light::Point {
            position,
            intensity,
        } => point::sample(position, intensity, p),
        Light::Spot {
            position,
            direction,
            intensity,
            cos_inner,
            cos_outer,
        } => spot::sample(position, direction, intensity, cos_inner, cos_outer, p),
        Light::Directional {
            direction,
            irradiance,
        } => Some(directional::sample(direction, irradiance)),
        _ => None,
    }
}

#[cfg(test)]
mod tests;
