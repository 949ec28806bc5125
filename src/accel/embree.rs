//! Embree 4 backend: builds one Embree scene over a glint `Scene` and answers `Accel` queries with it.
//! Meshes placed once are flattened into world space; meshes placed more often become instanced child scenes.
//!
//! ABI note (see shared/EMBREE.md, section 3): `embree4-sys` 0.0.12 carries Embree 4.2 headers while the
//! library loaded is 4.4, whose `RTCHit` is longer (`instPrimID`). Every ray-hit handed to Embree is
//! therefore a padded [`RayHit`], and the intersect/occluded arguments are always NULL (the query
//! context differs in size between the two versions). All `unsafe` of the crate's Embree use lives here.

use std::cell::Cell;
use std::ffi::{c_char, c_int, c_void, CStr};
use std::mem::size_of;
use std::ptr;
use std::sync::atomic::{AtomicIsize, Ordering};
use std::sync::{Arc, Mutex};

use embree4_sys as sys;

use super::{Accel, AccelError};
use crate::csg::CsgObject;
use crate::geometry::{Hit, Ray, CSG_BIT};
use crate::scene::{Mesh, Scene};

/// `RTC_INVALID_GEOMETRY_ID`: the geomID/instID of "no hit" / "not inside an instance".
const INVALID_ID: u32 = sys::RTC_INVALID_GEOMETRY_ID;

/// An `RTCRayHit` with room for the fields Embree 4.4 appends (`RTCRayHit` is 80 bytes in the 4.2
/// bindings, 96 in the 4.4 library, which writes `instPrimID` at bytes 80..84 on every hit).
/// Only pointers to the whole wrapper are handed to Embree.
#[repr(C, align(16))]
struct RayHit {
    rh: sys::RTCRayHit,
    _pad: [u32; 4],
}

/// Eight `RTCRayHit`s in Embree's SOA packet, with room for the eight `instPrimID` lanes 4.4
/// appends (640 bytes in the bindings, 672 in the library).
#[repr(C, align(32))]
struct RayHit8 {
    rh: sys::RTCRayHit8,
    _pad: [u32; 8],
}

/// The active lanes of an 8-wide query (Embree needs the mask 32-byte aligned).
#[repr(C, align(32))]
struct Valid8([i32; 8]);

// The layout the library expects: 96-byte ray-hits, and a 48-byte RTCRay (unchanged since 4.0).
const _: () = assert!(size_of::<RayHit>() == 96);
const _: () = assert!(size_of::<RayHit8>() == 672);
const _: () = assert!(size_of::<sys::RTCRay>() == 48);
const _: () = assert!(size_of::<sys::RTCRayHit>() == 80);

/// Embree's ray for `ray`, tagged with `id` (the index of the world ray the alpha filter should use).
///
/// Embree accepts hits with `t` in `(tnear, tfar]`, glint in `(t_min, t_max)`: `tfar` is the float just
/// below `t_max` so both backends agree at the boundary (`inf` becomes `f32::MAX`).
fn rtc_ray(ray: &Ray, id: u32) -> sys::RTCRay {
    sys::RTCRay {
        org_x: ray.o.x,
        org_y: ray.o.y,
        org_z: ray.o.z,
        tnear: ray.t_min,
        dir_x: ray.d.x,
        dir_y: ray.d.y,
        dir_z: ray.d.z,
        time: ray.time,
        tfar: ray.t_max.next_down(),
        mask: u32::MAX,
        id,
        flags: 0,
    }
}

impl RayHit {
    fn new(ray: &Ray, id: u32) -> Self {
        Self {
            rh: sys::RTCRayHit {
                ray: rtc_ray(ray, id),
                hit: sys::RTCHit {
                    Ng_x: 0.0,
                    Ng_y: 0.0,
                    Ng_z: 0.0,
                    u: 0.0,
                    v: 0.0,
                    primID: INVALID_ID,
                    geomID: INVALID_ID,
                    instID: [INVALID_ID; 1],
                },
            },
            _pad: [0; 4],
        }
    }

    fn hit(&self, csg_base: u32) -> Option<Hit> {
        let h = &self.rh.hit;
        hit_of(
            (h.geomID, h.instID[0], h.primID),
            (self.rh.ray.tfar, h.u, h.v),
            csg_base,
        )
    }
}

impl RayHit8 {
    /// An empty packet.
    fn zeroed() -> Self {
        // SAFETY: RTCRayHit8 is plain f32/u32 arrays, for which all-zero bytes are valid.
        unsafe { std::mem::zeroed() }
    }

    /// Loads up to eight `rays` (ids `first + lane`) into the packet, in place (returned, the
    /// 672-byte packet was copied once more: 1-4% of a render); returns the active lanes, the
    /// lanes past the rays inactive.
    fn load(&mut self, rays: &[Ray], first: u32) -> Valid8 {
        let mut valid = Valid8([0; 8]);
        for (lane, ray) in rays.iter().enumerate().take(8) {
            let r = rtc_ray(ray, first + lane as u32);
            let (q, h) = (&mut self.rh.ray, &mut self.rh.hit);
            (q.org_x[lane], q.org_y[lane], q.org_z[lane]) = (r.org_x, r.org_y, r.org_z);
            (q.dir_x[lane], q.dir_y[lane], q.dir_z[lane]) = (r.dir_x, r.dir_y, r.dir_z);
            (q.tnear[lane], q.tfar[lane], q.time[lane]) = (r.tnear, r.tfar, r.time);
            (q.mask[lane], q.id[lane], q.flags[lane]) = (r.mask, r.id, r.flags);
            (h.primID[lane], h.geomID[lane], h.instID[0][lane]) =
                (INVALID_ID, INVALID_ID, INVALID_ID);
            valid.0[lane] = -1;
        }
        valid
    }

    fn hit(&self, lane: usize, csg_base: u32) -> Option<Hit> {
        let h = &self.rh.hit;
        hit_of(
            (h.geomID[lane], h.instID[0][lane], h.primID[lane]),
            (self.rh.ray.tfar[lane], h.u[lane], h.v[lane]),
            csg_base,
        )
    }
}

/// Our hit from Embree's answer: `(geomID, instID[0], primID)` and `(tfar, u, v)`. Top-level
/// geometry IDs are instance indices (see `build`): an instanced hit names its instance in
/// `instID[0]`, a flattened one in `geomID`; IDs from `csg_base` on are CSG objects (user
/// geometries), reported with `CSG_BIT`.
fn hit_of(
    (geom, inst, prim): (u32, u32, u32),
    (t, u, v): (f32, f32, f32),
    csg_base: u32,
) -> Option<Hit> {
    if geom == INVALID_ID {
        return None;
    }
    let inst = if inst != INVALID_ID {
        inst
    } else if geom >= csg_base {
        (geom - csg_base) | CSG_BIT
    } else {
        geom
    };
    Some(Hit {
        t,
        u,
        v,
        inst,
        prim,
    })
}

thread_local! {
    /// The world-space rays of the query running on this thread, for the alpha filter: inside an
    /// instance Embree hands the filter an object-space ray, but `Scene::alpha_passes` must see the
    /// world ray (stochastic blending hashes it) to agree with the BVH. Set only around a query.
    static WORLD_RAYS: Cell<(*const Ray, usize)> = const { Cell::new((ptr::null(), 0)) };
}

/// Publishes `rays` to this thread's alpha filter for the duration of `f`.
fn with_world_rays<R>(rays: &[Ray], f: impl FnOnce() -> R) -> R {
    /// Clears the slot even if `f` unwinds, so no dangling pointer is left behind.
    struct Reset((*const Ray, usize));
    impl Drop for Reset {
        fn drop(&mut self) {
            WORLD_RAYS.with(|w| w.set(self.0));
        }
    }
    let _reset = Reset(WORLD_RAYS.with(|w| w.replace((rays.as_ptr(), rays.len()))));
    f()
}

/// Intersection and occlusion filter for geometries whose material needs an alpha test: rejects
/// (clears `valid`) every candidate hit that `Scene::alpha_passes` refuses. Written for any `N`.
///
/// # Safety
/// Called by Embree only, with the arguments of a filter callback; the geometry user pointer is the
/// `Scene` owned (through an `Arc`) by the `EmbreeAccel` being queried.
unsafe extern "C" fn alpha_filter(args: *const sys::RTCFilterFunctionNArguments) {
    // SAFETY: Embree passes a valid argument struct; the user pointer was set in `triangles` to the
    // scene kept alive by the accelerator for as long as queries can run.
    let args = unsafe { &*args };
    // SAFETY: as above.
    let scene = unsafe { &*(args.geometryUserPtr as *const Scene) };
    let n = args.N as usize;
    // RTCHitN and RTCRayN are SOA blocks of N lanes, 4 bytes a field. RTCHitN: Ng_x, Ng_y, Ng_z, u, v,
    // primID, geomID, instID[0] (the same up to here in 4.2 and 4.4). RTCRayN: org_x, org_y, org_z,
    // tnear, dir_x, dir_y, dir_z, time, tfar, mask, id, flags.
    let hit = args.hit as *const u32;
    let ray = args.ray as *const u32;
    let (world_ptr, world_len) = WORLD_RAYS.with(Cell::get);
    for lane in 0..n {
        // SAFETY: `valid`, `hit` and `ray` each hold N lanes per field, per Embree's filter contract;
        // the world-ray slice was published by `with_world_rays` on this thread and outlives the query.
        unsafe {
            let valid = args.valid.add(lane);
            if *valid == 0 {
                continue;
            }
            let field = |base: *const u32, f: usize| *base.add(f * n + lane);
            let u = f32::from_bits(field(hit, 3));
            let v = f32::from_bits(field(hit, 4));
            let prim = field(hit, 5);
            let geom = field(hit, 6);
            let inst0 = field(hit, 7);
            let inst = if inst0 != INVALID_ID { inst0 } else { geom };
            let id = field(ray, 10) as usize;
            let world = if world_len == 1 {
                *world_ptr
            } else if id < world_len {
                *world_ptr.add(id)
            } else {
                // Not reachable through this module's queries; the ray given is right at least for
                // flattened (world-space) geometry.
                let f = |k| f32::from_bits(field(ray, k));
                Ray {
                    o: glam::Vec3::new(f(0), f(1), f(2)),
                    d: glam::Vec3::new(f(4), f(5), f(6)),
                    t_min: f(3),
                    t_max: f(8),
                    seed: 0,
                    time: f(7),
                }
            };
            if !scene.alpha_passes(inst, prim, u, v, &world) {
                *valid = 0;
            }
        }
    }
}

/// A CSG callback's arguments and the `CsgObject` its geometry carries (`user` picks the user
/// pointer out of the arguments).
///
/// # Safety
/// `args` points to a callback's arguments from Embree, for a geometry made in `populate`: its
/// user pointer is a `CsgObject` that outlives the geometry.
unsafe fn csg_args<'a, A>(
    args: *const A,
    user: impl Fn(&A) -> *mut c_void,
) -> (&'a A, &'a CsgObject) {
    // SAFETY: per the function's contract.
    unsafe {
        let a = &*args;
        (a, &*(user(a) as *const CsgObject))
    }
}

/// The lanes of a packet of `n` that Embree marks active.
///
/// # Safety
/// `valid` must hold `n` lanes and stay readable while the iterator runs.
unsafe fn valid_lanes(valid: *const c_int, n: usize) -> impl Iterator<Item = usize> {
    // SAFETY: per the function's contract.
    (0..n).filter(move |&lane| unsafe { *valid.add(lane) } != 0)
}

/// Bounds callback of a CSG user geometry (one primitive: the whole object).
///
/// # Safety
/// Called by Embree only; the user pointer is the `CsgObject` set in `populate`.
unsafe extern "C" fn csg_bounds(args: *const sys::RTCBoundsFunctionArguments) {
    // SAFETY: Embree passes valid arguments of the geometry `populate` made.
    let (args, object) = unsafe { csg_args(args, |a| a.geometryUserPtr) };
    let b = object.step_bounds(args.timeStep as usize);
    // SAFETY: `bounds_o` points to one RTCBounds for Embree to read.
    unsafe {
        *args.bounds_o = sys::RTCBounds {
            lower_x: b.min.x,
            lower_y: b.min.y,
            lower_z: b.min.z,
            align0: 0.0,
            upper_x: b.max.x,
            upper_y: b.max.y,
            upper_z: b.max.z,
            align1: 0.0,
        };
    }
}

/// The world ray in lane `lane` of an `RTCRayN` of `n` lanes (SOA, 4 bytes a field: org_x, org_y,
/// org_z, tnear, dir_x, dir_y, dir_z, time, tfar, ...). Embree hits are in `(tnear, tfar]`, CSG hits in
/// `(t_min, t_max)`: `t_max` is the float after `tfar`.
///
/// # Safety
/// `ray` must hold `n` lanes of at least 9 fields.
unsafe fn lane_ray(ray: *const u32, n: usize, lane: usize) -> Ray {
    // SAFETY: per the function's contract.
    let f = |k: usize| f32::from_bits(unsafe { *ray.add(k * n + lane) });
    Ray {
        o: glam::Vec3::new(f(0), f(1), f(2)),
        d: glam::Vec3::new(f(4), f(5), f(6)),
        t_min: f(3),
        t_max: f(8).next_up(),
        seed: 0,
        time: f(7),
    }
}

/// Intersect callback of a CSG user geometry, for any packet width `N`: writes the closest CSG hit
/// into the lanes' `RTCRayHitN`. Fields up to `instID[0]` have the same SOA layout in 4.2 and 4.4
/// (4.4's `instPrimID` follows them and is left alone: glint never reads it).
///
/// # Safety
/// Called by Embree only, with an intersect callback's arguments; the user pointer is the
/// `CsgObject` set in `populate`.
unsafe extern "C" fn csg_intersect(args: *const sys::RTCIntersectFunctionNArguments) {
    // SAFETY: Embree passes valid arguments of the geometry `populate` made.
    let (args, object) = unsafe { csg_args(args, |a| a.geometryUserPtr) };
    let n = args.N as usize;
    let ray = args.rayhit as *mut u32;
    // RTCRayHitN: 12 ray fields of n lanes, then the hit: Ng_x, Ng_y, Ng_z, u, v, primID, geomID,
    // instID[0].
    // SAFETY: the hit block starts right after the ray block of the same RTCRayHitN.
    let hit = unsafe { ray.add(12 * n) };
    // SAFETY: `valid` has n lanes.
    for lane in unsafe { valid_lanes(args.valid, n) } {
        // SAFETY: the ray and hit blocks hold n lanes of each field, and the wrapper handed to
        // Embree (RayHit / padded packets) covers them.
        unsafe {
            let r = lane_ray(ray, n, lane);
            if let Some((t, surface)) = object.intersect(&r) {
                let put = |base: *mut u32, k: usize, v: u32| *base.add(k * n + lane) = v;
                put(ray, 8, t.to_bits());
                put(hit, 0, 0f32.to_bits());
                put(hit, 1, 0f32.to_bits());
                put(hit, 2, 0f32.to_bits());
                put(hit, 3, 0f32.to_bits());
                put(hit, 4, 0f32.to_bits());
                put(hit, 5, surface);
                put(hit, 6, args.geomID);
                put(hit, 7, INVALID_ID);
            }
        }
    }
}

/// Occluded callback of a CSG user geometry, for any `N`: sets `tfar` to -inf where it is hit.
///
/// # Safety
/// As for `csg_intersect`.
unsafe extern "C" fn csg_occluded(args: *const sys::RTCOccludedFunctionNArguments) {
    // SAFETY: Embree passes valid arguments of the geometry `populate` made.
    let (args, object) = unsafe { csg_args(args, |a| a.geometryUserPtr) };
    let n = args.N as usize;
    let ray = args.ray as *mut u32;
    // SAFETY: `valid` has n lanes.
    for lane in unsafe { valid_lanes(args.valid, n) } {
        // SAFETY: the ray block holds n lanes.
        unsafe {
            if object.occluded(&lane_ray(ray, n, lane)) {
                *ray.add(8 * n + lane) = f32::NEG_INFINITY.to_bits();
            }
        }
    }
}

/// Collects Embree's error messages (the 4.2 API has no "last error message" call).
///
/// # Safety
/// Called by Embree only; `user` is the `Mutex<Vec<String>>` boxed in the accelerator, which outlives
/// the device.
unsafe extern "C" fn on_error(user: *mut c_void, code: sys::RTCError, msg: *const c_char) {
    let text = if msg.is_null() {
        String::new()
    } else {
        // SAFETY: Embree passes a NUL-terminated message valid for the duration of the call.
        unsafe { CStr::from_ptr(msg) }
            .to_string_lossy()
            .into_owned()
    };
    // SAFETY: see the function's contract: `user` points to a live Mutex<Vec<String>>.
    let sink = unsafe { &*(user as *const Mutex<Vec<String>>) };
    if let Ok(mut v) = sink.lock() {
        v.push(format!("{code:?}: {text}"));
    }
}

/// Embree's memory monitor: keeps a running total of the bytes the device has allocated.
unsafe extern "C" fn on_memory(user: *mut c_void, bytes: isize, _post: bool) -> bool {
    // SAFETY: `user` is the `AtomicIsize` boxed in the `EmbreeAccel` that owns the device, which
    // outlives every allocation callback of that device.
    let total = unsafe { &*(user as *const AtomicIsize) };
    total.fetch_add(bytes, Ordering::Relaxed);
    true
}

/// Intel Embree 4 over the scene's instances.
/// Which triangle test Embree's scenes use.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Robustness {
    /// `RTC_SCENE_FLAG_ROBUST`: watertight, as the Rust backends are.
    Robust,
    /// Embree's default, faster test, which lets rays through exactly at shared edges and vertices.
    Fast,
}

pub struct EmbreeAccel {
    device: sys::RTCDevice,
    robustness: Robustness,
    /// The top-level scene; its geometry IDs are instance indices.
    top: sys::RTCScene,
    /// Object-space scenes of meshes used by several instances (released in `Drop`).
    children: Vec<sys::RTCScene>,
    /// Whether any geometry has the alpha filter, i.e. whether queries must publish their world rays.
    filtered: bool,
    /// Geometry ID of CSG object 0 (the number of instances); object `k` has ID `csg_base + k`.
    csg_base: u32,
    /// Messages from Embree's error callback; boxed so the pointer given to Embree stays put.
    errors: Box<Mutex<Vec<String>>>,
    /// Bytes the device holds, from its memory monitor; boxed for the same reason.
    memory: Box<AtomicIsize>,
    /// The scene the hits refer to; also the user data of filtered geometries, so it must outlive them.
    scene: Arc<Scene>,
}

// SAFETY: the raw handles are only used for queries after `build` committed every scene; Embree
// documents committed scenes as safe to query from any number of threads at once, and the device and
// scenes are reference counted internally. Nothing is mutated after `build` (the error sink is a Mutex).
unsafe impl Send for EmbreeAccel {}
// SAFETY: as above: `&self` methods only run concurrent read-only queries on committed scenes.
unsafe impl Sync for EmbreeAccel {}

impl EmbreeAccel {
    /// Builds robust Embree scenes over `scene`: one device, one committed top-level scene.
    pub fn build(scene: Arc<Scene>) -> Result<Self, AccelError> {
        Self::build_with(scene, Robustness::Robust)
    }

    /// `build` with the chosen triangle test.
    pub fn build_with(scene: Arc<Scene>, robustness: Robustness) -> Result<Self, AccelError> {
        // SAFETY: a NULL config asks for the default device; a NULL result is handled below.
        let device = unsafe { sys::rtcNewDevice(ptr::null()) };
        if device.is_null() {
            // SAFETY: with a NULL device, rtcGetDeviceError reports the thread's creation error.
            let code = unsafe { sys::rtcGetDeviceError(ptr::null_mut()) };
            return Err(AccelError::Embree(format!(
                "cannot create a device ({code:?})"
            )));
        }
        // From here on `Drop` releases whatever exists, also on the error paths.
        let mut accel = Self {
            device,
            robustness,
            top: ptr::null_mut(),
            children: Vec::new(),
            filtered: false,
            csg_base: 0,
            errors: Box::new(Mutex::new(Vec::new())),
            memory: Box::new(AtomicIsize::new(0)),
            scene,
        };
        let sink = &*accel.errors as *const Mutex<Vec<String>> as *mut c_void;
        // SAFETY: `device` is live; `sink` points into a Box owned by `accel`, which releases the
        // device in `Drop` before the Box is freed.
        unsafe { sys::rtcSetDeviceErrorFunction(device, Some(on_error), sink) };
        let memory = &*accel.memory as *const AtomicIsize as *mut c_void;
        // SAFETY: as for the error sink: the Box outlives the device that calls back into it.
        unsafe { sys::rtcSetDeviceMemoryMonitorFunction(device, Some(on_memory), memory) };
        accel.check("creating the device")?;
        accel.populate()?;
        Ok(accel)
    }

    /// Fills and commits the top-level scene (and child scenes of shared meshes).
    fn populate(&mut self) -> Result<(), AccelError> {
        let scene = Arc::clone(&self.scene);
        // Owned by `self` and released in `Drop`.
        self.top = self.new_scene()?;
        self.add_instances(&scene)?;
        self.csg_base = u32::try_from(scene.instances.len())
            .map_err(|_| AccelError::Embree("too many instances".into()))?;
        for (k, object) in scene.csg.iter().enumerate() {
            let id = self
                .csg_base
                .checked_add(k as u32)
                .filter(|&id| id != INVALID_ID)
                .ok_or_else(|| AccelError::Embree("too many geometries".into()))?;
            let geom = self.csg_geometry(object)?;
            self.attach(geom, id, "attaching a CSG geometry")?;
        }
        // SAFETY: the top scene is live and fully populated.
        unsafe { sys::rtcCommitScene(self.top) };
        self.check("committing the scene")
    }

    /// One geometry per non-empty instance, its ID the instance index (so hits name their
    /// instance without a lookup table).
    fn add_instances(&mut self, scene: &Scene) -> Result<(), AccelError> {
        let mut uses = vec![0usize; scene.meshes.len()];
        for inst in &scene.instances {
            uses[inst.mesh as usize] += 1;
        }
        // Child scene of each shared mesh, built on first use.
        let mut child_of: Vec<Option<sys::RTCScene>> = vec![None; scene.meshes.len()];
        for (index, inst) in scene.instances.iter().enumerate() {
            let m = inst.mesh as usize;
            let mesh = &scene.meshes[m];
            if mesh.indices.is_empty() || mesh.positions.is_empty() {
                continue; // nothing to hit; Embree would reject empty buffers
            }
            let alpha = scene.mesh_needs_alpha_test(inst.mesh);
            self.filtered |= alpha;
            let id = u32::try_from(index)
                .map_err(|_| AccelError::Embree("too many instances".into()))?;
            // A moving instance is always an Embree instance, with one transform per time step that
            // Embree interpolates linearly at the ray's time (as `Motion::at` does).
            let geom = if uses[m] == 1 && inst.motion.is_none() {
                // Cheaper than an instance: no transform during traversal, one BVH level less.
                self.triangles(mesh, Some(&inst.to_world), alpha)?
            } else {
                let child = match child_of[m] {
                    Some(c) => c,
                    None => *child_of[m].insert(self.child_scene(mesh, alpha)?),
                };
                let steps = match &inst.motion {
                    Some(motion) => motion.steps.as_slice(),
                    None => std::slice::from_ref(&inst.to_world),
                };
                self.instance(child, steps)
            };
            self.check("creating a geometry")?;
            self.attach(geom, id, "attaching a geometry")?;
        }
        Ok(())
    }

    /// A committed instance of the committed `child`, one transform per time step (NULL when
    /// Embree fails; the caller checks). The caller owns the returned reference.
    fn instance(&self, child: sys::RTCScene, steps: &[glam::Mat4]) -> sys::RTCGeometry {
        // SAFETY: device and child scene are live and the child is committed; the step count is
        // set before the per-step transforms, and Embree copies the 16 floats of each
        // column-major matrix during its call.
        unsafe {
            let g = sys::rtcNewGeometry(self.device, sys::RTCGeometryType::INSTANCE);
            if !g.is_null() {
                sys::rtcSetGeometryInstancedScene(g, child);
                sys::rtcSetGeometryTimeStepCount(g, steps.len() as u32);
                for (k, step) in steps.iter().enumerate() {
                    let cols = step.to_cols_array();
                    sys::rtcSetGeometryTransform(
                        g,
                        k as u32,
                        sys::RTCFormat::FLOAT4X4_COLUMN_MAJOR,
                        cols.as_ptr().cast(),
                    );
                }
                sys::rtcCommitGeometry(g);
            }
            g
        }
    }

    /// A committed user geometry whose callbacks trace `object`. The caller owns the returned
    /// reference.
    fn csg_geometry(&self, object: &CsgObject) -> Result<sys::RTCGeometry, AccelError> {
        // SAFETY: the device is live; the user pointer is a CsgObject inside the scene that `self`
        // keeps alive (through its Arc) and never mutates, so it outlives every callback.
        let geom = unsafe {
            let g = sys::rtcNewGeometry(self.device, sys::RTCGeometryType::USER);
            if !g.is_null() {
                sys::rtcSetGeometryUserPrimitiveCount(g, 1);
                // A moving object gets its bounds per time step; its callbacks read ray times.
                sys::rtcSetGeometryTimeStepCount(g, object.time_steps() as u32);
                sys::rtcSetGeometryUserData(g, object as *const CsgObject as *mut c_void);
                sys::rtcSetGeometryBoundsFunction(g, Some(csg_bounds), ptr::null_mut());
                sys::rtcSetGeometryIntersectFunction(g, Some(csg_intersect));
                sys::rtcSetGeometryOccludedFunction(g, Some(csg_occluded));
                sys::rtcCommitGeometry(g);
            }
            g
        };
        if geom.is_null() {
            return Err(self.error("creating a CSG user geometry"));
        }
        self.check("creating a CSG user geometry")?;
        Ok(geom)
    }

    /// Attaches `geom` to the top scene under `id`, handing it our reference.
    fn attach(&self, geom: sys::RTCGeometry, id: u32, what: &str) -> Result<(), AccelError> {
        // SAFETY: `geom` is a live, committed geometry (checked by the caller); the scene takes its
        // own reference, so ours is released right away.
        unsafe {
            sys::rtcAttachGeometryByID(self.top, geom, id);
            sys::rtcReleaseGeometry(geom);
        }
        self.check(what)
    }

    /// A committed object-space scene holding one mesh, for instancing; owned by `self.children`.
    fn child_scene(&mut self, mesh: &Mesh, alpha: bool) -> Result<sys::RTCScene, AccelError> {
        // Recorded in `children` at once so `Drop` releases it on every path.
        let child = self.new_scene()?;
        self.children.push(child);
        let geom = self.triangles(mesh, None, alpha)?;
        // SAFETY: `child` and `geom` are live; the scene keeps its own reference to the geometry.
        unsafe {
            sys::rtcAttachGeometry(child, geom);
            sys::rtcReleaseGeometry(geom);
            sys::rtcCommitScene(child);
        }
        self.check("committing a child scene")?;
        Ok(child)
    }

    /// An empty scene, in robust mode unless `Robustness::Fast` was asked for; the caller owns the
    /// handle.
    ///
    /// Without `ROBUST`, Embree's fast triangle test lets about 2% of rays aimed exactly at shared
    /// edges and vertices of a closed mesh slip through (tests/robustness.rs); glint promises
    /// watertightness like the BVH's, at a small cost in speed.
    fn new_scene(&self) -> Result<sys::RTCScene, AccelError> {
        // SAFETY: the device is live; a NULL scene is reported as an error.
        let scene = unsafe { sys::rtcNewScene(self.device) };
        if scene.is_null() {
            return Err(self.error("creating a scene"));
        }
        if self.robustness == Robustness::Robust {
            // SAFETY: `scene` is live and not yet committed.
            unsafe { sys::rtcSetSceneFlags(scene, sys::RTCSceneFlags::ROBUST) };
        }
        if let Err(e) = self.check("creating a scene") {
            // SAFETY: `scene` is ours and referenced nowhere else.
            unsafe { sys::rtcReleaseScene(scene) };
            return Err(e);
        }
        Ok(scene)
    }

    /// A committed triangle geometry of `mesh`, its vertices moved by `to_world` when given. The
    /// caller owns the returned reference.
    fn triangles(
        &self,
        mesh: &Mesh,
        to_world: Option<&glam::Mat4>,
        alpha: bool,
    ) -> Result<sys::RTCGeometry, AccelError> {
        // SAFETY: the device is live. Each buffer returned by rtcSetNewGeometryBuffer is checked for
        // NULL and holds `count` items of `stride` bytes (Embree adds the tail padding its SIMD loads
        // need), 4-byte aligned; we write exactly that many f32/u32 triples.
        let geom = unsafe {
            let geom = sys::rtcNewGeometry(self.device, sys::RTCGeometryType::TRIANGLE);
            if geom.is_null() {
                return Err(self.error("creating a triangle geometry"));
            }
            let verts = sys::rtcSetNewGeometryBuffer(
                geom,
                sys::RTCBufferType::VERTEX,
                0,
                sys::RTCFormat::FLOAT3,
                12,
                mesh.positions.len(),
            ) as *mut [f32; 3];
            let tris = sys::rtcSetNewGeometryBuffer(
                geom,
                sys::RTCBufferType::INDEX,
                0,
                sys::RTCFormat::UINT3,
                12,
                mesh.indices.len(),
            ) as *mut [u32; 3];
            if verts.is_null() || tris.is_null() {
                sys::rtcReleaseGeometry(geom);
                return Err(self.error("allocating geometry buffers"));
            }
            for (i, &p) in mesh.positions.iter().enumerate() {
                let p = to_world.map_or(p, |m| m.transform_point3(p));
                verts.add(i).write(p.to_array());
            }
            ptr::copy_nonoverlapping(mesh.indices.as_ptr(), tris, mesh.indices.len());
            if alpha {
                sys::rtcSetGeometryUserData(geom, Arc::as_ptr(&self.scene) as *mut c_void);
                sys::rtcSetGeometryIntersectFilterFunction(geom, Some(alpha_filter));
                sys::rtcSetGeometryOccludedFilterFunction(geom, Some(alpha_filter));
            }
            sys::rtcCommitGeometry(geom);
            geom
        };
        if let Err(e) = self.check("building a triangle geometry") {
            // SAFETY: `geom` is live and ours; nothing else references it yet.
            unsafe { sys::rtcReleaseGeometry(geom) };
            return Err(e);
        }
        Ok(geom)
    }

    /// Ok unless Embree reported an error (by code on this thread, or through the callback).
    fn check(&self, what: &str) -> Result<(), AccelError> {
        // SAFETY: the device is live for the lifetime of `self`.
        let code = unsafe { sys::rtcGetDeviceError(self.device) };
        let pending = self.errors.lock().is_ok_and(|v| !v.is_empty());
        if code == sys::RTCError::NONE && !pending {
            return Ok(());
        }
        Err(self.error(what))
    }

    /// An `AccelError` for `what`, with (and clearing) the messages Embree sent.
    fn error(&self, what: &str) -> AccelError {
        let msgs = self
            .errors
            .lock()
            .map(|mut v| std::mem::take(&mut *v).join("; "))
            .unwrap_or_default();
        AccelError::Embree(if msgs.is_empty() {
            format!("{what} failed")
        } else {
            format!("{what}: {msgs}")
        })
    }

    /// Runs `f` with this thread's world rays published when the scene has alpha-tested geometry.
    fn query<R>(&self, rays: &[Ray], f: impl FnOnce() -> R) -> R {
        if self.filtered {
            with_world_rays(rays, f)
        } else {
            f()
        }
    }

    /// Queries `rays` eight to a packet with `trace` and reads each lane's answer into `out` with
    /// `answer`; a ray's id is its index in `rays`, where the alpha filter finds the world ray.
    fn in_packets<T>(
        &self,
        rays: &[Ray],
        out: &mut [T],
        trace: impl Fn(&mut RayHit8, &Valid8),
        answer: impl Fn(&RayHit8, usize) -> T,
    ) {
        assert_eq!(rays.len(), out.len(), "one output slot per ray");
        self.query(rays, || {
            for (k, (rays, out)) in rays.chunks(8).zip(out.chunks_mut(8)).enumerate() {
                let mut p = RayHit8::zeroed();
                let valid = p.load(rays, 8 * k as u32);
                trace(&mut p, &valid);
                for (lane, slot) in out.iter_mut().enumerate() {
                    *slot = answer(&p, lane);
                }
            }
        });
    }

    fn intersect1(&self, rh: &mut RayHit) {
        // SAFETY: the top scene is committed; the pointer covers the whole padded 96-byte RayHit (the
        // 4.4 library writes past the 80-byte RTCRayHit of the bindings); NULL arguments are allowed.
        unsafe {
            sys::rtcIntersect1(
                self.top,
                (rh as *mut RayHit).cast::<sys::RTCRayHit>(),
                ptr::null_mut(),
            )
        };
    }

    fn intersect8(&self, p: &mut RayHit8, valid: &Valid8) {
        // SAFETY: the top scene is committed; the packet is the padded 672-byte RTCRayHit8 the 4.4
        // library writes, and the valid mask is 32-byte aligned; NULL arguments are allowed.
        unsafe {
            sys::rtcIntersect8(
                valid.0.as_ptr(),
                self.top,
                (p as *mut RayHit8).cast::<sys::RTCRayHit8>(),
                ptr::null_mut(),
            )
        };
    }

    fn occluded8(&self, p: &mut RayHit8, valid: &Valid8) {
        // SAFETY: the top scene is committed; an RTCRay8 (the same 384 bytes in 4.2 and 4.4) opens
        // the packet, and occlusion writes only its `tfar` lanes; the valid mask is 32-byte aligned;
        // NULL arguments are allowed.
        unsafe { sys::rtcOccluded8(valid.0.as_ptr(), self.top, &mut p.rh.ray, ptr::null_mut()) };
    }

    fn occluded1(&self, ray: &mut sys::RTCRay) {
        // SAFETY: the top scene is committed; RTCRay has the same 48-byte layout in 4.2 and 4.4 and
        // occlusion writes only `tfar`; NULL arguments are allowed.
        unsafe { sys::rtcOccluded1(self.top, ray, ptr::null_mut()) };
    }
}

impl Drop for EmbreeAccel {
    fn drop(&mut self) {
        // SAFETY: each handle is ours and released once; the top scene goes first (its instances hold
        // references to the children), the device last. `errors` and `scene` outlive these calls.
        unsafe {
            if !self.top.is_null() {
                sys::rtcReleaseScene(self.top);
            }
            for &c in &self.children {
                sys::rtcReleaseScene(c);
            }
            sys::rtcReleaseDevice(self.device);
        }
    }
}

impl Accel for EmbreeAccel {
    fn name(&self) -> &'static str {
        match self.robustness {
            Robustness::Robust => "embree",
            Robustness::Fast => "embree-fast",
        }
    }

    #[inline]
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let mut rh = RayHit::new(ray, 0);
        self.query(std::slice::from_ref(ray), || self.intersect1(&mut rh));
        rh.hit(self.csg_base)
    }

    /// Eight rays to a packet (`rtcIntersect8`).
    fn intersect_many(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        self.in_packets(
            rays,
            out,
            |p, valid| self.intersect8(p, valid),
            |p, lane| p.hit(lane, self.csg_base),
        );
    }

    #[inline]
    fn occluded(&self, ray: &Ray) -> bool {
        let mut r = rtc_ray(ray, 0);
        self.query(std::slice::from_ref(ray), || self.occluded1(&mut r));
        // Embree marks an occluded ray by setting tfar to -inf.
        r.tfar == f32::NEG_INFINITY
    }

    /// Eight rays to a packet (`rtcOccluded8`).
    fn occluded_many(&self, rays: &[Ray], out: &mut [bool]) {
        self.in_packets(
            rays,
            out,
            |p, valid| self.occluded8(p, valid),
            // Embree marks an occluded ray by setting tfar to -inf.
            |p, lane| p.rh.ray.tfar[lane] == f32::NEG_INFINITY,
        );
    }

    fn memory_bytes(&self) -> usize {
        self.memory.load(Ordering::Relaxed).max(0) as usize
    }

    fn as_embree(&self) -> Option<&EmbreeAccel> {
        Some(self)
    }
}

#[cfg(test)]
mod tests {
    // Queries are tested with every backend's in `accel::conformance`; here, Embree's own paths.
    use super::*;
    use crate::accel::testing::{
        alpha_quads, assert_batches_match_single, down, quad, scene_with as scene_of,
    };
    use crate::scene::{AlphaMode, Instance, Material};
    use glam::{Mat4, Vec3, Vec4};
    use rayon::prelude::*;

    fn build(s: Arc<Scene>) -> EmbreeAccel {
        EmbreeAccel::build(s).expect("embree builds")
    }

    /// Embree over one quad, the padded-struct tests' scene.
    fn one_quad() -> EmbreeAccel {
        build(scene_of(
            vec![quad()],
            vec![Instance::new(0, Mat4::IDENTITY)],
            vec![Material::default()],
        ))
    }

    /// The bytes of a plain-old-data value (f32/u32 fields, no padding holes of its own).
    fn bytes<T>(x: &T) -> Vec<u8> {
        // SAFETY: the callers' wrappers are f32/u32 arrays and fields throughout, every byte initialised.
        unsafe { std::slice::from_raw_parts((x as *const T).cast::<u8>(), size_of::<T>()) }.to_vec()
    }

    #[test]
    fn padded_rayhit_keeps_neighbour_intact() {
        let accel = one_quad();
        let ray = down(Vec3::new(0.7, 0.2, 1.0));
        let mut pair = [RayHit::new(&ray, 0), RayHit::new(&ray, 1)];
        pair[1]._pad = [0xDEAD_BEEF; 4];
        let before = bytes(&pair[1]);
        accel.intersect1(&mut pair[0]);
        assert!(pair[0].hit(u32::MAX).is_some(), "the triangle is hit");
        assert_eq!(
            before,
            bytes(&pair[1]),
            "a hit must not write into the next element"
        );
    }

    /// The same for packets: the 4.4 library writes eight `instPrimID` lanes past the bindings'
    /// 640-byte `RTCRayHit8`, into the wrapper's padding.
    #[test]
    fn padded_packet_keeps_neighbour_intact() {
        let accel = one_quad();
        let rays: Vec<Ray> = (0..8)
            .map(|k| down(Vec3::new(0.1 * k as f32 + 0.05, 0.2, 1.0)))
            .collect();
        let mut pair = [RayHit8::zeroed(), RayHit8::zeroed()];
        let valid = pair[0].load(&rays, 0);
        pair[1].load(&rays, 8);
        pair[1]._pad = [0xDEAD_BEEF; 8];
        let before = bytes(&pair[1]);
        let [first, _] = &mut pair;
        accel.intersect8(first, &valid);
        for (lane, ray) in rays.iter().enumerate() {
            assert!(first.hit(lane, u32::MAX).is_some(), "lane {lane} hits");
            assert_eq!(
                first.hit(lane, u32::MAX),
                accel.intersect(ray),
                "lane {lane}"
            );
        }
        assert_eq!(
            before,
            bytes(&pair[1]),
            "a hit must not write into the next packet"
        );
    }

    /// Batches publish all their world rays at once and the alpha filter finds each by ray id, also
    /// inside instances: they answer as single queries do (which `accel::conformance` checks).
    #[test]
    fn alpha_tested_batches_match_single_queries() {
        let mask = |alpha: f32| Material {
            alpha_mode: AlphaMode::Mask(0.5),
            base_color: Vec4::new(1.0, 1.0, 1.0, alpha),
            ..Default::default()
        };
        let blend = Material {
            alpha_mode: AlphaMode::Blend,
            base_color: Vec4::new(1.0, 1.0, 1.0, 0.5),
            ..Default::default()
        };
        for mat in [mask(0.2), mask(0.8), blend] {
            let accel = build(alpha_quads(mat));
            let rays: Vec<Ray> = (0..300)
                .map(|i| {
                    let x = (i % 3) as f32 * 10.0 + (i as f32 + 0.5) / 300.0;
                    let ray = down(Vec3::new(x, 0.9 * x.fract(), 1.0)).with_seed(i * 7919);
                    if i % 2 == 0 {
                        ray
                    } else {
                        Ray::segment(ray.o, ray.d, 1.5).with_seed(ray.seed)
                    }
                })
                .collect();
            assert_batches_match_single(&accel, &rays, "embree");
        }
    }

    #[test]
    fn rayon_matches_serial() {
        // A small field of quads, flattened and instanced, some rotated.
        let mut instances = vec![Instance::new(1, Mat4::IDENTITY)];
        for k in 0..20 {
            let f = k as f32;
            instances.push(Instance::new(
                0,
                Mat4::from_translation(Vec3::new(f * 0.3 - 3.0, f.sin(), f.cos()))
                    * Mat4::from_rotation_y(f * 0.7)
                    * Mat4::from_scale(Vec3::splat(1.0 + 0.1 * f)),
            ));
        }
        let accel = build(scene_of(
            vec![quad(), quad()],
            instances,
            vec![Material::default()],
        ));
        let mut state = 0x1234_5678_9ABC_DEF0u64;
        let mut rnd = move || {
            // splitmix64
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0
        };
        let rays: Vec<Ray> = (0..10_000)
            .map(|_| {
                let o = Vec3::new(rnd() * 4.0, rnd() * 4.0, rnd() * 4.0);
                let target = Vec3::new(rnd() * 3.0, rnd(), rnd());
                Ray::segment(o, target - o, 1.0 + rnd().abs())
            })
            .collect();
        let serial: Vec<_> = rays
            .iter()
            .map(|r| (accel.intersect(r), accel.occluded(r)))
            .collect();
        let parallel: Vec<_> = rays
            .par_iter()
            .map(|r| (accel.intersect(r), accel.occluded(r)))
            .collect();
        let bits = |v: &[(Option<Hit>, bool)]| -> Vec<_> {
            v.iter()
                .map(|(h, o)| {
                    (
                        h.map(|h| (h.t.to_bits(), h.u.to_bits(), h.v.to_bits(), h.inst, h.prim)),
                        *o,
                    )
                })
                .collect()
        };
        assert_eq!(bits(&serial), bits(&parallel));
        let hits = serial.iter().filter(|(h, _)| h.is_some()).count();
        assert!(hits > 100, "only {hits} hits: the test would prove little");
        // Any hit implies occlusion and vice versa.
        assert!(serial.iter().all(|(h, o)| h.is_some() == *o));
        let mut batch = vec![None; rays.len()];
        accel.intersect_many(&rays, &mut batch);
        let mut occluded = vec![false; rays.len()];
        accel.occluded_many(&rays, &mut occluded);
        assert_eq!(
            bits(
                &batch
                    .iter()
                    .zip(&occluded)
                    .map(|(h, &o)| (*h, o))
                    .collect::<Vec<_>>()
            ),
            bits(&serial)
        );
    }
}
