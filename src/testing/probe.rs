//! Tier-3 kernel probes: trace seeded rays with the GPU's `closest_hit` +
//! `surface_at` through the `probe` entry point, and the same with the CPU functions, so
//! tests compare the two ray by ray.

use crate::constants::{NO_ITEM, PROBE_ANY_HIT, PROBE_SHADING_NORMAL, PROBE_SHADOW_RAY};
pub use crate::constants::{
    PROBE_ANY_HIT as ANY_HIT, PROBE_CLOSEST_HIT as CLOSEST_HIT,
    PROBE_SHADING_NORMAL as SHADING_NORMAL, PROBE_SHADOW_RAY as SHADOW_RAY,
};
use crate::gpu::compile::lists::LaneLists;
use crate::gpu::compile::shader::Entry;
use crate::gpu::pipeline::{
    get_pipeline, LISTS_BINDING, PROBE_RAYS_BINDING, PROBE_RESULTS_BINDING,
};
use crate::gpu::upload::buffers::{read_back, scene_entries, upload_scene};
use crate::gpu::{GpuContext, GpuError};
use crate::pack::{PackedScene, SceneFeatures};
use crate::tracer::base::ray::{shadow_reach, Ray};
use crate::tracer::shading::shade::shadow_blocked;
use crate::tracer::shading::smooth::smooth_normal;
use crate::tracer::shading::surface::surface_at;
use crate::tracer::traversal::traverse::{any_hit, closest_hit, NoCounters};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;

/// A probe ray.
// Mirror of src/testing/probe.wgsl::ProbeRay — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct ProbeRay {
    pub origin: [f32; 3],
    pub t_max: f32,
    /// Unit direction.
    pub dir: [f32; 3],
    /// [`PROBE_CLOSEST_HIT`], [`PROBE_ANY_HIT`], [`PROBE_SHADOW_RAY`] (then `dir` holds
    /// the light's position and `t_max` the shaded surface's magnitude) or
    /// [`PROBE_SHADING_NORMAL`].
    pub mode: u32,
}

/// What a probe reports for one ray.
// Mirror of src/testing/probe.wgsl::ProbeResult — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct ProbeResult {
    /// 1 on a hit, 0 on a miss.
    pub hit: u32,
    pub t: f32,
    pub item: u32,
    /// A CSG hit's surface (leaf instance | `CSG_FLIP`); `NO_ITEM` otherwise.
    pub part: u32,
    /// `surface_at`'s geometric normal, or in `PROBE_SHADING_NORMAL` mode in a scene
    /// with smooth meshes `smooth_normal`'s (zero on a miss).
    pub normal: [f32; 3],
    pub _pad1: u32,
}

/// The CPU's answer for one probe ray (the `probe` entry point's invocation for it;
/// [`gpu_probe`] asks the GPU for many).
// Mirror of src/testing/probe.wgsl::probe — change both.
pub fn probe(scene: &PackedScene, pr: &ProbeRay) -> ProbeResult {
    let ray = Ray {
        origin: Vec3::from(pr.origin),
        dir: Vec3::from(pr.dir),
    };
    if pr.mode == PROBE_SHADOW_RAY {
        let (origin, position) = (ray.origin, ray.dir);
        let distance = (position - origin).length();
        return ProbeResult {
            hit: shadow_blocked(scene, origin, position, pr.t_max, &mut NoCounters) as u32,
            t: shadow_reach(origin, position, distance, pr.t_max),
            item: NO_ITEM,
            part: NO_ITEM,
            normal: [0.0; 3],
            _pad1: 0,
        };
    }
    if pr.mode == PROBE_ANY_HIT {
        return ProbeResult {
            hit: any_hit(scene, &ray, pr.t_max, &mut NoCounters) as u32,
            t: 0.0,
            item: NO_ITEM,
            part: NO_ITEM,
            normal: [0.0; 3],
            _pad1: 0,
        };
    }
    let hit = closest_hit(scene, &ray, pr.t_max, &mut NoCounters);
    let mut result = ProbeResult {
        hit: 0,
        t: hit.t,
        item: hit.item,
        part: hit.part,
        normal: [0.0; 3],
        _pad1: 0,
    };
    if hit.is_hit() {
        result.hit = 1;
        let s = surface_at(scene, &ray, &hit);
        result.normal = s.normal.to_array();
        if scene.features.contains(SceneFeatures::SMOOTH) && pr.mode == PROBE_SHADING_NORMAL {
            result.normal = smooth_normal(scene, &hit, &s).to_array();
        }
    }
    result
}

/// The GPU's answers for `rays` (at least one).
pub fn gpu_probe(
    ctx: &GpuContext,
    scene: &PackedScene,
    rays: &[ProbeRay],
) -> Result<Vec<ProbeResult>, GpuError> {
    assert!(!rays.is_empty(), "probe needs at least one ray");
    let compiled = get_pipeline(ctx, scene.features, Entry::Probe)?;
    let buffers = upload_scene(ctx, scene)?;
    let device = &ctx.device;
    let result_size = (rays.len() * std::mem::size_of::<ProbeResult>()) as u64;
    let staging = ctx.scoped("probe", || {
        use wgpu::util::DeviceExt;
        let ray_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("probe rays"),
            contents: bytemuck::cast_slice(rays),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let results = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("probe results"),
            size: result_size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("probe staging"),
            size: result_size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut entries = scene_entries(&buffers);
        entries.push(wgpu::BindGroupEntry {
            binding: PROBE_RAYS_BINDING,
            resource: ray_buffer.as_entire_binding(),
        });
        entries.push(wgpu::BindGroupEntry {
            binding: PROBE_RESULTS_BINDING,
            resource: results.as_entire_binding(),
        });
        // One list slot per ray (src/gpu/compile/lists.rs), where the kernel keeps lists in storage.
        let words = LaneLists::of(scene.features, ctx.kernel).words().max(1) as u64;
        let lists = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("probe ray lists"),
            size: rays.len() as u64 * words * 4,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        if ctx.kernel.lists_in_storage {
            entries.push(wgpu::BindGroupEntry {
                binding: LISTS_BINDING,
                resource: lists.as_entire_binding(),
            });
        }
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("glint probe"),
            layout: &compiled.layout,
            entries: &entries,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&compiled.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            let group = ctx.kernel.linear_workgroup_size();
            pass.dispatch_workgroups((rays.len() as u32).div_ceil(group), 1, 1);
        }
        encoder.copy_buffer_to_buffer(&results, 0, &staging, 0, result_size);
        ctx.queue.submit([encoder.finish()]);
        staging
    })?;
    let bytes = read_back(ctx, &staging, result_size)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}
