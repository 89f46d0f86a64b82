//! From a scene script to image files: run the script; at each `gr.render`, flatten, pack,
//! render and write the image atomically, telling a [`ProgressSink`] how each render
//! advances. Shared by the command line, the benchmark, the tests and embedding programs.

use crate::aa_map::{aa_samples_film, AaMapError};
use crate::film::Film;
use crate::gpu::{render_gpu, GpuContext, GpuRender, GpuRenderInfo, GpuRenderOptions};
use crate::image_io::{check_output_path, write_image_with, ImageIoError, OutputTransfer};
use crate::pack::{pack, PackError, PackedScene, SceneFeatures};
use crate::scene::flatten::flatten;
use crate::scene::flatten::FlatScene;
use crate::scene::lua::{SceneError, ScriptReport};
use crate::scene::{AaMode, DebugView, OptionOverrides, RenderRequest, SceneGraph};
use crate::script_driver::{run_script, ScriptSettings};
use crate::tracer::path::camera_media::{fill_camera_media, opaque_solid_around_eye};
use crate::tracer::sampling::render::{
    adaptive_leaf_counts, render, render_with_counters, RenderCounters,
};
use crate::write_policy::WritePolicy;
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Hears how each render advances: the command line draws it as a progress bar; a library
/// caller may show it its own way, or leave [`RenderSettings::progress`] empty.
pub trait ProgressSink: std::fmt::Debug + Send + Sync {
    /// A render of the image `output` begins; its `advance` calls follow.
    fn begin(&self, output: &Path);
    /// `done` of `total` units of the current render are finished (from any thread).
    fn advance(&self, done: u64, total: u64);
    /// The current render's film is made (before it is written).
    fn end(&self);
}

/// How to run a scene: everything the CLI can say.
#[derive(Clone, Debug, Default)]
pub struct RenderSettings {
    /// How the script runs: transform order and the sandbox's limits (one driver for
    /// every mode: [`crate::script_driver`]).
    pub script: ScriptSettings,
    /// Render-option flags (beat the script).
    pub overrides: OptionOverrides,
    /// `-o`: output of the first render; later renders of the same script get `-2`, `-3`…
    pub output: Option<PathBuf>,
    /// `--output-transfer`: how PNG and JPEG outputs encode the linear film.
    pub output_transfer: OutputTransfer,
    /// Print statistics (grid, features, rays) after each render.
    pub stats: bool,
    /// Hears each render's progress (the command line draws a bar; None: nothing hears).
    pub progress: Option<Arc<dyn ProgressSink>>,
    /// `--output-dir`: the folder the script's own output names are taken from and
    /// confined to (None: the current folder; `-o` is not confined).
    pub output_dir: Option<PathBuf>,
    /// `--allow-write`: further folders a script-named output may lie under.
    pub allow_write: Vec<PathBuf>,
    /// Which tracer renders.
    pub backend: Backend,
    /// `--adapter`: a substring of the GPU adapter's name.
    pub adapter: Option<String>,
    /// `--kernel-variant`: the GPU kernel variant, instead of the adapter's choice.
    pub kernel_variant: Option<crate::gpu::KernelVariant>,
    /// `--dump-kernels`: the folder each compiled GPU pipeline is written to.
    pub dump_kernels: Option<PathBuf>,
}

/// `--backend`: which tracer renders.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Backend {
    /// The CPU reference tracer.
    #[default]
    Cpu,
    /// The GPU tracer; no adapter is an error.
    Gpu,
    /// The GPU when a hardware adapter exists (or the one `--adapter` names), else the CPU
    /// with a one-line notice.
    Auto,
}

/// The tracer one render uses (a GPU context made once per script).
#[derive(Clone, Copy)]
pub enum Tracer<'a> {
    Cpu,
    Gpu(&'a GpuContext),
}

/// Resolves `backend` to a tracer, making the GPU context when needed; `auto` falls back
/// to the CPU, saying why on stderr when `explain` (`--stats`: every render's line says
/// which tracer drew it, so the reason is not repeated on every run).
pub fn acquire_gpu(
    backend: Backend,
    adapter: Option<&str>,
    explain: bool,
) -> Result<Option<GpuContext>, crate::gpu::GpuError> {
    match backend {
        Backend::Cpu => Ok(None),
        Backend::Gpu => Ok(Some(GpuContext::new(adapter)?)),
        Backend::Auto => match GpuContext::new(adapter) {
            // A software rasterizer (lavapipe) is slower than the CPU tracer on the same
            // cores: auto takes it only when it was asked for by name.
            Ok(ctx) if ctx.info.device_type == wgpu::DeviceType::Cpu && adapter.is_none() => {
                if explain {
                    eprintln!(
                        "glint: note: rendering on the CPU tracer; the only GPU adapter, {}, is a software one (slower here; --backend gpu uses it)",
                        ctx.info.name
                    );
                }
                Ok(None)
            }
            Ok(ctx) => Ok(Some(ctx)),
            Err(e) => {
                if explain {
                    eprintln!(
                        "glint: note: rendering on the CPU ({})",
                        crate::display_path::for_terminal(&e.to_string())
                    );
                }
                Ok(None)
            }
        },
    }
}

/// One finished render.
#[derive(Clone, Debug)]
pub struct RenderedImage {
    pub output: PathBuf,
    pub film: Film,
    pub packed: PackedScene,
    /// Flattening and packing (the grids included), before the render.
    pub build_time: Duration,
    pub render_time: Duration,
    pub counters: Option<RenderCounters>,
    /// Set when the GPU rendered it: features compiled in, pipeline compile time.
    pub gpu: Option<GpuRenderInfo>,
    /// The GPU adapter's name, when the GPU rendered it.
    pub adapter: Option<String>,
    /// What the film shows: the render, or a debug view of it.
    pub view: DebugView,
}

/// Why running a scene failed; each kind has its own exit code.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The script, or the scene it built, is wrong (exit code 3).
    #[error("{0}")]
    Scene(#[from] SceneError),
    /// The image could not be written (exit code 4).
    #[error("{0}")]
    Output(#[from] ImageIoError),
    /// The image of the `gr.render` call at `location` could not be written (exit code 4).
    #[error("{location}: gr.render: {error}")]
    OutputAt {
        location: String,
        error: ImageIoError,
    },
    /// No usable GPU, or the GPU render failed (exit code 5).
    #[error("{0}")]
    Gpu(#[from] crate::gpu::GpuError),
    /// The flags ask for something this render cannot give (exit code 2, as clap's).
    #[error("{0}")]
    Usage(#[from] AaMapError),
    /// A flag names something unusable (a folder that does not exist; exit code 2).
    #[error("{0}")]
    Flag(String),
}

impl RunError {
    pub fn exit_code(&self) -> i32 {
        match self {
            RunError::Scene(_) => 3,
            RunError::Output(_) | RunError::OutputAt { .. } => 4,
            RunError::Gpu(crate::gpu::GpuError::Setting { .. }) => 2,
            RunError::Gpu(_) => 5,
            RunError::Usage(_) | RunError::Flag(_) => 2,
        }
    }
}

/// `scene` packed for rendering: [`pack`], then, in scenes with refraction, the media
/// around the eye that primary rays start in (found by tracing the packed scene, so it
/// comes after packing).
pub fn pack_scene(scene: &FlatScene) -> Result<PackedScene, PackError> {
    let mut packed = pack(scene)?;
    if packed.features.contains(SceneFeatures::REFRACTION) {
        fill_camera_media(&mut packed);
    }
    Ok(packed)
}

/// The request with `overrides` applied, flattened and packed.
pub fn prepare_request(
    graph: &SceneGraph,
    request: &RenderRequest,
    overrides: &OptionOverrides,
) -> anyhow::Result<(RenderRequest, PackedScene)> {
    let mut request = request.clone();
    overrides.apply(&mut request.options);
    request.width = overrides.width.unwrap_or(request.width);
    request.height = overrides.height.unwrap_or(request.height);
    let scene = flatten(graph, &request)?;
    let packed = pack_scene(&scene)?;
    note_eye_inside_solid(&request, &scene, &packed);
    Ok((request, packed))
}

/// A note when the eye is inside an opaque solid ([`opaque_solid_around_eye`]), naming it:
/// the render shows its inside, usually not what was meant.
fn note_eye_inside_solid(request: &RenderRequest, scene: &FlatScene, packed: &PackedScene) {
    let Some(item) = opaque_solid_around_eye(packed) else {
        return;
    };
    let item = item as usize;
    let name = match scene.objects.get(item) {
        Some(object) => object.name.as_str(),
        None => match scene.csg.get(item - scene.objects.len()) {
            Some(csg) => csg.name.as_str(),
            None => return,
        },
    };
    // The node's own name, the last part of its path from the root.
    let name = crate::scene::short_name(name.rsplit('/').next().unwrap_or(name));
    let e = request.camera.eye;
    eprintln!(
        "glint: note: {}: gr.render: the eye {{{}, {}, {}}} is inside '{name}', an opaque solid: the camera sees only its inside (move the eye, argument 5, out of it)",
        request.location, e.x, e.y, e.z
    );
}

/// `--debug aa-samples`: adaptive anti-aliasing's leaf squares per pixel, mapped to
/// colours ([`crate::aa_map`]), decided by `tracer` (both decide alike). The film of the
/// returned image is the map; a render without adaptive AA is an [`AaMapError`].
pub fn render_aa_samples_map(
    graph: &SceneGraph,
    request: &RenderRequest,
    overrides: &OptionOverrides,
    tracer: Tracer,
) -> anyhow::Result<RenderedImage> {
    let build_start = Instant::now();
    let (request, packed) = prepare_request(graph, request, overrides)?;
    let build_time = build_start.elapsed();
    let mode = request.options.aa;
    if mode != AaMode::Adaptive {
        let mode = if mode == AaMode::None {
            "none"
        } else {
            "uniform"
        };
        return Err(AaMapError::NotAdaptive { mode }.into());
    }
    let start = Instant::now();
    let leaves = match tracer {
        Tracer::Gpu(ctx) => render_gpu(ctx, &packed, &GpuRenderOptions::default())?.leaf_counts,
        Tracer::Cpu => adaptive_leaf_counts(&packed),
    };
    let g = &packed.globals;
    let film = aa_samples_film(&leaves, g.width, g.height, g.aa_depth);
    Ok(RenderedImage {
        output: request.output.clone(),
        film,
        build_time,
        render_time: start.elapsed(),
        counters: None,
        gpu: None,
        adapter: match tracer {
            Tracer::Gpu(ctx) => Some(ctx.info.name.clone()),
            Tracer::Cpu => None,
        },
        packed,
        view: DebugView::AaSamples,
    })
}

/// Flattens, packs and renders one request with `tracer` (the CPU on the current rayon
/// pool, or the GPU).
pub fn render_request(
    graph: &SceneGraph,
    request: &RenderRequest,
    overrides: &OptionOverrides,
    stats: bool,
    progress: Option<&dyn ProgressSink>,
    tracer: Tracer,
) -> anyhow::Result<RenderedImage> {
    let build_start = Instant::now();
    let (request, packed) = prepare_request(graph, request, overrides)?;
    let build_time = build_start.elapsed();
    if let Some(sink) = progress {
        sink.begin(&request.output);
    }
    let tick = |done: u64, total: u64| {
        if let Some(sink) = progress {
            sink.advance(done, total);
        }
    };
    let end = || {
        if let Some(sink) = progress {
            sink.end();
        }
    };
    let start = Instant::now();
    if let Tracer::Gpu(ctx) = tracer {
        let options = GpuRenderOptions {
            progress: &tick,
            ..GpuRenderOptions::default()
        };
        let GpuRender { film, info, .. } = render_gpu(ctx, &packed, &options)?;
        end();
        if info.cpu_fallback_pixels > 0 {
            eprintln!(
                "glint: note: {} pixels of {} re-rendered on the CPU: they passed the software adapter's loop limit (Mesa: 65 535 loop iterations per invocation)",
                info.cpu_fallback_pixels,
                crate::display_path::shown(&request.output)
            );
        }
        return Ok(RenderedImage {
            output: request.output.clone(),
            film,
            packed,
            build_time,
            render_time: start.elapsed(),
            counters: None,
            gpu: Some(info),
            adapter: Some(ctx.info.name.clone()),
            view: shown_view(request.options.debug),
        });
    }
    let (film, counters) = if stats {
        let (film, counters) = render_with_counters(&packed, &tick);
        (film, Some(counters))
    } else {
        (render(&packed, &tick), None)
    };
    end();
    Ok(RenderedImage {
        output: request.output.clone(),
        film,
        packed,
        build_time,
        render_time: start.elapsed(),
        counters,
        gpu: None,
        adapter: None,
        view: shown_view(request.options.debug),
    })
}

/// What a rendered film shows for the scene's debug option: the AA map is made by
/// [`render_aa_samples_map`], never by a render, whose film is then the shaded image.
fn shown_view(debug: DebugView) -> DebugView {
    match debug {
        DebugView::AaSamples => DebugView::None,
        view => view,
    }
}

/// Output path of the `index`-th render (0-based) of a script.
pub fn output_path(settings_output: Option<&Path>, script_output: &Path, index: usize) -> PathBuf {
    let Some(base) = settings_output else {
        return script_output.to_path_buf();
    };
    if index == 0 {
        return base.to_path_buf();
    }
    crate::file_name::with_suffix(base, &format!("-{}", index + 1))
}

/// The file the `index`-th render (0-based) writes: the user's `-o` (numbered after the
/// first), else the script's own name, confined by `policy` (see [`WritePolicy`]); a
/// refused name is the scene's error.
pub fn render_output(
    settings: &RenderSettings,
    policy: &WritePolicy,
    script_output: &Path,
    index: usize,
) -> anyhow::Result<PathBuf> {
    match settings.output.as_deref() {
        Some(base) => Ok(output_path(Some(base), script_output, index)),
        None => policy.place(script_output).map_err(anyhow::Error::msg),
    }
}

/// The write rule of `settings` (`--output-dir`, `--allow-write`).
pub fn write_policy(settings: &RenderSettings) -> Result<WritePolicy, RunError> {
    WritePolicy::new(settings.output_dir.as_deref(), &settings.allow_write).map_err(RunError::Flag)
}

/// Runs a scene file, rendering and writing each `gr.render`; `on_image` sees each image
/// after it is written. Returns the script's report.
pub fn run_scene(
    path: &Path,
    settings: &RenderSettings,
    on_image: &mut dyn FnMut(&RenderedImage),
) -> Result<ScriptReport, RunError> {
    let policy = write_policy(settings)?;
    let mut gpu = acquire_gpu(
        settings.backend,
        settings.adapter.as_deref(),
        settings.stats,
    )?;
    if let Some(ctx) = gpu.as_mut() {
        apply_kernel_settings(ctx, settings)?;
    }
    let tracer = gpu.as_ref().map_or(Tracer::Cpu, Tracer::Gpu);
    let output_error: RefCell<Option<ImageIoError>> = RefCell::new(None);
    let mut index = 0;
    let mut on_render = |graph: &SceneGraph, request: &RenderRequest| -> anyhow::Result<()> {
        let output = render_output(settings, &policy, &request.output, index)?;
        index += 1;
        let fail = |e: ImageIoError| {
            let message = e.to_string();
            *output_error.borrow_mut() = Some(e);
            anyhow::anyhow!(message)
        };
        // Refuse an unwritable path before spending time on the render.
        check_output_path(&output).map_err(fail)?;
        let view = settings.overrides.debug.unwrap_or(request.options.debug);
        // The request names the file written (for the progress bar): `-o`'s, not the
        // script's.
        let request = &RenderRequest {
            output: output.clone(),
            ..request.clone()
        };
        let mut rendered = match view {
            DebugView::AaSamples => {
                render_aa_samples_map(graph, request, &settings.overrides, tracer)?
            }
            DebugView::None | DebugView::Uv => render_request(
                graph,
                request,
                &settings.overrides,
                settings.stats,
                settings.progress.as_deref(),
                tracer,
            )?,
        };
        rendered.output = output;
        write_rendered(&rendered, settings.output_transfer).map_err(fail)?;
        on_image(&rendered);
        Ok(())
    };
    match run_script(path, &settings.script, &mut on_render) {
        Ok(report) => Ok(report),
        Err(e) => Err(scene_error(e, output_error.into_inner())),
    }
}

/// Writes a render's image with the transfer `--output-transfer` asked for; an EXR
/// stays linear, with a note when sRGB was asked for.
fn write_rendered(image: &RenderedImage, transfer: OutputTransfer) -> Result<(), ImageIoError> {
    if transfer != OutputTransfer::Linear && crate::image_io::is_float_output(&image.output) {
        eprintln!(
            "glint: note: {} is EXR, written linear (float): --output-transfer applies to PNG and JPEG",
            crate::display_path::shown(&image.output)
        );
    }
    write_image_with(&image.film, &image.output, transfer)
}

/// `--kernel-variant` and `--dump-kernels` on a GPU context, before its first pipeline.
pub fn apply_kernel_settings(
    ctx: &mut GpuContext,
    settings: &RenderSettings,
) -> Result<(), crate::gpu::GpuError> {
    if let Some(variant) = settings.kernel_variant {
        ctx.force_kernel_variant(variant);
    }
    if let Some(dir) = &settings.dump_kernels {
        ctx.dump = Some(crate::gpu::device::dump::KernelDump::new(dir)?);
    }
    Ok(())
}

/// What a failed script run was: an output error recorded while writing an image (at the
/// `gr.render` that named the output, when the script named it), a GPU failure during a
/// render (the GPU's, not the scene's: exit code 5), a usage error, or the scene's own.
pub fn scene_error(error: SceneError, output_error: Option<ImageIoError>) -> RunError {
    if let Some(io) = output_error {
        return match &error {
            SceneError::Render { location, .. } => RunError::OutputAt {
                location: location.clone(),
                error: io,
            },
            _ => RunError::Output(io),
        };
    }
    match error {
        SceneError::Render { location, error } => match error.downcast::<crate::gpu::GpuError>() {
            Ok(gpu) => RunError::Gpu(gpu),
            Err(error) => match error.downcast::<AaMapError>() {
                Ok(usage) => RunError::Usage(usage),
                Err(error) => RunError::Scene(SceneError::Render { location, error }),
            },
        },
        other => RunError::Scene(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// A progress sink that writes down what it hears, in order.
    #[derive(Debug, Default)]
    struct Heard(Mutex<Vec<(&'static str, u64, u64)>>);

    impl ProgressSink for Heard {
        fn begin(&self, _output: &Path) {
            self.0.lock().unwrap().push(("begin", 0, 0));
        }
        fn advance(&self, done: u64, total: u64) {
            self.0.lock().unwrap().push(("advance", done, total));
        }
        fn end(&self) {
            self.0.lock().unwrap().push(("end", 0, 0));
        }
    }

    /// Each render of a script opens with `begin`, advances to its total and closes with
    /// `end` before the next one begins; without a sink nothing is heard and the render
    /// is the same.
    #[test]
    fn each_render_tells_the_progress_sink_begin_advances_and_end() {
        let dir = crate::testing::scratch::temp_dir("pipeline-progress");
        let scene = dir.join("two.lua");
        let render = "gr.render(root, 'out.png', 40, 24, {0,0,10}, {0,0,-1}, {0,1,0}, 50, \
                      {0.1,0.1,0.1}, {gr.light({1,2,3}, {1,1,1}, {1,0,0})})";
        let script = format!(
            "root = gr.node('root')\ns = gr.sphere('s')\nroot:add_child(s)\n\
             s:set_material(gr.material({{0.7,0.2,0.2}}, {{0.5,0.5,0.5}}, 25))\n{render}\n{render}\n"
        );
        std::fs::write(&scene, script).unwrap();
        let heard = Arc::new(Heard::default());
        let settings = RenderSettings {
            output: Some(dir.join("a.png")),
            progress: Some(heard.clone()),
            ..RenderSettings::default()
        };
        let mut films = Vec::new();
        run_scene(&scene, &settings, &mut |image| {
            films.push(image.film.clone())
        })
        .unwrap();
        let heard = heard.0.lock().unwrap().clone();
        let opens: Vec<usize> = heard
            .iter()
            .enumerate()
            .filter(|(_, h)| h.0 == "begin")
            .map(|(i, _)| i)
            .collect();
        assert_eq!(opens.len(), 2, "{heard:?}");
        for (n, &open) in opens.iter().enumerate() {
            let close = open + heard[open..].iter().position(|h| h.0 == "end").unwrap();
            assert!(
                opens.get(n + 1).is_none_or(|&next| close < next),
                "{heard:?}"
            );
            let advances = &heard[open + 1..close];
            assert!(advances.iter().all(|h| h.0 == "advance" && h.1 <= h.2));
            let total = advances.iter().map(|h| h.2).max().unwrap();
            assert!(
                total > 0 && advances.iter().any(|h| h.1 == total),
                "{heard:?}"
            );
        }
        let quiet = RenderSettings {
            output: Some(dir.join("b.png")),
            ..RenderSettings::default()
        };
        let mut quiet_films = Vec::new();
        run_scene(&scene, &quiet, &mut |image| {
            quiet_films.push(image.film.clone())
        })
        .unwrap();
        assert_eq!(films, quiet_films);
    }
}
