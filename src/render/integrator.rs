//! The one integrator: a unidirectional path tracer with next-event estimation, multiple importance
//! sampling between light and BSDF sampling (power heuristic), and Russian roulette.

use glam::{Vec2, Vec3, Vec4};

use super::features::PathFeatures;
use super::light::{LightContext, LightSampler, LightSet};
use super::offset::offset_ray_origin;
use super::surface::{self, SurfaceInteraction};
use crate::accel::{Accel, Tracer};
use crate::geometry::{Hit, Ray};
use crate::sample::mis::power_heuristic;
use crate::sample::{Dim, Sampler};
use crate::scene::features::Features;
use crate::scene::Scene;

/// The camera ray's closest hit, where it was traced ahead of the path (eight to a packet).
#[derive(Clone, Copy, Debug)]
pub enum FirstHit {
    /// The path traces the camera ray itself.
    Untraced,
    /// Traced: the hit, or none where the ray left the scene.
    Traced(Option<Hit>),
}

/// Bounce from which Russian roulette may end paths.
const ROULETTE_START: u32 = 3;

/// Survival probability per square root of the throughput: paths keep going while their throughput
/// is at least 1 / ROULETTE_SURVIVAL^2 = 0.44. On bunny-cornell (depth 5) the roulette at 1x was
/// most of the noise left (sigma 0.206; 0.173 with no roulette): at 1.5x it is 0.179 for 0.87x
/// the time to RMSE 0.01 (2x: 0.174, 0.82x). On many-emitters, whose noise is the choice among
/// its lights, more survival buys little (0.447 -> 0.440) and costs time: 1.02x the time to RMSE
/// 0.01 at 1.5x, 1.06x at 2x (alternated runs, benches/peers/README.md).
const ROULETTE_SURVIVAL: f32 = 1.5;
/// Shadow rays stop this fraction short of an area light, so they do not hit the light itself.
const SHADOW_SHORTEN: f32 = 1e-3;
/// Most thin transmissive surfaces a shadow ray passes through before it counts as blocked.
const MAX_THIN_LAYERS: u32 = 16;

pub struct Integrator<'a> {
    pub scene: &'a Scene,
    pub accel: Tracer<'a>,
    pub lights: LightSet,
    /// Number of bounces after the camera ray (1 = direct light only).
    pub max_depth: u32,
    /// The scene has thin transmissive surfaces, which shadow rays pass through (decided once: scenes
    /// without them trace plain occlusion rays).
    pub thin_shadows: bool,
    /// The scene has alpha-tested geometry, whose stochastic transparency reads the rays' seeds.
    pub alpha_seeds: bool,
}

/// The radiance a camera ray finds before any bounce: from emitters (emissive and unlit surfaces,
/// analytic lights) and from the environment.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Seen {
    pub emitters: Vec3,
    pub environment: Vec3,
}

impl Seen {
    pub fn total(&self) -> Vec3 {
        self.emitters + self.environment
    }
}

/// Radiance along one camera ray, its coverage (alpha), and how many rays it took.
#[derive(Clone, Copy, Debug)]
pub struct PathResult {
    pub radiance: Vec4,
    pub rays: u32,
}

impl<'a> Integrator<'a> {
    /// The integrator for `scene`, with the shadow-ray path its `features` need and lights chosen
    /// by `light_sampler`.
    pub fn new(
        scene: &'a Scene,
        accel: &'a dyn Accel,
        max_depth: u32,
        features: &Features,
        light_sampler: LightSampler,
    ) -> Self {
        Self {
            scene,
            accel: Tracer::new(accel),
            lights: LightSet::with_sampler(scene, light_sampler),
            max_depth,
            thin_shadows: features.thin_walls,
            alpha_seeds: features.alpha,
        }
    }

    /// The seed of stochastic transparency for the rays leaving `bounce`; without alpha-tested
    /// geometry nothing reads it, so no sample is drawn (samplers are stateless per dimension, so
    /// every other value stays the same).
    fn alpha_seed(&self, sampler: &mut impl Sampler, bounce: u32) -> u32 {
        if self.alpha_seeds {
            sampler.get_seed(bounce)
        } else {
            0
        }
    }

    /// The seed of a camera ray for stochastic transparency: `li` takes camera rays with it (and
    /// they may be traced ahead, together).
    pub fn camera_seed(&self, sampler: &mut impl Sampler) -> u32 {
        self.alpha_seed(sampler, 0)
    }

    /// Radiance along `camera_ray` (seeded by `camera_seed`), whose closest hit `first` may have found.
    pub fn li(&self, camera_ray: Ray, first: FirstHit, sampler: &mut impl Sampler) -> PathResult {
        let mut none = PathFeatures::default();
        if self.thin_shadows {
            self.li_with::<true, false>(camera_ray, first, sampler, &mut none)
        } else {
            self.li_with::<false, false>(camera_ray, first, sampler, &mut none)
        }
    }

    /// What a camera ray that meets no surface brings, as `li` finds it: the analytic lights in
    /// front of it and the environment, with coverage 0 unless an analytic light is there. (No
    /// sample dimension is drawn, so the caller need not restart its sampler: most of the image
    /// of an object in front of an environment is such rays.)
    pub fn missed(&self, camera_ray: &Ray) -> PathResult {
        let le = self.lights.emitted(camera_ray, f32::INFINITY, None);
        // Camera rays leave with unit directions (`RayCamera`).
        let l = le + self.lights.escaped_unit(camera_ray.d, None);
        let alpha = if le == Vec3::ZERO { 0.0 } else { 1.0 };
        PathResult {
            radiance: l.extend(alpha),
            rays: 1,
        }
    }

    /// What camera ray `ray` (unit direction) with closest hit `hit` brings back before any
    /// bounce, as `li` counts it; the companions of a split camera ray bring back this alone.
    pub fn seen(&self, ray: &Ray, hit: Option<&Hit>) -> Seen {
        let t_hit = hit.map_or(f32::INFINITY, |h| h.t);
        let mut emitters = self.lights.emitted(ray, t_hit, None);
        let environment = match hit {
            Some(h) => {
                emitters += surface::radiance_at(self.scene, h, ray);
                Vec3::ZERO
            }
            None => self.lights.escaped_unit(ray.d, None),
        };
        Seen {
            emitters,
            environment,
        }
    }

    /// `li`, also noting what the path saw for the feature images (the same samples: the features
    /// only watch; but the last ray always takes the closest-hit query, since the features may
    /// need its hit, where `li` may test the emitters instead: radiance equal to the last bits).
    pub fn li_features(
        &self,
        camera_ray: Ray,
        first: FirstHit,
        sampler: &mut impl Sampler,
        features: &mut PathFeatures,
    ) -> PathResult {
        if self.thin_shadows {
            self.li_with::<true, true>(camera_ray, first, sampler, features)
        } else {
            self.li_with::<false, true>(camera_ray, first, sampler, features)
        }
    }

    /// What fraction of a light's radiance reaches the end of `shadow`: 0 or 1 past opaque surfaces,
    /// and with `THIN` also the product of the straight-through transmittances of the thin smooth
    /// transmissive surfaces it crosses (glTF's thin walls let light through unbent, so a light
    /// behind a window still lights the room directly). Counts the rays traced.
    fn transmittance<const THIN: bool>(&self, mut shadow: Ray, rays: &mut u32) -> Vec3 {
        if !THIN {
            *rays += 1;
            return if self.accel.occluded(&shadow) {
                Vec3::ZERO
            } else {
                Vec3::ONE
            };
        }
        let mut tr = Vec3::ONE;
        for _ in 0..MAX_THIN_LAYERS {
            *rays += 1;
            let Some(hit) = self.accel.intersect(&shadow) else {
                return tr;
            };
            let si = SurfaceInteraction::new(self.scene, &hit, &shadow);
            tr *= si.bsdf.straight_transmittance(-shadow.d);
            if tr == Vec3::ZERO {
                return tr;
            }
            // Go on from the far side of the surface, to the same end point.
            let o = offset_ray_origin(si.p, -si.ng);
            let t_max = shadow.t_max - (o - shadow.o).dot(shadow.d) / shadow.d.length_squared();
            if t_max <= 0.0 {
                return tr;
            }
            shadow = Ray::segment(o, shadow.d, t_max).with_seed(shadow.seed);
        }
        Vec3::ZERO
    }

    /// With `FEATURES`, `features` follows the path; without, it is never touched (and the plain
    /// render compiles to the same code as before features existed).
    fn li_with<const THIN: bool, const FEATURES: bool>(
        &self,
        camera_ray: Ray,
        first: FirstHit,
        sampler: &mut impl Sampler,
        features: &mut PathFeatures,
    ) -> PathResult {
        let mut ray = camera_ray;
        let mut l = Vec3::ZERO;
        let mut alpha = 1.0;
        let mut rays = 0;
        let mut st = PathState::default();
        for bounce in 0.. {
            rays += 1;
            let hit = match (bounce, first) {
                (0, FirstHit::Traced(hit)) => hit,
                _ if !FEATURES
                    && bounce > 0
                    && bounce >= self.max_depth
                    && st.medium == Vec3::ZERO
                    && self.lights.few_emitters() =>
                {
                    // The last ray only looks for emitters: where a few emissive triangles are
                    // all of them, test those and ask the accelerator only whether the nearest
                    // is blocked (most last rays meet none and trace nothing).
                    let Some(h) = self.lights.nearest_emitter(&ray) else {
                        break;
                    };
                    let before = Ray::segment(ray.o, ray.d, h.t * (1.0 - SHADOW_SHORTEN))
                        .with_seed(ray.seed)
                        .with_time(ray.time);
                    if self.accel.occluded(&before) {
                        break;
                    }
                    Some(h)
                }
                _ => self.accel.intersect(&ray),
            };
            if st.medium != Vec3::ZERO {
                // Beer-Lambert over the segment inside; a ray that escapes an open medium is lost.
                let dist = hit.map_or(f32::INFINITY, |h| h.t * ray.d.length());
                st.beta *= (-st.medium * dist).exp();
            }
            // Analytic lights and environments are not in the accelerator: the ray collects their
            // (MIS-weighted) radiance up to the scene hit or on leaving the scene.
            let t_hit = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
            let le = self.lights.emitted(&ray, t_hit, st.prev());
            l += st.beta * le;
            let Some(hit) = hit else {
                if FEATURES {
                    features.escaped();
                }
                l += st.beta * self.lights.escaped(ray.d, st.prev());
                if bounce == 0 && le == Vec3::ZERO {
                    alpha = 0.0;
                }
                break;
            };
            // The last vertex only adds its emission: none to add, nothing to build.
            if !FEATURES
                && bounce >= self.max_depth
                && !SurfaceInteraction::can_emit(self.scene, &hit)
            {
                break;
            }
            // The triangle's data is fetched while the sampler draws this vertex's dimensions.
            // A dimension that nothing reads is not drawn (its values depend on the dimension
            // alone, so the others stay the same): one light needs no choice.
            self.scene.prefetch_triangle(&hit);
            let drawn_choice = self
                .lights
                .chooses()
                .then(|| sampler.get_1d(Dim::LightChoice, bounce));
            let u_light = sampler.get_2d(Dim::Light, bounce);
            let mut si = SurfaceInteraction::new(self.scene, &hit, &ray);
            let mut u_choice = drawn_choice.unwrap_or(0.5);
            if si.bsdf.dispersion.is_some() {
                let u = drawn_choice.unwrap_or_else(|| sampler.get_1d(Dim::LightChoice, bounce));
                u_choice = st.follow_one_channel(&mut si, u);
            }
            if FEATURES {
                features.hit(&si, bounce);
            }
            if si.emission != Vec3::ZERO {
                l += st.beta * si.emission * self.emission_weight(&si, st.prev());
            }
            // A surface that scatters nothing (a black emitter) ends the path: its light sample
            // and BSDF sample would each bring zero, after a light choice (many-emitters' light
            // BVH descent) for nothing.
            if bounce >= self.max_depth || si.unlit || si.bsdf.scatters_nothing() {
                break;
            }
            let leave = Leave {
                wo: -ray.d,
                seed: self.alpha_seed(sampler, bounce + 1),
                time: ray.time,
            };
            let nee = self.next_event::<THIN>(&si, &leave, (u_choice, u_light), st.beta, &mut rays);
            if let Some(c) = nee {
                l += c;
            }
            match self.scatter(&si, &leave, bounce, &mut st, sampler) {
                Some(next) => ray = next,
                None => break,
            }
        }
        PathResult {
            radiance: l.extend(alpha),
            rays,
        }
    }

    /// MIS weight of emission found by a BSDF sample from `prev` (1 for camera rays and after
    /// delta lobes).
    fn emission_weight(&self, si: &SurfaceInteraction, prev: Option<(f32, LightContext)>) -> f32 {
        match prev {
            None => 1.0,
            Some((pdf_bsdf, from)) => {
                let pdf_light = self
                    .lights
                    .pdf_triangle(si.inst, si.prim, &from, si.p, si.ng);
                power_heuristic(pdf_bsdf, pdf_light)
            }
        }
    }

    /// Next-event estimation at `si` of bounce `bounce` with the light chosen by `u_choice`: `beta`
    /// times the MIS-weighted light a light sample brings, if any (pointless when every lobe is a
    /// delta lobe, but the sample dimensions are drawn anyway).
    #[inline(always)]
    fn next_event<const THIN: bool>(
        &self,
        si: &SurfaceInteraction,
        leave: &Leave,
        (u_choice, u_light): (f32, Vec2),
        beta: Vec3,
        rays: &mut u32,
    ) -> Option<Vec3> {
        if si.bsdf.is_delta() {
            return None;
        }
        let ls = self
            .lights
            .sample(self.scene, &light_context(si), u_choice, u_light)?;
        let cos = ls.wi.dot(si.bsdf.frame.n);
        // The shading and geometric normals must agree on the side; behind the surface only
        // transmissive materials see lights.
        let side_ok = cos * ls.wi.dot(si.ng) > 0.0 && (cos > 0.0 || si.bsdf.transmits());
        if !side_ok || ls.li == Vec3::ZERO {
            return None;
        }
        let (f, pdf_bsdf) = si.bsdf.eval(leave.wo, ls.wi);
        if f == Vec3::ZERO {
            return None;
        }
        let o = origin_towards(si, ls.wi);
        // Aimed from the offset origin at the light's point itself: along `wi` from the offset
        // origin, a ray grazing the light's plane would meet it offset / |cos| early, past the
        // relative shortening (the ceiling 1 cm above the Cornell box light saw none of it).
        let (d, t_max) = if ls.dist.is_finite() {
            let to = si.p + ls.wi * ls.dist - o;
            let len = to.length();
            if len <= 0.0 {
                return None;
            }
            (to / len, len * (1.0 - SHADOW_SHORTEN))
        } else {
            (ls.wi, f32::INFINITY)
        };
        let shadow = Ray::segment(o, d, t_max)
            .with_seed(leave.seed)
            .with_time(leave.time);
        let tr = self.transmittance::<THIN>(shadow, rays);
        if tr == Vec3::ZERO {
            return None;
        }
        let w = if ls.is_delta {
            1.0
        } else {
            power_heuristic(ls.pdf, pdf_bsdf)
        };
        Some(beta * tr * f * ls.li * (cos.abs() * w / ls.pdf))
    }

    /// Continues the path by sampling the BSDF at `si` (then Russian roulette): the next ray, or
    /// None where the path ends.
    #[inline(always)]
    fn scatter(
        &self,
        si: &SurfaceInteraction,
        leave: &Leave,
        bounce: u32,
        st: &mut PathState,
        sampler: &mut impl Sampler,
    ) -> Option<Ray> {
        let u_lobe = if si.bsdf.chooses_lobe() {
            sampler.get_1d(Dim::BsdfLobe, bounce)
        } else {
            0.5
        };
        let u_dir = sampler.get_2d(Dim::Bsdf, bounce);
        let s = si.bsdf.sample(leave.wo, u_lobe, u_dir)?;
        // A shading normal can send a sample to the other side of the true surface than it meant
        // to: end the path there rather than leak light through it.
        let cos = s.wi.dot(si.bsdf.frame.n);
        if cos * s.wi.dot(si.ng) <= 0.0 {
            return None;
        }
        st.beta *= s.f * (cos.abs() / s.pdf);
        if cos < 0.0 && !si.bsdf.thin {
            // Crossing into or out of a thick transmissive object.
            st.medium = if si.bsdf.outside {
                si.bsdf.absorption
            } else {
                Vec3::ZERO
            };
        }
        // After a delta lobe no light sample could have found the emitter hit next, so it counts
        // fully; straight through a thin wall the previous vertex's MIS state holds, since shadow
        // rays see through it.
        if !s.straight {
            st.prev_pdf = (!s.delta).then_some(s.pdf);
            // Field by field: copied whole, the context's 4- and 8-byte stores were read back by
            // 8-byte loads that straddle them (a store-forwarding stall on every bounce).
            st.prev_from.p = si.p;
            st.prev_from.n = si.ng;
        }
        let ray = Ray::new(origin_towards(si, s.wi), s.wi)
            .with_seed(leave.seed)
            .with_time(leave.time);
        if bounce + 1 >= ROULETTE_START {
            // The square root of the throughput, as Cycles does, ends fewer paths than the
            // throughput itself: on bunny-cornell (depth 5) noise per sample fell from 0.244 to
            // 0.205 for 5% more time a sample, 0.74x the time to RMSE 0.01 (benches/peers).
            let q = (ROULETTE_SURVIVAL * st.beta.max_element().sqrt()).min(1.0);
            if q <= 0.0 || sampler.get_1d(Dim::Roulette, bounce) >= q {
                return None;
            }
            st.beta /= q;
        }
        Some(ray)
    }
}

/// Where lights are chosen for at `si`: light samples and the BSDF samples leaving it share it.
fn light_context(si: &SurfaceInteraction) -> LightContext {
    LightContext { p: si.p, n: si.ng }
}

/// What a path carries from vertex to vertex besides its ray.
struct PathState {
    /// Throughput.
    beta: Vec3,
    /// The pdf of the BSDF sample that produced the ray (for MIS on emitters the ray hits; none for
    /// camera rays and after delta lobes), and where it left from (the context `light_context`
    /// gives there; written in place, see `scatter`).
    prev_pdf: Option<f32>,
    prev_from: LightContext,
    /// Absorption coefficient of the medium the ray travels through (zero outside any).
    medium: Vec3,
    /// The RGB channel the path follows since its first dispersive vertex (KHR_materials_dispersion).
    channel: Option<usize>,
}

impl PathState {
    /// The BSDF sample that produced the ray, as the lights weigh it: its pdf and where it left.
    fn prev(&self) -> Option<(f32, LightContext)> {
        self.prev_pdf.map(|pdf| (pdf, self.prev_from))
    }

    /// At a dispersive vertex: the first one picks a channel uniformly from `u` (probability 1/3,
    /// so the throughput keeps 3 times that channel and nothing of the others), and every one
    /// sees that channel's IOR. Returns what is left of `u`, uniform again, for the light choice.
    fn follow_one_channel(&mut self, si: &mut SurfaceInteraction, u: f32) -> f32 {
        let (c, rest) = match self.channel {
            Some(c) => (c, u),
            None => {
                let c = ((u * 3.0) as usize).min(2);
                let mut keep = Vec3::ZERO;
                keep[c] = 3.0;
                self.beta *= keep;
                self.channel = Some(c);
                (c, (u * 3.0 - c as f32).clamp(0.0, 1.0 - f32::EPSILON))
            }
        };
        si.bsdf = si.bsdf.for_channel(c);
        rest
    }
}

impl Default for PathState {
    fn default() -> Self {
        Self {
            beta: Vec3::ONE,
            prev_pdf: None,
            prev_from: LightContext {
                p: Vec3::ZERO,
                n: Vec3::ZERO,
            },
            medium: Vec3::ZERO,
            channel: None,
        }
    }
}

/// How rays leave a vertex: towards `wo` came the incoming ray; new rays take its seed and time.
struct Leave {
    wo: Vec3,
    seed: u32,
    time: f32,
}

/// Where a ray in direction `d` leaves the surface: on the side `d` points to.
fn origin_towards(si: &SurfaceInteraction, d: Vec3) -> Vec3 {
    offset_ray_origin(si.p, if d.dot(si.ng) >= 0.0 { si.ng } else { -si.ng })
}
