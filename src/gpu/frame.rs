//! The device side of one GPU frame: the frame-sized output and guard buffers (one block
//! per chunk, bound at the block's offset), the chunk-sized scratch arrays, every
//! dispatch's uniform record in one buffer, and the encoding of a part of the frame into
//! one command buffer (one compute pass per adaptive tile, else one in all; wgpu orders
//! the dispatches' storage accesses).
//! The read-back staging buffer receives the output, the guard flags and, where the
//! adapter has timestamp queries, the frame's GPU time — all copied once, at the end.
//! Asked for per-pass times (`glint bench --gpu --passes`), each dispatch runs in a
//! compute pass of its own between two timestamps of its own.

use super::plan::{Dispatch, FramePlan, Workgroups};
use crate::gpu::device::context::GpuContext;
use crate::gpu::pipeline::{
    CompiledPipeline, GUARD_BINDING, LISTS_BINDING, OUTPUT_BINDING, SAMPLES_BINDING, SPLIT_BINDING,
    TILE_BINDING, WORK_ARGS_BINDING, WORK_COUNTS_BINDING, WORK_LIST_BINDING,
};
use crate::gpu::upload::buffers::{scene_entries, GpuTile, SceneBuffers};
use std::num::NonZeroU64;
use std::sync::Arc;

/// Where chunk k's output and guard flags lie in the frame buffers (bytes).
#[derive(Clone, Copy, Debug)]
pub struct Block {
    pub output_offset: u64,
    pub output_size: u64,
    pub guard_offset: u64,
    pub guard_size: u64,
}

/// Timestamp queries at the start of the frame's first pass and the end of its last, or
/// (`per_dispatch`) at the start and end of each dispatch's own pass.
struct Timestamps {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    per_dispatch: bool,
    count: u32,
}

/// Most timestamp queries a frame asks for (wgpu's cap on a query set).
const MAX_QUERIES: usize = wgpu::QUERY_SET_MAX_QUERIES as usize;

/// The frame's buffers and bind groups.
pub struct Frame<'a> {
    ctx: &'a GpuContext,
    output: wgpu::Buffer,
    guard: wgpu::Buffer,
    split: wgpu::Buffer,
    work_counts: wgpu::Buffer,
    work_args: wgpu::Buffer,
    samples: wgpu::Buffer,
    work_list: wgpu::Buffer,
    /// The per-ray lists' slots (`crate::gpu::compile::lists`), bound where the kernel has them.
    lists: wgpu::Buffer,
    pub blocks: Vec<Block>,
    /// Bytes of output, then of guard flags, then 8 per timestamp in `staging`.
    pub output_bytes: u64,
    pub guard_bytes: u64,
    pub staging: wgpu::Buffer,
    /// Bytes of `staging` the frame fills (a kept buffer may be larger).
    pub staging_len: u64,
    timestamps: Option<Timestamps>,
    /// One per dispatch, in the order of `dispatches`.
    bind_groups: Vec<wgpu::BindGroup>,
}

fn align(n: u64, to: u64) -> u64 {
    n.div_ceil(to) * to
}

fn buffer(ctx: &GpuContext, label: &str, size: u64, usage: wgpu::BufferUsages) -> wgpu::Buffer {
    ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(4),
        usage,
        mapped_at_creation: false,
    })
}

/// Each chunk's output (16 B a pixel) and guard (4 B) blocks at offsets the adapter
/// accepts for a storage binding.
fn blocks(ctx: &GpuContext, plan: &FramePlan) -> (Vec<Block>, u64, u64) {
    let a = (ctx.limits.min_storage_buffer_offset_alignment as u64).max(4);
    let (mut output, mut guard) = (0, 0);
    let blocks = plan
        .chunks
        .iter()
        .map(|c| {
            let b = Block {
                output_offset: output,
                output_size: c.block_pixels() * 16,
                guard_offset: guard,
                guard_size: c.block_pixels() * 4,
            };
            output += align(b.output_size, a);
            guard += align(b.guard_size, a);
            b
        })
        .collect();
    (blocks, output, guard)
}

/// `size` bytes of `buffer` from `offset`, as a binding.
pub(super) fn binding(buffer: &wgpu::Buffer, offset: u64, size: u64) -> wgpu::BindingResource<'_> {
    wgpu::BindingResource::Buffer(wgpu::BufferBinding {
        buffer,
        offset,
        size: NonZeroU64::new(size),
    })
}

/// `buffer`'s first `len` bytes from `offset` on, as a binding (a dispatch's view of the
/// samples or work buffers: `super::plan::BindingOffsets`).
fn from(buffer: &wgpu::Buffer, offset: u64, len: u64) -> wgpu::BindingResource<'_> {
    binding(buffer, offset, len - offset)
}

/// Bytes from one dispatch's uniform record (a `GpuTile`) to the next: the adapter's
/// `min_uniform_buffer_offset_alignment`, so each can be bound at its own offset.
pub(super) fn record_stride(ctx: &GpuContext) -> u64 {
    align(
        std::mem::size_of::<GpuTile>() as u64,
        u64::from(ctx.limits.min_uniform_buffer_offset_alignment).max(1),
    )
}

/// `tiles` laid out as uniform records `stride` bytes apart (record k at k · stride).
pub(super) fn record_bytes(stride: u64, tiles: impl ExactSizeIterator<Item = GpuTile>) -> Vec<u8> {
    let mut bytes = vec![0u8; (stride * tiles.len() as u64) as usize];
    for (k, tile) in tiles.enumerate() {
        let at = k * stride as usize;
        bytes[at..at + std::mem::size_of::<GpuTile>()].copy_from_slice(bytemuck::bytes_of(&tile));
    }
    bytes
}

/// Every dispatch's uniform record, one per `min_uniform_buffer_offset_alignment`
/// bytes (the stride returned), written once before the frame's first submit.
fn records(ctx: &GpuContext, dispatches: &[Dispatch]) -> (wgpu::Buffer, u64) {
    let stride = record_stride(ctx);
    let usage = wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST;
    let records = buffer(
        ctx,
        "dispatch records",
        stride * dispatches.len() as u64,
        usage,
    );
    let bytes = record_bytes(stride, dispatches.iter().map(|d| d.params));
    ctx.queue.write_buffer(&records, 0, &bytes);
    (records, stride)
}

/// The frame's timestamp queries, where the device has them: two, or two per dispatch
/// when `per_dispatch` (and the query set can hold them).
fn timestamps(ctx: &GpuContext, dispatches: usize, per_dispatch: bool) -> Option<Timestamps> {
    use wgpu::BufferUsages as U;
    let per_dispatch = per_dispatch && 2 * dispatches <= MAX_QUERIES;
    let count = if per_dispatch {
        2 * dispatches as u32
    } else {
        2
    };
    ctx.device
        .features()
        .contains(wgpu::Features::TIMESTAMP_QUERY)
        .then(|| Timestamps {
            queries: ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("frame time"),
                ty: wgpu::QueryType::Timestamp,
                count,
            }),
            resolve: buffer(
                ctx,
                "frame time",
                8 * count as u64,
                U::QUERY_RESOLVE | U::COPY_SRC,
            ),
            per_dispatch,
            count,
        })
}

impl<'a> Frame<'a> {
    /// Creates the frame's buffers and one bind group per dispatch, and timestamps per
    /// dispatch when `pass_times` (call inside the
    /// frame's error scope).
    pub fn new(
        ctx: &'a GpuContext,
        plan: &FramePlan,
        scene: &SceneBuffers,
        layout: &wgpu::BindGroupLayout,
        dispatches: &[Dispatch],
        pass_times: bool,
    ) -> Frame<'a> {
        use wgpu::BufferUsages as U;
        let storage = U::STORAGE | U::COPY_SRC | U::COPY_DST;
        let (blocks, output_bytes, guard_bytes) = blocks(ctx, plan);
        // The large buffers come from the context's pool (`crate::gpu::device::scratch`).
        let scratch = |size: u64, usage| ctx.scratch.take(&ctx.device, size, usage);
        let output = scratch(output_bytes, storage);
        let guard = scratch(guard_bytes, storage);
        let samples = scratch(plan.samples_len * 16, storage);
        let split = scratch(plan.split_len * 4, storage);
        let work_counts = buffer(ctx, "work counts", plan.work_levels * 4, storage);
        let work_list = scratch(plan.split_len * 4, storage);
        let lists = scratch(plan.lists_len * 4, U::STORAGE);
        let work_args = buffer(
            ctx,
            "work args",
            plan.work_levels * 24,
            storage | U::INDIRECT,
        );
        // Bound in place of work_args where a dispatch may read its arguments from it.
        let no_args = buffer(ctx, "no work args", plan.work_levels * 24, storage);
        let (records, stride) = records(ctx, dispatches);
        let (samples_len, work_len) = (plan.samples_len * 16, plan.work_levels * 4);
        let bind_groups = dispatches
            .iter()
            .enumerate()
            .map(|(k, d)| {
                let b = blocks[d.chunk];
                let mut entries = scene_entries(scene);
                let args = if d.writes_args { &work_args } else { &no_args };
                let (from_samples, from_work) = (d.offsets.samples, d.offsets.work);
                let own = [
                    (TILE_BINDING, binding(&records, k as u64 * stride, stride)),
                    (
                        OUTPUT_BINDING,
                        binding(&output, b.output_offset, b.output_size),
                    ),
                    (SAMPLES_BINDING, from(&samples, from_samples, samples_len)),
                    (SPLIT_BINDING, split.as_entire_binding()),
                    (GUARD_BINDING, binding(&guard, b.guard_offset, b.guard_size)),
                    (WORK_COUNTS_BINDING, from(&work_counts, from_work, work_len)),
                    (WORK_LIST_BINDING, work_list.as_entire_binding()),
                    (WORK_ARGS_BINDING, from(args, from_work, 6 * work_len)),
                ];
                entries.extend(
                    own.map(|(binding, resource)| wgpu::BindGroupEntry { binding, resource }),
                );
                if ctx.kernel.lists_in_storage {
                    // Exactly the plan's slots: the kernel counts them by the binding's length.
                    entries.push(wgpu::BindGroupEntry {
                        binding: LISTS_BINDING,
                        resource: binding(&lists, 0, plan.lists_len.max(1) * 4),
                    });
                }
                ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("glint dispatch"),
                    layout,
                    entries: &entries,
                })
            })
            .collect();
        let timestamps = timestamps(ctx, dispatches.len(), pass_times);
        let stamps = timestamps.as_ref().map_or(0, |t| 8 * t.count as u64);
        let staging_len = output_bytes + guard_bytes + stamps;
        let staging = scratch(staging_len, U::MAP_READ | U::COPY_DST);
        Frame {
            ctx,
            output,
            guard,
            split,
            work_counts,
            work_args,
            samples,
            work_list,
            lists,
            blocks,
            output_bytes,
            guard_bytes,
            staging,
            staging_len,
            timestamps,
            bind_groups,
        }
    }

    /// Whether the frame measures its GPU time with timestamp queries.
    pub fn timed(&self) -> bool {
        self.timestamps.is_some()
    }

    /// Whether each dispatch has its own pair of timestamps (then `staging` holds the
    /// start and end of dispatch k at 2k and 2k + 1, else the frame's start and end).
    pub fn timed_per_dispatch(&self) -> bool {
        self.timestamps.as_ref().is_some_and(|t| t.per_dispatch)
    }

    /// Encodes dispatches `range` (of the frame's `dispatches`) as one command buffer:
    /// the first part also clears the guard flags, the last copies the results out. A
    /// dispatch that starts an adaptive tile starts a new compute pass, after clearing
    /// the tile's split flags and work counts.
    pub fn encode_part(
        &self,
        pipelines: &[Arc<CompiledPipeline>],
        dispatches: &[Dispatch],
        range: std::ops::Range<usize>,
        first: bool,
        last: bool,
    ) -> wgpu::CommandBuffer {
        let mut encoder = self.ctx.device.create_command_encoder(&Default::default());
        if first {
            encoder.clear_buffer(&self.guard, 0, None);
        }
        let mut starts: Vec<usize> = range
            .clone()
            .filter(|&k| k == range.start || dispatches[k].clears_work)
            .collect();
        starts.push(range.end);
        for (s, pair) in starts.windows(2).enumerate() {
            if dispatches[pair[0]].clears_work {
                encoder.clear_buffer(&self.split, 0, None);
                encoder.clear_buffer(&self.work_counts, 0, None);
            }
            if self.timed_per_dispatch() {
                for k in pair[0]..pair[1] {
                    let at = 2 * k as u32;
                    self.encode_pass(
                        &mut encoder,
                        pipelines,
                        dispatches,
                        k..k + 1,
                        Some((Some(at), Some(at + 1))),
                    );
                }
                continue;
            }
            let (begin, end) = (first && s == 0, last && s + 2 == starts.len());
            let writes = (begin || end).then_some((begin.then_some(0), end.then_some(1)));
            self.encode_pass(
                &mut encoder,
                pipelines,
                dispatches,
                pair[0]..pair[1],
                writes,
            );
        }
        if last {
            let (o, g) = (self.output_bytes, self.guard_bytes);
            encoder.copy_buffer_to_buffer(&self.output, 0, &self.staging, 0, o);
            encoder.copy_buffer_to_buffer(&self.guard, 0, &self.staging, o, g);
            if let Some(t) = &self.timestamps {
                encoder.resolve_query_set(&t.queries, 0..t.count, &t.resolve, 0);
                let bytes = 8 * t.count as u64;
                encoder.copy_buffer_to_buffer(&t.resolve, 0, &self.staging, o + g, bytes);
            }
        }
        encoder.finish()
    }

    /// One compute pass over dispatches `range`, with timestamps at its start and end
    /// where `writes` names query indices.
    fn encode_pass(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pipelines: &[Arc<CompiledPipeline>],
        dispatches: &[Dispatch],
        range: std::ops::Range<usize>,
        writes: Option<(Option<u32>, Option<u32>)>,
    ) {
        let timestamp_writes = self
            .timestamps
            .as_ref()
            .zip(writes)
            .map(|(t, (begin, end))| wgpu::ComputePassTimestampWrites {
                query_set: &t.queries,
                beginning_of_pass_write_index: begin,
                end_of_pass_write_index: end,
            });
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("glint frame part"),
            timestamp_writes,
        });
        let run = dispatches.iter().zip(&self.bind_groups);
        for (d, bind_group) in run.take(range.end).skip(range.start) {
            pass.set_pipeline(&pipelines[d.entry].pipeline);
            pass.set_bind_group(0, bind_group, &[]);
            match d.workgroups {
                Workgroups::Direct(x, y) => pass.dispatch_workgroups(x, y, 1),
                Workgroups::Indirect(at) => pass.dispatch_workgroups_indirect(&self.work_args, at),
            }
        }
    }
}

impl Drop for Frame<'_> {
    /// The large buffers go back to the context's pool for the next frame (the queue
    /// orders that frame's work after this one's).
    fn drop(&mut self) {
        let buffers = [
            &self.output,
            &self.guard,
            &self.samples,
            &self.split,
            &self.work_list,
            &self.lists,
            &self.staging,
        ];
        self.ctx.scratch.give_back(buffers.map(|b| b.clone()));
    }
}
