//! Closest-hit throughput of the uniform grid against the BVH (and Embree) on identical rays, with the
//! grid's resolution, entries and memory for several `lambda`s. Not a test: timings, run by hand:
//!
//!     GRID_LAMBDAS=2,3,4 cargo run --release --example grid_bench -- [THREADS] [RAYS] [MODEL...]
//!
//! Scenes: an 82k-triangle icosphere, the Stanford bunny when the shared assets are present, the bunny
//! scaled small inside a 12-triangle room, and any model files given.

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use glam::{Mat4, Vec3};
use glint::accel::grid::{GridAccel, DEFAULT_LAMBDA};
use glint::accel::{self, compare, Accel, Backend};
use glint::scene::{generate, Instance, Scene};
use glint::Ray;
use rayon::prelude::*;

/// The model scaled to about 1% of a room 100 units wide, standing near its centre.
fn model_in_room(model: &Scene) -> Scene {
    let mut s = model.clone();
    let b = s.bounds();
    let scale = 1.0 / b.extent().max_element();
    let m = Mat4::from_scale(Vec3::splat(scale)) * Mat4::from_translation(-b.center());
    for inst in &mut s.instances {
        *inst = Instance::new(inst.mesh, m * inst.to_world);
    }
    let mut room = generate::box_mesh(Vec3::splat(-50.0), Vec3::splat(50.0));
    room.material = 0;
    s.meshes.push(room);
    s.instances
        .push(Instance::new(s.meshes.len() as u32 - 1, Mat4::IDENTITY));
    s
}

/// Camera-like rays in the room: from random points 2 to 40 units from the model, half aimed at the
/// model's bounds, half in random directions.
fn room_rays(n: usize, seed: u64) -> Vec<Ray> {
    (0..n)
        .into_par_iter()
        .map(|i| {
            let h = |k: u64| {
                (glint::geometry::mix64(seed ^ glint::geometry::mix64(i as u64 * 8 + k)) >> 40)
                    as f32
                    / (1u64 << 24) as f32
            };
            let dir = |a: f32, b: f32| {
                let z = 1.0 - 2.0 * a;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = std::f32::consts::TAU * b;
                Vec3::new(r * phi.cos(), r * phi.sin(), z)
            };
            let o = dir(h(0), h(1)) * (2.0 + 38.0 * h(2));
            if i % 2 == 0 {
                let target = (Vec3::new(h(3), h(4), h(5)) - 0.5) * 0.8;
                Ray::new(o, (target - o).normalize())
            } else {
                Ray::new(o, dir(h(3), h(4)))
            }
        })
        .collect()
}

fn mrays(a: &dyn Accel, rays: &[Ray], repeat: usize) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..repeat {
        let t = Instant::now();
        let hits = rays
            .par_chunks(1024)
            .map(|c| c.iter().filter(|r| a.intersect(r).is_some()).count())
            .sum::<usize>();
        std::hint::black_box(hits);
        best = best.min(t.elapsed().as_secs_f64());
        if best > 5.0 {
            break;
        }
    }
    rays.len() as f64 / best / 1e6
}

fn run(name: &str, scene: Scene, rays: Option<Vec<Ray>>, n: usize) {
    let scene = Arc::new(scene);
    let rays = rays.unwrap_or_else(|| compare::random_rays(&scene, n, 11));
    println!(
        "== {name}: {} triangles, {} rays",
        scene.triangle_count(),
        rays.len()
    );
    let mut bvh_rate = 0.0;
    for backend in Backend::all_available() {
        if backend == Backend::Grid {
            continue;
        }
        let t = Instant::now();
        let a = accel::build(scene.clone(), backend).unwrap();
        let build = t.elapsed().as_secs_f64();
        let rate = mrays(a.as_ref(), &rays, 3);
        if backend == Backend::Bvh {
            bvh_rate = rate;
        }
        println!(
            "  {backend:<6}            build {:7.1} ms  {:8.1} MB  {rate:7.2} Mrays/s",
            build * 1e3,
            a.memory_bytes() as f64 / 1e6
        );
    }
    let bvh = accel::build(scene.clone(), Backend::Bvh).unwrap();
    // GRID_LAMBDAS=1,3 picks the lambdas measured.
    let lambdas: Vec<f32> = std::env::var("GRID_LAMBDAS")
        .unwrap_or_else(|_| "1,2,3,4,6,8".into())
        .split(',')
        .filter_map(|x| x.trim().parse().ok())
        .collect();
    for lambda in lambdas {
        let t = Instant::now();
        let g = GridAccel::build_lambda(scene.clone(), lambda);
        let build = t.elapsed().as_secs_f64();
        let rate = mrays(&g, &rays, 3);
        let r = g.statics().resolution();
        let agree = compare::compare(&scene, &g, bvh.as_ref(), &rays[..rays.len().min(100_000)]);
        println!(
            "  grid l={lambda:<3}{} build {:7.1} ms  {:8.1} MB  {rate:7.3} Mrays/s  grid/bvh {:.3}  {}x{}x{} cells, {:.1}% occupied, {:.2} entries/tri, mismatches {}",
            if lambda == DEFAULT_LAMBDA { "*" } else { " " },
            build * 1e3,
            g.memory_bytes() as f64 / 1e6,
            rate / bvh_rate,
            r[0],
            r[1],
            r[2],
            100.0 * g.statics().occupied_cells() as f64 / g.statics().cell_count() as f64,
            g.statics().entry_count() as f64 / scene.triangle_count() as f64,
            agree.mismatch_count + agree.grazing + agree.edges
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let threads: usize = args.first().and_then(|s| s.parse().ok()).unwrap_or(2);
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(500_000);
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build_global()
        .unwrap();
    println!("{threads} threads");
    run(
        "icosphere(6, 0.05)",
        generate::single_mesh_scene(generate::icosphere(6, 0.05)),
        None,
        n,
    );
    let bunny_path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/assets/obj/stanford-bunny/stanford-bunny.obj");
    let small = if bunny_path.exists() {
        let bunny = Scene::load(&bunny_path).unwrap();
        run("stanford bunny", bunny.clone(), None, n);
        bunny
    } else {
        generate::single_mesh_scene(generate::icosphere(5, 0.05))
    };
    run(
        "small model in a large room",
        model_in_room(&small),
        Some(room_rays(n, 5)),
        n,
    );
    for p in args.iter().skip(2) {
        run(p, Scene::load(Path::new(p)).unwrap(), None, n);
    }
}
