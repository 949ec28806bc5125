//! The lights the integrator samples: punctual lights, every emissive triangle, analytic sphere, disk
//! and rectangle lights and environments, chosen in proportion to power (an alias table) or to a
//! bound on what each sends the shading point (the light BVH).
//!
//! Each kind lives in its own file with its sampling, pdf, hit and power; this file holds the set and
//! the thin dispatch over the kinds. Analytic lights are not in the accelerators: rays find them
//! through `emitted` (up to the scene hit) and environments through `escaped`, both returning
//! radiance already weighted by multiple importance sampling against the BSDF sample that made the
//! ray. They do not occlude anything.

mod alias;
mod area;
mod bounds;
mod bvh;
mod directional;
mod disk;
mod distribution;
mod environment;
mod point;
mod projected;
mod quad;
mod rect;
mod sphere;
mod spot;
mod triangle;

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

pub use alias::AliasTable;
pub use distribution::{Distribution1D, Distribution2D};

use crate::geometry::triangle::RayShear;
use crate::geometry::{Hit, Ray};
use crate::sample::mis::power_heuristic;
use crate::scene::{DirectionalLight, Light, PointLight, Scene, SpotLight};
use area::AreaLight;
use bounds::LightBounds;
use bvh::LightBvh;
use disk::Disk;
use environment::Environment;
use quad::Quad;
use rect::Rect;
use triangle::Triangle;

#[derive(Clone, Debug)]
enum Entry {
    Point(PointLight),
    Spot(SpotLight),
    Directional(DirectionalLight),
    Triangle(Triangle),
    Quad(Quad),
    Sphere(crate::scene::SphereLight),
    Disk(Disk),
    Rect(Rect),
    Environment(Environment),
}

impl Entry {
    /// The entry of a scene light and its weight (power) among the lights; `far_disk` is the area of
    /// the scene's bounding disk, through which lights at infinity send their flux.
    fn of_light(l: &Light, far_disk: f32) -> (Self, f32) {
        match l {
            Light::Point(l) => (Entry::Point(*l), point::power(l)),
            Light::Spot(l) => (Entry::Spot(*l), spot::power(l)),
            Light::Directional(l) => (Entry::Directional(*l), directional::power(l, far_disk)),
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

    /// The bounds of the entry's emission, of power `phi` (the entry's weight; a spot light's is
    /// its own, see `spot::bounds`); `None` for lights at infinity.
    fn bounds(&self, phi: f32) -> Option<LightBounds> {
        match self {
            Entry::Point(l) => Some(point::bounds(l, phi)),
            Entry::Spot(l) => Some(spot::bounds(l)),
            Entry::Directional(_) | Entry::Environment(_) => None,
            Entry::Triangle(t) => Some(t.bounds(phi)),
            Entry::Quad(q) => Some(q.bounds(phi)),
            Entry::Sphere(s) => Some(s.bounds(phi)),
            Entry::Disk(d) => Some(d.bounds(phi)),
            Entry::Rect(r) => Some(r.bounds(phi)),
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

/// From this many lights with bounds on (lights at infinity are chosen beside the tree),
/// `LightSampler::Auto` takes the BVH. Session 34, the BVH's time to RMSE 0.01 over the power
/// sampler's (32 spp x 2 seeds, 2 threads, medians of two runs): EmissiveStrengthTest's five lit
/// bays 0.39, the demo (a spot, a point light, an emissive panel) 0.56, LightsPunctualLamp 0.40,
/// many-emitters cut to 16 / 32 / 48 small triangles 0.60 / 0.53 / 0.43; one rect light beside an
/// environment (assets/scenes) 1.01-1.11, the same noise. (It took 64 before: session 16 measured
/// the cut many-emitters 1.06-1.08x at 32, with the four-wide tree and before the spot's bound.)
/// Session 8, sigma at equal spp, power -> bvh: many-emitters (1,200) 0.539 -> 0.456 at 1.17x the
/// time per sample, DamagedHelmet (its emissive triangles) 0.505 -> 0.482.
pub const AUTO_BVH_LIGHTS: usize = 2;

/// How next-event estimation picks the light to sample.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum LightSampler {
    /// The BVH where at least two lights are not at infinity (emissive triangles count one each,
    /// a rectangle of two one; directional lights and environments are chosen beside it), power
    /// otherwise.
    #[default]
    Auto,
    /// In proportion to power: blind to where the shading point is, O(1).
    Power,
    /// Through the light BVH: in proportion to a bound on what each light sends the point,
    /// O(log n); the nearer and better-facing light gets more samples.
    Bvh,
}

impl std::fmt::Display for LightSampler {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            LightSampler::Auto => "auto",
            LightSampler::Power => "power",
            LightSampler::Bvh => "bvh",
        })
    }
}

/// Where a light is chosen for: the shading point and its unit geometric normal (zero where there
/// is no surface). The same context must reach `sample` and the pdfs of the hits it competes with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightContext {
    pub p: Vec3,
    pub n: Vec3,
}

/// The distribution lights are chosen from.
enum Chooser {
    Power(AliasTable),
    Bvh(LightBvh),
}

impl Chooser {
    fn choose(&self, ctx: &LightContext, u: f32) -> Option<(usize, f32)> {
        match self {
            Chooser::Power(t) => t.sample(u),
            Chooser::Bvh(b) => b.choose(ctx.p, ctx.n, u),
        }
    }

    fn pmf(&self, ctx: &LightContext, i: usize) -> f32 {
        match self {
            Chooser::Power(t) => t.pmf(i),
            Chooser::Bvh(b) => b.pmf(ctx.p, ctx.n, i),
        }
    }
}

pub struct LightSet {
    entries: Vec<Entry>,
    chooser: Chooser,
    /// For each instance, where its triangle 0 is in `triangle_entry`, or `u32::MAX` when not
    /// emissive.
    first_triangle: Vec<u32>,
    /// The entry of each emissive triangle (a quad's two triangles share one).
    triangle_entry: Vec<u32>,
    /// Entries that rays can hit (spheres, disks, rectangles) and entries that escaping rays see.
    hittable: Vec<u32>,
    environments: Vec<u32>,
    /// The only emitters are a few emissive triangles, all of them sampled and opaque (no analytic
    /// area lights, environments, unlit surfaces, moving or alpha-tested emitters or emissive CSG
    /// surfaces).
    few_emitters: bool,
}

/// Most emissive triangles that `nearest_emitter` tests one by one.
const FEW_EMITTERS: usize = 16;

impl LightSet {
    /// The scene's lights, chosen by power.
    pub fn new(scene: &Scene) -> Self {
        Self::with_sampler(scene, LightSampler::Power)
    }

    pub fn with_sampler(scene: &Scene, sampler: LightSampler) -> Self {
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
                Entry::Point(_) | Entry::Spot(_) | Entry::Directional(_) if w <= 0.0 => continue,
                Entry::Environment(_) => environments.push(entries.len() as u32),
                _ if entry.area().is_some() => hittable.push(entries.len() as u32),
                _ => {}
            }
            entries.push(entry);
            weights.push(w);
        }
        let mut first_triangle = vec![u32::MAX; scene.instances.len()];
        let mut triangle_entry = Vec::new();
        let glows = |m: u32| {
            let m = &scene.materials[m as usize];
            m.unlit || m.is_emissive()
        };
        // Alpha-tested emitters too: rays pass their cut-outs, `nearest_emitter` would not.
        let all_sampled = !scene.instances.iter().any(|inst| {
            let m = scene.meshes[inst.mesh as usize].material;
            scene.materials[m as usize].unlit
                || (glows(m) && (inst.motion.is_some() || scene.mesh_needs_alpha_test(inst.mesh)))
        }) && !scene.csg.iter().any(|c| c.materials().any(glows));
        for (i, inst) in scene.instances.iter().enumerate() {
            let mesh = &scene.meshes[inst.mesh as usize];
            let mat = &scene.materials[mesh.material as usize];
            // A moving emitter is reached by BSDF sampling only: light samples on it would be
            // taken where it is at time 0, not at the ray's time.
            if !mat.is_emissive() || inst.motion.is_some() {
                continue;
            }
            first_triangle[i] = triangle_entry.len() as u32;
            // Consecutive triangles that make a rectangle of constant emission (a quad split in
            // two) are one light; the rest one each.
            let count = mesh.indices.len() as u32;
            let mut p = 0;
            // The partner a triangle did not pair with, which is the next triangle.
            let mut unpaired = None;
            while p < count {
                let t = unpaired
                    .take()
                    .unwrap_or_else(|| Triangle::new(scene, i as u32, p));
                let partner = (mat.emissive_tex.is_none() && p + 1 < count)
                    .then(|| Triangle::new(scene, i as u32, p + 1));
                let quad = partner
                    .as_ref()
                    .and_then(|next| Quad::pair(&t, next, mat.emissive));
                triangle_entry.push(entries.len() as u32);
                if let Some(q) = quad {
                    triangle_entry.push(entries.len() as u32);
                    weights.push(q.power());
                    entries.push(Entry::Quad(q));
                    p += 2;
                } else {
                    weights.push(t.power(scene, mat, mesh));
                    entries.push(Entry::Triangle(t));
                    unpaired = partner;
                    p += 1;
                }
            }
        }
        let bvh = match sampler {
            LightSampler::Auto => {
                let bounded = (entries.iter().zip(&weights))
                    .filter(|&(e, &w)| w > 0.0 && e.bounds(w).is_some())
                    .count();
                bounded >= AUTO_BVH_LIGHTS
            }
            LightSampler::Power => false,
            LightSampler::Bvh => true,
        };
        let chooser = if bvh {
            Chooser::Bvh(LightBvh::new(&weights, |i| entries[i].bounds(weights[i])))
        } else {
            Chooser::Power(AliasTable::new(&weights))
        };
        let few_emitters = all_sampled
            && hittable.is_empty()
            && environments.is_empty()
            && entries.len() <= FEW_EMITTERS;
        Self {
            chooser,
            entries,
            first_triangle,
            triangle_entry,
            hittable,
            environments,
            few_emitters,
        }
    }

    /// Whether `sample` reads its `u_choice`: not where one light is every choice.
    pub fn chooses(&self) -> bool {
        self.entries.len() > 1 || self.uses_bvh()
    }

    /// The environments' mean luminance over the sphere of directions (zero without one): about
    /// what a white diffuse surface under them reflects.
    pub fn environment_luminance(&self) -> f32 {
        self.environments
            .iter()
            .map(|&i| match &self.entries[i as usize] {
                Entry::Environment(e) => e.mean_luminance(),
                _ => 0.0,
            })
            .sum()
    }

    /// Whether the scene's only emitters are a few sampled emissive triangles, so that a ray that
    /// only looks for emitters can test them instead of asking for the closest hit
    /// (`nearest_emitter`).
    pub fn few_emitters(&self) -> bool {
        self.few_emitters
    }

    /// The nearest emissive triangle `ray` meets (each tested, watertight, on its world-space
    /// vertices); meaningful where `few_emitters`.
    pub fn nearest_emitter(&self, ray: &Ray) -> Option<Hit> {
        let sh = RayShear::new(ray.d);
        let mut best: Option<Hit> = None;
        for e in &self.entries {
            let t_max = best.map_or(ray.t_max, |b| b.t);
            let hit = match e {
                Entry::Triangle(t) => t.hit(ray.o, &sh, ray.t_min, t_max),
                Entry::Quad(q) => q.hit(ray.o, &sh, ray.t_min, t_max),
                _ => None,
            };
            if hit.is_some() {
                best = hit;
            }
        }
        best
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// Whether lights are chosen through the light BVH.
    pub fn uses_bvh(&self) -> bool {
        matches!(self.chooser, Chooser::Bvh(_))
    }

    /// Picks a light for `ctx` with `u_choice` and a point on it with `u`, as seen from `ctx.p`.
    pub fn sample(
        &self,
        scene: &Scene,
        ctx: &LightContext,
        u_choice: f32,
        u: Vec2,
    ) -> Option<LightSample> {
        let p = ctx.p;
        let (i, choice) = self.chooser.choose(ctx, u_choice)?;
        match &self.entries[i] {
            Entry::Point(l) => delta(point::sample(l, p), choice),
            Entry::Spot(l) => delta(spot::sample(l, p), choice),
            Entry::Directional(l) => delta(Some(directional::sample(l)), choice),
            Entry::Triangle(t) => t.sample(scene, ctx, u, choice),
            Entry::Quad(q) => q.sample(ctx, u, choice),
            Entry::Sphere(s) => s.sample(p, u, choice),
            Entry::Disk(d) => d.sample(p, u, choice),
            Entry::Rect(r) => r.sample(p, u, choice),
            Entry::Environment(e) => e.sample(u, choice),
        }
    }

    /// The solid-angle pdf with which `sample` would have chosen the point `q` (normal `nq`) on emissive
    /// triangle `(inst, prim)` for `ctx`: what multiple importance sampling needs for BSDF-sampled hits.
    pub fn pdf_triangle(&self, inst: u32, prim: u32, ctx: &LightContext, q: Vec3, nq: Vec3) -> f32 {
        // CSG surfaces (`Hit::csg`) and unlit instances are never sampled as lights.
        let first = self
            .first_triangle
            .get(inst as usize)
            .copied()
            .unwrap_or(u32::MAX);
        if first == u32::MAX {
            return 0.0;
        }
        let Some(&i) = self.triangle_entry.get((first + prim) as usize) else {
            return 0.0;
        };
        let i = i as usize;
        match &self.entries[i] {
            Entry::Triangle(t) => t.pdf(self.chooser.pmf(ctx, i), ctx, q, nq),
            Entry::Quad(quad) => quad.pdf(self.chooser.pmf(ctx, i), ctx, q),
            _ => 0.0,
        }
    }

    /// Radiance that `ray` receives from analytic area lights in front of `t_max` (the scene hit),
    /// each weighted against the BSDF sample of solid-angle pdf `pdf` that made the ray at `ctx`
    /// (`None` for camera rays and after specular bounces: weight 1). Lights do not stop the ray.
    #[inline(always)]
    pub fn emitted(&self, ray: &Ray, t_max: f32, prev: Option<(f32, LightContext)>) -> Vec3 {
        if self.hittable.is_empty() {
            return Vec3::ZERO;
        }
        self.emitted_by_hittable(ray, t_max, prev)
    }

    fn emitted_by_hittable(
        &self,
        ray: &Ray,
        t_max: f32,
        prev: Option<(f32, LightContext)>,
    ) -> Vec3 {
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
                    l += light.radiance() * self.mis_weight(prev, i, pdf);
                }
            }
        }
        l
    }

    /// Radiance from the environments in direction `d` of a ray that left the scene, weighted as in
    /// `emitted`.
    pub fn escaped(&self, d: Vec3, prev: Option<(f32, LightContext)>) -> Vec3 {
        self.escaped_unit(d.normalize_or_zero(), prev)
    }

    /// `escaped` for a direction already of unit length (a camera ray's), spared the
    /// normalisation (a view of the sky alone: 1.37-1.48 s -> 1.04-1.10 s, one thread). Inlined
    /// with the map lookup under it, whose calls each returned a colour through memory (the sky
    /// alone, 256 spp: 2.03 -> 1.85 s).
    #[inline(always)]
    pub fn escaped_unit(&self, d: Vec3, prev: Option<(f32, LightContext)>) -> Vec3 {
        let mut l = Vec3::ZERO;
        for &i in &self.environments {
            let i = i as usize;
            let Entry::Environment(e) = &self.entries[i] else {
                continue;
            };
            // A camera ray (or one after a delta lobe) has no light sample to weigh against, so
            // it needs no pdf (most of an environment-lit image is such rays).
            l += match prev {
                None => e.radiance(d),
                Some(_) => {
                    let (li, pdf) = e.radiance_and_pdf(d);
                    li * self.mis_weight(prev, i, pdf)
                }
            };
        }
        l
    }

    /// Radiance of environment entry `i` from unit direction `d` and the pdf of `sample` picking
    /// `d` (before the choice probability).
    #[cfg(test)]
    fn environment_radiance(&self, i: usize, d: Vec3) -> (Vec3, f32) {
        match &self.entries[i] {
            Entry::Environment(e) => e.radiance_and_pdf(d),
            _ => (Vec3::ZERO, 0.0),
        }
    }

    /// The multiple-importance weight of a BSDF sample (pdf and context in `prev`; `None`: no
    /// competing light sample, as for camera rays, so weight 1) finding entry `i` where light
    /// sampling would pick that direction with solid-angle pdf `pdf` once `i` is chosen.
    fn mis_weight(&self, prev: Option<(f32, LightContext)>, i: usize, pdf: f32) -> f32 {
        prev.map_or(1.0, |(b, ctx)| {
            power_heuristic(b, self.chooser.pmf(&ctx, i) * pdf)
        })
    }
}

/// The sample of a delta light from its direction, distance and arriving intensity (already
/// divided by distance squared), chosen with probability `choice`.
fn delta(sample: Option<(Vec3, f32, Vec3)>, choice: f32) -> Option<LightSample> {
    sample.map(|(wi, dist, li)| LightSample {
        wi,
        dist,
        li,
        pdf: choice,
        is_delta: true,
    })
}

#[cfg(test)]
mod tests;
