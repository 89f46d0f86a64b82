//! `glint render SCENE --backend both`: every `gr.render` of a script rendered by both
//! tracers in one run, both images written (`NAME-cpu.EXT`, `NAME-gpu.EXT`, and FLIP's
//! heat map when asked), the difference measured, and a verdict a CI job can use: the
//! images agree when at least `min_share` of the pixels are within `tolerance` in every
//! channel (the GPU parity tests' criterion, 99.9% within 2/255, by default).

use crate::diff::{diff_films, DiffReport};
use crate::gpu::GpuContext;
use crate::image_io::{check_output_path, write_image, ImageIoError};
use crate::pipeline::{
    output_path, render_output, render_request, scene_error, write_policy, RenderSettings,
    RunError, Tracer,
};
use crate::scene::lua::ScriptReport;
use crate::scene::{RenderRequest, SceneGraph};
use crate::script_driver::run_script;
use crate::write_policy::WritePolicy;
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The agreement `--backend both` asks for.
#[derive(Clone, Debug)]
pub struct ParitySettings {
    /// Largest per-channel difference a pixel may have and still agree ([0,1] units).
    pub tolerance: f32,
    /// Smallest share of agreeing pixels for the images to agree.
    pub min_share: f64,
    /// Where to write FLIP's heat map (later renders of a script get -2, -3…).
    pub heatmap: Option<PathBuf>,
}

impl Default for ParitySettings {
    fn default() -> Self {
        ParitySettings {
            tolerance: 2.0 / 255.0,
            min_share: 0.999,
            heatmap: None,
        }
    }
}

/// One render on both tracers.
#[derive(Clone, Debug)]
pub struct ParityResult {
    pub cpu_output: PathBuf,
    pub gpu_output: PathBuf,
    pub heatmap: Option<PathBuf>,
    pub cpu_time: Duration,
    pub gpu_time: Duration,
    pub report: DiffReport,
    /// Share of pixels within the tolerance.
    pub share_within: f64,
    pub agrees: bool,
}

/// `path` with `-tag` before its extension.
pub fn tagged(path: &Path, tag: &str) -> PathBuf {
    crate::file_name::with_suffix(path, &format!("-{tag}"))
}

/// Renders one request on both tracers, writes the images and compares them.
fn render_both(
    graph: &SceneGraph,
    request: &RenderRequest,
    settings: &RenderSettings,
    parity: &ParitySettings,
    ctx: &GpuContext,
    policy: &WritePolicy,
    index: usize,
) -> anyhow::Result<ParityResult> {
    // Each tagged name is a name of the script's (when it is), under the write rule.
    let [cpu_output, gpu_output] = ["cpu", "gpu"].map(|tag| match settings.output {
        Some(_) => render_output(settings, policy, &request.output, index).map(|o| tagged(&o, tag)),
        None => render_output(settings, policy, &tagged(&request.output, tag), index),
    });
    let (cpu_output, gpu_output) = (cpu_output?, gpu_output?);
    let heatmap = parity
        .heatmap
        .as_deref()
        .map(|h| output_path(Some(h), h, index));
    for path in [Some(&cpu_output), Some(&gpu_output), heatmap.as_ref()]
        .into_iter()
        .flatten()
    {
        check_output_path(path)?;
    }
    let o = &settings.overrides;
    let progress = settings.progress.as_deref();
    let cpu = render_request(graph, request, o, false, progress, Tracer::Cpu)?;
    let gpu = render_request(graph, request, o, false, progress, Tracer::Gpu(ctx))?;
    // Compared as films (linear); written as `--output-transfer` asks.
    let transfer = settings.output_transfer;
    crate::image_io::write_image_with(&cpu.film, &cpu_output, transfer)?;
    crate::image_io::write_image_with(&gpu.film, &gpu_output, transfer)?;
    let (report, heat) = diff_films(&cpu.film, &gpu.film)?;
    if let Some(path) = &heatmap {
        write_image(&heat, path)?;
    }
    let share_within = report.share_within(parity.tolerance);
    Ok(ParityResult {
        cpu_output,
        gpu_output,
        heatmap,
        cpu_time: cpu.render_time,
        gpu_time: gpu.render_time,
        agrees: share_within >= parity.min_share,
        share_within,
        report,
    })
}

/// Runs a scene file, rendering each `gr.render` on both tracers; `on_result` sees each
/// comparison. Returns the script's report and whether every render agreed.
pub fn run_scene_both(
    path: &Path,
    settings: &RenderSettings,
    parity: &ParitySettings,
    on_result: &mut dyn FnMut(&ParityResult),
) -> Result<(ScriptReport, bool), RunError> {
    let policy = write_policy(settings)?;
    let ctx = GpuContext::new(settings.adapter.as_deref())?;
    let output_error: RefCell<Option<ImageIoError>> = RefCell::new(None);
    let mut index = 0;
    let mut all_agree = true;
    let mut on_render = |graph: &SceneGraph, request: &RenderRequest| -> anyhow::Result<()> {
        let result = render_both(graph, request, settings, parity, &ctx, &policy, index).map_err(
            |e| match e.downcast::<ImageIoError>() {
                Ok(io) => {
                    let message = io.to_string();
                    *output_error.borrow_mut() = Some(io);
                    anyhow::anyhow!(message)
                }
                Err(e) => e,
            },
        )?;
        index += 1;
        all_agree &= result.agrees;
        on_result(&result);
        Ok(())
    };
    match run_script(path, &settings.script, &mut on_render) {
        Ok(report) => Ok((report, all_agree)),
        Err(e) => Err(scene_error(e, output_error.into_inner())),
    }
}
