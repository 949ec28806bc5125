//! Piecewise-constant distributions on [0,1) and [0,1)^2, sampled by inverting their CDFs: how
//! environment maps are importance-sampled (pbrt's Distribution1D/2D, continuous inside each cell).

use glam::Vec2;

/// A piecewise-constant density over [0, 1) with `func.len()` equal cells.
#[derive(Clone, Debug)]
pub struct Distribution1D {
    func: Vec<f32>,
    /// `cdf[0] = 0`, `cdf[n] = 1`.
    cdf: Vec<f32>,
    /// Integral of `func` over [0, 1).
    integral: f32,
    /// `guide[k]`: how many `cdf` entries are at most `k / G` (G = `guide.len() - 1`, a power of
    /// two, so that `u * G` and `k / G` are exact), so the search for `u` in `[k/G, (k+1)/G)` stays
    /// between `guide[k]` and `guide[k + 1]` and finds what a search of the whole CDF finds (the
    /// two binary searches of a 2D sample were 6% of an environment-lit render).
    guide: Vec<u32>,
}

impl Distribution1D {
    pub fn new(func: &[f32]) -> Self {
        let n = func.len().max(1);
        let func: Vec<f32> = if func.is_empty() {
            vec![0.0]
        } else {
            func.iter().map(|&f| f.max(0.0)).collect()
        };
        let mut cdf = Vec::with_capacity(n + 1);
        let mut acc = 0.0f64;
        cdf.push(0.0);
        for &f in &func {
            acc += f as f64 / n as f64;
            cdf.push(acc as f32);
        }
        let integral = acc as f32;
        if integral > 0.0 {
            for c in &mut cdf {
                *c = (*c as f64 / acc) as f32;
            }
        } else {
            // Uniform when everything is zero, so callers still get a valid density.
            for (i, c) in cdf.iter_mut().enumerate() {
                *c = i as f32 / n as f32;
            }
        }
        cdf[n] = 1.0;
        // About four cells a guide step (a quarter of `func`'s memory).
        let g = (n / 4).max(1).next_power_of_two();
        let mut guide = Vec::with_capacity(g + 1);
        let mut at = 0;
        for k in 0..=g {
            let x = k as f32 / g as f32;
            while at < cdf.len() && cdf[at] <= x {
                at += 1;
            }
            guide.push(at as u32);
        }
        Self {
            func,
            cdf,
            integral,
            guide,
        }
    }

    pub fn integral(&self) -> f32 {
        self.integral
    }

    /// The density at cell `i` (with respect to [0, 1)).
    pub fn pdf_cell(&self, i: usize) -> f32 {
        if self.integral > 0.0 {
            self.func[i] / self.integral
        } else {
            1.0
        }
    }

    /// A point in [0, 1), its cell, and the density there.
    pub fn sample(&self, u: f32) -> (f32, usize, f32) {
        let n = self.func.len();
        let g = self.guide.len() - 1;
        let k = ((u * g as f32) as usize).min(g);
        let lo = self.guide[k] as usize;
        let hi = self
            .guide
            .get(k + 1)
            .map_or(self.cdf.len(), |&h| h as usize);
        let i = (lo + self.cdf[lo..hi].partition_point(|&c| c <= u) - 1).min(n - 1);
        let width = self.cdf[i + 1] - self.cdf[i];
        let du = if width > 0.0 {
            ((u - self.cdf[i]) / width).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let x = ((i as f32 + du) / n as f32).min(1.0 - f32::EPSILON);
        (x, i, self.pdf_cell(i))
    }
}

/// A piecewise-constant density over [0, 1)^2: a marginal over rows (v), a conditional per row (u).
#[derive(Clone, Debug)]
pub struct Distribution2D {
    rows: Vec<Distribution1D>,
    marginal: Distribution1D,
    width: usize,
}

impl Distribution2D {
    /// From `func` in row-major order, `width` cells across.
    pub fn new(func: &[f32], width: usize) -> Self {
        let rows: Vec<Distribution1D> = func.chunks(width).map(Distribution1D::new).collect();
        let marginal = Distribution1D::new(&rows.iter().map(|r| r.integral()).collect::<Vec<_>>());
        Self {
            rows,
            marginal,
            width,
        }
    }

    /// A point in [0, 1)^2 and the density there.
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (v, row, pv) = self.marginal.sample(u.y);
        let (x, _, pu) = self.rows[row].sample(u.x);
        (Vec2::new(x, v), pu * pv)
    }

    /// The density at a point of [0, 1)^2.
    pub fn pdf(&self, p: Vec2) -> f32 {
        let h = self.rows.len();
        let row = ((p.y * h as f32) as usize).min(h - 1);
        let col = ((p.x * self.width as f32) as usize).min(self.width - 1);
        self.marginal.pdf_cell(row) * self.rows[row].pdf_cell(col)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guided_search_finds_the_cell_a_full_search_finds() {
        // A peaked function (most of the mass in a few cells, as a sun in a sky) and flat runs,
        // at sizes around the guide's powers of two.
        for n in [1, 2, 3, 7, 64, 100, 1000] {
            let f: Vec<f32> = (0..n)
                .map(|i| match i % 37 {
                    0 => 1e4,
                    1..=5 => 0.0,
                    k => k as f32 * 1e-3,
                })
                .collect();
            let d = Distribution1D::new(&f);
            for k in 0..20_000u32 {
                let u = (k as f32 / 20_000.0).min(1.0 - f32::EPSILON);
                let full = (d.cdf.partition_point(|&c| c <= u) - 1).min(n - 1);
                let (_, i, _) = d.sample(u);
                assert_eq!(i, full, "n {n}, u {u}");
            }
            // Exactly on every CDF value too (where the cells change).
            for &c in &d.cdf[..n] {
                let full = (d.cdf.partition_point(|&x| x <= c) - 1).min(n - 1);
                assert_eq!(d.sample(c).1, full, "n {n}, u {c}");
            }
        }
    }

    #[test]
    fn sampled_densities_match_the_function() {
        let f = [0.0, 1.0, 3.0, 0.0, 2.0, 2.0];
        let d = Distribution2D::new(&f, 3);
        // Density = f / mean(f) = f / (8 / 6).
        for (i, &fi) in f.iter().enumerate() {
            let p = Vec2::new((i % 3) as f32 / 3.0 + 0.1, (i / 3) as f32 / 2.0 + 0.2);
            assert!((d.pdf(p) - fi * 6.0 / 8.0).abs() < 1e-5);
        }
        for k in 0..64 {
            let u = Vec2::new((k % 8) as f32 / 8.0 + 0.03, (k / 8) as f32 / 8.0 + 0.05);
            let (p, pdf) = d.sample(u);
            assert!(pdf > 0.0);
            assert!((d.pdf(p) - pdf).abs() < 1e-5);
        }
    }
}
