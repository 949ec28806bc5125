//! The lights the integrator samples: punctual lights, every emissive triangle, analytic sphere, disk
//! and rectangle lights and environments, chosen in proportion to power through an alias table.
//!
//! Analytic lights are not in the accelerators: rays find them through `emitted` (up to the scene
//! hit) and environments through `escaped`, both returning radiance already weighted by multiple
//! importance sampling against the BSDF sample that made the ray. They do not occlude anything.

mod alias;
mod distribution;

use std::f32::consts::PI;
use std::sync::Arc;

use glam::{Vec2, Vec3};

pub use alias::AliasTable;
pub use distribution::{Distribution1D, Distribution2D};

use super::bsdf::luminance;
use super::surface::emission;
use crate::geometry::Ray;
use crate::scene::{EnvMap, Light, Scene};

#[derive(Clone, Debug)]
enum Entry {
    /// Point, spot and directional lights.
    Punctual(Light),
    /// A world-space emissive triangle: instance, primitive, vertices.
    Triangle {
        inst: u32,
        prim: u32,
        v: [Vec3; 3],
        area: f32,
    },
    Sphere {
        center: Vec3,
        radius: f32,
        radiance: Vec3,
    },
    Disk {
        center: Vec3,
        /// Unit normal, the emitting side.
        normal: Vec3,
        radius: f32,
        radiance: Vec3,
    },
    Rect {
        corner: Vec3,
        edge_u: Vec3,
        edge_v: Vec3,
        /// Unit `edge_u x edge_v`, the emitting side.
        normal: Vec3,
        area: f32,
        radiance: Vec3,
    },
    Environment {
        radiance: Vec3,
        /// The map and its importance-sampling distribution over lat-long coordinates (luminance
        /// times sin(theta)); a constant environment is sampled uniformly over the sphere.
        map: Option<(Arc<EnvMap>, Distribution2D)>,
    },
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
    match pdf_bsdf {
        None => 1.0,
        Some(b) => {
            let (a2, b2) = (pdf_light * pdf_light, b * b);
            if a2 + b2 == 0.0 {
                0.0
            } else {
                b2 / (a2 + b2)
            }
        }
    }
}

impl LightSet {
    pub fn new(scene: &Scene) -> Self {
        let mut entries = Vec::new();
        let mut weights = Vec::new();
        let (mut hittable, mut environments) = (Vec::new(), Vec::new());
        let radius = (scene.bounds().extent().length() * 0.5).max(1e-6);
        // Flux through the scene's bounding disk, for lights at infinity.
        let far_disk = PI * radius * radius;
        for l in &scene.lights {
            let (entry, w) = match l {
                Light::Point { intensity, .. } => {
                    (Entry::Punctual(l.clone()), 4.0 * PI * luminance(*intensity))
                }
                Light::Spot {
                    intensity,
                    cos_outer,
                    ..
                } => (
                    Entry::Punctual(l.clone()),
                    2.0 * PI * (1.0 - cos_outer) * luminance(*intensity),
                ),
                Light::Directional { irradiance, .. } => (
                    Entry::Punctual(l.clone()),
                    far_disk * luminance(*irradiance),
                ),
                &Light::Sphere {
                    center,
                    radius,
                    radiance,
                } => (
                    Entry::Sphere {
                        center,
                        radius,
                        radiance,
                    },
                    PI * 4.0 * PI * radius * radius * luminance(radiance),
                ),
                &Light::Disk {
                    center,
                    normal,
                    radius,
                    radiance,
                } => (
                    Entry::Disk {
                        center,
                        normal: normal.normalize_or_zero(),
                        radius,
                        radiance,
                    },
                    PI * PI * radius * radius * luminance(radiance),
                ),
                &Light::Rect {
                    corner,
                    edge_u,
                    edge_v,
                    radiance,
                } => {
                    let c = edge_u.cross(edge_v);
                    let area = c.length();
                    (
                        Entry::Rect {
                            corner,
                            edge_u,
                            edge_v,
                            normal: c.normalize_or_zero(),
                            area,
                            radiance,
                        },
                        PI * area * luminance(radiance),
                    )
                }
                Light::Environment { radiance, map } => {
                    // Irradiance on a plane is pi times the mean radiance over the sphere.
                    let (map, mean) = match map {
                        None => (None, luminance(*radiance)),
                        Some(m) => {
                            let (dist, mean) = env_distribution(m, *radiance);
                            (Some((m.clone(), dist)), mean)
                        }
                    };
                    (
                        Entry::Environment {
                            radiance: *radiance,
                            map,
                        },
                        far_disk * PI * mean,
                    )
                }
            };
            let w = if w.is_finite() { w.max(0.0) } else { 0.0 };
            match entry {
                // A punctual light of no power can never be seen: leave it out.
                Entry::Punctual(_) if w <= 0.0 => continue,
                Entry::Sphere { .. } | Entry::Disk { .. } | Entry::Rect { .. } => {
                    hittable.push(entries.len() as u32)
                }
                Entry::Environment { .. } => environments.push(entries.len() as u32),
                _ => {}
            }
            entries.push(entry);
            weights.push(w);
        }
        let mut first_triangle = vec![u32::MAX; scene.instances.len()];
        for (i, inst) in scene.instances.iter().enumerate() {
            let mesh = &scene.meshes[inst.mesh as usize];
            let mat = &scene.materials[mesh.material as usize];
            if !mat.is_emissive() {
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
        let area_sample = |q: Vec3, n: Vec3, area: f32, li: Vec3| {
            let to = q - p;
            let d2 = to.length_squared();
            let dist = d2.sqrt();
            if dist <= 0.0 || area <= 0.0 {
                return None;
            }
            let wi = to / dist;
            let cos_l = -n.dot(wi);
            (cos_l > 0.0).then(|| LightSample {
                wi,
                dist,
                li,
                pdf: choice * d2 / (cos_l * area),
                is_delta: false,
            })
        };
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
                let mut n = (v[1] - v[0]).cross(v[2] - v[0]).normalize_or_zero();
                // Emissive triangles are two-sided.
                if n.dot(q - p) > 0.0 {
                    n = -n;
                }
                let mesh = scene.mesh_of(*inst);
                let mat = &scene.materials[mesh.material as usize];
                let li = emission(scene, mat, mesh.uv_at(*prim, b1, b2));
                area_sample(q, n, *area, li)
            }
            &Entry::Sphere {
                center,
                radius,
                radiance,
            } => {
                let to_c = center - p;
                let dc2 = to_c.length_squared();
                let r2 = radius * radius;
                let omc_max = sphere_cone(dc2, r2)?;
                // Uniform in the subtended cone; 1 - cos(theta) kept directly for small cones.
                let omc = u.x * omc_max;
                let cos = 1.0 - omc;
                let sin = (omc * (2.0 - omc)).max(0.0).sqrt();
                let (sp, cp) = (2.0 * PI * u.y).sin_cos();
                let dc = dc2.sqrt();
                let w = to_c / dc;
                let (t, b) = w.any_orthonormal_pair();
                let wi = (t * (sin * cp) + b * (sin * sp) + w * cos).normalize();
                // Nearer intersection with the sphere along wi (clamped at grazing directions).
                let dist = dc * cos - (r2 - dc2 * sin * sin).max(0.0).sqrt();
                Some(LightSample {
                    wi,
                    dist: dist.max(0.0),
                    li: radiance,
                    pdf: choice / (2.0 * PI * omc_max),
                    is_delta: false,
                })
            }
            &Entry::Disk {
                center,
                normal,
                radius,
                radiance,
            } => {
                let (t, b) = normal.any_orthonormal_pair();
                let d = concentric_disk(u) * radius;
                let q = center + t * d.x + b * d.y;
                area_sample(q, normal, PI * radius * radius, radiance)
            }
            &Entry::Rect {
                corner,
                edge_u,
                edge_v,
                normal,
                area,
                radiance,
            } => area_sample(corner + edge_u * u.x + edge_v * u.y, normal, area, radiance),
            Entry::Environment { radiance, map } => {
                let (wi, pdf, li) = match map {
                    None => (uniform_sphere(u), 1.0 / (4.0 * PI), *radiance),
                    Some((m, dist)) => {
                        let (uv, pdf_uv) = dist.sample(u);
                        let (wi, sin_theta) = m.uv_to_direction(uv);
                        if sin_theta <= 0.0 || pdf_uv <= 0.0 {
                            return None;
                        }
                        let (x, y) = m.pixel_of(uv);
                        (
                            wi,
                            pdf_uv / (2.0 * PI * PI * sin_theta),
                            *radiance * m.pixels[y * m.width + x],
                        )
                    }
                };
                Some(LightSample {
                    wi,
                    dist: f32::INFINITY,
                    li,
                    pdf: choice * pdf,
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
        self.table.pmf(i) * d2 / (cos_l * area)
    }

    /// Whether any light is found by rays rather than only by sampling (analytic area lights or an
    /// environment).
    pub fn has_hittable(&self) -> bool {
        !self.hittable.is_empty() || !self.environments.is_empty()
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
            let hit = match self.entries[i] {
                Entry::Sphere {
                    center,
                    radius,
                    radiance,
                } => hit_sphere(o, d, center, radius).and_then(|t| {
                    let omc_max = sphere_cone((center - o).length_squared(), radius * radius)?;
                    Some((t, radiance, 1.0 / (2.0 * PI * omc_max)))
                }),
                Entry::Disk {
                    center,
                    normal,
                    radius,
                    radiance,
                } => hit_plane(o, d, center, normal)
                    .filter(|&(t, _)| (o + d * t - center).length_squared() <= radius * radius)
                    .map(|(t, cos)| (t, radiance, t * t / (cos * PI * radius * radius))),
                Entry::Rect {
                    corner,
                    edge_u,
                    edge_v,
                    normal,
                    area,
                    radiance,
                } => hit_plane(o, d, corner, normal)
                    .filter(|&(t, _)| {
                        let q = o + d * t - corner;
                        let (s, r) = (
                            q.dot(edge_u) / edge_u.length_squared(),
                            q.dot(edge_v) / edge_v.length_squared(),
                        );
                        // Exact for rectangles; a parallelogram would need the dual basis.
                        (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&r)
                    })
                    .map(|(t, cos)| (t, radiance, t * t / (cos * area))),
                _ => None,
            };
            if let Some((t, radiance, pdf)) = hit {
                if t < t_max {
                    l += radiance * mis_weight(pdf_bsdf, self.table.pmf(i) * pdf);
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
            let Entry::Environment { radiance, map } = &self.entries[i] else {
                continue;
            };
            let (li, pdf) = match map {
                None => (*radiance, 1.0 / (4.0 * PI)),
                Some((m, dist)) => {
                    let uv = m.direction_to_uv(d);
                    let sin_theta = (1.0 - (m.rotation.transpose() * d).y.powi(2))
                        .max(0.0)
                        .sqrt();
                    let pdf = if sin_theta > 0.0 {
                        dist.pdf(uv) / (2.0 * PI * PI * sin_theta)
                    } else {
                        0.0
                    };
                    (*radiance * m.lookup(d), pdf)
                }
            };
            l += li * mis_weight(pdf_bsdf, self.table.pmf(i) * pdf);
        }
        l
    }
}

/// The importance-sampling distribution of an environment map (luminance of `scale` times the pixel,
/// times sin(theta) for the lat-long area distortion) and the map's mean luminance over the sphere.
fn env_distribution(m: &EnvMap, scale: Vec3) -> (Distribution2D, f32) {
    let mut func = Vec::with_capacity(m.width * m.height);
    let mut sum = 0.0f64;
    for y in 0..m.height {
        let sin_theta = (PI * (y as f32 + 0.5) / m.height as f32).sin();
        for x in 0..m.width {
            let f = luminance(scale * m.pixels[y * m.width + x]).max(0.0) * sin_theta;
            sum += f as f64;
            func.push(f);
        }
    }
    // Integral over the sphere of luminance: sum f * (2 pi / w) * (pi / h); the mean divides by 4 pi.
    let mean = sum * (2.0 * std::f64::consts::PI * std::f64::consts::PI)
        / (m.width * m.height) as f64
        / (4.0 * std::f64::consts::PI);
    (Distribution2D::new(&func, m.width), mean as f32)
}

/// `1 - cos(theta_max)` of the cone a sphere (squared radius `r2`) subtends from squared distance
/// `dc2` to its centre; `None` from inside, where an outward-emitting sphere sends nothing.
fn sphere_cone(dc2: f32, r2: f32) -> Option<f32> {
    if dc2 <= r2 {
        return None;
    }
    let sin2 = r2 / dc2;
    let omc = sin2 / (1.0 + (1.0 - sin2).max(0.0).sqrt());
    (omc > 0.0).then_some(omc)
}

/// Distance along unit `d` from `o` (outside) to the near side of a sphere.
fn hit_sphere(o: Vec3, d: Vec3, center: Vec3, radius: f32) -> Option<f32> {
    let oc = o - center;
    let c = oc.length_squared() - radius * radius;
    if c <= 0.0 {
        return None;
    }
    let b = oc.dot(d);
    // Ray Tracing Gems ch. 7: the discriminant from the distance to the closest approach.
    let closest = oc - d * b;
    let disc = radius * radius - closest.length_squared();
    if b >= 0.0 || disc < 0.0 {
        return None;
    }
    let q = -b + disc.sqrt();
    let t = c / q;
    (t > 0.0).then_some(t)
}

/// Distance along unit `d` from `o` to the plane through `p` with unit normal `n`, when `o` is on
/// the side `n` faces and `d` goes towards the plane; also `cos` between `-d` and `n`.
fn hit_plane(o: Vec3, d: Vec3, p: Vec3, n: Vec3) -> Option<(f32, f32)> {
    let cos = -d.dot(n);
    let h = (o - p).dot(n);
    if cos <= 0.0 || h <= 0.0 {
        return None;
    }
    Some((h / cos, cos))
}

/// A uniformly distributed unit vector.
fn uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec3::new(r * c, r * s, z)
}

/// Shirley and Chiu's concentric map from the unit square to the unit disk (area-preserving).
fn concentric_disk(u: Vec2) -> Vec2 {
    let a = 2.0 * u - Vec2::ONE;
    if a == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let (r, theta) = if a.x.abs() > a.y.abs() {
        (a.x, std::f32::consts::FRAC_PI_4 * (a.y / a.x))
    } else {
        (
            a.y,
            std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (a.x / a.y),
        )
    };
    let (s, c) = theta.sin_cos();
    Vec2::new(r * c, r * s)
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
        _ => None,
    }
}

/// Uniform barycentrics (b1, b2) on a triangle (the square-root parameterisation).
fn uniform_triangle(u: Vec2) -> (f32, f32) {
    let s = u.x.sqrt();
    (s * (1.0 - u.y), s * u.y)
}
