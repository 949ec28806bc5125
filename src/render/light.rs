//! The lights the integrator samples: the scene's punctual lights and every emissive triangle, chosen
//! in proportion to an estimate of their power. The environment is reached by escaping rays only.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::bsdf::luminance;
use super::surface::emission;
use crate::scene::{Light, Scene};

#[derive(Clone, Debug)]
enum Entry {
    Punctual(Light),
    /// A world-space emissive triangle: instance, primitive, vertices.
    Triangle {
        inst: u32,
        prim: u32,
        v: [Vec3; 3],
        area: f32,
    },
}

/// A sampled light contribution at a shading point.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction towards the light.
    pub wi: Vec3,
    /// Distance to the light along `wi` (infinite for directional lights).
    pub dist: f32,
    /// Incident radiance (area lights) or irradiance-like quantity (delta lights), not divided by pdf.
    pub li: Vec3,
    /// Solid-angle pdf including the choice probability; for delta lights only the choice probability.
    pub pdf: f32,
    pub is_delta: bool,
}

pub struct LightSet {
    entries: Vec<Entry>,
    /// Cumulative selection probabilities, ending at 1.
    cdf: Vec<f32>,
    /// For each instance, the index of its first triangle entry, or `u32::MAX` when not emissive.
    first_triangle: Vec<u32>,
    pub environment: Vec3,
}

impl LightSet {
    pub fn new(scene: &Scene) -> Self {
        let mut entries = Vec::new();
        let mut weights = Vec::new();
        let mut environment = Vec3::ZERO;
        let radius = (scene.bounds().extent().length() * 0.5).max(1e-6);
        for l in &scene.lights {
            let w = match l {
                Light::Point { intensity, .. } => 4.0 * PI * luminance(*intensity),
                Light::Spot {
                    intensity,
                    cos_outer,
                    ..
                } => 2.0 * PI * (1.0 - cos_outer) * luminance(*intensity),
                Light::Directional { irradiance, .. } => {
                    PI * radius * radius * luminance(*irradiance)
                }
                Light::Environment { radiance } => {
                    environment += *radiance;
                    continue;
                }
            };
            if w > 0.0 {
                entries.push(Entry::Punctual(l.clone()));
                weights.push(w);
            }
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
                let v = scene.world_triangle(i as u32, p);
                let area = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).length();
                entries.push(Entry::Triangle {
                    inst: i as u32,
                    prim: p,
                    v,
                    area,
                });
                weights.push(PI * area * luminance(mat.emissive));
            }
        }
        let total: f32 = weights.iter().sum();
        let mut acc = 0.0;
        let cdf = weights
            .iter()
            .map(|w| {
                acc += w / total;
                acc
            })
            .collect();
        Self {
            entries,
            cdf,
            first_triangle,
            environment,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    fn probability(&self, i: usize) -> f32 {
        self.cdf[i] - if i == 0 { 0.0 } else { self.cdf[i - 1] }
    }

    /// Picks a light with `u_choice` and a point on it with `u`, as seen from `p`.
    pub fn sample(&self, scene: &Scene, p: Vec3, u_choice: f32, u: Vec2) -> Option<LightSample> {
        if self.entries.is_empty() {
            return None;
        }
        let i = self
            .cdf
            .partition_point(|&c| c <= u_choice)
            .min(self.entries.len() - 1);
        let choice = self.probability(i);
        if choice <= 0.0 {
            return None;
        }
        match &self.entries[i] {
            Entry::Punctual(light) => sample_punctual(light, p).map(|(wi, dist, li)| LightSample {
                wi,
                dist,
                li,
                pdf: choice,
                is_delta: true,
            }),
            Entry::Triangle {
                inst,
                prim,
                v,
                area,
            } => {
                let (b1, b2) = uniform_triangle(u);
                let q = v[0] * (1.0 - b1 - b2) + v[1] * b1 + v[2] * b2;
                let to = q - p;
                let d2 = to.length_squared();
                let dist = d2.sqrt();
                if dist <= 0.0 {
                    return None;
                }
                let wi = to / dist;
                let n = (v[1] - v[0]).cross(v[2] - v[0]).normalize_or_zero();
                let cos_l = n.dot(wi).abs();
                if cos_l <= 0.0 || *area <= 0.0 {
                    return None;
                }
                let mesh = scene.mesh_of(*inst);
                let mat = &scene.materials[mesh.material as usize];
                let li = emission(scene, mat, mesh.uv_at(*prim, b1, b2));
                Some(LightSample {
                    wi,
                    dist,
                    li,
                    pdf: choice * d2 / (cos_l * area),
                    is_delta: false,
                })
            }
        }
    }

    /// The solid-angle pdf with which `sample` would have chosen the point `q` (normal `nq`) on emissive
    /// triangle `(inst, prim)` from `p`: what multiple importance sampling needs for BSDF-sampled hits.
    pub fn pdf_triangle(&self, inst: u32, prim: u32, p: Vec3, q: Vec3, nq: Vec3) -> f32 {
        let first = self.first_triangle[inst as usize];
        if first == u32::MAX {
            return 0.0;
        }
        let i = (first + prim) as usize;
        let Entry::Triangle { area, .. } = &self.entries[i] else {
            return 0.0;
        };
        let to = q - p;
        let d2 = to.length_squared();
        let cos_l = nq.dot(to.normalize_or_zero()).abs();
        if cos_l <= 0.0 || *area <= 0.0 {
            return 0.0;
        }
        self.probability(i) * d2 / (cos_l * area)
    }
}

/// Direction, distance and arriving intensity (already divided by distance squared) of a delta light.
fn sample_punctual(light: &Light, p: Vec3) -> Option<(Vec3, f32, Vec3)> {
    match *light {
        Light::Point {
            position,
            intensity,
        } => {
            let to = position - p;
            let d2 = to.length_squared();
            (d2 > 0.0).then(|| (to / d2.sqrt(), d2.sqrt(), intensity / d2))
        }
        Light::Spot {
            position,
            direction,
            intensity,
            cos_inner,
            cos_outer,
        } => {
            let to = position - p;
            let d2 = to.length_squared();
            if d2 <= 0.0 {
                return None;
            }
            let wi = to / d2.sqrt();
            // KHR_lights_punctual's recommended smooth falloff between the cone angles.
            let scale = 1.0 / (cos_inner - cos_outer).max(1e-3);
            let a = ((direction.dot(-wi) - cos_outer) * scale).clamp(0.0, 1.0);
            (a > 0.0).then(|| (wi, d2.sqrt(), intensity * (a * a) / d2))
        }
        Light::Directional {
            direction,
            irradiance,
        } => Some((-direction.normalize(), f32::INFINITY, irradiance)),
        Light::Environment { .. } => None,
    }
}

/// Uniform barycentrics (b1, b2) on a triangle (the square-root parameterisation).
fn uniform_triangle(u: Vec2) -> (f32, f32) {
    let s = u.x.sqrt();
    (s * (1.0 - u.y), s * u.y)
}
