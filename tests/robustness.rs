//! Numerical robustness of every backend: rays aimed exactly at the shared vertices and edges of a closed
//! mesh always hit (watertightness), and a scene moved far from the origin or scaled keeps its hits.

use std::sync::Arc;

use glam::{Mat4, Vec3};
use glint::accel::{self, Backend};
use glint::scene::{generate, Instance};
use glint::Ray;

fn closed_sphere(transform: Mat4) -> Arc<glint::Scene> {
    let mut scene = generate::single_mesh_scene(generate::icosphere(4, 0.0));
    scene.instances = vec![Instance::new(0, transform)];
    Arc::new(scene)
}

/// Points on every vertex and along every edge of the mesh, in world space.
fn vertex_and_edge_targets(scene: &glint::Scene) -> Vec<Vec3> {
    let inst = &scene.instances[0];
    let mesh = &scene.meshes[0];
    let mut out = Vec::new();
    for t in &mesh.indices {
        let [a, b, c] = t.map(|i| inst.to_world.transform_point3(mesh.positions[i as usize]));
        out.push(a);
        for s in [0.25f32, 0.5, 0.75] {
            out.push(a.lerp(b, s));
            out.push(b.lerp(c, s));
        }
    }
    out
}

/// Rays crossing the closed sphere at each vertex/edge target (from outside, from the centre, and
/// the centre's occlusion query) that report no hit, and how many rays were cast.
fn slipped_through(backend: Backend) -> (usize, usize) {
    let scene = closed_sphere(Mat4::IDENTITY);
    let targets = vertex_and_edge_targets(&scene);
    let a = accel::build(scene.clone(), backend).unwrap();
    let mut missed = 0;
    // From outside towards each target, and from the centre outwards through it.
    for (k, &p) in targets.iter().enumerate() {
        // Crossing the (convex) surface at an angle: grazing touches of a lone vertex are not hits
        // that watertightness promises.
        let wobble = Vec3::new(
            (k as f32 * 0.37).sin(),
            (k as f32 * 0.23).cos(),
            (k as f32 * 0.11).cos(),
        );
        let n = p.normalize();
        let tangent = (wobble - n * wobble.dot(n)).normalize_or_zero();
        let dir = (n + 0.6 * tangent).normalize();
        let from_outside = Ray::new(p + dir * 5.0, -dir);
        let from_inside = Ray::new(Vec3::ZERO, p.normalize());
        let m = [
            a.intersect(&from_outside).is_none(),
            a.intersect(&from_inside).is_none(),
            !a.occluded(&from_inside),
        ];
        missed += m.iter().filter(|&&x| x).count();
    }
    (missed, 3 * targets.len())
}

#[test]
fn rays_through_vertices_and_edges_never_slip_through() {
    for backend in Backend::all_available() {
        let (missed, cast) = slipped_through(backend);
        assert_eq!(missed, 0, "{backend}: {missed} of {cast} rays missed");
    }
}

/// `embree-fast` (benchmarks only) is Embree's default test, which is not watertight: this is the
/// difference robust mode pays for.
#[cfg(feature = "embree")]
#[test]
fn embree_fast_is_not_watertight() {
    let (missed, cast) = slipped_through(Backend::EmbreeFast);
    assert!(missed > 0, "embree-fast: none of {cast} rays missed");
}

#[test]
fn far_and_scaled_scenes_keep_their_hits() {
    let base = closed_sphere(Mat4::IDENTITY);
    let rays = glint::accel::compare::random_rays(&base, 20_000, 5);
    for backend in Backend::all_available() {
        let a0 = accel::build(base.clone(), backend).unwrap();
        let reference: Vec<_> = rays.iter().map(|r| a0.intersect(r)).collect();
        for (offset, scale) in [(1e5f32, 1.0f32), (0.0, 1e-3), (0.0, 1e3), (1e5, 1e3)] {
            let m =
                Mat4::from_translation(Vec3::splat(offset)) * Mat4::from_scale(Vec3::splat(scale));
            let moved = closed_sphere(m);
            let a = accel::build(moved.clone(), backend).unwrap();
            // Coordinates near `offset` are quantised to its float spacing: in the reference's units
            // the geometry itself moves by up to that much, so hits may move by a few of them.
            let quantum = (offset + scale).abs() * f32::EPSILON / scale;
            let t_tol = |t: f32| 1e-4 * t + 8.0 * quantum;
            let (mut flipped, mut moved_hits) = (0, 0);
            for (r, want) in rays.iter().zip(&reference) {
                let ray = Ray::new(m.transform_point3(r.o), r.d);
                match (want, a.intersect(&ray)) {
                    (None, None) => {}
                    (Some(w), Some(g)) => {
                        moved_hits += ((g.t / scale - w.t).abs() > t_tol(w.t)) as usize
                    }
                    _ => flipped += 1,
                }
            }
            let differ = flipped + moved_hits;
            // Rays grazing a silhouette may flip, and grazing hits move by quantum / cos(angle): a
            // small fraction far from the origin, nothing systematic.
            let fraction = if offset != 0.0 { 5e-3f32 } else { 1e-3 };
            let allowed = ((rays.len() as f32) * fraction.max(20.0 * quantum)) as usize;
            assert!(
                differ <= allowed,
                "{backend} offset {offset} scale {scale}: {differ} of {} rays changed ({flipped} flipped)",
                rays.len()
            );
        }
    }
}
