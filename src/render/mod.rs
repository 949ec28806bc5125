//! Rendering: camera rays, materials, lights and the path-tracing integrator, run over image tiles in
//! parallel. The same seed gives the same image whatever the thread count or tile order.

pub mod bsdf;
pub mod camera;
pub mod emission_split;
pub mod feature_film;
pub mod features;
pub mod integrator;
pub mod job;
pub mod light;
pub mod offset;
pub mod surface;

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::{DVec4, Vec2, Vec3, Vec4};
use indicatif::ProgressBar;
use rayon::prelude::*;

pub use crate::film::aov::FeatureImages;
pub use camera::RayCamera;
pub use emission_split::EmissionSplits;
pub use integrator::{FirstHit, Integrator};
pub use light::LightSampler;

use emission_split::SplitPixels;
use feature_film::{DepthAxis, FeatureAcc};
use features::PathFeatures;

use crate::accel::Accel;
use crate::film::filter::{Filter, FilterKind};
use crate::film::shard::{PixelSum, Shard};
use crate::film::Image;
use crate::geometry::{Hit, Ray};
use crate::sample::{AnySampler, Dim, Sampler, SamplerKind};
use crate::scene::features::Features;
use crate::scene::{Camera, Scene};

/// Tile edge in pixels: small enough to balance load, big enough to amortise per-tile setup.
const TILE: usize = 16;
/// Camera rays of one pixel traced together (Embree's packet width).
const PACKET: usize = 8;

/// How samples are spread over the pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum AdaptiveMode {
    /// `spp` samples in every pixel (or rounds until `time_budget` is spent).
    #[default]
    Off,
    /// Rounds of growing sample counts; a pixel stops once its estimated relative error (from two
    /// interleaved half buffers, Dammertz et al. 2010, over its 3x3 neighbourhood) is under the
    /// target, and otherwise gets the samples that the 1/sqrt(n) law predicts it needs (at most twice
    /// what it has).
    Variance,
    /// Whitted-style image-space supersampling: sample the corners of the pixel, subdivide where
    /// they differ beyond the target contrast, recursively (box filter, no jitter).
    Corners,
}

impl std::fmt::Display for AdaptiveMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            AdaptiveMode::Off => "off",
            AdaptiveMode::Variance => "variance",
            AdaptiveMode::Corners => "corners",
        })
    }
}

#[derive(Clone, Debug)]
pub struct RenderSettings {
    pub width: usize,
    pub height: usize,
    /// Samples per pixel when not adaptive and without a time budget.
    pub spp: u32,
    /// Bounces after the camera ray (1 = direct light only).
    pub max_depth: u32,
    pub seed: u64,
    pub sampler: SamplerKind,
    pub filter: FilterKind,
    /// Filter radius in pixels (default: the filter's own).
    pub filter_radius: Option<f32>,
    pub adaptive: AdaptiveMode,
    /// Adaptive stopping threshold: the relative RMS error per pixel (`variance`), or the corner
    /// contrast (`corners`).
    pub target_error: f32,
    /// No pixel stops before this many samples (adaptive modes).
    pub min_spp: u32,
    /// No pixel takes more than this many samples (adaptive modes).
    pub max_spp: u32,
    /// Render in rounds until this much time is spent (then `spp` is ignored; the result depends on
    /// the machine's speed, so it is not reproducible).
    pub time_budget: Option<Duration>,
    /// Shutter interval in seconds relative to `frame_time`; open == close means no motion blur.
    /// The scene must be posed with these before its accelerator is built
    /// (`scene::animation::pose(scene, frame_time, shutter)`); the render itself draws ray times only
    /// when the posed scene has motion.
    pub shutter: [f32; 2],
    /// Seconds into the scene's animation at which the frame is taken (see `shutter`).
    pub frame_time: f32,
    /// Take only the sample indices of this shard in every pixel (non-adaptive renders); the
    /// shards' `RenderOutput::sums` add up to the whole render's.
    pub sample_shard: Option<Shard>,
    /// Also accumulate the feature images (`RenderOutput::features`; not in the corner mode). Off,
    /// the render does exactly what it did before they existed.
    pub feature_images: bool,
    /// How next-event estimation chooses among the lights.
    pub light_sampler: LightSampler,
    /// Camera rays a path takes for the emission it sees directly, in pixels where emitters have
    /// edges (`emission_split`).
    pub emission_splits: EmissionSplits,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 640,
            height: 480,
            spp: 16,
            max_depth: 5,
            seed: 0,
            sampler: SamplerKind::default(),
            filter: FilterKind::default(),
            filter_radius: None,
            adaptive: AdaptiveMode::Off,
            target_error: 0.01,
            min_spp: 16,
            max_spp: 1024,
            time_budget: None,
            shutter: [0.0, 0.0],
            frame_time: 0.0,
            sample_shard: None,
            feature_images: false,
            light_sampler: LightSampler::Auto,
            emission_splits: EmissionSplits::default(),
        }
    }
}

#[derive(Clone, Copy, Debug, Default)]
pub struct RenderStats {
    pub rays: u64,
    pub seconds: f64,
    /// Camera paths traced (all pixels).
    pub samples: u64,
    /// Fewest and most samples any pixel took.
    pub min_spp: u32,
    pub max_spp: u32,
    /// Sampling rounds (1 unless adaptive or time-budgeted).
    pub rounds: u32,
    /// Pixels whose paths split their camera rays for the emission seen directly.
    pub split_pixels: usize,
}

impl RenderStats {
    pub fn mrays_per_second(&self) -> f64 {
        self.rays as f64 / self.seconds.max(1e-9) / 1e6
    }
}

/// The image with what it took: statistics and the samples each pixel took (row-major).
#[derive(Clone, Debug)]
pub struct RenderOutput {
    pub image: Image,
    pub stats: RenderStats,
    pub spp: Vec<u32>,
    /// Each pixel's weighted sum of samples and of weights (what a sample shard keeps).
    pub sums: Vec<PixelSum>,
    /// The feature images, when `RenderSettings::feature_images` asked for them.
    pub features: Option<FeatureImages>,
}

impl RenderOutput {
    pub fn mean_spp(&self) -> f64 {
        self.stats.samples as f64 / self.spp.len().max(1) as f64
    }
}

/// Renders the scene through `camera` into a linear RGBA image.
pub fn render(
    scene: &Scene,
    accel: &dyn Accel,
    camera: &Camera,
    settings: &RenderSettings,
    progress: &ProgressBar,
) -> (Image, RenderStats) {
    let out = render_full(scene, accel, camera, settings, progress);
    (out.image, out.stats)
}

/// Weighted sums of one pixel: all its samples, and the even-numbered half (for error estimates).
#[derive(Clone, Copy, Debug, Default)]
struct Acc {
    sum: DVec4,
    w: f64,
    half: DVec4,
    half_w: f64,
    n: u32,
    /// Rays its samples traced (their cost, for the adaptive allocation).
    rays: u64,
}

impl Acc {
    fn value(&self) -> DVec4 {
        if self.w != 0.0 {
            self.sum / self.w
        } else {
            DVec4::ZERO
        }
    }
    fn half_value(&self) -> DVec4 {
        if self.half_w != 0.0 {
            self.half / self.half_w
        } else {
            DVec4::ZERO
        }
    }
    /// Squared relative error estimate of the pixel, summed over RGB: (I - A)^2 / (I^2 + 0.01).
    fn rel_err2(&self) -> f64 {
        let (i, a) = (self.value(), self.half_value());
        (0..3)
            .map(|c| (i[c] - a[c]) * (i[c] - a[c]) / (i[c] * i[c] + 0.01))
            .sum()
    }
}

/// One camera sample of a pixel: its index, its point in the pixel's 2D set, and the filter's
/// offset and weight for that point.
#[derive(Clone, Copy, Debug, Default)]
struct CameraSample {
    index: u32,
    u: Vec2,
    offset: Vec2,
    weight: f32,
}

struct Tile {
    x0: usize,
    y0: usize,
    x1: usize,
    px: Vec<Acc>,
    /// Feature sums per pixel, empty unless feature images are asked for.
    features: Vec<FeatureAcc>,
}

struct Ctx<'a> {
    integrator: Integrator<'a>,
    cam: RayCamera,
    filter: Filter,
    settings: &'a RenderSettings,
    pass: u32,
    axis: DepthAxis,
    /// Where paths split their camera rays (none: nowhere).
    splits: Option<SplitPixels>,
    /// The first pass is all the render's samples (no adaptive rounds, no time budget), so the
    /// camera rays' companions may take the pixel sequence's points past it.
    single_pass: bool,
}

impl Ctx<'_> {
    /// Whether this render keeps feature images (not in the corner mode, whose samples are not
    /// filtered as the others are).
    fn takes_features(&self) -> bool {
        self.settings.feature_images && self.settings.adaptive != AdaptiveMode::Corners
    }

    /// Takes this round's samples in every pixel of the tile; returns the rays traced.
    fn sample_tile(&self, tile: &mut Tile, target: &[u32]) -> u64 {
        let s = self.settings;
        let mut sampler = AnySampler::new(s.sampler, s.seed, self.pass);
        let mut rays = 0u64;
        let tw = tile.x1 - tile.x0;
        let mut unused = FeatureAcc::default();
        for (k, acc) in tile.px.iter_mut().enumerate() {
            let (x, y) = (tile.x0 + k % tw, tile.y0 + k / tw);
            let to = target[y * s.width + x];
            rays += if s.adaptive == AdaptiveMode::Corners {
                self.corners_pixel(&mut sampler, x, y, acc)
            } else if to <= acc.n {
                0
            } else if let Some(f) = tile.features.get_mut(k) {
                self.sample_pixel::<true>(&mut sampler, (x, y), to, acc, f)
            } else {
                self.sample_pixel::<false>(&mut sampler, (x, y), to, acc, &mut unused)
            };
        }
        rays
    }

    /// The camera ray of pixel (x, y)'s sample at `u` in the pixel, made in `slot` (`camera_ray`);
    /// returns the filter's offset and weight for it.
    #[inline(always)]
    fn pixel_ray(
        &self,
        (x, y): (usize, usize),
        u: Vec2,
        sampler: &mut AnySampler,
        slot: &mut Ray,
    ) -> (Vec2, f32) {
        let (offset, w) = self.filter.sample(u);
        let film = Vec2::new(x as f32 + 0.5, y as f32 + 0.5) + offset;
        self.camera_ray(film, sampler, slot);
        (offset, w)
    }

    /// The camera ray through `film` with its seed, as `Integrator::li` takes it, made in `slot`:
    /// a ray rebuilt around its seed and then copied read the seed's narrow store back through
    /// wide loads, a store-forwarding stall on every camera ray (with the camera inlined, a view of
    /// the sky alone 2.10 -> 1.97 s, 256 spp, one thread).
    #[inline(always)]
    fn camera_ray(&self, film: Vec2, sampler: &mut AnySampler, slot: &mut Ray) {
        *slot = self.cam.generate(film, sampler);
        slot.seed = self.integrator.camera_seed(sampler);
    }

    /// Takes samples `acc.n .. to` of pixel (x, y), with `FEATURES` also into `features`; returns
    /// the rays traced.
    fn sample_pixel<const FEATURES: bool>(
        &self,
        sampler: &mut AnySampler,
        (x, y): (usize, usize),
        to: u32,
        acc: &mut Acc,
        features: &mut FeatureAcc,
    ) -> u64 {
        let mut rays = 0u64;
        let mut next = acc.n;
        while next < to {
            // The camera rays of up to `PACKET` of the pixel's samples, traced together (they are
            // coherent: Embree answers them as one packet); then each path goes on alone.
            let mut takes = [CameraSample::default(); PACKET];
            let mut cam = [Ray::new(Vec3::ZERO, Vec3::Z); PACKET];
            let mut n = 0;
            while next < to && n < PACKET {
                let i = next;
                next += 1;
                if self.settings.sample_shard.is_some_and(|s| !s.takes(i)) {
                    continue;
                }
                sampler.start(x as u32, y as u32, i);
                let u = sampler.get_2d(Dim::Pixel, 0);
                let (offset, w) = self.pixel_ray((x, y), u, sampler, &mut cam[n]);
                takes[n] = CameraSample {
                    index: i,
                    u,
                    offset,
                    weight: w,
                };
                n += 1;
            }
            let mut first = [None; PACKET];
            self.integrator
                .accel
                .intersect_many(&cam[..n], &mut first[..n]);
            let mut split = [Vec3::ZERO; PACKET];
            if self.splits.as_ref().is_some_and(|s| s.at(x, y)) {
                rays +=
                    self.split_emission(sampler, (x, y), &takes[..n], (&cam, &first), &mut split);
            }
            // The rays that met nothing, looked up first in a loop of their own: the lookups (long
            // chains of dependent arithmetic) overlap one another there.
            let mut missed = [None; PACKET];
            if !FEATURES {
                for ((m, ray), hit) in missed.iter_mut().zip(&cam).zip(&first).take(n) {
                    if hit.is_none() {
                        *m = Some(self.integrator.missed(ray));
                    }
                }
            }
            for ((((take, &ray), &hit), &split), &missed) in takes
                .iter()
                .zip(&cam)
                .zip(&first)
                .zip(&split)
                .zip(&missed)
                .take(n)
            {
                let CameraSample {
                    index: i,
                    offset,
                    weight: w,
                    ..
                } = *take;
                let mut path = PathFeatures::default();
                let r = if let Some(r) = missed {
                    r
                } else {
                    // The sampler is stateless per dimension: restarted, it draws the path's
                    // dimensions as if the camera ray had just been made.
                    sampler.start(x as u32, y as u32, i);
                    let first = FirstHit::Traced(hit);
                    if FEATURES {
                        self.integrator.li_features(ray, first, sampler, &mut path)
                    } else {
                        self.integrator.li(ray, first, sampler)
                    }
                };
                rays += r.rays as u64;
                // A non-finite sample would poison the pixel: count it as black.
                let l = if r.radiance.is_finite() {
                    r.radiance.as_dvec4()
                } else {
                    DVec4::ZERO
                };
                let v = l * w as f64 + split.extend(0.0).as_dvec4();
                // What the features see as the sample's radiance: its share of `v`.
                let l = if w != 0.0 { v / w as f64 } else { l };
                if FEATURES {
                    features.add(&path, l, w as f64, offset, &self.axis);
                }
                acc.sum += v;
                acc.w += w as f64;
                if i % 2 == 0 {
                    acc.half += v;
                    acc.half_w += w as f64;
                }
            }
        }
        acc.n = acc.n.max(to);
        acc.rays += rays;
        rays
    }

    /// For the camera rays `cam` (closest hits `first`) of the samples `takes` of pixel (x, y):
    /// per sample, what its companions change of its weighted value (`emission_split`): the mean
    /// weighted emission seen by the k rays, less the camera ray's own; returns the rays traced.
    fn split_emission(
        &self,
        sampler: &mut AnySampler,
        (x, y): (usize, usize),
        takes: &[CameraSample],
        (cam, first): (&[Ray; PACKET], &[Option<Hit>; PACKET]),
        out: &mut [Vec3; PACKET],
    ) -> u64 {
        const MOST: usize = PACKET * (EmissionSplits::MOST - 1);
        let k = self.settings.emission_splits.count();
        let mut rays = [Ray::new(Vec3::ZERO, Vec3::Z); MOST];
        let mut weights = [0.0f32; MOST];
        let mut m = 0;
        for &CameraSample { index: i, u, .. } in takes {
            // The companions share the camera ray's lens position, time and seed (dimensions the
            // restarted sampler draws again alike).
            sampler.start(x as u32, y as u32, i);
            for j in 1..k {
                // The sequence's next passes, where no later pass takes them: then the pixel's
                // samples and their companions are one net.
                let extended = self
                    .single_pass
                    .then(|| sampler.get_2d_extension(Dim::Pixel, 0, j as u32))
                    .flatten();
                let u = extended.unwrap_or_else(|| emission_split::companion(u, j));
                let (_, w) = self.pixel_ray((x, y), u, sampler, &mut rays[m]);
                weights[m] = w;
                m += 1;
            }
        }
        let mut hits = [None; MOST];
        self.integrator
            .accel
            .intersect_many(&rays[..m], &mut hits[..m]);
        for (q, &CameraSample { weight: w, .. }) in takes.iter().enumerate() {
            let own = w * self.integrator.seen(&cam[q], first[q].as_ref()).total();
            let mut sum = own;
            for c in q * (k - 1)..(q + 1) * (k - 1) {
                sum += weights[c] * self.integrator.seen(&rays[c], hits[c].as_ref()).total();
            }
            let change = sum / k as f32 - own;
            out[q] = if change.is_finite() {
                change
            } else {
                Vec3::ZERO
            };
        }
        m as u64
    }

    /// Whitted-style adaptive supersampling of one pixel over its corners; returns rays traced.
    fn corners_pixel(&self, sampler: &mut AnySampler, x: usize, y: usize, acc: &mut Acc) -> u64 {
        let s = self.settings;
        // Deepest level L: (2^L + 1)^2 corner samples at most max_spp; at least the level whose
        // grid has min_spp corners.
        let mut max_level = 0u32;
        while max_level < 8 && ((2u64 << max_level) + 1).pow(2) <= s.max_spp.max(4) as u64 {
            max_level += 1;
        }
        let mut min_level = 0u32;
        while min_level < max_level && ((1u64 << min_level) + 1).pow(2) < s.min_spp as u64 {
            min_level += 1;
        }
        let g = 1usize << max_level;
        let mut cache: Vec<Option<Vec4>> = vec![None; (g + 1) * (g + 1)];
        let mut state = CornerState {
            next: 0,
            rays: 0,
            cache: &mut cache,
            g,
        };
        let v = self.quad(sampler, x, y, 0, 0, g, 0, min_level, max_level, &mut state);
        acc.sum = v.as_dvec4();
        acc.w = 1.0;
        acc.half = acc.sum;
        acc.half_w = 1.0;
        acc.n = state.next;
        state.rays
    }

    #[allow(clippy::too_many_arguments)]
    fn quad(
        &self,
        sampler: &mut AnySampler,
        x: usize,
        y: usize,
        ix: usize,
        iy: usize,
        size: usize,
        level: u32,
        min_level: u32,
        max_level: u32,
        st: &mut CornerState,
    ) -> Vec4 {
        let corners = [
            (ix, iy),
            (ix + size, iy),
            (ix, iy + size),
            (ix + size, iy + size),
        ]
        .map(|(cx, cy)| self.corner(sampler, x, y, cx, cy, st));
        let subdivide = level < max_level
            && (level < min_level || contrast(&corners) > self.settings.target_error);
        if subdivide {
            let h = size / 2;
            let mut sum = Vec4::ZERO;
            for (dx, dy) in [(0, 0), (h, 0), (0, h), (h, h)] {
                sum += self.quad(
                    sampler,
                    x,
                    y,
                    ix + dx,
                    iy + dy,
                    h,
                    level + 1,
                    min_level,
                    max_level,
                    st,
                );
            }
            sum / 4.0
        } else {
            (corners[0] + corners[1] + corners[2] + corners[3]) / 4.0
        }
    }

    fn corner(
        &self,
        sampler: &mut AnySampler,
        x: usize,
        y: usize,
        cx: usize,
        cy: usize,
        st: &mut CornerState,
    ) -> Vec4 {
        let k = cy * (st.g + 1) + cx;
        if let Some(v) = st.cache[k] {
            return v;
        }
        sampler.start(x as u32, y as u32, st.next);
        st.next += 1;
        let film = Vec2::new(
            x as f32 + cx as f32 / st.g as f32,
            y as f32 + cy as f32 / st.g as f32,
        );
        let mut ray = Ray::new(Vec3::ZERO, Vec3::Z);
        self.camera_ray(film, sampler, &mut ray);
        let r = self.integrator.li(ray, FirstHit::Untraced, sampler);
        st.rays += r.rays as u64;
        let v = if r.radiance.is_finite() {
            r.radiance
        } else {
            Vec4::ZERO
        };
        st.cache[k] = Some(v);
        v
    }
}

struct CornerState<'c> {
    next: u32,
    rays: u64,
    cache: &'c mut [Option<Vec4>],
    g: usize,
}

/// Largest per-channel contrast (max - min) / (max + min) of the corner samples.
fn contrast(c: &[Vec4; 4]) -> f32 {
    (0..3)
        .map(|k| {
            let lo = c.iter().map(|v| v[k]).fold(f32::INFINITY, f32::min);
            let hi = c.iter().map(|v| v[k]).fold(f32::NEG_INFINITY, f32::max);
            (hi - lo) / (hi + lo + 1e-4)
        })
        .fold(0.0, f32::max)
}

/// Renders and also returns the samples each pixel took (for adaptive sampling and time budgets).
pub fn render_full(
    scene: &Scene,
    accel: &dyn Accel,
    camera: &Camera,
    settings: &RenderSettings,
    progress: &ProgressBar,
) -> RenderOutput {
    let start = Instant::now();
    let (w, h) = (settings.width, settings.height);
    let adaptive = settings.adaptive;
    let (first, pass) = first_round(settings);
    // Decided once: a static scene never draws a time, a pinhole never a lens position (RayCamera),
    // an opaque scene's shadow rays are plain occlusion queries (Integrator).
    let features = Features::of(scene, camera);
    let mut ctx = Ctx {
        integrator: Integrator::new(
            scene,
            accel,
            settings.max_depth,
            &features,
            settings.light_sampler,
        ),
        cam: RayCamera::new(camera, w, h).with_time(features.motion),
        filter: Filter::new(settings.filter, settings.filter_radius),
        settings,
        pass,
        axis: depth_axis(camera),
        splits: None,
        single_pass: adaptive == AdaptiveMode::Off && settings.time_budget.is_none(),
    };
    // Only a scene whose camera may see emitters searches for their edges.
    if settings.emission_splits != EmissionSplits::One
        && features.emitting_surfaces
        && adaptive != AdaptiveMode::Corners
    {
        // How many pixels past its own a pixel's filter takes samples from.
        let reach = (ctx.filter.radius - 0.5).max(0.0).ceil() as usize;
        let found = SplitPixels::find(&ctx.integrator, &ctx.cam, (w, h), reach);
        ctx.splits = Some(found);
    }
    // Rounds that sample only some pixels balance better over smaller tiles.
    let edge = if adaptive == AdaptiveMode::Variance || settings.time_budget.is_some() {
        TILE / 2
    } else {
        TILE
    };
    let mut tiles = make_tiles(w, h, edge, ctx.takes_features());
    progress.set_length(0);
    let rays = AtomicU64::new(0);
    // Per-pixel sample count wanted after the current round (row-major).
    let mut target = vec![first; w * h];
    let mut rounds = 0u32;
    let render_start = Instant::now();
    loop {
        rounds += 1;
        progress.inc_length(tiles.len() as u64);
        tiles.par_iter_mut().for_each(|tile| {
            rays.fetch_add(ctx.sample_tile(tile, &target), Ordering::Relaxed);
            progress.inc(1);
        });
        if adaptive == AdaptiveMode::Corners {
            break;
        }
        let budget = settings.time_budget.map(|b| Budget {
            total: b,
            start,
            render_start,
        });
        match plan_next_round(&tiles, settings, budget) {
            Some(next) => target = next,
            None => break,
        }
    }
    progress.finish_and_clear();
    let mut out = collect(&tiles, settings, rays.into_inner(), rounds);
    out.stats.seconds = start.elapsed().as_secs_f64();
    out.stats.split_pixels = ctx.splits.as_ref().map_or(0, SplitPixels::count);
    out
}

/// Samples per pixel of the first round, and the samples per stratified pass.
fn first_round(settings: &RenderSettings) -> (u32, u32) {
    let first = match (settings.adaptive, settings.time_budget) {
        (AdaptiveMode::Variance, _) => settings.min_spp.max(1),
        (AdaptiveMode::Off, Some(_)) => 1,
        _ => settings.spp.max(1),
    };
    let pass = match (settings.adaptive, settings.time_budget) {
        (AdaptiveMode::Off, Some(_)) => 16,
        _ => first,
    };
    (first, pass)
}

/// The image cut into tiles of `edge` pixels, with feature sums when `features`.
fn make_tiles(w: usize, h: usize, edge: usize, features: bool) -> Vec<Tile> {
    (0..h.div_ceil(edge))
        .flat_map(|ty| (0..w.div_ceil(edge)).map(move |tx| (tx * edge, ty * edge)))
        .map(|(x0, y0)| {
            let (x1, y1) = ((x0 + edge).min(w), (y0 + edge).min(h));
            let n = (x1 - x0) * (y1 - y0);
            Tile {
                x0,
                y0,
                x1,
                px: vec![Acc::default(); n],
                features: vec![FeatureAcc::default(); if features { n } else { 0 }],
            }
        })
        .collect()
}

/// The camera's position and viewing axis at time 0, for depth.
fn depth_axis(camera: &Camera) -> DepthAxis {
    DepthAxis {
        eye: camera.to_world.transform_point3(glam::Vec3::ZERO),
        forward: camera
            .to_world
            .transform_vector3(glam::Vec3::NEG_Z)
            .normalize_or_zero(),
    }
}

/// A time budget: its length, when the render began and when its sampling began.
#[derive(Clone, Copy)]
struct Budget {
    total: Duration,
    start: Instant,
    render_start: Instant,
}

/// The samples each pixel should have after the next round, or None when the render is done.
fn plan_next_round(
    tiles: &[Tile],
    settings: &RenderSettings,
    budget: Option<Budget>,
) -> Option<Vec<u32>> {
    let (w, h) = (settings.width, settings.height);
    let counts = per_pixel(tiles, w, h, |a| a.n);
    let mut next: Vec<u32> = match settings.adaptive {
        AdaptiveMode::Variance => {
            // Rays per sample so far (at least 1): the cost of one more sample there.
            let cost = per_pixel(tiles, w, h, |a| {
                (a.rays as f64 / a.n.max(1) as f64).max(1.0)
            });
            plan_variance_round(&counts, &error_map(tiles, w, h), &cost, settings)
        }
        _ => match budget {
            Some(_) => counts.iter().map(|&n| 2 * n).collect(),
            None => counts.clone(),
        },
    };
    if let Some(b) = budget {
        fit_to_budget(&mut next, &counts, b);
    }
    let needed: u64 = next.iter().zip(&counts).map(|(a, b)| (a - b) as u64).sum();
    (needed > 0).then_some(next)
}

/// Scales every pixel's increment in `next` down to what the time left buys, at the speed so far.
fn fit_to_budget(next: &mut [u32], counts: &[u32], b: Budget) {
    let needed: u64 = next.iter().zip(counts).map(|(a, b)| (a - b) as u64).sum();
    let spent = b.render_start.elapsed().as_secs_f64();
    let done: u64 = counts.iter().map(|&n| n as u64).sum();
    let per_sample = spent / done.max(1) as f64;
    let left = b.total.as_secs_f64() - b.start.elapsed().as_secs_f64();
    let affordable = (left.max(0.0) / per_sample.max(1e-12) * 0.97) as u64;
    if needed > affordable {
        let f = affordable as f64 / needed as f64;
        for (t, &n) in next.iter_mut().zip(counts) {
            *t = n + ((*t - n) as f64 * f) as u32;
        }
    }
}

/// The render's output from its tiles (the caller sets the time).
fn collect(tiles: &[Tile], settings: &RenderSettings, rays: u64, rounds: u32) -> RenderOutput {
    let (w, h) = (settings.width, settings.height);
    let image = Image {
        width: w,
        height: h,
        pixels: per_pixel(tiles, w, h, |a| a.value().as_vec4()),
    };
    let spp = per_pixel(tiles, w, h, |a| a.n);
    let sums = per_pixel(tiles, w, h, |a| PixelSum {
        sum: a.sum,
        weight: a.w,
    });
    let min_spp = spp.iter().copied().min().unwrap_or(0);
    let features = tiles.first().filter(|t| !t.features.is_empty()).map(|_| {
        let acc = per_pixel_features(tiles, w, h);
        feature_film::images(w, h, &acc, min_spp)
    });
    let stats = RenderStats {
        rays,
        seconds: 0.0,
        samples: spp.iter().map(|&n| n as u64).sum(),
        min_spp,
        max_spp: spp.iter().copied().max().unwrap_or(0),
        rounds,
        split_pixels: 0,
    };
    RenderOutput {
        image,
        stats,
        spp,
        sums,
        features,
    }
}

/// Per-pixel squared relative error estimate, averaged over the pixel's 3x3 neighbourhood (so a
/// pixel whose two half buffers agree by chance does not stop alone).
fn error_map(tiles: &[Tile], w: usize, h: usize) -> Vec<f64> {
    let e = per_pixel(tiles, w, h, |a| a.rel_err2() / 3.0);
    (0..w * h)
        .into_par_iter()
        .map(|i| {
            let (x, y) = ((i % w) as isize, (i / w) as isize);
            let (mut s, mut n) = (0.0, 0);
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (u, v) = (x + dx, y + dy);
                    if u >= 0 && v >= 0 && (u as usize) < w && (v as usize) < h {
                        s += e[v as usize * w + u as usize];
                        n += 1;
                    }
                }
            }
            s / n as f64
        })
        .collect()
}

/// One value per pixel of the image (row-major), read from the tiles' accumulators.
fn per_pixel<T: Copy + Default>(
    tiles: &[Tile],
    w: usize,
    h: usize,
    f: impl Fn(&Acc) -> T,
) -> Vec<T> {
    let mut out = vec![T::default(); w * h];
    for t in tiles {
        let tw = t.x1 - t.x0;
        for (k, a) in t.px.iter().enumerate() {
            out[(t.y0 + k / tw) * w + t.x0 + k % tw] = f(a);
        }
    }
    out
}

/// The tiles' feature sums, row-major.
fn per_pixel_features(tiles: &[Tile], w: usize, h: usize) -> Vec<FeatureAcc> {
    let mut out = vec![FeatureAcc::default(); w * h];
    for t in tiles {
        let tw = t.x1 - t.x0;
        for (k, a) in t.features.iter().enumerate() {
            out[(t.y0 + k / tw) * w + t.x0 + k % tw] = *a;
        }
    }
    out
}

/// The variance-adaptive plan for the next round: the samples each pixel should have, given the
/// samples `n` it has, its squared relative error estimate `e` and its cost in rays per sample.
///
/// The goal is the image's mean squared relative error at `target_error^2` for the least time. With
/// per-sample variance `v = e n` and cost `c`, that is Neyman's allocation `n ∝ sqrt(v / c)`
/// (minimise `sum c n` subject to `mean(v / n) = t^2`). Giving every pixel the samples that bring it
/// to the target on its own costs as much as uniform sampling does whenever costs are equal, and
/// more when the noisy pixels are also the expensive ones (an object in front of a cheap
/// background), so it is not used. A pixel stops once its own error is under the target or it
/// has `max_spp`; none stops below `min_spp`; each round at most doubles a pixel's samples, since
/// early estimates are rough. All pixels stay put once the image's estimate meets the target.
fn plan_variance_round(n: &[u32], e: &[f64], cost: &[f64], s: &RenderSettings) -> Vec<u32> {
    let (min_spp, max_spp) = (s.min_spp.max(1), s.max_spp.max(s.min_spp.max(1)));
    let t2 = (s.target_error as f64).powi(2);
    let pixels = n.len().max(1) as f64;
    let image_err = e.iter().sum::<f64>() / pixels;
    let scale = n
        .iter()
        .zip(e)
        .zip(cost)
        .map(|((&n, &e), &c)| (e * n as f64 * c).sqrt())
        .sum::<f64>()
        / (pixels * t2);
    n.iter()
        .zip(e)
        .zip(cost)
        .map(|((&n, &e), &c)| {
            if n < min_spp {
                min_spp
            } else if image_err <= t2 || n >= max_spp || e <= t2 {
                n
            } else {
                let want = ((e * n as f64 / c).sqrt() * scale).ceil();
                if want <= n as f64 {
                    n
                } else {
                    // At least +25% (few rounds), at most doubling (little overshoot).
                    (want as u32).clamp(n + n.div_ceil(4), 2 * n).min(max_spp)
                }
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(target_error: f32) -> RenderSettings {
        RenderSettings {
            target_error,
            min_spp: 16,
            max_spp: 1 << 20,
            ..Default::default()
        }
    }

    #[test]
    fn variance_rounds_follow_neyman_allocation() {
        // Equal cost, per-sample variances v = e n of 1 : 4 : 16. Neyman wants samples
        // n_i = sqrt(v_i) * sum sqrt(v) / (P t^2) = [k, 2k, 4k] with k = 7 v_0 / (3 t^2); equal
        // per-pixel error would want 1 : 4 : 16. Choose t for k = 800.
        let n = [1000; 3];
        let e = [1e-6, 4e-6, 16e-6];
        let t = (7.0 * 1e-3 / (3.0 * 800.0f64)).sqrt() as f32;
        let plan = plan_variance_round(&n, &e, &[1.0; 3], &settings(t));
        assert_eq!(plan[0], 1000, "wants 800, has more: {plan:?}");
        assert!((1599..=1602).contains(&plan[1]), "wants 1600: {plan:?}");
        assert_eq!(plan[2], 2000, "wants 3200, at most doubles: {plan:?}");
        // Equal variance, four times the cost: half the samples (n ∝ 1 / sqrt(c)), wanted 2057
        // and 1029, so the first doubles and the second takes the smallest step.
        let plan = plan_variance_round(&[1000; 2], &[4e-6; 2], &[1.0, 4.0], &settings(t));
        assert_eq!(plan, [2000, 1250]);
    }

    #[test]
    fn variance_rounds_stop_at_the_target_and_respect_the_bounds() {
        let s = settings(0.01);
        // The image's error (mean 5e-5 < 1e-4) meets the target: nobody gets more.
        let plan = plan_variance_round(&[32, 32], &[1e-6, 9.9e-5], &[1.0; 2], &s);
        assert_eq!(plan, [32, 32]);
        // Below the minimum always rises to it; a pixel under the target on its own stops; one
        // at the maximum stops.
        let s = RenderSettings { max_spp: 64, ..s };
        let plan = plan_variance_round(&[8, 32, 64, 32], &[1.0, 1e-5, 1.0, 1.0], &[1.0; 4], &s);
        assert_eq!(plan[0], 16);
        assert_eq!(plan[1], 32);
        assert_eq!(plan[2], 64);
        assert!(plan[3] > 32 && plan[3] <= 64, "{plan:?}");
    }
}
