//! `glint bench --gpu`: the GPU tracer against the CPU reference on the same scenes, in
//! one run. Pipeline creation and the driver's first-dispatch compile are reported apart
//! from the steady render time; every timing comes with the GPU image's error against the
//! CPU image (FLIP mean and share of pixels within 2/255). Then a spheres-only scene with
//! its specialised shader against the generic one (every feature compiled in).

use super::bench_cmd::{fastest, load_scene, BenchArgs};
use crate::diff::diff_films;
use crate::gpu::{render_gpu_with_info, GpuContext};
use crate::pack::{PackedScene, SceneFeatures};
use crate::pipeline::pack_scene;
use crate::scene::AaMode;
use std::time::Instant;

/// Scenes of the comparison: the CS488 corpus' 2021+ family and glint's demo.
const SCENES: &[&str] = &[
    "a4-2021plus/simple.lua",
    "a4-2021plus/nonhier.lua",
    "a4-2021plus/hier.lua",
    "a4-2021plus/macho-cows.lua",
];

pub fn bench_gpu(args: &BenchArgs) -> anyhow::Result<()> {
    let ctx = GpuContext::new(args.adapter.as_deref())?;
    println!(
        "GPU adapter: {} ({:?})",
        ctx.info.name, ctx.info.device_type
    );
    println!(
        "\n## GPU vs CPU, 256×256, no anti-aliasing (fastest of {})",
        args.repeat
    );
    println!("| scene | features | pipeline | first dispatch extra | GPU | CPU | GPU/CPU time | FLIP mean | within 2/255 |");
    println!("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    let mut paths: Vec<_> = SCENES.iter().map(|s| args.cs488.join(s)).collect();
    paths.push(std::path::PathBuf::from("scenes/demo.lua"));
    for path in &paths {
        let mut scene = load_scene(path, 256, 256)?;
        scene.options.aa = AaMode::None;
        let packed = pack_scene(&scene)?;
        let name = path.file_stem().unwrap_or_default().to_string_lossy();
        let start = Instant::now();
        let (_, info) = render_gpu_with_info(&ctx, &packed, &|_, _| {})?;
        let first = start.elapsed();
        let (t_gpu, gpu) = fastest(args.repeat, || {
            render_gpu_with_info(&ctx, &packed, &|_, _| {})
        });
        let (gpu_film, _) = gpu?;
        let (t_cpu, cpu_film) = fastest(args.repeat, || crate::cpu::render(&packed, &|_, _| {}));
        let (report, _) = diff_films(&cpu_film, &gpu_film)?;
        println!(
            "| {name} | {} | {:.0} ms | {:.0} ms | {:.1} ms | {:.1} ms | {:.2} | {:.5} | {:.2}% |",
            packed.features,
            info.compile_time.as_secs_f64() * 1e3,
            (first.saturating_sub(t_gpu + info.compile_time)).as_secs_f64() * 1e3,
            t_gpu.as_secs_f64() * 1e3,
            t_cpu.as_secs_f64() * 1e3,
            t_gpu.as_secs_f64() / t_cpu.as_secs_f64(),
            report.flip_mean,
            100.0 * report.share_within(2.0 / 255.0),
        );
    }
    bench_specialisation(&ctx, args)
}

/// simple.lua (spheres only) with its own shader and with every feature compiled in.
fn bench_specialisation(ctx: &GpuContext, args: &BenchArgs) -> anyhow::Result<()> {
    let mut scene = load_scene(&args.cs488.join("a4-2021plus/simple.lua"), 256, 256)?;
    scene.options.aa = AaMode::None;
    let specialised = pack_scene(&scene)?;
    let mut generic: PackedScene = specialised.clone();
    // Every feature but the grid, which follows the scene's data.
    for (flag, _) in SceneFeatures::ALL {
        if *flag != SceneFeatures::GRID {
            generic.features.insert(*flag);
        }
    }
    println!("\n## Specialised vs generic shader, simple.lua (spheres only), 256×256");
    println!("| shader | features | pipeline | render | FLIP mean vs specialised |");
    println!("| --- | --- | ---: | ---: | ---: |");
    let mut reference = None;
    for (label, packed) in [("specialised", &specialised), ("generic", &generic)] {
        let (_, info) = render_gpu_with_info(ctx, packed, &|_, _| {})?;
        let (t, result) = fastest(args.repeat, || {
            render_gpu_with_info(ctx, packed, &|_, _| {})
        });
        let (film, _) = result?;
        let flip = match &reference {
            None => 0.0,
            Some(r) => diff_films(r, &film)?.0.flip_mean,
        };
        reference.get_or_insert(film);
        println!(
            "| {label} | {} | {:.0} ms | {:.1} ms | {flip:.5} |",
            packed.features,
            info.compile_time.as_secs_f64() * 1e3,
            t.as_secs_f64() * 1e3
        );
    }
    Ok(())
}
