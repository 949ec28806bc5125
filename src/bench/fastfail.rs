//! `glint bench fast-failure`: how many expensive ray/triangle tests the cheap bounding tests of the
//! object list save (sphere "pointing away" and distance, box slabs, nearest-first order), per ray kind.

use std::fmt::Write as _;
use std::sync::Arc;

use rayon::prelude::*;

use super::error::{BenchError, Result};
use super::input::Input;
use super::rays::{generate_rays, RayKind};
use crate::accel::list::{Counts, ObjectList, Pretests};
use crate::accel::{self, Accel, Backend};
use crate::geometry::Ray;

/// The pretest combinations measured, from none (brute force) to all.
pub const CONFIGS: [(&str, Pretests); 5] = [
    ("none (brute force)", Pretests::NONE),
    (
        "sphere",
        Pretests {
            sphere: true,
            boxes: false,
            ordered: false,
        },
    ),
    (
        "box",
        Pretests {
            sphere: false,
            boxes: true,
            ordered: false,
        },
    ),
    (
        "sphere + box",
        Pretests {
            sphere: true,
            boxes: true,
            ordered: false,
        },
    ),
    ("sphere + box + nearest first", Pretests::ALL),
];

/// One row: a pretest combination on one ray kind.
#[derive(Clone, Debug)]
pub struct Row {
    pub kind: RayKind,
    pub config: &'static str,
    pub rays: u64,
    pub triangle_tests: u64,
    pub sphere_tests: u64,
    pub pointing_away: u64,
    pub sphere_rejects: u64,
    pub box_tests: u64,
    pub box_rejects: u64,
    pub ordered_skips: u64,
}

/// Counts the tests for every ray kind and pretest combination on at most `max_rays` rays per kind
/// (every `k`-th ray of the set, so the sample spans the image).
pub fn run(input: &Input, width: usize, height: usize, max_rays: usize) -> Result<Vec<Row>> {
    crate::render::job::check_size(width, height)?;
    let scene = Arc::new(input.load()?);
    if scene.triangle_count() == 0 {
        return Err(BenchError::NoTriangles(input.to_string()));
    }
    let reference = accel::build(scene.clone(), Backend::Bvh)?;
    let sets = generate_rays(&scene, reference.as_ref(), width, height);
    let mut rows = Vec::new();
    for kind in RayKind::SINGLE {
        let all = sets.get(kind);
        let step = all.len().div_ceil(max_rays.max(1)).max(1);
        let rays: Vec<Ray> = all.iter().step_by(step).copied().collect();
        for (name, p) in CONFIGS {
            let list = ObjectList::build(scene.clone(), p, true);
            rays.par_iter().for_each(|r| {
                if kind.any_hit() {
                    list.occluded(r);
                } else {
                    list.intersect(r);
                }
            });
            let c = list.counts().expect("built with counting");
            rows.push(Row {
                kind,
                config: name,
                rays: Counts::get(&c.rays),
                triangle_tests: Counts::get(&c.triangle_tests),
                sphere_tests: Counts::get(&c.sphere_tests),
                pointing_away: Counts::get(&c.pointing_away),
                sphere_rejects: Counts::get(&c.sphere_rejects),
                box_tests: Counts::get(&c.box_tests),
                box_rejects: Counts::get(&c.box_rejects),
                ordered_skips: Counts::get(&c.ordered_skips),
            });
        }
    }
    Ok(rows)
}

pub fn table(input: &Input, objects: usize, rows: &[Row]) -> String {
    let mut s = format!("{input}: {objects} objects\n");
    let _ = writeln!(
        s,
        "{:<8} {:<30} {:>8} {:>12} {:>8} {:>10} {:>10} {:>10} {:>10}",
        "rays",
        "cheap tests",
        "count",
        "tri tests/ray",
        "saved",
        "away",
        "sphere rej",
        "box rej",
        "skipped"
    );
    for r in rows {
        let brute = rows
            .iter()
            .find(|b| b.kind == r.kind && b.config == CONFIGS[0].0)
            .map_or(0, |b| b.triangle_tests);
        let per = |n: u64| n as f64 / r.rays.max(1) as f64;
        let _ = writeln!(
            s,
            "{:<8} {:<30} {:>8} {:>12.1} {:>7.1}% {:>10.2} {:>10.2} {:>10.2} {:>10.2}",
            r.kind.to_string(),
            r.config,
            r.rays,
            per(r.triangle_tests),
            100.0 * (1.0 - r.triangle_tests as f64 / brute.max(1) as f64),
            per(r.pointing_away),
            per(r.sphere_rejects),
            per(r.box_rejects),
            per(r.ordered_skips),
        );
    }
    s += "(per ray: triangle tests; objects rejected by 'pointing away', by sphere distance, by box\n\
          slabs, and never visited because a closer hit came first)\n";
    s
}
