//! Tiled GPU rendering: each tile is a few passes (one compute dispatch each), followed by
//! a wait and a read-back, so progress advances per tile, no single dispatch runs long
//! enough to trip a driver watchdog, and the pixels land in the same [`Film`] the CPU
//! tracer fills.
//!
//! Every invocation traces one sample at most: Mesa's lavapipe (gallivm) caps the loop
//! iterations of one invocation at 65 535, summed over every loop of the shader, and past
//! that silently ends loops early. So the AA modes run in passes:
//! - none: `main`, one pixel centre per invocation;
//! - uniform n×n: `uniform_samples` (one invocation per (pixel, sample)), then
//!   `uniform_resolve` sums each pixel's samples in the CPU's order;
//! - adaptive: `adaptive_corners`, then for each level `adaptive_decide` and
//!   `adaptive_midpoints`, then `adaptive_integrate` (see `shaders/adaptive.wgsl`).
//!
//! On software adapters the kernels also check the limiter (`ITERATION_GUARD`) and flag
//! the pixels a tripped invocation touched (a single very heavy ray can still trip it);
//! those are re-rendered with the CPU tracer and counted in [`GpuRenderInfo`].

use super::buffers::{read_back, scene_entries, upload_scene, GpuTile, LIMITER_SENTINEL};
use super::context::GpuContext;
use super::pipeline::{
    get_pipeline, CompiledPipeline, GUARD_BINDING, OUTPUT_BINDING, SAMPLES_BINDING, SPLIT_BINDING,
    TILE_BINDING,
};
use super::shader::Entry;
use super::GpuError;
use crate::constants::{
    adaptive_tile_side, AA_ADAPTIVE, AA_UNIFORM, GPU_ADAPTIVE_LATTICE_SIDE, GPU_TILE_SIZE,
    GPU_UNIFORM_SAMPLES_SIDE, LINEAR_WORKGROUP_SIZE, WORKGROUP_SIZE,
};
use crate::cpu::render::render_pixel;
use crate::cpu::traverse::NoCounters;
use crate::film::Film;
use crate::pack::{PackedScene, SceneFeatures};
use crate::tiling::{split_offset, AdaptiveTile, RenderProgress};
use std::sync::Arc;
use std::time::Duration;

/// What a GPU render did besides the image (for `--stats`).
#[derive(Clone, Copy, Debug)]
pub struct GpuRenderInfo {
    /// The features compiled into the pipeline.
    pub features: SceneFeatures,
    /// Time to build the pipelines (when first compiled on this context).
    pub compile_time: Duration,
    pub tiles: u64,
    /// Side of the tiles, in pixels (smaller under deep adaptive or dense uniform AA).
    pub tile_side: u32,
    /// Whether the kernels checked Mesa's loop limiter (software adapters).
    pub iteration_guard: bool,
    /// Pixels whose GPU result the loop limiter spoiled, re-rendered on the CPU.
    pub cpu_fallback_pixels: u64,
}

/// Renders `scene` on `ctx`'s device.
pub fn render_gpu(
    ctx: &GpuContext,
    scene: &PackedScene,
    progress: RenderProgress,
) -> Result<Film, GpuError> {
    render_gpu_with_info(ctx, scene, progress).map(|(film, _)| film)
}

/// Renders `scene` on `ctx`'s device, reporting the pipeline's features and compile time.
pub fn render_gpu_with_info(
    ctx: &GpuContext,
    scene: &PackedScene,
    progress: RenderProgress,
) -> Result<(Film, GpuRenderInfo), GpuError> {
    render_gpu_detailed(ctx, scene, progress, LIMITER_SENTINEL).map(|(f, i, _)| (f, i))
}

/// Leaf squares per pixel of adaptive AA on the GPU (see
/// [`crate::cpu::render::adaptive_leaf_counts`]), row-major.
pub fn adaptive_leaf_counts_gpu(
    ctx: &GpuContext,
    scene: &PackedScene,
) -> Result<Vec<u32>, GpuError> {
    render_gpu_detailed(ctx, scene, &|_, _| {}, LIMITER_SENTINEL).map(|(_, _, l)| l)
}

/// The AA mode's passes and tile side.
#[derive(Clone, Copy)]
enum Mode {
    None,
    Uniform { n: u32 },
    Adaptive { depth: u32 },
}

/// A render in progress: the pipelines, buffers and bind group every pass shares.
struct Passes<'a> {
    ctx: &'a GpuContext,
    tile_buffer: wgpu::Buffer,
    guard: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

impl Passes<'_> {
    /// Runs `pipeline` over `workgroups` with `params` (one submit: the tile uniform is
    /// written between passes). `clear_guard` first zeroes the guard flags.
    fn run(
        &self,
        pipeline: &CompiledPipeline,
        params: GpuTile,
        workgroups: (u32, u32),
        clear_guard: bool,
    ) -> Result<(), GpuError> {
        self.ctx.scoped("tile dispatch", || {
            self.ctx
                .queue
                .write_buffer(&self.tile_buffer, 0, bytemuck::bytes_of(&params));
            let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
            if clear_guard {
                encoder.clear_buffer(&self.guard, 0, None);
            }
            {
                let mut pass = encoder.begin_compute_pass(&Default::default());
                pass.set_pipeline(&pipeline.pipeline);
                pass.set_bind_group(0, &self.bind_group, &[]);
                pass.dispatch_workgroups(workgroups.0, workgroups.1, 1);
            }
            self.ctx.queue.submit([encoder.finish()]);
        })
    }
}

fn linear(items: u32) -> (u32, u32) {
    (items.div_ceil(LINEAR_WORKGROUP_SIZE), 1)
}

fn square(w: u32, h: u32) -> (u32, u32) {
    (w.div_ceil(WORKGROUP_SIZE), h.div_ceil(WORKGROUP_SIZE))
}

/// Renders `scene`; also returns the output's alpha per pixel (adaptive AA's leaf counts).
/// `sentinel` is [`GpuTile::sentinel`] ([`LIMITER_SENTINEL`]; tests pass more than the
/// limit to trip the limiter on purpose and exercise the CPU fallback).
#[doc(hidden)]
pub fn render_gpu_detailed(
    ctx: &GpuContext,
    scene: &PackedScene,
    progress: RenderProgress,
    sentinel: u32,
) -> Result<(Film, GpuRenderInfo, Vec<u32>), GpuError> {
    let g = &scene.globals;
    let (w, h) = (g.width, g.height);
    let mode = match g.aa_mode {
        AA_ADAPTIVE => Mode::Adaptive { depth: g.aa_depth },
        AA_UNIFORM => Mode::Uniform { n: g.aa_samples },
        _ => Mode::None,
    };
    let side = match mode {
        Mode::None => GPU_TILE_SIZE,
        Mode::Uniform { n } => (GPU_UNIFORM_SAMPLES_SIDE / n.max(1)).clamp(1, GPU_TILE_SIZE),
        Mode::Adaptive { depth } => {
            adaptive_tile_side(GPU_TILE_SIZE, GPU_ADAPTIVE_LATTICE_SIDE, depth)
        }
    };
    let (samples_len, split_len) = match mode {
        Mode::None => (1, 1),
        Mode::Uniform { n } => ((side * side * n * n) as u64, 1),
        Mode::Adaptive { depth } => {
            let t = AdaptiveTile {
                origin: [0, 0],
                size: [side, side],
                side,
                depth,
            };
            (
                t.lattice_len() as u64,
                split_offset(side, depth).max(1) as u64,
            )
        }
    };
    let entries: &[Entry] = match mode {
        Mode::None => &[Entry::Render],
        Mode::Uniform { .. } => &[Entry::UniformSamples, Entry::UniformResolve],
        Mode::Adaptive { .. } => &[
            Entry::AdaptiveCorners,
            Entry::AdaptiveDecide,
            Entry::AdaptiveMidpoints,
            Entry::AdaptiveIntegrate,
        ],
    };
    let pipelines = entries
        .iter()
        .map(|&e| get_pipeline(ctx, scene.features, e))
        .collect::<Result<Vec<Arc<CompiledPipeline>>, GpuError>>()?;
    let compile_time = pipelines.iter().map(|p| p.compile_time).sum();
    let iteration_guard = pipelines[0].iteration_guard;
    super::buffers::check_size(ctx, "per-tile samples", samples_len * 16)?;
    let buffers = upload_scene(ctx, scene)?;
    let device = &ctx.device;
    let pixels_len = (side * side) as u64;
    let output_size = pixels_len * 16;
    let guard_size = pixels_len * 4;
    let storage = |label, size| {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    };
    let (passes, output, staging) = ctx.scoped("render set-up", || {
        let tile_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("tile"),
            size: std::mem::size_of::<GpuTile>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let output = storage("tile output", output_size);
        let samples = storage("tile samples", samples_len * 16);
        let split = storage("tile split flags", split_len * 4);
        let guard = storage("tile guard flags", guard_size);
        // Output, then guard flags.
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("tile staging"),
            size: output_size + guard_size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut entries = scene_entries(&buffers);
        for (binding, buffer) in [
            (TILE_BINDING, &tile_buffer),
            (OUTPUT_BINDING, &output),
            (SAMPLES_BINDING, &samples),
            (SPLIT_BINDING, &split),
            (GUARD_BINDING, &guard),
        ] {
            entries.push(wgpu::BindGroupEntry {
                binding,
                resource: buffer.as_entire_binding(),
            });
        }
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("glint render"),
            layout: &pipelines[0].layout,
            entries: &entries,
        });
        let passes = Passes {
            ctx,
            tile_buffer,
            guard,
            bind_group,
        };
        (passes, output, staging)
    })?;

    let tiles_x = w.div_ceil(side);
    let tiles_y = h.div_ceil(side);
    let total = (tiles_x * tiles_y) as u64;
    let mut film = Film::new(w, h);
    let mut alpha = vec![0u32; (w * h) as usize];
    let mut fallback = 0u64;
    for tile in 0..tiles_x * tiles_y {
        let (x0, y0) = ((tile % tiles_x) * side, (tile / tiles_x) * side);
        let (tw, th) = ((w - x0).min(side), (h - y0).min(side));
        let params = |level: u32, items: u32| GpuTile {
            origin: [x0, y0],
            size: [tw, th],
            side,
            level,
            items,
            sentinel,
        };
        match mode {
            Mode::None => passes.run(&pipelines[0], params(0, 0), square(tw, th), true)?,
            Mode::Uniform { n } => {
                let items = tw * th * n * n;
                passes.run(&pipelines[0], params(0, items), linear(items), true)?;
                passes.run(&pipelines[1], params(0, 0), square(tw, th), false)?;
            }
            Mode::Adaptive { depth } => {
                let items = (tw + 1) * (th + 1);
                passes.run(&pipelines[0], params(0, items), linear(items), true)?;
                for level in 0..depth {
                    let squares = (tw << level) * (th << level);
                    passes.run(
                        &pipelines[1],
                        params(level, squares),
                        linear(squares),
                        false,
                    )?;
                    let items = squares * 5;
                    passes.run(&pipelines[2], params(level, items), linear(items), false)?;
                }
                passes.run(&pipelines[3], params(0, 0), square(tw, th), false)?;
            }
        }
        ctx.scoped("tile read-back", || {
            let mut encoder = device.create_command_encoder(&Default::default());
            encoder.copy_buffer_to_buffer(&output, 0, &staging, 0, output_size);
            encoder.copy_buffer_to_buffer(&passes.guard, 0, &staging, output_size, guard_size);
            ctx.queue.submit([encoder.finish()]);
        })?;
        let bytes = read_back(ctx, &staging, output_size + guard_size)?;
        let (colours, flags) = bytes.split_at(output_size as usize);
        let pixels: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(colours);
        let flags: Vec<u32> = bytemuck::pod_collect_to_vec(flags);
        for ty in 0..th {
            for tx in 0..tw {
                let k = (ty * side + tx) as usize;
                let (x, y) = (x0 + tx, y0 + ty);
                let p = pixels[k];
                alpha[(y * w + x) as usize] = p[3] as u32;
                if flags[k] != 0 {
                    let c = render_pixel(scene, x, y, &mut NoCounters);
                    film.set(x, y, c.to_array());
                    fallback += 1;
                } else {
                    film.set(x, y, [p[0], p[1], p[2]]);
                }
            }
        }
        progress(tile as u64 + 1, total);
    }
    let info = GpuRenderInfo {
        features: scene.features,
        compile_time,
        tiles: total,
        tile_side: side,
        iteration_guard,
        cpu_fallback_pixels: fallback,
    };
    Ok((film, info, alpha))
}
