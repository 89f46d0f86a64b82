//! What the llvmpipe micro-benchmarks (`llvmpipe_loads`, `llvmpipe_branches`) share: the
//! set-up (the default adapter, the WGSL module, an output buffer of one u32 per
//! invocation), and one entry point dispatched over [`INVOCATIONS`] (workgroups of 64),
//! its bindings given as (binding, resource) pairs, timed by the host clock around submit
//! and wait, four times.

use glint::gpu::device::context::GpuContext;
use std::time::Instant;

/// Invocations of every timed dispatch.
pub const INVOCATIONS: u32 = 1 << 18;

/// A micro-benchmark's context, shader module and output buffer (one u32 per invocation).
pub struct Bench {
    pub ctx: GpuContext,
    pub module: wgpu::ShaderModule,
    pub out: wgpu::Buffer,
}

/// The default adapter's context (its name printed), `shader` compiled, the output buffer.
pub fn setup(shader: &str) -> Bench {
    let ctx = GpuContext::new(None).expect("adapter");
    println!("adapter: {}", ctx.info.name);
    let out = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: INVOCATIONS as u64 * 4,
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    });
    let module = ctx
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: None,
            source: wgpu::ShaderSource::Wgsl(shader.into()),
        });
    Bench { ctx, module, out }
}

/// Fastest of the last three of four timed dispatches, and the first (which includes
/// lavapipe's compile on first dispatch), in milliseconds.
pub struct Timing {
    pub best_ms: f64,
    pub first_ms: f64,
}

/// Dispatches `entry` of the bench's module four times with `bindings` in group 0.
pub fn time_entry(bench: &Bench, entry: &str, bindings: &[(u32, wgpu::BindingResource)]) -> Timing {
    let (ctx, module) = (&bench.ctx, &bench.module);
    let device = &ctx.device;
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: None,
        layout: None,
        module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    });
    let layout = pipeline.get_bind_group_layout(0);
    let entries: Vec<wgpu::BindGroupEntry> = bindings
        .iter()
        .map(|(binding, resource)| wgpu::BindGroupEntry {
            binding: *binding,
            resource: resource.clone(),
        })
        .collect();
    let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &layout,
        entries: &entries,
    });
    let mut times = Vec::new();
    for _ in 0..4 {
        let start = Instant::now();
        let mut enc = device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind, &[]);
            pass.dispatch_workgroups(INVOCATIONS / 64, 1, 1);
        }
        ctx.queue.submit([enc.finish()]);
        device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    Timing {
        best_ms: times[1..].iter().cloned().fold(f64::MAX, f64::min),
        first_ms: times[0],
    }
}
