//! KHR_materials_clearcoat's lobe: a dielectric GGX coat of IOR 1.5 with its own roughness and normal,
//! taking `weight * Schlick(N_c . V)` of the light and leaving the rest to the layers below it.

use glam::{Vec2, Vec3};

use super::microfacet::Ggx;
use super::{fresnel::schlick1, MIN_ALPHA};
use crate::geometry::Frame;

/// F0 of a dielectric of IOR 1.5 against air, ((1 - 1.5) / (1 + 1.5))^2.
pub const COAT_F0: f32 = 0.04;

#[derive(Clone, Copy, Debug)]
pub struct Coat {
    /// The coat's shading frame (its own normal map, else the interpolated normal).
    pub frame: Frame,
    /// clearcoat factor in [0, 1].
    pub weight: f32,
    /// GGX alpha (clearcoat roughness squared; 0: a delta mirror).
    pub alpha: f32,
}

impl Coat {
    pub fn new(frame: Frame, weight: f32, roughness: f32) -> Self {
        let r = roughness.clamp(0.0, 1.0);
        let alpha = r * r;
        Self {
            frame,
            weight: weight.clamp(0.0, 1.0),
            alpha: if alpha < MIN_ALPHA { 0.0 } else { alpha },
        }
    }

    pub fn is_delta(&self) -> bool {
        self.alpha == 0.0
    }

    /// The share of the light the coat takes at view `wo`: weight * Schlick(|N_c . V|) (the spec's
    /// fresnel_coat); the layers below get the rest.
    pub fn fresnel(&self, wo: Vec3) -> f32 {
        self.weight * schlick1(COAT_F0, self.frame.n.dot(wo).abs().min(1.0))
    }

    /// The coat's BRDF (its Fresnel share included) and the pdf of `sample`, for world directions;
    /// zero for a smooth (delta) coat.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (f32, f32) {
        let (o, i) = (self.frame.to_local(wo), self.frame.to_local(wi));
        if self.is_delta() || o.z <= 0.0 || i.z <= 0.0 {
            return (0.0, 0.0);
        }
        let h = (o + i).normalize();
        let ggx = Ggx::iso(self.alpha);
        let d = ggx.d(h);
        let f = self.fresnel(wo) * d * ggx.g2(o, i) / (4.0 * o.z * i.z);
        (f, ggx.g1(o) * d / (4.0 * o.z))
    }

    /// A reflected world direction: the mirror direction when smooth, else through a visible normal.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        let o = self.frame.to_local(wo);
        if o.z <= 0.0 {
            return None;
        }
        let i = if self.is_delta() {
            Vec3::new(-o.x, -o.y, o.z)
        } else {
            let h = Ggx::iso(self.alpha).sample_vndf(o, u);
            2.0 * o.dot(h) * h - o
        };
        (i.z > 0.0).then(|| self.frame.to_world(i))
    }
}
