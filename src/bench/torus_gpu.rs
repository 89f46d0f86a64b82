//! The GPU rows of `glint bench --torus`: the same rays through glint's torus test
//! (src/tracer/geometry/torus.wgsl, the tracer's own function) and through the textbook Ferrari
//! solver (shaders/bench/torus.wgsl, twin of `bench::ferrari`), one ray per invocation.
//! Timed from submit to completion (the rays are uploaded once, the results read back
//! once, outside the timing), so the rate is the kernel's.

use super::ferrari::FERRARI_ZERO;
use super::torus_rays::TorusRay;
use crate::constants::LINEAR_WORKGROUP_SIZE;
use crate::gpu::compile::shader::{assemble_common_with, validate};
use crate::gpu::upload::buffers::read_back;
use crate::gpu::{GpuContext, GpuError};
use crate::pack::SceneFeatures;
use bytemuck::{Pod, Zeroable};
use std::time::{Duration, Instant};
use wgpu::util::DeviceExt;

/// Which solver a GPU row runs.
#[derive(Clone, Copy, Debug)]
pub enum GpuTorusSolver {
    Glint,
    Ferrari,
}

// Mirror of shaders/bench/torus.wgsl::BenchTorusParams — change both.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct BenchTorusParams {
    rin: f32,
    rout: f32,
    solver: u32,
    count: u32,
}

// Mirror of shaders/bench/torus.wgsl::BenchRay — change both.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct BenchRay {
    o: [f32; 3],
    _pad0: f32,
    d: [f32; 3],
    _pad1: f32,
}

/// Which solver a dispatch runs (`BenchTorusParams::solver`).
pub const BENCH_SOLVER_GLINT: u32 = 0;
pub const BENCH_SOLVER_FERRARI: u32 = 1;

/// WGSL `const` declarations of the benchmark's own constants, in the form of the
/// tracer's prelude (`constants::wgsl_prelude`), which does not carry them.
pub fn bench_prelude() -> String {
    format!(
        "// Generated from src/bench/ — do not edit.\n\
         const BENCH_SOLVER_GLINT: u32 = {BENCH_SOLVER_GLINT}u;\n\
         const BENCH_SOLVER_FERRARI: u32 = {BENCH_SOLVER_FERRARI}u;\n\
         const FERRARI_ZERO: f32 = {FERRARI_ZERO:e};\n"
    )
}

/// The compiled benchmark kernel on one device.
pub struct GpuTorusBench {
    ctx: GpuContext,
    pipeline: wgpu::ComputePipeline,
}

impl GpuTorusBench {
    pub fn new(ctx: GpuContext) -> Result<GpuTorusBench, GpuError> {
        let features = SceneFeatures::TORUS;
        let kernel = bench_prelude() + include_str!("../../shaders/bench/torus.wgsl");
        let source = assemble_common_with(features, ("bench/torus.wgsl", &kernel));
        validate(&source, features)?;
        let device = &ctx.device;
        let pipeline = ctx.scoped("torus benchmark shader", || {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("glint torus bench"),
                source: wgpu::ShaderSource::Wgsl(source.as_str().into()),
            });
            // The layout is derived from what the entry point uses (only its own three
            // bindings), so the tracer's scene arrays need not be bound.
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("glint torus bench"),
                layout: None,
                module: &module,
                entry_point: Some("bench_torus"),
                compilation_options: Default::default(),
                cache: None,
            })
        })?;
        Ok(GpuTorusBench { ctx, pipeline })
    }

    pub fn adapter_name(&self) -> &str {
        &self.ctx.info.name
    }

    /// t of every ray (object space, unit directions) and the fastest of `repeat` timed
    /// dispatches.
    pub fn solve(
        &self,
        rays: &[TorusRay],
        rin: f32,
        rout: f32,
        solver: GpuTorusSolver,
        repeat: usize,
    ) -> Result<(Duration, Vec<f32>), GpuError> {
        let device = &self.ctx.device;
        let params = BenchTorusParams {
            rin,
            rout,
            solver: match solver {
                GpuTorusSolver::Glint => BENCH_SOLVER_GLINT,
                GpuTorusSolver::Ferrari => BENCH_SOLVER_FERRARI,
            },
            count: rays.len() as u32,
        };
        let bench_rays: Vec<BenchRay> = rays
            .iter()
            .map(|r| BenchRay {
                o: r.o.to_array(),
                _pad0: 0.0,
                d: r.d.to_array(),
                _pad1: 0.0,
            })
            .collect();
        let size = (rays.len().max(1) * 4) as u64;
        let (bind_group, results, staging) = self.ctx.scoped("torus benchmark buffers", || {
            let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("bench params"),
                contents: bytemuck::bytes_of(&params),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let ray_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("bench rays"),
                contents: bytemuck::cast_slice(&bench_rays),
                usage: wgpu::BufferUsages::STORAGE,
            });
            let results = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("bench t"),
                size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let staging = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("bench staging"),
                size,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("glint torus bench"),
                layout: &self.pipeline.get_bind_group_layout(0),
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 20,
                        resource: params.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 21,
                        resource: ray_buffer.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 22,
                        resource: results.as_entire_binding(),
                    },
                ],
            });
            (bind_group, results, staging)
        })?;
        let groups = (rays.len() as u32).div_ceil(LINEAR_WORKGROUP_SIZE);
        let dispatch = || {
            let mut encoder = device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_compute_pass(&Default::default());
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, &bind_group, &[]);
                pass.dispatch_workgroups(groups, 1, 1);
            }
            encoder
        };
        // The first dispatch pays the driver's compile: untimed.
        self.ctx.queue.submit([dispatch().finish()]);
        self.ctx.wait()?;
        let mut best = Duration::MAX;
        for _ in 0..repeat.max(1) {
            let start = Instant::now();
            self.ctx.queue.submit([dispatch().finish()]);
            self.ctx.wait()?;
            best = best.min(start.elapsed());
        }
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_buffer_to_buffer(&results, 0, &staging, 0, size);
        self.ctx.queue.submit([encoder.finish()]);
        let bytes = read_back(&self.ctx, &staging, size)?;
        let mut ts: Vec<f32> = bytemuck::pod_collect_to_vec(&bytes);
        ts.truncate(rays.len());
        Ok((best, ts))
    }
}
