//! Environments: radiance from every direction that leaves the scene, a constant or a lat-long map.
//! Light samples take a map where it is brighter than its mean, in proportion to the excess (MIS
//! compensation, Karlik et al. 2019, as pbrt-v4's): BSDF samples, which next-event estimation
//! always weighs them against, find the rest as well as any light sample could. A constant
//! environment (or map) takes no light samples.
//!
//! Measured against light samples by the whole luminance (session 34, 64 spp x 6 seeds, 2
//! threads): helmet-env sigma 0.901 -> 0.877, 0.026 -> 0.019 past its 200 sun-glint pixels; under
//! its sky map DamagedHelmet 1.153 -> 1.058, SheenCloth 0.088 -> 0.075, MetalRoughSpheres 0.580 ->
//! 0.565, ClearCoatCarPaint 0.464 -> 0.460, ToyCar the same. Under a uniform map it takes the
//! map's light samples away (2 seeds): EmissiveStrengthTest's cubes get them (0.195 -> 0.134), but
//! coated and sheen materials lose the defensive samples their lobe choice leaned on
//! (ClearCoatCarPaint 0.045 -> 0.052, ToyCar 0.029 -> 0.034).

use std::f32::consts::PI;
use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::{Distribution2D, LightSample};
use crate::render::bsdf::luminance;
use crate::scene::EnvMap;

#[derive(Clone, Debug)]
pub(super) struct Environment {
    radiance: Vec3,
    /// The map, and the distribution light samples take over its lat-long coordinates (`None`
    /// where nothing is above the mean: a uniform map).
    map: Option<(Arc<EnvMap>, Option<Distribution2D>)>,
    /// Mean luminance over the sphere (a constant's too).
    mean: f32,
    /// Mean over the sphere of the luminance above `mean`: what light samples are there for.
    excess: f32,
}

impl Environment {
    pub fn new(radiance: Vec3, map: Option<&Arc<EnvMap>>) -> Self {
        let (map, mean, excess) = match map {
            None => (None, luminance(radiance), 0.0),
            Some(m) => {
                let (dist, mean, excess) = distribution(m, radiance);
                (Some((m.clone(), dist)), mean, excess)
            }
        };
        Self {
            radiance,
            map,
            mean,
            excess,
        }
    }

    /// Mean luminance over the sphere of directions.
    pub fn mean_luminance(&self) -> f32 {
        self.mean
    }

    /// The environment's weight among the lights: the flux through `far_disk`, the area of the
    /// scene's bounding disk, of the part light samples take (irradiance on a plane is pi times the
    /// mean radiance over the sphere); zero where it takes none.
    pub fn power(&self, far_disk: f32) -> f32 {
        far_disk * PI * self.excess
    }

    pub fn sample(&self, u: Vec2, choice: f32) -> Option<LightSample> {
        let (m, Some(dist)) = self.map.as_ref()? else {
            return None;
        };
        let (uv, pdf_uv) = dist.sample(u);
        let (wi, sin_theta) = m.uv_to_direction(uv);
        if sin_theta <= 0.0 || pdf_uv <= 0.0 {
            return None;
        }
        let li = self.radiance * m.at_uv(uv);
        Some(LightSample {
            wi,
            dist: f32::INFINITY,
            li,
            pdf: choice * solid_angle_pdf(pdf_uv, sin_theta),
            is_delta: false,
        })
    }

    /// Radiance from unit direction `d`.
    #[inline(always)]
    pub fn radiance(&self, d: Vec3) -> Vec3 {
        match &self.map {
            None => self.radiance,
            Some((m, _)) => self.radiance * m.lookup(d),
        }
    }

    /// Radiance from unit direction `d`, and the solid-angle pdf (before the choice probability)
    /// with which `sample` picks `d` (zero where it never does).
    pub fn radiance_and_pdf(&self, d: Vec3) -> (Vec3, f32) {
        match &self.map {
            None | Some((_, None)) => (self.radiance(d), 0.0),
            Some((m, Some(dist))) => {
                let uv = m.direction_to_uv(d);
                let sin_theta = (1.0 - (m.rotation.transpose() * d).y.powi(2))
                    .max(0.0)
                    .sqrt();
                let pdf = if sin_theta > 0.0 {
                    solid_angle_pdf(dist.pdf(uv), sin_theta)
                } else {
                    0.0
                };
                // The pixel from the same coordinates (`lookup(d)` would take the inverse
                // trigonometry, 6% of an environment-lit render, a second time).
                (self.radiance * m.at_uv(uv), pdf)
            }
        }
    }
}

/// A lat-long pdf (over the unit square of (phi, theta) / (2 pi, pi)) as a solid-angle pdf.
fn solid_angle_pdf(pdf_uv: f32, sin_theta: f32) -> f32 {
    pdf_uv / (2.0 * PI * PI * sin_theta)
}

/// The distribution light samples take over an environment map (of radiance `scale` times the
/// pixel): each pixel's luminance above the mean, times sin(theta) for the lat-long area
/// distortion (`None` where no pixel is above it); the mean luminance over the sphere, and the
/// mean of the excess. Both means weigh the pixels as the distribution does (sin(theta) at the row's
/// centre), so a uniform map has no pixel above its mean; a pixel within 1e-5 of it counts as none
/// (rounding would otherwise leave a uniform map a distribution of noise).
fn distribution(m: &EnvMap, scale: Vec3) -> (Option<Distribution2D>, f32, f32) {
    let sin_theta: Vec<f32> = (0..m.height)
        .map(|y| (PI * (y as f32 + 0.5) / m.height as f32).sin())
        .collect();
    // Each pixel's luminance, then in place its excess over the mean times sin(theta).
    let mut func: Vec<f32> = m
        .pixels
        .iter()
        .map(|&p| luminance(scale * p).max(0.0))
        .collect();
    let (mut sum, mut weight) = (0.0f64, 0.0f64);
    for (row, &s) in func.chunks(m.width).zip(&sin_theta) {
        sum += row.iter().map(|&l| l as f64).sum::<f64>() * s as f64;
        weight += s as f64 * m.width as f64;
    }
    // Every row's sin(theta) is positive and a map has pixels (`EnvMap::new`), so weight is too.
    let mean = (sum / weight) as f32;
    let mut excess = 0.0f64;
    for (row, &s) in func.chunks_mut(m.width).zip(&sin_theta) {
        for f in row {
            *f = if *f > mean * (1.0 + 1e-5) {
                (*f - mean) * s
            } else {
                0.0
            };
            excess += *f as f64;
        }
    }
    let dist = (excess > 0.0).then(|| Distribution2D::new(&func, m.width));
    (dist, mean, (excess / weight) as f32)
}
