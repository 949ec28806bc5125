//! The tests every backend must pass, table-driven over `Backend::all_available()` and a few variants
//! (the BVH's portable SSE walk, other grid resolutions, other obvhs presets): brute-force agreement,
//! empty scenes, segment limits, barycentrics, instance ids, alpha masks, CSG objects, motion.
//!
//! Backends with glint's watertight triangle test (bvh, grid) must match brute force bit for bit;
//! the others (Embree, obvhs) must agree with it as `compare::compare` classifies agreement.

use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};

use super::bvh::{Bvh, BvhAccel};
use super::compare;
use super::grid::GridAccel;
use super::testing::{
    alpha_quads, assert_batches_match_single, brute, down, quad, rng, scene, scene_with, Brute,
};
use super::{Accel, Backend};
use crate::csg::{CsgObject, Node, Shape};
use crate::geometry::{Motion, Ray, CSG_BIT};
use crate::scene::{generate, AlphaMode, Instance, Material, Mesh, Scene};

/// One structure under test.
struct Case {
    name: String,
    /// Whether it uses glint's watertight triangle test, and so must match brute force exactly.
    exact: bool,
    build: Box<dyn Fn(Arc<Scene>) -> Box<dyn Accel>>,
}

impl Case {
    fn new(
        name: impl Into<String>,
        exact: bool,
        build: impl Fn(Arc<Scene>) -> Box<dyn Accel> + 'static,
    ) -> Self {
        Self {
            name: name.into(),
            exact,
            build: Box::new(build),
        }
    }
}

/// Every available backend, then the variants.
fn cases() -> Vec<Case> {
    let mut v: Vec<Case> = Backend::all_available()
        .into_iter()
        .map(|b| {
            let exact = matches!(b, Backend::Bvh | Backend::Grid);
            Case::new(b.to_string(), exact, move |s| {
                super::build(s, b).expect("the backend builds")
            })
        })
        .collect();
    v.push(Case::new("bvh (SSE walk)", true, |s| {
        Box::new(BvhAccel::build_with(s, |_, tris, ids| {
            Bvh::new(tris, ids).without_avx()
        }))
    }));
    v.push(Case::new("grid (lambda 8)", true, |s| {
        Box::new(GridAccel::build_lambda(s, 8.0))
    }));
    #[cfg(feature = "obvhs")]
    for name in ["medium_build", "fastest_build"] {
        v.push(Case::new(format!("obvhs ({name})"), false, move |s| {
            let params = super::obvhs::preset(name).expect("a known preset");
            Box::new(super::obvhs::ObvhsAccel::build_preset(s, name, params))
        }));
    }
    v
}

/// Checks every case's answers for `rays` against brute force (opaque static scenes only): exact
/// cases hit at the same distance, bit for bit, and `occluded` agrees; the others agree as
/// `compare` counts agreement, with at most `1 / loose` of the rays grazing or on edges. Returns
/// the number of rays that hit.
fn agree_with_brute_force(s: &Arc<Scene>, rays: &[Ray], loose: usize) -> usize {
    let want: Vec<_> = rays.iter().map(|r| brute(s, r)).collect();
    for case in cases() {
        let a = (case.build)(s.clone());
        let name = &case.name;
        if case.exact {
            for (ray, want) in rays.iter().zip(&want) {
                let got = a.intersect(ray);
                assert_eq!(
                    got.map(|h| h.t.to_bits()),
                    want.map(|h| h.t.to_bits()),
                    "{name}: ray {ray:?}: {got:?}, brute force {want:?}"
                );
                assert_eq!(a.occluded(ray), want.is_some(), "{name}: occluded, {ray:?}");
            }
        } else {
            let g = compare::compare(s, a.as_ref(), &Brute(s.clone()), rays);
            assert_eq!(g.mismatch_count, 0, "{name}: {:?}", g.mismatches);
            assert_eq!(g.occlusion_mismatches, 0, "{name}");
            assert!(g.grazing + g.edges <= rays.len() / loose, "{name}: {g:?}");
        }
    }
    want.iter().flatten().count()
}

fn random_dir(next: &mut impl FnMut() -> f32) -> Vec3 {
    Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize()
}

#[test]
fn random_rays_match_brute_force() {
    let s = scene(
        vec![generate::quad_grid(40), generate::icosphere(3, 0.1)],
        vec![
            Instance::new(0, Mat4::IDENTITY),
            Instance::new(
                0,
                Mat4::from_rotation_x(0.7) * Mat4::from_translation(Vec3::new(-5.0, 3.0, 4.0)),
            ),
            Instance::new(
                1,
                Mat4::from_translation(Vec3::new(20.0, 20.0, 3.0))
                    * Mat4::from_scale(Vec3::splat(4.0)),
            ),
        ],
    );
    let mut next = rng(0x1234_5678);
    let rays: Vec<Ray> = (0..10_000)
        .map(|_| {
            let o = Vec3::new(
                next() * 50.0 - 5.0,
                next() * 50.0 - 5.0,
                20.0 * next() - 5.0,
            );
            Ray::new(o, random_dir(&mut next))
        })
        .collect();
    let hits = agree_with_brute_force(&s, &rays, 500);
    assert!(hits > 1000, "test rays should hit often, hit {hits}");
}

/// A sphere placed many times (turned, scaled, overlapping) beside a ground quad, with the Rust
/// backends tracing every shared mesh as instances: they, Embree and brute force agree, hits
/// naming the right copy.
#[test]
fn many_copies_of_a_mesh_match_brute_force() {
    let n = 32;
    let mut instances = vec![Instance::new(0, Mat4::from_scale(Vec3::splat(30.0)))];
    instances.extend((0..n).map(|k| {
        let k = k as f32;
        Instance::new(
            1,
            Mat4::from_translation(Vec3::new(k % 6.0 * 1.5, (k / 6.0).floor() * 1.5, 1.5))
                * Mat4::from_rotation_z(0.3 * k)
                * Mat4::from_scale(Vec3::new(1.0, 0.5 + 0.05 * k, 1.0)),
        )
    }));
    let s = scene(
        vec![generate::quad_grid(4), generate::icosphere(2, 0.1)],
        instances,
    );
    let traced = super::instances::traced_as_instances(&s, 0);
    assert_eq!(traced.iter().filter(|t| **t).count(), n);
    let mut next = rng(0x51);
    let rays: Vec<Ray> = (0..10_000)
        .map(|_| {
            let o = Vec3::new(next() * 12.0 - 2.0, next() * 12.0 - 2.0, 6.0 + next() * 4.0);
            let d = Vec3::new(next() - 0.5, next() - 0.5, -1.0).normalize();
            Ray::new(o, d)
        })
        .collect();
    let mut cases: Vec<(String, Box<dyn Accel>)> = vec![
        (
            "bvh".into(),
            Box::new(BvhAccel::build_limited(
                s.clone(),
                |_, t, i| Bvh::new(t, i),
                0,
            )),
        ),
        (
            "grid".into(),
            Box::new(GridAccel::build_limited(
                s.clone(),
                |_, t, i| super::grid::Grid::new(t, i, super::grid::DEFAULT_LAMBDA),
                0,
            )),
        ),
    ];
    for b in Backend::all_available() {
        cases.push((b.to_string(), super::build(s.clone(), b).unwrap()));
    }
    let brute = Brute(s.clone());
    let hits = rays.iter().filter(|r| brute.intersect(r).is_some()).count();
    assert!(hits > 5000, "test rays should hit often, hit {hits}");
    for (name, a) in &cases {
        let g = compare::compare(&s, a.as_ref(), &brute, &rays);
        assert_eq!(g.mismatch_count, 0, "{name}: {:?}", g.mismatches);
        assert_eq!(g.occlusion_mismatches, 0, "{name}");
        assert!(g.grazing + g.edges <= rays.len() / 200, "{name}: {g:?}");
    }
}

/// A 5k-triangle sphere of radius 0.01 in a room a thousand times larger (for the grid: cells much
/// larger than the sphere's triangles, which all crowd into a few cells).
#[test]
fn small_detailed_model_inside_a_large_room() {
    let s = scene(
        vec![
            generate::box_mesh(Vec3::splat(-10.0), Vec3::splat(10.0)),
            generate::icosphere(4, 0.05),
        ],
        vec![
            Instance::new(0, Mat4::IDENTITY),
            Instance::new(
                1,
                Mat4::from_translation(Vec3::new(1.0, -2.0, 0.5))
                    * Mat4::from_scale(Vec3::splat(0.01)),
            ),
        ],
    );
    let mut next = rng(3);
    let rays: Vec<Ray> = (0..10_000)
        .map(|i| {
            let o = Vec3::new(
                next() * 18.0 - 9.0,
                next() * 18.0 - 9.0,
                next() * 18.0 - 9.0,
            );
            let target = Vec3::new(1.0, -2.0, 0.5)
                + 0.012 * Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
            let d = if i % 2 == 0 {
                (target - o).normalize()
            } else {
                random_dir(&mut next)
            };
            Ray::new(o, d)
        })
        .collect();
    let hits = agree_with_brute_force(&s, &rays, 500);
    assert_eq!(hits, rays.len(), "the room is closed: every ray hits");
    let on_sphere = rays
        .iter()
        .filter(|r| brute(&s, r).is_some_and(|h| h.inst == 1))
        .count();
    assert!(on_sphere > 2500, "{on_sphere}");
}

/// Rays through every vertex of a plane (corners of flat boxes and grid cells), along every axis from
/// inside and outside with both signs (including -0.0 components), and in axis planes.
#[test]
fn axis_parallel_rays_and_rays_through_vertices() {
    let s = scene(
        vec![generate::quad_grid(16), generate::icosphere(2, 0.0)],
        vec![
            Instance::new(0, Mat4::IDENTITY),
            Instance::new(
                1,
                Mat4::from_translation(Vec3::new(8.0, 8.0, 2.0))
                    * Mat4::from_scale(Vec3::splat(3.0)),
            ),
        ],
    );
    let mut rays = Vec::new();
    for y in 0..=16 {
        for x in 0..=16 {
            let o = Vec3::new(x as f32, y as f32, 30.0);
            rays.push(Ray::new(o, Vec3::new(-0.0, 0.0, -1.0)));
            rays.push(Ray::new(Vec3::new(o.x, o.y, 3.0), -Vec3::Z));
        }
    }
    let through_vertices = rays.len();
    let mut next = rng(99);
    for _ in 0..3000 {
        let o = Vec3::new(next() * 20.0 - 2.0, next() * 20.0 - 2.0, next() * 8.0 - 2.0);
        for d in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z] {
            rays.push(Ray::new(o, d));
        }
        // Along the plane itself, and diagonals in axis planes (two zero components).
        let d = Vec3::new(next() - 0.5, next() - 0.5, 0.0).normalize();
        rays.push(Ray::new(Vec3::new(o.x, o.y, 0.0), d));
        rays.push(Ray::new(o, d));
    }
    agree_with_brute_force(&s, &rays, 50);
    for r in &rays[..through_vertices] {
        assert!(brute(&s, r).is_some(), "a ray through a vertex hits: {r:?}");
    }
}

#[test]
fn empty_scenes_and_segment_limits() {
    let flat = scene(
        vec![generate::quad_grid(8)],
        vec![Instance::new(0, Mat4::IDENTITY)],
    );
    let mut next = rng(7);
    let segments: Vec<Ray> = (0..5000)
        .map(|_| {
            let o = Vec3::new(next() * 12.0 - 2.0, next() * 12.0 - 2.0, next() * 4.0 - 2.0);
            let d = random_dir(&mut next);
            let (a, b) = (next() * 10.0, next() * 10.0);
            Ray {
                t_min: a.min(b),
                t_max: a.max(b),
                ..Ray::new(o, d)
            }
        })
        .collect();
    agree_with_brute_force(&flat, &segments, 500);
    let down = Ray::new(Vec3::new(0.5, 0.3, 1.0), -Vec3::Z);
    let beyond = Ray {
        t_min: 1.01,
        ..down
    };
    let empty_mesh = scene(
        vec![Mesh::default()],
        vec![Instance::new(0, Mat4::IDENTITY)],
    );
    for case in cases() {
        let name = &case.name;
        for s in [scene(vec![], vec![]), empty_mesh.clone()] {
            let a = (case.build)(s);
            assert!(
                a.intersect(&Ray::new(Vec3::ZERO, Vec3::Z)).is_none(),
                "{name}"
            );
            assert!(!a.occluded(&Ray::new(Vec3::ZERO, Vec3::Z)), "{name}");
        }
        let a = (case.build)(flat.clone());
        assert!((a.intersect(&down).unwrap().t - 1.0).abs() < 1e-6, "{name}");
        assert!(a.occluded(&down), "{name}");
        assert!(!a.occluded(&Ray::segment(down.o, down.d, 0.99)), "{name}");
        assert!(a.occluded(&Ray::segment(down.o, down.d, 1.01)), "{name}");
        assert!(a.intersect(&Ray::segment(down.o, down.d, 0.99)).is_none());
        assert!(a.intersect(&beyond).is_none(), "{name}");
        assert!(!a.occluded(&beyond), "{name}");
        assert!(a.memory_bytes() > 0, "{name}");
    }
}

/// Barycentrics weight vertices 1 and 2; `t` is in units of the direction's length.
#[test]
fn unit_quad_hits_barycentrics_and_segments() {
    let s = scene_with(
        vec![quad()],
        vec![Instance::new(0, Mat4::IDENTITY)],
        vec![Material::default()],
    );
    for case in cases() {
        let name = &case.name;
        let a = (case.build)(s.clone());
        // Above triangle 0 (below the diagonal y = x): p = (0.7, 0.2) = u (1,0) + v (1,1).
        let h = a.intersect(&down(Vec3::new(0.7, 0.2, 2.0))).unwrap();
        assert_eq!((h.inst, h.prim), (0, 0), "{name}");
        assert!((h.t - 2.0).abs() < 1e-6, "{name}");
        let bary = (h.u - 0.5).abs() < 1e-5 && (h.v - 0.2).abs() < 1e-5;
        assert!(bary, "{name}: {h:?}");
        let h = a.intersect(&down(Vec3::new(0.2, 0.7, 2.0))).unwrap();
        assert_eq!(h.prim, 1, "{name}");
        assert!(a.intersect(&down(Vec3::new(1.5, 0.5, 2.0))).is_none());
        let up = Ray::new(Vec3::new(0.5, 0.5, 2.0), Vec3::Z);
        assert!(a.intersect(&up).is_none(), "{name}");
        let o = Vec3::new(0.5, 0.25, 2.0);
        assert!(a.occluded(&Ray::segment(o, Vec3::NEG_Z, 3.0)), "{name}");
        assert!(!a.occluded(&Ray::segment(o, Vec3::NEG_Z, 1.5)), "{name}");
        assert!(a.intersect(&Ray::segment(o, Vec3::NEG_Z, 1.5)).is_none());
        let h = a
            .intersect(&Ray::new(o, Vec3::new(0.0, 0.0, -4.0)))
            .unwrap();
        assert!((h.t - 0.5).abs() < 1e-6, "{name}: {h:?}");
    }
}

/// On random rays the barycentrics place the hit where the ray says it is.
#[test]
fn barycentrics_place_the_hit_on_the_ray() {
    let s = scene(
        vec![generate::icosphere(4, 0.05), generate::quad_grid(30)],
        vec![
            Instance::new(0, Mat4::IDENTITY),
            Instance::new(
                0,
                Mat4::from_translation(Vec3::new(2.5, 0.3, -0.5))
                    * Mat4::from_rotation_y(0.6)
                    * Mat4::from_scale(Vec3::splat(0.7)),
            ),
            Instance::new(
                1,
                Mat4::from_translation(Vec3::new(-3.0, -3.0, -2.0))
                    * Mat4::from_scale(Vec3::splat(0.25)),
            ),
        ],
    );
    let rays = compare::random_rays(&s, 20_000, 3);
    for case in cases() {
        let a = (case.build)(s.clone());
        let mut checked = 0;
        for ray in &rays {
            let Some(h) = a.intersect(ray) else {
                continue;
            };
            let [p0, p1, p2] = s.world_triangle(h.inst, h.prim);
            // Skip grazing hits, where t, u, v are ill-conditioned.
            let n = (p1 - p0).cross(p2 - p0).normalize();
            if n.dot(ray.d.normalize()).abs() < 0.1 {
                continue;
            }
            let p = p0 * (1.0 - h.u - h.v) + p1 * h.u + p2 * h.v;
            let q = ray.at(h.t);
            assert!(
                (p - q).length() < 1e-4 * (1.0 + q.length()),
                "{}: {p} vs {q}",
                case.name
            );
            checked += 1;
        }
        assert!(checked > 10_000, "{}: {checked}", case.name);
    }
}

/// A 3 mm model, with rays leaving its surfaces: hits within micrometres are found.
#[test]
fn small_scenes_keep_near_hits() {
    let s = scene(
        vec![generate::icosphere(4, 0.05)],
        vec![Instance::new(0, Mat4::from_scale(Vec3::splat(1e-3)))],
    );
    let mut rays = compare::random_rays(&s, 20_000, 11);
    // Start just inside the sphere: the nearest hit is within micrometres.
    for r in &mut rays {
        if let Some(h) = brute(&s, r) {
            r.o += r.d * (h.t - 2e-6);
        }
    }
    agree_with_brute_force(&s, &rays, 100);
}

/// Mesh 0 placed three times (one scaled), mesh 1 once: hits name their instance (for Embree both
/// instanced and flattened geometry), with barycentrics and distances in world units.
#[test]
fn instances_report_their_index() {
    let s = scene_with(
        vec![quad(), quad()],
        vec![
            Instance::new(1, Mat4::from_translation(Vec3::new(0.0, 0.0, -5.0))),
            Instance::new(0, Mat4::from_translation(Vec3::new(10.0, 0.0, 0.0))),
            Instance::new(0, Mat4::from_translation(Vec3::new(20.0, 0.0, -1.0))),
            Instance::new(
                0,
                Mat4::from_translation(Vec3::new(30.0, 0.0, 0.0))
                    * Mat4::from_scale(Vec3::splat(4.0)),
            ),
        ],
        vec![Material::default()],
    );
    for case in cases() {
        let name = &case.name;
        let a = (case.build)(s.clone());
        // Ray origin, then instance, triangle, distance and (where checked) barycentrics. Scaled by
        // 4, (33, 1) is (0.75, 0.25) in object space, triangle 0.
        for (o, id, t, uv) in [
            ((0.2, 0.7, 1.0), (0, 1), 6.0, None),
            ((10.7, 0.2, 1.0), (1, 0), 1.0, Some((0.5, 0.2))),
            ((20.2, 0.7, 1.0), (2, 1), 2.0, None),
            ((33.0, 1.0, 3.0), (3, 0), 3.0, Some((0.5, 0.25))),
        ] {
            let h = a.intersect(&down(Vec3::from(o))).unwrap();
            assert_eq!((h.inst, h.prim), id, "{name}: {o:?}");
            assert!((h.t - t).abs() < 1e-5, "{name}: {o:?}: {h:?}");
            if let Some((u, v)) = uv {
                assert!(
                    (h.u - u).abs() < 1e-5 && (h.v - v).abs() < 1e-5,
                    "{name}: {h:?}"
                );
            }
        }
        assert!(a.intersect(&down(Vec3::new(5.0, 0.5, 1.0))).is_none());
        let o = Vec3::new(33.0, 1.0, 3.0);
        assert!(a.occluded(&Ray::segment(o, Vec3::NEG_Z, 3.5)), "{name}");
        assert!(!a.occluded(&Ray::segment(o, Vec3::NEG_Z, 2.5)), "{name}");
    }
}

#[test]
fn alpha_masks_cut_out() {
    for (alpha, visible) in [(0.2, false), (0.8, true)] {
        let mat = Material {
            alpha_mode: AlphaMode::Mask(0.5),
            base_color: Vec4::new(1.0, 1.0, 1.0, alpha),
            ..Default::default()
        };
        assert!(mat.needs_alpha_test());
        let s = alpha_quads(mat);
        for case in cases() {
            let name = &case.name;
            let a = (case.build)(s.clone());
            let h = a.intersect(&down(Vec3::new(0.5, 0.25, 1.0))).unwrap();
            assert_eq!(h.inst, if visible { 0 } else { 3 }, "{name}: alpha {alpha}");
            for x in [10.5, 20.5] {
                let ray = down(Vec3::new(x, 0.25, 1.0));
                assert_eq!(
                    a.intersect(&ray).is_some(),
                    visible,
                    "{name}: alpha {alpha}"
                );
                assert_eq!(a.occluded(&ray), visible, "{name}: alpha {alpha}");
            }
            let shadow = Ray::segment(Vec3::new(0.5, 0.25, 1.0), Vec3::NEG_Z, 1.5);
            assert_eq!(a.occluded(&shadow), visible, "{name}: alpha {alpha}");
        }
    }
}

/// Blending is stochastic per ray seed: every backend makes the scene's decision for the world ray.
#[test]
fn alpha_blend_follows_the_scene_decision() {
    let mat = Material {
        alpha_mode: AlphaMode::Blend,
        base_color: Vec4::new(1.0, 1.0, 1.0, 0.5),
        ..Default::default()
    };
    let s = scene_with(
        vec![quad()],
        vec![
            Instance::new(0, Mat4::IDENTITY),
            Instance::new(0, Mat4::from_translation(Vec3::new(2.0, 0.0, 0.0))),
        ],
        vec![mat],
    );
    for case in cases() {
        let name = &case.name;
        let a = (case.build)(s.clone());
        let mut passes = 0;
        for i in 0..200 {
            let x = 2.0 + (i as f32 + 0.5) / 200.0;
            let ray = down(Vec3::new(x, 0.9 * x.fract(), 1.0)).with_seed(i * 7919);
            let expected = s.alpha_passes(1, 0, 0.0, 0.0, &ray);
            let h = a.intersect(&ray);
            assert_eq!(h.is_some(), expected, "{name}: ray {i}");
            if let Some(h) = h {
                assert!(s.alpha_passes(h.inst, h.prim, h.u, h.v, &ray), "{name}");
                passes += 1;
            }
            assert_eq!(a.occluded(&ray), expected, "{name}: ray {i}");
        }
        assert!(passes > 50 && passes < 150, "{name}: {passes} of 200 pass");
    }
}

fn sphere(center: Vec3, radius: f32) -> Node {
    Node::primitive(Shape::Sphere { center, radius }, 0)
}

/// A CSG sphere and a mesh quad in one scene: the nearer wins, at its analytic distance, and CSG
/// hits name their object with `CSG_BIT`.
#[test]
fn csg_objects_and_meshes_share_the_queries() {
    let mut s = generate::single_mesh_scene(quad());
    s.instances = vec![Instance::new(
        0,
        Mat4::from_translation(Vec3::new(-0.5, -0.5, 0.0)),
    )];
    s.csg = vec![
        CsgObject::new(sphere(Vec3::ZERO, 0.25), Mat4::from_translation(Vec3::Z)).unwrap(),
        CsgObject::new(
            Node::difference(vec![sphere(Vec3::ZERO, 1.0), sphere(Vec3::ZERO, 1.2)]),
            Mat4::IDENTITY,
        )
        .unwrap(),
        CsgObject::new(
            sphere(Vec3::ZERO, 0.25),
            Mat4::from_translation(Vec3::new(3.0, 0.0, -1.0)),
        )
        .unwrap(),
    ];
    let s = Arc::new(s);
    let rays: Vec<Ray> = {
        let mut next = rng(5);
        (0..4000)
            .map(|_| {
                let o = Vec3::new(next() * 8.0 - 2.0, next() * 4.0 - 2.0, 4.0);
                let target = Vec3::new(next() * 4.0 - 0.5, next() - 0.5, next() * 2.0 - 1.0);
                Ray::new(o, (target - o).normalize())
            })
            .collect()
    };
    let reference = (cases()[0].build)(s.clone());
    for case in cases() {
        let name = &case.name;
        let a = (case.build)(s.clone());
        // From above: the sphere at z = 1 (radius 0.25) before the quad at z = 0.
        let h = a.intersect(&down(Vec3::new(0.0, 0.0, 3.0))).unwrap();
        assert_eq!(h.csg().map(|(o, _)| o), Some(0), "{name}: {h:?}");
        assert_eq!(h.inst, CSG_BIT, "{name}");
        assert!((h.t - 1.75).abs() < 1e-5, "{name}: {}", h.t);
        // From below: the quad first (off its diagonal, which obvhs's test may slip through).
        let h = a
            .intersect(&Ray::new(Vec3::new(0.1, -0.1, -3.0), Vec3::Z))
            .unwrap();
        assert_eq!(h.inst, 0, "{name}: {h:?}");
        assert!((h.t - 3.0).abs() < 1e-5, "{name}: {h:?}");
        // Beside the quad: the sphere at x = 3, z = -1 alone; segments end before and after it.
        let o = Vec3::new(3.0, 0.0, 3.0);
        let h = a.intersect(&down(o)).unwrap();
        assert_eq!(h.csg().map(|(o, _)| o), Some(2), "{name}");
        assert!((h.t - 3.75).abs() < 1e-5, "{name}: {}", h.t);
        assert!(a.occluded(&Ray::segment(o, Vec3::NEG_Z, 3.8)), "{name}");
        assert!(!a.occluded(&Ray::segment(o, Vec3::NEG_Z, 3.7)), "{name}");
        assert!(a
            .intersect(&Ray {
                t_min: 4.0,
                ..down(o)
            })
            .is_some_and(|h| h.csg().is_some()));
        // The empty difference is never hit.
        let g = compare::compare(&s, a.as_ref(), reference.as_ref(), &rays);
        assert_eq!(g.mismatch_count, 0, "{name}: {:?}", g.mismatches);
        assert_eq!(g.occlusion_mismatches, 0, "{name}");
        for r in &rays {
            assert!(a
                .intersect(r)
                .and_then(|h| h.csg())
                .is_none_or(|(o, _)| o != 1));
        }
        // Batched queries (Embree's eight-wide packets, through the CSG callbacks too) answer as
        // single ones do.
        let hits = assert_batches_match_single(a.as_ref(), &rays, name);
        let csg_hits = hits.iter().filter(|h| h.is_some_and(|h| h.csg().is_some()));
        assert!(csg_hits.count() > 100, "{name}: too few CSG hits to test");
    }
}

/// A box moving along x during the shutter in front of a static quad: it is hit where it is at the
/// ray's time, and the quad behind it elsewhere.
#[test]
fn moving_instances_are_hit_where_they_are_at_the_ray_time() {
    let mut moving = Instance::new(0, Mat4::IDENTITY);
    moving.motion = Some(Motion {
        steps: vec![
            Mat4::IDENTITY,
            Mat4::from_translation(Vec3::new(4.0, 0.0, 0.0)),
        ],
    });
    let behind = Instance::new(
        1,
        Mat4::from_translation(Vec3::new(-2.0, -2.0, -3.0)) * Mat4::from_scale(Vec3::splat(10.0)),
    );
    let s = scene(
        vec![
            generate::box_mesh(Vec3::splat(-0.5), Vec3::splat(0.5)),
            quad(),
        ],
        vec![moving, behind],
    );
    assert!(s.has_motion());
    for case in cases() {
        let name = &case.name;
        let a = (case.build)(s.clone());
        for (time, x, on_box) in [
            (0.0, 0.0, true),
            (0.0, 2.0, false),
            (0.5, 2.0, true),
            (1.0, 4.3, true),
            (1.0, 0.0, false),
        ] {
            let ray = Ray::new(Vec3::new(x, 0.0, 5.0), -Vec3::Z).with_time(time);
            let h = a.intersect(&ray).unwrap();
            let (inst, t) = if on_box { (0, 4.5) } else { (1, 8.0) };
            assert_eq!(h.inst, inst, "{name}: time {time}, x {x}");
            assert!(
                (h.t - t).abs() < 1e-5,
                "{name}: time {time}, x {x}: {}",
                h.t
            );
            assert!(a.occluded(&ray), "{name}");
            let short = Ray::segment(ray.o, ray.d, 6.0).with_time(time);
            assert_eq!(a.occluded(&short), on_box, "{name}: time {time}, x {x}");
        }
    }
}

#[test]
fn rays_that_are_no_rays_hit_nothing() {
    // NaN and zero directions and NaN limits: a miss in every backend, never a panic.
    let s = scene(
        vec![generate::quad_grid(8)],
        vec![Instance::new(0, Mat4::IDENTITY)],
    );
    let o = Vec3::new(1.0, 1.0, 1.0);
    let rays = [
        Ray::new(o, Vec3::ZERO),
        Ray::new(o, Vec3::NAN),
        Ray::new(o, Vec3::new(f32::INFINITY, 0.0, -1.0)),
        Ray::segment(o, -Vec3::Z, f32::NAN),
    ];
    for case in cases() {
        let accel = (case.build)(s.clone());
        for ray in &rays {
            assert!(accel.intersect(ray).is_none(), "{}: {ray:?}", case.name);
            assert!(!accel.occluded(ray), "{}: {ray:?}", case.name);
        }
    }
}
