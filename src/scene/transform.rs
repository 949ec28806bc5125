//! The transform of a scene-file element (`transform = { translate, rotate_x/y/z, scale }` or a
//! `matrix`), shared by CSG nodes and the scene description's assets.

use glam::{Mat4, Vec3};
use serde::Deserialize;

/// A scale: one factor, or one per axis.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(untagged)]
pub enum Scale {
    Uniform(f32),
    PerAxis([f32; 3]),
}

/// An affine transform from a scene file. Applied in this order: scale, then rotate about x, y and z
/// (degrees), then translate. `matrix` (16 numbers, column-major) excludes the others.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, try_from = "TransformFields")]
pub struct TransformSpec {
    pub translate: Option<[f32; 3]>,
    pub rotate_x: Option<f32>,
    pub rotate_y: Option<f32>,
    pub rotate_z: Option<f32>,
    pub scale: Option<Scale>,
    pub matrix: Option<[f32; 16]>,
}

/// What the file may hold, before the exclusivity check.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TransformFields {
    translate: Option<[f32; 3]>,
    rotate_x: Option<f32>,
    rotate_y: Option<f32>,
    rotate_z: Option<f32>,
    scale: Option<Scale>,
    matrix: Option<[f32; 16]>,
}

/// Why a scene file's transform is refused.
#[derive(Debug, thiserror::Error)]
pub enum TransformError {
    #[error("transform: `matrix` cannot be combined with translate/rotate/scale")]
    MatrixWithParts,
    #[error("transform: values must be finite")]
    NotFinite,
}

impl TryFrom<TransformFields> for TransformSpec {
    type Error = TransformError;
    fn try_from(f: TransformFields) -> Result<Self, TransformError> {
        let t = TransformSpec {
            translate: f.translate,
            rotate_x: f.rotate_x,
            rotate_y: f.rotate_y,
            rotate_z: f.rotate_z,
            scale: f.scale,
            matrix: f.matrix,
        };
        let parts = t.translate.is_some()
            || t.rotate_x.is_some()
            || t.rotate_y.is_some()
            || t.rotate_z.is_some()
            || t.scale.is_some();
        if t.matrix.is_some() && parts {
            return Err(TransformError::MatrixWithParts);
        }
        if !t.to_mat4().is_finite() {
            return Err(TransformError::NotFinite);
        }
        Ok(t)
    }
}

impl TransformSpec {
    /// Why the transform cannot place anything (singular: a zero scale), if so.
    pub fn problem(&self) -> Option<&'static str> {
        (self.to_mat4().determinant().abs() < 1e-12).then_some("is singular (a zero scale?)")
    }

    pub fn to_mat4(&self) -> Mat4 {
        if let Some(m) = self.matrix {
            return Mat4::from_cols_array(&m);
        }
        let s = match self.scale {
            None => Vec3::ONE,
            Some(Scale::Uniform(k)) => Vec3::splat(k),
            Some(Scale::PerAxis(v)) => Vec3::from_array(v),
        };
        let deg = |a: Option<f32>| a.unwrap_or(0.0).to_radians();
        Mat4::from_translation(Vec3::from_array(self.translate.unwrap_or([0.0; 3])))
            * Mat4::from_rotation_z(deg(self.rotate_z))
            * Mat4::from_rotation_y(deg(self.rotate_y))
            * Mat4::from_rotation_x(deg(self.rotate_x))
            * Mat4::from_scale(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<TransformSpec, String> {
        toml::from_str::<std::collections::BTreeMap<String, TransformSpec>>(s)
            .map(|m| m["t"].clone())
            .map_err(|e| e.to_string())
    }

    #[test]
    fn order_is_scale_rotate_translate() {
        let t = parse("t = { translate = [1, 2, 3], rotate_z = 90, scale = 2 }").unwrap();
        let p = t.to_mat4().transform_point3(Vec3::X);
        // (1,0,0) -> scale (2,0,0) -> rotate z 90 (0,2,0) -> translate (1,4,3).
        assert!((p - Vec3::new(1.0, 4.0, 3.0)).length() < 1e-5, "{p}");
        let t = parse("t = { scale = [1, 2, 3] }").unwrap();
        assert_eq!(
            t.to_mat4().transform_vector3(Vec3::ONE),
            Vec3::new(1.0, 2.0, 3.0)
        );
        let t = parse("t = { matrix = [1,0,0,0, 0,1,0,0, 0,0,1,0, 5,6,7,1] }").unwrap();
        assert_eq!(
            t.to_mat4().transform_point3(Vec3::ZERO),
            Vec3::new(5.0, 6.0, 7.0)
        );
    }

    #[test]
    fn typos_and_mixtures_are_errors() {
        let e = parse("t = { translat = [1, 2, 3] }").unwrap_err();
        assert!(e.contains("translat"), "{e}");
        let e =
            parse("t = { matrix = [1,0,0,0, 0,1,0,0, 0,0,1,0, 5,6,7,1], scale = 2 }").unwrap_err();
        assert!(e.contains("matrix"), "{e}");
    }
}
