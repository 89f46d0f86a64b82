//! Tiled GPU rendering: one dispatch per GPU_TILE_SIZE² tile, each followed by a wait and
//! a read-back, so progress advances per tile, no single dispatch runs long enough to trip
//! a driver watchdog, and the pixels land in the same [`Film`] the CPU tracer fills.

use super::buffers::{read_back, scene_entries, upload_scene, GpuTile};
use super::context::GpuContext;
use super::pipeline::{get_pipeline, OUTPUT_BINDING, TILE_BINDING};
use super::shader::Entry;
use super::GpuError;
use crate::constants::{GPU_TILE_SIZE, WORKGROUP_SIZE};
use crate::cpu::RenderProgress;
use crate::film::Film;
use crate::pack::{PackedScene, SceneFeatures};
use std::time::Duration;

/// What a GPU render did besides the image (for `--stats`).
#[derive(Clone, Copy, Debug)]
pub struct GpuRenderInfo {
    /// The features compiled into the pipeline.
    pub features: SceneFeatures,
    /// Time to build that pipeline (when it was first compiled on this context).
    pub compile_time: Duration,
    pub tiles: u64,
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
    let (w, h) = (scene.globals.width, scene.globals.height);
    let compiled = get_pipeline(ctx, scene.features, Entry::Render)?;
    let buffers = upload_scene(ctx, scene)?;
    let device = &ctx.device;
    let tile_pixels = (GPU_TILE_SIZE * GPU_TILE_SIZE) as u64;
    let output_size = tile_pixels * 16;
    let (tile_buffer, output, staging, bind_group) = ctx.scoped("render set-up", || {
        let tile_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("tile"),
            size: std::mem::size_of::<GpuTile>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("tile output"),
            size: output_size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("tile staging"),
            size: output_size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut entries = scene_entries(&buffers);
        entries.push(wgpu::BindGroupEntry {
            binding: TILE_BINDING,
            resource: tile_buffer.as_entire_binding(),
        });
        entries.push(wgpu::BindGroupEntry {
            binding: OUTPUT_BINDING,
            resource: output.as_entire_binding(),
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("glint render"),
            layout: &compiled.layout,
            entries: &entries,
        });
        (tile_buffer, output, staging, bind_group)
    })?;

    let tiles_x = w.div_ceil(GPU_TILE_SIZE);
    let tiles_y = h.div_ceil(GPU_TILE_SIZE);
    let total = (tiles_x * tiles_y) as u64;
    let mut film = Film::new(w, h);
    for tile in 0..tiles_x * tiles_y {
        let (x0, y0) = (
            (tile % tiles_x) * GPU_TILE_SIZE,
            (tile / tiles_x) * GPU_TILE_SIZE,
        );
        let (tw, th) = ((w - x0).min(GPU_TILE_SIZE), (h - y0).min(GPU_TILE_SIZE));
        ctx.scoped("tile dispatch", || {
            let params = GpuTile {
                origin: [x0, y0],
                _pad: [0; 2],
            };
            ctx.queue
                .write_buffer(&tile_buffer, 0, bytemuck::bytes_of(&params));
            let mut encoder = device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_compute_pass(&Default::default());
                pass.set_pipeline(&compiled.pipeline);
                pass.set_bind_group(0, &bind_group, &[]);
                pass.dispatch_workgroups(
                    tw.div_ceil(WORKGROUP_SIZE),
                    th.div_ceil(WORKGROUP_SIZE),
                    1,
                );
            }
            // Only the rows this tile covers.
            let rows = th as u64 * GPU_TILE_SIZE as u64 * 16;
            encoder.copy_buffer_to_buffer(&output, 0, &staging, 0, rows);
            ctx.queue.submit([encoder.finish()]);
        })?;
        let rows = th as u64 * GPU_TILE_SIZE as u64 * 16;
        let bytes = read_back(ctx, &staging, rows)?;
        let pixels: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&bytes);
        for ty in 0..th {
            for tx in 0..tw {
                let p = pixels[(ty * GPU_TILE_SIZE + tx) as usize];
                film.set(x0 + tx, y0 + ty, [p[0], p[1], p[2]]);
            }
        }
        progress(tile as u64 + 1, total);
    }
    let info = GpuRenderInfo {
        features: scene.features,
        compile_time: compiled.compile_time,
        tiles: total,
    };
    Ok((film, info))
}
