//! `glint view`'s device side: progressive uniform anti-aliasing on the device that also
//! presents the window. The per-pixel sums live in one storage buffer ([`SumBuffer`])
//! for the whole session: `view_sample` (src/tracer/sampling/progressive.wgsl) adds sample k of every pixel
//! to it in frame k, the window's present pass reads it, and the CPU tracer's sums are
//! uploaded into it when that tracer refines instead. Nothing is read back except for S
//! (save) and, on software adapters, the loop limiter's flags, so a refining frame on a
//! hardware GPU costs its dispatches and one present.
//!
//! The window is dispatched in full-width bands ([`view_bands`]), as many as the per-ray
//! lists' slots need (`crate::gpu::plan::slot_budget`, the rule `glint render`'s chunks
//! follow): a kernel that keeps its lists in storage (`crate::gpu::compile::lists`, the hardware
//! variant) has a slot for each pixel of a band, so the view runs the same kernel variant
//! as `glint render`, with no private arrays for a GPU compiler to put in scratch memory.
//! Without lists in storage the window is one band, one dispatch.
//!
//! On software adapters the kernel checks Mesa's loop limiter (`ITERATION_GUARD`): a
//! pixel whose sample tripped it keeps its sum and is flagged, and
//! [`Progressive::trace_sample`] re-traces that sample on the CPU tracer
//! (`crate::tracer::sampling::progressive::view_sample`, the kernel's twin) into the sum, as `glint
//! render` re-renders its flagged pixels (`crate::gpu::render`); so the view converges to the
//! render's image there too.
//!
//! In the hardware variant the frames go through the wavefront kernels (with glass, a
//! tree's passes and fold) instead of `view_sample` ([`ViewWavefront`]: the same sums, bit for bit), the
//! bands then also bounded by their queues.
//!
//! The view's own copy of the globals (camera moved, preview size) is a uniform written
//! before each restart; the scene's tables are uploaded once per scene load.

use crate::constants::ALL_STRATA;
use crate::gpu::compile::shader::Entry;
use crate::gpu::device::context::GpuContext;
use crate::gpu::frame::{binding, record_bytes, record_stride};
use crate::gpu::pipeline::{
    get_pipeline, CompiledPipeline, GUARD_BINDING, LISTS_BINDING, OUTPUT_BINDING, SAMPLES_BINDING,
    SPLIT_BINDING, TILE_BINDING, WORK_ARGS_BINDING, WORK_COUNTS_BINDING, WORK_LIST_BINDING,
};
use crate::gpu::plan::chunking::{bands, slot_budget};
use crate::gpu::plan::{AdapterBounds, Chunk};
use crate::gpu::render::adapter_bounds;
use crate::gpu::upload::buffers::{
    read_back, scene_entries, upload_scene, GpuTile, SceneBuffers, LIMITER_SENTINEL,
};
use crate::gpu::view::view_wavefront::{ViewBindings, ViewWavefront};
use crate::gpu::wavefront::view_wavefront_shape;
use crate::gpu::GpuError;
use crate::pack::{PackedGlobals, PackedScene};
use crate::tiling::PixelRect;
use crate::tracer::sampling::progressive::view_sample;
use rayon::prelude::*;
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
        crate::gpu::upload::buffers::check_size(ctx, "view sums", pixels * SUM_BYTES)?;
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

/// The full-width bands a `width` × `height` window is dispatched in: as many rows each
/// as give every pixel of a band a list slot under `bounds` (one band when the kernel
/// keeps no lists in storage), fit one 2-D dispatch and, through the wavefront kernels,
/// whose queues fit one binding. A band is laid out `width` pixels a row, so its pixel
/// (x, y) has slot y·width + x.
pub fn view_bands(width: u32, height: u32, bounds: AdapterBounds) -> Vec<Chunk> {
    let (w, h) = (width.max(1), height.max(1));
    let dispatch_rows = bounds.max_workgroups.saturating_mul(bounds.workgroup_side);
    // A tree's generation: up to TREE_PATHS_PER_SAMPLE paths (list slots) a pixel.
    let per_pixel = bounds.wavefront.map_or(1, |s| s.slots_per_sample());
    let mut rows = (slot_budget(bounds) / (per_pixel * u64::from(w))).clamp(1, u64::from(h)) as u32;
    if let Some(shape) = bounds.wavefront {
        let per_row = u64::from(w) * shape.vec4s_per_sample() * 16;
        rows = rows.min((bounds.max_binding / per_row).clamp(1, u64::from(h)) as u32);
    }
    bands(PixelRect::full(w, h), rows.min(dispatch_rows), 1)
}

/// What the loop-limiter fallback did since the last restart ([`Progressive::set_globals`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Retraced {
    /// Samples re-traced on the CPU tracer.
    pub samples: u64,
    /// The distinct pixels they were of.
    pub pixels: u64,
}

/// A scene on the device, ready to add one sample per pixel per [`Self::encode_sample`]
/// (or [`Self::trace_sample`], which also re-traces what the loop limiter cut short).
pub struct Progressive {
    /// `view_sample`, or the wavefront's first kernel (the layout and kernel variant).
    pipeline: Arc<CompiledPipeline>,
    /// The wavefront kernels, where the kernel has them for the scene.
    wavefront: Option<ViewWavefront>,
    globals: wgpu::Buffer,
    guard: wgpu::Buffer,
    /// The sums the samples are added to (a handle on the session's [`SumBuffer`]).
    sums: wgpu::Buffer,
    /// The per-ray lists' slots (`crate::gpu::compile::lists`), as many as the full image's widest
    /// band has pixels (a preview's bands have no more); unbound where the kernel keeps
    /// its lists in private arrays.
    lists: wgpu::Buffer,
    lane_words: u32,
    bounds: AdapterBounds,
    /// The bands of the current size, each band's tile record (`record_stride` bytes
    /// apart in `tiles`) and bind group.
    bands: Vec<Chunk>,
    tiles: wgpu::Buffer,
    record_stride: u64,
    bind_groups: Vec<wgpu::BindGroup>,
    /// The size the globals say (the full image or a preview).
    size: [u32; 2],
    /// Pixels the guard buffer holds (the full image).
    guard_pixels: u64,
    /// The limiter check's loop length ([`GpuTile::sentinel`]; a test hook).
    sentinel: u32,
    /// The loop-limiter fallback since the last restart, and the pixels it re-traced.
    retraced: Retraced,
    retraced_pixels: Vec<bool>,
    /// Kept alive for the bind groups.
    scene: SceneBuffers,
    unused: Vec<wgpu::Buffer>,
}

/// Bytes of the per-ray lists that `bands` need: `per_pixel` slots of `lane_words` words
/// for each pixel of the largest band (a tree's: its paths; the kernel learns its slots
/// from the binding's length, lists.wgsl::begin_lane).
fn lists_bytes(bands: &[Chunk], lane_words: u32, per_pixel: u64) -> u64 {
    let slots = bands.iter().map(Chunk::block_pixels).max().unwrap_or(1);
    slots * per_pixel * 4 * u64::from(lane_words)
}

impl Progressive {
    /// Uploads `scene`, compiles (or finds) its `view_sample` pipeline and binds `sums`.
    pub fn new(
        ctx: &GpuContext,
        scene: &PackedScene,
        sums: &SumBuffer,
    ) -> Result<Progressive, GpuError> {
        let shape = view_wavefront_shape(ctx.kernel, scene);
        let g = &scene.globals;
        let bounds = AdapterBounds {
            wavefront: shape,
            ..adapter_bounds(ctx, ctx.kernel, scene.features)
        };
        let full_bands = view_bands(g.width, g.height, bounds);
        let wavefront = match shape {
            Some(shape) => {
                // A preview's narrower rows may make a band of more pixels than the
                // full image's widest, up to what one binding of queues holds.
                let widest = full_bands.iter().map(Chunk::block_pixels).max();
                let queues = bounds.max_binding / (shape.vec4s_per_sample() * 16);
                let pixels = u64::from(g.width) * u64::from(g.height);
                let band_pixels = widest.unwrap_or(1).max(queues.min(pixels));
                Some(ViewWavefront::new(ctx, scene.features, shape, band_pixels)?)
            }
            None => None,
        };
        let pipeline = match &wavefront {
            Some(w) => Arc::clone(w.first_pipeline()),
            None => get_pipeline(ctx, scene.features, Entry::ViewSample)?,
        };
        let buffers = upload_scene(ctx, scene)?;
        let guard_pixels = u64::from(g.width) * u64::from(g.height);
        let lane_words = bounds.lane_list_words;
        let per_pixel = shape.map_or(1, |s| s.slots_per_sample());
        let lists_bytes = lists_bytes(&full_bands, lane_words, per_pixel);
        if lane_words > 0 {
            crate::gpu::upload::buffers::check_size(ctx, "view per-ray lists", lists_bytes)?;
        }
        use wgpu::BufferUsages as U;
        ctx.scoped("view setup", || {
            let device = &ctx.device;
            let globals = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("view globals"),
                contents: bytemuck::bytes_of(g),
                usage: U::UNIFORM | U::COPY_DST,
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
            let lists = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("view per-ray lists"),
                size: lists_bytes.max(4),
                usage: U::STORAGE,
                mapped_at_creation: false,
            });
            // view_sample reads none of the other AA passes' buffers; the layout (one for
            // every render entry) still has them.
            let unused: Vec<wgpu::Buffer> = (0..5).map(|_| storage("unused", 256)).collect();
            let tiles = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("view tiles"),
                size: record_stride(ctx),
                usage: U::UNIFORM | U::COPY_DST,
                mapped_at_creation: false,
            });
            let mut progressive = Progressive {
                pipeline: Arc::clone(&pipeline),
                wavefront,
                globals,
                guard,
                sums: sums.buffer.clone(),
                lists,
                lane_words,
                bounds,
                bands: Vec::new(),
                tiles,
                record_stride: record_stride(ctx),
                bind_groups: Vec::new(),
                size: [g.width, g.height],
                guard_pixels,
                sentinel: LIMITER_SENTINEL,
                retraced: Retraced::default(),
                retraced_pixels: vec![false; guard_pixels as usize],
                scene: buffers,
                unused,
            };
            progressive.bind(ctx, g.width, g.height);
            progressive
        })
    }

    /// Plans the bands of a `width` × `height` image and makes their bind groups.
    fn bind(&mut self, ctx: &GpuContext, width: u32, height: u32) {
        let bands = view_bands(width, height, self.bounds);
        let device = &ctx.device;
        let records = self.record_stride * bands.len() as u64;
        if self.tiles.size() < records {
            self.tiles = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("view tiles"),
                size: records,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
        }
        let per_pixel = self
            .wavefront
            .as_ref()
            .map_or(1, |w| w.shape().slots_per_sample());
        let lists_size = lists_bytes(&bands, self.lane_words, per_pixel);
        debug_assert!(lists_size <= self.lists.size());
        if let Some(wavefront) = &mut self.wavefront {
            let lists = self.pipeline.kernel.lists_in_storage;
            let with = ViewBindings {
                scene: &self.scene,
                globals: &self.globals,
                sums: &self.sums,
                guard: &self.guard,
                split: &self.unused[1],
                work_list: &self.unused[3],
                lists: lists.then_some((&self.lists, lists_size)),
            };
            wavefront.bind(ctx, &bands, self.bounds, with);
            self.bind_groups = Vec::new();
            self.bands = bands;
            return;
        }
        let tile_size = std::mem::size_of::<GpuTile>() as u64;
        self.bind_groups = (0..bands.len() as u64)
            .map(|k| {
                let mut entries = scene_entries(&self.scene);
                entries[0].resource = self.globals.as_entire_binding();
                let own = [
                    (
                        TILE_BINDING,
                        binding(&self.tiles, k * self.record_stride, tile_size),
                    ),
                    (OUTPUT_BINDING, self.sums.as_entire_binding()),
                    (GUARD_BINDING, self.guard.as_entire_binding()),
                    (SAMPLES_BINDING, self.unused[0].as_entire_binding()),
                    (SPLIT_BINDING, self.unused[1].as_entire_binding()),
                    (WORK_COUNTS_BINDING, self.unused[2].as_entire_binding()),
                    (WORK_LIST_BINDING, self.unused[3].as_entire_binding()),
                    (WORK_ARGS_BINDING, self.unused[4].as_entire_binding()),
                ];
                entries.extend(
                    own.map(|(binding, resource)| wgpu::BindGroupEntry { binding, resource }),
                );
                if self.pipeline.kernel.lists_in_storage {
                    entries.push(wgpu::BindGroupEntry {
                        binding: LISTS_BINDING,
                        resource: binding(&self.lists, 0, lists_size.max(4)),
                    });
                }
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("glint view"),
                    layout: &self.pipeline.layout,
                    entries: &entries,
                })
            })
            .collect();
        self.bands = bands;
    }

    /// The globals the next samples use (a moved camera, a preview size); the size must
    /// not exceed the scene's. Restarts the loop-limiter fallback's counts.
    pub fn set_globals(&mut self, ctx: &GpuContext, globals: &PackedGlobals) {
        debug_assert!(u64::from(globals.width) * u64::from(globals.height) <= self.guard_pixels);
        ctx.queue
            .write_buffer(&self.globals, 0, bytemuck::bytes_of(globals));
        if [globals.width, globals.height] != self.size {
            self.bind(ctx, globals.width, globals.height);
        }
        self.size = [globals.width, globals.height];
        self.retraced = Retraced::default();
        self.retraced_pixels.fill(false);
    }

    /// Whether the frames go through the wavefront kernels (else `view_sample`).
    pub fn runs_wavefront(&self) -> bool {
        self.wavefront.is_some()
    }

    /// The bands the window is dispatched in, at the current size.
    pub fn bands(&self) -> &[Chunk] {
        &self.bands
    }

    /// Whether the kernel checks the software adapter's loop limiter: then frames go
    /// through [`Self::trace_sample`], which re-traces what it cut short.
    pub fn checks_limiter(&self) -> bool {
        self.pipeline.kernel.iteration_guard
    }

    /// Encodes sample `s` of every pixel, added to the sums (`s` = 0 starts them); on a
    /// kernel that [checks the limiter](Self::checks_limiter), the pixels it cut short
    /// keep their sums and are flagged for [`Self::trace_sample`]'s fallback.
    pub fn encode_sample(&self, ctx: &GpuContext, encoder: &mut wgpu::CommandEncoder, s: u32) {
        if let Some(wavefront) = &self.wavefront {
            let bounds = self.bounds;
            wavefront.encode(ctx, encoder, &self.bands, s, self.sentinel, bounds);
            return;
        }
        let records = record_bytes(
            self.record_stride,
            self.bands.iter().map(|band| GpuTile {
                origin: band.origin,
                size: band.size,
                side: band.side,
                level: s,
                items: 0,
                sentinel: self.sentinel,
                stratum: ALL_STRATA,
                slice: 0,
            }),
        );
        // Written before the submit that carries this pass (queue writes come first).
        ctx.queue.write_buffer(&self.tiles, 0, &records);
        if self.checks_limiter() {
            encoder.clear_buffer(&self.guard, 0, None);
        }
        let side = self.pipeline.kernel.workgroup_side;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("view_sample"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline.pipeline);
        for (band, group) in self.bands.iter().zip(&self.bind_groups) {
            pass.set_bind_group(0, group, &[]);
            let [w, h] = band.size;
            pass.dispatch_workgroups(w.div_ceil(side), h.div_ceil(side), 1);
        }
    }

    /// Adds sample `s` of every pixel of `scene` (whose globals [`Self::set_globals`]
    /// gave) to `sums`, waits for it and, where the loop limiter cut a pixel's sample
    /// short, re-traces that sample on the CPU tracer into the pixel's sum: the sum is
    /// then what `view_sample` on the CPU would have added to it. Returns how many
    /// samples were re-traced.
    pub fn trace_sample(
        &mut self,
        ctx: &GpuContext,
        scene: &PackedScene,
        sums: &SumBuffer,
        s: u32,
    ) -> Result<u64, GpuError> {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        self.encode_sample(ctx, &mut encoder, s);
        ctx.queue.submit([encoder.finish()]);
        if !self.checks_limiter() {
            return Ok(0);
        }
        let [w, h] = self.size;
        debug_assert_eq!([scene.globals.width, scene.globals.height], self.size);
        let pixels = u64::from(w) * u64::from(h);
        let flagged: Vec<usize> = self
            .limited_flags(ctx, pixels)?
            .iter()
            .enumerate()
            .filter(|(_, &f)| f != 0)
            .map(|(p, _)| p)
            .collect();
        if flagged.is_empty() {
            return Ok(0);
        }
        let mut all = sums.read(ctx, pixels)?;
        let fixed: Vec<[f32; 4]> = flagged
            .par_iter()
            .map(|&p| {
                let (x, y) = ((p % w as usize) as u32, (p / w as usize) as u32);
                view_sample(scene, x, y, s, all[p])
            })
            .collect();
        for (&p, sum) in flagged.iter().zip(fixed) {
            all[p] = sum;
            if !self.retraced_pixels[p] {
                self.retraced_pixels[p] = true;
                self.retraced.pixels += 1;
            }
        }
        self.retraced.samples += flagged.len() as u64;
        sums.upload(ctx, &all);
        Ok(flagged.len() as u64)
    }

    /// What the loop-limiter fallback re-traced since the last restart.
    pub fn retraced(&self) -> Retraced {
        self.retraced
    }

    /// The loop-limiter check's sentinel, for tests: more iterations than the limiter
    /// allows (65 535) trip it in every invocation of a kernel that checks it.
    #[doc(hidden)]
    pub fn set_limiter_sentinel(&mut self, sentinel: u32) {
        self.sentinel = sentinel;
    }

    /// The first `pixels` loop-limiter flags of the last frame (waits for the device).
    fn limited_flags(&self, ctx: &GpuContext, pixels: u64) -> Result<Vec<u32>, GpuError> {
        let size = pixels * 4;
        let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("view guard read-back"),
            size: size.max(4),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&self.guard, 0, &staging, 0, size);
        ctx.queue.submit([encoder.finish()]);
        Ok(bytemuck::pod_collect_to_vec(&read_back(
            ctx, &staging, size,
        )?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bounds(words: u32, max_binding: u64) -> AdapterBounds {
        AdapterBounds {
            max_binding,
            max_workgroups: 65_535,
            workgroup_side: 8,
            lane_list_words: words,
            wavefront: None,
        }
    }

    /// Every row in exactly one band, every band full width and within the slots.
    #[test]
    fn bands_cover_the_window_once_within_the_slots() {
        for (w, h) in [(640, 400), (80, 50), (1, 1), (37, 5), (4096, 3000)] {
            for b in [
                bounds(0, 128 << 20),
                bounds(562, 128 << 20),
                bounds(272, 4 << 20),
            ] {
                let bands = view_bands(w, h, b);
                let mut next = 0;
                for band in &bands {
                    assert_eq!((band.origin, band.size[0], band.side), ([0, next], w, w));
                    assert!(band.block_pixels() <= slot_budget(b).max(u64::from(w)));
                    next += band.size[1];
                }
                assert_eq!(next, h, "{w}×{h} {b:?}");
                if b.lane_list_words == 0 {
                    assert_eq!(bands.len(), 1, "no lists: the window in one dispatch");
                }
            }
        }
        // scrabble.lua's 562 words a slot at 4096 × 3000: 256 MiB of slots, several bands.
        assert!(view_bands(4096, 3000, bounds(562, 1 << 30)).len() > 1);
    }
}
