//! Distribution ray tracing against closed forms: the thin lens's circle of confusion, the streak of an
//! object moving during the shutter, glTF animation sampling, and backends agreeing on moving scenes.

mod common;

use std::sync::Arc;

use glam::{Mat4, Quat, Vec3, Vec4};
use glint::accel::Backend;
use glint::film::filter::FilterKind;
use glint::film::Image;
use glint::render::RenderSettings;
use glint::scene::animation::{self, Channel, Curve, Interpolation, Node, Property};
use glint::scene::{Animation, Camera, Instance, Lens, Material, Mesh, Scene};

const SIZE: usize = 96;
const YFOV: f32 = 0.5;

/// Pixels per unit of tan(angle) off the view axis for the test camera.
fn pixels_per_tan() -> f32 {
    0.5 * SIZE as f32 / (0.5 * YFOV).tan()
}

/// An emissive square of side `side` facing +Z, centred on the origin.
fn emissive_square(side: f32) -> (Mesh, Material) {
    let h = 0.5 * side;
    let mesh = Mesh {
        name: "square".into(),
        positions: vec![
            Vec3::new(-h, -h, 0.0),
            Vec3::new(h, -h, 0.0),
            Vec3::new(h, h, 0.0),
            Vec3::new(-h, h, 0.0),
        ],
        normals: vec![Vec3::Z; 4],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Default::default()
    };
    let material = Material {
        base_color: Vec4::new(0.0, 0.0, 0.0, 1.0),
        emissive: Vec3::ONE,
        ..Default::default()
    };
    (mesh, material)
}

/// Emission only, box filter: an image that is exactly the blurred square (plus pixel integration).
fn settings(spp: u32) -> RenderSettings {
    RenderSettings {
        width: SIZE,
        height: SIZE,
        spp,
        max_depth: 0,
        filter: FilterKind::Box,
        seed: 7,
        ..Default::default()
    }
}

fn camera() -> Camera {
    Camera::look_at(Vec3::ZERO, -Vec3::Z, Vec3::Y, YFOV)
}

#[test]
fn defocus_blur_matches_the_thin_lens_circle_of_confusion() {
    let (side, focus, radius) = (0.1f32, 2.0f32, 0.3f32);
    let (mesh, material) = emissive_square(side);
    // Behind the plane of focus, in front of it, and on it.
    for d in [4.0f32, 1.25, 2.0] {
        let scene = Arc::new(Scene {
            meshes: vec![mesh.clone()],
            instances: vec![Instance::new(0, Mat4::from_translation(-Vec3::Z * d))],
            materials: vec![material.clone()],
            ..Default::default()
        });
        let mut cam = camera();
        cam.lens = Some(Lens {
            radius,
            focus_distance: focus,
        });
        let img = common::render_with(&scene, &cam, Backend::Bvh, &settings(64));
        let (mx, my, vx, vy) = common::moments(&img);
        // A uniform disk of radius R has E[r^2] = R^2 / 2; the square and the pixel (box) add
        // side^2 / 12 and 1/12 per axis.
        let coc = radius * (1.0 / focus - 1.0 / d).abs() * pixels_per_tan();
        let square = side / d * pixels_per_tan();
        let extra = 2.0 * (square * square + 1.0) as f64 / 12.0;
        let measured = (2.0 * (vx + vy - extra)).max(0.0).sqrt();
        eprintln!("d {d}: circle of confusion radius {coc:.3} px, measured {measured:.3} px");
        assert!(
            (mx - 48.0).abs() < 0.2 && (my - 48.0).abs() < 0.2,
            "{mx} {my}"
        );
        // On the variance, which stays meaningful in focus (radius 0): within 2%.
        let want = (coc * coc) as f64 / 2.0 + extra;
        assert!(
            (vx + vy - want).abs() < 0.02 * want,
            "d {d}: expected radius {coc}, measured {measured} (E[r^2] {} vs {want})",
            vx + vy
        );
    }
}

/// A square at depth `depth` moving along +x at `speed` units per second, over a shutter of
/// `shutter` seconds, through the glTF animation path (channel, pose, motion steps).
fn moving_square(side: f32, depth: f32, speed: f32, shutter: f32) -> Scene {
    let (mesh, material) = emissive_square(side);
    let start = Vec3::new(-0.5 * speed - 0.05, 0.0, -depth);
    let mut scene = Scene {
        meshes: vec![mesh],
        instances: vec![Instance::new(0, Mat4::from_translation(start))],
        materials: vec![material],
        ..Default::default()
    };
    scene.animation = Some(Animation {
        name: "slide".into(),
        nodes: vec![Node {
            parent: None,
            translation: start,
            rotation: Quat::IDENTITY,
            scale: Vec3::ONE,
        }],
        channels: vec![Channel {
            node: 0,
            property: Property::Translation,
            curve: Curve {
                interpolation: Interpolation::Linear,
                times: vec![0.0, 10.0],
                values: vec![
                    start.extend(0.0),
                    (start + Vec3::X * speed * 10.0).extend(0.0),
                ],
            },
        }],
        instances: vec![(0, 0)],
        ..Default::default()
    });
    animation::pose(&mut scene, 0.5, [0.0, shutter]);
    scene
}

#[test]
fn motion_blur_streak_is_speed_times_shutter() {
    let (side, depth, speed, shutter) = (0.1f32, 3.0f32, 2.0f32, 0.1f32);
    let scene = Arc::new(moving_square(side, depth, speed, shutter));
    assert!(scene.has_motion());
    assert_eq!(scene.instances[0].motion.as_ref().unwrap().steps.len(), 2);
    let img = common::render_with(&scene, &camera(), Backend::Bvh, &settings(64));
    let (mx, my, vx, vy) = common::moments(&img);
    let ppt = pixels_per_tan();
    // The streak: a box of length L = v s (screen) convolved with the square and the pixel.
    let streak = speed * shutter / depth * ppt;
    let square = side / depth * ppt;
    let base = (square * square + 1.0) as f64 / 12.0;
    let measured = (12.0 * (vx - base)).sqrt();
    // Starts where the square is at frame time 0.5 (x = -0.05).
    let x0 = 48.0 + -0.05 / depth * ppt;
    eprintln!("streak {streak:.3} px, measured {measured:.3} px; y variance {vy:.4} vs {base:.4}");
    assert!(
        (measured - streak as f64).abs() < 0.02 * streak as f64,
        "expected {streak}, measured {measured}"
    );
    assert!((mx - (x0 + 0.5 * streak) as f64).abs() < 0.1, "{mx}");
    assert!((my - 48.0).abs() < 0.05);
    assert!((vy - base).abs() < 0.05, "{vy} vs {base}");
}

#[test]
fn a_moving_camera_streaks_a_still_object() {
    let (side, depth, shift) = (0.1f32, 3.0f32, 0.2f32);
    let (mesh, material) = emissive_square(side);
    let scene = Arc::new(Scene {
        meshes: vec![mesh],
        instances: vec![Instance::new(0, Mat4::from_translation(-Vec3::Z * depth))],
        materials: vec![material],
        ..Default::default()
    });
    assert!(!scene.has_motion());
    let mut cam = camera();
    cam.motion = Some(glint::geometry::Motion {
        steps: vec![
            cam.to_world,
            Mat4::from_translation(Vec3::X * shift) * cam.to_world,
        ],
    });
    let img = common::render_with(&scene, &cam, Backend::Bvh, &settings(64));
    let (mx, _, vx, _) = common::moments(&img);
    let ppt = pixels_per_tan();
    let streak = shift / depth * ppt;
    let square = side / depth * ppt;
    let measured = (12.0 * (vx - (square * square + 1.0) as f64 / 12.0)).sqrt();
    eprintln!("camera streak {streak:.3} px, measured {measured:.3} px");
    assert!((measured - streak as f64).abs() < 0.02 * streak as f64);
    // The camera moves right, so the square slides left from the centre.
    assert!((mx - (48.0 - 0.5 * streak) as f64).abs() < 0.1, "{mx}");
}

#[test]
fn backends_agree_on_a_moving_scene() {
    let scene = Arc::new(moving_square(0.3, 3.0, 2.0, 0.1));
    let reference = common::render_with(&scene, &camera(), Backend::Bvh, &settings(8));
    for backend in Backend::all_available() {
        let img = common::render_with(&scene, &camera(), backend, &settings(8));
        let diff: f64 = img
            .pixels
            .iter()
            .zip(&reference.pixels)
            .map(|(a, b)| (a.x - b.x).abs() as f64)
            .sum::<f64>()
            / img.pixels.len() as f64;
        eprintln!("{backend}: mean |difference| to bvh {diff:.2e}");
        assert!(diff < 1e-3, "{backend}: {diff}");
    }
    // BoxAnimated (rotation and translation, a hierarchy) through every backend, lit.
    let Some(assets) = common::shared_assets() else {
        return;
    };
    let path = assets.join("gltf/BoxAnimated/glTF-Binary/BoxAnimated.glb");
    if !path.exists() {
        eprintln!("{} absent: skipping", path.display());
        return;
    }
    let mut scene = Scene::load(&path).unwrap();
    animation::pose(&mut scene, 1.6, [0.0, 0.3]);
    assert!(scene.instances.iter().any(|i| i.motion.is_some()));
    let settings = RenderSettings {
        width: 48,
        height: 48,
        spp: 8,
        max_depth: 2,
        ..Default::default()
    };
    let cam = glint::scene::defaults::default_view(&mut scene, 1.0);
    let scene = Arc::new(scene);
    let reference = common::render_with(&scene, &cam, Backend::Bvh, &settings);
    for backend in Backend::all_available() {
        let img = common::render_with(&scene, &cam, backend, &settings);
        let diff: f64 = img
            .pixels
            .iter()
            .zip(&reference.pixels)
            .map(|(a, b)| (a - b).abs().truncate().max_element() as f64)
            .sum::<f64>()
            / img.pixels.len() as f64;
        eprintln!("BoxAnimated, {backend}: mean |difference| to bvh {diff:.2e}");
        assert!(diff < 2e-3, "{backend}: {diff}");
    }
}

/// glTF's animation samplers, read back through the `gltf` crate's own accessor reader and checked
/// against the spec's formulas at keys and halfway between them, for every animation of
/// InterpolationTest (step, linear, cubic spline on translation, rotation and scale).
#[test]
fn interpolation_test_animations_sample_as_the_spec_says() {
    let Some(assets) = common::shared_assets() else {
        return;
    };
    let path = assets.join("gltf/InterpolationTest/glTF-Binary/InterpolationTest.glb");
    if !path.exists() {
        eprintln!("{} absent: skipping", path.display());
        return;
    }
    let (doc, buffers, _) = gltf::import(&path).unwrap();
    let mut checked = 0;
    for anim in doc.animations() {
        let scene = Scene::load_with(
            &path,
            &glint::scene::LoadOptions {
                animation: anim.index(),
                ..Default::default()
            },
        )
        .unwrap();
        let a = scene.animation.as_ref().expect("animation kept");
        for ch in anim.channels() {
            let reader = ch.reader(|b| Some(&buffers[b.index()]));
            let times: Vec<f32> = reader.read_inputs().unwrap().collect();
            let values: Vec<Vec4> = match reader.read_outputs().unwrap() {
                gltf::animation::util::ReadOutputs::Translations(v)
                | gltf::animation::util::ReadOutputs::Scales(v) => {
                    v.map(|x| Vec3::from(x).extend(0.0)).collect()
                }
                gltf::animation::util::ReadOutputs::Rotations(r) => {
                    r.into_f32().map(Vec4::from).collect()
                }
                _ => continue,
            };
            let node = ch.target().node().index() as u32;
            let interp = ch.sampler().interpolation();
            let cubic = interp == gltf::animation::Interpolation::CubicSpline;
            let key = |k: usize| if cubic { values[3 * k + 1] } else { values[k] };
            let (inst, _) = *a.instances.iter().find(|(_, n)| *n == node).unwrap();
            let value_at = |t: f32| {
                let mut s = scene.clone();
                animation::pose(&mut s, t, [0.0, 0.0]);
                let (sc, rot, tr) = s.instances[inst as usize]
                    .to_world
                    .to_scale_rotation_translation();
                match ch.target().property() {
                    gltf::animation::Property::Translation => tr.extend(0.0),
                    gltf::animation::Property::Scale => sc.extend(0.0),
                    _ => Vec4::from(rot),
                }
            };
            let same = |a: Vec4, b: Vec4| {
                if ch.target().property() == gltf::animation::Property::Rotation {
                    Quat::from_vec4(a).angle_between(Quat::from_vec4(b).normalize()) < 1e-3
                } else {
                    (a - b).length() < 1e-4 * (1.0 + b.length())
                }
            };
            for k in 0..times.len() {
                assert!(
                    same(value_at(times[k]), key(k)),
                    "{:?} key {k}",
                    anim.name()
                );
                if k + 1 == times.len() {
                    continue;
                }
                let (t0, t1) = (times[k], times[k + 1]);
                let mid = 0.5 * (t0 + t1);
                let want = match interp {
                    gltf::animation::Interpolation::Step => key(k),
                    gltf::animation::Interpolation::Linear
                        if ch.target().property() == gltf::animation::Property::Rotation =>
                    {
                        Vec4::from(Quat::from_vec4(key(k)).slerp(Quat::from_vec4(key(k + 1)), 0.5))
                    }
                    gltf::animation::Interpolation::Linear => 0.5 * (key(k) + key(k + 1)),
                    // Hermite at s = 1/2: the mean of the keys plus dt / 8 (out_k - in_k+1).
                    gltf::animation::Interpolation::CubicSpline => {
                        let v = 0.5 * (key(k) + key(k + 1))
                            + (t1 - t0) / 8.0 * (values[3 * k + 2] - values[3 * (k + 1)]);
                        if ch.target().property() == gltf::animation::Property::Rotation {
                            v.normalize()
                        } else {
                            v
                        }
                    }
                };
                assert!(
                    same(value_at(mid), want),
                    "{:?} between keys {k} and {}: {} vs {want}",
                    anim.name(),
                    k + 1,
                    value_at(mid)
                );
                checked += 1;
            }
        }
    }
    eprintln!("{checked} key intervals checked");
    assert!(checked >= 9 * 3, "{checked}");
}

/// The project's scene files (lens, shutter, moving CSG, area lights, glass) load, use what they
/// say they use, and render finite and alike in every backend.
#[test]
fn scene_files_render_alike_in_every_backend() {
    use glint::scene::features::Features;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 3, "{files:?}");
    for path in files {
        let (scene, camera) = common::load_for_render(&path, 48, 32);
        let f = Features::of(&scene, &camera);
        if path.ends_with("effects.toml") {
            assert!(
                f.motion && f.lens && f.transmission && f.area_lights,
                "{f:?}"
            );
        }
        let s = RenderSettings {
            width: 48,
            height: 32,
            spp: 4,
            seed: 5,
            ..Default::default()
        };
        let images: Vec<Image> = common::render_backends()
            .into_iter()
            .map(|b| common::render_with(&scene, &camera, b, &s))
            .collect();
        let m0 = images[0].mean_rgb();
        assert!(m0 > 0.0, "{}: black", path.display());
        for img in &images {
            assert!(!img.has_non_finite(), "{}", path.display());
            let mad = img.mean_abs_diff(&images[0]);
            assert!(mad < 0.01 * m0, "{}: {mad} vs mean {m0}", path.display());
        }
    }
}
