//! The command line: clap definitions and the `render` and `info` subcommands.
//! Nothing else in glint knows about flags; errors travel up as `anyhow` chains to `main`.

pub mod bench;
pub mod turntable;

use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand, ValueEnum};
use glam::Vec3;
use indicatif::{ProgressBar, ProgressStyle};

use crate::accel::{self, Backend};
use crate::film;
use crate::render::{self, RenderSettings};
use crate::scene::{animation, defaults, Camera, EnvMap, Light, Projection, Scene};

/// Largest accepted image edge, in pixels.
const MAX_EDGE: usize = 32_768;
/// Largest accepted pixel count (the film holds 16 bytes a pixel: 2 GiB at this size).
const MAX_PIXELS: usize = 1 << 27;

#[derive(Parser, Debug)]
#[command(
    name = "glint",
    version,
    about = "Render glTF 2.0 and OBJ models with Embree 4 or a Rust BVH"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a model to PNG (tonemapped sRGB) or EXR (linear float RGBA).
    Render(RenderArgs),
    /// Print what a model file holds: nodes, meshes, triangles, materials, lights, cameras, animations.
    Info {
        /// A .gltf, .glb or .obj file.
        input: PathBuf,
    },
    /// Benchmarks: ray throughput per backend (`rays`).
    #[command(subcommand)]
    Bench(bench::BenchCommand),
    /// Render a turntable sequence (camera orbit or --spin): resumable, shardable, with previews.
    Turntable(turntable::TurntableArgs),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DefaultLights {
    /// Add the rig when the file has no light of its own.
    Auto,
    On,
    Off,
}

/// Image size, sampling and backend: the flags every rendering command shares.
#[derive(clap::Args, Debug)]
pub struct ImageArgs {
    #[arg(long, default_value_t = 800)]
    pub width: usize,
    #[arg(long, default_value_t = 600)]
    pub height: usize,
    /// Samples per pixel.
    #[arg(long, default_value_t = 16)]
    pub spp: u32,
    /// Bounces after the camera ray (1 = direct light only).
    #[arg(long, default_value_t = 5)]
    pub max_depth: u32,
    /// Ray-tracing backend: embree, bvh, grid (or obvhs, when built with that feature).
    #[arg(long, default_value_t = Backend::default_available())]
    pub backend: Backend,
}

impl ImageArgs {
    /// Refuses sizes and sample counts that cannot be rendered (or would not fit in memory).
    pub fn validate(&self) -> Result<()> {
        let (w, h) = (self.width, self.height);
        if w == 0 || h == 0 || w > MAX_EDGE || h > MAX_EDGE {
            bail!("image size {w}x{h} is out of range (1..={MAX_EDGE} per edge)");
        }
        if w * h > MAX_PIXELS {
            bail!("image size {w}x{h} is out of range (at most {MAX_PIXELS} pixels)");
        }
        if self.spp == 0 || self.spp > 1 << 20 {
            bail!("--spp {} is out of range (1..={})", self.spp, 1 << 20);
        }
        Ok(())
    }
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

/// A progress bar on stderr with `template`, hidden when `quiet` or when stderr is not a terminal.
pub(crate) fn progress_bar(quiet: bool, template: &str) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template(template)
            .expect("valid template")
            .progress_chars("=> "),
    );
    bar
}

#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// A .gltf, .glb or .obj file.
    pub input: PathBuf,
    /// Output image: .png or .exr.
    #[arg(short, long)]
    pub output: PathBuf,
    #[command(flatten)]
    pub image: ImageArgs,
    /// Camera of the file to use, by index or name (default: the first; framed when the file has none).
    #[arg(long)]
    pub camera: Option<String>,
    /// Camera position (x,y,z); overrides the file's camera.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub eye: Option<Vec3>,
    /// Point the camera looks at (x,y,z); defaults to the centre of the model.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub look_at: Option<Vec3>,
    /// Up direction (x,y,z) for --eye/--look-at.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub up: Option<Vec3>,
    /// Vertical field of view in degrees.
    #[arg(long)]
    pub fov: Option<f32>,
    /// Exposure in stops, applied when writing PNG.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub exposure: f32,
    /// The default light rig (environment + key light).
    #[arg(long, value_enum, default_value_t = DefaultLights::Auto)]
    pub default_lights: DefaultLights,
    /// Light the model with an environment map: a lat-long (equirectangular) .exr or .hdr image of
    /// linear radiance, +Y up, its centre column facing +X (the glTF Sample Viewer's orientation). It
    /// replaces the default rig's constant environment, or the file's environment.
    #[arg(long, value_name = "FILE.exr|.hdr")]
    pub env: Option<PathBuf>,
    /// Multiplier on the --env map's radiance.
    #[arg(long, default_value_t = 1.0, requires = "env")]
    pub env_strength: f32,
    /// Turn the --env map about +Y by this many degrees (counter-clockwise seen from above).
    #[arg(
        long,
        default_value_t = 0.0,
        allow_hyphen_values = true,
        requires = "env"
    )]
    pub env_rotation: f32,
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// No progress bar or summary line.
    #[arg(short, long)]
    pub quiet: bool,
    /// Print the features the scene uses and the ones glint skips for it.
    #[arg(short, long)]
    pub verbose: bool,
    /// Sample generator: random, stratified or sobol (Owen-scrambled).
    #[arg(long, value_enum, default_value_t = crate::sample::SamplerKind::default())]
    pub sampler: crate::sample::SamplerKind,
    /// Pixel reconstruction filter: box, tent, gaussian or mitchell.
    #[arg(long, value_enum, default_value_t = crate::film::filter::FilterKind::default())]
    pub filter: crate::film::filter::FilterKind,
    /// Filter radius in pixels (default: box 0.5, tent 1, gaussian 1.5, mitchell 2).
    #[arg(long)]
    pub filter_radius: Option<f32>,
    /// Adaptive sampling: rounds until the image's estimated relative RMS error is under
    /// --target-error, samples going where they cut the error most per ray; converged pixels stop.
    #[arg(long)]
    pub adaptive: bool,
    /// Adaptive method: variance (error from half buffers, in rounds) or corners (Whitted-style
    /// subdivision where corner samples differ); implies --adaptive.
    #[arg(long, value_enum)]
    pub adaptive_mode: Option<render::AdaptiveMode>,
    /// Adaptive threshold: the image's relative RMS error (variance) or corner contrast (corners).
    #[arg(long, default_value_t = 0.01)]
    pub target_error: f32,
    /// Fewest samples an adaptive pixel takes.
    #[arg(long, default_value_t = 16)]
    pub min_spp: u32,
    /// Most samples an adaptive pixel takes.
    #[arg(long, default_value_t = 1024)]
    pub max_spp: u32,
    /// Render progressively until this time is spent (e.g. 30s, 2m, 500ms); --spp is then ignored.
    #[arg(long = "time", value_parser = parse_duration)]
    pub time_budget: Option<std::time::Duration>,
    /// Also write the samples each pixel took (.exr: counts; .png: counts / the most).
    #[arg(long)]
    pub spp_map: Option<PathBuf>,
    /// Extra images beside the output, comma separated: `spp` writes OUTPUT's name with `.spp`
    /// before the extension (what --spp-map FILE writes elsewhere).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub aov: Vec<Aov>,
    #[command(flatten)]
    pub lens: LensArgs,
    #[command(flatten)]
    pub time: TimeArgs,
    /// Flags given on the command line (they win over a scene file's [render] settings).
    #[arg(skip)]
    pub explicit: Vec<String>,
}

impl RenderArgs {
    /// Takes a scene file's render settings for every flag the command line left at its default.
    fn apply_file_settings(&mut self, s: &crate::scene::desc::FileSettings) -> Result<()> {
        let free = |id: &str| !self.explicit.iter().any(|e| e == id);
        let (w, h, spp, depth, seed) = (
            free("width"),
            free("height"),
            free("spp"),
            free("max_depth"),
            free("seed"),
        );
        let (sampler, filter, backend) = (free("sampler"), free("filter"), free("backend"));
        let img = &mut self.image;
        if let Some(v) = s.width.filter(|_| w) {
            img.width = v;
        }
        if let Some(v) = s.height.filter(|_| h) {
            img.height = v;
        }
        if let Some(v) = s.spp.filter(|_| spp) {
            img.spp = v;
        }
        if let Some(v) = s.max_depth.filter(|_| depth) {
            img.max_depth = v;
        }
        if let Some(v) = s.seed.filter(|_| seed) {
            self.seed = v;
        }
        if let Some(v) = s.sampler.filter(|_| sampler) {
            self.sampler = v;
        }
        if let Some(v) = s.filter.filter(|_| filter) {
            self.filter = v;
        }
        if let Some(v) = s.backend.as_ref().filter(|_| backend) {
            img.backend = v.parse().map_err(|e: String| {
                anyhow::anyhow!("{}: [render] backend: {e}", self.input.display())
            })?;
        }
        Ok(())
    }
}

/// Parses the process's arguments, remembering which flags were given explicitly, and runs them.
pub fn main() -> Result<()> {
    use clap::{CommandFactory, FromArgMatches};
    let matches = Cli::command().get_matches();
    let mut cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    if let (Command::Render(args), Some((_, sub))) = (&mut cli.command, matches.subcommand()) {
        args.explicit = sub
            .ids()
            .filter(|id| {
                sub.value_source(id.as_str()) == Some(clap::parser::ValueSource::CommandLine)
            })
            .map(|id| id.to_string())
            .collect();
    }
    run(cli)
}

/// Depth of field: a thin lens, by aperture radius or f-number, focused at a distance or on a pixel.
#[derive(clap::Args, Debug, Default)]
pub struct LensArgs {
    /// Lens aperture radius in scene units (a thin lens; 0 or absent = pinhole).
    #[arg(long, conflicts_with = "fstop")]
    pub aperture: Option<f32>,
    /// Lens f-number; the focal length comes from the vertical field of view on a 24 mm (full-frame)
    /// sensor with scene units in metres: f = 12 mm / tan(fov / 2), aperture radius f / (2 N).
    #[arg(long)]
    pub fstop: Option<f32>,
    /// Distance of the plane in focus, along the view axis (default: the model's centre).
    #[arg(long, conflicts_with = "focus_on")]
    pub focus_distance: Option<f32>,
    /// Focus on what pixel X,Y sees (its depth along the view axis).
    #[arg(long, value_parser = parse_pixel)]
    pub focus_on: Option<[u32; 2]>,
}

/// Motion blur and animation time.
#[derive(clap::Args, Debug, Default)]
pub struct TimeArgs {
    /// Shutter interval OPEN,CLOSE in seconds relative to --frame-time (e.g. 0,0.033); equal values
    /// mean no motion blur.
    #[arg(long, value_parser = parse_shutter, allow_hyphen_values = true)]
    pub shutter: Option<[f32; 2]>,
    /// Seconds into the file's animation at which the frame is taken.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub frame_time: f32,
    /// Which of the file's animations plays, by index (default: the first).
    #[arg(long, default_value_t = 0)]
    pub animation: usize,
}

fn parse_pixel(s: &str) -> Result<[u32; 2], String> {
    match s
        .split(',')
        .map(|c| c.trim().parse::<u32>())
        .collect::<Vec<_>>()[..]
    {
        [Ok(x), Ok(y)] => Ok([x, y]),
        _ => Err(format!(
            "'{s}': expected a pixel X,Y (two non-negative integers)"
        )),
    }
}

fn parse_shutter(s: &str) -> Result<[f32; 2], String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|c| c.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("'{s}': {e} (expected OPEN,CLOSE in seconds)"))?;
    match v[..] {
        [a, b] if a.is_finite() && b.is_finite() && a <= b => Ok([a, b]),
        _ => Err(format!(
            "'{s}': expected OPEN,CLOSE in seconds with OPEN <= CLOSE"
        )),
    }
}

impl LensArgs {
    /// The thin lens these flags ask for on `camera` (None for a pinhole); without a lens flag, the
    /// camera's own (a scene file's). `--focus-on` traces a ray through the pixel; the default focus
    /// is the model's centre.
    pub fn lens(
        &self,
        scene: &Scene,
        accel: &dyn accel::Accel,
        camera: &Camera,
        size: (usize, usize),
    ) -> Result<Option<crate::scene::Lens>> {
        let yfov = match camera.projection {
            Projection::Perspective { yfov, .. } => yfov,
            Projection::Orthographic { .. } => defaults::DEFAULT_FOV_DEG.to_radians(),
        };
        let radius = match (self.aperture, self.fstop) {
            (Some(a), _) if !(a >= 0.0 && a.is_finite()) => {
                bail!("--aperture must be a non-negative radius")
            }
            (Some(a), _) => a,
            (None, Some(n)) if !(n > 0.0 && n.is_finite()) => bail!("--fstop must be positive"),
            (None, Some(n)) => crate::scene::Lens::from_fstop(n, yfov, 1.0).radius,
            (None, None) => {
                if self.focus_distance.is_some() || self.focus_on.is_some() {
                    bail!("--focus-distance and --focus-on need --aperture or --fstop");
                }
                return Ok(camera.lens);
            }
        };
        if radius == 0.0 {
            return Ok(None);
        }
        let axis = camera.to_world.transform_vector3(-Vec3::Z).normalize();
        let focus_distance = match (self.focus_distance, self.focus_on) {
            (Some(d), _) if !(d > 0.0 && d.is_finite()) => {
                bail!("--focus-distance must be positive")
            }
            (Some(d), _) => d,
            (None, Some([x, y])) => {
                let (w, h) = size;
                if x as usize >= w || y as usize >= h {
                    bail!("--focus-on {x},{y} is outside the {w}x{h} image");
                }
                let cam = render::RayCamera::new(camera, w, h);
                let ray = cam.ray(glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
                let hit = accel.intersect(&ray).with_context(|| {
                    format!("--focus-on {x},{y}: the pixel sees no surface to focus on")
                })?;
                hit.t * ray.d.dot(axis)
            }
            (None, None) => {
                let (center, _) = defaults::bounding_sphere(&scene.bounds());
                (center - camera.position()).dot(axis).max(1e-3)
            }
        };
        Ok(Some(crate::scene::Lens {
            radius,
            focus_distance,
        }))
    }
}

/// A duration such as `30s`, `1.5m`, `500ms` or `20` (seconds).
pub fn parse_duration(s: &str) -> Result<std::time::Duration, String> {
    let t = s.trim();
    let (num, scale) = if let Some(n) = t.strip_suffix("ms") {
        (n, 1e-3)
    } else if let Some(n) = t.strip_suffix('s') {
        (n, 1.0)
    } else if let Some(n) = t.strip_suffix('m') {
        (n, 60.0)
    } else if let Some(n) = t.strip_suffix('h') {
        (n, 3600.0)
    } else {
        (t, 1.0)
    };
    match num.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(std::time::Duration::from_secs_f64(v * scale)),
        _ => Err(format!(
            "'{s}': expected a positive duration such as 30s, 2m or 500ms"
        )),
    }
}

fn parse_vec3(s: &str) -> Result<Vec3, String> {
    let v: Vec<f32> = s
        .split(',')
        .map(|c| c.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("'{s}': {e} (expected x,y,z)"))?;
    match v[..] {
        [x, y, z] if x.is_finite() && y.is_finite() && z.is_finite() => Ok(Vec3::new(x, y, z)),
        _ => Err(format!("'{s}': expected three finite numbers x,y,z")),
    }
}

pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Render(args) => render_command(args),
        Command::Info { input } => info_command(&input),
        Command::Bench(cmd) => bench::run(cmd),
        Command::Turntable(args) => turntable::run(args),
    }
}

/// Loads a model posed at the start of its first animation (skins and morphs included).
fn load(path: &std::path::Path) -> Result<Scene> {
    let mut scene = load_animated(path, 0)?;
    animation::pose(&mut scene, 0.0, [0.0, 0.0]);
    Ok(scene)
}

/// Loads a model with animation `animation` of the file chosen (when it has any).
fn load_animated(path: &std::path::Path, animation: usize) -> Result<Scene> {
    let scene = Scene::load_with_animation(path, animation)?;
    for w in &scene.warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(scene)
}

fn info_command(input: &std::path::Path) -> Result<()> {
    let scene = load(input)?;
    let s = &scene.stats;
    let mut text = format!(
        "{}\n  nodes       {}\n  meshes      {} ({} primitives)\n  triangles   {}\n  materials   {}\n  \
         textures    {}\n  lights      {}\n  cameras     {}\n  animations  {}\n  instances   {}\n",
        input.display(),
        s.nodes,
        s.meshes,
        s.primitives,
        s.triangles,
        s.materials,
        s.textures,
        s.lights,
        s.cameras,
        s.animations,
        scene.instances.len()
    );
    let b = scene.bounds();
    if !b.is_empty() {
        text += &format!(
            "  bounds      {:?} .. {:?}\n",
            b.min.to_array(),
            b.max.to_array()
        );
    }
    print_out(&text)
}

/// Writes to stdout; a reader that went away (`glint info x | head`) is not an error.
pub(crate) fn print_out(text: &str) -> Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|_| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(e.into()),
        _ => Ok(()),
    }
}

/// The camera to render through: the file's (by `--camera`), or one framing the model, then adjusted
/// by `--eye`, `--look-at`, `--up` and `--fov`.
fn choose_camera(scene: &Scene, args: &RenderArgs) -> Result<Camera> {
    let aspect = args.image.width as f32 / args.image.height as f32;
    let fov = args.fov.map(|f| f.to_radians());
    if let Some(f) = fov {
        if !(f > 0.0 && f < std::f32::consts::PI) {
            bail!("--fov must be between 0 and 180 degrees");
        }
    }
    let file_camera = match &args.camera {
        Some(sel) => {
            let found = match sel.parse::<usize>() {
                Ok(i) => scene.cameras.get(i),
                Err(_) => scene.cameras.iter().find(|c| &c.name == sel),
            };
            let names: Vec<_> = scene.cameras.iter().map(|c| c.name.as_str()).collect();
            Some(found.cloned().with_context(|| {
                format!(
                    "{}: no camera '{sel}' (the file has {}: {names:?})",
                    scene.source.display(),
                    scene.cameras.len()
                )
            })?)
        }
        None => scene.cameras.first().cloned(),
    };
    let yfov = fov.unwrap_or(defaults::DEFAULT_FOV_DEG.to_radians());
    let mut camera = match file_camera {
        Some(c) if args.eye.is_none() && args.look_at.is_none() => c,
        _ => {
            let bounds = scene.bounds();
            let (center, _) = defaults::bounding_sphere(&bounds);
            let target = args.look_at.unwrap_or(center);
            match args.eye {
                Some(eye) => {
                    if (eye - target).length() == 0.0 {
                        bail!("--eye and --look-at are the same point");
                    }
                    let mut up = args.up.unwrap_or(Vec3::Y);
                    if (target - eye).normalize().cross(up.normalize()).length() < 1e-4 {
                        up = Vec3::Z;
                    }
                    Camera::look_at(eye, target, up, yfov)
                }
                None => {
                    let mut c = defaults::frame_bounds(
                        &bounds,
                        defaults::default_view_direction(),
                        yfov,
                        aspect,
                    );
                    if args.look_at.is_some() {
                        let eye = c.position() - center + target;
                        c = Camera::look_at(eye, target, args.up.unwrap_or(Vec3::Y), yfov);
                    }
                    c
                }
            }
        }
    };
    if let (Some(f), Projection::Perspective { yfov, .. }) = (fov, &mut camera.projection) {
        *yfov = f;
    }
    Ok(camera)
}

/// The environment light of `--env`, `--env-strength` and `--env-rotation`.
fn env_light(path: &std::path::Path, args: &RenderArgs) -> Result<Light> {
    if !(args.env_strength.is_finite() && args.env_strength >= 0.0) {
        bail!(
            "--env-strength must be a finite number >= 0, not {}",
            args.env_strength
        );
    }
    if !args.env_rotation.is_finite() {
        bail!("--env-rotation must be finite");
    }
    let map = EnvMap::load(path)?.rotated_y(args.env_rotation.to_radians());
    Ok(Light::Environment {
        radiance: Vec3::splat(args.env_strength),
        map: Some(Arc::new(map)),
    })
}

/// Per-pixel images a render can write beside its output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Aov {
    /// Samples each pixel took.
    Spp,
}

/// `out.exr` -> `out.spp.exr`: an AOV's file beside the output, in the output's format.
fn aov_path(output: &std::path::Path, aov: &str) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    let ext = output.extension().unwrap_or_default().to_string_lossy();
    output.with_file_name(format!("{stem}.{aov}.{ext}"))
}

fn render_command(mut args: RenderArgs) -> Result<()> {
    // Fail on a bad output name before spending time on the render.
    film::Format::from_path(&args.output)?;
    if args.aov.contains(&Aov::Spp) && args.spp_map.is_none() {
        args.spp_map = Some(aov_path(&args.output, "spp"));
    }
    if let Some(map) = &args.spp_map {
        film::Format::from_path(map)?;
    }
    if let Some(parent) = args.output.parent().filter(|p| !p.as_os_str().is_empty()) {
        if !parent.is_dir() {
            bail!("{}: output folder does not exist", parent.display());
        }
    }
    if let Some(n) = args.threads {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n.max(1))
            .build_global()
            .context("setting up the thread pool")?;
    }

    let t0 = Instant::now();
    let environment = args
        .env
        .as_deref()
        .map(|path| env_light(path, &args))
        .transpose()?;
    let mut scene = load_animated(&args.input, args.time.animation)?;
    let shutter = args.time.shutter.unwrap_or([0.0, 0.0]);
    animation::pose(&mut scene, args.time.frame_time, shutter);
    let load_s = t0.elapsed().as_secs_f64();
    args.apply_file_settings(&scene.settings)?;
    args.image.validate()?;
    let mut camera = choose_camera(&scene, &args)?;
    let rig = args.default_lights.wanted(&scene);
    if let Some(env) = environment {
        scene
            .lights
            .retain(|l| !matches!(l, Light::Environment { .. }));
        if rig {
            scene
                .lights
                .extend(defaults::light_rig_with_environment(&camera.to_world, env));
        } else {
            scene.lights.push(env);
        }
    } else if rig {
        scene.lights.extend(defaults::light_rig(&camera.to_world));
    }
    let scene = Arc::new(scene);

    let t1 = Instant::now();
    let accel = accel::build(scene.clone(), args.image.backend)?;
    let build_s = t1.elapsed().as_secs_f64();
    camera.lens = args.lens.lens(
        &scene,
        accel.as_ref(),
        &camera,
        (args.image.width, args.image.height),
    )?;

    let progress = progress_bar(
        args.quiet,
        "{spinner} rendering [{bar:40}] {percent}% tiles, eta {eta}",
    );
    let settings = RenderSettings {
        width: args.image.width,
        height: args.image.height,
        spp: args.image.spp,
        max_depth: args.image.max_depth,
        seed: args.seed,
        sampler: args.sampler,
        filter: args.filter,
        filter_radius: args.filter_radius,
        adaptive: match (args.adaptive, args.adaptive_mode) {
            (_, Some(m)) => m,
            (true, None) => render::AdaptiveMode::Variance,
            (false, None) => render::AdaptiveMode::Off,
        },
        target_error: args.target_error,
        min_spp: args.min_spp,
        max_spp: args.max_spp,
        time_budget: args.time_budget,
        shutter,
        frame_time: args.time.frame_time,
    };
    if args.verbose {
        let features = crate::scene::features::Features::of(&scene, &camera);
        eprintln!("{}: {}", args.input.display(), features.describe());
    }
    let out = render::render_full(&scene, accel.as_ref(), &camera, &settings, &progress);
    let (image, stats) = (&out.image, out.stats);
    film::write(image, &args.output, args.exposure)?;
    if let Some(path) = &args.spp_map {
        let scale = match film::Format::from_path(path)? {
            film::Format::Exr => 1.0,
            film::Format::Png => 1.0 / stats.max_spp.max(1) as f32,
        };
        let values: Vec<f32> = out.spp.iter().map(|&n| n as f32 * scale).collect();
        film::write(
            &film::Image::from_scalars(args.image.width, args.image.height, &values),
            path,
            0.0,
        )?;
    }
    let spp_text = if stats.min_spp == stats.max_spp {
        format!("{}", stats.max_spp)
    } else {
        format!(
            "{:.1} (min {}, max {}, {} rounds)",
            out.mean_spp(),
            stats.min_spp,
            stats.max_spp,
            stats.rounds
        )
    };
    if !args.quiet {
        eprintln!(
            "{}: {}x{} at {} spp with {} in {:.2} s: {} rays, {:.2} Mrays/s (load {:.2} s, build {:.3} s)",
            args.output.display(),
            args.image.width,
            args.image.height,
            spp_text,
            accel.name(),
            stats.seconds,
            stats.rays,
            stats.mrays_per_second(),
            load_s,
            build_s
        );
    }
    Ok(())
}
