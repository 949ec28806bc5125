//! The GGX (Trowbridge-Reitz) microfacet distribution with Smith's height-correlated masking, and
//! sampling of its visible normals (Heitz 2018), isotropic or stretched along the frame's tangent
//! (KHR_materials_anisotropy), shared by the base's specular lobes and the clearcoat.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

/// A GGX distribution in the local frame: alpha `ax` along the tangent (x), `ay` along the
/// bitangent (y). Isotropic ones take the isotropic formulas, so their results stay as they were.
#[derive(Clone, Copy, Debug)]
pub(super) struct Ggx {
    pub ax: f32,
    pub ay: f32,
}

impl Ggx {
    pub fn iso(alpha: f32) -> Self {
        Self {
            ax: alpha,
            ay: alpha,
        }
    }

    fn isotropic(&self) -> bool {
        self.ax == self.ay
    }

    /// The distribution of normals D(h).
    pub fn d(&self, h: Vec3) -> f32 {
        if self.isotropic() {
            return ggx_d(h.z, self.ay);
        }
        let (x, y) = (h.x / self.ax, h.y / self.ay);
        let s = x * x + y * y + h.z * h.z;
        1.0 / (PI * self.ax * self.ay * s * s)
    }

    /// Smith's Lambda.
    fn lambda(&self, w: Vec3) -> f32 {
        if self.isotropic() {
            return lambda(w, self.ay);
        }
        let (x, y) = (self.ax * w.x, self.ay * w.y);
        0.5 * ((1.0 + (x * x + y * y) / (w.z * w.z)).sqrt() - 1.0)
    }

    pub fn g1(&self, w: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Smith's height-correlated masking-shadowing for a pair of directions.
    pub fn g2(&self, o: Vec3, i: Vec3) -> f32 {
        1.0 / (1.0 + self.lambda(o) + self.lambda(i))
    }

    /// A normal visible from `o` (Heitz 2018): `o` stretched to the unit-roughness configuration,
    /// a point on the projected hemisphere, and the normal there stretched back.
    pub fn sample_vndf(&self, o: Vec3, u: Vec2) -> Vec3 {
        let vh = Vec3::new(self.ax * o.x, self.ay * o.y, o.z).normalize();
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
        Vec3::new(self.ax * nh.x, self.ay * nh.y, nh.z.max(1e-6)).normalize()
    }
}

fn ggx_d(cos_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let c2 = cos_h * cos_h;
    let denom = c2 * (a2 - 1.0) + 1.0;
    a2 / (PI * denom * denom)
}

/// Smith's Lambda for isotropic GGX.
fn lambda(w: Vec3, alpha: f32) -> f32 {
    let c2 = w.z * w.z;
    let t2 = (1.0 - c2).max(0.0) / c2;
    0.5 * ((1.0 + alpha * alpha * t2).sqrt() - 1.0)
}
