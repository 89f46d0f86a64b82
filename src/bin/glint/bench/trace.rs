//! `glint bench --trace SCENE.lua`: the CPU tracer's traversal alone, in rays per second,
//! for comparison with Embree on the same rays (`tools/benches/embree/`).
//!
//! One camera ray per pixel through the pixel centre (no anti-aliasing), traced with
//! `closest_hit`; then, for every hit and every light in front of the hit surface, one
//! shadow ray (`any_hit`) from the offset hit point to the light (an area light's
//! centre), as shading would trace it. Nothing is shaded. Ray generation and the shadow
//! rays' set-up are not timed; each phase is timed over all rays, fastest of `--repeat`.
//! The hits are summarised by counts and a checksum of the hit items, so that another
//! tracer given the same rays (`--dump-rays`) can be checked to find the same hits; an
//! untimed pass over the same rays counts the cells visited and primitives tested.

use super::timing::fastest;
use super::trace_dump::{check_dumpable, write_trace_dump};
use glint::bench::trace_rays::{
    camera_rays, count_work, load_first_render, shadow_rays, summarise, trace_primary_into,
    trace_shadow_into, TraceSummary,
};
use glint::pack::PackedScene;
use glint::pipeline::pack_scene;
use glint::script_driver::ScriptSettings;
use glint::tracer::traversal::traverse::hit_miss;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// What `--trace` needs from the command line.
#[derive(Clone, Debug)]
pub struct TraceBenchArgs {
    pub scene: PathBuf,
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub repeat: usize,
    pub dump_rays: Option<PathBuf>,
    /// How the script runs (readable folders, memory budget, limits).
    pub script: ScriptSettings,
}

pub fn bench_trace(args: &TraceBenchArgs) -> anyhow::Result<()> {
    let scene = load_first_render(&args.scene, args.width, args.height, &args.script)?;
    let build_start = Instant::now();
    let packed = pack_scene(&scene)?;
    let build = build_start.elapsed();
    if args.dump_rays.is_some() {
        check_dumpable(&packed)?;
    }
    let primary = camera_rays(&packed);
    // The answers go to buffers written once before timing (as the Embree harness does),
    // so the timings hold no first-touch page faults.
    let mut hits = vec![hit_miss(); primary.len()];
    let (t_primary, ()) = fastest(args.repeat, || {
        trace_primary_into(&packed, &primary, &mut hits)
    });
    let shadow = shadow_rays(&packed, &primary, &hits);
    let mut occluded = vec![false; shadow.len()];
    let (t_shadow, ()) = fastest(args.repeat, || {
        trace_shadow_into(&packed, &shadow, &mut occluded)
    });
    let summary = summarise(&packed, &hits, &occluded);
    let work = count_work(&packed, &primary, &shadow);
    let (accel_bytes, stored_triangles) = packed.accel_memory();
    println!("primary: {} Mrays/s", rate(mrays(primary.len(), t_primary)));
    println!("shadow: {} Mrays/s", rate(mrays(shadow.len(), t_shadow)));
    println!(
        "memory: {:.1} bytes per triangle",
        accel_bytes as f64 / stored_triangles.max(1) as f64
    );
    print_details(&packed, &summary, build, t_primary, t_shadow, args.repeat);
    for (name, counters, rays) in [
        ("primary", &work[0], primary.len()),
        ("shadow", &work[1], shadow.len()),
    ] {
        let per_ray = |n: u64| n as f64 / rays.max(1) as f64;
        println!(
            "{name} work: {:.2} cells visited, {:.2} primitives tested per ray (untimed count)",
            per_ray(counters.cells_visited),
            per_ray(counters.items_tested)
        );
    }
    if let Some(path) = &args.dump_rays {
        write_trace_dump(path, &packed, &primary, &hits, &shadow, &occluded)?;
        println!(
            "rays and geometry written to {}",
            glint::display_path::shown(path)
        );
    }
    Ok(())
}

fn print_details(
    packed: &PackedScene,
    s: &TraceSummary,
    build: Duration,
    t_primary: Duration,
    t_shadow: Duration,
    repeat: usize,
) {
    let g = &packed.globals;
    println!(
        "image: {}×{}, {} triangles, {} other items, {} lights, {} threads",
        g.width,
        g.height,
        packed.triangles.len(),
        g.num_instances,
        g.num_lights,
        rayon::current_num_threads()
    );
    println!(
        "primary rays: {} ({} hit) in {:.1} ms",
        s.primary_rays,
        s.primary_hits,
        t_primary.as_secs_f64() * 1e3
    );
    println!(
        "shadow rays: {} ({} occluded) in {:.1} ms",
        s.shadow_rays,
        s.shadow_occluded,
        t_shadow.as_secs_f64() * 1e3
    );
    println!("hit checksum: {}", s.hit_checksum);
    println!(
        "build (pack + grid): {:.1} ms; times: fastest of {}",
        build.as_secs_f64() * 1e3,
        repeat.max(1)
    );
}

/// A rate with three decimals, or three significant digits below 1 (the slow scenes run
/// at thousandths of a Mray/s). Plain decimal, never exponent notation.
pub fn rate(x: f64) -> String {
    let decimals = if x > 0.0 && x < 1.0 {
        (2 - x.log10().floor() as i32).max(3) as usize
    } else {
        3
    };
    format!("{x:.decimals$}")
}

fn mrays(rays: usize, time: Duration) -> f64 {
    rays as f64 / time.as_secs_f64().max(1e-9) / 1e6
}

#[cfg(test)]
mod tests {
    use super::rate;

    #[test]
    fn rates_keep_three_significant_digits_below_one() {
        assert_eq!(rate(31.25), "31.250");
        assert_eq!(rate(1.0), "1.000");
        assert_eq!(rate(0.5), "0.500");
        assert_eq!(rate(0.0123), "0.0123");
        assert_eq!(rate(0.000965), "0.000965");
        assert_eq!(rate(0.0), "0.000");
    }
}
