//! The `[[light]]` tables of a scene file: punctual, area and environment lights, each checked and
//! turned into a scene `Light` (area lights facing a point or along a normal).

use std::path::{Path, PathBuf};

use glam::Vec3;
use serde::Deserialize;

use crate::scene::{
    DirectionalLight, DiskLight, EnvMap, Light, LoadError, PointLight, RectLight, SphereLight,
    SpotLight,
};

/// Why a light of a scene file is refused.
#[derive(Debug, thiserror::Error)]
pub(super) enum LightError {
    #[error("color and strength must be finite and not negative")]
    Color,
    #[error("{0} must be positive")]
    NotPositive(&'static str),
    #[error("give exactly one of normal and look_at")]
    Facing,
    #[error("the facing direction is zero")]
    ZeroFacing,
    #[error("a corner rectangle faces edge_u x edge_v")]
    CornerFacing,
    #[error("a rect light takes center and size, or corner, edge_u and edge_v")]
    RectShape,
    #[error("the rectangle has no area")]
    NoArea,
    #[error("{0}")]
    EnvMap(LoadError),
}

/// A light of the scene file; `color` is linear RGB, scaled by the strength field of its kind.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub(super) enum LightDesc {
    Point(PointDesc),
    Spot(SpotDesc),
    Directional(DirectionalDesc),
    Sphere(SphereDesc),
    Disk(DiskDesc),
    Rect(RectDesc),
    Environment(EnvironmentDesc),
}

/// An emitting sphere: `radiance` (W/sr/m^2) is `color * strength`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SphereDesc {
    center: [f32; 3],
    radius: f32,
    #[serde(default = "white")]
    color: [f32; 3],
    strength: f32,
}

/// A one-sided disk facing `look_at` (or along `normal`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DiskDesc {
    center: [f32; 3],
    radius: f32,
    normal: Option<[f32; 3]>,
    look_at: Option<[f32; 3]>,
    #[serde(default = "white")]
    color: [f32; 3],
    strength: f32,
}

/// A one-sided rectangle: `center` and `size = [w, h]` facing `look_at` (or along `normal`), or the
/// parallelogram `corner + s edge_u + t edge_v` emitting towards `edge_u x edge_v`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RectDesc {
    center: Option<[f32; 3]>,
    size: Option<[f32; 2]>,
    normal: Option<[f32; 3]>,
    look_at: Option<[f32; 3]>,
    corner: Option<[f32; 3]>,
    edge_u: Option<[f32; 3]>,
    edge_v: Option<[f32; 3]>,
    #[serde(default = "white")]
    color: [f32; 3],
    strength: f32,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PointDesc {
    position: [f32; 3],
    #[serde(default = "white")]
    color: [f32; 3],
    /// W/sr.
    intensity: f32,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SpotDesc {
    position: [f32; 3],
    look_at: [f32; 3],
    #[serde(default = "white")]
    color: [f32; 3],
    intensity: f32,
    /// Full-intensity half angle and cut-off half angle, degrees.
    #[serde(default)]
    inner_angle: f32,
    #[serde(default = "outer")]
    outer_angle: f32,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DirectionalDesc {
    /// Where the light travels to.
    direction: [f32; 3],
    #[serde(default = "white")]
    color: [f32; 3],
    /// Irradiance on a surface facing the light.
    irradiance: f32,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct EnvironmentDesc {
    #[serde(default = "white")]
    color: [f32; 3],
    #[serde(default = "super::material::one")]
    strength: f32,
    /// A lat-long (equirectangular) .exr or .hdr map, relative to the scene file.
    map: Option<PathBuf>,
    /// Turns the map about +Y, degrees.
    #[serde(default)]
    rotate_y: f32,
}

pub(super) fn white() -> [f32; 3] {
    [1.0; 3]
}
fn outer() -> f32 {
    45.0
}

/// `c` scaled by `k`: finite and not negative.
fn rgb(c: [f32; 3], k: f32) -> Result<Vec3, LightError> {
    let v = Vec3::from(c) * k;
    if v.is_finite() && v.min_element() >= 0.0 {
        Ok(v)
    } else {
        Err(LightError::Color)
    }
}

fn positive(name: &'static str, v: f32) -> Result<f32, LightError> {
    if v > 0.0 && v.is_finite() {
        Ok(v)
    } else {
        Err(LightError::NotPositive(name))
    }
}

/// The unit normal of an area light: given, or towards `look_at`.
fn facing(
    center: Vec3,
    normal: Option<[f32; 3]>,
    look_at: Option<[f32; 3]>,
) -> Result<Vec3, LightError> {
    let n = match (normal, look_at) {
        (Some(n), None) => Vec3::from(n),
        (None, Some(t)) => Vec3::from(t) - center,
        _ => return Err(LightError::Facing),
    };
    let n = n.normalize_or_zero();
    if n == Vec3::ZERO || !n.is_finite() {
        return Err(LightError::ZeroFacing);
    }
    Ok(n)
}

impl LightDesc {
    pub(super) fn to_light(&self, dir: &Path) -> Result<Light, LightError> {
        Ok(match self {
            LightDesc::Point(p) => Light::Point(PointLight {
                position: p.position.into(),
                intensity: rgb(p.color, p.intensity)?,
            }),
            LightDesc::Spot(s) => Light::Spot(SpotLight {
                position: s.position.into(),
                direction: facing(s.position.into(), None, Some(s.look_at))?,
                intensity: rgb(s.color, s.intensity)?,
                cos_inner: s.inner_angle.to_radians().cos(),
                cos_outer: s.outer_angle.to_radians().cos(),
            }),
            LightDesc::Directional(d) => Light::Directional(DirectionalLight {
                direction: facing(Vec3::ZERO, Some(d.direction), None)?,
                irradiance: rgb(d.color, d.irradiance)?,
            }),
            LightDesc::Sphere(s) => Light::Sphere(SphereLight {
                center: s.center.into(),
                radius: positive("radius", s.radius)?,
                radiance: rgb(s.color, s.strength)?,
            }),
            LightDesc::Disk(d) => Light::Disk(DiskLight {
                center: d.center.into(),
                normal: facing(d.center.into(), d.normal, d.look_at)?,
                radius: positive("radius", d.radius)?,
                radiance: rgb(d.color, d.strength)?,
            }),
            LightDesc::Rect(r) => Light::Rect(r.to_rect()?),
            LightDesc::Environment(e) => {
                let map = match &e.map {
                    Some(p) => Some(std::sync::Arc::new(
                        EnvMap::load(&dir.join(p))
                            .map_err(LightError::EnvMap)?
                            .rotated_y(e.rotate_y.to_radians()),
                    )),
                    None => None,
                };
                Light::Environment {
                    radiance: rgb(e.color, e.strength)?,
                    map,
                }
            }
        })
    }
}

impl RectDesc {
    /// The parallelogram from a centre, size and facing, or from a corner and two edges.
    fn to_rect(&self) -> Result<RectLight, LightError> {
        let (corner, edge_u, edge_v) = match (
            self.center,
            self.size,
            self.corner,
            self.edge_u,
            self.edge_v,
        ) {
            (Some(c), Some([w, h]), None, None, None) => {
                let c = Vec3::from(c);
                let n = facing(c, self.normal, self.look_at)?;
                positive("size", w.min(h))?;
                // Width along the horizontal most across the normal, height up.
                let frame = crate::geometry::Frame::from_normal(n);
                let across = if n.cross(Vec3::Y).length() > 1e-3 {
                    Vec3::Y.cross(n).normalize()
                } else {
                    frame.t
                };
                let up = n.cross(across);
                let (eu, ev) = (across * w, up * h);
                (c - 0.5 * (eu + ev), eu, ev)
            }
            (None, None, Some(c), Some(u), Some(v)) => {
                if self.normal.is_some() || self.look_at.is_some() {
                    return Err(LightError::CornerFacing);
                }
                (Vec3::from(c), Vec3::from(u), Vec3::from(v))
            }
            _ => return Err(LightError::RectShape),
        };
        if edge_u.cross(edge_v).length() <= 0.0 {
            return Err(LightError::NoArea);
        }
        Ok(RectLight {
            corner,
            edge_u,
            edge_v,
            radiance: rgb(self.color, self.strength)?,
        })
    }
}
