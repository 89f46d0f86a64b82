//! What the `glint bench` subcommands share: the arguments (`BenchArgs`) and loading a
//! scene script into a flat scene, and packing it with a chosen grid mode.

use crate::script_args::ScriptArgs;
use glint::pack::PackedScene;
use glint::pipeline::pack_scene;
use glint::scene::flatten::FlatScene;
use glint::scene::GridMode;
use glint::script_driver::{run_script, ScriptSettings};
use std::path::PathBuf;

#[derive(clap::Args, Clone, Debug)]
pub struct BenchArgs {
    /// The CS488 corpus (macho-cows.lua is taken from its a4-2021plus folder).
    #[arg(long, default_value = "scenes/cs488")]
    pub cs488: PathBuf,
    /// Largest N of the random-triangle sweep (powers of ten from 10³; at most 10⁸).
    #[arg(long, default_value_t = 1_000_000, value_parser = triangle_count)]
    pub max_triangles: usize,
    /// Rays per random-triangle measurement (1 to 10⁸).
    #[arg(long, default_value_t = 200_000, value_parser = ray_count)]
    pub rays: usize,
    /// Timed repetitions of each measurement (the fastest is reported).
    #[arg(long, default_value_t = 3)]
    pub repeat: usize,
    /// Also sweep the grid density λ.
    #[arg(long)]
    pub densities: bool,
    /// Only the GPU-vs-CPU comparison (needs a GPU adapter; lavapipe counts).
    #[arg(long)]
    pub gpu: bool,
    /// Only the ray–torus solver comparison (glint's against Ferrari's closed form).
    #[arg(long)]
    pub torus: bool,
    /// GPU adapter to use: a substring of its name.
    #[arg(long)]
    pub adapter: Option<String>,
    /// --gpu: side of the 2-D kernels' square workgroup (1, 2, 4 or 8; the 1-D kernels run
    /// its square), instead of the one chosen from the adapter. To measure a GPU.
    #[arg(long, value_parser = ["1", "2", "4", "8"])]
    pub workgroup_side: Option<String>,
    /// --gpu: keep the traversal's per-ray mailboxes (on), only one item slot (last) or
    /// none (off), instead of the adapter's choice (last: the full caches cost a hardware
    /// kernel up to 48 VGPRs). To measure a GPU.
    #[arg(long, value_parser = ["on", "last", "off"])]
    pub mailboxes: Option<String>,
    /// --gpu: also time each pass of the frame with the scene's own AA (timestamp queries
    /// around every dispatch), summed per kernel and quadtree level.
    #[arg(long)]
    pub passes: bool,
    /// Only the error-against-time sweep of the AA and shadow settings (`bench_sweep`).
    #[arg(long)]
    pub sweep: bool,
    /// --sweep: a tiny run (24×24, a few settings) that checks the machinery.
    #[arg(long, requires = "sweep")]
    pub quick: bool,
    /// --sweep: sweep this scene (repeatable) instead of glint's own four (demo,
    /// soft-shadows, macho-cows, scrabble), at --size pixels wide and the scene's own
    /// aspect ratio.
    #[arg(long = "scene", requires = "sweep", value_name = "SCENE.lua")]
    pub sweep_scenes: Vec<PathBuf>,
    /// --sweep: image width in pixels (the built-in scenes square, but scrabble's at 16:9).
    #[arg(long, default_value_t = 96, value_parser = clap::value_parser!(u32).range(8..=2048))]
    pub size: u32,
    /// --sweep: no GPU column.
    #[arg(long)]
    pub cpu_only: bool,
    /// --sweep: seconds the GPU column may take in all (compile runs included; more than
    /// 0, at most a week).
    #[arg(long, default_value_t = 120.0, value_parser = budget_seconds)]
    pub gpu_budget: f64,
    /// --sweep: where the error-against-time plot (SVG) goes.
    #[arg(long, default_value = "error-vs-time.svg")]
    pub plot: PathBuf,
    /// Only the trace benchmark of this scene: camera rays (one per pixel) and one shadow
    /// ray per hit and light through the CPU tracer's traversal, no shading (`bench_trace`).
    #[arg(long, value_name = "SCENE.lua")]
    pub trace: Option<PathBuf>,
    /// --trace: image width (default: the scene's).
    #[arg(long, requires = "trace", value_parser = clap::value_parser!(u32).range(1..))]
    pub width: Option<u32>,
    /// --trace: image height (default: the scene's).
    #[arg(long, requires = "trace", value_parser = clap::value_parser!(u32).range(1..))]
    pub height: Option<u32>,
    /// --trace: also write the geometry and the exact rays, with glint's answers, for the
    /// Embree harness (`tools/benches/embree/`; format in `bench::trace_dump`).
    #[arg(long, requires = "trace", value_name = "FILE")]
    pub dump_rays: Option<PathBuf>,
    /// The sandbox's limits and readable folders, as `glint render`'s (tools/benches/scenes/
    /// read the CS488 corpus's meshes through `--allow-read`; a 10⁶-triangle OBJ needs a
    /// larger `--memory-limit`).
    #[command(flatten)]
    pub script: ScriptArgs,
    /// Worker threads (default: all cores).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub threads: Option<u32>,
}

/// Most triangles the random-triangle sweep may build (about 10 GB with its grid): a
/// larger `--max-triangles` is a usage error, not an allocation that aborts.
pub const MAX_SWEEP_TRIANGLES: usize = 100_000_000;
/// Most rays a random-triangle measurement may cast (3.2 GB of rays and hits).
pub const MAX_BENCH_RAYS: usize = 100_000_000;
/// Longest `--gpu-budget`, in seconds (a week).
pub const MAX_GPU_BUDGET_SECONDS: f64 = 604_800.0;

/// `--max-triangles`: a whole number from 1 to [`MAX_SWEEP_TRIANGLES`].
fn triangle_count(text: &str) -> Result<usize, String> {
    whole_number_in(text, 1, MAX_SWEEP_TRIANGLES)
}

/// `--rays`: a whole number from 1 (no rays would time nothing, and print inf/NaN
/// rates) to [`MAX_BENCH_RAYS`].
fn ray_count(text: &str) -> Result<usize, String> {
    whole_number_in(text, 1, MAX_BENCH_RAYS)
}

fn whole_number_in(text: &str, low: usize, high: usize) -> Result<usize, String> {
    match text.parse::<u128>() {
        Ok(n) if (low as u128..=high as u128).contains(&n) => Ok(n as usize),
        _ => Err(format!("expected a whole number from {low} to {high}")),
    }
}

/// `--gpu-budget`: seconds, finite and positive, at most [`MAX_GPU_BUDGET_SECONDS`]
/// (NaN, infinity or a negative time would reach `Duration::from_secs_f64`, which panics).
fn budget_seconds(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(s) if s > 0.0 && s <= MAX_GPU_BUDGET_SECONDS => Ok(s),
        _ => Err(format!(
            "expected seconds, more than 0 and at most {MAX_GPU_BUDGET_SECONDS}"
        )),
    }
}

impl BenchArgs {
    /// How the benchmarks run their scripts: the flags, through the one script driver.
    pub fn script_settings(&self) -> anyhow::Result<ScriptSettings> {
        self.script.settings(None).map_err(anyhow::Error::msg)
    }
}

/// The scene's first `gr.render` at `width`×`height`, run with the default settings.
pub fn load_scene(path: &std::path::Path, width: u32, height: u32) -> anyhow::Result<FlatScene> {
    load_scene_with(path, width, height, &ScriptSettings::default())
}

/// [`load_scene`], the script run under `settings` (as `glint render` runs it).
pub fn load_scene_with(
    path: &std::path::Path,
    width: u32,
    height: u32,
    settings: &ScriptSettings,
) -> anyhow::Result<FlatScene> {
    glint::bench::trace_rays::load_first_render(path, Some(width), Some(height), settings)
}

/// Height over width of the image a scene's (first) `gr.render` asks for.
pub fn scene_aspect(path: &std::path::Path, settings: &ScriptSettings) -> anyhow::Result<f64> {
    let mut aspect = None;
    run_script(path, settings, &mut |_, request| {
        aspect.get_or_insert(f64::from(request.height) / f64::from(request.width));
        Ok(())
    })?;
    aspect.ok_or_else(|| {
        anyhow::anyhow!("{} never calls gr.render", glint::display_path::shown(path))
    })
}

pub fn with_grid(scene: &FlatScene, grid: GridMode) -> anyhow::Result<PackedScene> {
    let mut scene = scene.clone();
    scene.options.grid = grid;
    Ok(pack_scene(&scene)?)
}
