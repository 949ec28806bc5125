//! Turntable sequences: sharded and resumed runs give the same frames, byte for byte, as one run;
//! off-centre models stay framed; the binary end to end (resume, previews, errors).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

use glam::{Mat4, Vec3};
use glint::accel::{self, Backend};
use glint::render::{RayCamera, RenderSettings};
use glint::scene::{defaults, generate, Instance, Scene};
use glint::turntable::{self, FrameNames, LightMode, Motion, Orbit, Shard, Turntable};
use indicatif::ProgressBar;

const W: usize = 32;
const H: usize = 24;
const FRAMES: u32 = 12;

fn demo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/demo/demo.glb")
}

fn duck() -> Option<PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/assets/gltf/Duck/glTF-Binary/Duck.glb");
    if p.is_file() {
        Some(p)
    } else {
        eprintln!("{} not found: skipping it", p.display());
        None
    }
}

/// A turntable as the CLI sets it up, with the scene (default rig from frame 0's camera) and its accel.
struct Setup {
    scene: Arc<Scene>,
    accel: Box<dyn accel::Accel>,
    base: Turntable,
}

fn setup(scene: Scene, motion: Motion, lights: LightMode, shutter: f32) -> Setup {
    let mut scene = scene;
    let yfov = defaults::DEFAULT_FOV_DEG.to_radians();
    let orbit = Orbit::framing(
        &scene.bounds(),
        yfov,
        W as f32 / H as f32,
        20f32.to_radians(),
    );
    let base = Turntable {
        frames: FRAMES,
        names: FrameNames::from_output(Path::new("unused/"), None, FRAMES).unwrap(),
        orbit,
        motion,
        lights,
        shutter_angle: shutter,
        settings: RenderSettings {
            width: W,
            height: H,
            spp: 2,
            max_depth: 3,
            seed: 7,
            ..Default::default()
        },
        exposure: 0.0,
        view: Default::default(),
        overwrite: false,
        denoise: None,
    };
    if !defaults::has_own_lights(&scene) {
        scene
            .lights
            .extend(defaults::light_rig(&base.first_camera().to_world));
    }
    let scene = Arc::new(scene);
    let accel = accel::build(scene.clone(), Backend::Bvh).unwrap();
    Setup { scene, accel, base }
}

impl Setup {
    fn run(
        &self,
        dir: &Path,
        shard: Option<Shard>,
        range: Option<std::ops::Range<u32>>,
    ) -> turntable::SequenceReport {
        let tt = Turntable {
            names: FrameNames::from_output(dir, None, FRAMES).unwrap(),
            ..self.base.clone()
        };
        let frames = turntable::select_frames(FRAMES, shard, range).unwrap();
        tt.render_sequence(
            &self.scene,
            self.accel.as_ref(),
            &frames,
            &ProgressBar::hidden(),
        )
        .unwrap()
    }
}

fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn assert_same_frames(a: &Path, b: &Path) {
    let (fa, fb) = (files(a), files(b));
    assert_eq!(fa.len(), FRAMES as usize, "{fa:?}");
    assert_eq!(fa, fb);
    for name in &fa {
        let (x, y) = (
            std::fs::read(a.join(name)).unwrap(),
            std::fs::read(b.join(name)).unwrap(),
        );
        assert!(
            x == y,
            "{name} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

/// One unsharded run, two shards, and a killed-then-resumed run all produce the same 12 files.
fn shards_and_resume_match(scene: Scene, motion: Motion, lights: LightMode, shutter: f32) {
    let s = setup(scene, motion, lights, shutter);
    let tmp = tempfile::tempdir().unwrap();
    let (whole, sharded, resumed) = (
        tmp.path().join("whole"),
        tmp.path().join("sharded"),
        tmp.path().join("resumed"),
    );

    let r = s.run(&whole, None, None);
    assert_eq!(r.rendered, (0..FRAMES).collect::<Vec<_>>());

    let r0 = s.run(&sharded, Some(Shard { index: 0, count: 2 }), None);
    let r1 = s.run(&sharded, Some(Shard { index: 1, count: 2 }), None);
    assert_eq!(r0.rendered, vec![0, 2, 4, 6, 8, 10]);
    assert_eq!(r1.rendered, vec![1, 3, 5, 7, 9, 11]);
    assert_same_frames(&whole, &sharded);

    // "Killed" after frames 0..5, plus a stray frame 9 from another machine: the rerun renders only
    // the rest, and each frame exactly once over both runs.
    let first = s.run(&resumed, None, Some(0..5));
    let stray = s.run(&resumed, None, Some(9..10));
    let mtime = |f: &str| {
        std::fs::metadata(resumed.join(f))
            .unwrap()
            .modified()
            .unwrap()
    };
    let before = mtime("frame_0002.png");
    let second = s.run(&resumed, None, None);
    assert_eq!(first.rendered, vec![0, 1, 2, 3, 4]);
    assert_eq!(stray.rendered, vec![9]);
    assert_eq!(second.rendered, vec![5, 6, 7, 8, 10, 11]);
    assert_eq!(second.skipped, vec![0, 1, 2, 3, 4, 9]);
    assert_eq!(
        mtime("frame_0002.png"),
        before,
        "a finished frame was rendered again"
    );
    assert_same_frames(&whole, &resumed);
    // And a third run has nothing left to do.
    assert!(s.run(&resumed, None, None).rendered.is_empty());
}

#[test]
fn demo_shards_and_resume_give_identical_frames() {
    let scene = Scene::load(&demo()).unwrap();
    shards_and_resume_match(scene, Motion::Orbit, LightMode::World, 0.0);
}

#[test]
fn spin_with_motion_blur_shards_and_resumes_identically() {
    // Moving lights (per-frame light copies) and sub-frames must stay deterministic too.
    let scene = Scene::load(&demo()).unwrap();
    shards_and_resume_match(scene, Motion::Spin, LightMode::World, 180.0);
}

#[test]
fn shared_duck_shards_and_resume_give_identical_frames() {
    let Some(duck) = duck() else { return };
    let scene = Scene::load(&duck).unwrap();
    shards_and_resume_match(scene, Motion::Orbit, LightMode::Camera, 0.0);
}

fn corners(b: &glint::Aabb) -> impl Iterator<Item = Vec3> + '_ {
    (0..8).map(move |i| {
        Vec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        )
    })
}

#[test]
fn off_centre_model_stays_framed_in_every_frame() {
    let mut scene = generate::single_mesh_scene(generate::icosphere(2, 0.0));
    // Far from the origin and stretched, so a camera aimed at the origin, or framing by one box
    // face, would lose it.
    let m = Mat4::from_translation(Vec3::new(100.0, 50.0, -30.0))
        * Mat4::from_scale(Vec3::new(3.0, 1.0, 0.5));
    scene.instances = vec![Instance::new(0, m)];
    let bounds = scene.bounds();
    for motion in [Motion::Orbit, Motion::Spin] {
        for elevation in [-60f32, 0.0, 20.0, 75.0] {
            for (w, h) in [(W, H), (24, 32)] {
                let yfov = defaults::DEFAULT_FOV_DEG.to_radians();
                let mut s = setup(scene.clone(), motion, LightMode::World, 0.0);
                s.base.orbit =
                    Orbit::framing(&bounds, yfov, w as f32 / h as f32, elevation.to_radians());
                for f in 0..FRAMES {
                    for dt in [0.0, 0.4] {
                        let (cam, _) = s.base.view_at(&s.scene.lights, f as f32 + dt);
                        let rc = RayCamera::new(&cam, w, h);
                        for c in corners(&bounds) {
                            let p = rc.project(c).expect("corner behind the camera");
                            assert!(
                                p.x > 0.0 && p.x < w as f32 && p.y > 0.0 && p.y < h as f32,
                                "frame {f}, elevation {elevation}: corner {c:?} at {p:?}"
                            );
                        }
                        let centre = rc.project(bounds.center()).unwrap();
                        assert!(
                            (centre - glam::Vec2::new(w as f32, h as f32) * 0.5).length() < 0.5
                        );
                    }
                }
            }
        }
    }
}

fn glint() -> Command {
    Command::new(env!("CARGO_BIN_EXE_glint"))
}

#[test]
fn binary_renders_resumes_and_previews() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("frames");
    let pattern = dir.join("demo_##.png");
    let gif = tmp.path().join("demo.gif");
    let sheet = tmp.path().join("sheet.png");
    let common = |extra: &[&str]| {
        let mut c = glint();
        c.arg("turntable")
            .arg(demo())
            .args([
                "--frames", "12", "--width", "32", "--height", "24", "--spp", "2", "--seed", "7",
            ])
            .arg("-o")
            .arg(&pattern)
            .args(["--preview"])
            .arg(&gif)
            .arg("--contact-sheet")
            .arg(&sheet)
            .args(["--backend", "bvh", "--threads", "2"])
            .args(extra);
        c
    };
    // One shard only: frames missing, so previews are skipped with a warning.
    let out = common(&["--shard", "1/3"]).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("previews skipped"), "{err}");
    assert!(
        err.contains("load") && err.contains("build") && err.contains("per frame"),
        "{err}"
    );
    assert_eq!(
        files(&dir),
        ["demo_01.png", "demo_04.png", "demo_07.png", "demo_10.png"]
    );
    assert!(!gif.exists());

    // The rest: the four frames on disk are skipped, then the previews are built.
    let out = common(&[]).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("8 frames rendered, 4 skipped"), "{err}");
    assert_eq!(files(&dir).len(), 12);
    let f0 = image::open(dir.join("demo_00.png")).unwrap();
    assert_eq!((f0.width(), f0.height()), (32, 24));
    let sheet_img = image::open(&sheet).unwrap();
    assert_eq!((sheet_img.width(), sheet_img.height()), (4 * 32, 3 * 24));
    let gif_frames = {
        use image::AnimationDecoder;
        let dec = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(
            std::fs::File::open(&gif).unwrap(),
        ))
        .unwrap();
        dec.into_frames().collect_frames().unwrap()
    };
    assert_eq!(gif_frames.len(), 12);
    // No temporary file is left beside the frames or previews.
    assert!(files(&dir).iter().all(|f| !f.ends_with(".tmp")));
    assert!(files(tmp.path()).iter().all(|f| !f.ends_with(".tmp")));

    // Finished: nothing to load, build or render.
    let out = common(&[]).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success() && err.contains("nothing to render"),
        "{err}"
    );
}

#[test]
fn binary_rejects_bad_sequences_clearly() {
    let tmp = tempfile::tempdir().unwrap();
    let out_dir = tmp.path().join("f");
    let cases: [(&[&str], &str); 6] = [
        (&["--shard", "2/2"], "below the count"),
        (&["--shard", "0/0"], "at least 1"),
        (&["--frames", "0"], "--frames 0"),
        (&["--frame-range", "5..3"], "empty"),
        (&["--frame-range", "200..300"], "past the last frame"),
        (&["--preview", "x.mp4"], ".gif"),
    ];
    for (extra, expected) in cases {
        let out = glint()
            .arg("turntable")
            .arg(demo())
            .arg("-o")
            .arg(&out_dir)
            .args(extra)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{extra:?} succeeded");
        assert!(err.contains(expected), "{extra:?}: {err}");
    }
    // A plain file name is neither a pattern nor a folder.
    let out = glint()
        .arg("turntable")
        .arg(demo())
        .arg("-o")
        .arg(tmp.path().join("x.png"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("pattern with #"));
    assert!(!out_dir.exists(), "a refused run created its folder");
}
