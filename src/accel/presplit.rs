//! Triangle pre-splitting for the BVH build (Karras & Aila 2013): a long, thin triangle set
//! diagonally in its box gets several references with smaller boxes, each around one part of it.
//!
//! A diagonal sliver's box is mostly empty space, and every ray through that space pays for its
//! node and leaf. Split into parts along the box's longest axis, the parts' boxes hug the triangle
//! and the SAH build can put them in different subtrees. The budget of extra references goes to
//! the triangles whose boxes exceed the smallest box a triangle of their area can have, in
//! proportion to the cube root of that excess (Karras & Aila's priority), so a mesh of
//! well-shaped triangles gets few.

use glam::{DVec3, Vec3};

use crate::geometry::Aabb;

/// Extra references, as a fraction of the triangles, that the splits may add.
pub(super) const BUDGET: f32 = 0.3;

/// The boxes of the parts of triangle `t` for `pieces` references (at least one), each
/// containing its part of the triangle, together covering it: the box with the largest surface
/// is halved across its longest axis until there are `pieces`.
pub(super) fn part_boxes(t: &[Vec3; 3], pieces: usize, out: &mut Vec<Aabb>) {
    let start = out.len();
    out.push(Aabb::from_points(*t));
    let tri = t.map(|v| v.as_dvec3());
    while out.len() - start < pieces {
        let Some(k) = (start..out.len())
            .max_by(|&a, &b| out[a].surface_area().total_cmp(&out[b].surface_area()))
        else {
            break;
        };
        let b = out[k];
        let axis = b.extent().max_position();
        let plane = 0.5 * (b.min[axis] + b.max[axis]);
        // A box already thin along every axis (a point, rounding) has nothing left to split.
        if !(b.min[axis] < plane && plane < b.max[axis]) {
            break;
        }
        let (lo, hi) = (
            clip(&tri, axis, plane, false),
            clip(&tri, axis, plane, true),
        );
        let (Some(lo), Some(hi)) = (lo.map(|l| meet(l, b)), hi.map(|h| meet(h, b))) else {
            break;
        };
        out[k] = lo;
        out.push(hi);
    }
}

/// The box of the part of the triangle on one side of the plane `x[axis] = plane` (`above`: the
/// side of larger values), rounded outwards: its corners there and where its edges cross the
/// plane. None if no part lies there.
fn clip(t: &[DVec3; 3], axis: usize, plane: f32, above: bool) -> Option<Aabb> {
    let c = plane as f64;
    let side = |v: DVec3| if above { v[axis] >= c } else { v[axis] <= c };
    let mut bounds: Option<(DVec3, DVec3)> = None;
    let mut add = |p: DVec3| {
        bounds = Some(bounds.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))));
    };
    for i in 0..3 {
        let (a, b) = (t[i], t[(i + 1) % 3]);
        if side(a) {
            add(a);
        }
        if (a[axis] - c) * (b[axis] - c) < 0.0 {
            let s = (c - a[axis]) / (b[axis] - a[axis]);
            let mut p = a + (b - a) * s;
            p[axis] = c;
            add(p);
        }
    }
    let (lo, hi) = bounds?;
    // The double-precision crossings rounded outwards to f32, and a relative margin on top: the
    // parts' boxes must never cut into the triangle.
    let margin = (hi - lo).max_element() * 1e-6;
    Some(Aabb {
        min: down(lo - DVec3::splat(margin)),
        max: up(hi + DVec3::splat(margin)),
    })
}

/// The f32 point at or below `v` in each coordinate.
fn down(v: DVec3) -> Vec3 {
    let f = v.as_vec3();
    Vec3::from_array(std::array::from_fn(|i| {
        if f[i] as f64 > v[i] {
            f[i].next_down()
        } else {
            f[i]
        }
    }))
}

/// The f32 point at or above `v` in each coordinate.
fn up(v: DVec3) -> Vec3 {
    let f = v.as_vec3();
    Vec3::from_array(std::array::from_fn(|i| {
        if (f[i] as f64) < v[i] {
            f[i].next_up()
        } else {
            f[i]
        }
    }))
}

/// The overlap of two boxes.
fn meet(a: Aabb, b: Aabb) -> Aabb {
    Aabb {
        min: a.min.max(b.min),
        max: a.max.min(b.max),
    }
}

/// How many references each triangle gets: one, plus its share of `BUDGET` extra ones by the
/// cube root of how far its box's surface exceeds twice the triangle's own area (what a right
/// triangle along the axes has).
pub(super) fn pieces(tris: &[[Vec3; 3]]) -> Vec<usize> {
    let excess: Vec<f64> = tris
        .iter()
        .map(|t| {
            let area = (t[1] - t[0]).cross(t[2] - t[0]).length();
            let box_area = Aabb::from_points(*t).surface_area();
            let e = (box_area - 2.0 * area).max(0.0) as f64;
            if e.is_finite() {
                e.cbrt()
            } else {
                0.0
            }
        })
        .collect();
    let total: f64 = excess.iter().sum();
    let budget = BUDGET as f64 * tris.len() as f64;
    excess
        .iter()
        .map(|&e| {
            if total > 0.0 {
                1 + (budget * e / total) as usize
            } else {
                1
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parts' boxes lie inside the triangle's box, cover every point of the triangle, and
    /// are together smaller than its box, for a diagonal sliver in any orientation.
    #[test]
    fn parts_cover_the_triangle_with_smaller_boxes() {
        let slivers = [
            [
                Vec3::ZERO,
                Vec3::new(10.0, 10.0, 0.1),
                Vec3::new(10.2, 9.8, 0.0),
            ],
            [
                Vec3::new(-3.0, 7.0, 1.0),
                Vec3::new(5.0, -1.0, 9.0),
                Vec3::new(5.1, -1.2, 8.7),
            ],
            [
                Vec3::new(1e4, 1e4, 1e4),
                Vec3::new(1e4 + 3.0, 1e4 + 3.0, 1e4 + 3.0),
                Vec3::new(1e4 + 3.01, 1e4 + 2.99, 1e4 + 3.0),
            ],
        ];
        for t in &slivers {
            let whole = Aabb::from_points(*t);
            for pieces in [1, 2, 5, 8] {
                let mut boxes = Vec::new();
                part_boxes(t, pieces, &mut boxes);
                assert_eq!(boxes.len(), pieces);
                for b in &boxes {
                    assert!(b.min.cmpge(whole.min).all() && b.max.cmple(whole.max).all());
                }
                // Every point of a fine barycentric grid is in some part's box.
                let n = 200;
                for i in 0..=n {
                    for j in 0..=n - i {
                        let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
                        let p = t[0] * (1.0 - u - v) + t[1] * u + t[2] * v;
                        let inside = |b: &Aabb| p.cmpge(b.min).all() && p.cmple(b.max).all();
                        assert!(
                            boxes.iter().any(inside),
                            "{t:?}, {pieces} parts: {p} uncovered"
                        );
                    }
                }
                if pieces > 1 {
                    let sum: f32 = boxes.iter().map(Aabb::surface_area).sum();
                    assert!(sum < 0.8 * whole.surface_area(), "{pieces} parts: {sum}");
                }
            }
        }
    }

    /// Triangles along the axes get no extra references; a diagonal sliver among them gets the
    /// whole budget.
    #[test]
    fn the_budget_goes_to_triangles_with_wasteful_boxes() {
        let mut tris = vec![[Vec3::ZERO, Vec3::X, Vec3::Y]; 99];
        tris.push([Vec3::ZERO, Vec3::splat(10.0), Vec3::new(10.1, 9.9, 10.0)]);
        let p = pieces(&tris);
        assert!(p[..99].iter().all(|&k| k == 1));
        assert_eq!(p[99], 1 + (BUDGET * 100.0) as usize);
    }
}
