//! Benchmarks that glint runs on itself: ray throughput per backend (`rays`).
//! Each measures on identical inputs and reports ratios from one run, since machines are noisy.

pub mod rays;
