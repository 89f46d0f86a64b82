//! `glint view`'s frames through the wavefront kernels (the hardware variant, where
//! `view_sample` is not in the module; with glass a tree's passes and fold before the
//! store): per band, the camera pass
//! takes the frame's stratum of each pixel, the generations trace the samples as a
//! render's chunk does, and `wavefront_view_store` (`src/tracer/sampling/progressive.wgsl`) adds each
//! sample's colour to its pixel's sum as `view_sample` adds it, so the sums are the
//! megakernel's bit for bit. The queues (`samples`), counters and indirect arguments are
//! one band's, reused band after band; each dispatch has its own uniform record and bind
//! group, the records rewritten per frame (the stratum changes).

use crate::constants::ALL_STRATA;
use crate::gpu::compile::shader::Entry;
use crate::gpu::device::context::GpuContext;
use crate::gpu::frame::{binding, record_bytes, record_stride};
use crate::gpu::pipeline::{
    get_pipeline, CompiledPipeline, GUARD_BINDING, LISTS_BINDING, OUTPUT_BINDING, SAMPLES_BINDING,
    SPLIT_BINDING, TILE_BINDING, WORK_ARGS_BINDING, WORK_COUNTS_BINDING, WORK_LIST_BINDING,
};
use crate::gpu::plan::shape::WavefrontShape;
use crate::gpu::plan::view::view_wavefront_dispatches;
use crate::gpu::plan::Workgroups;
use crate::gpu::plan::{AdapterBounds, Chunk, Dispatch};
use crate::gpu::upload::buffers::{scene_entries, SceneBuffers};
use crate::gpu::GpuError;
use crate::pack::SceneFeatures;
use std::sync::Arc;

/// The buffers a band's wavefront passes bind besides the view's own: for [`ViewWavefront::bind`].
pub struct ViewBindings<'a> {
    pub scene: &'a SceneBuffers,
    pub globals: &'a wgpu::Buffer,
    pub sums: &'a wgpu::Buffer,
    pub guard: &'a wgpu::Buffer,
    pub split: &'a wgpu::Buffer,
    pub work_list: &'a wgpu::Buffer,
    /// The per-ray lists and the bytes of them the bands use, where the kernel has them.
    pub lists: Option<(&'a wgpu::Buffer, u64)>,
}

/// The wavefront kernels' pipelines and one band's queues.
pub struct ViewWavefront {
    /// In [`Entry::WAVEFRONT_VIEW`] order.
    pipelines: Vec<Arc<CompiledPipeline>>,
    shape: WavefrontShape,
    samples: wgpu::Buffer,
    work_counts: wgpu::Buffer,
    work_args: wgpu::Buffer,
    /// Bound in place of `work_args` where a pass may read its arguments from it.
    no_args: wgpu::Buffer,
    records: wgpu::Buffer,
    stride: u64,
    /// Per band, one bind group per dispatch (its record, the args it writes).
    bind_groups: Vec<Vec<wgpu::BindGroup>>,
}

impl ViewWavefront {
    /// The pipelines for `features`, and queues for a band of at most `band_pixels`.
    pub fn new(
        ctx: &GpuContext,
        features: SceneFeatures,
        shape: WavefrontShape,
        band_pixels: u64,
    ) -> Result<ViewWavefront, GpuError> {
        let entries: &[Entry] = match shape.tree {
            true => &Entry::WAVEFRONT_VIEW_TREE,
            false => &Entry::WAVEFRONT_VIEW,
        };
        let pipelines = entries
            .iter()
            .map(|&e| get_pipeline(ctx, features, e))
            .collect::<Result<Vec<_>, GpuError>>()?;
        let samples_bytes = shape.vec4s_per_sample() * band_pixels * 16;
        crate::gpu::upload::buffers::check_size(ctx, "view wavefront queues", samples_bytes)?;
        use wgpu::BufferUsages as U;
        let storage = U::STORAGE | U::COPY_DST;
        let buffer = |label, size: u64, usage| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(256),
                usage,
                mapped_at_creation: false,
            })
        };
        // The generations' indirect arguments (a tree's rounds' first; with CSG their shadow slices'); the 5
        // counters.
        let levels = shape.work_levels();
        Ok(ViewWavefront {
            samples: buffer("view wavefront queues", samples_bytes, storage),
            work_counts: buffer("view work counts", levels * 4, storage),
            work_args: buffer("view work args", levels * 24, storage | U::INDIRECT),
            no_args: buffer("view no work args", levels * 24, storage),
            records: buffer("view records", 256, U::UNIFORM | U::COPY_DST),
            stride: record_stride(ctx),
            pipelines,
            shape,
            bind_groups: Vec::new(),
        })
    }

    /// The shape the view's queues and dispatches are sized by.
    pub fn shape(&self) -> WavefrontShape {
        self.shape
    }

    /// The pipeline whose layout and kernel variant the view's passes share.
    pub fn first_pipeline(&self) -> &Arc<CompiledPipeline> {
        &self.pipelines[0]
    }

    /// Frame `stratum`'s dispatches of each of `bands`.
    fn dispatches(
        &self,
        bands: &[Chunk],
        stratum: u32,
        sentinel: u32,
        bounds: AdapterBounds,
    ) -> Vec<Vec<Dispatch>> {
        bands
            .iter()
            .map(|&band| view_wavefront_dispatches(band, self.shape, stratum, sentinel, bounds))
            .collect()
    }

    /// Makes the bind groups of `bands`' dispatches (the records are written per frame).
    pub fn bind(
        &mut self,
        ctx: &GpuContext,
        bands: &[Chunk],
        bounds: AdapterBounds,
        with: ViewBindings,
    ) {
        let queue_bytes = |band: &Chunk| band.block_pixels() * self.shape.vec4s_per_sample() * 16;
        debug_assert!(bands.iter().all(|b| queue_bytes(b) <= self.samples.size()));
        let all = self.dispatches(bands, ALL_STRATA, 0, bounds);
        let count: u64 = all.iter().map(|d| d.len() as u64).sum();
        if self.records.size() < count * self.stride {
            self.records = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("view records"),
                size: count * self.stride,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
        }
        let layout = &self.pipelines[0].layout;
        let mut k = 0u64;
        self.bind_groups =
            all.iter()
                .map(|band| {
                    band.iter()
                        .map(|d| {
                            let mut entries = scene_entries(with.scene);
                            entries[0].resource = with.globals.as_entire_binding();
                            let args = if d.writes_args {
                                &self.work_args
                            } else {
                                &self.no_args
                            };
                            let own = [
                                (
                                    TILE_BINDING,
                                    binding(&self.records, k * self.stride, self.stride),
                                ),
                                (OUTPUT_BINDING, with.sums.as_entire_binding()),
                                (SAMPLES_BINDING, self.samples.as_entire_binding()),
                                (SPLIT_BINDING, with.split.as_entire_binding()),
                                (GUARD_BINDING, with.guard.as_entire_binding()),
                                (WORK_COUNTS_BINDING, self.work_counts.as_entire_binding()),
                                (WORK_LIST_BINDING, with.work_list.as_entire_binding()),
                                (WORK_ARGS_BINDING, args.as_entire_binding()),
                            ];
                            k += 1;
                            entries.extend(own.map(|(binding, resource)| wgpu::BindGroupEntry {
                                binding,
                                resource,
                            }));
                            if let Some((lists, size)) = with.lists {
                                entries.push(wgpu::BindGroupEntry {
                                    binding: LISTS_BINDING,
                                    resource: binding(lists, 0, size.max(4)),
                                });
                            }
                            ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                                label: Some("glint view wavefront"),
                                layout,
                                entries: &entries,
                            })
                        })
                        .collect()
                })
                .collect();
    }

    /// Encodes frame `stratum` of every band: its records written, then per band the
    /// counters cleared and its passes in one compute pass.
    pub fn encode(
        &self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        bands: &[Chunk],
        stratum: u32,
        sentinel: u32,
        bounds: AdapterBounds,
    ) {
        let all = self.dispatches(bands, stratum, sentinel, bounds);
        let records = record_bytes(
            self.stride,
            all.iter()
                .flatten()
                .map(|d| d.params)
                .collect::<Vec<_>>()
                .into_iter(),
        );
        // Written before the submit that carries these passes (queue writes come first).
        ctx.queue.write_buffer(&self.records, 0, &records);
        for (band, groups) in all.iter().zip(&self.bind_groups) {
            encoder.clear_buffer(&self.work_counts, 0, None);
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("view wavefront"),
                timestamp_writes: None,
            });
            for (d, group) in band.iter().zip(groups) {
                pass.set_pipeline(&self.pipelines[d.entry].pipeline);
                pass.set_bind_group(0, group, &[]);
                match d.workgroups {
                    Workgroups::Direct(x, y) => pass.dispatch_workgroups(x, y, 1),
                    Workgroups::Indirect(at) => {
                        pass.dispatch_workgroups_indirect(&self.work_args, at)
                    }
                }
            }
        }
    }
}
