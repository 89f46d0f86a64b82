//! `glint bench --gpu`: the GPU tracer against the CPU reference on the same scenes, in
//! one run, at 512×512 with AA none and with the scene's default AA. Per scene: the rays
//! traced (counted by the CPU reference, which traces the same samples), the GPU's own
//! time from timestamp queries where the adapter has them (else wall time, said so),
//! Mrays/s, the frame's dispatches, submits and host waits, and the shader's specialised
//! feature set; every timing comes with the GPU image's error against the CPU image
//! (FLIP mean and share of pixels within 2/255). Pipeline creation and the driver's
//! first-dispatch compile are kept out of the steady times. Then a spheres-only scene
//! with its specialised shader against the generic one (every feature compiled in).
//! With `--passes`, a table of GPU time per pass (kernel and quadtree level) of each
//! scene's default-AA frame, the fastest of `--repeat` frames timed pass by pass.

use super::common::{load_scene, BenchArgs};
use super::timing::fastest;
use glint::diff::diff_films;
use glint::gpu::{render_gpu, GpuContext, GpuRender, GpuRenderOptions};
use glint::mailboxes::Mailboxes;
use glint::pack::{PackedScene, SceneFeatures};
use glint::pipeline::pack_scene;
use glint::scene::AaMode;
use glint::tracer::sampling::render::render_with_counters;
use std::time::Instant;

/// Scenes of the comparison: the CS488 corpus' 2021+ family and glint's demo.
const SCENES: &[&str] = &[
    "a4-2021plus/simple.lua",
    "a4-2021plus/nonhier.lua",
    "a4-2021plus/hier.lua",
    "a4-2021plus/macho-cows.lua",
];

/// Side of the benchmark's images.
const SIDE: u32 = 512;

pub fn bench_gpu(args: &BenchArgs) -> anyhow::Result<()> {
    let mut ctx = GpuContext::new(args.adapter.as_deref())?;
    let chosen = ctx.kernel;
    if let Some(side) = &args.workgroup_side {
        ctx.kernel.workgroup_side = side.parse()?;
    }
    if let Some(mailboxes) = &args.mailboxes {
        ctx.kernel.mailboxes = Mailboxes::from_option_name(mailboxes)
            .ok_or_else(|| anyhow::anyhow!("--mailboxes: on, last or off"))?;
    }
    let timed = ctx
        .device
        .features()
        .contains(wgpu::Features::TIMESTAMP_QUERY);
    println!(
        "GPU adapter: {} ({:?}, {:?}); kernel: {}{} (the adapter allows {} invocations a workgroup); GPU time from {}",
        ctx.info.name,
        ctx.info.device_type,
        ctx.info.backend,
        ctx.kernel,
        if ctx.kernel == chosen {
            " (chosen from the adapter)".to_string()
        } else {
            format!(" (set on the command line; the adapter's choice: {chosen})")
        },
        ctx.limits.max_compute_invocations_per_workgroup,
        if timed { "timestamp queries" } else { "wall time (the adapter has no timestamp queries)" }
    );
    if ctx.info.device_type == wgpu::DeviceType::Cpu {
        println!("{}", glint::gpu::device::context::llvmpipe_threads_line());
    }
    println!(
        "\n## GPU vs CPU, {SIDE}×{SIDE} (fastest of {})",
        args.repeat
    );
    println!("| scene | AA | features | rays | GPU wall | GPU time | Mrays/s (GPU time) | CPU wall | GPU/CPU wall | dispatches / submits / host waits | pipeline | first dispatch extra | FLIP mean | within 2/255 |");
    println!("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    let mut paths: Vec<_> = SCENES.iter().map(|s| args.cs488.join(s)).collect();
    paths.push(std::path::PathBuf::from("scenes/demo.lua"));
    for path in &paths {
        for aa in [Some(AaMode::None), None] {
            bench_scene(&ctx, args, path, aa)?;
        }
    }
    if args.passes {
        bench_passes(&ctx, args, &paths)?;
    }
    bench_specialisation(&ctx, args)
}

/// Per scene, its default-AA frame's GPU time per kind of pass (the frame of least
/// total of `--repeat`), and the share of each in the total.
fn bench_passes(
    ctx: &GpuContext,
    args: &BenchArgs,
    paths: &[std::path::PathBuf],
) -> anyhow::Result<()> {
    println!("\n## GPU time per pass, {SIDE}×{SIDE}, default AA (each dispatch timed alone; fastest frame of {})", args.repeat);
    println!("| scene | pass | level | dispatches | GPU time | share |");
    println!("| --- | --- | ---: | ---: | ---: | ---: |");
    let options = GpuRenderOptions {
        pass_times: true,
        ..GpuRenderOptions::default()
    };
    for path in paths {
        let packed = pack_scene(&load_scene(path, SIDE, SIDE)?)?;
        let name = path.file_stem().unwrap_or_default().to_string_lossy();
        let mut best: Option<Vec<glint::gpu::PassTime>> = None;
        let total =
            |p: &[glint::gpu::PassTime]| p.iter().map(|t| t.time).sum::<std::time::Duration>();
        for _ in 0..args.repeat.max(1) {
            let times = render_gpu(ctx, &packed, &options)?.pass_times;
            anyhow::ensure!(
                !times.is_empty(),
                "--passes: no per-pass times (the adapter has no timestamp queries, or the frame has more dispatches than a query set holds)"
            );
            if best.as_ref().is_none_or(|b| total(&times) < total(b)) {
                best = Some(times);
            }
        }
        let best = best.unwrap_or_default();
        let sum = total(&best).as_secs_f64();
        for p in &best {
            println!(
                "| {name} | {} | {} | {} | {:.1} ms | {:.1}% |",
                p.entry,
                p.level,
                p.dispatches,
                p.time.as_secs_f64() * 1e3,
                100.0 * p.time.as_secs_f64() / sum
            );
        }
        println!("| {name} | all | | | {:.1} ms | 100% |", sum * 1e3);
    }
    Ok(())
}

/// One row: `path` at SIDE² under `aa` (None: the scene's own AA).
fn bench_scene(
    ctx: &GpuContext,
    args: &BenchArgs,
    path: &std::path::Path,
    aa: Option<AaMode>,
) -> anyhow::Result<()> {
    let mut scene = load_scene(path, SIDE, SIDE)?;
    if let Some(aa) = aa {
        scene.options.aa = aa;
    }
    let packed = pack_scene(&scene)?;
    let name = path.file_stem().unwrap_or_default().to_string_lossy();
    let start = Instant::now();
    let plain = GpuRenderOptions::default();
    let info = render_gpu(ctx, &packed, &plain)?.info;
    let first = start.elapsed();
    let (t_gpu, gpu) = fastest(args.repeat, || render_gpu(ctx, &packed, &plain));
    let GpuRender {
        film: gpu_film,
        info: info_steady,
        ..
    } = gpu?;
    let (t_cpu, cpu_film) = fastest(args.repeat, || glint::tracer::render(&packed, &|_, _| {}));
    let (_, counters) = render_with_counters(&packed, &|_, _| {});
    let (report, _) = diff_films(&cpu_film, &gpu_film)?;
    let gpu_time = info_steady.gpu_time.unwrap_or(t_gpu);
    println!(
        "| {name} | {} | {} | {} | {:.1} ms | {:.1} ms{} | {:.2} | {:.1} ms | {:.2} | {} / {} / {} | {:.0} ms | {:.0} ms | {:.5} | {:.2}% |",
        format!("{:?}", scene.options.aa).to_lowercase(),
        packed.features,
        counters.rays,
        t_gpu.as_secs_f64() * 1e3,
        gpu_time.as_secs_f64() * 1e3,
        if info_steady.gpu_time.is_some() { "" } else { " (wall)" },
        counters.rays as f64 / gpu_time.as_secs_f64() * 1e-6,
        t_cpu.as_secs_f64() * 1e3,
        t_gpu.as_secs_f64() / t_cpu.as_secs_f64(),
        info_steady.dispatches,
        info_steady.submits,
        info_steady.host_waits,
        info.compile_time.as_secs_f64() * 1e3,
        (first.saturating_sub(t_gpu + info.compile_time)).as_secs_f64() * 1e3,
        report.flip_mean,
        100.0 * report.share_within(2.0 / 255.0),
    );
    Ok(())
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
        let plain = GpuRenderOptions::default();
        let info = render_gpu(ctx, packed, &plain)?.info;
        let (t, result) = fastest(args.repeat, || render_gpu(ctx, packed, &plain));
        let film = result?.film;
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
