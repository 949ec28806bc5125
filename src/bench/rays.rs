//! `glint bench rays`: the same primary, shadow and diffuse rays traced by every backend, with build
//! time and memory, throughput per thread count and agreement with Embree.

use std::fmt::{self, Write as _};
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::error::{BenchError, Result};
use super::input::Input;
use crate::accel::{self, compare, Accel, Backend};
use crate::geometry::mix64;
use crate::geometry::Frame;
use crate::geometry::Ray;
use crate::render::light::{LightContext, LightSampler, LightSet};
use crate::render::offset::offset_ray_origin;
use crate::render::RayCamera;
use crate::sample::warp::cosine_hemisphere;
use crate::scene::{defaults, Scene};

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum RayKind {
    /// Camera rays through pixel centres (coherent).
    Primary,
    /// From the first-hit points to a sampled light (any-hit queries).
    Shadow,
    /// Cosine-distributed bounces from the first-hit points (incoherent).
    Diffuse,
    /// The primary rays eight neighbours at a time (`Accel::intersect_many`: Embree's 8-wide
    /// packets, as renders trace each pixel's camera rays; one by one elsewhere). Its agreement
    /// column is the single rays' (the Embree tests hold packets to the single answers bit for bit).
    Packets,
    /// The shadow rays eight neighbours at a time (`Accel::occluded_many`), as a bounce's shadow
    /// rays would be if the paths of a pixel's samples went on together.
    ShadowPackets,
    /// The diffuse rays eight neighbours at a time, likewise.
    DiffusePackets,
}

impl RayKind {
    /// The kinds traced one ray at a time.
    pub const SINGLE: [RayKind; 3] = [RayKind::Primary, RayKind::Shadow, RayKind::Diffuse];
    pub const ALL: [RayKind; 6] = [
        RayKind::Primary,
        RayKind::Shadow,
        RayKind::Diffuse,
        RayKind::Packets,
        RayKind::ShadowPackets,
        RayKind::DiffusePackets,
    ];

    /// Whether the rays are any-hit queries.
    pub fn any_hit(self) -> bool {
        matches!(self, RayKind::Shadow | RayKind::ShadowPackets)
    }
}

impl fmt::Display for RayKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            RayKind::Primary => "primary",
            RayKind::Shadow => "shadow",
            RayKind::Diffuse => "diffuse",
            RayKind::Packets => "packets",
            RayKind::ShadowPackets => "shadow-packets",
            RayKind::DiffusePackets => "diffuse-packets",
        })
    }
}

#[derive(Clone, Debug)]
pub struct RaysConfig {
    pub backends: Vec<Backend>,
    pub kinds: Vec<RayKind>,
    pub threads: Vec<usize>,
    pub width: usize,
    pub height: usize,
    pub repeat: usize,
    /// Pose the scene's animation at `frame_time` with this shutter (seconds), so that moving
    /// instances are measured with motion; rays then carry random times.
    pub shutter: Option<[f32; 2]>,
    pub frame_time: f32,
}

#[derive(Clone, Debug)]
pub struct KindResult {
    pub kind: RayKind,
    pub rays: usize,
    /// (threads, Mrays/s), best of the repetitions.
    pub mrays: Vec<(usize, f64)>,
    /// Fraction of rays answered as Embree answers them (None when Embree is not measured).
    pub agreement: Option<f64>,
}

#[derive(Clone, Debug)]
pub struct BackendResult {
    pub backend: Backend,
    pub build_seconds: f64,
    pub memory_bytes: usize,
    pub kinds: Vec<KindResult>,
}

#[derive(Clone, Debug)]
pub struct Report {
    pub input: String,
    pub triangles: usize,
    pub results: Vec<BackendResult>,
}

/// The three ray sets of a scene, in a fixed order (generation is not timed).
pub struct RaySets {
    pub primary: Vec<Ray>,
    pub shadow: Vec<Ray>,
    pub diffuse: Vec<Ray>,
}

impl RaySets {
    pub fn get(&self, kind: RayKind) -> &[Ray] {
        match kind {
            RayKind::Primary | RayKind::Packets => &self.primary,
            RayKind::Shadow | RayKind::ShadowPackets => &self.shadow,
            RayKind::Diffuse | RayKind::DiffusePackets => &self.diffuse,
        }
    }
}

fn unit(h: u64) -> f32 {
    (h >> 40) as f32 / (1u64 << 24) as f32
}

/// Camera rays through pixel centres, then from each first hit (found with `accel`) a shadow ray to a
/// sampled light and a cosine-distributed diffuse ray.
pub fn generate_rays(scene: &Scene, accel: &dyn Accel, width: usize, height: usize) -> RaySets {
    let camera = defaults::default_camera(scene, width as f32 / height as f32);
    let mut lit = scene.clone();
    defaults::light_if_unlit(&mut lit, &camera.to_world);
    // By power, so the shadow rays stay those earlier runs traced.
    let lights = LightSet::with_sampler(&lit, LightSampler::Power);
    let cam = RayCamera::new(&camera, width, height);
    // Times spread over the shutter when something moves (0 otherwise, as renders do).
    let timed = scene.has_motion();
    let primary: Vec<Ray> = (0..width * height)
        .map(|i| {
            let time = if timed {
                unit(mix64(i as u64 ^ 0x7F4A_7C15_9E37_79B9))
            } else {
                0.0
            };
            cam.ray(Vec2::new(
                (i % width) as f32 + 0.5,
                (i / width) as f32 + 0.5,
            ))
            .with_time(time)
        })
        .collect();
    let secondary: Vec<(Option<Ray>, Ray)> = primary
        .par_iter()
        .enumerate()
        .filter_map(|(i, r)| {
            let h = accel.intersect(r)?;
            let (p, mut n) = scene.hit_geometry(&h, r);
            if n == Vec3::ZERO {
                return None;
            }
            if n.dot(r.d) > 0.0 {
                n = -n;
            }
            let o = offset_ray_origin(p, n);
            let u = |k: u64| unit(mix64(i as u64 * 4 + k));
            let shadow = lights
                .sample(&lit, &LightContext { p, n }, u(0), Vec2::new(u(1), u(2)))
                .map(|ls| Ray::segment(o, ls.wi, ls.dist * (1.0 - 1e-3)).with_time(r.time));
            let d = Frame::from_normal(n).to_world(cosine_hemisphere(Vec2::new(u(3), u(1))));
            Some((shadow, Ray::new(o, d).with_time(r.time)))
        })
        .collect();
    RaySets {
        shadow: secondary.iter().filter_map(|s| s.0).collect(),
        diffuse: secondary.iter().map(|s| s.1).collect(),
        primary,
    }
}

/// Traces every ray (closest hit, or any hit for shadow rays) and returns a count so the work is kept.
fn trace(accel: &dyn Accel, rays: &[Ray], kind: RayKind) -> usize {
    rays.par_chunks(1024)
        .map(|c| match kind {
            RayKind::Shadow => c.iter().filter(|r| accel.occluded(r)).count(),
            RayKind::Primary | RayKind::Diffuse => {
                c.iter().filter(|r| accel.intersect(r).is_some()).count()
            }
            RayKind::Packets | RayKind::DiffusePackets => {
                in_packets(c, |p, out| accel.intersect_many(p, out), Option::is_some)
            }
            RayKind::ShadowPackets => in_packets(c, |p, out| accel.occluded_many(p, out), |&o| o),
        })
        .sum()
}

/// Traces `rays` eight at a time with `query` and counts the answers `counts` keeps.
fn in_packets<T: Copy + Default>(
    rays: &[Ray],
    query: impl Fn(&[Ray], &mut [T]),
    counts: impl Fn(&T) -> bool,
) -> usize {
    let mut out = [T::default(); 8];
    rays.chunks(8)
        .map(|p| {
            let out = &mut out[..p.len()];
            query(p, out);
            out.iter().filter(|a| counts(a)).count()
        })
        .sum()
}

pub fn run(input: &Input, config: &RaysConfig) -> Result<Report> {
    if config.threads.contains(&0) {
        return Err(BenchError::ZeroThreads);
    }
    crate::render::job::check_size(config.width, config.height)?;
    let mut scene = input.load()?;
    if let Some(shutter) = config.shutter {
        crate::scene::animation::pose(&mut scene, config.frame_time, shutter);
    }
    let scene = Arc::new(scene);
    if scene.triangle_count() == 0 && scene.csg.is_empty() {
        return Err(BenchError::NothingToTrace(input.to_string()));
    }
    // The same rays for every backend, generated with the Rust BVH (always available).
    let reference = accel::build(scene.clone(), Backend::Bvh)?;
    let sets = generate_rays(&scene, reference.as_ref(), config.width, config.height);
    drop(reference);

    // Every backend is built, then timed in turn within each repetition (not all of one backend's
    // runs, then the next's): these machines' speed drifts over seconds, and a drift between two
    // backends' blocks of runs was read as a difference between the backends.
    let mut builds: Vec<(f64, Option<Box<dyn Accel>>)> = config
        .backends
        .iter()
        .map(|_| (f64::INFINITY, None))
        .collect();
    for _ in 0..config.repeat {
        for (&backend, (seconds, built)) in config.backends.iter().zip(&mut builds) {
            let t = Instant::now();
            let a = accel::build(scene.clone(), backend)?;
            *seconds = seconds.min(t.elapsed().as_secs_f64());
            *built = Some(a);
        }
    }
    let accels: Vec<(f64, Box<dyn Accel>)> = builds
        .into_iter()
        .map(|(s, a)| (s, a.expect("repeat >= 1")))
        .collect();
    // Agreement is with the Embree measured here, when it is.
    let embree = config
        .backends
        .iter()
        .position(|&b| b == Backend::Embree)
        .map(|i| accels[i].1.as_ref());
    let mut kinds: Vec<Vec<KindResult>> = config.backends.iter().map(|_| Vec::new()).collect();
    for &kind in &config.kinds {
        let rays = sets.get(kind);
        let mut mrays: Vec<Vec<(usize, f64)>> = accels.iter().map(|_| Vec::new()).collect();
        for &threads in &config.threads {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(BenchError::ThreadPool)?;
            let mut best = vec![f64::INFINITY; accels.len()];
            for _ in 0..config.repeat {
                for ((_, accel), best) in accels.iter().zip(&mut best) {
                    let t = Instant::now();
                    std::hint::black_box(pool.install(|| trace(accel.as_ref(), rays, kind)));
                    *best = best.min(t.elapsed().as_secs_f64());
                }
            }
            for (m, best) in mrays.iter_mut().zip(best) {
                m.push((threads, rays.len() as f64 / best.max(1e-9) / 1e6));
            }
        }
        for ((k, (_, accel)), mrays) in kinds.iter_mut().zip(&accels).zip(mrays) {
            k.push(KindResult {
                kind,
                rays: rays.len(),
                mrays,
                agreement: embree
                    .map(|e| agreement(&scene, accel.as_ref(), e, rays, kind.any_hit())),
            });
        }
    }
    let results = config
        .backends
        .iter()
        .zip(accels)
        .zip(kinds)
        .map(
            |((&backend, (build_seconds, accel)), kinds)| BackendResult {
                backend,
                build_seconds,
                memory_bytes: accel.memory_bytes(),
                kinds,
            },
        )
        .collect();
    Ok(Report {
        input: input.to_string(),
        triangles: scene.triangle_count(),
        results,
    })
}

/// Fraction of rays for which `a` answers as `reference` does (closest hit: same primitive and
/// distance, or a tie; any hit: the same yes or no).
fn agreement(
    scene: &Scene,
    a: &dyn Accel,
    reference: &dyn Accel,
    rays: &[Ray],
    any_hit: bool,
) -> f64 {
    if rays.is_empty() {
        return 1.0;
    }
    if any_hit {
        let same = rays
            .par_iter()
            .filter(|r| a.occluded(r) == reference.occluded(r))
            .count();
        same as f64 / rays.len() as f64
    } else {
        compare::compare(scene, a, reference, rays).fraction_same()
    }
}

impl Report {
    /// A plain-text table: one row per backend and ray kind.
    pub fn table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "{}: {} triangles", self.input, self.triangles);
        let threads: Vec<usize> = self
            .results
            .first()
            .and_then(|r| r.kinds.first())
            .map(|k| k.mrays.iter().map(|m| m.0).collect())
            .unwrap_or_default();
        let _ = write!(
            s,
            "{:<11} {:<15} {:>9} {:>9} {:>9}",
            "backend", "kind", "rays", "build ms", "memory MB"
        );
        for t in &threads {
            let _ = write!(s, " {:>10}", format!("Mrays/s {t}t"));
        }
        let _ = writeln!(s, " {:>10}", "vs embree");
        for r in &self.results {
            for k in &r.kinds {
                let _ = write!(
                    s,
                    "{:<11} {:<15} {:>9} {:>9.1} {:>9.1}",
                    r.backend.to_string(),
                    k.kind.to_string(),
                    k.rays,
                    r.build_seconds * 1e3,
                    r.memory_bytes as f64 / (1 << 20) as f64
                );
                for (_, m) in &k.mrays {
                    let _ = write!(s, " {m:>10.2}");
                }
                match k.agreement {
                    Some(a) => {
                        let _ = writeln!(s, " {:>9.4}%", a * 100.0);
                    }
                    None => {
                        let _ = writeln!(s, " {:>10}", "-");
                    }
                }
            }
        }
        s
    }

    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "input": self.input,
            "triangles": self.triangles,
            "backends": self.results.iter().map(|r| serde_json::json!({
                "backend": r.backend.to_string(),
                "build_seconds": r.build_seconds,
                "memory_bytes": r.memory_bytes,
                "kinds": r.kinds.iter().map(|k| serde_json::json!({
                    "kind": k.kind.to_string(),
                    "rays": k.rays,
                    "mrays_per_second": k.mrays.iter().map(|(t, m)| serde_json::json!({"threads": t, "mrays": m})).collect::<Vec<_>>(),
                    "agreement_with_embree": k.agreement,
                })).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
        })
    }

    pub fn write_json(&self, path: &Path) -> Result<()> {
        let text = serde_json::to_string_pretty(&self.to_json())?;
        let tmp = path.with_extension("json.tmp");
        std::fs::write(&tmp, text).map_err(BenchError::write(&tmp))?;
        std::fs::rename(&tmp, path).map_err(|source| BenchError::Rename {
            path: path.to_path_buf(),
            source,
        })
    }
}
