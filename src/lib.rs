//! glint: a CPU ray tracer for glTF 2.0 and OBJ assets, with Embree 4 and a pure-Rust BVH side by side.
//! Data flows one way: file -> `scene` -> `accel` -> `render` -> `film` -> file.

pub mod accel;
pub mod bench;
pub mod cli;
pub mod csg;
pub mod film;
pub mod geometry;
pub mod render;
pub mod sample;
pub mod scene;
pub mod turntable;

pub use geometry::{Aabb, Hit, Ray};
pub use scene::Scene;
