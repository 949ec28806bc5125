//! Benchmarks that glint runs on itself: ray throughput per backend (`rays`), error against time per
//! sampler and adaptive mode (`convergence`), tests saved by cheap pretests (`fastfail`), time saved
//! by skipping unused features (`features`).
//! Each measures on identical inputs and reports ratios from one run, since machines are noisy.

pub mod convergence;
pub mod denoise;
pub mod error;
pub mod fastfail;
pub mod features;
pub mod input;
pub mod rays;
