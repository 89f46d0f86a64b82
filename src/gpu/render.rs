//! Whole-frame GPU rendering: the frame is planned as a few large chunks
//! ([`super::plan`]), every pass of every chunk is encoded back to back into at most
//! [`GPU_FRAME_PARTS`](crate::constants::GPU_FRAME_PARTS) submits with no host wait between them, and the image comes back
//! in one read-back ([`super::frame`]). The host waits once per part, to advance the
//! progress bar; one error scope covers the frame. Counts of submits and host waits are
//! kept in [`GpuRenderInfo`] (a test checks they do not grow with the image).
//!
//! Every invocation traces one sample at most: Mesa's lavapipe (gallivm) caps the loop
//! iterations of one invocation at 65 535, summed over every loop of the shader, and past
//! that silently ends loops early. So the AA modes run in passes:
//! - none: `main`, one pixel centre per invocation;
//! - uniform n×n: `uniform_samples` (one invocation per (pixel, sample)), then
//!   `uniform_resolve` sums each pixel's samples in the CPU's order;
//! - adaptive: `adaptive_corners`, then for each level `adaptive_decide` and
//!   `adaptive_midpoints`, then `adaptive_integrate` (see `src/tracer/sampling/adaptive.wgsl`); in
//!   the hardware variant the corner and midpoint passes run through the wavefront
//!   kernels (`src/tracer/wavefront/wavefront_lattice.wgsl`), as AA none does.
//!
//! On software adapters the kernels also check the limiter (`ITERATION_GUARD`) and flag
//! the pixels a tripped invocation touched (a single very heavy ray can still trip it);
//! those are re-rendered with the CPU tracer and counted in [`GpuRenderInfo`].

use super::frame::Frame;
use super::plan::{AdapterBounds, Dispatch, FramePlan};
use super::wavefront::wavefront_shape;
use super::GpuError;
use crate::film::Film;
use crate::gpu::compile::kernel::KernelConfig;
use crate::gpu::compile::lists::LaneLists;
use crate::gpu::compile::shader::Entry;
use crate::gpu::device::context::GpuContext;
use crate::gpu::device::pipeline_cache::CompileSummary;
use crate::gpu::pipeline::{get_pipeline, CompiledPipeline};
use crate::gpu::upload::buffers::{take_mapped, upload_scene, LIMITER_SENTINEL};
use crate::pack::{PackedScene, SceneFeatures};
use crate::tiling::{PixelRect, RenderProgress};
use crate::tracer::sampling::render::render_pixel;
use crate::tracer::traversal::traverse::NoCounters;
use std::sync::Arc;
use std::time::Duration;

/// What a GPU render did besides the image (for `--stats`).
#[derive(Clone, Copy, Debug)]
pub struct GpuRenderInfo {
    /// The features compiled into the pipeline.
    pub features: SceneFeatures,
    /// Time to build the pipelines (when first compiled on this context).
    pub compile_time: Duration,
    /// `compile_time` step by step, and what the on-disk pipeline cache did.
    pub compile: CompileSummary,
    /// Chunks of the frame (see [`super::plan`]).
    pub tiles: u64,
    /// Row stride of the widest chunk, in pixels (the image width for AA none and
    /// uniform AA's bands, the square side of adaptive AA's tiles).
    pub tile_side: u32,
    /// Compute dispatches, queue submits and host waits of the frame.
    pub dispatches: u32,
    pub submits: u32,
    pub host_waits: u32,
    /// GPU time of the frame from timestamp queries (None: the adapter has none).
    pub gpu_time: Option<Duration>,
    /// The kernel variant the frame ran (workgroup size, mailboxes, and whether the
    /// kernels checked Mesa's loop limiter: `kernel.iteration_guard`, software adapters).
    pub kernel: super::KernelConfig,
    /// Pixels whose GPU result the loop limiter spoiled, re-rendered on the CPU.
    pub cpu_fallback_pixels: u64,
}

/// How a GPU render runs: `GpuRenderOptions::default()` is a plain render.
#[derive(Clone, Copy)]
pub struct GpuRenderOptions<'a> {
    /// Called with (parts done, parts) as the frame's submits complete.
    pub progress: RenderProgress<'a>,
    /// The loop limiter's sentinel ([`crate::gpu::upload::buffers::GpuTile::sentinel`]): a test hook;
    /// tests pass more than the limit to trip the limiter on purpose and exercise the CPU
    /// fallback.
    #[doc(hidden)]
    pub limiter_sentinel: u32,
    /// Time each dispatch on its own (timestamp queries around a compute pass each) and
    /// return the sums per kind of pass in [`GpuRender::pass_times`]; the passes then
    /// cannot overlap, so the frame may take a little longer (`glint bench --gpu
    /// --passes`).
    pub pass_times: bool,
    /// Render only these pixels (a farm's tile, `--crop`), into a film of the window's
    /// size; `None`: the whole frame.
    pub window: Option<PixelRect>,
}

impl Default for GpuRenderOptions<'_> {
    fn default() -> Self {
        GpuRenderOptions {
            progress: &|_, _| {},
            limiter_sentinel: LIMITER_SENTINEL,
            pass_times: false,
            window: None,
        }
    }
}

/// What a GPU render returns besides errors.
pub struct GpuRender {
    pub film: Film,
    pub info: GpuRenderInfo,
    /// Adaptive AA's leaf squares per pixel, row-major (see
    /// [`crate::tracer::sampling::render::adaptive_leaf_counts`]); meaningful with adaptive AA only.
    pub leaf_counts: Vec<u32>,
    /// With [`GpuRenderOptions::pass_times`] on an adapter with timestamp queries: GPU
    /// time per kind of pass, in the order of the frame's first dispatch of each.
    pub pass_times: Vec<PassTime>,
}

/// The GPU time of one kind of pass of a frame, summed over its dispatches.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTime {
    /// The kernel's entry point, as the WGSL names it (`adaptive_midpoints`).
    pub entry: &'static str,
    /// The quadtree level of adaptive AA's per-level passes (decide, work arguments,
    /// midpoints; else 0).
    pub level: u32,
    /// Dispatches summed (one per chunk).
    pub dispatches: u32,
    pub time: Duration,
}

/// The frame's results as read back: colours (alpha: adaptive AA's leaf count), guard
/// flags and GPU time.
struct ReadBack {
    bytes: Vec<u8>,
    gpu_time: Option<Duration>,
    /// Each dispatch's GPU time, when timed per dispatch.
    dispatch_times: Vec<Duration>,
    /// Host waits it took.
    host_waits: u32,
}

/// What the dispatch plan may use of `ctx`'s adapter for a kernel of variant `kernel`
/// over a scene with `features`: the largest storage binding, the workgroups per
/// dimension, the workgroup side and the words of a per-ray list slot (the render's and
/// the view's plans alike).
pub(super) fn adapter_bounds(
    ctx: &GpuContext,
    kernel: KernelConfig,
    features: SceneFeatures,
) -> AdapterBounds {
    AdapterBounds {
        max_binding: ctx
            .limits
            .max_storage_buffer_binding_size
            .min(ctx.limits.max_buffer_size),
        max_workgroups: ctx.limits.max_compute_workgroups_per_dimension,
        workgroup_side: kernel.workgroup_side,
        lane_list_words: LaneLists::of(features, kernel).words(),
        wavefront: None,
    }
}

/// Renders `scene` on `ctx`'s device: the one entry point of the GPU tracer.
pub fn render_gpu(
    ctx: &GpuContext,
    scene: &PackedScene,
    options: &GpuRenderOptions,
) -> Result<GpuRender, GpuError> {
    let (progress, sentinel) = (options.progress, options.limiter_sentinel);
    let bounds = AdapterBounds {
        wavefront: wavefront_shape(ctx.kernel, scene),
        ..adapter_bounds(ctx, ctx.kernel, scene.features)
    };
    let g = &scene.globals;
    let window = options.window.unwrap_or(PixelRect::full(g.width, g.height));
    let plan = FramePlan::for_window(g, bounds, window);
    let pipelines = plan
        .mode
        .entries()
        .iter()
        .map(|&e| get_pipeline(ctx, scene.features, e))
        .collect::<Result<Vec<Arc<CompiledPipeline>>, GpuError>>()?;
    crate::gpu::upload::buffers::check_size(ctx, "per-chunk samples", plan.samples_len * 16)?;
    let buffers = upload_scene(ctx, scene)?;
    // Dispatches part by part, and where each part's run ends.
    let mut dispatches: Vec<Dispatch> = Vec::new();
    let mut part_ends = Vec::new();
    for part in &plan.parts {
        for chunk in part.clone() {
            dispatches.extend(plan.dispatches(chunk, sentinel, bounds));
        }
        part_ends.push(dispatches.len());
    }
    let (frame, submissions) = ctx.scoped("frame", || {
        let layout = &pipelines[0].layout;
        let frame = Frame::new(
            ctx,
            &plan,
            &buffers,
            layout,
            &dispatches,
            options.pass_times,
        );
        let mut start = 0;
        let mut submissions = Vec::new();
        for (k, &end) in part_ends.iter().enumerate() {
            let last = k + 1 == part_ends.len();
            let commands = frame.encode_part(&pipelines, &dispatches, start..end, k == 0, last);
            submissions.push(ctx.queue.submit([commands]));
            start = end;
        }
        (frame, submissions)
    })?;
    let submits = submissions.len() as u32;
    let read = wait_and_read(ctx, &frame, submissions, progress)?;
    let (film, alpha, fallback) = scatter(scene, window, &plan, &frame, &read.bytes);
    let info = GpuRenderInfo {
        features: scene.features,
        compile_time: pipelines.iter().map(|p| p.compile_time).sum(),
        compile: CompileSummary::of(pipelines.iter().map(|p| &p.steps)),
        tiles: plan.chunks.len() as u64,
        tile_side: plan.chunks.iter().map(|c| c.side).max().unwrap_or(0),
        dispatches: dispatches.len() as u32,
        submits,
        host_waits: read.host_waits,
        gpu_time: read.gpu_time,
        kernel: pipelines[0].kernel,
        cpu_fallback_pixels: fallback,
    };
    Ok(GpuRender {
        film,
        info,
        leaf_counts: alpha,
        pass_times: pass_times(&plan, &dispatches, &read.dispatch_times),
    })
}

/// The dispatches' `times` summed per entry point and level, in the order of each
/// kind's first dispatch (empty when `times` is).
fn pass_times(plan: &FramePlan, dispatches: &[Dispatch], times: &[Duration]) -> Vec<PassTime> {
    let mut sums: Vec<PassTime> = Vec::new();
    for (d, &time) in dispatches.iter().zip(times) {
        let entry = plan.mode.entries()[d.entry];
        let per_level = matches!(
            entry,
            Entry::AdaptiveDecide | Entry::AdaptiveWorkArgs | Entry::AdaptiveMidpoints
        );
        let (entry, level) = (entry.name(), if per_level { d.params.level } else { 0 });
        match sums
            .iter_mut()
            .find(|p| p.entry == entry && p.level == level)
        {
            Some(sum) => {
                sum.dispatches += 1;
                sum.time += time;
            }
            None => sums.push(PassTime {
                entry,
                level,
                dispatches: 1,
                time,
            }),
        }
    }
    sums
}

/// Waits for each submitted part in turn (one host wait each, reporting progress) and
/// maps the staging buffer with the last: the queue never waits for the host.
fn wait_and_read(
    ctx: &GpuContext,
    frame: &Frame,
    submissions: Vec<wgpu::SubmissionIndex>,
    progress: RenderProgress,
) -> Result<ReadBack, GpuError> {
    let total = submissions.len() as u64;
    let size = frame.staging_len;
    let (tx, rx) = std::sync::mpsc::channel();
    let mut host_waits = 0;
    for (k, index) in submissions.into_iter().enumerate() {
        if k as u64 + 1 == total {
            let tx = tx.clone();
            frame
                .staging
                .map_async(wgpu::MapMode::Read, 0..size, move |r| {
                    let _ = tx.send(r);
                });
        }
        ctx.wait_for(index)?;
        host_waits += 1;
        progress(k as u64 + 1, total);
    }
    let bytes = take_mapped(&frame.staging, size, rx.try_recv().ok())?;
    let at = (frame.output_bytes + frame.guard_bytes) as usize;
    let ticks: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes[at..]);
    let period = ctx.queue.get_timestamp_period() as f64;
    let between = |from: u64, to: u64| {
        Duration::from_secs_f64(to.saturating_sub(from) as f64 * period * 1e-9)
    };
    // The frame's start and end, or every dispatch's.
    let gpu_time = frame
        .timed()
        .then(|| between(ticks[0], ticks[ticks.len() - 1]));
    let dispatch_times = match frame.timed_per_dispatch() {
        true => ticks.chunks(2).map(|t| between(t[0], t[1])).collect(),
        false => Vec::new(),
    };
    Ok(ReadBack {
        bytes,
        gpu_time,
        dispatch_times,
        host_waits,
    })
}

/// The read-back blocks into a film of `window`, the alpha channel and the count of
/// pixels the loop limiter spoiled (re-rendered here with the CPU tracer).
fn scatter(
    scene: &PackedScene,
    window: PixelRect,
    plan: &FramePlan,
    frame: &Frame,
    bytes: &[u8],
) -> (Film, Vec<u32>, u64) {
    let (w, h) = (window.width(), window.height());
    let mut film = Film::new(w, h);
    let mut alpha = vec![0u32; (w * h) as usize];
    let mut fallback = 0;
    let guard_base = frame.output_bytes as usize;
    for (chunk, block) in plan.chunks.iter().zip(&frame.blocks) {
        let o = block.output_offset as usize;
        let colours: Vec<[f32; 4]> =
            bytemuck::pod_collect_to_vec(&bytes[o..o + block.output_size as usize]);
        let g = guard_base + block.guard_offset as usize;
        let flags: Vec<u32> =
            bytemuck::pod_collect_to_vec(&bytes[g..g + block.guard_size as usize]);
        let [x0, y0] = chunk.origin;
        for ty in 0..chunk.size[1] {
            for tx in 0..chunk.size[0] {
                let k = (ty * chunk.side + tx) as usize;
                // Image pixel (x, y); (fx, fy) in the window's film.
                let (x, y) = (x0 + tx, y0 + ty);
                let (fx, fy) = (x - window.x0, y - window.y0);
                let p = colours[k];
                alpha[(fy * w + fx) as usize] = p[3] as u32;
                if flags[k] != 0 {
                    let c = render_pixel(scene, x, y, &mut NoCounters);
                    film.set(fx, fy, c.to_array());
                    fallback += 1;
                } else {
                    film.set(fx, fy, [p[0], p[1], p[2]]);
                }
            }
        }
    }
    (film, alpha, fallback)
}
