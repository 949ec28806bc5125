//! What each KHR material layer costs a render: one sphere under the default light rig, rendered in a
//! plain metallic-roughness dielectric and with each layer added, alternating in every round, with
//! seconds per sample relative to the plain material (best of the rounds). Not a test: run by hand:
//!
//!     cargo run --release --example layer_cost -- [SPP] [SIZE] [ROUNDS]

use glam::{Vec3, Vec4};
use glint::accel::Backend;
use glint::render::job::{DefaultLights, JobOptions, Overrides, Setup};
use glint::scene::layers::{
    Anisotropy, Clearcoat, DiffuseTransmission, Iridescence, MaterialLayers, Sheen,
};
use glint::scene::{generate, Material};

/// The plain material with `edit` applied to its layers (and the rest of it).
fn with(name: &'static str, edit: impl Fn(&mut Material)) -> (&'static str, Material) {
    let mut m = Material {
        name: name.into(),
        base_color: Vec4::new(0.8, 0.5, 0.3, 1.0),
        metallic: 0.0,
        roughness: 0.4,
        layers: MaterialLayers::default(),
        ..Default::default()
    };
    edit(&mut m);
    (name, m)
}

fn variants() -> Vec<(&'static str, Material)> {
    let glass = |m: &mut Material| {
        m.base_color = Vec4::ONE;
        m.roughness = 0.0;
        m.transmission = 1.0;
        m.thickness = 1.0;
    };
    vec![
        with("plain", |_| {}),
        with("clearcoat", |m| {
            m.layers.clearcoat = Some(Clearcoat {
                factor: 1.0,
                factor_tex: None,
                roughness: 0.2,
                roughness_tex: None,
                normal_tex: None,
                normal_scale: 1.0,
            })
        }),
        with("sheen", |m| {
            m.layers.sheen = Some(Sheen {
                color: Vec3::new(0.9, 0.8, 0.9),
                color_tex: None,
                roughness: 0.5,
                roughness_tex: None,
            })
        }),
        with("specular colour", |m| {
            m.layers.specular_color = Vec3::new(1.2, 0.8, 0.5)
        }),
        with("iridescence", |m| {
            m.layers.iridescence = Some(Iridescence {
                factor: 1.0,
                factor_tex: None,
                ior: 1.3,
                thickness_min: 100.0,
                thickness_max: 400.0,
                thickness_tex: None,
            })
        }),
        with("anisotropy", |m| {
            m.layers.anisotropy = Some(Anisotropy {
                strength: 0.8,
                rotation: 0.5,
                texture: None,
            })
        }),
        with("diffuse transmission", |m| {
            m.layers.diffuse_transmission = Some(DiffuseTransmission {
                factor: 0.5,
                factor_tex: None,
                color: Vec3::new(0.9, 0.6, 0.5),
                color_tex: None,
            })
        }),
        with("glass", glass),
        with("glass + dispersion", |m| {
            glass(m);
            m.layers.dispersion = 1.0;
        }),
    ]
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let num = |i: usize, d: usize| args.get(i).and_then(|a| a.parse().ok()).unwrap_or(d);
    let (spp, size, rounds) = (num(0, 16) as u32, num(1, 160), num(2, 3));
    let mut mesh = generate::icosphere(4, 0.0);
    // Tangents around the vertical axis, so that the anisotropic material has its frame.
    mesh.tangents = mesh
        .normals
        .iter()
        .map(|n| {
            Vec3::Y
                .cross(*n)
                .try_normalize()
                .unwrap_or(Vec3::X)
                .extend(1.0)
        })
        .collect();
    let flags = Overrides {
        width: Some(size),
        height: Some(size),
        spp: Some(spp),
        max_depth: Some(8),
        backend: Some(Backend::Bvh),
        ..Default::default()
    };
    let opts = JobOptions {
        flags,
        default_lights: DefaultLights::On,
        ..Default::default()
    };
    let setups = variants()
        .into_iter()
        .map(|(label, m)| {
            let mut scene = generate::single_mesh_scene(mesh.clone());
            scene.materials = vec![m];
            Ok((label, Setup::new(scene, &opts)?))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let mut best = vec![f64::INFINITY; setups.len()];
    for round in 0..rounds {
        for (k, (label, s)) in setups.iter().enumerate() {
            let stats = s
                .clone()
                .build()?
                .render(&indicatif::ProgressBar::hidden())
                .stats;
            println!(
                "round {round} {label:>20}: {:.3} s, {} rays",
                stats.seconds, stats.rays
            );
            best[k] = best[k].min(stats.seconds);
        }
    }
    println!("{size}x{size} at {spp} spp, best of {rounds} alternated rounds:");
    for ((label, _), t) in setups.iter().zip(&best) {
        println!("{label:>20}: {:.3} s, {:.2} x plain", t, t / best[0]);
    }
    Ok(())
}
