//! Pearson's chi-square test for the sampling tests: observed counts per cell against the counts a
//! pdf integrated over each cell expects. Test-only.

/// The p-value of `observed` counts against `expected` ones, cell by cell; cells expecting fewer
/// than 5 are pooled into one (dropped if the pool still expects fewer). A small p-value says the
/// samples do not follow the pdf.
pub(crate) fn pearson_p_value(observed: &[f64], expected: &[f64]) -> f64 {
    let (mut chi2, mut dof) = (0.0f64, 0.0f64);
    let (mut pool_o, mut pool_e) = (0.0f64, 0.0f64);
    for (o, e) in observed.iter().zip(expected) {
        if *e < 5.0 {
            pool_o += o;
            pool_e += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            dof += 1.0;
        }
    }
    if pool_e >= 5.0 {
        chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        dof += 1.0;
    }
    chi2_p_value(chi2, (dof - 1.0).max(1.0))
}

/// Standard normal upper tail, from erfc (Abramowitz and Stegun 7.1.26, error under 1.5e-7).
fn normal_tail(z: f64) -> f64 {
    let x = z.abs() / std::f64::consts::SQRT_2;
    let t = 1.0 / (1.0 + 0.3275911 * x);
    let poly = t
        * (0.254829592
            + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
    let erfc = poly * (-x * x).exp();
    if z >= 0.0 {
        0.5 * erfc
    } else {
        1.0 - 0.5 * erfc
    }
}

/// Upper tail of the chi-square distribution with `k` degrees of freedom (Wilson-Hilferty).
fn chi2_p_value(x: f64, k: f64) -> f64 {
    let z = ((x / k).powf(1.0 / 3.0) - (1.0 - 2.0 / (9.0 * k))) / (2.0 / (9.0 * k)).sqrt();
    normal_tail(z)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Counts that match their expectation pass; counts shifted between cells fail.
    #[test]
    fn pearson_accepts_matching_counts_and_rejects_shifted_ones() {
        let expected = vec![100.0; 20];
        let close: Vec<f64> = (0..20).map(|i| 100.0 + [-6.0, 6.0][i % 2]).collect();
        assert!(pearson_p_value(&close, &expected) > 0.5);
        let shifted: Vec<f64> = (0..20).map(|i| 100.0 + [-30.0, 30.0][i % 2]).collect();
        assert!(pearson_p_value(&shifted, &expected) < 1e-6);
    }
}
