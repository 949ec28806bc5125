//! What a scene uses (motion, lens, transmission, textures, area lights, environment, CSG, ...),
//! derived once before rendering so the renderer builds only the paths it needs.

use super::{Camera, Light, Scene};

/// Declares `Features` with one `bool` per feature and `Features::list`, which names them in the
/// same order (so a new feature cannot be left out of `--verbose`).
macro_rules! features {
    ($($(#[$doc:meta])* $field:ident: $name:literal,)*) => {
        /// The rendering features one scene and camera need. Each `false` is a path glint skips: a
        /// static scene builds flat accelerators and never samples time, a pinhole never samples a
        /// lens, an opaque scene's shadow rays stop at the first hit.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        pub struct Features {
            $($(#[$doc])* pub $field: bool,)*
        }

        impl Features {
            /// Every feature by name, with whether the scene uses it.
            pub fn list(&self) -> Vec<(&'static str, bool)> {
                vec![$(($name, self.$field)),*]
            }
        }
    };
}

features! {
    /// Instances or the camera move during the shutter: two-level traversal, ray times sampled.
    motion: "motion",
    /// A thin lens: lens positions sampled.
    lens: "lens",
    /// Materials that refract (solid) or pass light (thin walls).
    transmission: "transmission",
    /// Thin walls with specular transmission: shadow rays walk through surfaces (the integrator's
    /// thin path; diffusely transmitting walls scatter, so they do not need it).
    thin_walls: "thin walls",
    textures: "textures",
    /// Alpha cutouts or blending: hits are filtered during traversal.
    alpha: "alpha",
    /// Emissive triangles, sampled as area lights.
    emissive_triangles: "emissive triangles",
    /// Analytic sphere, disk and rectangle lights.
    area_lights: "area lights",
    /// Surfaces or area lights a camera may see: camera rays split where their edges lie.
    emitting_surfaces: "emitting surfaces",
    punctual_lights: "punctual lights",
    environment: "environment",
    /// An environment map, importance-sampled.
    environment_map: "environment map",
    csg: "CSG",
}

impl Features {
    pub fn of(scene: &Scene, camera: &Camera) -> Self {
        let mats = &scene.materials;
        let lights = &scene.lights;
        let area_lights = lights.iter().any(|l| {
            matches!(
                l,
                Light::Sphere { .. } | Light::Disk { .. } | Light::Rect { .. }
            )
        });
        Self {
            motion: scene.has_motion() || camera.motion.is_some(),
            lens: camera.lens.is_some_and(|l| l.radius > 0.0),
            transmission: mats.iter().any(|m| m.is_transmissive()),
            thin_walls: mats
                .iter()
                .any(|m| m.is_specular_transmissive() && m.is_thin_walled()),
            textures: !scene.textures.is_empty(),
            alpha: (0..scene.meshes.len() as u32).any(|m| scene.mesh_needs_alpha_test(m)),
            emissive_triangles: scene
                .instances
                .iter()
                .any(|i| scene.material_of_mesh(i.mesh).is_emissive()),
            area_lights,
            emitting_surfaces: area_lights || mats.iter().any(|m| m.unlit || m.is_emissive()),
            punctual_lights: lights
                .iter()
                .any(|l| matches!(l, Light::Point(_) | Light::Spot(_) | Light::Directional(_))),
            environment: lights
                .iter()
                .any(|l| matches!(l, Light::Environment { .. })),
            environment_map: lights
                .iter()
                .any(|l| matches!(l, Light::Environment { map: Some(_), .. })),
            csg: !scene.csg.is_empty(),
        }
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

    /// Diffuse transmission makes a scene transmissive (lights behind such surfaces are sampled
    /// through them), but it scatters, so shadow rays need not walk thin walls for it.
    #[test]
    fn diffuse_transmission_is_transmission_without_thin_wall_shadows() {
        let mut scene = generate::single_mesh_scene(generate::icosphere(1, 0.0));
        let camera = Camera::look_at(glam::Vec3::Z * 5.0, glam::Vec3::ZERO, glam::Vec3::Y, 0.7);
        scene.materials[0].metallic = 0.0;
        scene.materials[0].layers.diffuse_transmission =
            Some(crate::scene::layers::DiffuseTransmission {
                factor: 1.0,
                factor_tex: None,
                color: glam::Vec3::ONE,
                color_tex: None,
            });
        let f = Features::of(&scene, &camera);
        assert!(f.transmission && !f.thin_walls);
        // A metal cannot transmit, diffusely or not.
        scene.materials[0].metallic = 1.0;
        assert!(!Features::of(&scene, &camera).transmission);
    }
}
