//! Compute pipelines specialised per feature set, compiled once per (features, kernel,
//! entry) on a context and cached there. The bind group layout depends only on the entry
//! and the kernel variant (every table of the packed scene is always bound, sampled or,
//! with `storage_tables`, as a read-only storage texture), so one layout serves every
//! feature specialisation.

use crate::gpu::compile::kernel::KernelConfig;
use crate::gpu::compile::shader::{assemble_with, validate, Entry};
use crate::gpu::device::context::GpuContext;
use crate::gpu::GpuError;
use crate::pack::SceneFeatures;
use std::sync::Arc;
use std::time::Instant;

pub use crate::gpu::compile::bindings::SCENE_TABLE_BINDINGS;
use crate::gpu::device::pipeline_cache::Lap;
pub use crate::gpu::device::pipeline_cache::{
    CompileSteps, CompileSummary, CompileTimes, CompiledPipeline, PipelineCache,
};
use crate::gpu::upload::tables::{table_layout_entry, SCENE_TABLE_FORMATS};
/// Render entry: tile uniform and output buffer.
pub const TILE_BINDING: u32 = 7;
pub const OUTPUT_BINDING: u32 = 8;
/// Probe entry: rays in, results out.
pub const PROBE_RAYS_BINDING: u32 = 9;
pub const PROBE_RESULTS_BINDING: u32 = 10;
/// Render entries: per-sample colours, adaptive split flags, CPU-fallback flags.
pub const SAMPLES_BINDING: u32 = 11;
pub const SPLIT_BINDING: u32 = 12;
pub const GUARD_BINDING: u32 = 13;
/// Adaptive AA's compacted work: per-level counts and lists of split squares, and the
/// indirect arguments of the passes over them.
pub const WORK_COUNTS_BINDING: u32 = 17;
pub const WORK_LIST_BINDING: u32 = 18;
pub const WORK_ARGS_BINDING: u32 = 19;
/// Both modules, in kernels with `lists_in_storage`: the per-ray lists' slots
/// (`src/gpu/compile/lists.rs`).
pub const LISTS_BINDING: u32 = 25;

fn storage(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn uniform(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// The bind group layout entries of `entry`: globals, the scene's tables, then the
/// entry's own (also what `spirv` renumbers and `glint kernels` lays out in Vulkan).
pub fn layout_entries(entry: Entry, kernel: KernelConfig) -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut entries = vec![uniform(0)];
    let tables = SCENE_TABLE_BINDINGS.iter().zip(SCENE_TABLE_FORMATS);
    entries.extend(tables.map(|(&b, f)| table_layout_entry(b, f, kernel.storage_tables)));
    if entry.is_render() {
        entries.push(uniform(TILE_BINDING));
        for b in [
            OUTPUT_BINDING,
            SAMPLES_BINDING,
            SPLIT_BINDING,
            GUARD_BINDING,
            WORK_COUNTS_BINDING,
            WORK_LIST_BINDING,
            WORK_ARGS_BINDING,
        ] {
            entries.push(storage(b, false));
        }
    } else {
        entries.push(storage(PROBE_RAYS_BINDING, true));
        entries.push(storage(PROBE_RESULTS_BINDING, false));
    }
    if kernel.lists_in_storage {
        entries.push(storage(LISTS_BINDING, false));
    }
    entries
}

/// The bind group layout of `entry` ([`layout_entries`]).
fn bind_group_layout(
    device: &wgpu::Device,
    entry: Entry,
    kernel: KernelConfig,
) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("glint scene"),
        entries: &layout_entries(entry, kernel),
    })
}

/// The shader module of `source`, validated and created once per context: the entries of
/// one module (every entry of the render module) share it, so naga parses and validates it
/// once, not once per entry. Records the two steps' times in `steps` when it does.
fn shader_module(
    ctx: &GpuContext,
    source: &str,
    features: SceneFeatures,
    steps: &mut CompileSteps,
) -> Result<wgpu::ShaderModule, GpuError> {
    let known = |m: &std::collections::HashMap<String, wgpu::ShaderModule>| m.get(source).cloned();
    if let Some(module) = ctx.pipelines.modules.lock().ok().and_then(|m| known(&m)) {
        return Ok(module);
    }
    let mut lap = Lap::start();
    // naga first: its messages point into the assembled source.
    validate(source, features)?;
    steps.times.validate = lap.next();
    let module = ctx.scoped("shader compilation", || {
        ctx.device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("glint tracer"),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            })
    })?;
    steps.times.shader_module = lap.next();
    if let Ok(mut map) = ctx.pipelines.modules.lock() {
        map.insert(source.to_string(), module.clone());
    }
    Ok(module)
}

/// The pipeline for (features, entry) in `ctx`'s kernel variant, compiled on first use.
pub fn get_pipeline(
    ctx: &GpuContext,
    features: SceneFeatures,
    entry: Entry,
) -> Result<Arc<CompiledPipeline>, GpuError> {
    let kernel = ctx.kernel;
    let key = (features, kernel, entry);
    if let Some(p) = ctx
        .pipelines
        .map
        .lock()
        .ok()
        .and_then(|m| m.get(&key).cloned())
    {
        return Ok(p);
    }
    let start = Instant::now();
    let mut steps = CompileSteps::default();
    let mut lap = Lap::start();
    let source = assemble_with(features, entry, kernel);
    steps.times.assemble = lap.next();
    let module = shader_module(ctx, &source, features, &mut steps)?;
    let layout_of_entry = layout_entries(entry, kernel);
    crate::gpu::device::dump::dump_kernel(ctx.dump.as_ref(), entry, &source, &layout_of_entry)?;
    lap.next();
    let device = &ctx.device;
    let stored = ctx
        .disk_cache
        .open(device, &ctx.info, &source, kernel, entry);
    steps.times.cache_load = lap.next();
    let (pipeline, layout) = ctx.scoped("shader compilation", || {
        let layout = bind_group_layout(device, entry, kernel);
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("glint"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("glint tracer"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some(entry.name()),
            compilation_options: Default::default(),
            cache: stored.cache(),
        });
        steps.times.pipeline = lap.next();
        (pipeline, layout)
    })?;
    // The error scope's wait belongs to the compile.
    steps.times.pipeline += lap.next();
    steps.disk = ctx.disk_cache.keep(&stored);
    steps.times.cache_store = lap.next();
    let compiled = Arc::new(CompiledPipeline {
        pipeline,
        layout,
        compile_time: start.elapsed(),
        steps,
        features,
        kernel,
    });
    if let Ok(mut map) = ctx.pipelines.map.lock() {
        map.insert(key, Arc::clone(&compiled));
    }
    Ok(compiled)
}
