//! Stress of the binary: a turntable killed (SIGKILL) at several moments and resumed ends with the
//! frames of an unbroken run, byte for byte, and no temporary file; `--threads 64` renders what
//! `--threads 1` does; two processes writing one output path leave one whole file of one of them.
//! The long version (50 kills) is scripts/kill-resume.sh.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn glint() -> Command {
    Command::new(env!("CARGO_BIN_EXE_glint"))
}

fn demo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/demo/demo.glb")
}

const FRAMES: u32 = 8;

/// The turntable every run of the kill test makes: small frames, so that a run takes a moment.
fn turntable(out: &Path) -> Command {
    let mut c = glint();
    c.arg("turntable")
        .arg(demo())
        .arg("-o")
        .arg(out)
        .args([
            "--frames",
            &FRAMES.to_string(),
            "--width",
            "48",
            "--height",
            "32",
        ])
        .args([
            "--spp",
            "8",
            "--backend",
            "bvh",
            "--quiet",
            "--threads",
            "2",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    c
}

/// Every file of `dir` by name, with its bytes.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(e.path()).unwrap())
        })
        .collect();
    v.sort();
    v
}

#[test]
fn a_turntable_killed_at_any_moment_and_resumed_ends_with_the_unbroken_frames() {
    let dir = tempfile::tempdir().unwrap();
    let whole = dir.path().join("whole");
    let t = Instant::now();
    assert!(turntable(&whole).status().unwrap().success());
    let unbroken = t.elapsed();
    let expected = files(&whole);
    assert_eq!(expected.len(), FRAMES as usize);

    // Kills spread over the first run's length (a fixed sequence, so a failure can be rerun),
    // then one run to the end.
    let broken = dir.path().join("broken");
    let mut kills = 0;
    for k in 0..6u32 {
        let at = unbroken.mul_f64(f64::from(k * 37 % 11 + 1) / 12.0);
        let mut child = turntable(&broken).spawn().unwrap();
        std::thread::sleep(at);
        if child.try_wait().unwrap().is_none() {
            child.kill().unwrap();
            kills += 1;
        }
        child.wait().unwrap();
    }
    let status = turntable(&broken).status().unwrap();
    assert!(status.success());
    assert!(kills > 0, "no run was still going when killed");
    let got = files(&broken);
    let names = |v: &[(String, Vec<u8>)]| v.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(
        names(&got),
        names(&expected),
        "frames or temporary files differ"
    );
    for ((name, a), (_, b)) in got.iter().zip(&expected) {
        assert!(
            a == b,
            "{name} differs from the unbroken run's after {kills} kills"
        );
    }
}

/// Renders the demo at `threads` threads into `out` with `seed`.
fn render(out: &Path, threads: u32, seed: u64) -> Command {
    let mut c = glint();
    c.arg("render")
        .arg(demo())
        .arg("-o")
        .arg(out)
        .args([
            "--width",
            "40",
            "--height",
            "30",
            "--spp",
            "4",
            "--backend",
            "bvh",
            "--quiet",
        ])
        .args([
            "--threads",
            &threads.to_string(),
            "--seed",
            &seed.to_string(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    c
}

#[test]
fn sixty_four_threads_on_few_cores_render_the_one_thread_image() {
    let dir = tempfile::tempdir().unwrap();
    let (one, many) = (dir.path().join("one.exr"), dir.path().join("many.exr"));
    assert!(render(&one, 1, 3).status().unwrap().success());
    assert!(render(&many, 64, 3).status().unwrap().success());
    let (a, b) = (std::fs::read(&one).unwrap(), std::fs::read(&many).unwrap());
    assert!(a == b, "--threads 64 and --threads 1 differ");
}

#[test]
fn two_processes_writing_one_path_leave_one_whole_image() {
    let dir = tempfile::tempdir().unwrap();
    // The two images each process makes alone (different seeds, so they differ).
    let solo: Vec<Vec<u8>> = [1, 2]
        .iter()
        .map(|&seed| {
            let p = dir.path().join(format!("solo{seed}.png"));
            assert!(render(&p, 1, seed).status().unwrap().success());
            std::fs::read(p).unwrap()
        })
        .collect();
    assert!(solo[0] != solo[1]);
    let shared = dir.path().join("shared.png");
    for round in 0..3 {
        let _ = std::fs::remove_file(&shared);
        let mut a = render(&shared, 1, 1).spawn().unwrap();
        let mut b = render(&shared, 1, 2).spawn().unwrap();
        assert!(a.wait().unwrap().success() && b.wait().unwrap().success());
        let got = std::fs::read(&shared).unwrap();
        assert!(
            got == solo[0] || got == solo[1],
            "round {round}: the file is neither process's image"
        );
    }
    let left: Vec<String> = files(dir.path()).into_iter().map(|(n, _)| n).collect();
    assert_eq!(left, ["shared.png", "solo1.png", "solo2.png"]);
    // A render killed mid-run never leaves a partial file under the final name, and the next one
    // clears the temporary file it may have left.
    let killed = dir.path().join("killed.png");
    for wait_ms in [20, 60, 150] {
        let mut c = render(&killed, 1, 1).spawn().unwrap();
        std::thread::sleep(Duration::from_millis(wait_ms));
        let _ = c.kill();
        c.wait().unwrap();
        if let Ok(bytes) = std::fs::read(&killed) {
            assert_eq!(bytes, solo[0], "a killed render left a partial image");
        }
    }
    assert!(render(&killed, 1, 1).status().unwrap().success());
    let left: Vec<String> = files(dir.path()).into_iter().map(|(n, _)| n).collect();
    assert_eq!(left, ["killed.png", "shared.png", "solo1.png", "solo2.png"]);
}
