//! Rendering: camera rays, materials, lights and the path-tracing integrator, run over image tiles in
//! parallel. The same seed gives the same image whatever the thread count or tile order.

pub mod bsdf;
pub mod camera;
pub mod integrator;
pub mod light;
pub mod offset;
pub mod surface;

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

use glam::{Vec2, Vec4};
use indicatif::ProgressBar;
use rayon::prelude::*;

pub use camera::RayCamera;
pub use integrator::Integrator;

use crate::accel::Accel;
use crate::film::Image;
use crate::sample::{Dim, RandomSampler, Sampler};
use crate::scene::{Camera, Scene};

/// Tile edge in pixels: small enough to balance load, big enough to amortise per-tile setup.
const TILE: usize = 16;

#[derive(Clone, Debug)]
pub struct RenderSettings {
    pub width: usize,
    pub height: usize,
    pub spp: u32,
    /// Bounces after the camera ray (1 = direct light only).
    pub max_depth: u32,
    pub seed: u64,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 640,
            height: 480,
            spp: 16,
            max_depth: 5,
            seed: 0,
        }
    }
}

#[derive(Clone, Copy, Debug, Default)]
pub struct RenderStats {
    pub rays: u64,
    pub seconds: f64,
}

impl RenderStats {
    pub fn mrays_per_second(&self) -> f64 {
        self.rays as f64 / self.seconds.max(1e-9) / 1e6
    }
}

/// Renders the scene through `camera` into a linear RGBA image (box-filtered pixel samples).
pub fn render(
    scene: &Scene,
    accel: &dyn Accel,
    camera: &Camera,
    settings: &RenderSettings,
    progress: &ProgressBar,
) -> (Image, RenderStats) {
    let start = Instant::now();
    let integrator = Integrator::new(scene, accel, settings.max_depth);
    let cam = RayCamera::new(camera, settings.width, settings.height);
    let (w, h) = (settings.width, settings.height);
    let tiles: Vec<(usize, usize)> = (0..h.div_ceil(TILE))
        .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (tx * TILE, ty * TILE)))
        .collect();
    progress.set_length(tiles.len() as u64);
    let rays = AtomicU64::new(0);
    let spp = settings.spp.max(1);
    let rendered: Vec<((usize, usize), Vec<Vec4>)> = tiles
        .par_iter()
        .map(|&(x0, y0)| {
            let mut sampler = RandomSampler::new(settings.seed);
            let mut pixels = Vec::with_capacity(TILE * TILE);
            let mut tile_rays = 0u64;
            for y in y0..(y0 + TILE).min(h) {
                for x in x0..(x0 + TILE).min(w) {
                    let mut sum = Vec4::ZERO;
                    for i in 0..spp {
                        sampler.start(x as u32, y as u32, i);
                        let film = Vec2::new(x as f32, y as f32) + sampler.get_2d(Dim::Pixel, 0);
                        let r = integrator.li(cam.ray(film), &mut sampler);
                        // A non-finite sample would poison the pixel: count it as black.
                        if r.radiance.is_finite() {
                            sum += r.radiance;
                        }
                        tile_rays += r.rays as u64;
                    }
                    pixels.push(sum / spp as f32);
                }
            }
            rays.fetch_add(tile_rays, Ordering::Relaxed);
            progress.inc(1);
            ((x0, y0), pixels)
        })
        .collect();
    let mut image = Image::new(w, h);
    for ((x0, y0), pixels) in rendered {
        let tw = (x0 + TILE).min(w) - x0;
        for (k, p) in pixels.into_iter().enumerate() {
            image.pixels[(y0 + k / tw) * w + x0 + k % tw] = p;
        }
    }
    progress.finish_and_clear();
    let stats = RenderStats {
        rays: rays.into_inner(),
        seconds: start.elapsed().as_secs_f64(),
    };
    (image, stats)
}
