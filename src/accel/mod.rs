//! Ray queries over a Scene's triangles: one `Accel` trait (closest hit, any hit) and its backends.
//! `embree` wraps Intel Embree 4; the Rust backends (`bvh`, `grid`, `obvhs`) are each a triangle
//! structure in the one `layered` composition. All return the same hits for the same rays
//! (`conformance` holds the tests every backend must pass).

pub mod bvh;
pub mod compare;
#[cfg(test)]
mod conformance;
#[cfg(feature = "embree")]
pub mod embree;
pub mod flat;
pub mod grid;
pub mod instances;
pub mod layered;
pub mod list;
pub mod objects;
#[cfg(feature = "obvhs")]
pub mod obvhs;
#[cfg(test)]
mod testing;
mod tracer;

use std::fmt;
use std::str::FromStr;
use std::sync::Arc;

use crate::geometry::{Hit, Ray};
use crate::scene::Scene;
pub use tracer::Tracer;

/// An acceleration structure over one scene.
///
/// `intersect` returns the closest hit with `t` in `(ray.t_min, ray.t_max)`; `occluded` answers whether
/// any hit exists there (for shadow rays, with early exit). Hits on materials that need an alpha test
/// count only where `Scene::alpha_passes` says so.
pub trait Accel: Send + Sync {
    fn name(&self) -> &'static str;
    fn intersect(&self, ray: &Ray) -> Option<Hit>;
    fn occluded(&self, ray: &Ray) -> bool;
    /// The closest hits of several rays, `out[i]` for `rays[i]`, as `intersect` gives them: for
    /// backends that answer coherent rays faster together (Embree's 8-wide packets).
    fn intersect_many(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        for (ray, slot) in rays.iter().zip(out) {
            *slot = self.intersect(ray);
        }
    }
    /// The any-hit answers of several rays, `out[i]` for `rays[i]`, as `occluded` gives them (Embree
    /// answers eight at a time; renders do not call it: `glint bench rays` measures whether a
    /// bounce's rays traced together would pay).
    fn occluded_many(&self, rays: &[Ray], out: &mut [bool]) {
        for (ray, slot) in rays.iter().zip(out) {
            *slot = self.occluded(ray);
        }
    }
    /// Bytes held by the structure (for benchmarks).
    fn memory_bytes(&self) -> usize {
        0
    }
    /// This backend as Embree, whose queries `Tracer` calls directly.
    #[cfg(feature = "embree")]
    fn as_embree(&self) -> Option<&embree::EmbreeAccel> {
        None
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Backend {
    Embree,
    /// Embree without its robust mode: faster, but not watertight at shared edges and vertices
    /// (for `glint bench rays`; renders should use `embree`).
    EmbreeFast,
    Bvh,
    Grid,
    /// The `obvhs` crate's compressed wide BVH8 (a peer for benchmarks; `obvhs` feature).
    Obvhs,
}

impl Backend {
    /// Embree when this build has it, the Rust BVH otherwise.
    pub fn default_available() -> Self {
        if cfg!(feature = "embree") {
            Backend::Embree
        } else {
            Backend::Bvh
        }
    }

    pub fn all_available() -> Vec<Backend> {
        let mut v = vec![Backend::Bvh];
        if cfg!(feature = "embree") {
            v.push(Backend::Embree);
        }
        v.push(Backend::Grid);
        if cfg!(feature = "obvhs") {
            v.push(Backend::Obvhs);
        }
        v
    }
}

impl fmt::Display for Backend {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Backend::Embree => "embree",
            Backend::EmbreeFast => "embree-fast",
            Backend::Bvh => "bvh",
            Backend::Grid => "grid",
            Backend::Obvhs => "obvhs",
        })
    }
}

impl FromStr for Backend {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "embree" => Ok(Backend::Embree),
            "embree-fast" => Ok(Backend::EmbreeFast),
            "bvh" => Ok(Backend::Bvh),
            "grid" => Ok(Backend::Grid),
            "obvhs" => Ok(Backend::Obvhs),
            _ => Err(format!(
                "unknown backend '{s}' (expected embree, embree-fast, bvh, grid or obvhs)"
            )),
        }
    }
}

#[derive(Debug, thiserror::Error)]
pub enum AccelError {
    #[error("this glint was built without Embree (rebuild with the `embree` feature, or use --backend bvh)")]
    EmbreeUnavailable,
    #[error("this glint was built without obvhs (rebuild with `--features obvhs`, or use --backend bvh)")]
    ObvhsUnavailable,
    #[error("embree: {0}")]
    Embree(String),
}

/// Builds the chosen backend over the scene's instances and CSG objects.
pub fn build(scene: Arc<Scene>, backend: Backend) -> Result<Box<dyn Accel>, AccelError> {
    match backend {
        Backend::Bvh => Ok(Box::new(bvh::BvhAccel::build(scene))),
        Backend::Grid => Ok(Box::new(grid::GridAccel::build(scene))),
        #[cfg(feature = "embree")]
        Backend::Embree => Ok(Box::new(embree::EmbreeAccel::build(scene)?)),
        #[cfg(feature = "embree")]
        Backend::EmbreeFast => Ok(Box::new(embree::EmbreeAccel::build_with(
            scene,
            embree::Robustness::Fast,
        )?)),
        #[cfg(not(feature = "embree"))]
        Backend::Embree | Backend::EmbreeFast => Err(AccelError::EmbreeUnavailable),
        #[cfg(feature = "obvhs")]
        Backend::Obvhs => Ok(Box::new(obvhs::ObvhsAccel::build(scene))),
        #[cfg(not(feature = "obvhs"))]
        Backend::Obvhs => Err(AccelError::ObvhsUnavailable),
    }
}
