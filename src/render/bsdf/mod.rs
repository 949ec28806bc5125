//! glTF's layered BSDF (spec appendix B and the KHR material extensions), in a local shading frame:
//! the metallic-roughness base with its transmission (`base`), under an optional Charlie sheen
//! (`sheen`) and an optional GGX clearcoat (`coat`), combined by `layered`. Each lobe file keeps its
//! eval, sample and pdf side by side; a material without layers takes the base's path alone.

mod base;
mod coat;
mod diffuse_transmission;
mod dispersion;
mod energy;
mod fresnel;
mod iridescence;
mod layer_albedo;
mod layered;
mod microfacet;
pub mod sheen;
#[cfg(test)]
mod tests;

use glam::{Vec2, Vec3};

pub use coat::{Coat, COAT_F0};
pub use diffuse_transmission::DiffuseTransmission;
pub use dispersion::{channel_iors, CHANNEL_WAVELENGTHS};
pub use fresnel::fresnel_exact;
pub use iridescence::Iridescence;
pub use sheen::Sheen;

use crate::geometry::Frame;
use crate::scene::ShadingModel;

/// Probabilities of choosing among lobes or layers with rough weights `w` (positive total): in
/// proportion to the weights, mixed with a tenth of a uniform choice among the lobes that carry
/// at least `NEGLIGIBLE_SHARE` of the total, so that none of them is starved by a rough estimate;
/// lobes below it keep their bare proportion.
#[inline(always)]
fn choice_probabilities(w: [f32; 3]) -> [f32; 3] {
    let total: f32 = w.iter().sum();
    let counts = |x: f32| x > NEGLIGIBLE_SHARE * total;
    let (sum, active) = w
        .iter()
        .filter(|&&x| counts(x))
        .fold((0.0f32, 0.0f32), |(s, n), &x| (s + x, n + 1.0));
    let kept = sum / total;
    w.map(|x| {
        if counts(x) {
            kept * (0.9 * x / sum + 0.1 / active)
        } else {
            x / total
        }
    })
}

/// Share of the estimated total below which a lobe gets no uniform boost. Metal texels filtered to
/// a metalness just under 1 have a diffuse lobe of almost no weight, which the boost gave 5% of the
/// samples: on helmet-env (the sun mirrored by DamagedHelmet's rough metal) noise per sample fell
/// from 0.993 to 0.840 without it, the demo and DamagedHelmet under the default rig unchanged.
const NEGLIGIBLE_SHARE: f32 = 0.02;

/// GGX alpha below which the specular lobes are perfectly smooth (delta lobes): glTF roughness under
/// about 0.03 renders as a true mirror or clear glass.
const MIN_ALPHA: f32 = 1e-3;

/// The material at one surface point, in its shading frame. The frame's normal faces the side the
/// light leaves towards (the incoming ray's side); the far side is inside a transmissive object.
#[derive(Clone, Copy, Debug)]
pub struct Bsdf {
    pub frame: Frame,
    pub base: Vec3,
    pub metallic: f32,
    /// GGX alpha = perceptual roughness squared (0 for smooth, delta lobes); along the frame's
    /// bitangent when anisotropic.
    pub alpha: f32,
    /// GGX alpha along the frame's tangent: `alpha`, unless KHR_materials_anisotropy stretches it.
    pub alpha_t: f32,
    /// Weight of the dielectric specular layer (KHR_materials_specular).
    pub specular: f32,
    /// Tint of the dielectric F0 (KHR_materials_specular's colour; 1 leaves the Fresnel untouched).
    pub specular_color: Vec3,
    /// Fraction of the light entering the dielectric base that passes through the surface
    /// (KHR_materials_transmission) rather than being diffusely re-emitted.
    pub transmission: f32,
    /// Relative index of refraction: the far side's over the frame normal's side (1 / ior when the ray
    /// leaves a transmissive object).
    pub eta: f32,
    /// Thin-walled (glTF transmission without KHR_materials_volume): light passes straight through
    /// without bending, and there is no inside.
    pub thin: bool,
    /// The frame normal's side is outside the object (always, for opaque and thin surfaces).
    pub outside: bool,
    /// Absorption coefficient (per unit length) of the medium behind a thick transmissive surface
    /// (KHR_materials_volume), applied along the path segments inside it.
    pub absorption: Vec3,
    /// KHR_materials_clearcoat, on top of everything.
    pub coat: Option<Coat>,
    /// KHR_materials_sheen, between the coat and the base.
    pub sheen: Option<Sheen>,
    /// KHR_materials_iridescence: a thin film whose Fresnel replaces the base's specular one.
    pub iridescence: Option<Iridescence>,
    /// KHR_materials_diffuse_transmission: part of the base's diffuse light goes through.
    pub diffuse_transmission: Option<DiffuseTransmission>,
    /// KHR_materials_dispersion: the material's index of refraction per RGB channel (set only on
    /// thick transmissive surfaces); a path follows one channel from its first dispersive vertex.
    pub dispersion: Option<Vec3>,
    /// The layering and GGX scattering model (the glTF spec's by default).
    pub model: ShadingModel,
}

/// One sampled direction.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    pub wi: Vec3,
    /// BSDF value (without the cosine); for a delta lobe, its weight divided by |cos|.
    pub f: Vec3,
    /// Solid-angle pdf; for a delta lobe, the probability of choosing it.
    pub pdf: f32,
    /// A perfectly specular (delta) lobe: no light sample can reach this direction, so emitters hit
    /// next count fully (MIS weight 1).
    pub delta: bool,
    /// The ray continues undeviated through a thin smooth surface; shadow rays see through such
    /// surfaces, so the path keeps the MIS state of the vertex before it.
    pub straight: bool,
}

impl Bsdf {
    /// An opaque surface: glTF's metallic-roughness model.
    pub fn new(frame: Frame, base: Vec3, metallic: f32, roughness: f32, specular: f32) -> Self {
        let r = roughness.clamp(0.0, 1.0);
        let alpha = r * r;
        let alpha = if alpha < MIN_ALPHA { 0.0 } else { alpha };
        Self {
            frame,
            base,
            metallic: metallic.clamp(0.0, 1.0),
            alpha,
            alpha_t: alpha,
            specular: specular.clamp(0.0, 1.0),
            specular_color: Vec3::ONE,
            transmission: 0.0,
            eta: 1.5,
            thin: true,
            outside: true,
            absorption: Vec3::ZERO,
            coat: None,
            sheen: None,
            iridescence: None,
            diffuse_transmission: None,
            dispersion: None,
            model: ShadingModel::default(),
        }
    }

    /// The same surface with a transmissive dielectric base: `ior` of the material, `entering` when
    /// the ray arrives from outside (the front face), `thin` for thin-walled surfaces. The ior also
    /// sets the reflectance of opaque dielectrics (KHR_materials_ior), so call this for every material
    /// (after setting `diffuse_transmission`).
    pub fn with_dielectric(
        mut self,
        transmission: f32,
        ior: f32,
        thin: bool,
        entering: bool,
    ) -> Self {
        let ior = if ior.is_finite() && ior >= 1.0 {
            ior
        } else {
            1.5
        };
        self.transmission = transmission.clamp(0.0, 1.0);
        // Diffuse transmission makes a volume's boundary transmissive too.
        self.thin = thin || (self.transmission == 0.0 && self.diffuse_transmission.is_none());
        // Opaque and thin surfaces have no inside: every hit comes from the outside.
        self.outside = self.thin || entering;
        self.eta = if self.outside { ior } else { 1.0 / ior };
        self
    }

    /// KHR_materials_anisotropy: the specular lobes' roughness raised along `tangent` (a direction
    /// in the surface, made orthogonal to the normal here) to mix(alpha, 1, strength^2), the
    /// perpendicular roughness kept (at least MIN_ALPHA, so a smooth surface becomes a rough
    /// line-shaped lobe). Strength 0, or a tangent along the normal, changes nothing.
    pub fn with_anisotropy(mut self, strength: f32, tangent: Vec3) -> Self {
        let s = strength.clamp(0.0, 1.0);
        let n = self.frame.n;
        let t = (tangent - n * n.dot(tangent)).normalize_or_zero();
        if s == 0.0 || t == Vec3::ZERO {
            return self;
        }
        self.frame = Frame {
            t,
            b: n.cross(t),
            n,
        };
        self.alpha = self.alpha.max(MIN_ALPHA);
        self.alpha_t = self.alpha + (1.0 - self.alpha) * s * s;
        self
    }

    /// Whether the material has layers over the base (otherwise it pays for the base alone).
    fn layered(&self) -> bool {
        self.coat.is_some() || self.sheen.is_some()
    }

    /// Whether every lobe is a delta lobe (light sampling cannot contribute).
    pub fn is_delta(&self) -> bool {
        self.base_is_delta() && self.sheen.is_none() && self.coat.is_none_or(|c| c.is_delta())
    }

    /// Whether `sample` reads its `u_lobe`: not for a plain Lambert base, whose one lobe takes
    /// every sample (its probability is exactly 1).
    pub fn chooses_lobe(&self) -> bool {
        self.layered() || self.lambert_only() != Some(1.0)
    }

    /// Whether light can arrive from behind the surface.
    pub fn transmits(&self) -> bool {
        (self.transmission > 0.0 || self.diffuse_transmission.is_some()) && self.metallic < 1.0
    }

    /// BSDF value and the pdf with which `sample` picks `wi`, both for world directions; delta lobes
    /// are left out (they have no value for any given pair of directions).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if self.layered() {
            return self.layered_eval(wo, wi);
        }
        self.base_eval(self.frame.to_local(wo), self.frame.to_local(wi))
    }

    /// Samples a direction: a lobe chosen by `u_lobe`, its direction from `u`.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if self.layered() {
            return self.layered_sample(wo, u_lobe, u);
        }
        self.base_sample(wo, u_lobe, u)
    }

    /// What a shadow ray keeps when it passes straight through this surface from `wo`'s side: the
    /// transmission of a thin smooth surface (its delta lobe points straight on), zero for any other.
    pub fn straight_transmittance(&self, wo: Vec3) -> Vec3 {
        let t = self.base_straight_transmittance(wo);
        if t == Vec3::ZERO || !self.layered() {
            return t;
        }
        let cos = self.frame.n.dot(wo).abs();
        t * self.layer_scale(wo, cos, cos)
    }
}

pub use crate::geometry::colour::luminance;
