//! What a scene uses (motion, lens, transmission, textures, area lights, environment, CSG, ...),
//! derived once before rendering so the renderer builds only the paths it needs.

use super::{Camera, Light, Scene};

/// The rendering features one scene and camera need. Each `false` is a path glint skips: a static
/// scene builds flat accelerators and never samples time, a pinhole never samples a lens, an opaque
/// scene's shadow rays stop at the first hit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Features {
    /// Instances or the camera move during the shutter: two-level traversal, ray times sampled.
    pub motion: bool,
    /// A thin lens: lens positions sampled.
    pub lens: bool,
    /// Materials that refract (solid) or pass light (thin walls).
    pub transmission: bool,
    /// Thin transmissive walls: shadow rays walk through surfaces (the integrator's thin path).
    pub thin_walls: bool,
    pub textures: bool,
    /// Alpha cutouts or blending: hits are filtered during traversal.
    pub alpha: bool,
    /// Emissive triangles, sampled as area lights.
    pub emissive_triangles: bool,
    /// Analytic sphere, disk and rectangle lights.
    pub area_lights: bool,
    pub punctual_lights: bool,
    pub environment: bool,
    /// An environment map, importance-sampled.
    pub environment_map: bool,
    pub csg: bool,
}

impl Features {
    pub fn of(scene: &Scene, camera: &Camera) -> Self {
        let mats = &scene.materials;
        let lights = &scene.lights;
        Self {
            motion: scene.has_motion() || camera.motion.is_some(),
            lens: camera.lens.is_some_and(|l| l.radius > 0.0),
            transmission: mats.iter().any(|m| m.is_transmissive()),
            thin_walls: mats
                .iter()
                .any(|m| m.is_transmissive() && m.is_thin_walled()),
            textures: !scene.textures.is_empty(),
            alpha: mats.iter().any(|m| m.needs_alpha_test()),
            emissive_triangles: scene
                .instances
                .iter()
                .any(|i| scene.material_of_mesh(i.mesh).is_emissive()),
            area_lights: lights.iter().any(|l| {
                matches!(
                    l,
                    Light::Sphere { .. } | Light::Disk { .. } | Light::Rect { .. }
                )
            }),
            punctual_lights: lights.iter().any(|l| {
                matches!(
                    l,
                    Light::Point { .. } | Light::Spot { .. } | Light::Directional { .. }
                )
            }),
            environment: lights
                .iter()
                .any(|l| matches!(l, Light::Environment { .. })),
            environment_map: lights
                .iter()
                .any(|l| matches!(l, Light::Environment { map: Some(_), .. })),
            csg: !scene.csg.is_empty(),
        }
    }

    /// Every feature by name, with whether the scene uses it.
    pub fn list(&self) -> [(&'static str, bool); 12] {
        [
            ("motion", self.motion),
            ("lens", self.lens),
            ("transmission", self.transmission),
            ("thin walls", self.thin_walls),
            ("textures", self.textures),
            ("alpha", self.alpha),
            ("emissive triangles", self.emissive_triangles),
            ("area lights", self.area_lights),
            ("punctual lights", self.punctual_lights),
            ("environment", self.environment),
            ("environment map", self.environment_map),
            ("CSG", self.csg),
        ]
    }

    /// `uses: a, b; skips: c, d`, for `--verbose`.
    pub fn describe(&self) -> String {
        let pick = |used: bool| {
            let names: Vec<_> = self
                .list()
                .iter()
                .filter(|f| f.1 == used)
                .map(|f| f.0)
                .collect();
            if names.is_empty() {
                "nothing".to_string()
            } else {
                names.join(", ")
            }
        };
        format!("uses: {}; skips: {}", pick(true), pick(false))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Motion;
    use crate::scene::{generate, Lens, Material};

    #[test]
    fn a_static_pinhole_opaque_scene_skips_motion_lens_and_transmission() {
        let mut scene = generate::single_mesh_scene(generate::icosphere(2, 0.0));
        let mut camera = Camera::look_at(glam::Vec3::Z * 5.0, glam::Vec3::ZERO, glam::Vec3::Y, 0.7);
        let f = Features::of(&scene, &camera);
        assert!(!f.motion && !f.lens && !f.transmission && !f.thin_walls && !f.csg);
        assert!(f.describe().contains("skips: motion, lens, transmission"));

        camera.lens = Some(Lens {
            radius: 0.1,
            focus_distance: 5.0,
        });
        let m = scene.instances[0].to_world;
        scene.instances[0].motion = Some(Motion {
            steps: vec![m, glam::Mat4::from_translation(glam::Vec3::X) * m],
        });
        scene.materials.push(Material {
            transmission: 1.0,
            metallic: 0.0,
            ..Material::default()
        });
        let f = Features::of(&scene, &camera);
        assert!(f.motion && f.lens && f.transmission && f.thin_walls);
    }
}
