//! glTF's metallic-roughness BSDF (spec appendix B, KHR_materials_transmission/ior/volume): Lambert,
//! GGX/Smith reflection and transmission (Walter et al. 2007, visible normals after Heitz 2018), and
//! delta lobes for smooth mirrors and glass, evaluated and importance-sampled in a local shading frame.

use std::f32::consts::{FRAC_1_PI, PI};

use glam::{Vec2, Vec3};

use crate::geometry::Frame;
use crate::sample::warp::cosine_hemisphere;

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
    /// GGX alpha = perceptual roughness squared (0 for smooth, delta lobes).
    pub alpha: f32,
    /// Weight of the dielectric specular layer (KHR_materials_specular).
    pub specular: f32,
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
    /// Relative index of refraction crossed (1 unless refracted through a thick surface).
    pub eta: f32,
}

/// Probabilities of the three lobes (reflection, diffuse, transmission).
#[derive(Clone, Copy, Debug)]
struct Lobes {
    reflect: f32,
    diffuse: f32,
    transmit: f32,
}

impl Bsdf {
    /// An opaque surface: glTF's metallic-roughness model.
    pub fn new(frame: Frame, base: Vec3, metallic: f32, roughness: f32, specular: f32) -> Self {
        let r = roughness.clamp(0.0, 1.0);
        let alpha = r * r;
        Self {
            frame,
            base,
            metallic: metallic.clamp(0.0, 1.0),
            alpha: if alpha < MIN_ALPHA { 0.0 } else { alpha },
            specular: specular.clamp(0.0, 1.0),
            transmission: 0.0,
            eta: 1.5,
            thin: true,
            outside: true,
            absorption: Vec3::ZERO,
        }
    }

    /// The same surface with a transmissive dielectric base: `ior` of the material, `entering` when
    /// the ray arrives from outside (the front face), `thin` for thin-walled surfaces. The ior also
    /// sets the reflectance of opaque dielectrics (KHR_materials_ior), so call this for every material.
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
        self.thin = thin || self.transmission == 0.0;
        // Opaque and thin surfaces have no inside: every hit comes from the outside.
        self.outside = self.thin || entering;
        self.eta = if self.outside { ior } else { 1.0 / ior };
        self
    }

    /// Whether every lobe is a delta lobe (light sampling cannot contribute).
    pub fn is_delta(&self) -> bool {
        self.alpha == 0.0 && (self.metallic == 1.0 || self.transmission == 1.0)
    }

    /// A thick surface between equal indices: rough or not, it refracts nothing (the microfacet
    /// half vector of Walter et al. degenerates there), so its transmission is a straight delta.
    fn index_matched(&self) -> bool {
        !self.thin && (self.eta - 1.0).abs() < 1e-3
    }

    /// Whether light can arrive from behind the surface.
    pub fn transmits(&self) -> bool {
        self.transmission > 0.0 && self.metallic < 1.0
    }

    /// Fresnel reflectance of the dielectric layer (exact, scaled by the specular weight; total
    /// internal reflection reflects everything whatever the weight).
    fn fresnel_dielectric(&self, cos: f32) -> f32 {
        let f = fresnel_exact(cos, self.eta);
        if f >= 1.0 {
            1.0
        } else {
            self.specular * f
        }
    }

    /// Fresnel of the whole specular lobe: the dielectric and metal layers mixed by metalness.
    fn fresnel(&self, cos: f32) -> Vec3 {
        let metal = schlick(self.base, cos);
        Vec3::splat(self.fresnel_dielectric(cos)).lerp(metal, self.metallic)
    }

    /// Lobe choice probabilities at `wo`, from the lobes' rough weights, mixed with a little of a
    /// uniform choice so that no active lobe is starved.
    fn lobes(&self, cos_o: f32) -> Lobes {
        let mut fd = self.fresnel_dielectric(cos_o);
        if self.alpha > 0.0 {
            // Rough microfacets still refract where the macro surface reflects totally.
            fd = fd.min(0.95);
        }
        let under = (1.0 - self.metallic) * (1.0 - fd) * luminance(self.base);
        let w = [
            luminance(self.fresnel(cos_o)),
            under * (1.0 - self.transmission),
            under * self.transmission,
        ];
        let total: f32 = w.iter().sum();
        let active = w.iter().filter(|&&x| x > 0.0).count() as f32;
        if total <= 0.0 {
            return Lobes {
                reflect: 1.0,
                diffuse: 0.0,
                transmit: 0.0,
            };
        }
        let p = |x: f32| {
            if x > 0.0 {
                0.9 * x / total + 0.1 / active
            } else {
                0.0
            }
        };
        Lobes {
            reflect: p(w[0]),
            diffuse: p(w[1]),
            transmit: p(w[2]),
        }
    }

    /// Value and pdf of the non-delta lobes for local directions `o` (above) and `i`.
    fn eval_local(&self, o: Vec3, i: Vec3) -> (Vec3, f32) {
        if o.z <= 0.0 || i.z == 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let lobes = self.lobes(o.z);
        let smooth = self.alpha == 0.0;
        if i.z > 0.0 {
            let h = (o + i).normalize();
            let oh = o.dot(h).max(0.0);
            let diffuse = self.base
                * ((1.0 - self.metallic)
                    * (1.0 - self.transmission)
                    * (1.0 - self.fresnel_dielectric(oh))
                    * FRAC_1_PI);
            let mut f = diffuse;
            let mut pdf = lobes.diffuse * i.z * FRAC_1_PI;
            if !smooth {
                let d = ggx_d(h.z, self.alpha);
                f += self.fresnel(oh) * (d * g2(o, i, self.alpha) / (4.0 * o.z * i.z));
                pdf += lobes.reflect * g1(o, self.alpha) * d / (4.0 * o.z);
            }
            return (f, pdf);
        }
        if smooth || !self.transmits() || self.index_matched() {
            return (Vec3::ZERO, 0.0);
        }
        let tint = self.base * ((1.0 - self.metallic) * self.transmission);
        if self.thin {
            // The reflection lobe mirrored through the surface (the spec's H_T = V + L mirrored).
            let m = Vec3::new(i.x, i.y, -i.z);
            let h = (o + m).normalize();
            let d = ggx_d(h.z, self.alpha);
            let t = 1.0 - self.fresnel_dielectric(o.dot(h).max(0.0));
            let f = tint * (t * d * g2(o, m, self.alpha) / (4.0 * o.z * m.z));
            let pdf = lobes.transmit * g1(o, self.alpha) * d / (4.0 * o.z);
            return (f, pdf);
        }
        // Rough dielectric refraction (Walter et al. 2007), radiance scaled by 1 / eta^2.
        let eta = self.eta;
        let mut h = (o + i * eta).normalize_or_zero();
        if h.z < 0.0 {
            h = -h;
        }
        let (oh, ih) = (o.dot(h), i.dot(h));
        if h == Vec3::ZERO || oh <= 0.0 || ih >= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let denom = (ih + oh / eta) * (ih + oh / eta);
        let d = ggx_d(h.z, self.alpha);
        let t = 1.0 - self.fresnel_dielectric(oh);
        let f = tint
            * (t * d * g2(o, i, self.alpha) * (ih * oh).abs()
                / (denom * o.z * i.z.abs() * eta * eta));
        let pdf = lobes.transmit * g1(o, self.alpha) * d * oh / o.z * ih.abs() / denom;
        (f, pdf)
    }

    /// BSDF value and the pdf with which `sample` picks `wi`, both for world directions; delta lobes
    /// are left out (they have no value for any given pair of directions).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        self.eval_local(self.frame.to_local(wo), self.frame.to_local(wi))
    }

    /// Samples a direction: the reflection and transmission lobes through visible normals (or as
    /// delta lobes when smooth), the diffuse lobe by cosine.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let o = self.frame.to_local(wo);
        if o.z <= 0.0 {
            return None;
        }
        let lobes = self.lobes(o.z);
        let smooth = self.alpha == 0.0;
        let pick_reflect = u_lobe < lobes.reflect;
        let pick_transmit = !pick_reflect && u_lobe >= lobes.reflect + lobes.diffuse;
        let out = |i: Vec3, f: Vec3, pdf: f32, delta: bool, straight: bool, eta: f32| {
            (pdf > 0.0 && f != Vec3::ZERO).then(|| BsdfSample {
                wi: self.frame.to_world(i),
                f,
                pdf,
                delta,
                straight,
                eta,
            })
        };
        if smooth && pick_reflect {
            let i = Vec3::new(-o.x, -o.y, o.z);
            return out(i, self.fresnel(o.z) / o.z, lobes.reflect, true, false, 1.0);
        }
        if (smooth || self.index_matched()) && pick_transmit {
            let tint = self.base * ((1.0 - self.metallic) * self.transmission);
            let t = 1.0 - self.fresnel_dielectric(o.z);
            if self.thin {
                return out(-o, tint * (t / o.z), lobes.transmit, true, true, 1.0);
            }
            let i = refract(o, self.eta)?;
            let f = tint * (t / (-i.z * self.eta * self.eta));
            return out(i, f, lobes.transmit, true, false, self.eta);
        }
        let i = if pick_reflect {
            let h = sample_vndf(o, self.alpha, u);
            2.0 * o.dot(h) * h - o
        } else if pick_transmit {
            let h = sample_vndf(o, self.alpha, u);
            if self.thin {
                let r = 2.0 * o.dot(h) * h - o;
                Vec3::new(r.x, r.y, -r.z)
            } else {
                // Refract about the microfacet normal; total internal reflection there gives no
                // transmitted direction (its energy is the reflection lobe's).
                let oh = o.dot(h);
                let sin2_t = (1.0 - oh * oh).max(0.0) / (self.eta * self.eta);
                if sin2_t >= 1.0 {
                    return None;
                }
                let cos_t = (1.0 - sin2_t).sqrt();
                -o / self.eta + (oh / self.eta - cos_t) * h
            }
        } else {
            cosine_hemisphere(u)
        };
        if i.z == 0.0 || (pick_reflect && i.z < 0.0) || (pick_transmit && i.z > 0.0) {
            return None;
        }
        let (f, pdf) = self.eval_local(o, i);
        let eta = if i.z < 0.0 && !self.thin {
            self.eta
        } else {
            1.0
        };
        out(i, f, pdf, false, false, eta)
    }

    /// What a shadow ray keeps when it passes straight through this surface from `wo`'s side: the
    /// transmission of a thin smooth surface (its delta lobe points straight on), zero for any other.
    pub fn straight_transmittance(&self, wo: Vec3) -> Vec3 {
        if !(self.thin && self.alpha == 0.0 && self.transmits()) {
            return Vec3::ZERO;
        }
        let cos = self.frame.n.dot(wo).abs();
        self.base
            * ((1.0 - self.metallic) * self.transmission * (1.0 - self.fresnel_dielectric(cos)))
    }
}

/// Unpolarised Fresnel reflectance of a dielectric interface with relative index `eta` (far side over
/// near side) at incidence cosine `cos_i`; 1 under total internal reflection.
pub fn fresnel_exact(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// The direction refracted from local `o` (above) through the macro surface, or None under total
/// internal reflection.
fn refract(o: Vec3, eta: f32) -> Option<Vec3> {
    let sin2_t = (1.0 - o.z * o.z).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(Vec3::new(-o.x / eta, -o.y / eta, -cos_t))
}

pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

fn schlick(f0: Vec3, cos: f32) -> Vec3 {
    f0 + (Vec3::ONE - f0) * (1.0 - cos).clamp(0.0, 1.0).powi(5)
}

fn ggx_d(cos_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let c2 = cos_h * cos_h;
    let denom = c2 * (a2 - 1.0) + 1.0;
    a2 / (PI * denom * denom)
}

/// Smith's Lambda for GGX.
fn lambda(w: Vec3, alpha: f32) -> f32 {
    let c2 = w.z * w.z;
    let t2 = (1.0 - c2).max(0.0) / c2;
    0.5 * ((1.0 + alpha * alpha * t2).sqrt() - 1.0)
}

fn g1(w: Vec3, alpha: f32) -> f32 {
    1.0 / (1.0 + lambda(w, alpha))
}

/// Smith's height-correlated masking-shadowing for a pair of directions.
fn g2(o: Vec3, i: Vec3, alpha: f32) -> f32 {
    1.0 / (1.0 + lambda(o, alpha) + lambda(i, alpha))
}

/// A GGX normal visible from `o` (Heitz 2018, isotropic).
fn sample_vndf(o: Vec3, alpha: f32, u: Vec2) -> Vec3 {
    let vh = Vec3::new(alpha * o.x, alpha * o.y, o.z).normalize();
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = if len2 > 0.0 {
        Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt()
    } else {
        Vec3::X
    };
    let t2 = vh.cross(t1);
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    let p1 = r * phi.cos();
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
    let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
    Vec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(1e-6)).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hash(i: u32) -> f32 {
        (crate::geometry::mix64(i as u64) >> 40) as f32 / (1u64 << 24) as f32
    }

    /// The albedo from `sample` against uniform integration of `eval` over the whole sphere, for one
    /// BSDF and outgoing direction; returns (sampled, uniform).
    fn albedos(bsdf: &Bsdf, wo: Vec3, n: u32) -> (f64, f64) {
        let mut is = 0.0f64;
        for k in 0..n {
            let u = Vec2::new(hash(3 * k + 1), hash(3 * k + 2));
            if let Some(s) = bsdf.sample(wo, hash(3 * k), u) {
                assert!(!s.delta);
                is += (luminance(s.f) * s.wi.dot(bsdf.frame.n).abs() / s.pdf) as f64;
            }
        }
        // Uniform over the sphere (pdf 1 / (4 pi)), jittered on a grid of strata in (z, phi) so
        // that the narrow rough lobes still converge.
        let m = (n as f64).sqrt() as u32;
        let mut uni = 0.0f64;
        for a in 0..m {
            for b in 0..m {
                let k = a * m + b;
                let z = 2.0 * (a as f32 + hash(2 * k + 5)) / m as f32 - 1.0;
                let phi = 2.0 * PI * (b as f32 + hash(2 * k + 6)) / m as f32;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let wi = bsdf
                    .frame
                    .to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z));
                uni += (luminance(bsdf.eval(wo, wi).0) * z.abs() * 4.0 * PI) as f64;
            }
        }
        (is / n as f64, uni / (m * m) as f64)
    }

    /// The albedo estimated by importance sampling must equal the one from uniform sampling (a check
    /// that `sample`'s pdf is the density it really draws from, and that `eval` is consistent), for
    /// reflection, thick (entering and leaving) and thin rough transmission; and no lobe mix
    /// reflects or transmits more than comes in.
    #[test]
    fn sampled_albedo_matches_uniform_integration() {
        let frame = Frame::from_normal(Vec3::new(0.2, 0.3, 0.9).normalize());
        let base = Vec3::new(0.8, 0.5, 0.3);
        // (metallic, roughness, specular, transmission, thin, entering)
        for (metallic, roughness, specular, transmission, thin, entering) in [
            (0.0, 0.5, 1.0, 0.0, true, true),
            (1.0, 0.3, 1.0, 0.0, true, true),
            (0.5, 0.8, 1.0, 0.0, true, true),
            (0.0, 1.0, 1.0, 0.0, true, true),
            (0.0, 0.4, 0.0, 0.0, true, true),
            (0.0, 0.3, 1.0, 1.0, false, true),
            (0.0, 0.5, 1.0, 1.0, false, false),
            (0.0, 0.7, 1.0, 0.6, false, true),
            (0.0, 0.4, 1.0, 1.0, true, true),
            (0.3, 0.6, 1.0, 0.5, true, true),
        ] {
            let bsdf = Bsdf::new(frame, base, metallic, roughness, specular).with_dielectric(
                transmission,
                1.5,
                thin,
                entering,
            );
            for wo in [Vec3::new(0.5, 0.1, 0.6), Vec3::new(0.9, 0.0, 0.15)] {
                let wo = frame.to_world(wo.normalize());
                let (is, uni) = albedos(&bsdf, wo, 1_000_000);
                let label = format!(
                    "metallic {metallic} roughness {roughness} transmission {transmission} \
                     thin {thin} entering {entering}"
                );
                assert!(
                    (is - uni).abs() < 0.015 * uni.max(0.05),
                    "{label}: sampled {is} vs uniform {uni}"
                );
                assert!(is < 1.0, "{label}: albedo {is}");
            }
        }
    }

    /// White rough glass: what single scattering loses is the GGX masking, a few percent, never a gain
    /// (radiance scaling undone: importance-carrying weights must sum to at most 1).
    #[test]
    fn rough_glass_interface_conserves_energy() {
        let frame = Frame::from_normal(Vec3::Z);
        for (entering, cos) in [(true, 0.9f32), (true, 0.3), (false, 0.95), (false, 0.5)] {
            let bsdf = Bsdf::new(frame, Vec3::ONE, 0.0, 0.3, 1.0)
                .with_dielectric(1.0, 1.5, false, entering);
            let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            let n = 400_000;
            let mut sum = 0.0f64;
            for k in 0..n {
                let u = Vec2::new(hash(3 * k + 1), hash(3 * k + 2));
                if let Some(s) = bsdf.sample(wo, hash(3 * k), u) {
                    sum += (s.f.x * s.wi.z.abs() / s.pdf * s.eta * s.eta) as f64;
                }
            }
            let e = sum / n as f64;
            assert!(
                e > 0.9 && e < 1.0 + 3e-3,
                "entering {entering} cos {cos}: energy {e}"
            );
        }
    }

    /// Generalised reciprocity of the refraction BTDF: f(o -> i) eta_i^2 = f(i -> o) eta_o^2, and
    /// plain reciprocity of the reflection.
    #[test]
    fn btdf_is_reciprocal() {
        let n = Vec3::new(0.1, -0.2, 1.0).normalize();
        let outside = Bsdf::new(Frame::from_normal(n), Vec3::ONE, 0.0, 0.45, 1.0)
            .with_dielectric(1.0, 1.5, false, true);
        let inside = Bsdf::new(Frame::from_normal(-n), Vec3::ONE, 0.0, 0.45, 1.0)
            .with_dielectric(1.0, 1.5, false, false);
        let o = outside.frame.to_world(Vec3::new(0.4, 0.2, 0.8).normalize());
        for i in [
            Vec3::new(-0.3, -0.1, -0.9),
            Vec3::new(-0.2, -0.2, -0.95),
            Vec3::new(-0.4, -0.1, -0.85),
        ] {
            let i = outside.frame.to_world(i.normalize());
            let (f_oi, _) = outside.eval(o, i);
            let (f_io, _) = inside.eval(i, o);
            assert!(f_oi.x > 0.0);
            assert!(
                (f_oi.x * 2.25 - f_io.x).abs() < 1e-3 * f_io.x,
                "{} vs {}",
                f_oi.x * 2.25,
                f_io.x
            );
        }
        let r = Bsdf::new(
            Frame::from_normal(n),
            Vec3::new(0.7, 0.6, 0.2),
            0.3,
            0.5,
            1.0,
        );
        let i = r.frame.to_world(Vec3::new(-0.6, 0.3, 0.5).normalize());
        let (a, b) = (r.eval(o, i).0, r.eval(i, o).0);
        assert!((a - b).abs().max_element() < 1e-5 * a.max_element());
    }

    /// Beyond the critical angle, from inside glass, every sample reflects with weight exactly 1;
    /// below it, smooth glass splits the energy into Fresnel reflection and transmission, summing to 1.
    #[test]
    fn smooth_glass_reflects_totally_beyond_the_critical_angle() {
        let frame = Frame::from_normal(Vec3::Z);
        let inside =
            Bsdf::new(frame, Vec3::ONE, 0.0, 0.0, 1.0).with_dielectric(1.0, 1.5, false, false);
        assert!(inside.is_delta());
        let critical = (1.0f32 / 1.5).asin();
        let theta = critical + 0.05;
        let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
        for k in 0..1000 {
            let s = inside
                .sample(wo, hash(k), Vec2::new(hash(k + 7), 0.5))
                .expect("always reflects");
            assert!(s.delta && s.wi.z > 0.0);
            assert!((s.wi - Vec3::new(-wo.x, 0.0, wo.z)).length() < 1e-6);
            assert!((s.f.x * s.wi.z / s.pdf - 1.0).abs() < 1e-5);
        }
        // Below it, each lobe's weight times its choice probability is its Fresnel share, so the
        // expected weights add up to 1.
        for theta in [critical - 0.05, 0.2] {
            let wo = Vec3::new(theta.sin(), 0.0, theta.cos());
            let fr = fresnel_exact(wo.z, inside.eta);
            let lobes = inside.lobes(wo.z);
            assert!((lobes.reflect + lobes.transmit - 1.0).abs() < 1e-6);
            let (mut refl, mut trans) = (false, false);
            for k in 0..200 {
                let s = inside.sample(wo, hash(k), Vec2::ZERO).unwrap();
                let w = s.f.x * s.wi.z.abs() / s.pdf;
                if s.wi.z > 0.0 {
                    refl = true;
                    assert!((w * lobes.reflect - fr).abs() < 1e-5);
                } else {
                    trans = true;
                    // Snell's law, and the radiance scaling undone.
                    assert!((s.wi.x * inside.eta + wo.x).abs() < 1e-5);
                    assert!((w * s.eta * s.eta * lobes.transmit - (1.0 - fr)).abs() < 1e-5);
                }
            }
            assert!(refl && trans);
        }
    }

    /// Between equal indices roughness cannot bend light: a rough boundary of ior 1 passes it straight.
    #[test]
    fn index_matched_rough_boundary_is_straight() {
        let frame = Frame::from_normal(Vec3::Z);
        let b = Bsdf::new(frame, Vec3::ONE, 0.0, 0.8, 1.0).with_dielectric(1.0, 1.0, false, true);
        let wo = Vec3::new(0.6, 0.0, 0.8);
        for k in 0..100 {
            let s = b
                .sample(wo, hash(k), Vec2::new(hash(k + 1), hash(k + 2)))
                .unwrap();
            assert!(s.delta && (s.wi + wo).length() < 1e-6);
            assert!((s.f.x * s.wi.z.abs() / s.pdf - 1.0).abs() < 1e-5);
        }
    }

    /// A smooth metal is a mirror: one delta sample with weight Schlick(base, cos).
    #[test]
    fn smooth_metal_is_a_delta_mirror() {
        let frame = Frame::from_normal(Vec3::Z);
        let base = Vec3::new(0.9, 0.6, 0.3);
        let m = Bsdf::new(frame, base, 1.0, 0.0, 1.0);
        assert!(m.is_delta());
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let s = m.sample(wo, 0.5, Vec2::new(0.3, 0.7)).unwrap();
        assert!(s.delta && !s.straight);
        assert!((s.wi - Vec3::new(-0.6, 0.0, 0.8)).length() < 1e-6);
        let w = s.f * s.wi.z / s.pdf;
        assert!((w - schlick(base, 0.8)).abs().max_element() < 1e-6);
        // Nothing for light sampling to find.
        assert_eq!(m.eval(wo, s.wi).0, Vec3::ZERO);
    }

    /// A thin smooth wall lets light straight through, tinted by the base colour and less Fresnel.
    #[test]
    fn thin_smooth_wall_passes_light_straight() {
        let frame = Frame::from_normal(Vec3::Z);
        let tint = Vec3::new(1.0, 0.5, 0.25);
        let b = Bsdf::new(frame, tint, 0.0, 0.0, 1.0).with_dielectric(1.0, 1.5, true, false);
        let wo = Vec3::new(0.0, 0.6, 0.8);
        let expected = tint * (1.0 - fresnel_exact(0.8, 1.5));
        assert!(
            (b.straight_transmittance(wo) - expected)
                .abs()
                .max_element()
                < 1e-6
        );
        let mut seen = false;
        for k in 0..100 {
            let s = b.sample(wo, hash(k), Vec2::ZERO).unwrap();
            if s.wi.z < 0.0 {
                seen = true;
                assert!(s.straight && (s.wi + wo).length() < 1e-6);
                let w = s.f * s.wi.z.abs() / s.pdf * b.lobes(0.8).transmit;
                assert!((w - expected).abs().max_element() < 1e-5);
            }
        }
        assert!(seen);
        // Rough thin walls scatter instead: shadow rays do not pass them.
        let rough = Bsdf::new(frame, tint, 0.0, 0.4, 1.0).with_dielectric(1.0, 1.5, true, false);
        assert_eq!(rough.straight_transmittance(wo), Vec3::ZERO);
    }

    #[test]
    fn frame_is_orthonormal() {
        for n in [Vec3::Z, -Vec3::Z, Vec3::new(0.3, -0.4, 0.2).normalize()] {
            let f = Frame::from_normal(n);
            assert!(f.t.dot(f.b).abs() < 1e-6 && f.t.dot(n).abs() < 1e-6);
            assert!((f.t.cross(f.b) - n).length() < 1e-5);
        }
    }
}
