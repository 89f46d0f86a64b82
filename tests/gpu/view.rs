//! `glint view` in a real window: each test starts its own Xvfb (lavapipe presents to
//! it), runs `glint view` there and checks what the window shows or prints:
//! (a) after n² frames the presented image is `glint render --aa uniform --samples n`;
//! (b) a mouse drag moves the printed camera as an orbit does;
//! (c) saving a file the script read changes the window within a bounded time;
//! (d) a broken edit keeps the last image and shows the error, a fix brings it back;
//! (e) Esc and the window manager's close end the process cleanly.
//! Plus the device-side sums against the tracers' own renders, without a window, and the
//! harness's own failure when a view ends before its window opens.

use super::view_window::{View, Xvfb, WAIT};
use crate::common::{gpu_context, load_packed, root};
use glint::gpu::view::progressive::{Progressive, SumBuffer};
use glint::scene::{AaMode, AaSamples, OptionOverrides};
use glint::tracer::sampling::progressive::{accumulate_sample, film_of_sums};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// A scratch folder of its own for each test (two tests with one tag ran in parallel
/// used to share a folder and overwrite each other's screenshot).
fn temp_dir(name: &str) -> glint::testing::scratch::TempDir {
    glint::testing::scratch::temp_dir(&format!("view-{name}"))
}

fn glint(dir: &Path, args: &[&str]) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("glint runs");
    assert!(
        out.status.success(),
        "glint {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

fn load_rgb(path: &Path) -> image::RgbImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8()
}

/// Largest per-channel difference of two images of one size, in 1/255.
fn max_difference(a: &image::RgbImage, b: &image::RgbImage) -> u8 {
    assert_eq!(a.dimensions(), b.dimensions());
    a.as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(x, y)| x.abs_diff(*y))
        .max()
        .unwrap_or(0)
}

/// (a) on one tracer: `glint view --frames n² --screenshot` against `glint render`.
fn screenshot_equals_render(backend: &str) {
    screenshot_equals_render_of("demo.lua", backend, &[], None);
}

/// (a) for `scene` (in `scenes/`) on one tracer, with `flags` given to both the view and
/// the render; with `expect_kernel`, the GPU kernel variant the view must report it ran.
fn screenshot_equals_render_of(
    scene: &str,
    backend: &str,
    flags: &[&str],
    expect_kernel: Option<&str>,
) {
    let x = Xvfb::start();
    let dir = temp_dir(&format!("shot-{backend}"));
    let demo = root().join("scenes").join(scene);
    let demo = demo.to_str().unwrap();
    let size = [&["--width", "96", "--height", "60"][..], flags].concat();
    let mut view = View::start(
        &x,
        &dir,
        &[
            &[
                demo,
                "--backend",
                backend,
                "--samples",
                "3",
                "--frames",
                "9",
                "--screenshot",
                "shot.png",
            ][..],
            &size,
        ]
        .concat(),
    );
    let status = view
        .wait_exit(WAIT)
        .expect("glint view ends after its frames");
    assert!(
        status.success(),
        "glint view failed: {}",
        view.stderr.lock().unwrap().join("\n")
    );
    if let Some(kernel) = expect_kernel {
        let stderr = view.stderr.lock().unwrap().join("\n");
        assert!(
            stderr.contains(&format!("GPU kernel: {kernel}")),
            "the view did not run the kernel variant asked for ({kernel}): {stderr}"
        );
    }
    glint(
        &dir,
        &[
            &[
                "render",
                demo,
                "-o",
                "render.png",
                "--aa",
                "uniform",
                "--samples",
                "3",
                "--backend",
                backend,
            ][..],
            &size,
        ]
        .concat(),
    );
    let (shot, render) = (
        load_rgb(&dir.join("shot.png")),
        load_rgb(&dir.join("render.png")),
    );
    let diff = max_difference(&shot, &render);
    eprintln!("{scene}, {backend} tracer {flags:?}: the window after 9 frames differs from glint render by at most {diff}/255");
    assert!(
        diff <= 2,
        "{scene}, {backend} {flags:?}: the window shows {diff}/255 away from glint render"
    );
    // Not a blank window that happens to match a blank render.
    let lit = render
        .pixels()
        .filter(|p| p.0.iter().any(|&c| c > 40))
        .count();
    assert!(
        lit > 96 * 60 / 2,
        "the render is mostly dark: {lit} lit pixels"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn a_gpu_window_after_n_squared_frames_is_the_render() {
    screenshot_equals_render("gpu");
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn a_cpu_window_after_n_squared_frames_is_the_render() {
    screenshot_equals_render("cpu");
}

/// The hardware kernel variant (`--kernel-variant hardware`: per-ray lists in storage,
/// dispatched in bands; the camera ray in the loop) in the window, on a scene whose
/// dielectric ray stack lives in those lists: what a hardware GPU's view would run.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn a_hardware_kernel_window_on_glass_is_the_render() {
    screenshot_equals_render_of(
        "glass.lua",
        "gpu",
        &["--kernel-variant", "hardware"],
        Some(
            "workgroup 8×8/64, last-item mailbox, ray lists in storage, camera ray in loop, \
             any hit in one loop",
        ),
    );
}

/// The eye of a camera line the view printed (C).
fn eye_of(line: &str) -> [f64; 3] {
    let inside = line
        .split('{')
        .nth(1)
        .and_then(|s| s.split('}').next())
        .expect("an eye");
    let v: Vec<f64> = inside
        .split(", ")
        .map(|c| c.parse().expect("a number"))
        .collect();
    [v[0], v[1], v[2]]
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn a_mouse_drag_orbits_the_printed_camera() {
    let x = Xvfb::start();
    let dir = temp_dir("orbit");
    let demo = root().join("scenes/demo.lua");
    let mut view = View::start(
        &x,
        &dir,
        &[
            demo.to_str().unwrap(),
            "--width",
            "96",
            "--height",
            "60",
            "--aa",
            "none",
        ],
    );
    let window = view.window(&x, "glint view");
    view.wait_line(&view.stderr, 0, "image complete", WAIT);
    x.key(&window, "c");
    let (_, before) = view.wait_line(&view.stdout, 0, "eye, view, up, fov", WAIT);
    let next = view.stdout_len();
    let w = window.as_str();
    // A drag to the right, with the left button: orbit about the vertical axis.
    x.tool(
        "xdotool",
        &["mousemove", "--window", w, "30", "30", "mousedown", "1"],
    );
    x.tool(
        "xdotool",
        &[
            "mousemove",
            "--window",
            w,
            "50",
            "30",
            "mousemove",
            "--window",
            w,
            "70",
            "30",
            "mouseup",
            "1",
        ],
    );
    view.wait_line(&view.stderr, 0, "moving:", WAIT);
    x.key(w, "c");
    let (_, after) = view.wait_line(&view.stdout, next, "eye, view, up, fov", WAIT);
    let (e0, e1) = (eye_of(&before), eye_of(&after));
    assert_eq!(e0, [0.0, 3.2, 8.5], "the script's camera first: {before}");
    // Orbiting about the up axis keeps the height and turns the eye to one side.
    assert!((e1[1] - e0[1]).abs() < 1e-9, "the height changed: {after}");
    assert!(
        e1[0] < -0.5,
        "dragging right should swing the eye to -x: {after}"
    );
    // The distance from the axis through the pivot stays (the pivot is on x = 0).
    let r0 = e0[0].hypot(e0[2]);
    assert!(e1[0].hypot(e1[2]) < r0 + 1e-6, "{before} → {after}");
}

/// A scene whose sphere's colour comes from a required module (colour.lua), so that
/// live reload must watch a file besides the script.
fn write_module_scene(dir: &Path, colour: &str) {
    std::fs::write(
        dir.join("scene.lua"),
        "local colour = require 'colour'\n\
         local root = gr.node('root')\n\
         local ball = gr.sphere('ball')\n\
         ball:scale(3, 3, 3)\n\
         ball:set_material(gr.material(colour.kd, {0, 0, 0}, 10))\n\
         root:add_child(ball)\n\
         gr.render(root, 'scene.png', 64, 48, {0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 50,\n\
           {1, 1, 1}, {gr.light({0, 0, 10}, {0, 0, 0}, {1, 0, 0})})\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("colour.lua"),
        format!("return {{ kd = {colour} }}\n"),
    )
    .unwrap();
}

/// The window's centre pixel.
fn centre(x: &Xvfb, window: &str) -> [u8; 3] {
    let img = x.capture(window);
    img.get_pixel(img.width() / 2, img.height() / 2).0
}

/// Waits until the window's centre pixel satisfies `ok`, returning how long it took.
fn wait_for_centre(
    x: &Xvfb,
    window: &str,
    ok: impl Fn([u8; 3]) -> bool,
    limit: Duration,
) -> Duration {
    let start = Instant::now();
    loop {
        let c = centre(x, window);
        if ok(c) {
            return start.elapsed();
        }
        assert!(
            start.elapsed() < limit,
            "the window's centre is still {c:?} after {limit:?}"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

const RELOAD_LIMIT: Duration = Duration::from_secs(10);

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn saving_a_module_the_script_required_shows_the_change() {
    let x = Xvfb::start();
    let dir = temp_dir("reload");
    write_module_scene(&dir, "{0.9, 0.1, 0.1}");
    let mut view = View::start(&x, &dir, &["scene.lua", "--backend", "gpu", "--aa", "none"]);
    let window = view.window(&x, "glint view");
    view.wait_line(&view.stderr, 0, "image complete", WAIT);
    wait_for_centre(&x, &window, |c| c[0] > 150 && c[1] < 60, RELOAD_LIMIT);
    // Rewrite the module (not the script): the ball turns green.
    std::fs::write(dir.join("colour.lua"), "return { kd = {0.1, 0.9, 0.1} }\n").unwrap();
    let took = wait_for_centre(&x, &window, |c| c[1] > 150 && c[0] < 60, RELOAD_LIMIT);
    eprintln!(
        "the edit showed in the window after {} ms",
        took.as_millis()
    );
    view.wait_line(&view.stderr, 0, "reloaded scene.lua", WAIT);
}

/// A view of the red module scene in `dir` on the GPU tracer, with `extra` arguments,
/// once its red image shows: the view, its window, that image and the script's text.
fn red_view(x: &Xvfb, dir: &Path, extra: &[&str]) -> (View, String, image::RgbImage, String) {
    write_module_scene(dir, "{0.9, 0.1, 0.1}");
    let mut args = vec!["scene.lua", "--backend", "gpu", "--aa", "none"];
    args.extend(extra);
    let mut view = View::start(x, dir, &args);
    let window = view.window(x, "glint view");
    view.wait_line(&view.stderr, 0, "image complete", WAIT);
    wait_for_centre(x, &window, |c| c[0] > 150, RELOAD_LIMIT);
    let before = x.capture(&window);
    let good = std::fs::read_to_string(dir.join("scene.lua")).unwrap();
    (view, window, before, good)
}

/// Writes the script `good` back (its eye moved, so that it is a change) and waits for
/// the reload.
fn fix_and_reload(dir: &Path, view: &View, good: &str) {
    std::fs::write(
        dir.join("scene.lua"),
        good.replace("{0, 0, 10}, {0, 0, -1}", "{0, 0, 12}, {0, 0, -1}"),
    )
    .unwrap();
    view.wait_line(&view.stderr, 0, "reloaded scene.lua", RELOAD_LIMIT);
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn a_broken_edit_keeps_the_image_and_shows_the_error() {
    let x = Xvfb::start();
    let dir = temp_dir("broken");
    let (view, window, before, good) = red_view(&x, &dir, &[]);
    std::fs::write(
        dir.join("scene.lua"),
        good.replace("ball:scale(3, 3, 3)", "ball:scale(3, 3)"),
    )
    .unwrap();
    let (_, error) = view.wait_line(&view.stderr, 0, "glint view: error:", RELOAD_LIMIT);
    assert!(
        error.contains("scene.lua:4:"),
        "the error names file and line: {error}"
    );
    let title = x.window_name(&window);
    assert!(
        title.contains("ERROR") && title.contains("scene.lua:4:"),
        "title: {title}"
    );
    assert_eq!(
        max_difference(&before, &x.capture(&window)),
        0,
        "the last good image stays"
    );
    // Fixing the file brings the view back.
    fix_and_reload(&dir, &view, &good);
    let deadline = Instant::now() + RELOAD_LIMIT;
    while x.window_name(&window).contains("ERROR") {
        assert!(
            Instant::now() < deadline,
            "the error stays in the title after the fix"
        );
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// A reload to an image larger than the adapter can hold (2²⁷ pixels: their sums are
/// 2 GiB, over a storage binding's limit) says so, naming the limit and suggesting
/// `--backend cpu`, and keeps showing the last good image; a reload back recovers.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn a_reload_past_the_adapters_limits_says_so_and_keeps_the_image() {
    let x = Xvfb::start();
    let dir = temp_dir("reload-too-large");
    let (view, window, before, good) = red_view(&x, &dir, &["--memory-limit", "16384"]);
    let huge = good.replace("'scene.png', 64, 48", "'scene.png', 65536, 2048");
    assert_ne!(huge, good);
    std::fs::write(dir.join("scene.lua"), huge).unwrap();
    let (_, error) = view.wait_line(&view.stderr, 0, "glint view: error:", RELOAD_LIMIT);
    assert!(
        error.contains("view sums") && error.contains("--backend cpu"),
        "the error names the limit and the way out: {error}"
    );
    assert!(x.window_name(&window).contains("ERROR"));
    assert_eq!(
        max_difference(&before, &x.capture(&window)),
        0,
        "the last good image stays"
    );
    fix_and_reload(&dir, &view, &good);
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn escape_and_the_window_managers_close_end_the_view() {
    let dir = temp_dir("close");
    write_module_scene(&dir, "{0.5, 0.5, 0.5}");
    for how in ["Escape", "close"] {
        // A server each: the second view starts on a display the first left nothing on.
        let x = Xvfb::start();
        let mut view = View::start(&x, &dir, &["scene.lua", "--aa", "none"]);
        let window = view.window(&x, "glint view");
        view.wait_line(&view.stderr, 0, "image complete", WAIT);
        match how {
            "Escape" => x.key(&window, "Escape"),
            _ => x.close_as_window_manager(&window),
        }
        let status = view
            .wait_exit(Duration::from_secs(20))
            .unwrap_or_else(|| panic!("{how}: still running after 20 s"));
        assert!(status.success(), "{how}: exit status {status}");
        let deadline = Instant::now() + Duration::from_secs(10);
        while x.has_window("glint view") {
            assert!(
                Instant::now() < deadline,
                "{how}: the window outlived the process"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
    }
}

/// The harness itself: a view that ends before its window opens fails the wait for the
/// window at once, not after [`WAIT`], saying how it ended and what it printed.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn a_view_that_ends_early_fails_the_window_wait_with_its_status_and_output() {
    let x = Xvfb::start();
    let dir = temp_dir("ends");
    std::fs::write(dir.join("bad.lua"), "error('no scene in here')\n").unwrap();
    let mut view = View::start(&x, &dir, &["bad.lua"]);
    let started = Instant::now();
    let failure = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        view.window(&x, "glint view")
    }))
    .expect_err("a view whose script fails opens no window");
    let message = failure
        .downcast_ref::<String>()
        .expect("a formatted message");
    assert!(
        message.contains("glint view ended (exit status: 3)")
            && message.contains("no scene in here"),
        "{message}"
    );
    assert!(
        started.elapsed() < WAIT / 4,
        "the wait went on after the view ended: {:?}",
        started.elapsed()
    );
}

/// The device's progressive sums after n² frames against the GPU tracer's uniform
/// render of the same scene, and the CPU's against the CPU tracer's (no window).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn progressive_sums_converge_to_the_tracers_renders() {
    let Some(ctx) = gpu_context() else { return };
    let overrides = OptionOverrides {
        aa: Some(AaMode::Uniform),
        samples: AaSamples::parse("3").ok(),
        width: Some(48),
        height: Some(30),
        ..OptionOverrides::default()
    };
    let packed = load_packed(&root().join("scenes/demo.lua"), &overrides);
    let g = packed.globals;
    let pixels = u64::from(g.width * g.height);
    let sums = SumBuffer::new(&ctx, pixels).unwrap();
    let mut progressive = Progressive::new(&ctx, &packed, &sums).unwrap();
    progressive.set_globals(&ctx, &g);
    for s in 0..9 {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        progressive.encode_sample(&ctx, &mut encoder, s);
        ctx.queue.submit([encoder.finish()]);
    }
    let gpu = film_of_sums(&sums.read(&ctx, pixels).unwrap(), g.width, g.height);
    let reference = glint::gpu::render_gpu(&ctx, &packed, &Default::default())
        .unwrap()
        .film;
    let worst = worst_relative_difference(&gpu, &reference);
    // The same samples summed in the same order: only the division (host here, device
    // there) may round differently, by an ulp.
    assert!(
        worst <= 2.0 * f32::EPSILON,
        "GPU sums: largest relative difference {worst:e}"
    );
    let cpu = film_of_sums(&cpu_sums(&packed, 9), g.width, g.height);
    assert_eq!(
        cpu.pixels,
        crate::common::render_cpu(&packed).pixels,
        "CPU sums: bit for bit"
    );
}

/// The largest per-channel difference between two films, relative to `reference`'s.
fn worst_relative_difference(film: &glint::film::Film, reference: &glint::film::Film) -> f32 {
    film.pixels
        .iter()
        .zip(&reference.pixels)
        .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs() / b[c].abs().max(1e-30)))
        .fold(0.0f32, f32::max)
}

/// The CPU tracer's progressive sums of `packed` after `frames` samples a pixel.
fn cpu_sums(packed: &glint::pack::PackedScene, frames: u32) -> Vec<[f32; 4]> {
    let g = packed.globals;
    let mut sums = vec![[0.0f32; 4]; (g.width * g.height) as usize];
    for s in 0..frames {
        accumulate_sample(packed, s, &mut sums);
    }
    sums
}

/// `frames` samples of every pixel of `packed` added on the device the way the view adds
/// them on a software adapter (`trace_sample`: the limiter's fallback included); the sums
/// read back, and how many samples each frame re-traced on the CPU.
fn progressive_sums(
    ctx: &glint::gpu::GpuContext,
    packed: &glint::pack::PackedScene,
    frames: u32,
    sentinel: Option<u32>,
) -> (Progressive, Vec<[f32; 4]>, Vec<u64>) {
    let g = packed.globals;
    let pixels = u64::from(g.width * g.height);
    let sums = SumBuffer::new(ctx, pixels).unwrap();
    let mut progressive = Progressive::new(ctx, packed, &sums).unwrap();
    if let Some(sentinel) = sentinel {
        progressive.set_limiter_sentinel(sentinel);
    }
    progressive.set_globals(ctx, &g);
    let retraced = (0..frames)
        .map(|s| progressive.trace_sample(ctx, packed, &sums, s).unwrap())
        .collect();
    let read = sums.read(ctx, pixels).unwrap();
    // Every pixel has every sample, whether the GPU or the CPU fallback traced it.
    let short = read.iter().filter(|s| s[3] != frames as f32).count();
    assert_eq!(short, 0, "{short} pixels' sums lack samples");
    (progressive, read, retraced)
}

/// The loop limiter's fallback in the view: with the limiter check asked for more
/// iterations than lavapipe's limit (the render's test hook, `tile.sentinel`), every
/// sample trips it, so every sample is re-traced on the CPU tracer into the sums — which
/// must then be the CPU tracer's sums bit for bit, and the image `glint render`'s with
/// its own fallback (every pixel re-rendered on the CPU). Without the fallback the sums
/// would keep the short samples (or, as the kernel leaves a cut-short sum alone, no
/// samples at all). On a hardware adapter nothing trips and nothing is re-traced.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn limited_samples_are_re_traced_on_the_cpu() {
    let Some(ctx) = gpu_context() else { return };
    let overrides = OptionOverrides {
        aa: Some(AaMode::Uniform),
        samples: AaSamples::parse("3").ok(),
        width: Some(40),
        height: Some(24),
        ..OptionOverrides::default()
    };
    let packed = load_packed(&root().join("scenes/demo.lua"), &overrides);
    let g = packed.globals;
    let pixels = u64::from(g.width * g.height);
    let (progressive, sums, retraced) = progressive_sums(&ctx, &packed, 9, Some(70_000));
    let guarded = ctx.kernel.iteration_guard;
    eprintln!("guard {guarded}: samples re-traced per frame {retraced:?}");
    let expected = if guarded { pixels } else { 0 };
    assert!(retraced.iter().all(|&n| n == expected), "{retraced:?}");
    let r = progressive.retraced();
    assert_eq!((r.samples, r.pixels), (9 * expected, expected));
    let view = film_of_sums(&sums, g.width, g.height);
    let tripping = glint::gpu::GpuRenderOptions {
        limiter_sentinel: 70_000,
        ..Default::default()
    };
    let render = glint::gpu::render_gpu(&ctx, &packed, &tripping).unwrap();
    assert_eq!(render.info.cpu_fallback_pixels, expected);
    if guarded {
        assert!(
            sums == cpu_sums(&packed, 9),
            "the sums are not the CPU tracer's"
        );
        assert_eq!(view.pixels, render.film.pixels, "not glint render's image");
    }
}

/// The view's kernel with the per-ray lists in storage (the hardware variant, compiled
/// here on whatever adapter there is) on scenes that use them (glass.lua: the
/// dielectric ray stack; csg.lua: the CSG interval lists), with the adapter's binding
/// limit lowered so that the window takes several bands of list slots: the same sums as
/// the private-array kernel, bit for bit, and the same image as `glint render` of that
/// variant (within the 2 ulp of the division). Where lavapipe's loop limiter cut samples
/// short (csg.lua at this size, 48–80 samples a frame), they were re-traced on the CPU
/// (the view) and their pixels re-rendered on the CPU (the render), so there the image
/// is held to the CPU tracer's render as the GPU tracer is (tier 4).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn lists_in_storage_give_the_same_sums_in_bands() {
    let Some(mut ctx) = gpu_context() else { return };
    let chosen = (ctx.kernel, ctx.limits.clone());
    let overrides = OptionOverrides {
        aa: Some(AaMode::Uniform),
        samples: AaSamples::parse("2").ok(),
        width: Some(48),
        height: Some(40),
        ..OptionOverrides::default()
    };
    for file in ["scenes/glass.lua", "scenes/csg.lua"] {
        let packed = load_packed(&root().join(file), &overrides);
        let g = packed.globals;
        let mut results = Vec::new();
        for lists_in_storage in [false, true] {
            ctx.kernel = glint::gpu::KernelConfig {
                lists_in_storage,
                ..chosen.0
            };
            let words =
                glint::gpu::compile::lists::LaneLists::of(packed.features, ctx.kernel).words();
            assert_eq!(words > 0, lists_in_storage, "{file}: {}", ctx.kernel);
            // Slots for 10 rows of the window: 4 bands.
            ctx.limits.max_storage_buffer_binding_size = match words {
                0 => chosen.1.max_storage_buffer_binding_size,
                w => u64::from(g.width * 10 * 4 * w),
            };
            let (progressive, sums, retraced) = progressive_sums(&ctx, &packed, 4, None);
            let bands = progressive.bands().len();
            eprintln!(
                "{file}, {}: {bands} bands, re-traced {retraced:?}",
                ctx.kernel
            );
            assert_eq!(bands, if lists_in_storage { 4 } else { 1 }, "{file}");
            let view = film_of_sums(&sums, g.width, g.height);
            let render = glint::gpu::render_gpu(&ctx, &packed, &Default::default()).unwrap();
            let name = format!("view {file}, {}", ctx.kernel);
            if retraced.iter().sum::<u64>() > 0 {
                let cpu = crate::common::render_cpu(&packed);
                let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("view");
                glint::diff::assert_images_match(&name, &view, &cpu, 0.01, 0.999, &out)
                    .unwrap_or_else(|message| panic!("{message}"));
            } else if render.info.cpu_fallback_pixels == 0 {
                let worst = worst_relative_difference(&view, &render.film);
                assert!(
                    worst <= 2.0 * f32::EPSILON,
                    "{name}: {worst:e} from glint render"
                );
            }
            results.push((sums, retraced));
        }
        assert!(
            results[0] == results[1],
            "{file}: the sums differ with the lists in storage"
        );
    }
    (ctx.kernel, ctx.limits) = chosen;
}
