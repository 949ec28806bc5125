//! Turntable sequences: the scene is loaded and its accelerator built once, then N frames orbit it.
//! Frame naming, sharding, resume, orbit cameras, motion blur and previews; `cli::turntable` only parses.

use std::f32::consts::TAU;
use std::fs;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::{Mat4, Vec3};
use indicatif::ProgressBar;
use thiserror::Error;

use crate::accel::Accel;
use crate::film::aov::FeatureImages;
use crate::film::denoise::{DenoiseError, DenoiseOptions, Denoiser};
use crate::film::{self, FilmError, Format, Image};
use crate::geometry::mix64;
use crate::geometry::Aabb;
use crate::render::{self, RenderSettings};
use crate::scene::{defaults, Camera, Light, Scene};

/// Default camera elevation above the orbit plane, in degrees.
pub const DEFAULT_ELEVATION_DEG: f32 = 20.0;
/// Most sub-frames averaged for motion blur (fewer when `spp` is smaller: each needs one sample).
pub const MAX_SUBFRAMES: u32 = 8;
/// Longest accepted sequence: guards against a typo turning into a month of rendering.
pub const MAX_FRAMES: u32 = 1_000_000;
/// Digits of the frame number in folder mode (more when the sequence needs them).
const FOLDER_DIGITS: usize = 4;

#[derive(Debug, Error)]
pub enum TurntableError {
    #[error(transparent)]
    Film(#[from] FilmError),
    #[error(transparent)]
    Denoise(#[from] DenoiseError),
    #[error("{}: --format {format} disagrees with the pattern's extension", path.display())]
    FormatDisagrees { path: PathBuf, format: &'static str },
    #[error("{}: the frame pattern must hold one run of # (e.g. helmet_####.png)", .0.display())]
    HashRuns(PathBuf),
    #[error("{}: a sequence needs a frame pattern with # (e.g. frames/helmet_####.png) or a folder", .0.display())]
    NotASequence(PathBuf),
    #[error("--frames {0} is out of range (1..={MAX_FRAMES})")]
    Frames(u32),
    #[error("--shard {0}/{1}: the index must be below the count")]
    Shard(u32, u32),
    #[error("--frame-range {0}..{1} starts past the last frame ({2})")]
    RangePastEnd(u32, u32, u32),
    #[error("--frame-range {0}..{1} is empty")]
    RangeEmpty(u32, u32),
    #[error("the preview frame rate {0} is out of range (0 < fps <= 100)")]
    Fps(f32),
    #[error("no frames for the contact sheet")]
    NoFrames,
    #[error("creating {}", path.display())]
    CreateDir {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("reading {}", path.display())]
    ReadFrame {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    #[error("writing {}", path.display())]
    WritePreview {
        path: PathBuf,
        #[source]
        source: Box<TurntableError>,
    },
    #[error("renaming into {}", path.display())]
    Rename {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error(transparent)]
    Io(#[from] std::io::Error),
    #[error(transparent)]
    Image(#[from] image::ImageError),
}

type Result<T, E = TurntableError> = std::result::Result<T, E>;

/// Where frame `f` is written: a pattern whose file name holds one run of `#` (the zero-padded frame
/// index), or `frame_####.<ext>` inside a folder.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FrameNames {
    dir: PathBuf,
    prefix: String,
    digits: usize,
    suffix: String,
    format: Format,
}

fn extension(format: Format) -> &'static str {
    match format {
        Format::Png => "png",
        Format::Exr => "exr",
    }
}

impl FrameNames {
    /// Interprets `-o`: a pattern when its file name contains `#`, a folder when it ends with a
    /// separator, is an existing folder or has no extension. `format` (from `--format`) picks the
    /// folder's file type (default PNG); for a pattern it must agree with the pattern's extension.
    pub fn from_output(output: &Path, format: Option<Format>, frames: u32) -> Result<Self> {
        let text = output.to_string_lossy();
        let ends_with_sep = text.ends_with('/') || text.ends_with(std::path::MAIN_SEPARATOR);
        let name = output
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        if !ends_with_sep && name.contains('#') {
            let pattern_format = Format::from_path(output)?;
            if let Some(f) = format.filter(|&f| f != pattern_format) {
                return Err(TurntableError::FormatDisagrees {
                    path: output.to_path_buf(),
                    format: extension(f),
                });
            }
            let start = name.find('#').expect("contains #");
            let digits = name[start..].chars().take_while(|&c| c == '#').count();
            let (prefix, suffix) = (&name[..start], &name[start + digits..]);
            if suffix.contains('#') {
                return Err(TurntableError::HashRuns(output.to_path_buf()));
            }
            return Ok(Self {
                dir: output.parent().map(Path::to_path_buf).unwrap_or_default(),
                prefix: prefix.into(),
                digits,
                suffix: suffix.into(),
                format: pattern_format,
            });
        }
        if !ends_with_sep && !output.is_dir() && output.extension().is_some() {
            return Err(TurntableError::NotASequence(output.to_path_buf()));
        }
        let format = format.unwrap_or(Format::Png);
        let needed = frames.saturating_sub(1).max(1).ilog10() as usize + 1;
        Ok(Self {
            dir: output.to_path_buf(),
            prefix: "frame_".into(),
            digits: needed.max(FOLDER_DIGITS),
            suffix: format!(".{}", extension(format)),
            format,
        })
    }

    /// The file of frame `frame` (a number wider than the run of `#` is written in full).
    pub fn path(&self, frame: u32) -> PathBuf {
        let name = format!(
            "{}{:0w$}{}",
            self.prefix,
            frame,
            self.suffix,
            w = self.digits
        );
        self.dir.join(name)
    }

    pub fn format(&self) -> Format {
        self.format
    }

    /// The folder the frames go to ("" for the current one).
    pub fn dir(&self) -> &Path {
        &self.dir
    }
}

/// One machine's share of the frames: those with `frame % count == index`.
pub use crate::film::shard::Shard;

/// Parses a half-open frame range `A..B` (A < B).
pub fn parse_frame_range(s: &str) -> Result<Range<u32>, String> {
    let (a, b) = s
        .split_once("..")
        .ok_or_else(|| format!("'{s}': expected A..B (half-open, e.g. 0..30)"))?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|e| format!("'{s}': '{v}': {e}"))
    };
    let (a, b) = (parse(a)?, parse(b)?);
    if a >= b {
        return Err(format!("'{s}': the range is empty (A must be below B)"));
    }
    Ok(a..b)
}

/// The frames this run is responsible for, in order: the whole sequence, narrowed by a shard and/or a
/// range. A range reaching past the end is clipped (so fixed-size farm chunks need no special last
/// chunk); one starting past the end is an error.
pub fn select_frames(
    frames: u32,
    shard: Option<Shard>,
    range: Option<Range<u32>>,
) -> Result<Vec<u32>> {
    if frames == 0 || frames > MAX_FRAMES {
        return Err(TurntableError::Frames(frames));
    }
    if let Some(s) = shard {
        if s.count == 0 || s.index >= s.count {
            return Err(TurntableError::Shard(s.index, s.count));
        }
    }
    let range = match range {
        Some(r) if r.start >= frames => {
            return Err(TurntableError::RangePastEnd(r.start, r.end, frames - 1))
        }
        Some(r) if r.start >= r.end => return Err(TurntableError::RangeEmpty(r.start, r.end)),
        Some(r) => r.start..r.end.min(frames),
        None => 0..frames,
    };
    Ok(range
        .filter(|f| shard.is_none_or(|s| f % s.count == s.index))
        .collect())
}

/// The noise seed of a frame: depends only on the base seed and the frame index, so a frame is the
/// same image whichever machine, shard or resumed run renders it.
pub fn frame_seed(base: u64, frame: u32) -> u64 {
    mix64(base ^ mix64(frame as u64 ^ 0x7475_726E_7461_626C))
}

/// A camera circling a vertical (world +Y) axis through `center`.
#[derive(Clone, Debug, PartialEq)]
pub struct Orbit {
    pub center: Vec3,
    pub distance: f32,
    /// Radians above the horizontal plane through `center`.
    pub elevation: f32,
    /// Azimuth of frame 0 in radians; 0 puts the camera on +Z (glTF's front).
    pub start_azimuth: f32,
    /// Vertical field of view in radians.
    pub yfov: f32,
}

impl Orbit {
    /// An orbit around the centre of `bounds` at the distance where its bounding sphere fills the view.
    /// The sphere, unlike the box, looks the same from every angle, so every frame fits.
    pub fn framing(bounds: &Aabb, yfov: f32, aspect: f32, elevation: f32) -> Self {
        let (center, radius) = defaults::bounding_sphere(bounds);
        Self {
            center,
            // The same 5% margin as `glint render`'s framing camera.
            distance: defaults::framing_distance(radius, yfov, aspect) * 1.05,
            elevation,
            start_azimuth: 0.0,
            yfov,
        }
    }

    /// The camera `turn` radians around the orbit from frame 0.
    pub fn camera(&self, turn: f32) -> Camera {
        let az = self.start_azimuth + turn;
        let (se, ce) = self.elevation.sin_cos();
        let dir = Vec3::new(ce * az.sin(), se, ce * az.cos());
        let mut c = Camera::look_at(
            self.center + dir * self.distance,
            self.center,
            Vec3::Y,
            self.yfov,
        );
        c.name = "turntable".into();
        c
    }

    /// A rotation by `angle` about the orbit axis, applied to a light.
    pub fn rotate_light(&self, light: &Light, angle: f32) -> Light {
        let about_center = Mat4::from_translation(self.center)
            * Mat4::from_rotation_y(angle)
            * Mat4::from_translation(-self.center);
        light.transformed(&about_center)
    }
}

/// What moves between frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// The camera circles the model.
    Orbit,
    /// The model turns in front of a fixed camera.
    Spin,
}

/// What the lights (the file's and the default rig's) are attached to while the camera orbits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightMode {
    World,
    Camera,
}

/// Everything that defines a sequence, except the scene.
#[derive(Clone, Debug)]
pub struct Turntable {
    pub frames: u32,
    pub names: FrameNames,
    pub orbit: Orbit,
    pub motion: Motion,
    pub lights: LightMode,
    /// Degrees of the 360 degree frame interval the shutter is open (0: no motion blur).
    pub shutter_angle: f32,
    /// Image size, spp, depth, and the base seed (each frame mixes in its index).
    pub settings: RenderSettings,
    /// Stops, applied to PNG frames (EXR stays linear), the same on every frame.
    pub exposure: f32,
    /// The view transform of PNG frames and of the previews.
    pub view: film::ViewTransform,
    /// Render frames whose file already exists again.
    pub overwrite: bool,
    /// Denoise each frame, guided by its albedo and normal images, with these options.
    pub denoise: Option<DenoiseOptions>,
}

/// One rendered frame: the image, the guides when asked for, and the rays it took.
#[derive(Clone, Debug, Default)]
pub struct FrameRender {
    pub image: Image,
    pub features: Option<FeatureImages>,
    pub rays: u64,
}

impl FrameRender {
    /// Adds sub-frame `k` of `n`, weighted by `w` (a single sub-frame is taken as it is).
    fn add(
        &mut self,
        image: Image,
        features: Option<FeatureImages>,
        rays: u64,
        (k, n, w): (usize, usize, f32),
    ) {
        self.rays += rays;
        if n == 1 {
            (self.image, self.features) = (image, features);
            return;
        }
        if k == 0 {
            self.image = image;
            self.image.pixels.iter_mut().for_each(|p| *p *= w);
            self.features = features.map(|mut f| {
                f.albedo.iter_mut().for_each(|a| *a *= w);
                f.normal.iter_mut().for_each(|n| *n *= w);
                f
            });
            return;
        }
        for (a, p) in self.image.pixels.iter_mut().zip(&image.pixels) {
            *a += *p * w;
        }
        if let (Some(sum), Some(f)) = (&mut self.features, &features) {
            for (a, b) in sum.albedo.iter_mut().zip(&f.albedo) {
                *a += *b * w;
            }
            for (a, b) in sum.normal.iter_mut().zip(&f.normal) {
                *a += *b * w;
            }
        }
    }
}

/// What a sequence run did, and what it cost.
#[derive(Clone, Debug, Default)]
pub struct SequenceReport {
    pub rendered: Vec<u32>,
    /// Frames skipped because their file already existed.
    pub skipped: Vec<u32>,
    /// Seconds per rendered frame (render and write).
    pub frame_seconds: Vec<f64>,
    pub rays: u64,
    /// Seconds spent copying the scene once for per-frame lights (0 when the lights never move).
    pub scene_copy_seconds: f64,
}

impl SequenceReport {
    pub fn mean_frame_seconds(&self) -> f64 {
        self.frame_seconds.iter().sum::<f64>() / self.frame_seconds.len().max(1) as f64
    }
}

impl Turntable {
    /// How PNG frames and previews show the linear frames.
    pub fn display(&self) -> film::Display {
        film::Display::new(self.exposure, self.view)
    }

    /// The turntable rotation (radians) at `time`, measured in frames from frame 0.
    fn turn(&self, time: f32) -> f32 {
        TAU * time / self.frames as f32
    }

    /// Whether the lights change from frame to frame (then the integrator needs its own scene copy).
    pub fn lights_move(&self) -> bool {
        self.motion == Motion::Spin || self.lights == LightMode::Camera
    }

    /// The camera and lights at `time` (in frames), given the lights as placed for frame 0.
    ///
    /// `--spin` is rendered without touching the geometry, so the accelerator is never rebuilt: with a
    /// constant environment and punctual lights (emissive surfaces are geometry and turn with the
    /// model anyway), turning the model by `a` under world-fixed lights is exactly, in the model's
    /// frame, the camera orbiting by `-a` with the lights rotated by `-a` about the same axis. The
    /// camera stays fixed in the world, so world- and camera-fixed lights are the same thing there.
    pub fn view_at(&self, base_lights: &[Light], time: f32) -> (Camera, Vec<Light>) {
        let turn = self.turn(time);
        let (camera_turn, light_turn) = match (self.motion, self.lights) {
            (Motion::Orbit, LightMode::World) => (turn, 0.0),
            (Motion::Orbit, LightMode::Camera) => (turn, turn),
            (Motion::Spin, _) => (-turn, -turn),
        };
        let lights = if light_turn == 0.0 {
            base_lights.to_vec()
        } else {
            base_lights
                .iter()
                .map(|l| self.orbit.rotate_light(l, light_turn))
                .collect()
        };
        (self.orbit.camera(camera_turn), lights)
    }

    /// The frame-0 camera (the default light rig is placed relative to it).
    pub fn first_camera(&self) -> Camera {
        self.orbit.camera(0.0)
    }

    /// Sub-frame times (in frames, relative to the frame) and their samples per pixel. Without motion
    /// blur, one sub-frame at the frame's time with every sample. With a shutter angle `s`, the shutter
    /// is open over `s/360` of the frame interval, centred on the frame; it is split into `k` equal
    /// strata rendered at their midpoints with the pixel samples shared out among them, so the
    /// average is a stratified estimate of the box-shutter integral over time.
    pub fn subframes(&self) -> Vec<(f32, u32)> {
        let spp = self.settings.spp.max(1);
        if self.shutter_angle <= 0.0 {
            return vec![(0.0, spp)];
        }
        let k = spp.min(MAX_SUBFRAMES);
        let open = self.shutter_angle / 360.0;
        (0..k)
            .map(|i| {
                let t = ((i as f32 + 0.5) / k as f32 - 0.5) * open;
                (t, spp / k + u32::from(i < spp % k))
            })
            .collect()
    }

    /// Renders one frame into an image. `scene` must be the one `accel` was built over, or a copy of it
    /// differing only in `lights` (those are overwritten when the lights move). With `guides`, also
    /// the albedo and normal images the denoiser needs, averaged over sub-frames as the image is.
    pub fn render_frame(
        &self,
        scene: &mut SceneForFrames,
        accel: &dyn Accel,
        base_lights: &[Light],
        (frame, guides): (u32, bool),
    ) -> FrameRender {
        let seed = frame_seed(self.settings.seed, frame);
        let subframes = self.subframes();
        let mut sum = FrameRender::default();
        for (k, &(dt, spp)) in subframes.iter().enumerate() {
            let (camera, lights) = self.view_at(base_lights, frame as f32 + dt);
            let settings = RenderSettings {
                spp,
                seed: if subframes.len() == 1 {
                    seed
                } else {
                    mix64(seed ^ (k as u64 + 1))
                },
                feature_images: guides,
                ..self.settings.clone()
            };
            let scene = scene.with_lights(lights);
            let out = render::render_full(scene, accel, &camera, &settings, &ProgressBar::hidden());
            // Weighted by each sub-frame's share of the samples: the mean over all samples.
            let w = spp as f32 / self.settings.spp.max(1) as f32;
            sum.add(
                out.image,
                out.features,
                out.stats.rays,
                (k, subframes.len(), w),
            );
        }
        sum
    }

    /// Frames of `frames` that still need rendering (all of them with `overwrite`).
    pub fn pending(&self, frames: &[u32]) -> Vec<u32> {
        frames
            .iter()
            .copied()
            .filter(|&f| self.overwrite || !self.names.path(f).exists())
            .collect()
    }

    /// Renders `frames` (skipping those already on disk unless `overwrite`), writing each through
    /// `film::write` (temporary file + rename: a killed run leaves whole frames or none). `progress`
    /// counts the frames to render; its message says how many were skipped.
    pub fn render_sequence(
        &self,
        scene: &std::sync::Arc<Scene>,
        accel: &dyn Accel,
        frames: &[u32],
        progress: &ProgressBar,
    ) -> Result<SequenceReport> {
        if !self.names.dir().as_os_str().is_empty() {
            fs::create_dir_all(self.names.dir()).map_err(|source| TurntableError::CreateDir {
                path: self.names.dir().to_path_buf(),
                source,
            })?;
        }
        let mut report = SequenceReport::default();
        let todo = self.pending(frames);
        report.skipped = frames
            .iter()
            .copied()
            .filter(|f| !todo.contains(f))
            .collect();
        progress.set_length(todo.len() as u64);
        progress.set_message(format!("{} skipped", report.skipped.len()));
        let base_lights = scene.lights.clone();
        // One device for the whole sequence (creating one loads the library's kernels).
        let d = match self.denoise {
            Some(q) if !todo.is_empty() => Some(Denoiser::new(0, q)?),
            _ => None,
        };
        let t = Instant::now();
        let mut frame_scene = if self.lights_move() && !todo.is_empty() {
            SceneForFrames::Owned(Box::new(Scene::clone(scene)))
        } else {
            SceneForFrames::Shared(scene.clone())
        };
        if matches!(frame_scene, SceneForFrames::Owned(_)) {
            report.scene_copy_seconds = t.elapsed().as_secs_f64();
        }
        for f in todo {
            let path = self.names.path(f);
            // Another run (a resumed one, or an overlapping shard) may have finished it meanwhile.
            if !self.overwrite && path.exists() {
                report.skipped.push(f);
                progress.set_message(format!("{} skipped", report.skipped.len()));
                progress.inc(1);
                continue;
            }
            let t = Instant::now();
            let mut r = self.render_frame(&mut frame_scene, accel, &base_lights, (f, d.is_some()));
            if let Some(d) = &d {
                r.image = d.denoise(&r.image, r.features.as_ref().map(|f| f.guides()))?;
            }
            let rays = r.rays;
            film::write_with(&r.image, &path, &self.display())?;
            report.frame_seconds.push(t.elapsed().as_secs_f64());
            report.rays += rays;
            report.rendered.push(f);
            progress.inc(1);
        }
        report.skipped.sort_unstable();
        progress.finish_and_clear();
        Ok(report)
    }
}

/// The scene the integrator reads for a frame. The accelerator keeps its own `Arc` of the scene (for
/// geometry and alpha tests) and `render` takes the scene separately, so when the lights move we
/// render from one private copy whose `lights` are overwritten per frame: geometry is copied once per
/// run, never per frame, and nothing is rebuilt. When the lights never move, no copy is made.
pub enum SceneForFrames {
    Shared(std::sync::Arc<Scene>),
    // Boxed: a Scene is large, and the enum should not be.
    Owned(Box<Scene>),
}

impl SceneForFrames {
    fn with_lights(&mut self, lights: Vec<Light>) -> &Scene {
        match self {
            SceneForFrames::Shared(s) => {
                debug_assert!(s.lights == lights, "lights move but the scene is shared");
                s
            }
            SceneForFrames::Owned(s) => {
                s.lights = lights;
                s
            }
        }
    }
}

/// Frames of the whole sequence missing on disk.
pub fn missing_frames(names: &FrameNames, frames: u32) -> Vec<u32> {
    (0..frames).filter(|&f| !names.path(f).exists()).collect()
}

/// A frame from disk as display RGB: PNG as written, EXR tonemapped as a PNG frame would be.
pub fn read_display_frame(
    path: &Path,
    format: Format,
    display: &film::Display,
) -> Result<image::RgbImage> {
    match format {
        Format::Png => Ok(image::open(path)
            .map_err(|source| TurntableError::ReadFrame {
                path: path.to_path_buf(),
                source,
            })?
            .to_rgb8()),
        Format::Exr => {
            let img = film::read_exr(path)?;
            let mut out = image::RgbImage::new(img.width as u32, img.height as u32);
            for (o, p) in out.pixels_mut().zip(&img.pixels) {
                *o = image::Rgb(display.encode(p.truncate()));
            }
            Ok(out)
        }
    }
}

/// Removes what killed runs left of `frames` (and of the other files named in `extra`, previews):
/// temporary files whose writer is gone. Returns how many. A resumed run calls it first, so that a
/// sequence killed any number of times ends with its frames and nothing else.
pub fn remove_stale_temps(names: &FrameNames, frames: &[u32], extra: &[&Path]) -> usize {
    let ours: std::collections::HashSet<String> = frames
        .iter()
        .filter_map(|&f| Some(names.path(f).file_name()?.to_string_lossy().into_owned()))
        .collect();
    let mut removed = film::remove_stale_temps(names.dir(), |n| ours.contains(n));
    for p in extra {
        let (Some(dir), Some(name)) = (p.parent(), p.file_name()) else {
            continue;
        };
        removed += film::remove_stale_temps(dir, |n| std::ffi::OsStr::new(n) == name);
    }
    removed
}

/// Writes `out` through a temporary file beside it and a rename, like `film::write`.
fn write_atomically(out: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = out.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    if let Err(e) = write(&tmp) {
        let _ = fs::remove_file(&tmp);
        return Err(TurntableError::WritePreview {
            path: out.to_path_buf(),
            source: Box::new(e),
        });
    }
    fs::rename(&tmp, out).map_err(|source| TurntableError::Rename {
        path: out.to_path_buf(),
        source,
    })
}

fn downscale(img: image::RgbImage, max_width: u32) -> image::RgbImage {
    if img.width() <= max_width {
        return img;
    }
    let h = ((img.height() as u64 * max_width as u64) / img.width() as u64).max(1) as u32;
    image::imageops::resize(&img, max_width, h, image::imageops::FilterType::Triangle)
}

/// An animated, looping GIF of the whole sequence from the frames on disk (at most `max_width` wide),
/// one frame in memory at a time.
pub fn write_gif(
    names: &FrameNames,
    frames: u32,
    display: &film::Display,
    out: &Path,
    fps: f32,
    max_width: u32,
) -> Result<()> {
    use image::codecs::gif::{GifEncoder, Repeat};
    if !(fps > 0.0 && fps <= 100.0) {
        return Err(TurntableError::Fps(fps));
    }
    write_atomically(out, |tmp| {
        let file = std::io::BufWriter::new(fs::File::create(tmp)?);
        // Speed 10 of 1..=30: NeuQuant quality close to the best at a fraction of the time.
        let mut enc = GifEncoder::new_with_speed(file, 10);
        enc.set_repeat(Repeat::Infinite)?;
        let delay = image::Delay::from_numer_denom_ms(1000, fps.round().max(1.0) as u32);
        for f in 0..frames {
            let rgb = downscale(
                read_display_frame(&names.path(f), names.format(), display)?,
                max_width,
            );
            let rgba = image::DynamicImage::ImageRgb8(rgb).to_rgba8();
            enc.encode_frame(image::Frame::from_parts(rgba, 0, 0, delay))?;
        }
        Ok(())
    })
}

/// A PNG grid of the sequence's frames, downscaled to at most `thumb_width` wide, in reading order.
pub fn write_contact_sheet(
    names: &FrameNames,
    frames: u32,
    display: &film::Display,
    out: &Path,
    thumb_width: u32,
) -> Result<()> {
    let cols = (frames as f64).sqrt().ceil().max(1.0) as u32;
    let rows = frames.div_ceil(cols);
    let mut sheet: Option<image::RgbImage> = None;
    for f in 0..frames {
        let thumb = downscale(
            read_display_frame(&names.path(f), names.format(), display)?,
            thumb_width,
        );
        let (tw, th) = thumb.dimensions();
        let sheet = sheet.get_or_insert_with(|| image::RgbImage::new(tw * cols, th * rows));
        let (x, y) = ((f % cols) * tw, (f / cols) * th);
        image::imageops::replace(sheet, &thumb, x as i64, y as i64);
    }
    let sheet = sheet.ok_or(TurntableError::NoFrames)?;
    write_atomically(out, |tmp| {
        sheet.save_with_format(tmp, image::ImageFormat::Png)?;
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::PointLight;

    #[test]
    fn pattern_names_pad_to_the_run_of_hashes() {
        let n = FrameNames::from_output(Path::new("frames/helmet_####.png"), None, 120).unwrap();
        assert_eq!(n.path(7), Path::new("frames/helmet_0007.png"));
        assert_eq!(n.path(12345), Path::new("frames/helmet_12345.png"));
        assert_eq!(n.format(), Format::Png);
        let n = FrameNames::from_output(Path::new("a#.exr"), Some(Format::Exr), 10).unwrap();
        assert_eq!(n.path(3), Path::new("a3.exr"));
        assert!(FrameNames::from_output(Path::new("a##_##.png"), None, 10).is_err());
        assert!(FrameNames::from_output(Path::new("a_##.bmp"), None, 10).is_err());
        assert!(FrameNames::from_output(Path::new("a_##.png"), Some(Format::Exr), 10).is_err());
        // A file name without # is neither a pattern nor a folder.
        assert!(FrameNames::from_output(Path::new("out.png"), None, 10).is_err());
    }

    #[test]
    fn folder_names_use_frame_prefix_and_format() {
        let n = FrameNames::from_output(Path::new("frames/"), Some(Format::Exr), 120).unwrap();
        assert_eq!(n.path(3), Path::new("frames/frame_0003.exr"));
        let n = FrameNames::from_output(Path::new("out"), None, 200_000).unwrap();
        assert_eq!(n.path(3), Path::new("out/frame_000003.png"));
    }

    #[test]
    fn shards_and_ranges_parse_and_validate() {
        assert_eq!("3/8".parse::<Shard>(), Ok(Shard { index: 3, count: 8 }));
        for bad in ["8/8", "1/0", "3", "a/2", "-1/2", "1/2/3"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        assert_eq!(parse_frame_range("2..5"), Ok(2..5));
        for bad in ["5..5", "6..2", "2-5", "..4", "1..x"] {
            assert!(parse_frame_range(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn selections_partition_the_sequence() {
        let s = |i, n| Some(Shard { index: i, count: n });
        assert_eq!(select_frames(7, s(1, 3), None).unwrap(), vec![1, 4]);
        let mut all: Vec<u32> = (0..3)
            .flat_map(|i| select_frames(10, s(i, 3), None).unwrap())
            .collect();
        all.sort_unstable();
        assert_eq!(all, (0..10).collect::<Vec<_>>());
        assert_eq!(select_frames(10, None, Some(8..20)).unwrap(), vec![8, 9]);
        assert_eq!(select_frames(10, s(0, 2), Some(3..8)).unwrap(), vec![4, 6]);
        assert!(select_frames(0, None, None).is_err());
        assert!(select_frames(10, None, Some(10..12)).is_err());
    }

    #[test]
    fn frame_seeds_differ_and_depend_only_on_base_and_frame() {
        assert_eq!(frame_seed(5, 3), frame_seed(5, 3));
        assert_ne!(frame_seed(5, 3), frame_seed(5, 4));
        assert_ne!(frame_seed(5, 3), frame_seed(6, 3));
    }

    #[test]
    fn spin_is_a_reversed_orbit_with_lights_carried_along() {
        let orbit = Orbit {
            center: Vec3::new(1.0, 2.0, 3.0),
            distance: 5.0,
            elevation: 0.3,
            start_azimuth: 0.0,
            yfov: 0.7,
        };
        let tt = Turntable {
            frames: 4,
            names: FrameNames::from_output(Path::new("x/"), None, 4).unwrap(),
            orbit,
            motion: Motion::Spin,
            lights: LightMode::World,
            shutter_angle: 0.0,
            settings: RenderSettings::default(),
            exposure: 0.0,
            view: Default::default(),
            overwrite: false,
            denoise: None,
        };
        let base = vec![Light::Point(PointLight {
            position: Vec3::new(1.0, 5.0, 8.0),
            intensity: Vec3::ONE,
        })];
        let (cam, lights) = tt.view_at(&base, 1.0);
        // A quarter turn of the model: the camera goes a quarter turn the other way, to -X.
        let d = cam.position() - tt.orbit.center;
        assert!(d.x < -4.0 && d.z.abs() < 1e-4, "{d:?}");
        // The light keeps its place relative to the camera.
        let Light::Point(PointLight { position, .. }) = lights[0] else {
            unreachable!()
        };
        let rel0 = tt
            .first_camera()
            .to_world
            .inverse()
            .transform_point3(Vec3::new(1.0, 5.0, 8.0));
        let rel1 = cam.to_world.inverse().transform_point3(position);
        assert!((rel0 - rel1).length() < 1e-4);
    }

    #[test]
    fn subframes_share_out_the_samples() {
        let settings = RenderSettings {
            spp: 19,
            ..Default::default()
        };
        let tt = Turntable {
            frames: 4,
            names: FrameNames::from_output(Path::new("x/"), None, 4).unwrap(),
            orbit: Orbit::framing(&Aabb::EMPTY, 0.7, 1.0, 0.3),
            motion: Motion::Orbit,
            lights: LightMode::World,
            shutter_angle: 180.0,
            settings,
            exposure: 0.0,
            view: Default::default(),
            overwrite: false,
            denoise: None,
        };
        let s = tt.subframes();
        assert_eq!(s.len() as u32, MAX_SUBFRAMES);
        assert_eq!(s.iter().map(|x| x.1).sum::<u32>(), 19);
        assert!(s.iter().all(|x| x.0.abs() < 0.25));
    }
}
