//! The traversal work the mailboxes save, scene by scene: the CPU tracer's `bench --trace`
//! rays (one camera ray a pixel, one shadow ray per hit and light) counted under each
//! `Mailboxes` setting — the GPU kernels make the same tests in the same order under the
//! same setting (tests/gpu/gpu_probes.rs). `cargo run --example mailbox_work -- [--width N]
//! SCENE.lua...` prints cells visited and primitives (items and triangles) tested.

use glint::bench::trace_rays::{
    camera_rays, count_work, load_first_render, shadow_rays, trace_primary,
};
use glint::mailboxes::Mailboxes;
use glint::pack::pack;
use std::path::Path;

fn main() -> anyhow::Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut width = None;
    if let Some(i) = args.iter().position(|a| a == "--width") {
        width = Some(args[i + 1].parse::<u32>()?);
        args.drain(i..i + 2);
    }
    println!("| scene | rays | mailboxes | cells visited | primitives tested | tests vs. full |");
    println!("| --- | ---: | --- | ---: | ---: | ---: |");
    for path in &args {
        let flat = load_first_render(Path::new(path), width, None, &Default::default())?;
        let mut scene = pack(&flat)?;
        let rays = camera_rays(&scene);
        let hits = trace_primary(&scene, &rays);
        let shadow = shadow_rays(&scene, &rays, &hits);
        let mut full_tests = 0;
        for m in Mailboxes::ALL {
            scene.mailboxes = m;
            let [p, s] = count_work(&scene, &rays, &shadow);
            let tests = p.items_tested + s.items_tested;
            if m == Mailboxes::Full {
                full_tests = tests;
            }
            println!(
                "| {} | {} | {m} | {} | {} | {:.2}× |",
                Path::new(path).file_name().unwrap().to_string_lossy(),
                rays.len() + shadow.len(),
                p.cells_visited + s.cells_visited,
                tests,
                tests as f64 / full_tests as f64
            );
        }
    }
    Ok(())
}
