//! Criterion benches of the accelerators on generated meshes: build time and closest-hit throughput,
//! so that regressions show. `glint bench rays` (the acceleration issue) reports the full comparison.

use std::sync::Arc;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use glint::accel::{self, compare, Backend};
use glint::scene::generate;

fn bench_accel(c: &mut Criterion) {
    let scene = Arc::new(generate::single_mesh_scene(generate::icosphere(6, 0.05)));
    let rays = compare::random_rays(&scene, 100_000, 7);

    let mut build = c.benchmark_group("build icosphere-6 (82k triangles)");
    build.sample_size(10);
    for backend in Backend::all_available() {
        build.bench_function(BenchmarkId::from_parameter(backend), |b| {
            b.iter(|| accel::build(scene.clone(), backend).unwrap())
        });
    }
    build.finish();

    let mut trace = c.benchmark_group("closest hit, 100k random rays");
    trace.sample_size(10);
    trace.throughput(Throughput::Elements(rays.len() as u64));
    for backend in Backend::all_available() {
        let a = accel::build(scene.clone(), backend).unwrap();
        trace.bench_function(BenchmarkId::from_parameter(backend), |b| {
            b.iter(|| rays.iter().filter(|r| a.intersect(r).is_some()).count())
        });
    }
    trace.finish();
}

criterion_group!(benches, bench_accel);
criterion_main!(benches);
