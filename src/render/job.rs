//! A render job: one place turns a scene and typed options into what a render needs (the scene posed
//! and lit, the camera, the settings, the accelerator and the focused lens); every command uses it.

mod settings;
mod view;

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use indicatif::ProgressBar;

pub use settings::{
    check_size, file_overrides, resolve, Basics, Overrides, MAX_EDGE, MAX_PIXELS, MAX_SPP,
};
pub use view::{CameraChoice, CameraRef, Environment, LensOptions, View};

use super::{render_full, RenderOutput, RenderSettings};
use crate::accel::{self, Accel, AccelError, Backend};
use crate::scene::features::Features;
use crate::scene::{
    animation, defaults, Camera, Light, LoadError, LoadOptions, Scene, SceneChoice, UpAxis,
};

#[derive(Debug, thiserror::Error)]
pub enum JobError {
    #[error(transparent)]
    Load(#[from] LoadError),
    #[error(transparent)]
    Accel(#[from] AccelError),
    #[error("{}: [render] backend: {message}", path.display())]
    FileBackend { path: PathBuf, message: String },
    #[error("image size {0}x{1} is out of range (1..={MAX_EDGE} per edge)")]
    EdgeOutOfRange(usize, usize),
    #[error("image size {0}x{1} is out of range (at most {MAX_PIXELS} pixels)")]
    PixelsOutOfRange(usize, usize),
    #[error("--spp {0} is out of range (1..={MAX_SPP})")]
    SppOutOfRange(u32),
    #[error("--fov must be between 0 and 180 degrees")]
    Fov,
    #[error("{}: no camera '{camera}' (the file has {}: {names:?})", path.display(), names.len())]
    NoCamera {
        path: PathBuf,
        camera: String,
        names: Vec<String>,
    },
    #[error("{}: --model-up turns model files; this scene has CSG objects, so place its parts with the scene file's transforms", .0.display())]
    TurnCsg(PathBuf),
    #[error("--eye and --look-at are the same point")]
    EyeIsTarget,
    #[error("--env-strength must be a finite number >= 0, not {0}")]
    EnvStrength(f32),
    #[error("--env-rotation must be finite")]
    EnvRotation,
    #[error("--aperture must be a non-negative radius")]
    Aperture,
    #[error("--fstop must be positive")]
    Fstop,
    #[error("--focus-distance and --focus-on need --aperture or --fstop")]
    FocusWithoutLens,
    #[error("--focus-distance must be positive")]
    FocusDistance,
    #[error("--focus-on {x},{y} is outside the {w}x{h} image")]
    FocusOutside { x: u32, y: u32, w: usize, h: usize },
    #[error("--focus-on {x},{y}: the pixel sees no surface to focus on")]
    FocusOnNothing { x: u32, y: u32 },
}

/// Whether the default light rig (a soft environment and a key light) goes into the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum DefaultLights {
    /// Add the rig when the file has no light of its own.
    #[default]
    Auto,
    On,
    Off,
}

impl DefaultLights {
    /// Whether the rig goes into this scene.
    pub fn wanted(self, scene: &Scene) -> bool {
        match self {
            DefaultLights::On => true,
            DefaultLights::Off => false,
            DefaultLights::Auto => !defaults::has_own_lights(scene),
        }
    }
}

/// The moment the frame shows: which animation, how far into it, and the shutter around it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Time {
    /// Which of the file's animations plays (read when the job loads the file).
    pub animation: usize,
    /// Seconds into the animation.
    pub frame_time: f32,
    /// Shutter OPEN, CLOSE in seconds relative to `frame_time` (equal: no motion blur).
    pub shutter: [f32; 2],
}

/// Everything a render is set up from, besides the scene.
#[derive(Clone, Debug, Default)]
pub struct JobOptions {
    /// The command's own defaults for what neither the flags nor the scene file give.
    pub defaults: Basics,
    /// What the command line gives (it beats the scene file's `[render]` settings).
    pub flags: Overrides,
    /// The rest of the settings (filter radius, adaptive sampling, time budget); its basics and
    /// shutter are replaced by those resolved here.
    pub sampling: RenderSettings,
    pub view: View,
    pub environment: Option<Environment>,
    pub default_lights: DefaultLights,
    pub lens: LensOptions,
    pub time: Time,
    /// KHR_materials_variants: the material variant to dress the meshes in (an error when the scene
    /// has no variant of that name).
    pub variant: Option<String>,
    /// The axis the file calls up; the scene is turned so that it becomes +Y.
    pub up_axis: UpAxis,
    /// Which of a glTF file's scenes to load (read when the job loads the file).
    pub scene: SceneChoice,
}

impl JobOptions {
    /// The light of the environment map, when there is one (loaded before the scene, so that a bad
    /// map fails fast).
    fn environment_light(&self) -> Result<Option<Light>, JobError> {
        self.environment
            .as_ref()
            .map(Environment::light)
            .transpose()
    }
}

/// A scene posed and lit, its camera and settings decided: all but the accelerator.
#[derive(Clone, Debug)]
pub struct Setup {
    pub scene: Scene,
    pub camera: Camera,
    pub settings: RenderSettings,
    pub backend: Backend,
    /// The lens to focus once the accelerator is built.
    pub lens: LensOptions,
    /// Seconds spent loading the file (and environment map) and posing it.
    pub load_seconds: f64,
}

impl Setup {
    /// Loads `path` (with the environment map first, and animation `opts.time.animation`), handing
    /// each of the loader's warnings to `warn`, and sets it up.
    pub fn load(
        path: &Path,
        opts: &JobOptions,
        warn: &mut dyn FnMut(&str),
    ) -> Result<Setup, JobError> {
        let t = Instant::now();
        let environment = opts.environment_light()?;
        let scene = Scene::load_with(
            path,
            &LoadOptions {
                scene: opts.scene.clone(),
                animation: opts.time.animation,
            },
        )?;
        scene.warnings.iter().for_each(|w| warn(w));
        Self::assemble(scene, environment, opts, t)
    }

    /// Sets up a scene in hand. One already posed (its animation taken) stays as it is.
    pub fn new(scene: Scene, opts: &JobOptions) -> Result<Setup, JobError> {
        let t = Instant::now();
        let environment = opts.environment_light()?;
        Self::assemble(scene, environment, opts, t)
    }

    fn assemble(
        mut scene: Scene,
        environment: Option<Light>,
        opts: &JobOptions,
        start: Instant,
    ) -> Result<Setup, JobError> {
        let time = opts.time;
        if let Some(v) = &opts.variant {
            scene.select_variant(v)?;
        }
        animation::pose(&mut scene, time.frame_time, time.shutter);
        if opts.up_axis != UpAxis::Y && !scene.csg.is_empty() {
            return Err(JobError::TurnCsg(scene.source.clone()));
        }
        scene.turn_up(opts.up_axis);
        let load_seconds = start.elapsed().as_secs_f64();
        let file = file_overrides(&scene.settings, &scene.source, &opts.flags)?;
        let basics = resolve(opts.defaults, &file, &opts.flags);
        basics.validate()?;
        let camera = opts.view.camera(&scene, basics.aspect())?;
        light(&mut scene, &camera, environment, opts.default_lights);
        scene.shading = basics.shading();
        Ok(Setup {
            scene,
            camera,
            settings: settings(&basics, &opts.sampling, &time),
            backend: basics.backend,
            lens: opts.lens,
            load_seconds,
        })
    }

    /// Builds the accelerator and focuses the lens.
    pub fn build(self) -> Result<RenderJob, JobError> {
        let scene = Arc::new(self.scene);
        let t = Instant::now();
        let accel = accel::build(scene.clone(), self.backend)?;
        let build_seconds = t.elapsed().as_secs_f64();
        let mut camera = self.camera;
        let size = (self.settings.width, self.settings.height);
        camera.lens = self.lens.lens(&scene, accel.as_ref(), &camera, size)?;
        Ok(RenderJob {
            scene,
            accel,
            camera,
            settings: self.settings,
            load_seconds: self.load_seconds,
            build_seconds,
        })
    }
}

/// Adds the default rig placed from `camera` (when wanted) and puts `environment` in place of the
/// file's or the rig's environment.
fn light(scene: &mut Scene, camera: &Camera, environment: Option<Light>, rig: DefaultLights) {
    let rig = rig.wanted(scene);
    match environment {
        Some(env) => {
            scene
                .lights
                .retain(|l| !matches!(l, Light::Environment { .. }));
            if rig {
                let lights = defaults::light_rig_with_environment(&camera.to_world, env);
                scene.lights.extend(lights);
            } else {
                scene.lights.push(env);
            }
        }
        None if rig => scene.lights.extend(defaults::light_rig(&camera.to_world)),
        None => {}
    }
}

fn settings(b: &Basics, rest: &RenderSettings, t: &Time) -> RenderSettings {
    RenderSettings {
        width: b.width,
        height: b.height,
        spp: b.spp,
        max_depth: b.max_depth,
        seed: b.seed,
        sampler: b.sampler,
        filter: b.filter,
        shutter: t.shutter,
        frame_time: t.frame_time,
        ..rest.clone()
    }
}

/// A render ready to run: the scene, its accelerator, the camera and the settings.
pub struct RenderJob {
    pub scene: Arc<Scene>,
    pub accel: Box<dyn Accel>,
    pub camera: Camera,
    pub settings: RenderSettings,
    pub load_seconds: f64,
    pub build_seconds: f64,
}

impl RenderJob {
    /// Sets up `scene` with `opts` and builds it.
    pub fn prepare(scene: Scene, opts: &JobOptions) -> Result<RenderJob, JobError> {
        Setup::new(scene, opts)?.build()
    }

    /// What the scene and camera use (and so what the render skips).
    pub fn features(&self) -> Features {
        Features::of(&self.scene, &self.camera)
    }

    pub fn render(&self, progress: &ProgressBar) -> RenderOutput {
        self.render_with(&self.settings, progress)
    }

    /// Renders with other settings (sample counts, samplers, seeds) over the same scene and camera.
    pub fn render_with(&self, settings: &RenderSettings, progress: &ProgressBar) -> RenderOutput {
        render_full(
            &self.scene,
            self.accel.as_ref(),
            &self.camera,
            settings,
            progress,
        )
    }
}
