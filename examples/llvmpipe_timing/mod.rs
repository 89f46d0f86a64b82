//! What the llvmpipe micro-benchmarks (`llvmpipe_loads`, `llvmpipe_branches`) share: one
//! entry point of a WGSL module dispatched over `invocations` (workgroups of 64), its
//! bindings given as (binding, resource) pairs, timed by the host clock around submit
//! and wait, four times.

use std::time::Instant;

/// Fastest of the last three of four timed dispatches, and the first (which includes
/// lavapipe's compile on first dispatch), in milliseconds.
pub struct Timing {
    pub best_ms: f64,
    pub first_ms: f64,
}

/// Dispatches `entry` of `module` four times with `bindings` in group 0.
pub fn time_entry(
    ctx: &glint::gpu::context::GpuContext,
    module: &wgpu::ShaderModule,
    entry: &str,
    bindings: &[(u32, wgpu::BindingResource)],
    invocations: u32,
) -> Timing {
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
            pass.dispatch_workgroups(invocations / 64, 1, 1);
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
