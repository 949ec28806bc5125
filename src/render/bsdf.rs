//! glTF's metallic-roughness BRDF (spec appendix B): Lambert plus GGX/Smith microfacets with Schlick
//! Fresnel, evaluated and importance-sampled (visible normals, Heitz 2018) in a local shading frame.

use std::f32::consts::{FRAC_1_PI, PI};

use glam::{Vec2, Vec3};

/// An orthonormal frame with `n` as local +Z.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub t: Vec3,
    pub b: Vec3,
    pub n: Vec3,
}

impl Frame {
    /// Any frame around `n` (Duff et al. 2017, branchless and continuous except at one pole).
    pub fn from_normal(n: Vec3) -> Self {
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        Self {
            t: Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
            b: Vec3::new(b, sign + n.y * n.y * a, -n.y),
            n,
        }
    }

    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.t), v.dot(self.b), v.dot(self.n))
    }

    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.t * v.x + self.b * v.y + self.n * v.z
    }
}

/// Roughness below this is clamped: a perfectly specular lobe needs a delta path (distribution issue).
const MIN_ALPHA: f32 = 1e-3;

/// The material at one surface point, in its shading frame.
#[derive(Clone, Copy, Debug)]
pub struct Bsdf {
    pub frame: Frame,
    pub base: Vec3,
    pub metallic: f32,
    /// GGX alpha = perceptual roughness squared.
    pub alpha: f32,
    /// Weight of the dielectric specular layer (KHR_materials_specular).
    pub specular: f32,
}

#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    pub wi: Vec3,
    /// BRDF value (without the cosine).
    pub f: Vec3,
    pub pdf: f32,
}

impl Bsdf {
    pub fn new(frame: Frame, base: Vec3, metallic: f32, roughness: f32, specular: f32) -> Self {
        let r = roughness.clamp(0.0, 1.0);
        Self {
            frame,
            base,
            metallic: metallic.clamp(0.0, 1.0),
            alpha: (r * r).max(MIN_ALPHA),
            specular: specular.clamp(0.0, 1.0),
        }
    }

    /// Fresnel of the dielectric layer (F0 = 0.04, scaled by the specular weight).
    fn fresnel_dielectric(&self, cos: f32) -> f32 {
        self.specular * (0.04 + 0.96 * (1.0 - cos).clamp(0.0, 1.0).powi(5))
    }

    /// Fresnel of the whole specular lobe: the dielectric and metal layers mixed by metalness.
    fn fresnel(&self, cos: f32) -> Vec3 {
        let metal = schlick(self.base, cos);
        Vec3::splat(self.fresnel_dielectric(cos)).lerp(metal, self.metallic)
    }

    /// Probability of choosing the specular lobe, from the lobes' rough weights at `wo`.
    fn specular_probability(&self, cos_o: f32) -> f32 {
        let spec = luminance(self.fresnel(cos_o));
        let diff =
            (1.0 - self.metallic) * luminance(self.base) * (1.0 - self.fresnel_dielectric(cos_o));
        if diff <= 0.0 {
            1.0
        } else if spec <= 0.0 {
            0.0
        } else {
            (spec / (spec + diff)).clamp(0.05, 0.95)
        }
    }

    /// BRDF value and the pdf with which `sample` picks `wi`, both for world directions.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let (o, i) = (self.frame.to_local(wo), self.frame.to_local(wi));
        if o.z <= 0.0 || i.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let h = (o + i).normalize();
        let oh = o.dot(h).max(0.0);
        let d = ggx_d(h.z, self.alpha);
        let g2 = 1.0 / (1.0 + lambda(o, self.alpha) + lambda(i, self.alpha));
        let spec = self.fresnel(oh) * (d * g2 / (4.0 * o.z * i.z));
        let diffuse =
            self.base * ((1.0 - self.metallic) * (1.0 - self.fresnel_dielectric(oh)) * FRAC_1_PI);
        let ps = self.specular_probability(o.z);
        let pdf_spec = g1(o, self.alpha) * d / (4.0 * o.z);
        let pdf = ps * pdf_spec + (1.0 - ps) * i.z * FRAC_1_PI;
        (spec + diffuse, pdf)
    }

    /// Samples a direction: the specular lobe through visible normals, the diffuse lobe by cosine.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let o = self.frame.to_local(wo);
        if o.z <= 0.0 {
            return None;
        }
        let i = if u_lobe < self.specular_probability(o.z) {
            let h = sample_vndf(o, self.alpha, u);
            let i = 2.0 * o.dot(h) * h - o;
            if i.z <= 0.0 {
                return None;
            }
            i
        } else {
            cosine_hemisphere(u)
        };
        let wi = self.frame.to_world(i);
        let (f, pdf) = self.eval(wo, wi);
        (pdf > 0.0).then_some(BsdfSample { wi, f, pdf })
    }
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

pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hash(i: u32) -> f32 {
        (crate::sample::mix64(i as u64) >> 40) as f32 / (1u64 << 24) as f32
    }

    /// The albedo estimated by importance sampling must equal the one from uniform sampling (a check
    /// that `sample`'s pdf is the density it really draws from, and that `eval` is consistent).
    #[test]
    fn sampled_albedo_matches_uniform_integration() {
        let frame = Frame::from_normal(Vec3::new(0.2, 0.3, 0.9).normalize());
        for (metallic, roughness, specular) in [
            (0.0, 0.5, 1.0),
            (1.0, 0.3, 1.0),
            (0.5, 0.8, 1.0),
            (0.0, 1.0, 1.0),
            (0.0, 0.4, 0.0),
        ] {
            let bsdf = Bsdf::new(
                frame,
                Vec3::new(0.8, 0.5, 0.3),
                metallic,
                roughness,
                specular,
            );
            let wo = frame.to_world(Vec3::new(0.5, 0.1, 0.6).normalize());
            let n = 2_000_000;
            let (mut is, mut uni) = (0.0f64, 0.0f64);
            for k in 0..n {
                let u = Vec2::new(hash(3 * k + 1), hash(3 * k + 2));
                if let Some(s) = bsdf.sample(wo, hash(3 * k), u) {
                    is += (luminance(s.f) * s.wi.dot(frame.n) / s.pdf) as f64;
                }
                // Uniform hemisphere: pdf 1 / (2 pi).
                let z = u.x;
                let r = (1.0 - z * z).sqrt();
                let phi = 2.0 * PI * u.y;
                let wi = frame.to_world(Vec3::new(r * phi.cos(), r * phi.sin(), z));
                uni += (luminance(bsdf.eval(wo, wi).0) * z * 2.0 * PI) as f64;
            }
            let (is, uni) = (is / n as f64, uni / n as f64);
            assert!(
                (is - uni).abs() < 0.01 * uni.max(0.05),
                "metallic {metallic} roughness {roughness}: sampled {is} vs uniform {uni}"
            );
            assert!(is < 1.0);
        }
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
