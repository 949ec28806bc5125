//! The one integrator: a unidirectional path tracer with next-event estimation, multiple importance
//! sampling between light and BSDF sampling (power heuristic), and Russian roulette.

use glam::{Vec3, Vec4};

use super::light::LightSet;
use super::offset::offset_ray_origin;
use super::surface::SurfaceInteraction;
use crate::accel::Accel;
use crate::geometry::Ray;
use crate::sample::mis::power_heuristic;
use crate::sample::{Dim, Sampler};
use crate::scene::features::Features;
use crate::scene::Scene;

/// Bounce from which Russian roulette may end paths.
const ROULETTE_START: u32 = 3;
/// Shadow rays stop this fraction short of an area light, so they do not hit the light itself.
const SHADOW_SHORTEN: f32 = 1e-3;
/// Most thin transmissive surfaces a shadow ray passes through before it counts as blocked.
const MAX_THIN_LAYERS: u32 = 16;

pub struct Integrator<'a> {
    pub scene: &'a Scene,
    pub accel: &'a dyn Accel,
    pub lights: LightSet,
    /// Number of bounces after the camera ray (1 = direct light only).
    pub max_depth: u32,
    /// The scene has thin transmissive surfaces, which shadow rays pass through (decided once: scenes
    /// without them trace plain occlusion rays).
    pub thin_shadows: bool,
}

/// Radiance along one camera ray, its coverage (alpha), and how many rays it took.
#[derive(Clone, Copy, Debug)]
pub struct PathResult {
    pub radiance: Vec4,
    pub rays: u32,
}

impl<'a> Integrator<'a> {
    /// The integrator for `scene`, with the shadow-ray path its `features` need.
    pub fn new(
        scene: &'a Scene,
        accel: &'a dyn Accel,
        max_depth: u32,
        features: &Features,
    ) -> Self {
        Self {
            scene,
            accel,
            lights: LightSet::new(scene),
            max_depth,
            thin_shadows: features.thin_walls,
        }
    }

    pub fn li(&self, camera_ray: Ray, sampler: &mut dyn Sampler) -> PathResult {
        if self.thin_shadows {
            self.li_with::<true>(camera_ray, sampler)
        } else {
            self.li_with::<false>(camera_ray, sampler)
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

    fn li_with<const THIN: bool>(&self, camera_ray: Ray, sampler: &mut dyn Sampler) -> PathResult {
        let mut ray = camera_ray.with_seed(sampler.get_seed(0));
        let mut l = Vec3::ZERO;
        let mut beta = Vec3::ONE;
        let mut alpha = 1.0;
        let mut rays = 0;
        // The pdf of the BSDF sample that produced `ray`, and where it left from (for MIS on
        // emitters the ray hits).
        let mut prev: Option<(f32, Vec3)> = None;
        // Absorption coefficient of the medium the ray travels through (zero outside any).
        let mut medium = Vec3::ZERO;
        // Product of the eta^2 factors refraction put into `beta`, kept out of Russian roulette.
        let mut eta_scale = 1.0f32;
        for bounce in 0.. {
            rays += 1;
            let hit = self.accel.intersect(&ray);
            if medium != Vec3::ZERO {
                // Beer-Lambert over the segment inside; a ray that escapes an open medium is lost.
                let dist = hit.map_or(f32::INFINITY, |h| h.t * ray.d.length());
                beta *= (-medium * dist).exp();
            }
            // Analytic lights and environments are not in the accelerator: the ray collects their
            // (MIS-weighted) radiance up to the scene hit or on leaving the scene.
            let pdf_prev = prev.map(|(pdf, _)| pdf);
            let t_hit = hit.as_ref().map_or(f32::INFINITY, |h| h.t);
            let le = self.lights.emitted(&ray, t_hit, pdf_prev);
            l += beta * le;
            let Some(hit) = hit else {
                l += beta * self.lights.escaped(ray.d, pdf_prev);
                if bounce == 0 && le == Vec3::ZERO {
                    alpha = 0.0;
                }
                break;
            };
            let si = SurfaceInteraction::new(self.scene, &hit, &ray);
            if si.emission != Vec3::ZERO {
                let w = match prev {
                    None => 1.0,
                    Some((pdf_bsdf, from)) => {
                        let pdf_light = self
                            .lights
                            .pdf_triangle(si.inst, si.prim, from, si.p, si.ng);
                        power_heuristic(pdf_bsdf, pdf_light)
                    }
                };
                l += beta * si.emission * w;
            }
            if bounce >= self.max_depth || si.unlit {
                break;
            }
            let wo = -ray.d;
            let seed = sampler.get_seed(bounce + 1);
            let n = si.bsdf.frame.n;
            // Rays leave on the side of the surface their direction points to.
            let origin_towards =
                |d: Vec3| offset_ray_origin(si.p, if d.dot(si.ng) >= 0.0 { si.ng } else { -si.ng });

            // Next-event estimation (pointless when every lobe is a delta lobe).
            let u_choice = sampler.get_1d(Dim::LightChoice, bounce);
            let u_light = sampler.get_2d(Dim::Light, bounce);
            let light = if si.bsdf.is_delta() {
                None
            } else {
                self.lights.sample(self.scene, si.p, u_choice, u_light)
            };
            if let Some(ls) = light {
                let cos = ls.wi.dot(n);
                // The shading and geometric normals must agree on the side; behind the surface
                // only transmissive materials see lights.
                let side_ok = cos * ls.wi.dot(si.ng) > 0.0 && (cos > 0.0 || si.bsdf.transmits());
                if side_ok && ls.li != Vec3::ZERO {
                    let (f, pdf_bsdf) = si.bsdf.eval(wo, ls.wi);
                    if f != Vec3::ZERO {
                        let t_max = if ls.dist.is_finite() {
                            (ls.dist * (1.0 - SHADOW_SHORTEN)).max(0.0)
                        } else {
                            f32::INFINITY
                        };
                        let shadow = Ray::segment(origin_towards(ls.wi), ls.wi, t_max)
                            .with_seed(seed)
                            .with_time(ray.time);
                        let tr = self.transmittance::<THIN>(shadow, &mut rays);
                        if tr != Vec3::ZERO {
                            let w = if ls.is_delta {
                                1.0
                            } else {
                                power_heuristic(ls.pdf, pdf_bsdf)
                            };
                            l += beta * tr * f * ls.li * (cos.abs() * w / ls.pdf);
                        }
                    }
                }
            }

            // Continue the path by sampling the BSDF.
            let u_lobe = sampler.get_1d(Dim::BsdfLobe, bounce);
            let u_dir = sampler.get_2d(Dim::Bsdf, bounce);
            let Some(s) = si.bsdf.sample(wo, u_lobe, u_dir) else {
                break;
            };
            // A shading normal can send a sample to the other side of the true surface than it
            // meant to: end the path there rather than leak light through it.
            let cos = s.wi.dot(n);
            if cos * s.wi.dot(si.ng) <= 0.0 {
                break;
            }
            beta *= s.f * (cos.abs() / s.pdf);
            if cos < 0.0 && !si.bsdf.thin {
                // Crossing into or out of a thick transmissive object.
                medium = if si.bsdf.outside {
                    si.bsdf.absorption
                } else {
                    Vec3::ZERO
                };
                eta_scale *= s.eta * s.eta;
            }
            // After a delta lobe no light sample could have found the emitter hit next, so it
            // counts fully; straight through a thin wall the previous vertex's MIS state holds,
            // since shadow rays see through it.
            if !s.straight {
                prev = (!s.delta).then_some((s.pdf, si.p));
            }
            ray = Ray::new(origin_towards(s.wi), s.wi)
                .with_seed(seed)
                .with_time(ray.time);

            if bounce + 1 >= ROULETTE_START {
                let q = (beta.max_element() * eta_scale).min(0.95);
                if q <= 0.0 || sampler.get_1d(Dim::Roulette, bounce) >= q {
                    break;
                }
                beta /= q;
            }
        }
        PathResult {
            radiance: l.extend(alpha),
            rays,
        }
    }
}
