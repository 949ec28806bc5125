//! Every backend must agree with the others: Embree and the Rust BVH, and the grid and the BVH, on a
//! million random rays per model (same primitive, same distance), and all of them on whole renders of
//! every asset (no NaN, mean absolute difference tiny).

mod common;

use glint::accel::{self, compare, Backend};
use glint::render::RenderSettings;

#[test]
fn every_asset_renders_finite_and_identically_in_both_backends() {
    let settings = RenderSettings {
        width: 48,
        height: 36,
        spp: 2,
        max_depth: 3,
        seed: 1,
        ..Default::default()
    };
    let files = common::all_model_files();
    assert!(!files.is_empty());
    for path in files {
        let (scene, camera) = common::load_for_render(&path, settings.width, settings.height);
        let images: Vec<_> = Backend::all_available()
            .into_iter()
            .map(|b| (b, common::render_with(&scene, &camera, b, &settings)))
            .collect();
        for (b, img) in &images {
            assert!(
                !img.has_non_finite(),
                "{}: {b} left a NaN/Inf pixel",
                path.display()
            );
        }
        let (b0, a) = &images[0];
        for (b1, b) in &images[1..] {
            let mean = a.mean_rgb().max(1e-6);
            let mad = a.mean_abs_diff(b);
            eprintln!(
                "{}: mean {mean:.4}, {b0}/{b1} MAD {mad:.2e}",
                path.display()
            );
            assert!(
                mad <= 1e-3 * mean,
                "{}: {b0} and {b1} differ, MAD {mad} vs mean {mean}",
                path.display()
            );
        }
    }
}

/// The pairs compared ray by ray, with how many rays: the BVH against Embree (when built with it) on a
/// million, the grid against the BVH on fewer (the grid is slow on some assets, and with the same
/// triangle test the two must agree exactly anyway).
fn pairs() -> Vec<(Backend, Backend, usize)> {
    let mut v = Vec::new();
    if cfg!(feature = "embree") {
        v.push((Backend::Bvh, Backend::Embree, RAYS));
    }
    v.push((Backend::Grid, Backend::Bvh, RAYS / 5));
    v
}

const RAYS: usize = 1_000_000;

#[test]
fn a_million_random_rays_per_model_hit_the_same_primitive() {
    for path in common::all_model_files() {
        let scene = std::sync::Arc::new(glint::Scene::load(&path).unwrap());
        if scene.triangle_count() == 0 {
            continue;
        }
        let rays = compare::random_rays(&scene, RAYS, 42);
        for (first, second, n) in pairs() {
            let a = accel::build(scene.clone(), first).unwrap();
            let b = accel::build(scene.clone(), second).unwrap();
            let started = std::time::Instant::now();
            let g = compare::compare(&scene, a.as_ref(), b.as_ref(), &rays[..n]);
            let took = started.elapsed().as_secs_f64();
            let name = format!("{} ({first} vs {second})", path.display());
            check_agreement(&name, first, second, &g, took);
        }
    }
}

fn check_agreement(name: &str, first: Backend, second: Backend, g: &compare::Agreement, took: f64) {
    eprintln!(
        "{name}, {took:.2} s: {} rays, {} hits, {} same, {} ties, {} grazing, {} silhouette edges, {} alpha edges, {} at the origin, {} mismatches, {} occlusion mismatches",
        g.rays,
        g.hits,
        g.same,
        g.ties,
        g.grazing,
        g.edges,
        g.alpha_edges,
        g.at_origin,
        g.mismatch_count,
        g.occlusion_mismatches
    );
    for (ray, a, b) in &g.mismatches {
        eprintln!("  {ray:?}\n    {first:<6} {a:?}\n    {second:<6} {b:?}");
    }
    let rays = g.rays;
    assert!(g.hits > rays / 4, "{name}: too few hits to mean anything");
    assert_eq!(g.mismatch_count, 0, "{name}");
    // Grazing disagreements are rare (a property of float geometry, not of either backend).
    assert!(g.grazing <= rays / 2000, "{name}: {} grazing", g.grazing);
    assert!(g.edges <= rays / 10000, "{name}: {} edges", g.edges);
    assert!(
        g.alpha_edges <= rays / 10000,
        "{name}: {} alpha edges",
        g.alpha_edges
    );
    // An origin within a few ulps of a triangle's plane: one in a million here.
    assert!(
        g.at_origin <= rays / 100_000,
        "{name}: {} at the origin",
        g.at_origin
    );
    assert_eq!(g.occlusion_mismatches, 0, "{name}");
}
