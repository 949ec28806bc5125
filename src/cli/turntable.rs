//! `glint turntable`: flags for a turntable sequence, then `crate::turntable` does the work.
//! Load and build happen once; a finished sequence (all frames on disk) skips both and only previews.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Result};
use clap::ValueEnum;

use super::args::{finite, Args, DenoiseArgs};
use super::{load, progress_bar};
use crate::film::Format;
use crate::render::job::{self, Basics, CameraChoice, JobOptions, Overrides, Setup, View};
use crate::scene::{defaults, LoadOptions};
use crate::turntable::{
    self, FrameNames, LightMode, Motion, Orbit, Shard, Turntable, DEFAULT_ELEVATION_DEG,
};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum FrameFormat {
    Png,
    Exr,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Lights {
    /// Lights stay where they are while the camera moves.
    World,
    /// Lights turn with the camera, so every frame is lit the same way.
    Camera,
}

#[derive(clap::Args, Debug)]
pub struct TurntableArgs {
    /// A .gltf, .glb or .obj file.
    pub input: PathBuf,
    /// Frame pattern with a run of # for the frame index (frames/helmet_####.png), or a folder
    /// (frames are then frame_####.<format> inside it; created when missing).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Frames in one full turn.
    #[arg(long, default_value_t = 120)]
    pub frames: u32,
    /// File type of the frames in folder mode (a pattern's extension decides otherwise).
    #[arg(long, value_enum)]
    pub format: Option<FrameFormat>,
    /// Camera height above the model's centre, in degrees.
    #[arg(long, value_parser = finite, default_value_t = DEFAULT_ELEVATION_DEG, allow_hyphen_values = true)]
    pub elevation: f32,
    /// Azimuth of frame 0 in degrees (0: in front, on +Z).
    #[arg(long, value_parser = finite, default_value_t = 0.0, allow_hyphen_values = true)]
    pub azimuth: f32,
    /// Camera distance from the model's centre (default: the bounding sphere fills the view).
    #[arg(long, value_parser = finite)]
    pub distance: Option<f32>,
    /// Turn the model in front of a fixed camera instead of orbiting the camera.
    #[arg(long)]
    pub spin: bool,
    /// What the lights are fixed to while the camera orbits.
    #[arg(long, value_enum, default_value_t = Lights::World)]
    pub lights: Lights,
    /// Motion blur: degrees of the frame interval the shutter is open (e.g. 180).
    #[arg(long, value_parser = finite)]
    pub shutter_angle: Option<f32>,
    /// Render only frames f with f mod N == I (I/N), for one machine of N.
    #[arg(long)]
    pub shard: Option<Shard>,
    /// Render only frames A..B (half-open; clipped to the sequence).
    #[arg(long, value_parser = turntable::parse_frame_range)]
    pub frame_range: Option<std::ops::Range<u32>>,
    /// Render frames whose file already exists again (default: skip them, which resumes a run).
    #[arg(long)]
    pub overwrite: bool,
    /// Animated GIF of the whole sequence, built once every frame is on disk.
    #[arg(long)]
    pub preview: Option<PathBuf>,
    /// Frame rate of the GIF preview.
    #[arg(long, value_parser = finite, default_value_t = 24.0)]
    pub preview_fps: f32,
    /// Largest GIF width in pixels (frames are downscaled to it).
    #[arg(long, default_value_t = 480)]
    pub preview_width: u32,
    /// PNG grid of all frames, built once every frame is on disk.
    #[arg(long)]
    pub contact_sheet: Option<PathBuf>,
    #[command(flatten)]
    pub denoise: DenoiseArgs,
    #[command(flatten)]
    pub common: Args,
}

fn check_extension(path: &Path, ext: &str, flag: &str) -> Result<()> {
    let ok = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(ext));
    if !ok {
        bail!("{flag} {}: expected a .{ext} file", path.display());
    }
    Ok(())
}

/// The checked flags of one turntable run.
struct Plan {
    basics: Basics,
    yfov: f32,
    shutter_angle: f32,
    names: FrameNames,
    selected: Vec<u32>,
}

pub fn run(args: TurntableArgs) -> Result<()> {
    let plan = plan(&args)?;
    args.common.set_threads()?;
    remove_stale_temps(&args, &plan);
    let exists = |f: &u32| plan.names.path(*f).exists();
    if !args.overwrite && plan.selected.iter().all(exists) {
        // A finished (or finished-by-other-shards) sequence: no need to load or build anything.
        if !args.common.quiet {
            eprintln!(
                "{}: all {} selected frames exist; nothing to render",
                args.input.display(),
                plan.selected.len()
            );
        }
    } else {
        render_frames(&args, &plan)?;
    }
    if args.preview.is_some() || args.contact_sheet.is_some() {
        write_previews(&args, &plan.names)?;
    }
    Ok(())
}

fn plan(args: &TurntableArgs) -> Result<Plan> {
    // A sequence takes its settings from the command line only (not from a scene file's [render]).
    let basics = job::resolve(
        Basics::default(),
        &Overrides::default(),
        &args.common.overrides(),
    );
    basics.validate()?;
    args.denoise.check()?;
    if !(args.elevation > -90.0 && args.elevation < 90.0) {
        bail!("--elevation must be between -90 and 90 degrees (exclusive)");
    }
    if !args.azimuth.is_finite() {
        bail!("--azimuth must be a finite number of degrees");
    }
    let yfov = args
        .common
        .fov
        .unwrap_or(defaults::DEFAULT_FOV_DEG)
        .to_radians();
    if !(yfov > 0.0 && yfov < std::f32::consts::PI) {
        bail!("--fov must be between 0 and 180 degrees");
    }
    if let Some(d) = args.distance.filter(|d| !(d.is_finite() && *d > 0.0)) {
        bail!("--distance {d} must be a positive number");
    }
    let shutter_angle = args.shutter_angle.unwrap_or(0.0);
    if !(0.0..=360.0).contains(&shutter_angle) {
        bail!("--shutter-angle {shutter_angle} is out of range (0..=360 degrees)");
    }
    if let Some(p) = &args.preview {
        check_extension(p, "gif", "--preview")?;
    }
    if let Some(p) = &args.contact_sheet {
        check_extension(p, "png", "--contact-sheet")?;
    }
    let format = args.format.map(|f| match f {
        FrameFormat::Png => Format::Png,
        FrameFormat::Exr => Format::Exr,
    });
    let names = FrameNames::from_output(&args.output, format, args.frames)?;
    let selected = turntable::select_frames(args.frames, args.shard, args.frame_range.clone())?;
    Ok(Plan {
        basics,
        yfov,
        shutter_angle,
        names,
        selected,
    })
}

/// Clears what killed runs of this sequence left: temporary files of dead processes beside the
/// selected frames and the previews.
fn remove_stale_temps(args: &TurntableArgs, plan: &Plan) {
    let previews: Vec<&Path> = [&args.preview, &args.contact_sheet]
        .into_iter()
        .flatten()
        .map(PathBuf::as_path)
        .collect();
    let stale = turntable::remove_stale_temps(&plan.names, &plan.selected, &previews);
    if stale > 0 && !args.common.quiet {
        eprintln!("removed {stale} temporary files that an interrupted run left behind");
    }
}

/// The GIF and the contact sheet, once every frame of the sequence is on disk.
fn write_previews(args: &TurntableArgs, names: &FrameNames) -> Result<()> {
    let missing = turntable::missing_frames(names, args.frames);
    if let Some(first) = missing.first() {
        eprintln!(
            "warning: previews skipped: {} of {} frames are not on disk yet (first: {}); run again once every shard has finished",
            missing.len(),
            args.frames,
            names.path(*first).display()
        );
        return Ok(());
    }
    let t = Instant::now();
    if let Some(p) = &args.preview {
        turntable::write_gif(
            names,
            args.frames,
            &args.common.display(),
            p,
            args.preview_fps,
            args.preview_width,
        )?;
    }
    if let Some(p) = &args.contact_sheet {
        turntable::write_contact_sheet(names, args.frames, &args.common.display(), p, 256)?;
    }
    if !args.common.quiet {
        eprintln!("previews written in {:.2} s", t.elapsed().as_secs_f64());
    }
    Ok(())
}

fn render_frames(args: &TurntableArgs, plan: &Plan) -> Result<()> {
    let t0 = Instant::now();
    let scene = load(
        &args.input,
        &LoadOptions {
            scene: args.common.scene.clone().unwrap_or_default(),
            ..Default::default()
        },
    )?;
    let load_s = t0.elapsed().as_secs_f64();
    let basics = &plan.basics;
    // The orbit frames the scene as the job will turn it.
    let mut orbit = Orbit::framing(
        &scene.bounds().transformed(&args.common.model_up.to_y_up()),
        plan.yfov,
        basics.aspect(),
        args.elevation.to_radians(),
    );
    orbit.start_azimuth = args.azimuth.to_radians();
    if let Some(d) = args.distance {
        orbit.distance = d;
    }
    let opts = JobOptions {
        defaults: *basics,
        flags: Overrides::all(*basics),
        view: View {
            camera: CameraChoice::Given(orbit.camera(0.0)),
            ..Default::default()
        },
        default_lights: args.common.default_lights,
        variant: args.common.variant.clone(),
        up_axis: args.common.model_up,
        ..Default::default()
    };
    let job = Setup::new(scene, &opts)?.build()?;
    let tt = Turntable {
        frames: args.frames,
        names: plan.names.clone(),
        orbit,
        motion: if args.spin {
            Motion::Spin
        } else {
            Motion::Orbit
        },
        lights: match args.lights {
            Lights::World => LightMode::World,
            Lights::Camera => LightMode::Camera,
        },
        shutter_angle: plan.shutter_angle,
        settings: job.settings.clone(),
        exposure: args.common.exposure,
        view: args.common.view,
        overwrite: args.overwrite,
        denoise: args.denoise.asked(),
    };
    let progress = progress_bar(
        args.common.quiet,
        "{spinner} turntable [{bar:40}] {pos}/{len} frames ({msg}), {elapsed} elapsed, eta {eta}",
    );
    let report = tt.render_sequence(&job.scene, job.accel.as_ref(), &plan.selected, &progress)?;
    if !args.common.quiet {
        print_report(
            args,
            plan,
            &report,
            load_s,
            job.build_seconds,
            job.accel.name(),
        );
    }
    Ok(())
}

fn print_report(
    args: &TurntableArgs,
    plan: &Plan,
    report: &turntable::SequenceReport,
    load_s: f64,
    build_s: f64,
    accel: &str,
) {
    let basics = &plan.basics;
    let total: f64 = report.frame_seconds.iter().sum();
    eprintln!(
        "{}: {} frames rendered, {} skipped (of {} selected, {} in the sequence), {}x{} at {} spp with {accel}",
        args.input.display(),
        report.rendered.len(),
        report.skipped.len(),
        plan.selected.len(),
        args.frames,
        basics.width,
        basics.height,
        basics.spp,
    );
    eprintln!(
        "cost: load {load_s:.3} s, build {build_s:.3} s (once), per frame {:.3} s mean ({:.2} s for {} frames, {:.2} Mrays/s){}",
        report.mean_frame_seconds(),
        total,
        report.rendered.len(),
        report.rays as f64 / total.max(1e-9) / 1e6,
        if report.scene_copy_seconds > 0.0 {
            format!(", scene copy for moving lights {:.3} s", report.scene_copy_seconds)
        } else {
            String::new()
        }
    );
}
