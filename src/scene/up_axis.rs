//! The axis a model file treats as up, and the turn of a loaded scene that makes it glint's +Y
//! (Z-up scans and CAD exports): instances, their motion, lights and the file's cameras.

use glam::Mat4;

use super::Scene;
use crate::geometry::Motion;

/// Which axis of the file points up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum UpAxis {
    X,
    /// glTF's convention, and glint's.
    #[default]
    Y,
    Z,
}

impl UpAxis {
    /// The rotation taking this axis to +Y. Z-up maps (x, y, z) to (x, z, -y), as Blender's glTF
    /// exporter converts; X-up maps (x, y, z) to (-y, x, z). Both keep handedness.
    pub fn to_y_up(self) -> Mat4 {
        match self {
            UpAxis::X => Mat4::from_rotation_z(std::f32::consts::FRAC_PI_2),
            UpAxis::Y => Mat4::IDENTITY,
            UpAxis::Z => Mat4::from_rotation_x(-std::f32::consts::FRAC_PI_2),
        }
    }
}

impl Scene {
    /// Turns everything placed in the scene so that the file's `up` becomes +Y. CSG objects are not
    /// turned: the caller refuses a scene with them (a scene file places its parts itself).
    pub fn turn_up(&mut self, up: UpAxis) {
        if up == UpAxis::Y {
            return;
        }
        let r = up.to_y_up();
        let turn = |m: &mut Option<Motion>| {
            if let Some(m) = m {
                m.steps.iter_mut().for_each(|s| *s = r * *s);
            }
        };
        for inst in &mut self.instances {
            let mut motion = inst.motion.take();
            turn(&mut motion);
            *inst = super::Instance::new(inst.mesh, r * inst.to_world);
            inst.motion = motion;
        }
        for l in &mut self.lights {
            *l = l.transformed(&r);
        }
        for c in &mut self.cameras {
            c.to_world = r * c.to_world;
            turn(&mut c.motion);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Instance, Light, PointLight};
    use glam::Vec3;

    #[test]
    fn each_axis_turns_to_y_keeping_handedness() {
        for (up, axis) in [
            (UpAxis::X, Vec3::X),
            (UpAxis::Y, Vec3::Y),
            (UpAxis::Z, Vec3::Z),
        ] {
            let r = up.to_y_up();
            let y = r.transform_vector3(axis);
            assert!((y - Vec3::Y).length() < 1e-6, "{up:?}: {y}");
            assert!((r.determinant() - 1.0).abs() < 1e-6);
        }
        let r = UpAxis::Z.to_y_up();
        let p = r.transform_point3(Vec3::new(1.0, 2.0, 3.0));
        assert!((p - Vec3::new(1.0, 3.0, -2.0)).length() < 1e-6, "{p}");
    }

    #[test]
    fn turning_moves_instances_motion_lights_and_cameras() {
        let mut s = Scene::default();
        let mut inst = Instance::new(0, Mat4::from_translation(Vec3::new(0.0, 0.0, 2.0)));
        inst.motion = Some(Motion {
            steps: vec![
                inst.to_world,
                Mat4::from_translation(Vec3::new(0.0, 0.0, 4.0)),
            ],
        });
        s.instances.push(inst);
        s.lights.push(Light::Point(PointLight {
            position: Vec3::new(0.0, 0.0, 5.0),
            intensity: Vec3::ONE,
        }));
        s.cameras.push(crate::scene::Camera::look_at(
            Vec3::new(0.0, -5.0, 0.0),
            Vec3::ZERO,
            Vec3::Z,
            0.8,
        ));
        let untouched = s.clone();
        s.turn_up(UpAxis::Y);
        assert_eq!(s.instances[0].to_world, untouched.instances[0].to_world);
        s.turn_up(UpAxis::Z);
        let at = |m: Mat4| m.transform_point3(Vec3::ZERO);
        assert!((at(s.instances[0].to_world) - Vec3::new(0.0, 2.0, 0.0)).length() < 1e-6);
        let steps = &s.instances[0].motion.as_ref().unwrap().steps;
        assert!((at(steps[1]) - Vec3::new(0.0, 4.0, 0.0)).length() < 1e-6);
        match s.lights[0] {
            Light::Point(PointLight { position, .. }) => {
                assert!((position - Vec3::new(0.0, 5.0, 0.0)).length() < 1e-6)
            }
            ref l => panic!("{l:?}"),
        }
        // The camera looked along +Y with +Z up; now along -Z with +Y up.
        let c = &s.cameras[0];
        let forward = c.to_world.transform_vector3(Vec3::NEG_Z);
        let up = c.to_world.transform_vector3(Vec3::Y);
        assert!((forward - Vec3::NEG_Z).length() < 1e-5, "{forward}");
        assert!((up - Vec3::Y).length() < 1e-5, "{up}");
        assert!((c.position() - Vec3::new(0.0, 0.0, 5.0)).length() < 1e-5);
    }
}
