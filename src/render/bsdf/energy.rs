//! Multiple-scattering energy compensation for the GGX specular lobes (Turquin 2019, with Kulla and
//! Conty 2017's multi-bounce Fresnel, as Cycles' multiscatter GGX does): single scatter scaled by
//! 1 + F_ms (1 - E) / E, from a table of the white lobe's directional albedo E computed at first use.

use std::sync::OnceLock;

use glam::{Vec2, Vec3};

use super::microfacet::Ggx;

/// Table nodes along roughness (sqrt(alpha), 0..1) and along the view cosine (0..1).
const N: usize = 32;
/// Stratified VNDF samples per node and axis.
pub(super) const STRATA: usize = 24;

/// The white (F = 1) single-scatter GGX albedo E(roughness, cos) and its cosine-weighted hemispherical
/// average E_avg(roughness).
struct AlbedoTable {
    e: [[f32; N]; N],
    e_avg: [f32; N],
}

fn node(k: usize) -> f32 {
    k as f32 / (N - 1) as f32
}

/// Visits the stratified visible-normal reflections of the white lobe at view cosine `mu` that
/// stay above the surface: each one's V.H and weight G2 / G1 (the VNDF estimator's term with F = 1),
/// out of `STRATA`^2 samples.
pub(super) fn for_each_reflection(alpha: f32, mu: f32, mut visit: impl FnMut(f32, f32)) {
    let ggx = Ggx::iso(alpha.max(1e-4));
    let mu = mu.clamp(1e-3, 1.0);
    let o = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
    for a in 0..STRATA {
        for b in 0..STRATA {
            let u = Vec2::new(
                (a as f32 + 0.5) / STRATA as f32,
                (b as f32 + 0.5) / STRATA as f32,
            );
            let h = ggx.sample_vndf(o, u);
            let oh = o.dot(h);
            let i = 2.0 * oh * h - o;
            if i.z > 0.0 {
                visit(oh, ggx.g2(o, i) / ggx.g1(o));
            }
        }
    }
}

/// The white lobe's albedo at view cosine `mu`: mean of G2 / G1 over visible normals, zero where
/// the reflected direction falls below the surface.
pub(crate) fn white_albedo(alpha: f32, mu: f32) -> f32 {
    let mut sum = 0.0f64;
    for_each_reflection(alpha, mu, |_, w| sum += w as f64);
    (sum / (STRATA * STRATA) as f64) as f32
}

fn table() -> &'static AlbedoTable {
    static TABLE: OnceLock<AlbedoTable> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut e = [[0.0; N]; N];
        let mut e_avg = [0.0; N];
        for (r, row) in e.iter_mut().enumerate() {
            let alpha = node(r) * node(r);
            for (m, v) in row.iter_mut().enumerate() {
                *v = white_albedo(alpha, node(m));
            }
            // E_avg = 2 * integral of E(mu) mu dmu, by the trapezoid rule over the nodes.
            let f = |m: usize| row[m] * node(m);
            let h = node(1);
            e_avg[r] = 2.0 * h * ((f(0) + f(N - 1)) * 0.5 + (1..N - 1).map(f).sum::<f32>());
        }
        AlbedoTable { e, e_avg }
    })
}

/// Linear interpolation of `at(k)` at `x` in 0..1 over `n` evenly spaced nodes.
pub(super) fn lerp_nodes(x: f32, n: usize, at: impl Fn(usize) -> f32) -> f32 {
    let t = x.clamp(0.0, 1.0) * (n - 1) as f32;
    let k = (t as usize).min(n - 2);
    let f = t - k as f32;
    at(k) * (1.0 - f) + at(k + 1) * f
}

/// E and E_avg for a distribution (anisotropic ones by the roughness of sqrt(ax ay), as Cycles).
fn lookup(ggx: &Ggx, mu: f32) -> (f32, f32) {
    let t = table();
    let rough = (ggx.ax * ggx.ay).sqrt().sqrt();
    let e = lerp_nodes(rough, N, |r| lerp_nodes(mu, N, |m| t.e[r][m]));
    let e_avg = lerp_nodes(rough, N, |r| t.e_avg[r]);
    (e.max(1e-3), e_avg)
}

/// The factor on the single-scatter lobe at view cosine `mu`, for a lobe whose Fresnel averages
/// `fss` over the hemisphere (1: white, the factor is 1 / E and the lobe's albedo 1).
pub(super) fn compensation(ggx: &Ggx, mu: f32, fss: Vec3) -> Vec3 {
    let (e, e_avg) = lookup(ggx, mu);
    let missing = (1.0 - e) / e;
    let fms = fss * e_avg / (Vec3::ONE - fss * (1.0 - e_avg));
    Vec3::ONE + fms * missing
}

/// The share of the white compensated lobe the Fresnel-weighted one keeps: (1 + F_ms m) / (1 + m),
/// which scales a Fresnel-based estimate of the lobe's albedo (Cycles' layering estimate).
pub(super) fn darkening(ggx: &Ggx, mu: f32, fss: f32) -> f32 {
    let (e, _) = lookup(ggx, mu);
    let missing = (1.0 - e) / e;
    compensation(ggx, mu, Vec3::splat(fss)).x / (1.0 + missing)
}

/// Hemispherical average of Schlick's Fresnel, 2 * integral of F(mu) mu dmu = F0 + (1 - F0) / 21.
pub(super) fn schlick_average(f0: Vec3) -> Vec3 {
    f0 + (Vec3::ONE - f0) / 21.0
}

/// Hemispherical average of the exact dielectric Fresnel for relative index `eta` (Kulla and
/// Conty's fits, on either side of the interface).
pub(super) fn dielectric_average(eta: f32) -> f32 {
    if eta >= 1.0 {
        (eta - 1.0) / (4.08567 + 1.00071 * eta)
    } else {
        0.997118 + eta * (0.1014 - eta * (0.965241 + 0.130607 * eta))
    }
}
