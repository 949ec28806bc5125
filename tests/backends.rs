//! Embree and the Rust BVH must agree: on a million random rays per model (same primitive, same
//! distance) and on whole renders of every asset (no NaN, mean absolute difference tiny).

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
        if let [(_, a), (_, b)] = &images[..] {
            let mean = a.mean_rgb().max(1e-6);
            let mad = a.mean_abs_diff(b);
            eprintln!("{}: mean {mean:.4}, backend MAD {mad:.2e}", path.display());
            assert!(
                mad <= 1e-3 * mean,
                "{}: backends differ, MAD {mad} vs mean {mean}",
                path.display()
            );
        }
    }
}

#[cfg(feature = "embree")]
#[test]
fn a_million_random_rays_per_model_hit_the_same_primitive() {
    const RAYS: usize = 1_000_000;
    for path in common::all_model_files() {
        let scene = std::sync::Arc::new(glint::Scene::load(&path).unwrap());
        if scene.triangle_count() == 0 {
            continue;
        }
        let rays = compare::random_rays(&scene, RAYS, 42);
        let bvh = accel::build(scene.clone(), Backend::Bvh).unwrap();
        let embree = accel::build(scene.clone(), Backend::Embree).unwrap();
        let g = compare::compare(&scene, bvh.as_ref(), embree.as_ref(), &rays);
        eprintln!(
            "{}: {} rays, {} hits, {} same, {} ties, {} grazing, {} silhouette edges, {} alpha edges, {} mismatches, {} occlusion mismatches",
            path.display(),
            g.rays,
            g.hits,
            g.same,
            g.ties,
            g.grazing,
            g.edges,
            g.alpha_edges,
            g.mismatch_count,
            g.occlusion_mismatches
        );
        for (ray, a, b) in &g.mismatches {
            eprintln!("  {ray:?}\n    bvh    {a:?}\n    embree {b:?}");
        }
        assert!(
            g.hits > RAYS / 4,
            "{}: too few hits to mean anything",
            path.display()
        );
        assert_eq!(g.mismatch_count, 0, "{}", path.display());
        // Grazing disagreements are rare (a property of float geometry, not of either backend).
        assert!(
            g.grazing <= RAYS / 2000,
            "{}: {} grazing",
            path.display(),
            g.grazing
        );
        assert!(
            g.edges <= RAYS / 10000,
            "{}: {} edges",
            path.display(),
            g.edges
        );
        assert!(
            g.alpha_edges <= RAYS / 10000,
            "{}: {} alpha edges",
            path.display(),
            g.alpha_edges
        );
        assert_eq!(g.occlusion_mismatches, 0, "{}", path.display());
    }
}
