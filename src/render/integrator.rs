//! The one integrator: a unidirectional path tracer with next-event estimation, multiple importance
//! sampling between light and BSDF sampling (power heuristic), and Russian roulette.

use glam::{Vec3, Vec4};

use super::light::LightSet;
use super::offset::offset_ray_origin;
use super::surface::SurfaceInteraction;
use crate::accel::Accel;
use crate::geometry::Ray;
use crate::sample::{Dim, Sampler};
use crate::scene::Scene;

/// Bounce from which Russian roulette may end paths.
const ROULETTE_START: u32 = 3;
/// Shadow rays stop this fraction short of an area light, so they do not hit the light itself.
const SHADOW_SHORTEN: f32 = 1e-3;

pub struct Integrator<'a> {
    pub scene: &'a Scene,
    pub accel: &'a dyn Accel,
    pub lights: LightSet,
    /// Number of bounces after the camera ray (1 = direct light only).
    pub max_depth: u32,
}

/// Radiance along one camera ray, its coverage (alpha), and how many rays it took.
#[derive(Clone, Copy, Debug)]
pub struct PathResult {
    pub radiance: Vec4,
    pub rays: u32,
}

fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 == 0.0 {
        0.0
    } else {
        a2 / (a2 + b2)
    }
}

impl<'a> Integrator<'a> {
    pub fn new(scene: &'a Scene, accel: &'a dyn Accel, max_depth: u32) -> Self {
        Self {
            scene,
            accel,
            lights: LightSet::new(scene),
            max_depth,
        }
    }

    pub fn li(&self, camera_ray: Ray, sampler: &mut dyn Sampler) -> PathResult {
        let mut ray = camera_ray.with_seed(sampler.get_seed(0));
        let mut l = Vec3::ZERO;
        let mut beta = Vec3::ONE;
        let mut alpha = 1.0;
        let mut rays = 0;
        // The pdf of the BSDF sample that produced `ray`, and where it left from (for MIS on
        // emitters the ray hits).
        let mut prev: Option<(f32, Vec3)> = None;
        for bounce in 0.. {
            rays += 1;
            let Some(hit) = self.accel.intersect(&ray) else {
                l += beta * self.lights.environment;
                if bounce == 0 {
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
            if bounce >= self.max_depth {
                break;
            }
            let wo = -ray.d;
            let seed = sampler.get_seed(bounce + 1);
            let origin = offset_ray_origin(si.p, si.ng);
            let n = si.bsdf.frame.n;

            // Next-event estimation.
            let u_choice = sampler.get_1d(Dim::LightChoice, bounce);
            let u_light = sampler.get_2d(Dim::Light, bounce);
            if let Some(ls) = self.lights.sample(self.scene, si.p, u_choice, u_light) {
                let cos = ls.wi.dot(n);
                if cos > 0.0 && ls.wi.dot(si.ng) > 0.0 && ls.li != Vec3::ZERO {
                    let (f, pdf_bsdf) = si.bsdf.eval(wo, ls.wi);
                    if f != Vec3::ZERO {
                        let t_max = if ls.dist.is_finite() {
                            (ls.dist * (1.0 - SHADOW_SHORTEN)).max(0.0)
                        } else {
                            f32::INFINITY
                        };
                        rays += 1;
                        let shadow = Ray::segment(origin, ls.wi, t_max)
                            .with_seed(seed)
                            .with_time(ray.time);
                        if !self.accel.occluded(&shadow) {
                            let w = if ls.is_delta {
                                1.0
                            } else {
                                power_heuristic(ls.pdf, pdf_bsdf)
                            };
                            l += beta * f * ls.li * (cos * w / ls.pdf);
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
            // A shading normal can send a sample below the true surface: end the path there
            // rather than leak light through it.
            if s.wi.dot(si.ng) <= 0.0 {
                break;
            }
            beta *= s.f * (s.wi.dot(n).abs() / s.pdf);
            prev = Some((s.pdf, si.p));
            ray = Ray::new(origin, s.wi).with_seed(seed).with_time(ray.time);

            if bounce + 1 >= ROULETTE_START {
                let q = beta.max_element().min(0.95);
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
