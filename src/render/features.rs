//! What one camera path tells the feature images (AOVs): the denoiser's albedo and normal at the first
//! non-specular vertex, and the camera ray's own hit (position, instance, material) for the others.

use glam::Vec3;

use super::surface::SurfaceInteraction;

/// The camera ray's hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FirstHit {
    pub p: Vec3,
    pub instance: u32,
    pub material: u32,
}

/// The features of one path, filled in by `Integrator::li_features` as the path goes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PathFeatures {
    /// Base colour of the first surface that is not a perfect mirror or clear glass: reflections
    /// and refractions show the albedo of what they reflect (as OIDN asks). 1 where the path left
    /// the scene first (its light is all illumination).
    pub albedo: Vec3,
    /// Shading normal there (facing the incoming ray), or that of the last smooth surface before
    /// the path left; zero when the camera ray hit nothing (OIDN's "no surface").
    pub normal: Vec3,
    pub first: Option<FirstHit>,
    /// A non-specular vertex has been reached: later vertices change nothing.
    settled: bool,
}

impl PathFeatures {
    /// The path reached `si` (at `bounce`).
    pub fn hit(&mut self, si: &SurfaceInteraction, bounce: u32) {
        if bounce == 0 {
            self.first = Some(FirstHit {
                p: si.p,
                instance: si.inst,
                material: si.material,
            });
        }
        if self.settled {
            return;
        }
        self.albedo = si.bsdf.base;
        self.normal = si.bsdf.frame.n;
        self.settled = si.unlit || !si.bsdf.is_delta();
    }

    /// The path left the scene.
    pub fn escaped(&mut self) {
        if !self.settled {
            self.albedo = Vec3::ONE;
            self.settled = true;
        }
    }
}
