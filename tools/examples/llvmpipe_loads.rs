//! Micro-benchmark: what one read costs a compute shader on the default adapter, from a
//! storage buffer against `textureLoad` from a texture, for 16-byte and 4-byte elements at
//! random and at lane-coherent addresses (2^18 invocations × 256 dependent reads each;
//! `alu_only` is the same loop without reads). On Mesa 22.3's llvmpipe the storage
//! reads cost several times the texel fetches, which is why glint keeps its scene in
//! textures (docs/gpu.md, "The scene in tables"). The `_4k` entries read 4 096 elements
//! of 16 bytes from a sampled 2-D texture, a uniform buffer and a 1-D texture, and
//! `stex_random` reads a 2-D texture bound as a read-only storage texture (the other
//! kinds of binding that could hold glint's tables; docs/gpu.md, "Instructions counted
//! on llvmpipe"). Run: `cargo run --release --example llvmpipe_loads`.
#[path = "llvmpipe_timing/mod.rs"]
mod llvmpipe_timing;
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
@group(0) @binding(5) var<uniform> udata: array<vec4<u32>, 4096>;
@group(0) @binding(6) var tex1: texture_1d<u32>;
@group(0) @binding(7) var stex: texture_storage_2d<rgba32uint, read>;
@compute @workgroup_size(64)
fn tex_random_4k(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    for (var k = 0u; k < 256u; k++) {
        let j = (i >> 8u) & 4095u;
        let v = textureLoad(tex, vec2<i32>(i32(j % W), i32(j / W)), 0);
        acc += v.x ^ v.y ^ v.z ^ v.w;
        i = next(i, v, id.x);
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn ubo_random_4k(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    for (var k = 0u; k < 256u; k++) {
        let v = udata[(i >> 8u) & 4095u];
        acc += v.x ^ v.y ^ v.z ^ v.w;
        i = next(i, v, id.x);
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn tex1d_random_4k(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    for (var k = 0u; k < 256u; k++) {
        let v = textureLoad(tex1, i32((i >> 8u) & 4095u), 0);
        acc += v.x ^ v.y ^ v.z ^ v.w;
        i = next(i, v, id.x);
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn stex_random(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    for (var k = 0u; k < 256u; k++) {
        let j = (i >> 8u) & (N - 1u);
        let v = textureLoad(stex, vec2<i32>(i32(j % W), i32(j / W)));
        acc += v.x ^ v.y ^ v.z ^ v.w;
        i = next(i, v, id.x);
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
    let bench = llvmpipe_timing::setup(SHADER);
    let ctx = &bench.ctx;
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
    let view = texture_view(ctx, 256, wgpu::TextureFormat::Rgba32Uint, &words);
    let viewr = texture_view(ctx, 512, wgpu::TextureFormat::R32Uint, &words);
    let ubo = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(&words[..4096 * 4]),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let (d1, d2) = (wgpu::TextureDimension::D1, wgpu::TextureDimension::D2);
    let rgba = wgpu::TextureFormat::Rgba32Uint;
    let sampled = wgpu::TextureUsages::TEXTURE_BINDING;
    let view1 = view_of(ctx, d1, [4096, 1], rgba, sampled, &words[..4096 * 4]);
    // Bound as a read-only storage texture.
    let storage = wgpu::TextureUsages::STORAGE_BINDING;
    let sview = view_of(ctx, d2, [256, 256], rgba, storage, &words);
    for entry in [
        "ssbo_scalar",
        "texr_scalar",
        "alu_only",
        "ssbo_random",
        "tex_random",
        "ssbo_coherent",
        "tex_coherent",
        "tex_random_4k",
        "ubo_random_4k",
        "tex1d_random_4k",
        "stex_random",
    ] {
        let mut bindings = vec![(2, bench.out.as_entire_binding())];
        if entry == "ssbo_random" || entry == "ssbo_coherent" {
            bindings.push((0, data.as_entire_binding()));
        }
        if entry == "ssbo_scalar" {
            bindings.push((3, data.as_entire_binding()));
        }
        if entry == "texr_scalar" {
            bindings.push((4, wgpu::BindingResource::TextureView(&viewr)));
        }
        if entry.starts_with("tex_") {
            bindings.push((1, wgpu::BindingResource::TextureView(&view)));
        }
        if entry == "ubo_random_4k" {
            bindings.push((5, ubo.as_entire_binding()));
        }
        if entry == "tex1d_random_4k" {
            bindings.push((6, wgpu::BindingResource::TextureView(&view1)));
        }
        if entry == "stex_random" {
            bindings.push((7, wgpu::BindingResource::TextureView(&sview)));
        }
        let timing = llvmpipe_timing::time_entry(&bench, entry, &bindings);
        let (best, first) = (timing.best_ms, timing.first_ms);
        let reads = llvmpipe_timing::INVOCATIONS as f64 * 256.0;
        println!(
            "{entry:14} best {best:8.1} ms  {:6.2} ns/read (first {:.1} ms)",
            best * 1e6 / reads,
            first
        );
    }
}

/// A `side`×`side` texture of `format` holding `words` (as many as it takes), as a view.
fn texture_view(
    ctx: &glint::gpu::device::context::GpuContext,
    side: u32,
    format: wgpu::TextureFormat,
    words: &[u32],
) -> wgpu::TextureView {
    let usage = wgpu::TextureUsages::TEXTURE_BINDING;
    view_of(
        ctx,
        wgpu::TextureDimension::D2,
        [side, side],
        format,
        usage,
        words,
    )
}

/// A texture of `dimension`, `[width, height]`, `format` and `usage` holding `words`, as a
/// view.
fn view_of(
    ctx: &glint::gpu::device::context::GpuContext,
    dimension: wgpu::TextureDimension,
    [width, height]: [u32; 2],
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    words: &[u32],
) -> wgpu::TextureView {
    let texture = ctx.device.create_texture_with_data(
        &ctx.queue,
        &wgpu::TextureDescriptor {
            label: None,
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension,
            format,
            usage,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(words),
    );
    texture.create_view(&Default::default())
}
