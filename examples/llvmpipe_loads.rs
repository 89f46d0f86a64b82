//! Micro-benchmark: what one read costs a compute shader on the default adapter, from a
//! storage buffer against `textureLoad` from a texture, for 16-byte and 4-byte elements at
//! random and at lane-coherent addresses (2^18 invocations × 256 dependent reads each;
//! `alu_only` is the same loop without reads). On Mesa 22.3's llvmpipe the storage
//! reads cost several times the texel fetches, which is why glint keeps its scene in
//! textures (docs/gpu.md, "The scene in tables"). Run: `cargo run --release --example
//! llvmpipe_loads`.
use std::time::Instant;
use wgpu::util::DeviceExt;

const SHADER: &str = r#"
@group(0) @binding(0) var<storage, read> data: array<vec4<u32>>;
@group(0) @binding(1) var tex: texture_2d<u32>;
@group(0) @binding(2) var<storage, read_write> out_buf: array<u32>;
@group(0) @binding(3) var<storage, read> words: array<u32>;
@group(0) @binding(4) var texr: texture_2d<u32>;
@compute @workgroup_size(64)
fn ssbo_scalar(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    for (var k = 0u; k < 256u; k++) {
        let v = words[(i >> 8u) & (4u * N - 1u)];
        acc += v;
        i = i * 1664525u + 1013904223u + (v & 1u);
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn texr_scalar(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    for (var k = 0u; k < 256u; k++) {
        let j = (i >> 8u) & (4u * N - 1u);
        let v = textureLoad(texr, vec2<i32>(i32(j % 512u), i32(j / 512u)), 0).x;
        acc += v;
        i = i * 1664525u + 1013904223u + (v & 1u);
    }
    out_buf[id.x] = acc;
}
const N: u32 = 65536u;
const W: u32 = 256u;
fn next(i: u32, v: vec4<u32>, id: u32) -> u32 {
    return (i * 1664525u + 1013904223u + (v.x & 1u)) ;
}
@compute @workgroup_size(64)
fn ssbo_random(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    for (var k = 0u; k < 256u; k++) {
        let v = data[(i >> 8u) & (N - 1u)];
        acc += v.x ^ v.y ^ v.z ^ v.w;
        i = next(i, v, id.x);
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn tex_random(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    for (var k = 0u; k < 256u; k++) {
        let j = (i >> 8u) & (N - 1u);
        let v = textureLoad(tex, vec2<i32>(i32(j % W), i32(j / W)), 0);
        acc += v.x ^ v.y ^ v.z ^ v.w;
        i = next(i, v, id.x);
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn ssbo_coherent(@builtin(global_invocation_id) id: vec3<u32>) {
    var acc = 0u;
    var base = (id.x / 8u) * 8u;
    for (var k = 0u; k < 256u; k++) {
        let v = data[(base + k * 97u + (id.x & 7u)) & (N - 1u)];
        acc += v.x ^ v.y ^ v.z ^ v.w;
        base += v.x & 1u;
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn tex_coherent(@builtin(global_invocation_id) id: vec3<u32>) {
    var acc = 0u;
    var base = (id.x / 8u) * 8u;
    for (var k = 0u; k < 256u; k++) {
        let j = (base + k * 97u + (id.x & 7u)) & (N - 1u);
        let v = textureLoad(tex, vec2<i32>(i32(j % W), i32(j / W)), 0);
        acc += v.x ^ v.y ^ v.z ^ v.w;
        base += v.x & 1u;
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn alu_only(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    for (var k = 0u; k < 256u; k++) {
        let j = (i >> 8u) & (N - 1u);
        let v = vec4<u32>(j, j * 3u, j ^ 5u, j + 7u);
        acc += v.x ^ v.y ^ v.z ^ v.w;
        i = next(i, v, id.x);
    }
    out_buf[id.x] = acc;
}
"#;

fn main() {
    let ctx = glint::gpu::context::GpuContext::new(None).expect("adapter");
    println!("adapter: {}", ctx.info.name);
    let device = &ctx.device;
    let n = 65536usize;
    let words: Vec<u32> = (0..n * 4)
        .map(|i| (i as u32).wrapping_mul(2654435761))
        .collect();
    let data = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(&words),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let tex = device.create_texture_with_data(
        &ctx.queue,
        &wgpu::TextureDescriptor {
            label: None,
            size: wgpu::Extent3d {
                width: 256,
                height: 256,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Uint,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(&words),
    );
    let view = tex.create_view(&Default::default());
    let texr = device.create_texture_with_data(
        &ctx.queue,
        &wgpu::TextureDescriptor {
            label: None,
            size: wgpu::Extent3d {
                width: 512,
                height: 512,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::R32Uint,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(&words),
    );
    let viewr = texr.create_view(&Default::default());
    let invocations = 1u32 << 18;
    let out = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: invocations as u64 * 4,
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(SHADER.into()),
    });
    for entry in [
        "ssbo_scalar",
        "texr_scalar",
        "alu_only",
        "ssbo_random",
        "tex_random",
        "ssbo_coherent",
        "tex_coherent",
    ] {
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: None,
            layout: None,
            module: &module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        });
        let layout = pipeline.get_bind_group_layout(0);
        let mut entries = vec![wgpu::BindGroupEntry {
            binding: 2,
            resource: out.as_entire_binding(),
        }];
        if entry == "ssbo_random" || entry == "ssbo_coherent" {
            entries.push(wgpu::BindGroupEntry {
                binding: 0,
                resource: data.as_entire_binding(),
            });
        }
        if entry == "ssbo_scalar" {
            entries.push(wgpu::BindGroupEntry {
                binding: 3,
                resource: data.as_entire_binding(),
            });
        }
        if entry == "texr_scalar" {
            entries.push(wgpu::BindGroupEntry {
                binding: 4,
                resource: wgpu::BindingResource::TextureView(&viewr),
            });
        }
        if entry.starts_with("tex_") {
            entries.push(wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(&view),
            });
        }
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
        let reads = invocations as f64 * 256.0;
        let best = times[1..].iter().cloned().fold(f64::MAX, f64::min);
        println!(
            "{entry:14} best {best:8.1} ms  {:6.2} ns/read (first {:.1} ms)",
            best * 1e6 / reads,
            times[0]
        );
    }
}
