//! Warps from the unit square onto the domains the renderer samples (disk, hemisphere, cone,
//! triangle, spherical triangle, spherical rectangle, and the square itself by a bilinear
//! density), each beside its pdf on that domain and its inverse back to the square.
//!
//! The forward maps keep the arithmetic the renders were made with: images depend on their last bits.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use glam::{Vec2, Vec3};

/// Shirley and Chiu's concentric map from the unit square to the unit disk: area-preserving and of low
/// distortion, so stratified samples stay stratified.
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let a = 2.0 * u - Vec2::ONE;
    if a == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let (r, theta) = if a.x.abs() > a.y.abs() {
        (a.x, FRAC_PI_4 * (a.y / a.x))
    } else {
        (a.y, FRAC_PI_2 - FRAC_PI_4 * (a.x / a.y))
    };
    let (s, c) = theta.sin_cos();
    Vec2::new(r * c, r * s)
}

/// The area density of `concentric_disk` on the unit disk.
pub fn concentric_disk_pdf() -> f32 {
    1.0 / PI
}

/// The square point `concentric_disk` maps to `p` (on the unit disk).
pub fn concentric_disk_inverse(p: Vec2) -> Vec2 {
    if p == Vec2::ZERO {
        return Vec2::splat(0.5);
    }
    let r = p.length();
    // In each quadrant wedge the signed radius is the dominant square coordinate and the angle from
    // the wedge's axis (within +-pi/4) scales the other one.
    let a = if p.x.abs() > p.y.abs() {
        let ax = r.copysign(p.x);
        Vec2::new(ax, ax * (p.y / p.x).atan() / FRAC_PI_4)
    } else {
        let ay = r.copysign(p.y);
        Vec2::new(ay * (p.x / p.y).atan() / FRAC_PI_4, ay)
    };
    (a + Vec2::ONE) * 0.5
}

/// Cosine-weighted directions on the hemisphere around +z (Malley's method over the polar disk map).
pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt())
}

/// The solid-angle density of `cosine_hemisphere` at a direction of z component `cos_theta`.
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) / PI
}

/// The square point `cosine_hemisphere` maps to unit `w` (z >= 0).
pub fn cosine_hemisphere_inverse(w: Vec3) -> Vec2 {
    Vec2::new(w.x * w.x + w.y * w.y, turn_fraction(w))
}

/// Uniform directions in the cone around +z whose half-angle has `1 - cos` = `omc_max`; the cone is
/// given by one minus its cosine because that stays exact for the small cones of far spheres. Returns
/// the local direction and its sin(theta).
pub fn uniform_cone(u: Vec2, omc_max: f32) -> (Vec3, f32) {
    let omc = u.x * omc_max;
    let cos = 1.0 - omc;
    let sin = (omc * (2.0 - omc)).max(0.0).sqrt();
    let (sp, cp) = (2.0 * PI * u.y).sin_cos();
    (Vec3::new(sin * cp, sin * sp, cos), sin)
}

/// The solid angle of the cone `uniform_cone` samples.
pub fn uniform_cone_solid_angle(omc_max: f32) -> f32 {
    2.0 * PI * omc_max
}

/// The solid-angle density of `uniform_cone` inside its cone.
pub fn uniform_cone_pdf(omc_max: f32) -> f32 {
    1.0 / uniform_cone_solid_angle(omc_max)
}

/// The square point `uniform_cone` maps to unit `w` inside the cone.
pub fn uniform_cone_inverse(w: Vec3, omc_max: f32) -> Vec2 {
    // 1 - cos from the sine, exact near the axis: (1 - cos)(1 + cos) = sin^2.
    let omc = (w.x * w.x + w.y * w.y) / (1.0 + w.z);
    Vec2::new(omc / omc_max, turn_fraction(w))
}

/// Uniform barycentrics `(b1, b2)` on a triangle (the square-root parameterisation).
pub fn uniform_triangle(u: Vec2) -> (f32, f32) {
    let s = u.x.sqrt();
    (s * (1.0 - u.y), s * u.y)
}

/// The density of `uniform_triangle` over barycentric coordinates (the triangle b1, b2 >= 0,
/// b1 + b2 <= 1 has area 1/2); over a world triangle it is one over the area.
pub fn uniform_triangle_pdf() -> f32 {
    2.0
}

/// The square point `uniform_triangle` maps to barycentrics `(b1, b2)`.
pub fn uniform_triangle_inverse(b1: f32, b2: f32) -> Vec2 {
    let s = b1 + b2;
    Vec2::new(s * s, if s > 0.0 { b2 / s } else { 0.0 })
}

/// The solid angle of the spherical triangle with unit corners `a`, `b`, `c` (Van Oosterom and
/// Strackee's formula: no arccosines, so accurate down to tiny triangles).
pub fn spherical_triangle_area(a: Vec3, b: Vec3, c: Vec3) -> f32 {
    (2.0 * a
        .dot(b.cross(c))
        .atan2(1.0 + a.dot(b) + a.dot(c) + b.dot(c)))
    .abs()
}

/// A direction uniform in solid angle over the spherical triangle with unit corners `a`, `b`, `c`
/// (Arvo 1995): `u.x` picks the sub-triangle of the right area, `u.y` the point along its arc; the
/// pdf is one over `spherical_triangle_area`. None for a degenerate triangle.
pub fn spherical_triangle(a: Vec3, b: Vec3, c: Vec3, u: Vec2) -> Option<Vec3> {
    let (alpha, area, _) = arvo_angles(a, b, c)?;
    // The sub-triangle a, b, c' with area u.x * area: the angle at a stays alpha.
    let ap = PI + u.x * area;
    let (sin_ap, cos_ap) = ap.sin_cos();
    let (sin_alpha, cos_alpha) = alpha.sin_cos();
    let sin_phi = sin_ap * cos_alpha - cos_ap * sin_alpha;
    let cos_phi = cos_ap * cos_alpha + sin_ap * sin_alpha;
    let k1 = cos_phi + cos_alpha;
    let k2 = sin_phi - sin_alpha * a.dot(b);
    let cos_bp = ((k2 + (k2 * cos_phi - k1 * sin_phi) * cos_alpha)
        / ((k2 * sin_phi + k1 * cos_phi) * sin_alpha))
        .clamp(-1.0, 1.0);
    let sin_bp = (1.0 - cos_bp * cos_bp).max(0.0).sqrt();
    let cp = cos_bp * a + sin_bp * (c - a * c.dot(a)).try_normalize()?;
    // Uniform along the arc from b to c' (in the cosine of the angle to b).
    let cos_t = 1.0 - u.y * (1.0 - cp.dot(b));
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    Some(cos_t * b + sin_t * (cp - b * cp.dot(b)).try_normalize()?)
}

/// What Arvo's map and its inverse share: the angle at `a`, the area (from the corner angles,
/// between the planes of the edges meeting there) and the unit normal of the plane through the
/// origin, `a` and `b`; None for a degenerate triangle (also for a NaN area).
fn arvo_angles(a: Vec3, b: Vec3, c: Vec3) -> Option<(f32, f32, Vec3)> {
    let (n_ab, n_bc, n_ca) = (
        a.cross(b).try_normalize()?,
        b.cross(c).try_normalize()?,
        c.cross(a).try_normalize()?,
    );
    let alpha = angle_between(n_ab, -n_ca);
    let beta = angle_between(n_bc, -n_ab);
    let gamma = angle_between(n_ca, -n_bc);
    let area = alpha + beta + gamma - PI;
    (!area.is_nan() && area > 0.0).then_some((alpha, area, n_ab))
}

/// The square point `spherical_triangle(a, b, c, u)` maps to direction `w` (pbrt-v4's inversion of
/// Arvo's map): the sub-triangle a, b, c' through `w` gives `u.x` by its area, the arc from b to c'
/// gives `u.y`. None for a degenerate triangle.
pub fn spherical_triangle_inverse(a: Vec3, b: Vec3, c: Vec3, w: Vec3) -> Option<Vec2> {
    let (alpha, area, n_ab) = arvo_angles(a, b, c)?;
    // c' is where the great circle through b and w meets the arc from a to c.
    let mut cp = b.cross(w).cross(c.cross(a)).try_normalize()?;
    if cp.dot(a + c) < 0.0 {
        cp = -cp;
    }
    // Within 0.1 degrees of a, the sub-triangle's area is lost to rounding: it is empty.
    let ux = if a.dot(cp) > 0.999_998_5 {
        0.0
    } else {
        match (cp.cross(b).try_normalize(), a.cross(cp).try_normalize()) {
            (Some(n_cpb), Some(n_acp)) => {
                let sub = alpha + angle_between(n_ab, n_cpb) + angle_between(n_acp, -n_cpb) - PI;
                sub / area
            }
            _ => 0.5,
        }
    };
    let uy = (1.0 - w.dot(b)) / (1.0 - cp.dot(b));
    Some(Vec2::new(ux.clamp(0.0, 1.0), uy.clamp(0.0, 1.0)))
}

/// A rectangle as seen from a point, set up for Urena, Fajardo and King's (2013) sampling of the
/// solid angle it subtends: in the frame of its edges, with the point at the origin and the
/// rectangle's plane at z = `z0` < 0; `x0..x1` and `y0..y1` are its extents in that plane.
#[derive(Clone, Copy, Debug)]
pub struct SphericalRectangle {
    origin: Vec3,
    /// The frame: unit edges and the normal pointing away from the rectangle.
    x: Vec3,
    y: Vec3,
    z: Vec3,
    x0: f32,
    x1: f32,
    y0: f32,
    y1: f32,
    z0: f32,
    /// The z components of the normals of the planes through the origin and the edges at y0 and y1.
    b0: f32,
    b1: f32,
    /// The offset of the sub-rectangle area in `sample` (2 pi less two of the corner angles).
    k: f32,
    area: f32,
}

impl SphericalRectangle {
    /// The rectangle with corner `corner` and orthogonal edges `ex`, `ey`, seen from `p`; None
    /// where it subtends no solid angle (degenerate, or `p` in its plane).
    pub fn new(p: Vec3, corner: Vec3, ex: Vec3, ey: Vec3) -> Option<Self> {
        let (exl, eyl) = (ex.length(), ey.length());
        let (x, y) = (ex / exl, ey / eyl);
        let mut z = x.cross(y);
        let d = corner - p;
        let (x0, y0, mut z0) = (d.dot(x), d.dot(y), d.dot(z));
        if z0 > 0.0 {
            z = -z;
            z0 = -z0;
        }
        let (x1, y1) = (x0 + exl, y0 + eyl);
        let v00 = Vec3::new(x0, y0, z0);
        let v01 = Vec3::new(x0, y1, z0);
        let v10 = Vec3::new(x1, y0, z0);
        let v11 = Vec3::new(x1, y1, z0);
        let n0 = v00.cross(v10).try_normalize()?;
        let n1 = v10.cross(v11).try_normalize()?;
        let n2 = v11.cross(v01).try_normalize()?;
        let n3 = v01.cross(v00).try_normalize()?;
        let (g0, g1) = (angle_between(-n0, n1), angle_between(-n1, n2));
        let (g2, g3) = (angle_between(-n2, n3), angle_between(-n3, n0));
        let k = 2.0 * PI - g2 - g3;
        let area = g0 + g1 - k;
        if area.is_nan() || area <= 0.0 {
            return None;
        }
        Some(Self {
            origin: p,
            x,
            y,
            z,
            x0,
            x1,
            y0,
            y1,
            z0,
            b0: n0.z,
            b1: n2.z,
            k,
            area,
        })
    }

    /// The solid angle (sr); the pdf of `sample` is its inverse.
    pub fn solid_angle(&self) -> f32 {
        self.area
    }

    /// A point of the rectangle whose direction from the origin is uniform in solid angle: `u.x`
    /// picks the sub-rectangle `x0..xu` of area `u.x` times the whole, `u.y` the height along it
    /// (uniform in the sine of its elevation).
    pub fn sample(&self, u: Vec2) -> Vec3 {
        let au = u.x * self.area + self.k;
        let fu = (au.cos() * self.b0 - self.b1) / au.sin();
        let cu = (1.0 / (fu * fu + self.b0 * self.b0).sqrt())
            .copysign(fu)
            .clamp(-1.0 + f32::EPSILON, 1.0 - f32::EPSILON);
        let xu = (-(cu * self.z0) / (1.0 - cu * cu).max(0.0).sqrt()).clamp(self.x0, self.x1);
        let dd = (xu * xu + self.z0 * self.z0).sqrt();
        let (h0, h1) = self.heights(dd);
        let hv = h0 + u.y * (h1 - h0);
        let yv = if hv * hv < 1.0 - 1e-6 {
            hv * dd / (1.0 - hv * hv).sqrt()
        } else {
            self.y1
        };
        self.origin + self.x * xu + self.y * yv.clamp(self.y0, self.y1) + self.z * self.z0
    }

    /// The square point `sample` maps to point `q` of the rectangle.
    pub fn inverse(&self, q: Vec3) -> Vec2 {
        let d = q - self.origin;
        let (xu, yv) = (d.dot(self.x), d.dot(self.y));
        // The sub-rectangle x0..xu, as `sample` measures it.
        let corner = self.origin + self.x * self.x0 + self.y * self.y0 + self.z * self.z0;
        let sub = Self::new(
            self.origin,
            corner,
            self.x * (xu - self.x0),
            self.y * (self.y1 - self.y0),
        )
        .map_or(0.0, |s| s.area);
        let dd = (xu * xu + self.z0 * self.z0).sqrt();
        let (h0, h1) = self.heights(dd);
        let hv = yv / (dd * dd + yv * yv).sqrt();
        Vec2::new(
            (sub / self.area).clamp(0.0, 1.0),
            ((hv - h0) / (h1 - h0)).clamp(0.0, 1.0),
        )
    }

    /// The sines of the elevations of the rectangle's edges at y0 and y1 seen across distance `dd`.
    fn heights(&self, dd: f32) -> (f32, f32) {
        let h = |y: f32| y / (dd * dd + y * y).sqrt();
        (h(self.y0), h(self.y1))
    }
}

/// `x` in [0, 1] with density proportional to the line from `a` at 0 to `b` at 1 (a, b >= 0).
fn linear(u: f32, a: f32, b: f32) -> f32 {
    if a + b <= 0.0 {
        return u;
    }
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    let x = u * (a + b) / (a + (a * a + u * (b * b - a * a)).max(0.0).sqrt());
    x.min(1.0 - f32::EPSILON / 2.0)
}

fn linear_inverse(x: f32, a: f32, b: f32) -> f32 {
    if a + b <= 0.0 {
        return x;
    }
    x * (a * (2.0 - x) + b * x) / (a + b)
}

/// A point of the unit square with density proportional to the bilinear interpolation of the
/// corner weights `w` (at (0, 0), (1, 0), (0, 1), (1, 1); non-negative): y from its marginal, then
/// x from its conditional. Used to warp a square sample by the cosines at a light's corners.
pub fn bilinear(u: Vec2, w: [f32; 4]) -> Vec2 {
    let y = linear(u.y, w[0] + w[1], w[2] + w[3]);
    let lerp = |a: f32, b: f32| a + y * (b - a);
    Vec2::new(linear(u.x, lerp(w[0], w[2]), lerp(w[1], w[3])), y)
}

pub fn bilinear_pdf(p: Vec2, w: [f32; 4]) -> f32 {
    if p.min_element() < 0.0 || p.max_element() > 1.0 {
        return 0.0;
    }
    let sum = w.iter().sum::<f32>();
    if sum <= 0.0 {
        return 1.0;
    }
    let (x, y) = (p.x, p.y);
    4.0 * ((1.0 - x) * (1.0 - y) * w[0]
        + x * (1.0 - y) * w[1]
        + (1.0 - x) * y * w[2]
        + x * y * w[3])
        / sum
}

pub fn bilinear_inverse(p: Vec2, w: [f32; 4]) -> Vec2 {
    let lerp = |a: f32, b: f32| a + p.y * (b - a);
    Vec2::new(
        linear_inverse(p.x, lerp(w[0], w[2]), lerp(w[1], w[3])),
        linear_inverse(p.y, w[0] + w[1], w[2] + w[3]),
    )
}

/// The angle between unit vectors, accurate near 0 and pi (half-chord arcsines).
fn angle_between(v1: Vec3, v2: Vec3) -> f32 {
    if v1.dot(v2) < 0.0 {
        PI - 2.0 * ((v1 + v2).length() / 2.0).min(1.0).asin()
    } else {
        2.0 * ((v2 - v1).length() / 2.0).min(1.0).asin()
    }
}

/// The azimuth of `w` around +z as a fraction of a turn, in [0, 1).
fn turn_fraction(w: Vec3) -> f32 {
    let phi = w.y.atan2(w.x);
    let t = if phi < 0.0 { phi + 2.0 * PI } else { phi } / (2.0 * PI);
    if t >= 1.0 {
        0.0
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI as PI64;

    /// The midpoints of an n x n grid over the unit square.
    fn grid(n: usize) -> impl Iterator<Item = Vec2> {
        (0..n * n).map(move |k| Vec2::new((k % n) as f32 + 0.5, (k / n) as f32 + 0.5) / n as f32)
    }

    fn assert_round_trip(u: Vec2, back: Vec2, what: &str) {
        assert!(
            (u - back).abs().max_element() < 2e-4,
            "{what}: {u} -> {back}"
        );
    }

    /// The integral of `pdf(theta)` over the directions with theta below `theta_max` (midpoint rule;
    /// the pdfs here do not depend on phi).
    fn integrate_over_cap(theta_max: f64, pdf: impl Fn(f64) -> f64) -> f64 {
        let n = 4096;
        let dt = theta_max / n as f64;
        (0..n)
            .map(|i| {
                let t = (i as f64 + 0.5) * dt;
                pdf(t) * t.sin() * dt * 2.0 * PI64
            })
            .sum()
    }

    #[test]
    fn concentric_disk_is_uniform_and_inverts() {
        // Uniform on the unit disk: its pdf times the disk's area is one, and the mean squared radius
        // of a grid of samples is 1/2.
        assert!((concentric_disk_pdf() * PI - 1.0).abs() < 1e-6);
        let n = 64;
        let m = grid(n)
            .map(|u| concentric_disk(u).length_squared())
            .sum::<f32>()
            / (n * n) as f32;
        assert!((m - 0.5).abs() < 1e-3, "{m}");
        for u in grid(37) {
            let p = concentric_disk(u);
            assert!(p.length() <= 1.0 + 1e-6);
            assert_round_trip(u, concentric_disk_inverse(p), "concentric disk");
        }
    }

    #[test]
    fn cosine_hemisphere_pdf_integrates_to_one_and_inverts() {
        let total =
            integrate_over_cap(PI64 / 2.0, |t| cosine_hemisphere_pdf(t.cos() as f32) as f64);
        assert!((total - 1.0).abs() < 1e-4, "{total}");
        for u in grid(37) {
            let w = cosine_hemisphere(u);
            assert!((w.length() - 1.0).abs() < 1e-5 && w.z >= 0.0);
            assert_round_trip(u, cosine_hemisphere_inverse(w), "cosine hemisphere");
        }
    }

    #[test]
    fn uniform_cone_pdf_integrates_to_one_and_inverts() {
        for theta_max in [1e-3f64, 0.3, 1.2, PI64 / 2.0, 2.5] {
            let omc_max = (1.0 - theta_max.cos()) as f32;
            let total = integrate_over_cap(theta_max, |_| uniform_cone_pdf(omc_max) as f64);
            assert!((total - 1.0).abs() < 1e-3, "theta {theta_max}: {total}");
            for u in grid(23) {
                let (w, sin) = uniform_cone(u, omc_max);
                assert!((w.length() - 1.0).abs() < 1e-5, "{w}");
                assert!((sin - w.truncate().length()).abs() < 1e-6);
                assert!(w.z >= (1.0 - omc_max) - 1e-6);
                assert_round_trip(u, uniform_cone_inverse(w, omc_max), "uniform cone");
            }
        }
    }

    #[test]
    fn uniform_triangle_pdf_integrates_to_one_and_inverts() {
        // Midpoint rule over the barycentric triangle, cells cut by the diagonal counted by halves.
        let n = 256;
        let h = 1.0 / n as f64;
        let mut total = 0.0f64;
        for i in 0..n {
            for j in 0..n - i {
                let cell = if i + j == n - 1 { 0.5 } else { 1.0 };
                total += uniform_triangle_pdf() as f64 * cell * h * h;
            }
        }
        assert!((total - 1.0).abs() < 1e-9, "{total}");
        for u in grid(37) {
            let (b1, b2) = uniform_triangle(u);
            assert!(b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0 + 1e-6);
            assert_round_trip(u, uniform_triangle_inverse(b1, b2), "uniform triangle");
        }
    }

    #[test]
    fn bilinear_pdf_integrates_to_one_matches_its_samples_and_inverts() {
        for w in [
            [1.0, 1.0, 1.0, 1.0],
            [0.01, 0.5, 2.0, 0.3],
            [0.0, 1.0, 0.0, 1.0],
        ] {
            let n = 256;
            let total = grid(n).map(|p| bilinear_pdf(p, w)).sum::<f32>() / (n * n) as f32;
            assert!((total - 1.0).abs() < 1e-4, "{w:?}: {total}");
            // 4 x 4 bins of a grid of samples hold what the pdf gives them (midpoint rule).
            let mut bins = [0f64; 16];
            let m = 512;
            for u in grid(m) {
                let p = bilinear(u, w);
                assert!(p.min_element() >= 0.0 && p.max_element() < 1.0, "{p}");
                let k = (p.y * 4.0) as usize * 4 + (p.x * 4.0) as usize;
                bins[k] += 1.0 / (m * m) as f64;
                assert_round_trip(u, bilinear_inverse(p, w), "bilinear");
            }
            for (k, &got) in bins.iter().enumerate() {
                let cell = Vec2::new((k % 4) as f32, (k / 4) as f32) / 4.0;
                let expected = grid(32)
                    .map(|q| bilinear_pdf(cell + q / 4.0, w) as f64)
                    .sum::<f64>()
                    / (16.0 * 1024.0);
                assert!(
                    (got - expected).abs() < 0.02 * expected + 1e-4,
                    "{w:?} bin {k}: {got} vs {expected}"
                );
            }
        }
    }

    /// A triangle of unequal sides and angles, in front of the origin.
    const LOPSIDED: [Vec3; 3] = [
        Vec3::new(0.3, -0.2, 1.0),
        Vec3::new(2.0, 0.4, 0.6),
        Vec3::new(-0.5, 1.5, 0.9),
    ];

    #[test]
    fn spherical_triangle_inverts() {
        let v = LOPSIDED;
        for p in [
            Vec3::ZERO,
            Vec3::new(0.2, 0.1, 0.75),
            Vec3::new(0.0, 0.0, -8.0),
        ] {
            let [a, b, c] = v.map(|q| (q - p).normalize());
            for u in grid(37) {
                let w = spherical_triangle(a, b, c, u).unwrap();
                let back = spherical_triangle_inverse(a, b, c, w).unwrap();
                assert!(
                    (u - back).abs().max_element() < 2e-3,
                    "from {p}: {u} -> {back}"
                );
            }
        }
        assert!(spherical_triangle_inverse(Vec3::X, Vec3::X, Vec3::Y, Vec3::Z).is_none());
    }

    /// Uniform in solid angle over a rectangle, checked by counting: 4 x 4 cells of
    /// the rectangle receive samples in proportion to the solid angles they subtend (each measured
    /// as a rectangle of its own); samples invert; the solid angle matches the sum of the cells'.
    #[test]
    fn spherical_rectangle_is_uniform_in_solid_angle_and_inverts() {
        let (corner, ex, ey) = (
            Vec3::new(-0.7, 1.0, -0.4),
            Vec3::new(1.6, 0.0, 0.0),
            Vec3::new(0.0, 0.6, 0.8),
        );
        for p in [
            Vec3::ZERO,
            Vec3::new(0.1, 1.6, 0.2),
            Vec3::new(3.0, -2.0, 1.0),
        ] {
            let r = SphericalRectangle::new(p, corner, ex, ey).unwrap();
            let cell = |i: usize, j: usize| {
                let c = corner + ex * (i as f32 / 4.0) + ey * (j as f32 / 4.0);
                SphericalRectangle::new(p, c, ex / 4.0, ey / 4.0)
                    .unwrap()
                    .solid_angle() as f64
            };
            let total: f64 = (0..16).map(|k| cell(k % 4, k / 4)).sum();
            assert!(
                (total - r.solid_angle() as f64).abs() < 1e-4 * total,
                "from {p}: {total} vs {}",
                r.solid_angle()
            );
            let mut bins = [0f64; 16];
            // Points of the R2 sequence, not a grid: the sub-rectangle edges are lines of
            // constant u.x, and a grid aligned with them miscounts whole columns of cells.
            let m = 512;
            let r2 = (0..m * m).map(|k| {
                let k = k as f64 + 0.5;
                Vec2::new(
                    (k * 0.754_877_666_2).fract() as f32,
                    (k * 0.569_840_291).fract() as f32,
                )
            });
            for u in r2 {
                let q = r.sample(u);
                let d = q - corner;
                let (s, t) = (
                    d.dot(ex) / ex.length_squared(),
                    d.dot(ey) / ey.length_squared(),
                );
                assert!(
                    (-1e-5..=1.0 + 1e-5).contains(&s) && (-1e-5..=1.0 + 1e-5).contains(&t),
                    "from {p}: {s} {t}"
                );
                assert!(d.dot(ex.cross(ey)).abs() < 1e-5, "off the plane");
                let k = ((t * 4.0) as usize).min(3) * 4 + ((s * 4.0) as usize).min(3);
                bins[k] += 1.0 / (m * m) as f64;
                let back = r.inverse(q);
                assert!(
                    (u - back).abs().max_element() < 2e-3,
                    "from {p}: {u} -> {back}"
                );
            }
            for (k, &got) in bins.iter().enumerate() {
                let expected = cell(k % 4, k / 4) / total;
                assert!(
                    (got - expected).abs() < 0.01 * expected + 1e-4,
                    "from {p}, cell {k}: {got} vs {expected}"
                );
            }
        }
        // From a point in its plane it subtends nothing.
        assert!(SphericalRectangle::new(corner + ex * 2.0, corner, ex, ey).is_none());
    }

    #[test]
    fn spherical_triangle_is_uniform_on_the_octant() {
        let (a, b, c) = (Vec3::X, Vec3::Y, Vec3::Z);
        let area = spherical_triangle_area(a, b, c);
        assert!((area as f64 - PI64 / 2.0).abs() < 1e-6, "{area}");
        // Uniform over the octant is uniform in z and in azimuth: 4 x 4 equal bins.
        let mut bins = [0u32; 16];
        for u in grid(64) {
            let w = spherical_triangle(a, b, c, u).unwrap();
            assert!(
                (w.length() - 1.0).abs() < 1e-5 && w.min_element() > -1e-5,
                "{w}"
            );
            let phi = w.y.atan2(w.x).clamp(0.0, PI / 2.0 - 1e-6) / (PI / 2.0);
            let k = ((w.z.clamp(0.0, 0.999_999) * 4.0) as usize) * 4 + (phi * 4.0) as usize;
            bins[k] += 1;
        }
        for (k, &n) in bins.iter().enumerate() {
            assert!(
                (n as f64 - 256.0).abs() < 0.1 * 256.0,
                "bin {k}: {n} of 4096"
            );
        }
    }

    #[test]
    fn spherical_triangle_integrates_like_area_sampling() {
        // The lopsided triangle seen from the origin; the integral of a smooth f over its solid angle
        // by both samplers (f / pdf with the solid-angle pdf; f cos / d^2 / pdf_area by area).
        let v = LOPSIDED;
        let f = |w: Vec3| 1.0 + 3.0 * w.x * w.x + w.y;
        let [a, b, c] = v.map(|p| p.normalize());
        let omega = spherical_triangle_area(a, b, c) as f64;
        let n = (v[1] - v[0]).cross(v[2] - v[0]);
        let area = 0.5 * n.length() as f64;
        let (mut sph, mut flat) = (0.0f64, 0.0f64);
        let cells = grid(128).count() as f64;
        for u in grid(128) {
            let w = spherical_triangle(a, b, c, u).unwrap();
            sph += f(w) as f64 * omega;
            let (b1, b2) = uniform_triangle(u);
            let q = v[0] * (1.0 - b1 - b2) + v[1] * b1 + v[2] * b2;
            let wq = q.normalize();
            let cos = (n.normalize().dot(wq)).abs() as f64;
            flat += f(wq) as f64 * cos / q.length_squared() as f64 * area;
        }
        let (sph, flat) = (sph / cells, flat / cells);
        assert!((sph - flat).abs() < 2e-3 * flat, "{sph} vs {flat}");
        assert!(spherical_triangle(a, a, c, Vec2::splat(0.5)).is_none());
    }

    #[test]
    fn spherical_triangle_integrates_like_area_sampling_from_a_grazing_point() {
        // The Cornell box light (two triangles, 1.98 m up) from the ceiling 1 cm above its plane:
        // slivers near the horizon and, above the light, a triangle of 5.5 sr. The irradiance on
        // the ceiling by both samplers (each a 512^2 quadrature) agrees to 1e-3 (relative).
        let tris = [
            [
                Vec3::new(-0.24, 1.98, 0.16),
                Vec3::new(-0.24, 1.98, -0.22),
                Vec3::new(0.23, 1.98, -0.22),
            ],
            [
                Vec3::new(-0.24, 1.98, 0.16),
                Vec3::new(0.23, 1.98, -0.22),
                Vec3::new(0.23, 1.98, 0.16),
            ],
        ];
        let cos = |w: Vec3| (-w.y).max(0.0) as f64;
        let cells = grid(512).count() as f64;
        for pz in [-0.23f32, -0.3, 0.0, 0.215] {
            let p = Vec3::new(0.01, 1.99, pz);
            for v in tris {
                let [a, b, c] = v.map(|q| (q - p).normalize());
                let omega = spherical_triangle_area(a, b, c) as f64;
                let n = (v[1] - v[0]).cross(v[2] - v[0]);
                let area = 0.5 * n.length() as f64;
                let (mut sph, mut flat) = (0.0f64, 0.0f64);
                for u in grid(512) {
                    sph += cos(spherical_triangle(a, b, c, u).unwrap()) * omega;
                    let (b1, b2) = uniform_triangle(u);
                    let q = v[0] * (1.0 - b1 - b2) + v[1] * b1 + v[2] * b2 - p;
                    let wq = q.normalize();
                    let cos_l = n.normalize().dot(wq).abs() as f64;
                    flat += cos(wq) * cos_l / q.length_squared() as f64 * area;
                }
                let (sph, flat) = (sph / cells, flat / cells);
                assert!(
                    (sph - flat).abs() < 1e-3 * flat,
                    "z {pz}, {omega} sr: {sph} vs {flat}"
                );
            }
        }
    }
}
