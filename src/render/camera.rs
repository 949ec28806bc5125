//! Turning film positions into primary rays: a pinhole (perspective) or orthographic projection.
//! The camera looks down its local -Z with +Y up, as glTF defines.

use glam::{Mat4, Vec2, Vec3};

use crate::geometry::Ray;
use crate::scene::{Camera, Projection};

/// A camera fixed to an image size, ready to generate rays.
#[derive(Clone, Debug)]
pub struct RayCamera {
    to_world: Mat4,
    kind: Kind,
    width: f32,
    height: f32,
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    /// Half extents of the image plane at distance 1.
    Pinhole {
        half: Vec2,
    },
    Orthographic {
        half: Vec2,
    },
}

impl RayCamera {
    pub fn new(camera: &Camera, width: usize, height: usize) -> Self {
        let image_aspect = width as f32 / height as f32;
        let kind = match camera.projection {
            Projection::Perspective { yfov, .. } => {
                // The image's own aspect wins: the file's aspect only says how the author framed it.
                let hy = (yfov * 0.5).tan();
                Kind::Pinhole {
                    half: Vec2::new(hy * image_aspect, hy),
                }
            }
            // As for perspective, the image's aspect decides the width; `xmag` only records the author's.
            Projection::Orthographic { ymag, .. } => Kind::Orthographic {
                half: Vec2::new(ymag.abs() * image_aspect, ymag.abs()).max(Vec2::splat(1e-6)),
            },
        };
        Self {
            to_world: camera.to_world,
            kind,
            width: width as f32,
            height: height as f32,
        }
    }

    /// The ray through film position `film` (pixels, origin top left, y down).
    pub fn ray(&self, film: Vec2) -> Ray {
        // Normalised device coordinates in [-1, 1], y up.
        let ndc = Vec2::new(
            2.0 * film.x / self.width - 1.0,
            1.0 - 2.0 * film.y / self.height,
        );
        let (o, d) = match self.kind {
            Kind::Pinhole { half } => (Vec3::ZERO, Vec3::new(ndc.x * half.x, ndc.y * half.y, -1.0)),
            Kind::Orthographic { half } => {
                (Vec3::new(ndc.x * half.x, ndc.y * half.y, 0.0), -Vec3::Z)
            }
        };
        Ray::new(
            self.to_world.transform_point3(o),
            self.to_world.transform_vector3(d).normalize(),
        )
    }

    /// Where a world point lands on the film (pixels), if in front of a pinhole camera.
    pub fn project(&self, p: Vec3) -> Option<Vec2> {
        let local = self.to_world.inverse().transform_point3(p);
        let ndc = match self.kind {
            Kind::Pinhole { half } => {
                if local.z >= 0.0 {
                    return None;
                }
                Vec2::new(local.x / -local.z / half.x, local.y / -local.z / half.y)
            }
            Kind::Orthographic { half } => Vec2::new(local.x / half.x, local.y / half.y),
        };
        Some(Vec2::new(
            (ndc.x + 1.0) * 0.5 * self.width,
            (1.0 - ndc.y) * 0.5 * self.height,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_ray_looks_at_target_and_projection_inverts() {
        let cam = Camera::look_at(Vec3::new(1.0, 2.0, 5.0), Vec3::ZERO, Vec3::Y, 0.8);
        let rc = RayCamera::new(&cam, 64, 32);
        let r = rc.ray(Vec2::new(32.0, 16.0));
        assert!((r.d - (-Vec3::new(1.0, 2.0, 5.0)).normalize()).length() < 1e-5);
        let film = Vec2::new(10.5, 27.25);
        let p = rc.ray(film).at(3.0);
        assert!((rc.project(p).unwrap() - film).length() < 1e-3);
    }
}
