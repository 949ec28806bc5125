//! The command line: clap definitions and the `info` subcommand; `render`, `turntable` and `bench`
//! live beside it. Nothing else in glint knows about flags; errors travel up as `anyhow` chains to `main`.

pub mod args;
pub mod bench;
pub mod merge;
pub mod render;
pub mod turntable;

use std::io::IsTerminal;
use std::path::PathBuf;

use anyhow::Result;
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

use crate::scene::{animation, LoadOptions, Scene};

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
    Render(render::RenderArgs),
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
    /// Add the sample shards of a still (`render --sample-shard I/N`) into the whole render's image.
    Merge(merge::MergeArgs),
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

/// Parses the process's arguments and runs them.
pub fn main() -> Result<()> {
    run(Cli::parse())
}

pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Render(args) => render::run(args),
        Command::Info { input } => info_command(&input),
        Command::Bench(cmd) => bench::run(cmd),
        Command::Turntable(args) => turntable::run(args),
        Command::Merge(args) => merge::run(args),
    }
}

/// Loads a model posed at the start of its first animation (skins and morphs included), printing the
/// loader's warnings.
fn load(path: &std::path::Path, opts: &LoadOptions) -> Result<Scene> {
    let mut scene = Scene::load_with(path, opts)?;
    for w in &scene.warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    animation::pose(&mut scene, 0.0, [0.0, 0.0]);
    Ok(scene)
}

fn info_command(input: &std::path::Path) -> Result<()> {
    let scene = load(input, &LoadOptions::default())?;
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
    text += &extensions_text(s);
    if s.scenes.len() > 1 {
        text += &format!(
            "  scenes      {} (--scene N|NAME): {}\n",
            s.scenes.len(),
            s.scenes.join(", ")
        );
    }
    if !scene.variants.is_empty() {
        text += &format!(
            "  variants    {} (--variant NAME)\n",
            scene.variants.names.join(", ")
        );
    }
    print_out(&text)
}

/// The file's used and required extensions, each marked with whether glint reads it.
fn extensions_text(s: &crate::scene::SceneStats) -> String {
    let mark = |e: &String| {
        let how = if crate::scene::gltf::supports(e) {
            "supported"
        } else {
            "not supported"
        };
        format!("{e} ({how})")
    };
    let mut text = String::new();
    for (label, list) in [
        ("extensions used    ", &s.extensions_used),
        ("extensions required", &s.extensions_required),
    ] {
        if !list.is_empty() {
            let items: Vec<String> = list.iter().map(mark).collect();
            text += &format!("  {label} {}\n", items.join(", "));
        }
    }
    text
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
