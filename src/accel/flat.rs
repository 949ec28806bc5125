//! The world-space triangle soup the Rust backends build over: every instance's triangles moved to
//! world space, each with its identity and whether its material needs an alpha test.

use glam::Vec3;
use rayon::prelude::*;

use crate::geometry::triangle::Hits;
use crate::geometry::{Hit, Ray};
use crate::scene::Scene;

/// Marks an instance id whose material needs an alpha test.
const ALPHA_BIT: u32 = 1 << 31;

/// Triangle identity: instance (top bit: alpha-tested) and primitive within its mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TriId {
    inst: u32,
    pub prim: u32,
}

impl TriId {
    /// Fills unused slots (packet lanes); never reported as a hit.
    pub const NONE: TriId = TriId {
        inst: u32::MAX,
        prim: u32::MAX,
    };

    pub fn new(inst: u32, prim: u32, alpha_tested: bool) -> Self {
        Self {
            inst: inst | if alpha_tested { ALPHA_BIT } else { 0 },
            prim,
        }
    }

    /// This identity with `base` added to its instance (the alpha bit kept).
    #[inline(always)]
    pub fn rebased(self, base: u32) -> Self {
        Self {
            inst: self.inst.wrapping_add(base),
            prim: self.prim,
        }
    }

    pub fn inst(self) -> u32 {
        self.inst & !ALPHA_BIT
    }

    pub fn alpha_tested(self) -> bool {
        self.inst & ALPHA_BIT != 0
    }

    /// Whether a candidate hit at barycentrics `(u, v)` counts: always, unless the material cuts it out.
    #[inline(always)]
    pub fn accepts(self, scene: &Scene, u: f32, v: f32, ray: &Ray) -> bool {
        !self.alpha_tested() || scene.alpha_passes(self.inst(), self.prim, u, v, ray)
    }
}

/// Takes the accepted lanes of one packet test in lane order into the nearest hit so far, shrinking
/// `t_max` as it goes so that later, farther lanes drop out. Returns true when `any` and a lane was
/// accepted (an occlusion query is then answered).
// Plain arguments rather than a state struct: this is the innermost loop of both walks and the
// borrowed `t_max` stays in a register once inlined.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn take_lanes(
    any: bool,
    h: &Hits,
    mut mask: u32,
    id_of: impl Fn(usize) -> TriId,
    scene: &Scene,
    ray: &Ray,
    t_max: &mut f32,
    best: &mut Option<Hit>,
) -> bool {
    while mask != 0 {
        let lane = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        if h.t[lane] >= *t_max {
            continue;
        }
        let id = id_of(lane);
        if !id.accepts(scene, h.u[lane], h.v[lane], ray) {
            continue;
        }
        *t_max = h.t[lane];
        *best = Some(Hit {
            t: h.t[lane],
            u: h.u[lane],
            v: h.v[lane],
            inst: id.inst(),
            prim: id.prim,
        });
        if any {
            return true;
        }
    }
    false
}

/// World-space vertices of every triangle of every instance not `skip`ped, and their identities,
/// in instance order. Moving instances must be skipped (they have no single world position).
pub fn flatten(scene: &Scene, skip: &[bool]) -> (Vec<[Vec3; 3]>, Vec<TriId>) {
    let mut tris = Vec::with_capacity(scene.triangle_count());
    let mut ids = Vec::with_capacity(tris.capacity());
    let kept: Vec<u32> = (0..scene.instances.len() as u32)
        .filter(|&i| !skip[i as usize])
        .collect();
    let mesh_of = |i: u32| &scene.meshes[scene.instances[i as usize].mesh as usize];
    // A large mesh is spread over the threads vertex by vertex; a run of small ones instance by
    // instance (a trip through the thread pool per 4-triangle instance made 100k of them take 2 s).
    let large = |i: u32| mesh_of(i).indices.len() >= SPREAD_TRIANGLES;
    let mut k = 0;
    while k < kept.len() {
        let first = kept[k];
        let spread = large(first);
        let end = if spread {
            k + 1
        } else {
            k + kept[k..]
                .iter()
                .position(|&i| large(i))
                .unwrap_or(kept.len() - k)
        };
        let run = &kept[k..end];
        if spread {
            let inst = &scene.instances[first as usize];
            let mesh = mesh_of(first);
            let world: Vec<Vec3> = mesh
                .positions
                .par_iter()
                .map(|&p| inst.to_world.transform_point3(p))
                .collect();
            tris.par_extend(
                mesh.indices
                    .par_iter()
                    .map(|idx| idx.map(|v| world[v as usize])),
            );
        } else {
            tris.par_extend(run.par_iter().flat_map_iter(|&i| {
                let inst = &scene.instances[i as usize];
                let mesh = mesh_of(i);
                mesh.indices.iter().map(move |idx| {
                    idx.map(|v| inst.to_world.transform_point3(mesh.positions[v as usize]))
                })
            }));
        }
        for &i in run {
            debug_assert!(
                scene.instances[i as usize].motion.is_none(),
                "a moving instance cannot be flattened"
            );
            let alpha = scene.mesh_needs_alpha_test(scene.instances[i as usize].mesh);
            ids.extend((0..mesh_of(i).indices.len() as u32).map(|p| TriId::new(i, p, alpha)));
        }
        k = end;
    }
    (tris, ids)
}

/// Meshes with at least this many triangles are flattened with all threads on the one mesh.
const SPREAD_TRIANGLES: usize = 4096;
