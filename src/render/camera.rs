//! Turning film positions into primary rays: a pinhole (perspective) or orthographic projection, with
//! an optional thin lens and shutter time. The camera looks down its local -Z with +Y up (glTF).

use glam::{Mat4, Vec2, Vec3};

use crate::geometry::Motion;
use crate::geometry::Ray;
use crate::sample::warp::concentric_disk;
use crate::sample::{Dim, Sampler};
use crate::scene::{Camera, Lens, Projection};

/// A camera fixed to an image size, ready to generate rays.
#[derive(Clone, Debug)]
pub struct RayCamera {
    to_world: Mat4,
    kind: Kind,
    width: f32,
    height: f32,
    lens: Option<Lens>,
    motion: Option<Motion>,
    /// Whether camera rays carry a time drawn from `Dim::Time` (only when something moves).
    timed: bool,
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
            lens: camera.lens.filter(|l| l.radius > 0.0),
            motion: camera.motion.clone(),
            timed: camera.motion.is_some(),
        }
    }

    /// Also draws ray times when `timed` (the scene has moving instances), not only for a moving camera.
    pub fn with_time(mut self, timed: bool) -> Self {
        self.timed |= timed;
        self
    }

    /// The ray through film position `film` (pixels, origin top left, y down) of a pinhole at time 0.
    pub fn ray(&self, film: Vec2) -> Ray {
        self.ray_at(film, Vec2::splat(0.5), 0.0)
    }

    /// The camera ray through `film`, drawing a lens position (`Dim::Lens`) only for a thin lens and
    /// a time (`Dim::Time`) only when something moves.
    #[inline(always)]
    pub fn generate(&self, film: Vec2, sampler: &mut impl Sampler) -> Ray {
        let u_lens = match self.lens {
            Some(_) => sampler.get_2d(Dim::Lens, 0),
            None => Vec2::splat(0.5),
        };
        let time = if self.timed {
            sampler.get_1d(Dim::Time, 0)
        } else {
            0.0
        };
        self.ray_at(film, u_lens, time)
    }

    /// The ray through `film` from lens sample `u_lens` (the disk's centre at (0.5, 0.5)) at shutter
    /// time `time`.
    #[inline(always)]
    pub fn ray_at(&self, film: Vec2, u_lens: Vec2, time: f32) -> Ray {
        // Normalised device coordinates in [-1, 1], y up.
        let ndc = Vec2::new(
            2.0 * film.x / self.width - 1.0,
            1.0 - 2.0 * film.y / self.height,
        );
        let (mut o, mut d) = match self.kind {
            Kind::Pinhole { half } => (Vec3::ZERO, Vec3::new(ndc.x * half.x, ndc.y * half.y, -1.0)),
            Kind::Orthographic { half } => {
                (Vec3::new(ndc.x * half.x, ndc.y * half.y, 0.0), -Vec3::Z)
            }
        };
        if let Some(lens) = self.lens {
            // Every ray through this film point meets the pinhole ray on the plane of focus.
            let focus = o + d * (lens.focus_distance / -d.z);
            let l = concentric_disk(u_lens) * lens.radius;
            o += Vec3::new(l.x, l.y, 0.0);
            d = focus - o;
        }
        let to_world = match &self.motion {
            Some(m) => m.at(time),
            None => self.to_world,
        };
        Ray::new(
            to_world.transform_point3(o),
            to_world.transform_vector3(d).normalize(),
        )
        .with_time(time)
    }

    /// Pixels per unit of `tan(angle)` off the axis (vertical), for a perspective camera: converts
    /// angular blur into image blur.
    pub fn pixels_per_tan(&self) -> Option<f32> {
        match self.kind {
            Kind::Pinhole { half } => Some(0.5 * self.height / half.y),
            Kind::Orthographic { .. } => None,
        }
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
    fn thin_lens_rays_meet_on_the_focus_plane() {
        let mut cam = Camera::look_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, Vec3::Y, 0.7);
        cam.lens = Some(Lens {
            radius: 0.3,
            focus_distance: 4.0,
        });
        let rc = RayCamera::new(&cam, 64, 48);
        let film = Vec2::new(20.5, 11.25);
        let pin = rc.ray(film);
        let target = pin.o + pin.d * (4.0 / -pin.d.z);
        let mut spread = 0.0f32;
        for (i, u) in [(0.0, 0.0), (1.0, 0.3), (0.2, 0.9), (0.99, 0.99)]
            .iter()
            .enumerate()
        {
            let r = rc.ray_at(film, Vec2::new(u.0, u.1), 0.0);
            let at = r.o + r.d * ((r.o.z - target.z) / -r.d.z);
            assert!(
                (at - target).length() < 1e-4,
                "sample {i}: {at} vs {target}"
            );
            assert!((r.o.z - 4.0).abs() < 1e-6);
            spread = spread.max(r.o.truncate().length());
        }
        assert!(spread > 0.2 && spread <= 0.3 + 1e-6, "{spread}");
    }

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
