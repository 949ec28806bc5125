//! Piecewise-constant distributions on [0,1) and [0,1)^2, sampled by inverting their CDFs: how
//! environment maps are importance-sampled (pbrt's Distribution1D/2D, continuous inside each cell).

use glam::Vec2;

/// A cell of a piecewise-constant density: the CDF where it starts and its density, side by side,
/// so that a sample reads both from one cache line. (In three arrays, and an environment's rows
/// each in their own, a sample of a sky waited on four or five cache misses, 7% of an
/// environment-lit render.)
#[derive(Clone, Copy, Debug)]
struct Cell {
    cdf: f32,
    pdf: f32,
}

/// A piecewise-constant density over [0, 1) with `func.len()` equal cells.
#[derive(Clone, Debug)]
pub struct Distribution1D {
    /// The CDF runs from `cells[0].cdf = 0` to 1 past the last cell.
    cells: Vec<Cell>,
    /// `guide[k]`: how many CDF values (with the closing 1) are at most `k / G` (G = `guide.len() -
    /// 1`, a power of two, so that `u * G` and `k / G` are exact), so the search for `u` in
    /// `[k/G, (k+1)/G)` stays between `guide[k]` and `guide[k + 1]` and finds what a search of the
    /// whole CDF finds (the two binary searches of a 2D sample were 6% of an environment-lit
    /// render).
    guide: Vec<u32>,
}

impl Distribution1D {
    pub fn new(func: &[f32]) -> Self {
        let mut cells = Vec::new();
        let mut guide = Vec::new();
        tabulate(func, func.len().max(1), &mut cells, &mut guide);
        Self { cells, guide }
    }

    /// The density at cell `i` (with respect to [0, 1)).
    pub fn pdf_cell(&self, i: usize) -> f32 {
        self.cells[i].pdf
    }

    /// A point in [0, 1), its cell, and the density there.
    pub fn sample(&self, u: f32) -> (f32, usize, f32) {
        sample(&self.cells, &self.guide, u)
    }
}

/// Appends the `n` cells and the guide of the density `func` (negative values and those past its
/// end as zero; uniform when nothing is positive) to `cells` and `guide`; returns its integral
/// over [0, 1).
fn tabulate(func: &[f32], n: usize, cells: &mut Vec<Cell>, guide: &mut Vec<u32>) -> f32 {
    let f = |i: usize| func.get(i).map_or(0.0, |&f| f.max(0.0));
    let mut cdf = Vec::with_capacity(n + 1);
    let mut acc = 0.0f64;
    cdf.push(0.0);
    for i in 0..n {
        acc += f(i) as f64 / n as f64;
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
    cells.extend((0..n).map(|i| Cell {
        cdf: cdf[i],
        pdf: if integral > 0.0 { f(i) / integral } else { 1.0 },
    }));
    // About four cells a guide step (a quarter of `func`'s memory).
    let g = guide_steps(n);
    let mut at = 0;
    for k in 0..=g {
        let x = k as f32 / g as f32;
        while at < cdf.len() && cdf[at] <= x {
            at += 1;
        }
        guide.push(at as u32);
    }
    integral
}

/// The steps of the guide of `n` cells.
fn guide_steps(n: usize) -> usize {
    (n / 4).max(1).next_power_of_two()
}

/// A point in [0, 1) of the density with `cells` and `guide`, its cell, and the density there.
fn sample(cells: &[Cell], guide: &[u32], u: f32) -> (f32, usize, f32) {
    let n = cells.len();
    let g = guide.len() - 1;
    let k = ((u * g as f32) as usize).min(g);
    // The closing CDF value 1 is above every u in [0, 1): the search never needs it (at u = 1,
    // the last cell either way).
    let lo = (guide[k] as usize).min(n);
    let hi = guide.get(k + 1).map_or(n, |&h| h as usize).clamp(lo, n);
    let i = (lo + cells[lo..hi].partition_point(|c| c.cdf <= u) - 1).min(n - 1);
    let start = cells[i].cdf;
    let width = cells.get(i + 1).map_or(1.0, |c| c.cdf) - start;
    let du = if width > 0.0 {
        ((u - start) / width).clamp(0.0, 1.0)
    } else {
        0.5
    };
    let x = ((i as f32 + du) / n as f32).min(1.0 - f32::EPSILON);
    (x, i, cells[i].pdf)
}

/// A piecewise-constant density over [0, 1)^2: a marginal over rows (v), a conditional per row (u),
/// the rows' cells and guides each in one array (a row's cells `width` apart, its guide `guide`
/// entries apart).
#[derive(Clone, Debug)]
pub struct Distribution2D {
    marginal: Distribution1D,
    cells: Vec<Cell>,
    guides: Vec<u32>,
    width: usize,
    guide: usize,
}

impl Distribution2D {
    /// From `func` in row-major order, `width` cells across.
    pub fn new(func: &[f32], width: usize) -> Self {
        let width = width.max(1);
        let rows = func.len().div_ceil(width).max(1);
        let guide = guide_steps(width) + 1;
        let mut cells = Vec::with_capacity(rows * width);
        let mut guides = Vec::with_capacity(rows * guide);
        // `tabulate` reads only the row's `width` values (a short last row padded with zeros).
        let integrals: Vec<f32> = (0..rows)
            .map(|r| {
                tabulate(
                    func.get(r * width..).unwrap_or(&[]),
                    width,
                    &mut cells,
                    &mut guides,
                )
            })
            .collect();
        Self {
            marginal: Distribution1D::new(&integrals),
            cells,
            guides,
            width,
            guide,
        }
    }

    /// Row `r`'s cells and guide.
    fn row(&self, r: usize) -> (&[Cell], &[u32]) {
        (
            &self.cells[r * self.width..(r + 1) * self.width],
            &self.guides[r * self.guide..(r + 1) * self.guide],
        )
    }

    /// A point in [0, 1)^2 and the density there.
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        let (v, row, pv) = self.marginal.sample(u.y);
        let (cells, guide) = self.row(row);
        let (x, _, pu) = sample(cells, guide, u.x);
        (Vec2::new(x, v), pu * pv)
    }

    /// The density at a point of [0, 1)^2.
    pub fn pdf(&self, p: Vec2) -> f32 {
        let rows = self.marginal.cells.len();
        let row = ((p.y * rows as f32) as usize).min(rows - 1);
        let col = ((p.x * self.width as f32) as usize).min(self.width - 1);
        self.marginal.pdf_cell(row) * self.cells[row * self.width + col].pdf
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
            let cdf: Vec<f32> = d.cells.iter().map(|c| c.cdf).chain([1.0]).collect();
            for k in 0..20_000u32 {
                let u = (k as f32 / 20_000.0).min(1.0 - f32::EPSILON);
                let full = (cdf.partition_point(|&c| c <= u) - 1).min(n - 1);
                let (_, i, _) = d.sample(u);
                assert_eq!(i, full, "n {n}, u {u}");
            }
            // Exactly on every CDF value too (where the cells change).
            for &c in &cdf[..n] {
                let full = (cdf.partition_point(|&x| x <= c) - 1).min(n - 1);
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
