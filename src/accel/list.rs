//! The seed's "fast failure": a flat list of objects, each behind cheap bounding tests (ray pointing
//! away from its sphere, sphere distance, box slabs) that reject a ray before its triangles are tried.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use glam::Vec3;

use super::flat::TriId;
use super::Accel;
use crate::geometry::triangle::{self, RayShear};
use crate::geometry::{gamma, Aabb, Hit, Ray};
use crate::scene::Scene;

/// Which cheap tests run before an object's triangles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pretests {
    /// Bounding sphere: "pointing away" (origin outside, centre behind) and closest-approach tests.
    pub sphere: bool,
    /// Axis-aligned box slabs (after the sphere when both are on).
    pub boxes: bool,
    /// Visit objects nearest-entry first and stop once the next entry lies beyond the closest hit.
    pub ordered: bool,
}

impl Pretests {
    pub const NONE: Pretests = Pretests {
        sphere: false,
        boxes: false,
        ordered: false,
    };
    pub const ALL: Pretests = Pretests {
        sphere: true,
        boxes: true,
        ordered: true,
    };
}

/// How often each test ran and how often it rejected, over a stream of rays.
#[derive(Debug, Default)]
pub struct Counts {
    pub rays: AtomicU64,
    pub sphere_tests: AtomicU64,
    /// Rejections by the cheapest form: origin outside the sphere, centre behind it.
    pub pointing_away: AtomicU64,
    pub sphere_rejects: AtomicU64,
    pub box_tests: AtomicU64,
    pub box_rejects: AtomicU64,
    /// Objects never visited because an earlier hit was closer than their entry.
    pub ordered_skips: AtomicU64,
    /// The expensive tests: ray/triangle.
    pub triangle_tests: AtomicU64,
}

impl Counts {
    fn add(c: &AtomicU64, n: u64) {
        if n != 0 {
            c.fetch_add(n, Ordering::Relaxed);
        }
    }

    pub fn get(c: &AtomicU64) -> u64 {
        c.load(Ordering::Relaxed)
    }
}

struct Object {
    center: Vec3,
    radius: f32,
    bounds: Aabb,
    tris: Vec<[Vec3; 3]>,
    ids: Vec<TriId>,
}

/// One object per instance, tested in a flat list.
pub struct ObjectList {
    scene: Arc<Scene>,
    objects: Vec<Object>,
    pretests: Pretests,
    counts: Option<Counts>,
}

/// Per-ray tallies, added to the shared counters once per ray.
#[derive(Default)]
struct Tally {
    sphere_tests: u64,
    pointing_away: u64,
    sphere_rejects: u64,
    box_tests: u64,
    box_rejects: u64,
    ordered_skips: u64,
    triangle_tests: u64,
}

impl ObjectList {
    pub fn build(scene: Arc<Scene>, pretests: Pretests, count: bool) -> Self {
        // Moving instances are left out: this backend traces only the static scene.
        let moving: Vec<bool> = scene.instances.iter().map(|i| i.motion.is_some()).collect();
        let (tris, ids) = super::flat::flatten(&scene, &moving);
        let mut objects: Vec<Object> = Vec::with_capacity(scene.instances.len());
        for (t, id) in tris.into_iter().zip(ids) {
            if objects.last().is_none_or(|o| o.ids[0].inst() != id.inst()) {
                objects.push(Object {
                    center: Vec3::ZERO,
                    radius: 0.0,
                    bounds: Aabb::EMPTY,
                    tris: Vec::new(),
                    ids: Vec::new(),
                });
            }
            let o = objects.last_mut().expect("pushed above");
            o.bounds = t.iter().fold(o.bounds, |b, &p| b.grow(p));
            o.tris.push(t);
            o.ids.push(id);
        }
        for o in &mut objects {
            o.center = o.bounds.center();
            // Widened by a few ulps of the coordinates so rounding never rejects a true hit.
            let r = o
                .tris
                .iter()
                .flatten()
                .map(|p| (*p - o.center).length())
                .fold(0.0f32, f32::max);
            o.radius = r * (1.0 + gamma(8)) + o.center.abs().max_element() * gamma(4);
        }
        Self {
            scene,
            objects,
            pretests,
            counts: count.then(Counts::default),
        }
    }

    pub fn counts(&self) -> Option<&Counts> {
        self.counts.as_ref()
    }

    /// The entry distance of the ray into object `o`'s bounds, or None when a pretest rejects it.
    fn enter(&self, o: &Object, ray: &Ray, inv_d: Vec3, tally: &mut Tally) -> Option<f32> {
        let mut entry = ray.t_min;
        if self.pretests.sphere {
            tally.sphere_tests += 1;
            let oc = o.center - ray.o;
            let r2 = o.radius * o.radius;
            let outside = oc.length_squared() > r2;
            let along = oc.dot(ray.d);
            // Cheapest: the origin lies outside and the centre behind it, so the sphere is behind.
            if outside && along < 0.0 {
                tally.pointing_away += 1;
                return None;
            }
            let dd = ray.d.length_squared();
            // Squared distance from the centre to the ray's line, without cancellation.
            let perp2 = (oc - ray.d * (along / dd)).length_squared();
            if perp2 > r2 {
                tally.sphere_rejects += 1;
                return None;
            }
            if outside {
                entry = entry.max((along - (dd * (r2 - perp2)).max(0.0).sqrt()) / dd);
            }
        }
        if self.pretests.boxes {
            tally.box_tests += 1;
            let Some((near, _)) = o.bounds.clip(ray.o, inv_d, ray.t_min, f32::INFINITY) else {
                tally.box_rejects += 1;
                return None;
            };
            entry = entry.max(near);
        }
        Some(entry)
    }

    fn trace(&self, ray: &Ray, any: bool) -> Option<Hit> {
        let mut tally = Tally::default();
        let inv_d = ray.d.recip();
        let sh = RayShear::new(ray.d);
        let mut best: Option<Hit> = None;
        let visit = |o: &Object, tally: &mut Tally, best: &mut Option<Hit>| -> bool {
            for (t, &id) in o.tris.iter().zip(&o.ids) {
                tally.triangle_tests += 1;
                let t_max = best.map_or(ray.t_max, |b| b.t);
                if let Some(h) = triangle::intersect(ray.o, &sh, t[0], t[1], t[2], ray.t_min, t_max)
                {
                    if id.accepts(&self.scene, h.u, h.v, ray) {
                        *best = Some(Hit {
                            t: h.t,
                            u: h.u,
                            v: h.v,
                            inst: id.inst(),
                            prim: id.prim,
                        });
                        if any {
                            return true;
                        }
                    }
                }
            }
            false
        };
        if self.pretests.ordered && !any {
            let mut order: Vec<(f32, usize)> = self
                .objects
                .iter()
                .enumerate()
                .filter_map(|(i, o)| self.enter(o, ray, inv_d, &mut tally).map(|t| (t, i)))
                .collect();
            order.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (k, &(entry, i)) in order.iter().enumerate() {
                // A conservative entry beyond the closest hit cannot hold a closer one.
                if best.is_some_and(|b| entry > b.t * (1.0 + gamma(4))) {
                    tally.ordered_skips += (order.len() - k) as u64;
                    break;
                }
                visit(&self.objects[i], &mut tally, &mut best);
            }
        } else {
            for o in &self.objects {
                if self.enter(o, ray, inv_d, &mut tally).is_some()
                    && visit(o, &mut tally, &mut best)
                {
                    break;
                }
            }
        }
        if let Some(c) = &self.counts {
            Counts::add(&c.rays, 1);
            Counts::add(&c.sphere_tests, tally.sphere_tests);
            Counts::add(&c.pointing_away, tally.pointing_away);
            Counts::add(&c.sphere_rejects, tally.sphere_rejects);
            Counts::add(&c.box_tests, tally.box_tests);
            Counts::add(&c.box_rejects, tally.box_rejects);
            Counts::add(&c.ordered_skips, tally.ordered_skips);
            Counts::add(&c.triangle_tests, tally.triangle_tests);
        }
        best
    }
}

impl Accel for ObjectList {
    fn name(&self) -> &'static str {
        "list"
    }

    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        self.trace(ray, false)
    }

    fn occluded(&self, ray: &Ray) -> bool {
        self.trace(ray, true).is_some()
    }

    fn memory_bytes(&self) -> usize {
        self.objects
            .iter()
            .map(|o| o.tris.len() * (36 + 8) + std::mem::size_of::<Object>())
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::testing::{brute, rng};
    use crate::scene::generate;
    use glam::Mat4;

    /// Every combination of pretests gives the brute-force answer bit for bit, and the pretests
    /// take triangle tests away.
    #[test]
    fn pretests_never_change_the_answer_and_save_triangle_tests() {
        let mesh = generate::icosphere(3, 0.0);
        let instances: Vec<_> = (0..12)
            .map(|i| {
                let m = Mat4::from_translation(Vec3::new(
                    (i % 4) as f32 * 3.0,
                    (i / 4) as f32 * 3.0,
                    0.0,
                ));
                crate::scene::Instance::new(0, m)
            })
            .collect();
        let s = crate::accel::testing::scene(vec![mesh], instances);
        let mut r = rng(7);
        let rays: Vec<Ray> = (0..1500)
            .map(|_| {
                let o = Vec3::new(r() * 14.0 - 2.0, r() * 10.0 - 2.0, 6.0 + r() * 2.0);
                let target = Vec3::new(r() * 10.0, r() * 7.0, r() - 0.5);
                Ray::new(o, (target - o).normalize())
            })
            .collect();
        let want: Vec<_> = rays.iter().map(|r| brute(&s, r)).collect();
        assert!(
            want.iter().flatten().count() > 150,
            "the rays should hit often"
        );
        let mut tests = Vec::new();
        for (sphere, boxes, ordered) in [
            (false, false, false),
            (true, false, false),
            (false, true, false),
            (true, true, true),
        ] {
            let p = Pretests {
                sphere,
                boxes,
                ordered,
            };
            let list = ObjectList::build(s.clone(), p, true);
            let mut hits = 0;
            for ray in &rays {
                let want = brute(&s, ray);
                let got = list.intersect(ray);
                assert_eq!(
                    got.map(|g| g.t.to_bits()),
                    want.map(|w| w.t.to_bits()),
                    "{p:?} {ray:?}"
                );
                assert_eq!(list.occluded(ray), want.is_some());
                hits += want.is_some() as u32;
            }
            assert!(hits > 300, "the rays should hit often: {hits}");
            tests.push(Counts::get(&list.counts().unwrap().triangle_tests));
        }
        // Each pretest must save most of the brute-force work on this sparse scene.
        assert!(
            tests[1] * 3 < tests[0] && tests[2] * 3 < tests[0],
            "{tests:?}"
        );
        assert!(tests[3] <= tests[1].min(tests[2]), "{tests:?}");
    }
}
