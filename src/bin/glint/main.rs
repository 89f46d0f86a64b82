//! The `glint` binary: the command line (clap) of `render`, `diff`, `bench`, `assemble`,
//! `view`, `info` and `kernels`, and each subcommand's body; what they call is the
//! library `glint` (docs/architecture.md). Beside it: [`bench`], [`kernels`] and [`view`]
//! (the benchmarks, the kernel instrument and the window), the flags several subcommands
//! share ([`script_args`], [`farm_args`]), and what they print ([`progress`], [`stats`]).

mod bench;
mod diff_cmd;
mod farm_args;
mod kernels;
mod kernels_cmd;
mod progress;
mod script_args;
mod stats;
mod view;

use clap::{Args, Parser, Subcommand, ValueEnum};
use glint::display_path::for_terminal;
use glint::scene::flatten::MAX_PIXELS;
use glint::scene::lua::MAX_IMAGE_SIDE;
use glint::scene::options::{
    parse_aperture, parse_background, parse_debug_view, parse_focus, parse_grid_mode, parse_shading,
};
use glint::scene::{
    AaDepth, AaMode, AaSamples, Background, DebugView, GridMode, OptionOverrides, Shading,
    ShadowSamples, TraceDepth, TransformOrder,
};
use std::path::PathBuf;
use std::process::ExitCode;

/// Most worker threads `--threads` accepts (each has its own stack; thousands would
/// only cost memory and start-up time).
const MAX_THREADS: u32 = 256;

#[derive(Parser)]
#[command(
    name = "glint",
    version,
    about = "A Whitted-style ray tracer for CS488 Lua scenes"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene script and render each of its gr.render calls.
    Render(RenderArgs),
    /// Compare two images: RMSE, PSNR, max difference, FLIP mean.
    Diff {
        /// Reference image (PNG, JPEG or EXR).
        a: PathBuf,
        /// Test image.
        b: PathBuf,
        /// Write FLIP's error map (magma colours) here.
        #[arg(long)]
        heatmap: Option<PathBuf>,
    },
    /// Benchmarks: primary rays with and without the grid, grid scaling with N triangles;
    /// --trace SCENE: traversal alone in rays/s (beside Embree: tools/benches/).
    Bench(bench::common::BenchArgs),
    /// Join tiles of one render (`render --tile`/`--crop`) into its image, bit for bit the
    /// full render; refuses tiles of other renders, gaps and overlaps.
    Assemble(farm_args::AssembleArgs),
    /// Open a window showing the scene traced progressively (GPU or CPU tracer), with a
    /// camera to move and live reload of the script and every file it reads
    /// (docs/view.md).
    View(view::ViewArgs),
    /// List the GPU adapters (Vulkan, Metal, DX12, or the backends WGPU_BACKEND names)
    /// and their limits.
    Info,
    /// The GPU kernels' registers, spills, scratch and waves per SIMD, compiled by a real
    /// GPU compiler (RADV's null device with --family, else a hardware Vulkan device).
    Kernels(kernels_cmd::KernelsArgs),
}

#[derive(Clone, Copy, ValueEnum)]
enum OrderArg {
    Pre,
    Post,
}

#[derive(Clone, Copy, ValueEnum, PartialEq)]
enum BackendArg {
    Cpu,
    Gpu,
    Auto,
    Both,
}

#[derive(Args)]
struct RenderArgs {
    /// The scene script (Lua, CS488 `gr` language).
    scene: PathBuf,
    /// Output image (.png, .exr or .jpg); default: the file named in gr.render. Further
    /// gr.render calls of the same script get -2, -3… before the extension.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// How PNG and JPEG outputs encode the linear film: linear (A4's convention, the
    /// default) or srgb (the sRGB transfer curve before 8-bit quantisation, a
    /// display-referred image). EXR stays linear.
    #[arg(long, value_name = "linear|srgb", default_value = "linear",
          value_parser = glint::image_io::OutputTransfer::parse)]
    output_transfer: glint::image_io::OutputTransfer,
    /// Image width (overrides gr.render's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_IMAGE_SIDE as i64))]
    width: Option<u32>,
    /// Image height (overrides gr.render's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_IMAGE_SIDE as i64))]
    height: Option<u32>,
    /// Transform order: pre (M = Op·M, 2015 and later) or post (M = M·Op, up to Summer 2015).
    #[arg(long, value_enum)]
    transform_order: Option<OrderArg>,
    /// Worker threads (default: all cores). The image does not depend on it.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_THREADS as i64))]
    threads: Option<u32>,
    /// Print grid, feature and ray statistics after each render.
    #[arg(long)]
    stats: bool,
    /// The sandbox's limits and readable folders (the same flags as `bench`).
    #[command(flatten)]
    script: script_args::ScriptArgs,
    /// The folder the image names a script gives gr.render are taken from and confined
    /// to (default: the current folder). -o is not confined.
    #[arg(long, value_name = "DIR")]
    output_dir: Option<PathBuf>,
    /// A further folder a script-named image may be written under (repeatable).
    #[arg(long, value_name = "DIR")]
    allow_write: Vec<PathBuf>,
    /// Tracer: cpu (the reference), gpu (wgpu compute: Vulkan, Metal or DX12), auto (a
    /// hardware GPU when one exists, else the CPU; --stats says why), or both
    /// (render on each, write NAME-cpu and NAME-gpu, print the difference and both times;
    /// exit code 6 when they differ beyond --min-within).
    #[arg(long, value_enum, default_value = "auto")]
    backend: BackendArg,
    /// --backend both: write FLIP's heat map of the difference here.
    #[arg(long)]
    heatmap: Option<PathBuf>,
    /// --backend both: smallest share of pixels (0–1) within --tolerance for the images
    /// to agree.
    #[arg(long, default_value_t = 0.999, value_parser = parse_share)]
    min_within: f64,
    /// --backend both: largest per-channel difference of an agreeing pixel, in 1/255.
    #[arg(long, default_value_t = 2.0, value_parser = parse_non_negative)]
    tolerance: f32,
    /// GPU adapter to use: a substring of its name (see `glint info`).
    #[arg(long)]
    adapter: Option<String>,
    /// GPU kernel variant: hardware or software, instead of the one chosen by adapter
    /// (renders on the GPU tracer).
    #[arg(long, value_parser = glint::gpu::KernelVariant::parse)]
    kernel_variant: Option<glint::gpu::KernelVariant>,
    /// Write every GPU pipeline the render creates into DIR as ENTRY.wgsl and ENTRY.spv
    /// (the SPIR-V wgpu hands a Vulkan driver); renders on the GPU tracer.
    #[arg(long, value_name = "DIR")]
    dump_kernels: Option<PathBuf>,
    /// Anti-aliasing: none, uniform or adaptive.
    #[arg(long, value_parser = parse_aa)]
    aa: Option<AaMode>,
    /// n of uniform n×n anti-aliasing.
    #[arg(long, value_parser = AaSamples::parse)]
    samples: Option<AaSamples>,
    /// Adaptive AA: the contrast (among a pixel's corner and centre samples) that splits
    /// the pixel; a square of side 2^-k pixel splits at 2^k times its corners' contrast
    /// (samples that hit different objects, also in a mirror, or saw a penumbra or texture
    /// detail at the pixel's scale, split down to 4×4 squares per pixel whatever it is).
    #[arg(long, value_parser = parse_non_negative)]
    aa_threshold: Option<f32>,
    /// Adaptive AA: deepest split.
    #[arg(long, value_parser = AaDepth::parse)]
    aa_depth: Option<AaDepth>,
    /// Overrides every area light's n (n×n shadow samples).
    #[arg(long, value_parser = ShadowSamples::parse)]
    shadow_samples: Option<ShadowSamples>,
    /// Deepest reflection/refraction chain.
    #[arg(long, value_parser = TraceDepth::parse)]
    max_depth: Option<TraceDepth>,
    /// Drop secondary rays contributing less than this (0–1).
    #[arg(long, value_parser = parse_weight)]
    min_weight: Option<f32>,
    /// Background: r,g,b (solid) or r,g,b/r,g,b (top/bottom gradient).
    #[arg(long, value_parser = parse_background)]
    background: Option<Background>,
    /// Acceleration: auto, off (brute force) or a density λ (cells ≈ λ × items).
    #[arg(long, value_parser = parse_grid_mode)]
    grid: Option<GridMode>,
    /// Debug view (overrides the scene option `debug`; none turns a scene's debug view
    /// off). uv: render colour = (u mod 1, v mod 1, 0) of the first surface hit.
    /// aa-samples: write adaptive AA's leaf squares per pixel instead of the render, on
    /// the magma ramp, log scale (black: 1, not split; pale yellow: 4^aa-depth); needs
    /// adaptive AA.
    #[arg(long, value_parser = parse_debug_view)]
    debug: Option<DebugView>,
    /// Mesh shading (overrides the scene option `shading`): smooth interpolates the
    /// vertex normals of meshes that have them (OBJ `vn`, inline normals); flat shades
    /// every triangle with its own plane's normal.
    #[arg(long, value_parser = parse_shading)]
    shading: Option<Shading>,
    /// Depth of field (overrides the scene option `aperture`): the thin lens's radius in
    /// scene units; 0 is the pinhole camera.
    #[arg(long, allow_negative_numbers = true, value_parser = parse_aperture)]
    aperture: Option<f32>,
    /// Depth of field (overrides the scene option `focus`): the distance from the eye,
    /// along the view direction, of the plane in focus (default: the length of the
    /// script's view vector).
    #[arg(long, allow_negative_numbers = true, value_parser = parse_focus)]
    focus: Option<f32>,
    /// Tiles and frames for render farms (docs/farm.md).
    #[command(flatten)]
    farm: farm_args::FarmArgs,
}

fn parse_aa(s: &str) -> Result<AaMode, String> {
    AaMode::parse(s).ok_or_else(|| format!("aa must be {}, got '{s}'", AaMode::CHOICES))
}

fn parse_non_negative(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!("expected a non-negative number, got '{s}'")),
    }
}

fn parse_weight(s: &str) -> Result<f32, String> {
    match s.parse::<f32>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("expected a weight from 0 to 1, got '{s}'")),
    }
}

fn parse_share(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("expected a share between 0 and 1, got '{s}'")),
    }
}

fn main() -> ExitCode {
    // Mesa's device-select layer complains on stderr when XDG_RUNTIME_DIR is unset; glint
    // picks adapters itself, so the layer is not needed. Set before any thread starts.
    if std::env::var_os("NODEVICE_SELECT").is_none() {
        // SAFETY: single-threaded here, before wgpu, rayon or anything else runs.
        unsafe { std::env::set_var("NODEVICE_SELECT", "1") };
    }
    // More llvmpipe worker threads than cores, for lavapipe's load balance (a no-op on
    // other adapters; the user's own LP_NUM_THREADS wins).
    // SAFETY: as above, single-threaded and before any GPU instance.
    unsafe { glint::gpu::device::context::set_default_llvmpipe_threads() };
    glint::image_io::remove_temp_files_on_signals();
    let cli = Cli::parse();
    if let Command::Kernels(args) = &cli.command {
        // SAFETY: still single-threaded (signal handlers only), and no Vulkan loader yet.
        if let Err(message) = unsafe { kernels_cmd::set_driver_env(args) } {
            eprintln!("glint: error: {}", for_terminal(&message));
            return ExitCode::from(5);
        }
    }
    if matches!(
        cli.command,
        Command::Render(_) | Command::Bench(_) | Command::View(_)
    ) {
        // A bad cache setting is the command line's mistake (exit code 2), found before
        // anything runs rather than when the first GPU pipeline is compiled.
        if let Err(e) = glint::gpu::device::disk_cache::check_switch() {
            eprintln!("glint: error: {}", for_terminal(&e.to_string()));
            return ExitCode::from(2);
        }
    }
    let result = match cli.command {
        Command::Render(args) => render(args),
        Command::Diff { a, b, heatmap } => diff_cmd::run_diff(&a, &b, heatmap.as_deref())
            .map(|_| ())
            .map_err(|e| (e.to_string(), e.exit_code())),
        Command::Bench(args) => bench::cmd::run_bench(&args).map_err(|e| (format!("{e:#}"), 1)),
        Command::Assemble(args) => {
            glint::farm::assemble::assemble(&args.tiles, &args.output, args.memory_budget())
                .map(|()| eprintln!("glint: wrote {}", glint::display_path::shown(&args.output)))
                .map_err(|e| (e.to_string(), e.exit_code()))
        }
        Command::View(args) => view::run(&args),
        Command::Info => {
            info();
            Ok(())
        }
        Command::Kernels(args) => kernels_cmd::run_kernels(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err((message, code)) => {
            // A script can make its message any size: at most a few KiB reach the terminal.
            eprintln!(
                "glint: error: {}",
                for_terminal(&glint::scene::lua::cap_message(&message))
            );
            ExitCode::from(code)
        }
    }
}

fn render(args: RenderArgs) -> Result<(), (String, u8)> {
    check_render_args(&args)?;
    let transform_order = args.transform_order.map(|o| match o {
        OrderArg::Pre => TransformOrder::Pre,
        OrderArg::Post => TransformOrder::Post,
    });
    let script = args.script.settings(transform_order).map_err(|e| (e, 2))?;
    let settings = glint::pipeline::RenderSettings {
        script,
        overrides: OptionOverrides {
            aa: args.aa,
            samples: args.samples,
            aa_threshold: args.aa_threshold,
            aa_depth: args.aa_depth,
            shadow_samples: args.shadow_samples,
            max_depth: args.max_depth,
            min_weight: args.min_weight,
            background: args.background,
            grid: args.grid,
            debug: args.debug,
            shading: args.shading,
            aperture: args.aperture,
            focus: args.focus,
            width: args.width.filter(|&w| w > 0),
            height: args.height.filter(|&h| h > 0),
        },
        output: args.output.clone(),
        output_transfer: args.output_transfer,
        stats: args.stats,
        progress: Some(std::sync::Arc::new(progress::ProgressBars::default())),
        output_dir: args.output_dir.clone(),
        allow_write: args.allow_write.clone(),
        backend: match args.backend {
            BackendArg::Cpu => glint::pipeline::Backend::Cpu,
            BackendArg::Gpu => glint::pipeline::Backend::Gpu,
            // The kernel flags are about the GPU tracer: no quiet fallback to the CPU.
            BackendArg::Auto if kernel_flag(&args).is_some() => glint::pipeline::Backend::Gpu,
            BackendArg::Auto | BackendArg::Both => glint::pipeline::Backend::Auto,
        },
        adapter: args.adapter.clone(),
        kernel_variant: args.kernel_variant,
        dump_kernels: args.dump_kernels.clone(),
    };
    if args.heatmap.is_some() && args.backend != BackendArg::Both {
        return Err(("--heatmap needs --backend both".into(), 2));
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0) as usize)
        .build()
        .map_err(|e| (format!("cannot start {:?} threads: {e}", args.threads), 1))?;
    if args.farm.settings().any() {
        return pool.install(|| render_farm(&args, &settings));
    }
    if args.backend == BackendArg::Both {
        let parity = glint::parity::ParitySettings {
            tolerance: args.tolerance / 255.0,
            min_share: args.min_within,
            heatmap: args.heatmap,
        };
        return pool.install(|| render_both(&args.scene, &settings, &parity));
    }
    let report = pool.install(|| {
        glint::pipeline::run_scene(&args.scene, &settings, &mut |image| {
            report_image(image, &settings)
        })
    });
    match report {
        Ok(report) => {
            if let Some(evidence) = &report.looks_pre2015 {
                if !report.order_set_by_script && settings.script.transform_order.is_none() {
                    eprintln!(
                        "glint: hint: this scene looks like a pre-2015 CS488 scene ({evidence}); if it looks wrong, try --transform-order post (gr.transform_order('pre') in the scene silences this hint)"
                    );
                }
            }
            no_render_outcome(&args, report.renders)
        }
        Err(e) => Err((e.to_string(), e.exit_code() as u8)),
    }
}

/// `render` with tiles or frames ([`glint::farm::run`]).
fn render_farm(
    args: &RenderArgs,
    settings: &glint::pipeline::RenderSettings,
) -> Result<(), (String, u8)> {
    let refuse = |flag: &str| {
        Err((
            format!(
                "{flag} does not combine with --tile, --crop, --frames, --frame or --skip-existing"
            ),
            2,
        ))
    };
    if args.backend == BackendArg::Both {
        return refuse("--backend both");
    }
    if args.stats {
        return refuse("--stats");
    }
    if args.debug == Some(DebugView::AaSamples) {
        return refuse("--debug aa-samples");
    }
    if args.output_transfer != glint::image_io::OutputTransfer::Linear {
        return refuse("--output-transfer srgb");
    }
    let farm = args.farm.settings();
    let run = glint::farm::run::run_farm(&args.scene, settings, &farm, &mut |image| {
        let b = image.bounds;
        let (w, h) = image.full_size;
        let part = if b == glint::tiling::PixelRect::full(w, h) {
            format!("{w}×{h}")
        } else {
            format!("pixels {b} of {w}×{h}")
        };
        if image.skipped {
            eprintln!(
                "glint: kept {} ({part}: written already with this digest)",
                glint::display_path::shown(&image.output)
            );
        } else {
            eprintln!(
                "glint: wrote {} ({part}, {:.2} s on the {})",
                glint::display_path::shown(&image.output),
                image.render_time.as_secs_f64(),
                image.tracer
            );
        }
    })
    .map_err(|e| (e.to_string(), e.exit_code()))?;
    if !run.reads_frame && args.farm.frames.is_some() {
        eprintln!(
            "glint: note: {} never reads `frame` or `clock`: every frame of --frames is the same image",
            glint::display_path::shown(&args.scene)
        );
    }
    no_render_outcome(args, run.renders)
}

/// After a script ran: with no `gr.render` nothing was written, a note; and an error
/// (exit code 3) when `-o` asked for an image.
fn no_render_outcome(args: &RenderArgs, renders: usize) -> Result<(), (String, u8)> {
    if renders > 0 {
        return Ok(());
    }
    match &args.output {
        Some(out) => Err((
            format!(
                "{} never called gr.render, so -o {} was not written (gr.render(root, file, width, height, …) renders; docs/scene-language.md)",
                glint::display_path::shown(&args.scene),
                glint::display_path::shown(out)
            ),
            3,
        )),
        None => {
            eprintln!(
                "glint: note: {} never called gr.render; nothing written",
                glint::display_path::shown(&args.scene)
            );
            Ok(())
        }
    }
}

/// The first GPU kernel flag given (`--kernel-variant`, `--dump-kernels`), if any.
fn kernel_flag(args: &RenderArgs) -> Option<&'static str> {
    if args.kernel_variant.is_some() {
        Some("--kernel-variant")
    } else if args.dump_kernels.is_some() {
        Some("--dump-kernels")
    } else {
        None
    }
}

/// Checks of `render`'s flags that clap's value parsers cannot make alone (exit code 2).
fn check_render_args(args: &RenderArgs) -> Result<(), (String, u8)> {
    if let Some(flag) = kernel_flag(args) {
        let refused = match args.backend {
            BackendArg::Cpu => Some("--backend cpu"),
            BackendArg::Both => Some("--backend both"),
            _ if args.farm.settings().any() => Some("--tile, --crop, --frames or --frame"),
            _ => None,
        };
        if let Some(other) = refused {
            return Err((
                format!(
                    "{flag} is about the GPU tracer's kernels; it does not combine with {other}"
                ),
                2,
            ));
        }
    }
    if let (Some(w), Some(h)) = (args.width, args.height) {
        if u64::from(w) * u64::from(h) > MAX_PIXELS {
            return Err((
                format!(
                    "--width {w} --height {h} is {} pixels, over glint's limit of {MAX_PIXELS}",
                    u64::from(w) * u64::from(h)
                ),
                2,
            ));
        }
    }
    if let Some(out) = &args.output {
        if !glint::image_io::is_supported_output(out) {
            return Err((
                format!(
                    "-o {}: glint writes images by their extension: {}",
                    glint::display_path::shown(out),
                    glint::image_io::SUPPORTED_EXTENSIONS
                ),
                2,
            ));
        }
    }
    let folders = (args.allow_write.iter().map(|d| ("--allow-write", d)))
        .chain(args.output_dir.iter().map(|d| ("--output-dir", d)));
    for (flag, dir) in folders {
        if !dir.is_dir() {
            return Err((
                format!("{flag} {}: not a folder", glint::display_path::shown(dir)),
                2,
            ));
        }
    }
    Ok(())
}

/// The line `glint render` prints for each image written (and `--stats`).
fn report_image(
    image: &glint::pipeline::RenderedImage,
    settings: &glint::pipeline::RenderSettings,
) {
    if image.view == DebugView::AaSamples {
        eprintln!(
            "glint: wrote {} (adaptive AA leaf squares per pixel, {}×{}, decided on the {} in {:.2} s)",
            glint::display_path::shown(&image.output),
            image.film.width,
            image.film.height,
            if image.adapter.is_some() { "GPU" } else { "CPU" },
            image.render_time.as_secs_f64()
        );
        return;
    }
    eprintln!(
        "glint: wrote {} ({}×{}, {:.2} s on the {})",
        glint::display_path::shown(&image.output),
        image.film.width,
        image.film.height,
        image.render_time.as_secs_f64(),
        if image.gpu.is_some() { "GPU" } else { "CPU" }
    );
    if settings.stats {
        eprint!("{}", stats::format_stats(image));
    }
}

/// `--backend both`: each render on both tracers, the figures on stdout; exit code 6 when
/// any pair differs beyond the tolerance.
fn render_both(
    scene: &std::path::Path,
    settings: &glint::pipeline::RenderSettings,
    parity: &glint::parity::ParitySettings,
) -> Result<(), (String, u8)> {
    let result = glint::parity::run_scene_both(scene, settings, parity, &mut |r| {
        println!(
            "{} vs {}: CPU {:.3} s, GPU {:.3} s (GPU/CPU {:.2})",
            glint::display_path::shown(&r.cpu_output),
            glint::display_path::shown(&r.gpu_output),
            r.cpu_time.as_secs_f64(),
            r.gpu_time.as_secs_f64(),
            r.gpu_time.as_secs_f64() / r.cpu_time.as_secs_f64()
        );
        println!("{}", r.report);
        if let Some(h) = &r.heatmap {
            println!("heat map: {}", glint::display_path::shown(h));
        }
        println!(
            "{}: {:.3}% of pixels within {:.1}/255 (needed: {:.3}%)",
            if r.agrees { "agree" } else { "DIFFER" },
            100.0 * r.share_within,
            parity.tolerance * 255.0,
            100.0 * parity.min_share
        );
    });
    match result {
        Ok((_, true)) => Ok(()),
        Ok((_, false)) => Err((
            "the CPU and GPU images differ beyond the tolerance".into(),
            6,
        )),
        Err(e) => Err((e.to_string(), e.exit_code() as u8)),
    }
}

/// `glint info`: every adapter with its backend, type and key limits.
fn info() {
    let adapters = glint::gpu::list_adapters();
    if adapters.is_empty() {
        println!(
            "no GPU adapters (backends: WGPU_BACKEND, or Vulkan, Metal and DX12); glint renders with --backend cpu"
        );
        return;
    }
    for (i, a) in adapters.iter().enumerate() {
        println!("adapter {i}: {}", a.name);
        println!(
            "  backend: {}, device type: {}, driver: {}",
            a.backend, a.device_type, a.driver
        );
        println!(
            "  max storage buffer binding: {} MiB, max buffer: {} MiB, storage buffers per stage: {}",
            a.max_storage_buffer_binding_size >> 20,
            a.max_buffer_size >> 20,
            a.max_storage_buffers_per_shader_stage
        );
        println!(
            "  max 2-D texture side: {} (the scene's tables: up to {} M texels each)",
            a.max_texture_dimension_2d,
            (glint::gpu::upload::tables::TABLE_ROW * a.max_texture_dimension_2d as u64) >> 20
        );
        println!(
            "  max invocations per workgroup: {}, max workgroups per dimension: {}",
            a.max_compute_invocations_per_workgroup, a.max_compute_workgroups_per_dimension
        );
        println!("  glint's kernel on it: {}", a.kernel);
        if a.device_type == "Cpu" {
            println!("  {}", glint::gpu::device::context::llvmpipe_threads_line());
        }
    }
}
