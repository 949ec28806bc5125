//! The binary end to end: renders of the demo scene, `info`, and bad invocations that must fail cleanly.

mod common;

use std::path::Path;
use std::process::{Command, Output};

fn glint(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(args)
        .output()
        .expect("run glint")
}

fn demo() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/demo/demo.glb")
        .to_string_lossy()
        .into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn renders_the_demo_to_png_and_exr_with_each_backend() {
    let dir = tempfile::tempdir().unwrap();
    for backend in glint::accel::Backend::all_available() {
        for ext in ["png", "exr"] {
            let out = dir.path().join(format!("demo-{backend}.{ext}"));
            let o = glint(&[
                "render",
                &demo(),
                "-o",
                out.to_str().unwrap(),
                "--width",
                "40",
                "--height",
                "30",
                "--spp",
                "2",
                "--backend",
                &backend.to_string(),
            ]);
            assert!(o.status.success(), "{}", stderr(&o));
            assert!(stderr(&o).contains("Mrays/s"), "{}", stderr(&o));
            let size = if ext == "png" {
                let img = image::open(&out).unwrap();
                (img.width() as usize, img.height() as usize)
            } else {
                let img = glint::film::read_exr(&out).unwrap();
                assert!(!img.has_non_finite());
                (img.width, img.height)
            };
            assert_eq!(size, (40, 30));
        }
    }
    // Nothing but the outputs (two per backend): no temporary files left.
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        2 * glint::accel::Backend::all_available().len()
    );
}

#[test]
fn info_prints_the_counts() {
    let o = glint(&["info", &demo()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    for key in [
        "nodes",
        "meshes",
        "triangles",
        "materials",
        "lights",
        "cameras",
        "animations",
    ] {
        assert!(text.contains(key), "{key} missing from:\n{text}");
    }
    assert!(text.contains("lights      2"), "{text}");
    assert!(text.contains("cameras     1"), "{text}");
}

#[test]
fn bad_invocations_fail_with_a_message_and_leave_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.png");
    let out = out.to_str().unwrap();
    let missing = dir.path().join("nope.glb");
    let demo = demo();
    let demo = demo.as_str();
    // `render DEMO -o OUT` and the given flags.
    let render = |flags: &[&'static str]| {
        let mut args = vec!["render", demo, "-o", out];
        args.extend_from_slice(flags);
        args
    };
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["render", missing.to_str().unwrap(), "-o", out],
            "nope.glb",
        ),
        (vec!["render", demo, "-o", "x.bmp"], "x.bmp"),
        (render(&["--width", "0"]), "out of range"),
        (render(&["--camera", "7"]), "no camera"),
        (render(&["--backend", "gpu"]), "gpu"),
        (render(&["--eye", "1,2"]), "x,y,z"),
        (vec!["info", missing.to_str().unwrap()], "nope.glb"),
        (
            render(&["--focus-distance", "2"]),
            "need --aperture or --fstop",
        ),
        (render(&["--fstop", "0"]), "--fstop must be positive"),
        (
            render(&["--aperture", "0.1", "--focus-on", "900,2"]),
            "outside",
        ),
        (
            render(&[
                "--width",
                "8",
                "--height",
                "8",
                "--aperture",
                "0.1",
                "--focus-on",
                "4,4",
                "--eye",
                "0,0,100",
                "--look-at",
                "0,0,200",
            ]),
            "sees no surface",
        ),
        (render(&["--shutter", "0.1,0"]), "OPEN <= CLOSE"),
        // NaN and infinities in numeric flags used to run on into black images.
        (
            render(&["--exposure", "nan"]),
            "'nan': expected a finite number",
        ),
        (
            render(&["--frame-time", "inf"]),
            "'inf': expected a finite number",
        ),
        (
            render(&["--filter-radius", "1e30"]),
            "above 0 and at most 16",
        ),
        (render(&["--filter-radius", "0"]), "above 0 and at most 16"),
        (
            vec!["turntable", demo, "-o", out, "--elevation", "NaN"],
            "'NaN': expected a finite number",
        ),
        // A bench of no rays reported 0 Mrays/s; one of a billion would have run out of memory.
        // The benches refuse the sizes a render refuses.
        (
            vec!["bench", "rays", demo, "--width", "0"],
            "image size 0x768 is out of range",
        ),
        (
            vec![
                "bench", "rays", demo, "--width", "30000", "--height", "30000",
            ],
            "image size 30000x30000 is out of range",
        ),
    ];
    for (args, needle) in cases {
        let o = glint(&args);
        assert!(!o.status.success(), "{args:?} succeeded");
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"), "{args:?}: {}", stderr(&o));
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn same_seed_same_image_whatever_the_thread_count() {
    let (scene, camera) = common::load_for_render(Path::new(&demo()), 32, 24);
    let settings = glint::render::RenderSettings {
        width: 32,
        height: 24,
        spp: 3,
        max_depth: 4,
        seed: 9,
        ..Default::default()
    };
    let backend = glint::accel::Backend::Bvh;
    let with_threads = |n: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
            .install(|| common::render_with(&scene, &camera, backend, &settings))
    };
    let one = with_threads(1);
    assert_eq!(one, with_threads(3));
    let other_seed = common::render_with(
        &scene,
        &camera,
        backend,
        &glint::render::RenderSettings {
            seed: 10,
            ..settings.clone()
        },
    );
    assert_ne!(one, other_seed);
}

#[test]
fn a_reader_that_goes_away_is_not_a_crash() {
    // As in `glint info model.glb | head -1`: the pipe closes before glint writes.
    let mut child = Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(["info", &demo()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run glint");
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
}

#[test]
fn scene_file_settings_apply_unless_a_flag_is_given() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("s.toml");
    std::fs::write(
        &scene,
        format!(
            "[render]\nwidth = 24\nheight = 18\nspp = 2\n\n[[asset]]\npath = {:?}\n\n\
             [[light]]\ntype = \"environment\"\nstrength = 0.5\n",
            demo()
        ),
    )
    .unwrap();
    let out = dir.path().join("a.png");
    let o = glint(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(image::image_dimensions(&out).unwrap(), (24, 18));
    let o = glint(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--width",
        "30",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(image::image_dimensions(&out).unwrap(), (30, 18));
}

#[test]
fn env_maps_light_renders_and_bad_ones_are_named() {
    let dir = tempfile::tempdir().unwrap();
    // A 4 x 2 lat-long map: bright sky row above a dark ground row.
    let mut sky = glint::film::Image::new(4, 2);
    for (i, p) in sky.pixels.iter_mut().enumerate() {
        let v = if i < 4 { 2.0 } else { 0.1 };
        *p = glam::Vec4::new(v, v, v, 1.0);
    }
    let map = dir.path().join("sky.exr");
    glint::film::write(&sky, &map, 0.0).unwrap();
    let out = dir.path().join("lit.exr");
    let args = |env: &str| {
        vec![
            "render".to_string(),
            demo(),
            "-o".into(),
            out.to_str().unwrap().into(),
            "--width".into(),
            "16".into(),
            "--height".into(),
            "12".into(),
            "--spp".into(),
            "2".into(),
            "--env".into(),
            env.into(),
            "--env-strength".into(),
            "0.5".into(),
            "--env-rotation".into(),
            "-30".into(),
        ]
    };
    let run = |a: Vec<String>| glint(&a.iter().map(String::as_str).collect::<Vec<_>>());
    let o = run(args(map.to_str().unwrap()));
    assert!(o.status.success(), "{}", stderr(&o));
    let img = glint::film::read_exr(&out).unwrap();
    assert!(!img.has_non_finite());
    // Background pixels see the map: the top row the sky or the ground, times the strength.
    let top = img.get(0, 0);
    assert!(top.x > 0.04 && top.x < 1.01, "top-left pixel {top}");

    let bad = dir.path().join("bad.hdr");
    std::fs::write(&bad, b"#?RADIANCE\nnot really").unwrap();
    for path in [
        bad,
        dir.path().join("absent.exr"),
        dir.path().join("sky.png"),
    ] {
        let o = run(args(path.to_str().unwrap()));
        assert!(!o.status.success());
        let name = path.file_name().unwrap().to_str().unwrap();
        assert!(stderr(&o).contains(name), "{}", stderr(&o));
    }
}

#[test]
fn verbose_lists_skipped_features_and_the_bench_times_forcing_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("v.png");
    let args = ["--width", "24", "--height", "18", "--spp", "2"];
    let demo = demo();
    let mut render = vec!["render", &demo, "-o", out.to_str().unwrap(), "--verbose"];
    render.extend(args);
    let o = glint(&render);
    assert!(o.status.success(), "{}", stderr(&o));
    // The demo is static, seen through a pinhole, opaque, and has no CSG.
    let lists = |o: &Output| -> (String, String) {
        let text = stderr(o);
        let line = text
            .lines()
            .find(|l| l.contains("uses: "))
            .unwrap_or_else(|| {
                panic!("no feature list in {text}");
            });
        let (uses, skips) = line.split_once("; skips: ").expect("uses; skips");
        (
            uses.split_once("uses: ").unwrap().1.to_string(),
            skips.to_string(),
        )
    };
    let (uses, skips) = lists(&o);
    for f in ["motion", "lens", "transmission", "CSG"] {
        assert!(
            skips.contains(f) && !uses.contains(f),
            "{f}: {uses} / {skips}"
        );
    }
    render.push("--aperture");
    render.push("0.05");
    let o = glint(&render);
    assert!(o.status.success(), "{}", stderr(&o));
    let (uses, skips) = lists(&o);
    assert!(
        uses.contains("lens") && !skips.contains("lens"),
        "{uses} / {skips}"
    );

    let mut bench = vec!["bench", "features", "icosphere:2", "--repeat", "1"];
    bench.extend(args);
    let o = glint(&bench);
    assert!(o.status.success(), "{}", stderr(&o));
    let table = String::from_utf8_lossy(&o.stdout).into_owned();
    // Rows end in the image difference; forcing skipped machinery on (`+` rows) changes sampling
    // at most, so those images stay close.
    let rows: Vec<(&str, f64)> = table
        .lines()
        .filter_map(|l| Some((l, l.split_whitespace().last()?.parse().ok()?)))
        .collect();
    let forced: Vec<f64> = rows
        .iter()
        .filter(|(l, _)| l.starts_with('+') || l.starts_with("all"))
        .map(|r| r.1)
        .collect();
    assert_eq!(forced.len(), 4, "{table}");
    assert!(forced.iter().all(|d| *d < 0.05), "{table}");
    assert!(
        rows.iter().any(|(l, _)| l.starts_with("- glossy")),
        "{table}"
    );
}

/// `--sample-shard I/N` over four machines, merged, gives the whole render's EXR byte for byte; a
/// shard of another scene is refused, and a missing one is named.
#[test]
fn four_sample_shards_merge_into_the_whole_render() {
    let dir = tempfile::tempdir().unwrap();
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/demo/demo.glb");
    let other = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let other = std::fs::read_dir(&other)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "toml"))
        .unwrap();
    let base = [
        "--width",
        "24",
        "--height",
        "16",
        "--spp",
        "8",
        "--seed",
        "3",
        "--threads",
        "2",
        "-q",
    ];
    let render = |input: &std::path::Path, out: &std::path::Path, shard: Option<&str>| {
        let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_glint"));
        cmd.arg("render").arg(input).arg("-o").arg(out).args(base);
        if let Some(s) = shard {
            cmd.args(["--sample-shard", s]);
        }
        let st = cmd.output().unwrap();
        assert!(
            st.status.success(),
            "{}",
            String::from_utf8_lossy(&st.stderr)
        );
    };
    let whole = dir.path().join("whole.exr");
    render(&scene, &whole, None);
    let mut parts = vec![];
    for i in 0..4 {
        let p = dir.path().join(format!("part{i}.exr"));
        render(&scene, &p, Some(&format!("{i}/4")));
        parts.push(p);
    }
    let merge = |parts: &[std::path::PathBuf], out: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
            .arg("merge")
            .args(parts)
            .arg("-o")
            .arg(out)
            .output()
            .unwrap()
    };
    let merged = dir.path().join("merged.exr");
    let st = merge(&parts, &merged);
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    assert_eq!(
        std::fs::read(&merged).unwrap(),
        std::fs::read(&whole).unwrap()
    );
    // Missing shards are named.
    let st = merge(&parts[..2], &dir.path().join("m2.exr"));
    let err = String::from_utf8_lossy(&st.stderr);
    assert!(!st.status.success() && err.contains("2/4, 3/4"), "{err}");
    // A shard of another scene is refused.
    let foreign = dir.path().join("foreign.exr");
    render(&other, &foreign, Some("3/4"));
    let mut mixed = parts[..3].to_vec();
    mixed.push(foreign);
    let st = merge(&mixed, &dir.path().join("m3.exr"));
    let err = String::from_utf8_lossy(&st.stderr);
    assert!(
        !st.status.success() && err.contains("another scene"),
        "{err}"
    );
}
