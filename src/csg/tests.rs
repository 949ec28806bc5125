use glam::{Mat4, Vec3};
use proptest::prelude::*;

use super::*;
use crate::render::offset::offset_ray_origin;

fn iv(t0: f32, t1: f32, s0: u32, s1: u32) -> Interval {
    Interval { t0, t1, s0, s1 }
}

const TOL: f32 = 1e-4;

fn tol(_: f32) -> f32 {
    TOL
}

fn spans(l: &Intervals) -> Vec<(f32, f32)> {
    l.as_slice().iter().map(|i| (i.t0, i.t1)).collect()
}

#[test]
fn algebra_by_hand() {
    let a = Intervals::from_slice(&[iv(1.0, 4.0, 1, 2), iv(6.0, 8.0, 3, 4)]);
    let b = Intervals::from_slice(&[iv(3.0, 7.0, 10, 11)]);
    let u = Intervals::combine(Op::Union, &a, &b, tol);
    assert_eq!(u.as_slice(), &[iv(1.0, 8.0, 1, 4)]);
    let i = Intervals::combine(Op::Intersection, &a, &b, tol);
    assert_eq!(i.as_slice(), &[iv(3.0, 4.0, 10, 2), iv(6.0, 7.0, 3, 11)]);
    let d = Intervals::combine(Op::Difference, &a, &b, tol);
    // The subtracted surfaces appear flipped.
    assert_eq!(
        d.as_slice(),
        &[iv(1.0, 3.0, 1, 10 | FLIP), iv(7.0, 8.0, 11 | FLIP, 4)]
    );
    // Coincident faces: [1,4] minus [1,2] leaves [2,4], with no sliver at 1.
    let c = Intervals::combine(
        Op::Difference,
        &Intervals::from_slice(&[iv(1.0, 4.0, 1, 2)]),
        &Intervals::from_slice(&[iv(1.0 + TOL / 2.0, 2.0, 5, 6)]),
        tol,
    );
    assert_eq!(c.as_slice(), &[iv(2.0, 4.0, 6 | FLIP, 2)]);
    // Touching intervals merge in a union.
    let t = Intervals::combine(
        Op::Union,
        &Intervals::from_slice(&[iv(1.0, 2.0, 1, 2)]),
        &Intervals::from_slice(&[iv(2.0, 3.0, 3, 4)]),
        tol,
    );
    assert_eq!(t.as_slice(), &[iv(1.0, 3.0, 1, 4)]);
}

#[test]
fn overflow_keeps_the_nearest_and_a_limit() {
    let many: Vec<Interval> = (0..20)
        .map(|k| iv(k as f32 * 2.0, k as f32 * 2.0 + 1.0, k, k))
        .collect();
    let l = Intervals::from_slice(&many);
    assert_eq!(l.as_slice().len(), CAPACITY);
    assert_eq!(l.limit(), CAPACITY as f32 * 2.0);
    let u = Intervals::combine(Op::Union, &l, &Intervals::EMPTY, tol);
    assert_eq!(u.as_slice().len(), CAPACITY);
    assert!(u.limit() <= l.limit());
    assert!(
        u.first_in(31.5, f32::INFINITY).is_none(),
        "nothing is claimed past the limit"
    );

    // An object of 20 spheres in a row: the closest hit is right, whatever lies beyond capacity.
    let spheres: Vec<Node> = (0..20)
        .map(|k| {
            Node::primitive(
                Shape::Sphere {
                    center: Vec3::new(k as f32 * 3.0, 0.0, 0.0),
                    radius: 1.0,
                },
                0,
            )
        })
        .collect();
    let obj = CsgObject::new(Node::union(spheres), Mat4::IDENTITY).unwrap();
    let r = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X);
    let (t, _) = obj.intersect(&r).unwrap();
    assert!((t - 4.0).abs() < 1e-5);
    // From inside the 18th sphere: the next surface is its far side.
    let r = Ray::new(Vec3::new(51.0, 0.0, 0.0), Vec3::X);
    assert!((obj.intersect(&r).unwrap().0 - 1.0).abs() < 1e-5);
    assert!(
        obj.intervals(&Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X))
            .limit()
            < f32::INFINITY
    );
}

/// Sorted, disjoint lists with integer boundaries (so coincidences are exact).
fn list() -> impl Strategy<Value = Intervals> {
    proptest::collection::vec((0u32..4, 1u32..4), 0..8).prop_map(|steps| {
        let mut t = -10.0f32;
        let mut out = Vec::new();
        for (k, (gap, len)) in steps.into_iter().enumerate() {
            let t0 = t + gap as f32 + if k == 0 { 0.0 } else { 1.0 };
            let t1 = t0 + len as f32;
            out.push(iv(t0, t1, 2 * k as u32, 2 * k as u32 + 1));
            t = t1;
        }
        Intervals::from_slice(&out)
    })
}

fn same(a: &Intervals, b: &Intervals) -> bool {
    spans(a) == spans(b)
}

proptest! {
    #[test]
    fn union_with_itself_is_itself(a in list()) {
        let u = Intervals::combine(Op::Union, &a, &a, tol);
        prop_assert!(same(&u, &a));
        prop_assert_eq!(u.as_slice(), a.as_slice());
    }

    #[test]
    fn minus_itself_is_empty(a in list()) {
        prop_assert!(Intervals::combine(Op::Difference, &a, &a, tol).is_empty());
    }

    #[test]
    fn intersection_commutes_and_results_are_well_formed(a in list(), b in list(), c in list()) {
        let ab = Intervals::combine(Op::Intersection, &a, &b, tol);
        let ba = Intervals::combine(Op::Intersection, &b, &a, tol);
        prop_assert!(same(&ab, &ba));
        for op in [Op::Union, Op::Intersection, Op::Difference] {
            let r = Intervals::combine(op, &a, &b, tol);
            prop_assert!(r.is_well_formed(), "{:?}: {:?}", op, spans(&r));
            let r = Intervals::combine(op, &r, &c, tol);
            prop_assert!(r.is_well_formed(), "{:?}: {:?}", op, spans(&r));
        }
    }

    #[test]
    fn de_morgan(a in list(), b in list(), c in list()) {
        // A - (B u C) = (A - B) n (A - C), and A - (B n C) = (A - B) u (A - C).
        for (inner, outer) in [(Op::Union, Op::Intersection), (Op::Intersection, Op::Union)] {
            let bc = Intervals::combine(inner, &b, &c, tol);
            let lhs = Intervals::combine(Op::Difference, &a, &bc, tol);
            let rhs = Intervals::combine(
                outer,
                &Intervals::combine(Op::Difference, &a, &b, tol),
                &Intervals::combine(Op::Difference, &a, &c, tol),
                tol,
            );
            prop_assert!(same(&lhs, &rhs), "{:?} vs {:?}", spans(&lhs), spans(&rhs));
        }
        // A n B = A - (A - B).
        let ab = Intervals::combine(Op::Intersection, &a, &b, tol);
        let amab = Intervals::combine(Op::Difference, &a, &Intervals::combine(Op::Difference, &a, &b, tol), tol);
        prop_assert!(same(&ab, &amab));
    }
}

/// The cube [-1, 1]^3, material 0.
fn unit_cube() -> Node {
    Node::primitive(
        Shape::Box {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        },
        0,
    )
}

fn sphere(c: Vec3, r: f32) -> Node {
    Node::primitive(
        Shape::Sphere {
            center: c,
            radius: r,
        },
        0,
    )
}

#[test]
fn sphere_minus_itself_and_a_bigger_one_is_empty() {
    let a = CsgObject::new(
        Node::difference(vec![sphere(Vec3::ZERO, 1.0), sphere(Vec3::ZERO, 1.0)]),
        Mat4::IDENTITY,
    )
    .unwrap();
    let b = CsgObject::new(
        Node::difference(vec![sphere(Vec3::ZERO, 1.0), sphere(Vec3::ZERO, 1.5)]),
        Mat4::from_translation(Vec3::new(3.0, -2.0, 7.0)),
    )
    .unwrap();
    let mut rng = Rng(7);
    for _ in 0..2000 {
        let o = Vec3::new(rng.f(), rng.f(), rng.f()) * 4.0;
        let d = (Vec3::new(rng.f(), rng.f(), rng.f()) * 0.5 - o).normalize();
        assert!(a.intersect(&Ray::new(o, d)).is_none());
        let o = o + Vec3::new(3.0, -2.0, 7.0);
        assert!(b.intersect(&Ray::new(o, d)).is_none());
    }
}

#[test]
fn lens_depth_matches_the_closed_form() {
    // Two spheres of radius R with centres at x = -c and x = +c; their intersection is a lens.
    let (r, c) = (1.0f32, 0.6f32);
    let lens = CsgObject::new(
        Node::intersection(vec![
            sphere(Vec3::new(-c, 0.0, 0.0), r),
            sphere(Vec3::new(c, 0.0, 0.0), r),
        ]),
        Mat4::IDENTITY,
    )
    .unwrap();
    let rim = (r * r - c * c).sqrt();
    let mut worst = 0.0f32;
    let mut hits = 0;
    for i in 0..41 {
        for j in 0..41 {
            let (y, z) = (i as f32 / 20.0 - 1.0, j as f32 / 20.0 - 1.0);
            let rho2 = y * y + z * z;
            let ray = Ray::new(Vec3::new(-5.0, y, z), Vec3::X);
            let got = lens.intersect(&ray);
            if rho2.sqrt() < rim - 1e-3 {
                // Entering through the sphere centred at +c.
                let want = 5.0 + c - (r * r - rho2).sqrt();
                let (t, s) = got.expect("inside the lens' rim");
                worst = worst.max((t - want).abs());
                let n = lens.surface(s, ray.at(t), 0.0).n;
                let want_n = (ray.at(t) - Vec3::new(c, 0.0, 0.0)).normalize();
                assert!(n.dot(want_n) > 0.9999, "{n} vs {want_n}");
                // The thickness is the closed form too: 2 (sqrt(R^2 - rho^2) - c).
                let l = lens.intervals(&ray);
                let thick = l.as_slice()[0].t1 - l.as_slice()[0].t0;
                assert!((thick - 2.0 * ((r * r - rho2).sqrt() - c)).abs() < 1e-5);
                hits += 1;
            } else if rho2.sqrt() > rim + 1e-3 {
                assert!(got.is_none());
            }
        }
    }
    assert!(hits > 300);
    assert!(worst < 2e-6, "worst depth error {worst}");
    eprintln!("lens: {hits} rays, worst depth error {worst:e}");
}

struct Rng(u64);

impl Rng {
    /// Uniform in [-1, 1).
    fn f(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 23) as f32 - 1.0
    }
}

#[test]
fn subtracted_surfaces_face_out_of_the_result() {
    let obj = CsgObject::new(
        Node::difference(vec![
            unit_cube(),
            Node::Primitive {
                shape: Shape::Sphere {
                    center: Vec3::ZERO,
                    radius: 1.3,
                },
                transform: Mat4::IDENTITY,
                material: 1,
            },
        ]),
        Mat4::IDENTITY,
    )
    .unwrap();
    // Through a face's centre: the sphere covers the whole axis inside the box, so the ray passes.
    assert!(obj
        .intersect(&Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z))
        .is_none());
    // Towards a corner: box face first (material 0, outward normal)...
    let o = Vec3::new(0.8, 0.8, 5.0);
    let (t, s) = obj.intersect(&Ray::new(o, -Vec3::Z)).unwrap();
    assert!((t - 4.0).abs() < 1e-5);
    let surf = obj.surface(s, o - Vec3::Z * t, 0.0);
    assert_eq!((surf.n, surf.material), (Vec3::Z, 0));
    // ... then, inside the corner, the sphere's surface, with the normal towards the centre.
    let r = Ray {
        t_min: t + 1e-3,
        ..Ray::new(o, -Vec3::Z)
    };
    let (t2, s2) = obj.intersect(&r).unwrap();
    let p = r.at(t2);
    assert!((p.length() - 1.3).abs() < 1e-5);
    let surf = obj.surface(s2, p, 0.0);
    assert!(surf.n.dot(-p.normalize()) > 0.9999);
    assert_eq!(surf.material, 1);
}

#[test]
fn coincident_faces_leave_no_speckles() {
    // A slot cut into the top of a box by a second box whose top face coincides with the first's, but
    // reached through a different transform (so the two distances round differently).
    let slot = Node::Primitive {
        shape: Shape::Box {
            min: Vec3::splat(-0.5),
            max: Vec3::splat(0.5),
        },
        transform: Mat4::from_translation(Vec3::new(0.0, 0.0, 0.65))
            * Mat4::from_scale(Vec3::new(1.0, 1.0, 0.7)),
        material: 1,
    };
    let obj = CsgObject::new(
        Node::difference(vec![unit_cube(), slot]),
        Mat4::from_rotation_y(0.3) * Mat4::from_translation(Vec3::new(0.1, 0.2, 0.3)),
    )
    .unwrap();
    let to_world = Mat4::from_rotation_y(0.3) * Mat4::from_translation(Vec3::new(0.1, 0.2, 0.3));
    let mut rng = Rng(99);
    let (mut floor, mut speckles) = (0, 0);
    for _ in 0..5000 {
        // Aim at the slot's floor (z = 0.3 in object space) from above, at varied angles.
        let target = Vec3::new(rng.f() * 0.45, rng.f() * 0.45, 0.3);
        let from = target + Vec3::new(rng.f() * 0.05, rng.f() * 0.05, 3.0);
        let (o, t) = (
            to_world.transform_point3(from),
            to_world.transform_point3(target),
        );
        let ray = Ray::new(o, (t - o).normalize());
        let (th, s) = obj.intersect(&ray).expect("the slot's floor");
        let p = to_world.inverse().transform_point3(ray.at(th));
        if (p.z - 0.3).abs() < 1e-4 {
            floor += 1;
            let (leaf, _, flipped) = obj.split_surface(s);
            assert!(leaf == 1 && flipped);
        } else {
            speckles += 1;
        }
    }
    assert_eq!(speckles, 0, "{floor} rays reached the floor");
}

#[test]
fn tangent_rays_and_rays_from_inside() {
    let obj = CsgObject::new(sphere(Vec3::ZERO, 1.0), Mat4::IDENTITY).unwrap();
    for y in [1.0f32, 1.0 - 1e-7, 1.0 + 1e-7, 0.99999] {
        let r = Ray::new(Vec3::new(-3.0, y, 0.0), Vec3::X);
        let l = obj.intervals(&r);
        assert!(l.is_well_formed());
        if let Some((t, _)) = obj.intersect(&r) {
            assert!((r.at(t).length() - 1.0).abs() < 1e-5);
        }
    }
    // From the centre: the surface leaving the sphere, normal outward.
    let r = Ray::new(Vec3::ZERO, Vec3::new(0.3, 0.4, 0.5).normalize());
    let (t, s) = obj.intersect(&r).unwrap();
    assert!((t - 1.0).abs() < 1e-6);
    assert!(obj.surface(s, r.at(t), 0.0).n.dot(r.d) > 0.9999);
}

/// Every primitive, placed with a rotation, non-uniform scale and a translation, near and far from
/// the origin: rays leaving a surface (reflected outwards, or continuing inwards) never find that
/// surface again at their start.
#[test]
fn secondary_rays_do_not_rehit_their_surface() {
    let shapes = [
        Shape::Sphere {
            center: Vec3::new(0.1, 0.0, 0.0),
            radius: 1.0,
        },
        Shape::Box {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        },
        Shape::Cylinder {
            radius: 1.0,
            height: 2.0,
        },
        Shape::Cone {
            radius: 1.0,
            height: 2.0,
        },
        Shape::Torus {
            major: 1.0,
            minor: 0.35,
        },
    ];
    let mut rng = Rng(5);
    let mut worst_inward = f32::INFINITY;
    for (k, &shape) in shapes.iter().enumerate() {
        for offset in [Vec3::ZERO, Vec3::new(300.0, -120.0, 40.0), Vec3::splat(1e4)] {
            for scale in [0.01f32, 1.0, 50.0] {
                if scale * 1e3 < offset.max_element() {
                    // Waechter and Binder's offset (256 ulps of the coordinates) would be a sizeable
                    // part of the object (at 1e4 it is 0.25), as it would for a triangle mesh.
                    continue;
                }
                let m = Mat4::from_translation(offset)
                    * Mat4::from_rotation_y(0.7 + k as f32)
                    * Mat4::from_rotation_x(0.4)
                    * Mat4::from_scale(Vec3::new(1.0, 0.6, 1.3) * scale);
                let obj = CsgObject::new(Node::primitive(shape, 0), m).unwrap();
                let size = obj.bounds().extent().length();
                let mut n_hits = 0;
                for _ in 0..300 {
                    let target = m.transform_point3(Vec3::new(rng.f(), rng.f(), rng.f()) * 0.5);
                    let from =
                        target + Vec3::new(rng.f(), rng.f(), rng.f()).normalize() * size * 4.0;
                    let ray = Ray::new(from, (target - from).normalize());
                    let Some((t, s)) = obj.intersect(&ray) else {
                        continue;
                    };
                    n_hits += 1;
                    let surf = obj.surface(s, ray.at(t), 0.0);
                    let n = surf.n;
                    assert!(n.dot(ray.d) < 0.0, "entering surfaces face the ray");
                    // Reflected: leaves outwards; a convex shape is never hit again.
                    let refl = ray.d - 2.0 * ray.d.dot(n) * n;
                    let out = Ray::new(offset_ray_origin(surf.p, n), refl);
                    if !matches!(shape, Shape::Torus { .. }) {
                        assert!(
                            obj.intersect(&out).is_none(),
                            "{shape:?} at {offset} x{scale}: reflected ray hit again"
                        );
                    } else if let Some((t2, _)) = obj.intersect(&out) {
                        assert!(t2 > 1e-3 * size, "torus re-hit at {t2}");
                    }
                    // Continuing inwards: the next surface is the far side, not the entry point.
                    let inward = Ray::new(offset_ray_origin(surf.p, -n), ray.d);
                    let Some((t2, _)) = obj.intersect(&inward) else {
                        panic!("{shape:?} at {offset} x{scale}: inward ray {inward:?} from {:?} (t {t}, n {n}) never leaves", surf.p);
                    };
                    worst_inward = worst_inward.min(t2 / size);
                    assert!(
                        t2 > 1e-5 * size,
                        "{shape:?} at {offset} x{scale}: inward ray re-hit at {t2}"
                    );
                }
                assert!(n_hits > 50, "{shape:?}: {n_hits}");
            }
        }
    }
    eprintln!("closest inward exit: {worst_inward:e} of the object size");
}

#[test]
fn union_early_exit_matches_full_evaluation() {
    // A row of overlapping spheres and boxes under nested operations: the early-stopping closest-hit
    // path must agree with the first boundary of the full list.
    let mut kids = Vec::new();
    for k in 0..12 {
        let c = Vec3::new(k as f32 * 0.8 - 4.0, (k % 3) as f32 * 0.3, 0.0);
        kids.push(Node::difference(vec![
            sphere(c, 0.6),
            Node::primitive(
                Shape::Box {
                    min: c + Vec3::new(-0.2, -0.2, -1.0),
                    max: c + Vec3::new(0.2, 0.2, 1.0),
                },
                0,
            ),
        ]));
    }
    let obj = CsgObject::new(Node::union(kids), Mat4::from_rotation_z(0.2)).unwrap();
    let mut rng = Rng(3);
    let mut hits = 0;
    for _ in 0..5000 {
        let o = Vec3::new(rng.f() * 6.0, rng.f() * 3.0, rng.f() * 3.0);
        let d = Vec3::new(rng.f(), rng.f(), rng.f()).normalize();
        let ray = Ray::new(o, d);
        let full = obj.intervals(&ray).first_in(ray.t_min, ray.t_max);
        assert_eq!(obj.intersect(&ray), full);
        hits += full.is_some() as u32;
    }
    assert!(hits > 300, "{hits}");
}

#[test]
fn closed_mesh_operand_matches_the_triangle_bvh_and_the_analytic_box() {
    use crate::accel::{bvh::BvhAccel, Accel};
    use crate::scene::generate;
    use std::sync::Arc;
    // Alone, a mesh operand finds what the BVH finds over the same triangles, from outside and inside.
    let ico = generate::icosphere(3, 0.1);
    let solid = Arc::new(ico.to_solid().unwrap());
    let obj = CsgObject::new(
        Node::Mesh {
            mesh: solid,
            transform: Mat4::IDENTITY,
            material: 0,
        },
        Mat4::IDENTITY,
    )
    .unwrap();
    let bvh = BvhAccel::build(Arc::new(generate::single_mesh_scene(ico)));
    let mut rng = Rng(11);
    let (mut hits, mut inside) = (0, 0);
    for k in 0..4000 {
        let o = if k % 2 == 0 {
            Vec3::new(rng.f(), rng.f(), rng.f()) * 3.0
        } else {
            Vec3::new(rng.f(), rng.f(), rng.f()) * 0.5
        };
        let d = Vec3::new(rng.f(), rng.f(), rng.f()).normalize();
        let ray = Ray::new(o, d);
        let want = bvh.intersect(&ray).map(|h| h.t);
        let got = obj.intersect(&ray).map(|h| h.0);
        match (want, got) {
            (Some(w), Some(g)) => assert!((w - g).abs() <= 1e-6 * w.max(1.0), "{w} vs {g}"),
            (None, None) => {}
            _ => panic!("{ray:?}: bvh {want:?}, csg {got:?}"),
        }
        hits += want.is_some() as u32;
        inside += (k % 2 == 1) as u32;
    }
    assert!(hits > 2000 && inside > 0);

    // A 12-triangle cube minus a sphere renders as the analytic box minus the sphere.
    let sphere = || {
        Node::primitive(
            Shape::Sphere {
                center: Vec3::ZERO,
                radius: 1.3,
            },
            1,
        )
    };
    let cube = generate::box_mesh(Vec3::splat(-1.0), Vec3::splat(1.0));
    let meshed = CsgObject::new(
        Node::difference(vec![
            Node::Mesh {
                mesh: Arc::new(cube.to_solid().unwrap()),
                transform: Mat4::IDENTITY,
                material: 0,
            },
            sphere(),
        ]),
        Mat4::from_rotation_y(0.3),
    )
    .unwrap();
    let analytic = CsgObject::new(
        Node::difference(vec![unit_cube(), sphere()]),
        Mat4::from_rotation_y(0.3),
    )
    .unwrap();
    let mut same = 0;
    for _ in 0..4000 {
        let o = Vec3::new(rng.f(), rng.f(), rng.f()) * 4.0;
        let d = (Vec3::new(rng.f(), rng.f(), rng.f()) * 0.9 - o).normalize();
        let ray = Ray::new(o, d);
        match (meshed.intersect(&ray), analytic.intersect(&ray)) {
            (Some((tm, sm)), Some((ta, sa))) => {
                assert!((tm - ta).abs() < 1e-5, "{tm} vs {ta}");
                let (nm, na) = (
                    meshed.surface(sm, ray.at(tm), 0.0),
                    analytic.surface(sa, ray.at(ta), 0.0),
                );
                assert!(nm.n.dot(na.n) > 0.9999, "{} vs {}", nm.n, na.n);
                assert_eq!(nm.material, na.material);
                same += 1;
            }
            (None, None) => {}
            (x, y) => panic!("{ray:?}: mesh {x:?}, analytic {y:?}"),
        }
    }
    assert!(same > 1000, "{same}");
    // An open mesh has no inside.
    assert!(generate::quad_grid(2).to_solid().is_err());
}

#[test]
fn a_moving_object_is_hit_where_it_is_at_the_ray_time() {
    let ball = sphere(Vec3::ZERO, 1.0);
    // Rests at x = 0, moves to x = 4 while also scaling by 2 (a placement, not just a shift).
    let start = Mat4::IDENTITY;
    let end = Mat4::from_translation(Vec3::X * 4.0) * Mat4::from_scale(Vec3::splat(2.0));
    let obj = CsgObject::new(ball, start).unwrap().with_motion(Motion {
        steps: vec![start, end],
    });
    assert!(obj.moves() && obj.time_steps() == 2);
    let b = obj.bounds();
    assert!(b.min.x <= -1.0 && b.max.x >= 6.0 && b.max.y >= 2.0, "{b:?}");
    for time in [0.0f32, 0.25, 0.5, 1.0] {
        // Centre and radius at `time`: the blend of the two placements.
        let (c, r) = (Vec3::X * 4.0 * time, 1.0 + time);
        let ray = Ray::new(Vec3::new(c.x + 0.3, 0.2, 10.0), -Vec3::Z).with_time(time);
        let (t, s) = obj.intersect(&ray).expect("hits the moved sphere");
        let z = (r * r - 0.3f32 * 0.3 - 0.2 * 0.2).sqrt();
        assert!((t - (10.0 - z)).abs() < 1e-4, "time {time}: {t}");
        let surf = obj.surface(s, ray.at(t), time);
        assert!(
            (surf.p - ray.at(t)).length() < 1e-4,
            "time {time}: {}",
            surf.p
        );
        let radial = (surf.p - c).normalize();
        assert!(
            surf.n.dot(radial) > 0.9999,
            "time {time}: {} vs {radial}",
            surf.n
        );
        // The same ray at the far end of the shutter misses.
        let other = Ray {
            time: if time < 0.5 { 1.0 } else { 0.0 },
            ..ray
        };
        assert!(obj.intersect(&other).is_none(), "time {time}");
    }
    // A still placement is no motion.
    let still = CsgObject::new(sphere(Vec3::ZERO, 1.0), start)
        .unwrap()
        .with_motion(Motion {
            steps: vec![start; 3],
        });
    assert!(!still.moves());
}
