//! `glint view`'s device side: progressive uniform anti-aliasing on the device that also
//! presents the window. The per-pixel sums live in one storage buffer ([`SumBuffer`])
//! for the whole session: `view_sample` (shaders/progressive.wgsl) adds sample k of every pixel
//! to it in frame k, the window's present pass reads it, and the CPU tracer's sums are
//! uploaded into it when that tracer refines instead. Nothing is read back except for S
//! (save), so a refining frame costs one dispatch and one present.
//!
//! The view's own copy of the globals (camera moved, preview size) is a uniform written
//! before each restart; the scene's tables are uploaded once per scene load.

use super::buffers::{
    read_back, scene_entries, upload_scene, GpuTile, SceneBuffers, LIMITER_SENTINEL,
};
use super::context::GpuContext;
use super::pipeline::{
    get_pipeline, CompiledPipeline, GUARD_BINDING, OUTPUT_BINDING, SAMPLES_BINDING, SPLIT_BINDING,
    TILE_BINDING, WORK_ARGS_BINDING, WORK_COUNTS_BINDING, WORK_LIST_BINDING,
};
use super::shader::Entry;
use super::GpuError;
use crate::pack::{PackedGlobals, PackedScene};
use std::sync::Arc;
use wgpu::util::DeviceExt;

/// Bytes of one pixel's sum (RGB and the sample count, f32 each).
pub const SUM_BYTES: u64 = 16;

/// The per-pixel sums of the view's image: room for `capacity` pixels (the full image;
/// a reduced-resolution preview uses the start of it, at its own row stride).
pub struct SumBuffer {
    pub buffer: wgpu::Buffer,
    pub capacity: u64,
}

impl SumBuffer {
    pub fn new(ctx: &GpuContext, pixels: u64) -> Result<SumBuffer, GpuError> {
        super::buffers::check_size(ctx, "view sums", pixels * SUM_BYTES)?;
        use wgpu::BufferUsages as U;
        let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view sums"),
            size: (pixels * SUM_BYTES).max(SUM_BYTES),
            usage: U::STORAGE | U::COPY_DST | U::COPY_SRC,
            mapped_at_creation: false,
        });
        Ok(SumBuffer {
            buffer,
            capacity: pixels,
        })
    }

    /// Replaces the first pixels' sums with `sums` (the CPU tracer's).
    pub fn upload(&self, ctx: &GpuContext, sums: &[[f32; 4]]) {
        ctx.queue
            .write_buffer(&self.buffer, 0, bytemuck::cast_slice(sums));
    }

    /// The first `pixels` sums, read back (waits for the device).
    pub fn read(&self, ctx: &GpuContext, pixels: u64) -> Result<Vec<[f32; 4]>, GpuError> {
        let size = pixels * SUM_BYTES;
        let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view sums read-back"),
            size: size.max(SUM_BYTES),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&self.buffer, 0, &staging, 0, size);
        ctx.queue.submit([encoder.finish()]);
        let bytes = read_back(ctx, &staging, size)?;
        Ok(bytemuck::pod_collect_to_vec(&bytes))
    }
}

/// A scene on the device, ready to add one sample per pixel per [`Self::encode_sample`].
pub struct Progressive {
    pipeline: Arc<CompiledPipeline>,
    globals: wgpu::Buffer,
    tile: wgpu::Buffer,
    guard: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    /// The size the globals say (the full image or a preview), for the dispatch.
    size: [u32; 2],
    /// Pixels the guard buffer holds.
    guard_pixels: u64,
    /// Kept alive for the bind group.
    _scene: SceneBuffers,
    _unused: Vec<wgpu::Buffer>,
}

impl Progressive {
    /// Uploads `scene`, compiles (or finds) its `view_sample` pipeline and binds `sums`.
    pub fn new(
        ctx: &GpuContext,
        scene: &PackedScene,
        sums: &SumBuffer,
    ) -> Result<Progressive, GpuError> {
        let pipeline = get_pipeline(ctx, scene.features, Entry::ViewSample)?;
        let buffers = upload_scene(ctx, scene)?;
        let g = &scene.globals;
        let guard_pixels = u64::from(g.width) * u64::from(g.height);
        use wgpu::BufferUsages as U;
        ctx.scoped("view setup", || {
            let device = &ctx.device;
            let globals = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("view globals"),
                contents: bytemuck::bytes_of(g),
                usage: U::UNIFORM | U::COPY_DST,
            });
            let tile = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("view tile"),
                size: std::mem::size_of::<GpuTile>() as u64,
                usage: U::UNIFORM | U::COPY_DST,
                mapped_at_creation: false,
            });
            let storage = |label, size: u64| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(label),
                    size: size.max(256),
                    usage: U::STORAGE | U::COPY_DST,
                    mapped_at_creation: false,
                })
            };
            let guard = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("view guard"),
                size: (guard_pixels * 4).max(256),
                usage: U::STORAGE | U::COPY_DST | U::COPY_SRC,
                mapped_at_creation: false,
            });
            // view_sample reads none of the other AA passes' buffers; the layout (one for
            // every render entry) still has them.
            let unused: Vec<wgpu::Buffer> = (0..5).map(|_| storage("unused", 256)).collect();
            let mut entries = scene_entries(&buffers);
            entries[0].resource = globals.as_entire_binding();
            let own = [
                (TILE_BINDING, tile.as_entire_binding()),
                (OUTPUT_BINDING, sums.buffer.as_entire_binding()),
                (GUARD_BINDING, guard.as_entire_binding()),
                (SAMPLES_BINDING, unused[0].as_entire_binding()),
                (SPLIT_BINDING, unused[1].as_entire_binding()),
                (WORK_COUNTS_BINDING, unused[2].as_entire_binding()),
                (WORK_LIST_BINDING, unused[3].as_entire_binding()),
                (WORK_ARGS_BINDING, unused[4].as_entire_binding()),
            ];
            entries
                .extend(own.map(|(binding, resource)| wgpu::BindGroupEntry { binding, resource }));
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("glint view"),
                layout: &pipeline.layout,
                entries: &entries,
            });
            Progressive {
                pipeline: Arc::clone(&pipeline),
                globals,
                tile,
                guard,
                bind_group,
                size: [g.width, g.height],
                guard_pixels,
                _scene: buffers,
                _unused: unused,
            }
        })
    }

    /// The globals the next samples use (a moved camera, a preview size); the size must
    /// not exceed the scene's. Clears the loop-limiter flags.
    pub fn set_globals(&mut self, ctx: &GpuContext, globals: &PackedGlobals) {
        debug_assert!(u64::from(globals.width) * u64::from(globals.height) <= self.guard_pixels);
        ctx.queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(globals));
        self.size = [globals.width, globals.height];
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.clear_buffer(&self.guard, 0, None);
        ctx.queue.submit([encoder.finish()]);
    }

    /// Encodes sample `s` of every pixel, added to the sums (`s` = 0 starts them).
    pub fn encode_sample(&self, ctx: &GpuContext, encoder: &mut wgpu::CommandEncoder, s: u32) {
        let [w, h] = self.size;
        let tile = GpuTile {
            origin: [0, 0],
            size: [w, h],
            side: w,
            level: s,
            items: 0,
            sentinel: LIMITER_SENTINEL,
        };
        // Written before the submit that carries this pass (queue writes come first).
        ctx.queue
            .write_buffer(&self.tile, 0, bytemuck::bytes_of(&tile));
        let side = self.pipeline.kernel.workgroup_side;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("view_sample"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.dispatch_workgroups(w.div_ceil(side), h.div_ceil(side), 1);
    }

    /// How many pixels tripped the software adapter's loop limiter since the last
    /// [`Self::set_globals`] (their samples are short; waits for the device).
    pub fn limited_pixels(&self, ctx: &GpuContext) -> Result<u64, GpuError> {
        let size = self.guard_pixels * 4;
        let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view guard read-back"),
            size: size.max(4),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&self.guard, 0, &staging, 0, size);
        ctx.queue.submit([encoder.finish()]);
        let flags: Vec<u32> = bytemuck::pod_collect_to_vec(&read_back(ctx, &staging, size)?);
        Ok(flags.iter().filter(|&&f| f != 0).count() as u64)
    }
}
