//! KHR_materials_dispersion's tests: the per-channel IORs against the extension's definition of
//! the Abbe number, and refraction through a dispersive surface channel by channel.

use glam::{Vec2, Vec3};

use super::hash;
use crate::geometry::Frame;
use crate::render::bsdf::dispersion::ior_at;
use crate::render::bsdf::{channel_iors, Bsdf};

/// The Abbe number comes back from the channel IORs: V_d = (n_d - 1) / (n_F - n_C), with blue at
/// F, green at d and red at C; dispersion 0 leaves every channel at the material's IOR.
#[test]
fn channel_iors_give_back_the_abbe_number() {
    for ior in [1.33f32, 1.5, 2.4] {
        assert_eq!(channel_iors(ior, 0.0), Vec3::splat(ior));
        for dispersion in [0.33f32, 1.0, 2.0] {
            let n = channel_iors(ior, dispersion);
            let abbe = 20.0 / dispersion;
            assert!(n.x < n.y && n.y < n.z, "{n}");
            assert!((n.y - ior).abs() < 1e-4, "green {} vs {ior}", n.y);
            let back = (n.y - 1.0) / (n.z - n.x);
            assert!((back - abbe).abs() < 1e-3 * abbe, "V_d {back} vs {abbe}");
        }
    }
    // The clamp at 1 of a made-up extreme.
    assert_eq!(ior_at(1.01, 200.0, 700.0), 1.0);
}

/// A smooth dispersive glass refracts each channel by Snell's law with that channel's IOR: red
/// bends least, blue most; thin walls and dispersion 0 have no per-channel IOR.
#[test]
fn dispersive_glass_refracts_each_channel_by_its_ior() {
    let frame = Frame::from_normal(Vec3::Z);
    let glass = Bsdf::new(frame, Vec3::ONE, 0.0, 0.0, 1.0).with_dielectric(1.0, 1.5, false, true);
    assert!(glass.with_dispersion(0.0).dispersion.is_none());
    let thin = Bsdf::new(frame, Vec3::ONE, 0.0, 0.0, 1.0).with_dielectric(1.0, 1.5, true, true);
    assert!(thin.with_dispersion(1.0).dispersion.is_none());
    let glass = glass.with_dispersion(2.0);
    let iors = glass.dispersion.expect("per-channel IORs");
    let wo = Vec3::new(0.8, 0.0, 0.6);
    let mut sin_t = [0.0f32; 3];
    for (c, s) in sin_t.iter_mut().enumerate() {
        let b = glass.for_channel(c);
        let t = (0..64)
            .filter_map(|k| b.sample(wo, hash(k), Vec2::new(hash(k + 1), hash(k + 2))))
            .find(|s| s.wi.z < 0.0)
            .expect("a refracted sample");
        assert!(t.delta);
        *s = (t.wi.x * t.wi.x + t.wi.y * t.wi.y).sqrt();
        assert!((*s * iors[c] - 0.8).abs() < 1e-5, "Snell, channel {c}");
    }
    assert!(sin_t[0] > sin_t[1] && sin_t[1] > sin_t[2], "{sin_t:?}");
    // Leaving the glass, the same channel sees 1 / its IOR.
    let inside = Bsdf::new(frame, Vec3::ONE, 0.0, 0.0, 1.0)
        .with_dielectric(1.0, 1.5, false, false)
        .with_dispersion(2.0);
    for c in 0..3 {
        assert!((inside.for_channel(c).eta * iors[c] - 1.0).abs() < 1e-6);
    }
}
