//! Transforms as scene files write them: translate, rotations in degrees, scale, or a whole matrix.
//! Shared by assets, CSG nodes and anything else a scene file places.

use glam::{Mat4, Quat, Vec3};
use serde::Deserialize;

/// `{ translate = [x,y,z], rotate_x/rotate_y/rotate_z = degrees, scale = s or [x,y,z] }` applied in the
/// order scale, rotate x, y, z, translate; or `{ matrix = [16 numbers, column-major] }` alone.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransformSpec {
    pub translate: Option<[f32; 3]>,
    pub rotate_x: Option<f32>,
    pub rotate_y: Option<f32>,
    pub rotate_z: Option<f32>,
    pub scale: Option<Scale>,
    pub matrix: Option<[f32; 16]>,
}

#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum Scale {
    Uniform(f32),
    Axes([f32; 3]),
}

impl TransformSpec {
    pub fn to_mat4(&self) -> Mat4 {
        if let Some(m) = self.matrix {
            return Mat4::from_cols_array(&m);
        }
        let scale = match self.scale {
            None => Vec3::ONE,
            Some(Scale::Uniform(s)) => Vec3::splat(s),
            Some(Scale::Axes(a)) => Vec3::from(a),
        };
        let deg = |a: Option<f32>| a.unwrap_or(0.0).to_radians();
        let rotation = Quat::from_rotation_z(deg(self.rotate_z))
            * Quat::from_rotation_y(deg(self.rotate_y))
            * Quat::from_rotation_x(deg(self.rotate_x));
        Mat4::from_scale_rotation_translation(
            scale,
            rotation,
            Vec3::from(self.translate.unwrap_or([0.0; 3])),
        )
    }

    /// Why the transform cannot place anything (a matrix mixed with parts, or a singular or
    /// non-finite result), if so.
    pub fn problem(&self) -> Option<&'static str> {
        let parts = self.translate.is_some()
            || self.rotate_x.is_some()
            || self.rotate_y.is_some()
            || self.rotate_z.is_some()
            || self.scale.is_some();
        if self.matrix.is_some() && parts {
            return Some("'matrix' cannot be combined with translate, rotate or scale");
        }
        let m = self.to_mat4();
        if !m.is_finite() {
            return Some("is not finite");
        }
        if m.determinant().abs() < 1e-12 {
            return Some("is singular (a zero scale?)");
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_is_scale_rotate_translate() {
        let t: TransformSpec =
            toml::from_str("translate = [1, 2, 3]\nrotate_y = 90\nscale = 2").unwrap();
        let p = t.to_mat4().transform_point3(Vec3::X);
        // (1,0,0) scaled to (2,0,0), turned about y to (0,0,-2), moved by (1,2,3).
        assert!((p - Vec3::new(1.0, 2.0, 1.0)).length() < 1e-5, "{p}");
        assert!(t.problem().is_none());
        let bad: TransformSpec = toml::from_str("scale = [1, 0, 1]").unwrap();
        assert!(bad.problem().is_some());
        assert!(toml::from_str::<TransformSpec>("rotate = 3").is_err());
    }
}
