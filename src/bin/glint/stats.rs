//! `--stats`: what a render compiled in, how its grid came out, and what its rays cost.

use glint::pipeline::RenderedImage;
use std::fmt::Write;

/// Multi-line statistics of one render.
pub fn format_stats(image: &RenderedImage) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "  features: {}", image.packed.features);
    let _ = writeln!(
        out,
        "  build: flatten and pack {:.3} s (grids included)",
        image.build_time.as_secs_f64()
    );
    write_gpu(&mut out, image);
    write_items(&mut out, image);
    write_grids(&mut out, image);
    write_rays(&mut out, image);
    out
}

/// The GPU line (and the loop-limit guard's), when the GPU rendered.
fn write_gpu(out: &mut String, image: &RenderedImage) {
    if let Some(gpu) = &image.gpu {
        let _ = writeln!(
            out,
            "  gpu: {} — compiled in: {}; kernel: {}; pipelines compiled in {:.1} ms (lavapipe compiles again on the first dispatch; Mesa caches it); {} chunks (widest row stride {} pixels), {} dispatches in {} submits, {} host waits; GPU time {}",
            image.adapter.as_deref().unwrap_or("?"),
            gpu.features,
            gpu.kernel,
            gpu.compile_time.as_secs_f64() * 1e3,
            gpu.tiles,
            gpu.tile_side,
            gpu.dispatches,
            gpu.submits,
            gpu.host_waits,
            gpu.gpu_time.map_or("not measured (no timestamp queries)".to_string(), |t| {
                format!("{:.1} ms (timestamp queries)", t.as_secs_f64() * 1e3)
            })
        );
        write_compile(out, &gpu.compile);
        if gpu.kernel.iteration_guard {
            let _ = writeln!(
                out,
                "  loop-limit guard (software adapter): {} pixels re-rendered on the CPU",
                gpu.cpu_fallback_pixels
            );
        }
    }
}

/// Where the pipelines' compile time went, and what the on-disk pipeline cache did.
fn write_compile(out: &mut String, c: &glint::gpu::pipeline::CompileSummary) {
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    let _ = writeln!(
        out,
        "  gpu compile: WGSL assembly {:.1} ms, naga validation {:.1} ms, shader modules {:.1} ms, pipelines {:.1} ms, cache files {:.1} ms; pipeline cache: {} reused, {} written, {} rejected, {} uncached",
        ms(c.times.assemble),
        ms(c.times.validate),
        ms(c.times.shader_module),
        ms(c.times.pipeline),
        ms(c.times.cache_load + c.times.cache_store),
        c.reused,
        c.written,
        c.rejected,
        c.uncached
    );
}

/// What the scene grid holds: analytic objects, CSG objects, mesh instances and lights.
fn write_items(out: &mut String, image: &RenderedImage) {
    let packed = &image.packed;
    let g = &packed.globals;
    let csg_items = packed.instances[..g.num_instances as usize]
        .iter()
        .filter(|i| i.kind == glint::constants::KIND_CSG)
        .count();
    let csg = if csg_items > 0 {
        format!(
            " ({csg_items} CSG objects of {} primitives)",
            packed.instances.len() - g.num_instances as usize
        )
    } else {
        String::new()
    };
    let mesh_instances = packed.instances[..g.num_instances as usize]
        .iter()
        .filter(|i| i.kind == glint::constants::KIND_MESH)
        .count();
    let _ = writeln!(
        out,
        "  items: {} ({} analytic{csg}, {mesh_instances} mesh instances of {} meshes), {} stored triangles, {} lights",
        g.num_instances,
        g.num_instances as usize - mesh_instances,
        packed.meshes.len(),
        g.num_triangles,
        g.num_lights
    );
}

/// How the scene grid and the mesh grids came out.
fn write_grids(out: &mut String, image: &RenderedImage) {
    let packed = &image.packed;
    let g = &packed.globals;
    let grid = &packed.grid_stats;
    if g.grid_enabled != 0 {
        let [nx, ny, nz] = g.grid_dims;
        let _ = writeln!(
            out,
            "  grid: {nx}×{ny}×{nz} = {} cells, {:.2} items per non-empty cell (max {}), {:.1}% empty, {} references, built in {:.2} ms, {:.2} MiB",
            grid.cells,
            grid.mean_items_per_full_cell(),
            grid.max_items_in_cell,
            100.0 * grid.empty_share(),
            grid.references,
            grid.build_time.as_secs_f64() * 1e3,
            grid.memory_bytes as f64 / (1 << 20) as f64
        );
    } else {
        let _ = match grid.items {
            1 => writeln!(out, "  grid: off (one item: a grid could cull nothing)"),
            n => writeln!(out, "  grid: off (brute force over {n} items)"),
        };
    }
    let meshes = &packed.mesh_grid_stats;
    if !packed.meshes.is_empty() {
        let (bytes, stored) = packed.accel_memory();
        let _ = writeln!(
            out,
            "  mesh grids: {} cells, {:.2} triangles per non-empty cell (max {}), {:.1}% empty, {} references, built in {:.2} ms; structure {:.1} bytes per stored triangle",
            meshes.cells,
            meshes.mean_items_per_full_cell(),
            meshes.max_items_in_cell,
            100.0 * meshes.empty_share(),
            meshes.references,
            meshes.build_time.as_secs_f64() * 1e3,
            bytes as f64 / stored.max(1) as f64
        );
    }
}

/// What the rays cost, when the render counted them.
fn write_rays(out: &mut String, image: &RenderedImage) {
    if let Some(c) = image.counters {
        let rays = c.rays.max(1) as f64;
        let _ = writeln!(
            out,
            "  rays: {} (camera, shadow and secondary), {:.2} cells visited and {:.2} items tested per ray",
            c.rays,
            c.cells_visited as f64 / rays,
            c.items_tested as f64 / rays
        );
        let _ = writeln!(
            out,
            "  time: {:.3} s with counting, {:.3} Mrays/s",
            image.render_time.as_secs_f64(),
            rays / image.render_time.as_secs_f64() / 1e6
        );
    }
}
