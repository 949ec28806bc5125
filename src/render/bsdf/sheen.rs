//! KHR_materials_sheen's lobe: the "Charlie" sheen of Estevez and Kulla 2017 (exponentiated-sine
//! distribution, their fitted visibility), and its directional albedo E(cos, roughness) as a table.

use std::f32::consts::PI;
use std::sync::OnceLock;

use glam::{Vec2, Vec3};

use crate::sample::warp::uniform_cone;

/// Smallest sheen roughness: below it the distribution is too narrow for the albedo table.
const MIN_ROUGHNESS: f32 = 0.05;
/// Albedo table resolution: cosines 0..1 and roughnesses 0..1 at these many intervals.
const COS_STEPS: usize = 32;
const ROUGH_STEPS: usize = 32;

#[derive(Clone, Copy, Debug)]
pub struct Sheen {
    /// Linear sheen colour.
    pub color: Vec3,
    /// Perceptual sheen roughness, clamped to [MIN_ROUGHNESS, 1].
    pub roughness: f32,
    /// Distribution alpha: roughness squared.
    pub alpha: f32,
}

/// The Charlie distribution: (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi).
pub(super) fn d_charlie(cos_h: f32, alpha: f32) -> f32 {
    let inv = 1.0 / alpha;
    let sin2 = (1.0 - cos_h * cos_h).max(0.0);
    (2.0 + inv) * sin2.powf(0.5 * inv) / (2.0 * PI)
}

/// Estevez and Kulla's fit of the Charlie Lambda's exponent.
fn l_fit(x: f32, alpha: f32) -> f32 {
    let t = (1.0 - alpha) * (1.0 - alpha);
    let mix = |a: f32, b: f32| a + (b - a) * t;
    let (a, b, c) = (
        mix(21.5473, 25.3245),
        mix(3.82987, 3.32435),
        mix(0.19823, 0.16801),
    );
    let (d, e) = (mix(-1.97760, -1.27393), mix(-4.32054, -4.85967));
    a / (1.0 + b * x.powf(c)) + d * x + e
}

pub(super) fn lambda_sheen(cos: f32, alpha: f32) -> f32 {
    let c = cos.abs();
    if c < 0.5 {
        l_fit(c, alpha).exp()
    } else {
        (2.0 * l_fit(0.5, alpha) - l_fit(1.0 - c, alpha)).exp()
    }
}

/// The white (colour 1) sheen BRDF for local directions above the surface.
fn brdf(o: Vec3, i: Vec3, alpha: f32) -> f32 {
    let h = (o + i).normalize();
    let vis = 1.0 / ((1.0 + lambda_sheen(o.z, alpha) + lambda_sheen(i.z, alpha)) * 4.0 * o.z * i.z);
    d_charlie(h.z, alpha) * vis
}

impl Sheen {
    pub fn new(color: Vec3, roughness: f32) -> Self {
        let r = roughness.clamp(MIN_ROUGHNESS, 1.0);
        Self {
            color: color.clamp(Vec3::ZERO, Vec3::ONE),
            roughness: r,
            alpha: r * r,
        }
    }

    /// Value and pdf of `sample` for local directions (the base's shading frame).
    pub fn eval(&self, o: Vec3, i: Vec3) -> (Vec3, f32) {
        if o.z <= 0.0 || i.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        (self.color * brdf(o, i, self.alpha), self.pdf(o, i))
    }

    /// Half uniform over the hemisphere (the lobe is broad and grazing), half by the distribution's
    /// half vectors, whose density D cos(theta_h) integrates to 1.
    fn pdf(&self, o: Vec3, i: Vec3) -> f32 {
        let h = (o + i).normalize();
        let oh = o.dot(h);
        let by_h = if oh > 0.0 {
            d_charlie(h.z, self.alpha) * h.z / (4.0 * oh)
        } else {
            0.0
        };
        0.5 / (2.0 * PI) + 0.5 * by_h
    }

    /// A local direction above the surface, or None when the half vector reflects `o` below it.
    pub fn sample(&self, o: Vec3, u: Vec2) -> Option<Vec3> {
        if u.x < 0.5 {
            // A cone of half-angle 90 degrees is the hemisphere.
            return Some(uniform_cone(Vec2::new(2.0 * u.x, u.y), 1.0).0);
        }
        // sin(theta_h) has density (2 + 1/alpha) s^(1/alpha + 1): invert its CDF s^(2 + 1/alpha).
        let s = (2.0 * u.x - 1.0).powf(1.0 / (2.0 + 1.0 / self.alpha));
        let c = (1.0 - s * s).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        let h = Vec3::new(s * phi.cos(), s * phi.sin(), c);
        let i = 2.0 * o.dot(h) * h - o;
        (i.z > 0.0 && o.dot(h) > 0.0).then_some(i)
    }

    /// The white sheen's directional albedo at incidence cosine `cos`.
    pub fn albedo(&self, cos: f32) -> f32 {
        albedo(cos, self.roughness)
    }
}

/// E(cos, roughness) interpolated bilinearly from a table integrated once, on first use.
pub fn albedo(cos: f32, roughness: f32) -> f32 {
    static TABLE: OnceLock<Vec<f32>> = OnceLock::new();
    let t = TABLE.get_or_init(albedo_table);
    let x = cos.clamp(0.0, 1.0) * COS_STEPS as f32;
    let y = roughness.clamp(0.0, 1.0) * ROUGH_STEPS as f32;
    let (i, j) = (
        (x as usize).min(COS_STEPS - 1),
        (y as usize).min(ROUGH_STEPS - 1),
    );
    let (fx, fy) = (x - i as f32, y - j as f32);
    let at = |a: usize, b: usize| t[b * (COS_STEPS + 1) + a];
    let lo = at(i, j) * (1.0 - fx) + at(i + 1, j) * fx;
    let hi = at(i, j + 1) * (1.0 - fx) + at(i + 1, j + 1) * fx;
    lo * (1.0 - fy) + hi * fy
}

/// Midpoint quadrature in (theta, phi) over the hemisphere (symmetric in phi) at each table node.
fn albedo_table() -> Vec<f32> {
    const THETA: usize = 128;
    const PHI: usize = 48;
    let mut t = Vec::with_capacity((COS_STEPS + 1) * (ROUGH_STEPS + 1));
    for j in 0..=ROUGH_STEPS {
        let r = (j as f32 / ROUGH_STEPS as f32).max(MIN_ROUGHNESS);
        let alpha = r * r;
        for i in 0..=COS_STEPS {
            let c = (i as f32 / COS_STEPS as f32).max(1e-3);
            let o = Vec3::new((1.0 - c * c).sqrt(), 0.0, c);
            let mut sum = 0.0f64;
            for a in 0..THETA {
                let th = (a as f32 + 0.5) * 0.5 * PI / THETA as f32;
                let (st, ct) = th.sin_cos();
                for b in 0..PHI {
                    let ph = (b as f32 + 0.5) * PI / PHI as f32;
                    let wi = Vec3::new(st * ph.cos(), st * ph.sin(), ct);
                    sum += (brdf(o, wi, alpha) * ct * st) as f64;
                }
            }
            let cell = (0.5 * PI / THETA as f32) * (PI / PHI as f32) * 2.0;
            t.push((sum * cell as f64) as f32);
        }
    }
    t
}
