//! Multiple importance sampling: how two strategies that can make the same sample share it.
//! Light sampling and BSDF sampling both weigh their contributions here.

/// Veach's power heuristic (exponent 2): the weight of a sample made by the strategy of pdf `a` when
/// the other strategy would have made it with pdf `b`; zero when neither could.
pub fn power_heuristic(a: f32, b: f32) -> f32 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 == 0.0 {
        0.0
    } else {
        a2 / (a2 + b2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_of_the_two_strategies_sum_to_one() {
        for (a, b) in [(1.0f32, 1.0f32), (0.3, 2.0), (5.0, 0.0), (1e-3, 7.0)] {
            let s = power_heuristic(a, b) + power_heuristic(b, a);
            assert!((s - 1.0).abs() < 1e-6, "{a} {b}: {s}");
        }
        assert_eq!(power_heuristic(0.0, 0.0), 0.0);
    }
}
