//! Warps from the unit square onto the domains the renderer samples (disk, hemisphere, cone,
//! triangle, spherical triangle), each beside its pdf on that domain and its inverse back to the square.
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
    let (n_ab, n_bc, n_ca) = (
        a.cross(b).try_normalize()?,
        b.cross(c).try_normalize()?,
        c.cross(a).try_normalize()?,
    );
    // The corner angles are between the planes of the edges meeting there.
    let alpha = angle_between(n_ab, -n_ca);
    let beta = angle_between(n_bc, -n_ab);
    let gamma = angle_between(n_ca, -n_bc);
    let area = alpha + beta + gamma - PI;
    // Also refuses a NaN area.
    if area.is_nan() || area <= 0.0 {
        return None;
    }
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
        // A lopsided triangle seen from the origin; the integral of a smooth f over its solid angle
        // by both samplers (f / pdf with the solid-angle pdf; f cos / d^2 / pdf_area by area).
        let v = [
            Vec3::new(0.3, -0.2, 1.0),
            Vec3::new(2.0, 0.4, 0.6),
            Vec3::new(-0.5, 1.5, 0.9),
        ];
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
