//! The dielectric layer's albedo as Cycles' layering estimates it (its `ggx_gen_schlick_ior_s`
//! table): the Fresnel over the rough lobe's visible normals, which `--layering albedo` scales by.

use std::sync::OnceLock;

use super::energy::{for_each_reflection, lerp_nodes, STRATA};
use super::fresnel::fresnel_exact;
use super::microfacet::Ggx;

/// Nodes along roughness (sqrt(alpha)), the view cosine and z = F0^(1/4) (Cycles' axes: z spreads
/// the nodes over the common indices), each 0..1.
const N: usize = 16;
/// The last z node stands for an index this large (z = 1 is an infinite index).
const ETA_MAX: f32 = 1e4;

fn node(k: usize) -> f32 {
    k as f32 / (N - 1) as f32
}

/// The relative index whose normal-incidence reflectance is z^4.
fn eta_of_z(z: f32) -> f32 {
    let z2 = z * z;
    if z2 >= 1.0 {
        ETA_MAX
    } else {
        ((1.0 + z2) / (1.0 - z2)).min(ETA_MAX)
    }
}

/// Cycles' estimate of the layer's albedo at view cosine `mu` for each index in `etas`: F0 + (1 -
/// F0) s, with s the mean over visible normals of the Fresnel's rise above F0 at V.H, (F(V.H) -
/// F0) / (1 - F0), a sample whose reflection falls below the surface counting 0 (as
/// `ggx_gen_schlick_ior_s` is integrated). A smooth lobe gives F(mu).
fn cycles_estimate(alpha: f32, mu: f32, etas: &[f32]) -> Vec<f32> {
    let f0s: Vec<f32> = etas.iter().map(|&eta| fresnel_exact(1.0, eta)).collect();
    let mut sums = vec![0.0f64; etas.len()];
    for_each_reflection(alpha, mu, |oh, _| {
        for ((sum, &eta), &f0) in sums.iter_mut().zip(etas).zip(&f0s) {
            let rise = if f0 < 1.0 {
                ((fresnel_exact(oh, eta) - f0) / (1.0 - f0)).clamp(0.0, 1.0)
            } else {
                1.0
            };
            *sum += rise as f64;
        }
    });
    let n = (STRATA * STRATA) as f64;
    sums.iter()
        .zip(&f0s)
        .map(|(s, &f0)| f0 + (1.0 - f0) * (s / n) as f32)
        .collect()
}

/// The table, indexed [roughness][cosine][z].
fn table() -> &'static [[[f32; N]; N]; N] {
    static TABLE: OnceLock<[[[f32; N]; N]; N]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let etas: Vec<f32> = (0..N).map(|k| eta_of_z(node(k))).collect();
        let mut t = [[[0.0; N]; N]; N];
        for (r, plane) in t.iter_mut().enumerate() {
            let alpha = node(r) * node(r);
            for (m, row) in plane.iter_mut().enumerate() {
                row.copy_from_slice(&cycles_estimate(alpha, node(m), &etas));
            }
        }
        t
    })
}

/// The estimated albedo of the lobe of `ggx` (anisotropic ones by the roughness of sqrt(ax ay), as
/// Cycles) at view cosine `mu` for relative index `eta` >= 1. The table's error against the
/// integral is its interpolation's (checked below 2e-3 at the midpoints between nodes in the tests).
pub(super) fn estimate(ggx: &Ggx, mu: f32, eta: f32) -> f32 {
    let t = table();
    let rough = (ggx.ax * ggx.ay).sqrt().sqrt();
    let z = ((eta - 1.0) / (eta + 1.0)).max(0.0).sqrt();
    lerp_nodes(rough, N, |r| {
        lerp_nodes(mu, N, |m| lerp_nodes(z, N, |k| t[r][m][k]))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_smooth_lobe_has_the_fresnel_of_the_view() {
        for mu in [0.05, 0.3, 0.7, 1.0] {
            let direct = fresnel_exact(mu, 1.5);
            let mean = cycles_estimate(0.0, mu, &[1.5])[0];
            assert!((mean - direct).abs() < 1e-4, "mu {mu}: {mean} vs {direct}");
        }
    }

    #[test]
    fn a_rough_lobe_reflects_less_than_the_grazing_view_and_more_than_head_on() {
        // Tilted microfacets see a grazing view less grazing (and a head-on one less head-on).
        let grazing = cycles_estimate(0.25, 0.1, &[1.5])[0];
        assert!(grazing < 0.5 * fresnel_exact(0.1, 1.5), "{grazing}");
        let head_on = cycles_estimate(0.25, 1.0, &[1.5])[0];
        assert!(head_on > fresnel_exact(1.0, 1.5), "{head_on}");
    }

    #[test]
    fn the_table_interpolates_the_integral_between_its_nodes() {
        let half = 0.5 / (N - 1) as f32;
        for (rough, mu, eta) in [
            (0.3 + half, 0.2 + half, 1.5),
            (0.7 + half, 0.6 + half, 1.33),
        ] {
            let ggx = Ggx::iso(rough * rough);
            let looked_up = estimate(&ggx, mu, eta);
            let direct = cycles_estimate(rough * rough, mu, &[eta])[0];
            assert!(
                (looked_up - direct).abs() < 2e-3,
                "rough {rough} mu {mu} eta {eta}: {looked_up} vs {direct}"
            );
        }
    }
}
