//! What a render sees through and by: the camera (the file's, a framing one, or one given, with
//! position and field-of-view overrides), an environment map, and a thin lens focused on the scene.

use std::path::PathBuf;
use std::str::FromStr;
use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::JobError;
use crate::accel::Accel;
use crate::render::RayCamera;
use crate::scene::{defaults, Camera, EnvMap, Lens, Light, Projection, Scene};

/// A camera of the file: by index, or by name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CameraRef {
    Index(usize),
    Name(String),
}

impl FromStr for CameraRef {
    type Err = std::convert::Infallible;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Ok(match s.parse::<usize>() {
            Ok(i) => CameraRef::Index(i),
            Err(_) => CameraRef::Name(s.to_string()),
        })
    }
}

impl std::fmt::Display for CameraRef {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CameraRef::Index(i) => write!(f, "{i}"),
            CameraRef::Name(n) => f.write_str(n),
        }
    }
}

/// Which camera the render starts from, before the overrides of `View`.
#[derive(Clone, Debug, Default)]
pub enum CameraChoice {
    /// The file's first camera, or one framing the model when it has none.
    #[default]
    First,
    /// A camera of the file (an error when it has no such camera).
    File(CameraRef),
    /// This camera (a turntable's frame-0 camera, a test's).
    Given(Camera),
}

/// The camera and what overrides it. With `eye` or `look_at`, the camera is placed anew: at `eye`
/// looking at `look_at` (default: the model's centre), or at the framing position moved so that it
/// looks at `look_at`.
#[derive(Clone, Debug, Default)]
pub struct View {
    pub camera: CameraChoice,
    pub eye: Option<Vec3>,
    pub look_at: Option<Vec3>,
    /// Up direction for `eye`/`look_at` (default +Y).
    pub up: Option<Vec3>,
    /// Vertical field of view in degrees.
    pub fov: Option<f32>,
}

impl View {
    /// The camera to render through, for an image of `aspect` (width over height).
    pub fn camera(&self, scene: &Scene, aspect: f32) -> Result<Camera, JobError> {
        let fov = self.fov.map(|f| f.to_radians());
        if let Some(f) = fov {
            if !(f > 0.0 && f < std::f32::consts::PI) {
                return Err(JobError::Fov);
            }
        }
        let start = match &self.camera {
            CameraChoice::First => scene.cameras.first().cloned(),
            CameraChoice::File(sel) => Some(file_camera(scene, sel)?),
            CameraChoice::Given(c) => Some(c.clone()),
        };
        let yfov = fov.unwrap_or(defaults::DEFAULT_FOV_DEG.to_radians());
        let mut camera = match start {
            Some(c) if self.eye.is_none() && self.look_at.is_none() => c,
            _ => self.placed(scene, yfov, aspect)?,
        };
        if let (Some(f), Projection::Perspective { yfov, .. }) = (fov, &mut camera.projection) {
            *yfov = f;
        }
        Ok(camera)
    }

    /// A camera at `eye` (or the framing position) looking at `look_at` (or the model's centre).
    fn placed(&self, scene: &Scene, yfov: f32, aspect: f32) -> Result<Camera, JobError> {
        let bounds = scene.bounds();
        let (center, _) = defaults::bounding_sphere(&bounds);
        let target = self.look_at.unwrap_or(center);
        let Some(eye) = self.eye else {
            let c =
                defaults::frame_bounds(&bounds, defaults::default_view_direction(), yfov, aspect);
            if self.look_at.is_none() {
                return Ok(c);
            }
            let eye = c.position() - center + target;
            return Ok(Camera::look_at(
                eye,
                target,
                self.up.unwrap_or(Vec3::Y),
                yfov,
            ));
        };
        if (eye - target).length() == 0.0 {
            return Err(JobError::EyeIsTarget);
        }
        let mut up = self.up.unwrap_or(Vec3::Y);
        if (target - eye).normalize().cross(up.normalize()).length() < 1e-4 {
            up = Vec3::Z;
        }
        Ok(Camera::look_at(eye, target, up, yfov))
    }
}

fn file_camera(scene: &Scene, sel: &CameraRef) -> Result<Camera, JobError> {
    let found = match sel {
        CameraRef::Index(i) => scene.cameras.get(*i),
        CameraRef::Name(name) => scene.cameras.iter().find(|c| &c.name == name),
    };
    found.cloned().ok_or_else(|| JobError::NoCamera {
        path: scene.source.clone(),
        camera: sel.to_string(),
        names: scene.cameras.iter().map(|c| c.name.clone()).collect(),
    })
}

/// A lat-long environment map lighting the model (replacing the file's or the rig's environment).
#[derive(Clone, Debug, PartialEq)]
pub struct Environment {
    /// An equirectangular .exr or .hdr of linear radiance.
    pub path: PathBuf,
    /// Multiplier on the map's radiance.
    pub strength: f32,
    /// Degrees about +Y (counter-clockwise seen from above).
    pub rotation: f32,
}

impl Environment {
    pub fn light(&self) -> Result<Light, JobError> {
        if !(self.strength.is_finite() && self.strength >= 0.0) {
            return Err(JobError::EnvStrength(self.strength));
        }
        if !self.rotation.is_finite() {
            return Err(JobError::EnvRotation);
        }
        let map = EnvMap::load(&self.path)?.rotated_y(self.rotation.to_radians());
        Ok(Light::Environment {
            radiance: Vec3::splat(self.strength),
            map: Some(Arc::new(map)),
        })
    }
}

/// Depth of field: a thin lens, by aperture radius or f-number, focused at a distance or on a pixel.
/// Without `aperture` or `fstop` the camera keeps its own lens (a scene file's).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LensOptions {
    /// Aperture radius in scene units (0 = pinhole).
    pub aperture: Option<f32>,
    /// F-number on a 24 mm sensor (`Lens::from_fstop`).
    pub fstop: Option<f32>,
    /// Distance of the plane in focus along the view axis (default: the model's centre).
    pub focus_distance: Option<f32>,
    /// Focus on what pixel X,Y sees (a ray is traced through it).
    pub focus_on: Option<[u32; 2]>,
}

impl LensOptions {
    /// The lens these options ask for on `camera` (None for a pinhole), for a `size` image.
    pub fn lens(
        &self,
        scene: &Scene,
        accel: &dyn Accel,
        camera: &Camera,
        size: (usize, usize),
    ) -> Result<Option<Lens>, JobError> {
        let yfov = match camera.projection {
            Projection::Perspective { yfov, .. } => yfov,
            Projection::Orthographic { .. } => defaults::DEFAULT_FOV_DEG.to_radians(),
        };
        let radius = match (self.aperture, self.fstop) {
            (Some(a), _) if !(a >= 0.0 && a.is_finite()) => return Err(JobError::Aperture),
            (Some(a), _) => a,
            (None, Some(n)) if !(n > 0.0 && n.is_finite()) => return Err(JobError::Fstop),
            (None, Some(n)) => Lens::from_fstop(n, yfov, 1.0).radius,
            (None, None) if self.focus_distance.is_some() || self.focus_on.is_some() => {
                return Err(JobError::FocusWithoutLens)
            }
            (None, None) => return Ok(camera.lens),
        };
        if radius == 0.0 {
            return Ok(None);
        }
        Ok(Some(Lens {
            radius,
            focus_distance: self.focus_distance(scene, accel, camera, size)?,
        }))
    }

    fn focus_distance(
        &self,
        scene: &Scene,
        accel: &dyn Accel,
        camera: &Camera,
        (w, h): (usize, usize),
    ) -> Result<f32, JobError> {
        let axis = camera.to_world.transform_vector3(-Vec3::Z).normalize();
        match (self.focus_distance, self.focus_on) {
            (Some(d), _) if !(d > 0.0 && d.is_finite()) => Err(JobError::FocusDistance),
            (Some(d), _) => Ok(d),
            (None, Some([x, y])) => {
                if x as usize >= w || y as usize >= h {
                    return Err(JobError::FocusOutside { x, y, w, h });
                }
                let ray =
                    RayCamera::new(camera, w, h).ray(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
                let hit = accel
                    .intersect(&ray)
                    .ok_or(JobError::FocusOnNothing { x, y })?;
                Ok(hit.t * ray.d.dot(axis))
            }
            (None, None) => {
                let (center, _) = defaults::bounding_sphere(&scene.bounds());
                Ok((center - camera.position()).dot(axis).max(1e-3))
            }
        }
    }
}
