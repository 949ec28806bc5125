//! Discrete distributions for choosing among lights: Vose's alias table, O(1) to sample and O(1) to
//! ask the probability of an outcome (what multiple importance sampling needs for every emitter hit).

/// An alias table over `n` outcomes with given non-negative weights.
#[derive(Clone, Debug, Default)]
pub struct AliasTable {
    /// Probability of keeping bucket `i` rather than going to `alias[i]`.
    keep: Vec<f32>,
    alias: Vec<u32>,
    /// Normalised probability of each outcome.
    pmf: Vec<f32>,
}

impl AliasTable {
    /// The table for `weights`; every probability is zero when the weights sum to zero (or are not
    /// finite), and sampling then returns `None`.
    pub fn new(weights: &[f32]) -> Self {
        let n = weights.len();
        let total: f64 = weights.iter().map(|&w| w.max(0.0) as f64).sum();
        // `total` is a sum of non-negative values, so it is positive, zero or NaN/inf.
        if n == 0 || total <= 0.0 || !total.is_finite() {
            return Self {
                keep: vec![0.0; n],
                alias: (0..n as u32).collect(),
                pmf: vec![0.0; n],
            };
        }
        let pmf: Vec<f32> = weights
            .iter()
            .map(|&w| (w.max(0.0) as f64 / total) as f32)
            .collect();
        // Vose: scaled probabilities (mean 1) split into small and large work lists; each small bucket
        // is topped up from a large one. f64 keeps the leftovers honest for many lights.
        let mut scaled: Vec<f64> = weights
            .iter()
            .map(|&w| w.max(0.0) as f64 / total * n as f64)
            .collect();
        let mut keep = vec![1.0f32; n];
        let mut alias: Vec<u32> = (0..n as u32).collect();
        let (mut small, mut large): (Vec<usize>, Vec<usize>) =
            (0..n).partition(|&i| scaled[i] < 1.0);
        while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
            small.pop();
            keep[s] = scaled[s] as f32;
            alias[s] = l as u32;
            scaled[l] -= 1.0 - scaled[s];
            if scaled[l] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        // What remains is 1 up to rounding.
        for i in small.into_iter().chain(large) {
            keep[i] = 1.0;
        }
        Self { keep, alias, pmf }
    }

    pub fn len(&self) -> usize {
        self.pmf.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pmf.is_empty()
    }

    /// The probability of outcome `i`.
    pub fn pmf(&self, i: usize) -> f32 {
        self.pmf[i]
    }

    /// An outcome for `u` in [0, 1), with its probability.
    pub fn sample(&self, u: f32) -> Option<(usize, f32)> {
        let n = self.pmf.len();
        if n == 0 {
            return None;
        }
        let x = u * n as f32;
        let i = (x as usize).min(n - 1);
        let frac = x - i as f32;
        let j = if frac < self.keep[i] {
            i
        } else {
            self.alias[i] as usize
        };
        let p = self.pmf[j];
        (p > 0.0).then_some((j, p))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn selection_frequencies_match_the_weights() {
        let weights = [3.0, 0.0, 1.0, 10.0, 0.5, 5.5, 0.0, 2.0];
        let total: f32 = weights.iter().sum();
        let t = AliasTable::new(&weights);
        let n = 200_000;
        let mut counts = [0u32; 8];
        for k in 0..n {
            // A stratified sweep of [0, 1): exact frequencies up to one count per bucket boundary.
            let (i, p) = t.sample((k as f32 + 0.5) / n as f32).unwrap();
            assert!((p - weights[i] / total).abs() < 1e-6);
            counts[i] += 1;
        }
        for (i, &w) in weights.iter().enumerate() {
            let f = counts[i] as f32 / n as f32;
            assert!(
                (f - w / total).abs() < 1e-4,
                "outcome {i}: {f} vs {}",
                w / total
            );
            assert!((t.pmf(i) - w / total).abs() < 1e-6);
        }
    }

    #[test]
    fn degenerate_weights_sample_nothing() {
        assert!(AliasTable::new(&[]).sample(0.3).is_none());
        let t = AliasTable::new(&[0.0, 0.0]);
        assert!(t.sample(0.7).is_none());
        assert_eq!(t.pmf(1), 0.0);
        let one = AliasTable::new(&[2.0]);
        assert_eq!(one.sample(0.999_999), Some((0, 1.0)));
    }
}
