//! The accelerator as a renderer queries it ray by ray: Embree's queries called directly, so that
//! they inline into the path loop, and every other backend through its `Accel` trait object.

use super::Accel;
use crate::geometry::{Hit, Ray};

/// A backend for per-ray queries. Through the trait object each closest hit came back as an
/// `Option<Hit>` in memory, written in narrow stores and read in wide loads (a store-forwarding
/// stall a ray); matched here, Embree's wrapper inlines. Byte-identical, and at most 1% faster
/// (bunny-cornell 1.41 -> 1.40 s, many-emitters 1.40 -> 1.39 s, helmet-env 1.60 -> 1.61 s; one
/// thread, medians of five alternated runs).
#[derive(Clone, Copy)]
pub enum Tracer<'a> {
    #[cfg(feature = "embree")]
    Embree(&'a super::embree::EmbreeAccel),
    Any(&'a dyn Accel),
}

impl<'a> Tracer<'a> {
    pub fn new(accel: &'a dyn Accel) -> Self {
        #[cfg(feature = "embree")]
        if let Some(e) = accel.as_embree() {
            return Self::Embree(e);
        }
        Self::Any(accel)
    }

    /// The accelerator behind it.
    pub fn accel(&self) -> &'a dyn Accel {
        match *self {
            #[cfg(feature = "embree")]
            Self::Embree(e) => e,
            Self::Any(a) => a,
        }
    }

    #[inline(always)]
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        match self {
            #[cfg(feature = "embree")]
            Self::Embree(e) => e.intersect(ray),
            Self::Any(a) => a.intersect(ray),
        }
    }

    #[inline(always)]
    pub fn occluded(&self, ray: &Ray) -> bool {
        match self {
            #[cfg(feature = "embree")]
            Self::Embree(e) => e.occluded(ray),
            Self::Any(a) => a.occluded(ray),
        }
    }

    pub fn intersect_many(&self, rays: &[Ray], out: &mut [Option<Hit>]) {
        self.accel().intersect_many(rays, out);
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::{Mat4, Vec3};

    use super::*;
    use crate::accel::testing::{down, quad, scene_with};
    use crate::accel::{build, Backend};
    use crate::scene::{Instance, Material};

    /// Each backend answers through the tracer as through its trait object, Embree by its own arm.
    #[test]
    fn the_tracer_answers_as_the_backend() {
        let scene = scene_with(
            vec![quad()],
            vec![Instance::new(0, Mat4::IDENTITY)],
            vec![Material::default()],
        );
        for backend in [Backend::Embree, Backend::Bvh, Backend::Grid] {
            let Ok(accel) = build(Arc::clone(&scene), backend) else {
                continue;
            };
            let tracer = Tracer::new(accel.as_ref());
            #[cfg(feature = "embree")]
            assert_eq!(
                matches!(tracer, Tracer::Embree(_)),
                backend == Backend::Embree,
                "{backend:?}"
            );
            let mut hits = 0;
            for k in 0..32 {
                let ray = down(Vec3::new(k as f32 / 16.0 - 0.5, 0.3, 1.0));
                let hit = tracer.intersect(&ray);
                hits += hit.is_some() as usize;
                assert_eq!(hit, accel.intersect(&ray), "{backend:?}, ray {k}");
                assert_eq!(tracer.occluded(&ray), accel.occluded(&ray));
                assert_eq!(tracer.occluded(&ray), hit.is_some());
            }
            // The rays cross the quad's edge: both answers are exercised.
            assert!((1..32).contains(&hits), "{backend:?}: {hits} hits");
        }
    }
}
