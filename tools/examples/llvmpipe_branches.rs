//! Micro-benchmark: what a branch that no lane takes costs a compute shader on the default
//! adapter. `plain` is a loop of cheap integer work; `dead_alu` adds, inside the loop, an
//! `if` that no invocation takes around ~100 float operations; `dead_loop` the same work
//! inside a loop within the untaken `if`; `dead_switch` a switch whose untaken arms hold
//! it. If the adapter skips branches with no active lane, all four cost the same. Run:
//! `cargo run --release --example llvmpipe_branches`.
#[path = "llvmpipe_timing/mod.rs"]
mod llvmpipe_timing;

const SHADER: &str = r#"
@group(0) @binding(0) var<storage, read_write> out_buf: array<u32>;
@group(0) @binding(1) var<storage, read> param: array<u32>;
fn heavy(x: f32) -> f32 {
    var y = x;
    for (var r = 0u; r < 12u; r++) {
        y = sqrt(abs(y * 1.0001 + 0.5)) * 1.37 - y * 0.25;
        y = y * y * 0.5 + 0.125 / (abs(y) + 1.0);
        y = fma(y, 0.75, 0.2) - floor(y);
    }
    return y;
}
fn hash(i: u32) -> u32 { return i * 1664525u + 1013904223u; }
@compute @workgroup_size(64)
fn plain(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    for (var k = 0u; k < 256u; k++) { i = hash(i); acc += i >> 7u; }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn dead_alu(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    let never = param[0];
    for (var k = 0u; k < 256u; k++) {
        i = hash(i); acc += i >> 7u;
        if (i == never) { acc += u32(heavy(f32(acc))); }
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn dead_loop(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    let never = param[0];
    for (var k = 0u; k < 256u; k++) {
        i = hash(i); acc += i >> 7u;
        if (i == never) {
            for (var j = 0u; j < (i & 7u); j++) { acc += u32(heavy(f32(acc + j))); }
        }
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn dead_switch(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    let kind = param[1];
    for (var k = 0u; k < 256u; k++) {
        i = hash(i); acc += i >> 7u;
        switch kind {
            case 1u: { acc += u32(heavy(f32(acc))); }
            case 2u: { acc += u32(heavy(f32(acc ^ 3u))); }
            case 3u: { acc += u32(heavy(f32(acc ^ 5u))); }
            default: { acc += 1u; }
        }
    }
    out_buf[id.x] = acc;
}
@compute @workgroup_size(64)
fn live_alu(@builtin(global_invocation_id) id: vec3<u32>) {
    var i = id.x * 2654435761u;
    var acc = 0u;
    let never = param[0];
    for (var k = 0u; k < 256u; k++) {
        i = hash(i); acc += i >> 7u;
        if (i != never) { acc += u32(heavy(f32(acc))); }
    }
    out_buf[id.x] = acc;
}
"#;

fn main() {
    let bench = llvmpipe_timing::setup(SHADER);
    let param = wgpu::util::DeviceExt::create_buffer_init(
        &bench.ctx.device,
        &wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytemuck::cast_slice(&[7u32, 0u32]),
            usage: wgpu::BufferUsages::STORAGE,
        },
    );
    for entry in ["plain", "dead_alu", "dead_loop", "dead_switch", "live_alu"] {
        let mut bindings = vec![(0, bench.out.as_entire_binding())];
        if entry != "plain" {
            bindings.push((1, param.as_entire_binding()));
        }
        let timing = llvmpipe_timing::time_entry(&bench, entry, &bindings);
        let (best, first) = (timing.best_ms, timing.first_ms);
        let per_iteration = best * 1e6 / (llvmpipe_timing::INVOCATIONS as f64 * 256.0);
        println!(
            "{entry:12} best {best:8.1} ms  {per_iteration:6.2} ns per iteration (first {first:.1} ms)"
        );
    }
}
