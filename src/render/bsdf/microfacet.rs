//! The GGX (Trowbridge-Reitz) microfacet distribution with Smith's height-correlated masking, and
//! sampling of its visible normals (Heitz 2018), shared by the base's specular lobes and the clearcoat.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

pub(super) fn ggx_d(cos_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let c2 = cos_h * cos_h;
    let denom = c2 * (a2 - 1.0) + 1.0;
    a2 / (PI * denom * denom)
}

/// Smith's Lambda for GGX.
fn lambda(w: Vec3, alpha: f32) -> f32 {
    let c2 = w.z * w.z;
    let t2 = (1.0 - c2).max(0.0) / c2;
    0.5 * ((1.0 + alpha * alpha * t2).sqrt() - 1.0)
}

pub(super) fn g1(w: Vec3, alpha: f32) -> f32 {
    1.0 / (1.0 + lambda(w, alpha))
}

/// Smith's height-correlated masking-shadowing for a pair of directions.
pub(super) fn g2(o: Vec3, i: Vec3, alpha: f32) -> f32 {
    1.0 / (1.0 + lambda(o, alpha) + lambda(i, alpha))
}

/// A GGX normal visible from `o` (Heitz 2018, isotropic).
pub(super) fn sample_vndf(o: Vec3, alpha: f32, u: Vec2) -> Vec3 {
    let vh = Vec3::new(alpha * o.x, alpha * o.y, o.z).normalize();
    let len2 = vh.x * vh.x + vh.y * vh.y;
    let t1 = if len2 > 0.0 {
        Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt()
    } else {
        Vec3::X
    };
    let t2 = vh.cross(t1);
    let r = u.x.sqrt();
    let phi = 2.0 * PI * u.y;
    let p1 = r * phi.cos();
    let s = 0.5 * (1.0 + vh.z);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * phi.sin();
    let nh = p1 * t1 + p2 * t2 + (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt() * vh;
    Vec3::new(alpha * nh.x, alpha * nh.y, nh.z.max(1e-6)).normalize()
}
