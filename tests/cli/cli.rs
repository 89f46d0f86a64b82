//! The `glint` binary end to end: renders write atomically where asked, and bad input of
//! every kind exits with a clear message, the documented exit code, no panic and no
//! output file left behind.

use crate::common;

use common::{corpus, temp_dir};
use std::path::Path;
use std::process::{Command, Output};

fn glint(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("glint runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Files in `dir` other than the scene inputs named in `inputs`.
fn outputs(dir: &Path, inputs: &[&str]) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !inputs.contains(&n.as_str()))
        .collect();
    names.sort();
    names
}

const GOOD_RENDER: &str = "gr.render(root, 'out.png', 8, 8, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {gr.light({5,5,5}, {1,1,1}, {1,0,0})})\n";

/// Runs `scene` (plus extra files) in a fresh folder; asserts failure with exit code
/// `code`, a message containing each of `needles`, no panic, and nothing written.
fn assert_fails(
    tag: &str,
    scene: &str,
    extra: &[(&str, &str)],
    args: &[&str],
    code: i32,
    needles: &[&str],
) {
    let dir = temp_dir(tag);
    std::fs::write(dir.join("scene.lua"), scene).unwrap();
    let mut inputs = vec!["scene.lua"];
    for (name, text) in extra {
        std::fs::write(dir.join(name), text).unwrap();
        inputs.push(name);
    }
    let mut all_args = vec!["render", "scene.lua"];
    all_args.extend_from_slice(args);
    let out = glint(&all_args, &dir);
    let err = stderr(&out);
    assert_eq!(
        out.status.code(),
        Some(code),
        "{tag}: exit code; stderr:\n{err}"
    );
    assert!(!err.contains("panicked"), "{tag}: panicked:\n{err}");
    for needle in needles {
        assert!(
            err.contains(needle),
            "{tag}: stderr lacks {needle:?}:\n{err}"
        );
    }
    assert_eq!(
        outputs(&dir, &inputs),
        Vec::<String>::new(),
        "{tag}: files left behind"
    );
}

#[test]
fn renders_a_scene_and_writes_png_and_exr() {
    let dir = temp_dir("cli-ok");
    let scene =
        format!("root = gr.node('root')\ns = gr.sphere('s')\nroot:add_child(s)\n{GOOD_RENDER}");
    std::fs::write(dir.join("scene.lua"), scene).unwrap();
    let out = glint(&["render", "scene.lua"], &dir);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(outputs(&dir, &["scene.lua"]), vec!["out.png"]);
    let out = glint(
        &[
            "render",
            "scene.lua",
            "-o",
            "x.exr",
            "--width",
            "4",
            "--height",
            "3",
        ],
        &dir,
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let film = glint::image_io::read_image(&dir.join("x.exr")).unwrap();
    assert_eq!((film.width, film.height), (4, 3));
}

#[test]
fn syntax_error() {
    assert_fails(
        "syntax",
        "root = gr.node('root'\n",
        &[],
        &[],
        3,
        &["scene.lua:2:", "expected"],
    );
}

#[test]
fn wrong_argument_type() {
    let scene = format!("root = gr.node('root')\ns = gr.nh_sphere('s', 'here', 1)\n{GOOD_RENDER}");
    assert_fails(
        "types",
        &scene,
        &[],
        &[],
        3,
        &["scene.lua:2:", "gr.nh_sphere", "argument 2"],
    );
}

#[test]
fn negative_radius() {
    let scene =
        format!("root = gr.node('root')\ns = gr.nh_sphere('s', {{0,0,0}}, -1)\n{GOOD_RENDER}");
    assert_fails(
        "radius",
        &scene,
        &[],
        &[],
        3,
        &["scene.lua:2:", "gr.nh_sphere", "radius", "-1"],
    );
}

#[test]
fn nan_input() {
    let scene = format!("root = gr.node('root')\nroot:translate(0/0, 0, 0)\n{GOOD_RENDER}");
    assert_fails(
        "nan",
        &scene,
        &[],
        &[],
        3,
        &["scene.lua:2:", "translate", "finite", "nan"],
    );
}

#[test]
fn singular_transform() {
    let scene = format!("root = gr.node('root')\nroot:scale(1, 0, 1)\n{GOOD_RENDER}");
    assert_fails(
        "singular",
        &scene,
        &[],
        &[],
        3,
        &["scene.lua:2:", "scale", "singular"],
    );
}

#[test]
fn missing_obj() {
    let scene = format!("root = gr.node('root')\nm = gr.mesh('m', 'nothere.obj')\n{GOOD_RENDER}");
    assert_fails(
        "missing-obj",
        &scene,
        &[],
        &[],
        3,
        &["scene.lua:2:", "nothere.obj"],
    );
}

#[test]
fn missing_and_undecodable_textures() {
    let scene = format!(
        "root = gr.node('root')\nm = gr.material('m')\nm:set_diffuse('nothere.png')\n{GOOD_RENDER}"
    );
    assert_fails(
        "missing-texture",
        &scene,
        &[],
        &[],
        3,
        &[
            "scene.lua:3: material:set_diffuse: argument 1 (file): cannot read texture",
            "nothere.png",
        ],
    );
    let scene = format!(
        "root = gr.node('root')\nm = gr.material('m')\nm:set_bump('junk.png', 2)\n{GOOD_RENDER}"
    );
    assert_fails(
        "junk-texture",
        &scene,
        &[("junk.png", "not a png")],
        &[],
        3,
        &[
            "scene.lua:3: material:set_bump: argument 1 (file): cannot decode texture",
            "junk.png",
        ],
    );
}

#[test]
fn unknown_debug_view_is_a_usage_error() {
    assert_fails(
        "debug-view",
        GOOD_RENDER,
        &[],
        &["--debug", "normals"],
        2,
        &["none", "uv"],
    );
}

/// `--shading flat` beats the scene's vertex normals (a different image, the same as the
/// scene option `shading = 'flat'`); a bad value is a usage error naming the choices.
#[test]
fn shading_flag_forces_flat_shading() {
    let dir = temp_dir("cli-shading");
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn -1 -1 1\nvn 1 0 1\nvn 0 1 1\nf 1//1 2//2 3//3\n";
    std::fs::write(dir.join("t.obj"), obj).unwrap();
    let scene = |options: &str| {
        format!(
            "root = gr.node('root')\nt = gr.mesh('t', 't.obj')\nroot:add_child(t)\n\
             gr.render(root, 'out.png', 8, 8, {{0.3,0.3,3}}, {{0,0,-1}}, {{0,1,0}}, 30, {{0.1,0.1,0.1}}, \
             {{gr.light({{5,5,5}}, {{1,1,1}}, {{1,0,0}})}}{options})\n"
        )
    };
    std::fs::write(dir.join("scene.lua"), scene("")).unwrap();
    std::fs::write(dir.join("flat.lua"), scene(", {shading = 'flat'}")).unwrap();
    let render = |args: &[&str], out: &str| {
        let mut all = vec!["render"];
        all.extend_from_slice(args);
        all.extend_from_slice(&["-o", out]);
        let o = glint(&all, &dir);
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read(dir.join(out)).unwrap()
    };
    let smooth = render(&["scene.lua"], "smooth.png");
    let flag = render(&["scene.lua", "--shading", "flat"], "flag.png");
    let option = render(&["flat.lua"], "option.png");
    assert_ne!(smooth, flag, "--shading flat changed nothing");
    assert_eq!(flag, option);
    assert_eq!(
        render(&["flat.lua", "--shading", "smooth"], "back.png"),
        smooth
    );
    assert_fails(
        "shading",
        GOOD_RENDER,
        &[],
        &["--shading", "phong"],
        2,
        &["'smooth'", "'flat'"],
    );
}

#[test]
fn malformed_obj() {
    let scene = format!(
        "root = gr.node('root')\nm = gr.mesh('m', 'bad.obj')\nroot:add_child(m)\n{GOOD_RENDER}"
    );
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 zero\nf 1 2 3\n";
    assert_fails(
        "bad-obj",
        &scene,
        &[("bad.obj", obj)],
        &[],
        3,
        &["bad.obj:3", "zero"],
    );
}

#[test]
fn runaway_loop() {
    let scene = "while true do end\n";
    assert_fails(
        "runaway",
        scene,
        &[],
        &["--instruction-limit", "100000"],
        3,
        &["scene.lua", "instruction limit"],
    );
}

#[test]
fn os_execute_is_refused() {
    let scene = "os.execute('touch pwned')\n";
    assert_fails(
        "execute",
        scene,
        &[],
        &[],
        3,
        &["scene.lua:1:", "os.execute"],
    );
}

#[test]
fn io_open_is_refused() {
    let scene = "local f = io.open('pwned', 'w')\n";
    assert_fails("io", scene, &[], &[], 3, &["scene.lua:1:", "io"]);
}

#[test]
fn unknown_output_extension_fails_before_rendering() {
    let scene = format!("root = gr.node('root')\n{GOOD_RENDER}");
    assert_fails(
        "ext",
        &scene,
        &[],
        &["-o", "out.bmp"],
        // Refused before the script runs, naming the flag (issue 56; was exit code 4 after
        // the script ran).
        2,
        &["-o out.bmp", ".png"],
    );
}

#[test]
fn bad_flag_value_is_a_usage_error() {
    let scene = format!("root = gr.node('root')\n{GOOD_RENDER}");
    assert_fails(
        "flag",
        &scene,
        &[],
        &["--aa", "sometimes"],
        2,
        &["'none', 'uniform' or 'adaptive'"],
    );
    assert_fails(
        "grid",
        &scene,
        &[],
        &["--grid", "dense"],
        2,
        &["grid must be"],
    );
    for (flag, value, range) in [
        ("--max-depth", "65", "from 0 to 64"),
        ("--shadow-samples", "0", "from 1 to 64"),
        ("--samples", "65", "from 1 to 64"),
        ("--aa-depth", "7", "from 0 to 6"),
    ] {
        assert_fails(
            flag,
            &scene,
            &[],
            &[flag, value],
            2,
            &[flag, range, &format!("'{value}'")],
        );
    }
}

#[test]
fn broken_corpus_scene_is_a_clean_lua_error() {
    let dir = temp_dir("icosa");
    let scene = corpus().join("a4-pre2015/icosa.lua");
    let out = glint(
        &[
            "render",
            scene.to_str().unwrap(),
            "--transform-order",
            "post",
        ],
        &dir,
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(
        err.contains("icosa.lua:") && !err.contains("panicked"),
        "{err}"
    );
    assert_eq!(outputs(&dir, &[]), Vec::<String>::new());
}

#[test]
fn error_in_a_later_render_keeps_earlier_images_only() {
    // The first gr.render writes its image; the script then fails: that image stays, and
    // nothing half-written appears.
    let scene = format!("root = gr.node('root')\n{GOOD_RENDER}error('boom')\n");
    let dir = temp_dir("later");
    std::fs::write(dir.join("scene.lua"), scene).unwrap();
    let out = glint(&["render", "scene.lua"], &dir);
    assert_eq!(out.status.code(), Some(3));
    assert!(stderr(&out).contains("scene.lua:3:"), "{}", stderr(&out));
    assert_eq!(outputs(&dir, &["scene.lua"]), vec!["out.png"]);
}

/// `--debug aa-samples` writes the leaf-square map of adaptive AA: the render's size,
/// several values on a scene with edges, each pixel the ramp colour of its leaf count;
/// the GPU (when there is one) writes the same map.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn debug_aa_samples_maps_adaptive_leaf_counts() {
    let scene = corpus().join("a4-2021plus/nonhier.lua");
    let (w, h, depth) = (40u32, 30u32, 3u32);
    let dir = temp_dir("aa-map");
    let size = [w.to_string(), h.to_string(), depth.to_string()];
    let map_on = |backend: &str, name: &str| {
        let args = [
            "render",
            scene.to_str().unwrap(),
            "-o",
            name,
            "--width",
            &size[0],
            "--height",
            &size[1],
            "--aa",
            "adaptive",
            "--aa-depth",
            &size[2],
            "--backend",
            backend,
            "--debug",
            "aa-samples",
        ];
        let out = glint(&args, &dir);
        assert!(out.status.success(), "{backend}: {}", stderr(&out));
        glint::image_io::read_image(&dir.join(name)).unwrap()
    };
    let map = map_on("cpu", "map-cpu.png");
    assert_eq!((map.width, map.height), (w, h));

    let overrides = glint::scene::OptionOverrides {
        width: Some(w),
        height: Some(h),
        aa: Some(glint::scene::AaMode::Adaptive),
        aa_depth: Some(glint::scene::AaDepth::constant(depth)),
        ..Default::default()
    };
    let packed = common::load_packed(&scene, &overrides);
    let leaves = glint::tracer::sampling::render::adaptive_leaf_counts(&packed);
    let ramp = glint::aa_map::magma_ramp();
    let rgb = map.to_rgb8();
    for (k, &l) in leaves.iter().enumerate() {
        let expected = glint::aa_map::aa_samples_colour(&ramp, l, depth);
        assert_eq!(rgb[3 * k..3 * k + 3], expected, "pixel {k}: {l} leaves");
    }
    let mut distinct: Vec<[u8; 3]> = rgb.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    distinct.sort();
    distinct.dedup();
    assert!(distinct.len() > 1, "a scene with edges gives a flat map");

    // The GPU half only where GPU tests run (built with GLINT_SKIP_GPU=1, asking for a
    // context is the mistake the marks guard against).
    if !cfg!(glint_skip_gpu) && common::gpu_context().is_some() {
        let gpu = map_on("gpu", "map-gpu.png");
        assert_eq!(gpu.to_rgb8(), rgb, "GPU and CPU maps differ");
    }
}

/// The scene option `debug = 'aa-samples'` and the flag `--debug aa-samples` are one
/// setting: the same map, byte for byte; `--debug none` turns the scene's off.
#[test]
fn debug_aa_samples_is_one_option_for_script_and_flag() {
    let dir = temp_dir("aa-map-option");
    let body = "root = gr.node('root')\ns = gr.sphere('s')\nroot:add_child(s)\n";
    let with_option = GOOD_RENDER.replace("{1,0,0})})", "{1,0,0})}, {debug='aa-samples'})");
    assert_ne!(with_option, GOOD_RENDER);
    std::fs::write(dir.join("flag.lua"), format!("{body}{GOOD_RENDER}")).unwrap();
    std::fs::write(dir.join("option.lua"), format!("{body}{with_option}")).unwrap();
    let run = |script: &str, out: &str, extra: &[&str]| {
        let mut args = vec!["render", script, "-o", out, "--backend", "cpu"];
        args.extend_from_slice(extra);
        let o = glint(&args, &dir);
        assert!(o.status.success(), "{script}: {}", stderr(&o));
        std::fs::read(dir.join(out)).unwrap()
    };
    let by_flag = run("flag.lua", "flag.png", &["--debug", "aa-samples"]);
    let by_option = run("option.lua", "option.png", &[]);
    assert_eq!(
        by_flag, by_option,
        "the scene option and the flag give different maps"
    );
    let render = run("flag.lua", "render.png", &[]);
    let turned_off = run("option.lua", "off.png", &["--debug", "none"]);
    assert_eq!(
        render, turned_off,
        "--debug none leaves the scene's debug view on"
    );
    assert_ne!(render, by_flag, "the map is the render");
}

#[test]
fn debug_aa_samples_without_adaptive_aa_is_a_usage_error() {
    let scene = format!("root = gr.node('root')\n{GOOD_RENDER}");
    assert_fails(
        "aa-map-uniform",
        &scene,
        &[],
        &["--aa", "uniform", "--debug", "aa-samples"],
        2,
        &["--debug aa-samples", "'uniform'", "--aa adaptive"],
    );
}

/// `glint bench --sweep --quick --cpu-only --repeat 1` with `extra` arguments, in `cwd`.
fn quick_sweep(extra: &[&str], cwd: &Path) -> Output {
    let mut args = vec!["bench", "--sweep", "--quick", "--cpu-only", "--repeat", "1"];
    args.extend_from_slice(extra);
    glint(&args, cwd)
}

/// `glint bench --sweep --quick` runs the whole sweep machinery on tiny images: the table,
/// the reference residuals, the default rule, the adaptive-vs-uniform and slope figures,
/// and the plot.
/// (No timing is asserted: performance is measured by the benchmark, not by tests.)
#[test]
fn bench_sweep_quick_prints_its_figures_and_writes_the_plot() {
    let dir = temp_dir("sweep");
    let plot = dir.join("plot.svg");
    let out = quick_sweep(&["--plot", plot.to_str().unwrap()], &common::root());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}\n{text}", stderr(&out));
    for needle in [
        "| soft-shadows | uniform 2×2 |",
        "| demo | adaptive t=0.1 d=2 |",
        "aa none, shadows 4×4",
        "Reference residuals",
        "Adaptive AA against uniform 4×4",
        "Default rule",
        "against uniform 4×4 (target",
        "slope",
        "GPU column skipped: --cpu-only",
    ] {
        assert!(text.contains(needle), "stdout lacks {needle:?}:\n{text}");
    }
    let svg = std::fs::read_to_string(&plot).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(svg.matches("<polyline").count() >= 4, "{svg}");
    assert_eq!(
        outputs(&dir, &[]),
        vec!["plot.svg"],
        "temp file left behind"
    );
}

/// `glint bench --sweep --scene FILE` sweeps the user's scene instead of glint's own, at
/// `--size` pixels wide and the scene's own aspect ratio, and by default writes the plot
/// to the current folder.
#[test]
fn bench_sweep_on_a_scene_of_ones_own() {
    let dir = temp_dir("sweep-own");
    let scene = dir.join("wide.lua");
    std::fs::write(
        &scene,
        "s = gr.sphere('s') s:set_material(gr.material({0.8, 0.2, 0.2}, {0.5, 0.5, 0.5}, 25))
         gr.render(s, 'wide.png', 40, 20, {0, 0, 4}, {0, 0, -1}, {0, 1, 0}, 50,
                   {0.3, 0.3, 0.3}, {gr.light({2, 3, 4}, {0.9, 0.9, 0.9}, {1, 0, 0})})",
    )
    .unwrap();
    let out = quick_sweep(&["--scene", scene.to_str().unwrap()], &dir);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}\n{text}", stderr(&out));
    assert!(text.contains("| wide 24×12 | uniform 2×2 |"), "{text}");
    assert!(!text.contains("| demo |"), "{text}");
    let svg = std::fs::read_to_string(dir.join("error-vs-time.svg")).unwrap();
    assert!(svg.starts_with("<svg"));
}

#[test]
fn bad_csg_operand_and_too_deep_csg() {
    let scene = format!(
        "root = gr.node('root')\nm = gr.mesh('m', {{{{0,0,0}},{{1,0,0}},{{0,1,0}}}}, {{{{0,1,2}}}})\nc = gr.csg('c', 'd', gr.sphere('s'), m)\n{GOOD_RENDER}"
    );
    assert_fails(
        "csg-mesh",
        &scene,
        &[],
        &[],
        3,
        &[
            "scene.lua:3:",
            "gr.csg: argument 4 (b) must be a primitive or CSG node",
            "mesh node 'm'",
        ],
    );
    let mut scene = String::from("root = gr.node('root')\nn = gr.sphere('s')\n");
    for i in 1..=17 {
        scene += &format!("n = gr.csg('c{i}', 'u', n, gr.sphere('s{i}'))\n");
    }
    scene += &format!("root:add_child(n)\n{GOOD_RENDER}");
    assert_fails(
        "csg-depth",
        &scene,
        &[],
        &[],
        3,
        &[
            "gr.render",
            "CSG node 'root/c17' nests CSG operations deeper than 16 levels",
        ],
    );
}

/// `--backend both`: both images and the heat map written, the figures and both times
/// printed, exit 0 when the tracers agree; a share outside 0–1, or `--heatmap` without
/// `--backend both`, is a command-line error.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn backend_both_renders_on_both_tracers_and_judges_them() {
    if common::gpu_context().is_none() {
        return;
    }
    let scene = corpus().join("a4-2021plus/nonhier.lua");
    let dir = temp_dir("both");
    let args = [
        "render",
        scene.to_str().unwrap(),
        "-o",
        "n.png",
        "--width",
        "48",
        "--height",
        "32",
        "--aa",
        "none",
        "--backend",
        "both",
        "--heatmap",
        "heat.png",
    ];
    let out = glint(&args, &dir);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{}{stdout}", stderr(&out));
    assert_eq!(
        outputs(&dir, &[]),
        vec!["heat.png", "n-cpu.png", "n-gpu.png"]
    );
    for needle in ["CPU ", "GPU ", "FLIP mean", "agree:", "within 2.0/255"] {
        assert!(stdout.contains(needle), "{needle}: {stdout}");
    }
    // A share outside 0–1 is a command-line error.
    let mut bad = args.to_vec();
    bad.extend(["--min-within", "1.5"]);
    assert_eq!(glint(&bad, &dir).status.code(), Some(2));
    // --heatmap alone is refused before anything renders.
    let lone = ["render", scene.to_str().unwrap(), "--heatmap", "h.png"];
    let out = glint(&lone, &dir);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("--backend both"), "{}", stderr(&out));
}

/// `--backend both` fails with exit code 6 when the images differ beyond the tolerance:
/// with a tolerance of 0 and every pixel required, the f32 rounding differences of the
/// GPU's sqrt, division and normalize (a few ulps in some pixels of the unquantised
/// films) are enough.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn backend_both_exits_6_when_the_images_differ() {
    if common::gpu_context().is_none() {
        return;
    }
    let dir = temp_dir("both-differ");
    let scene = corpus().join("a4-2021plus/macho-cows.lua");
    let args = [
        "render",
        scene.to_str().unwrap(),
        "-o",
        "c.exr",
        "--width",
        "64",
        "--height",
        "64",
        "--aa",
        "none",
        "--backend",
        "both",
        "--tolerance",
        "0",
        "--min-within",
        "1",
    ];
    let out = glint(&args, &dir);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert_eq!(out.status.code(), Some(6), "{}{stdout}", stderr(&out));
    assert!(stdout.contains("DIFFER"), "{stdout}");
}

/// `glint info` lists each adapter with the kernel variant glint would compile on it
/// (workgroup size and mailboxes, chosen from the adapter's type and limits).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn info_names_the_kernel_variant_of_each_adapter() {
    let Some(_) = common::gpu_context() else {
        return;
    };
    let out = glint(&["info"], &temp_dir("info"));
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    let adapters = text.lines().filter(|l| l.starts_with("adapter ")).count();
    let kernels: Vec<&str> = text
        .lines()
        .filter_map(|l| l.strip_prefix("  glint's kernel on it: "))
        .collect();
    assert!(adapters >= 1, "{text}");
    assert_eq!(kernels.len(), adapters, "{text}");
    // Each adapter's texture side, which bounds the scene's tables (src/gpu/upload/tables.rs).
    let sides = text
        .lines()
        .filter(|l| l.starts_with("  max 2-D texture side: ") && l.contains("texels each"))
        .count();
    assert_eq!(sides, adapters, "{text}");
    for k in kernels {
        assert!(
            k.starts_with("workgroup ") && k.contains("mailbox"),
            "{text}"
        );
    }
    // A software adapter (lavapipe) keeps one mailbox slot and guards its loops, and glint
    // gives llvmpipe four worker threads a core unless the user set LP_NUM_THREADS.
    if text.contains("device type: Cpu") {
        assert!(
            text.contains("llvmpipe worker threads: ") && text.contains("(LP_NUM_THREADS)"),
            "{text}"
        );
        let mine = Command::new(env!("CARGO_BIN_EXE_glint"))
            .arg("info")
            .env("LP_NUM_THREADS", "3")
            .output()
            .unwrap();
        let mine = String::from_utf8_lossy(&mine.stdout);
        assert!(
            mine.contains("llvmpipe worker threads: 3 (LP_NUM_THREADS)"),
            "{mine}"
        );
        assert!(
            text.contains("last-item mailbox, iteration guard"),
            "{text}"
        );
    }
}

const TRIANGLE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

/// Issue 37: the course ran `./A4 Assets/scene.lua` from the assignment folder, and its
/// scenes name `'Assets/cow.obj'`: found from the folder glint was started in when the
/// scene lies inside it; otherwise the error names both paths tried, and a case-only
/// near miss is offered.
#[test]
fn relative_paths_resolve_beside_the_scene_then_from_the_start_folder() {
    let dir = temp_dir("course-layout");
    std::fs::create_dir_all(dir.join("Assets")).unwrap();
    std::fs::write(dir.join("Assets/cow.obj"), TRIANGLE_OBJ).unwrap();
    std::fs::write(dir.join("Assets/Eevee.obj"), TRIANGLE_OBJ).unwrap();
    let scene = |file: &str| {
        format!(
            "root = gr.node('root')\nm = gr.mesh('m', '{file}')\nroot:add_child(m)\n{GOOD_RENDER}"
        )
    };
    for (file, ok) in [
        ("Assets/cow.obj", true),
        ("cow.obj", true),
        ("Assets/nothere.obj", false),
    ] {
        std::fs::write(dir.join("Assets/scene.lua"), scene(file)).unwrap();
        let out = glint(&["render", "Assets/scene.lua", "-o", "out.png"], &dir);
        let err = stderr(&out);
        assert_eq!(out.status.success(), ok, "{file}: {err}");
        if !ok {
            assert!(
                err.contains(
                    "Assets/scene.lua:2: gr.mesh: cannot read mesh file 'Assets/nothere.obj'"
                ) && err.contains("'Assets/Assets/nothere.obj'")
                    && err.contains("from the folder glint was started in"),
                "{err}"
            );
        }
    }
    std::fs::write(dir.join("Assets/scene.lua"), scene("eevee.obj")).unwrap();
    let out = glint(&["render", "Assets/scene.lua", "-o", "out.png"], &dir);
    assert!(
        stderr(&out).contains("did you mean 'Eevee.obj'?"),
        "{}",
        stderr(&out)
    );
    std::fs::write(dir.join("Assets/scene.lua"), scene("assets/eevee.obj")).unwrap();
    let out = glint(&["render", "Assets/scene.lua", "-o", "out.png"], &dir);
    assert!(
        stderr(&out).contains("did you mean 'Assets/Eevee.obj'?"),
        "{}",
        stderr(&out)
    );
    // A scene outside the start folder gains nothing from it.
    let elsewhere = temp_dir("course-elsewhere");
    std::fs::write(elsewhere.join("scene.lua"), scene("Assets/cow.obj")).unwrap();
    let path = elsewhere.join("scene.lua");
    let out = glint(&["render", path.to_str().unwrap(), "-o", "out.png"], &dir);
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
}

/// Issue 37: a note per call site on stderr for arguments glint does not use (also a
/// non-table after gr.render's lights, which is ignored); --ignore-extra-arguments
/// silences them.
#[test]
fn extra_arguments_are_noted_on_stderr_unless_ignored() {
    let dir = temp_dir("extra-arguments");
    // (A sphere under the root: an empty root would get a note of its own.)
    let scene = "root = gr.node('root') root:add_child(gr.sphere('s'))\nm = gr.material({1,1,1}, {0,0,0}, 10, 0.5)\n\
        gr.render(root, 'out.png', 8, 8, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {gr.light({5,5,5}, {1,1,1}, {1,0,0})}, 4)\n";
    std::fs::write(dir.join("scene.lua"), scene).unwrap();
    let out = glint(&["render", "scene.lua"], &dir);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert_eq!(err.matches("glint: note: scene.lua:").count(), 2, "{err}");
    assert!(
        err.contains("glint: note: scene.lua:2: gr.material: uses 3 arguments but was passed 4"),
        "{err}"
    );
    assert!(
        err.contains("glint: note: scene.lua:3: gr.render: ignores argument 11"),
        "{err}"
    );
    let out = glint(&["render", "scene.lua", "--ignore-extra-arguments"], &dir);
    assert!(
        out.status.success() && !stderr(&out).contains("note: scene.lua"),
        "{}",
        stderr(&out)
    );
}

/// Every mode runs the script through one driver: `--backend both` refuses a read outside
/// the allowed folders, stops a runaway at `--script-timeout` and honours
/// `--memory-limit` exactly as `--backend cpu` does (same exit code, same message), and
/// `--allow-read` widens both alike.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn backend_both_runs_the_script_under_the_same_limits_as_cpu() {
    if common::gpu_context().is_none() {
        return;
    }
    let outside = temp_dir("both-limits-outside");
    std::fs::write(
        outside.join("tri.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let mesh = outside.join("tri.obj").display().to_string();
    let read_outside =
        format!("root = gr.node('root')\nroot:add_child(gr.mesh('m', '{mesh}'))\n{GOOD_RENDER}");
    // An instruction limit far above what the timeout allows, so only the timeout stops it.
    let runaway = "local x = 0\nwhile true do x = x + 1 end\n";
    let hungry = "local s = string.rep('x', 64 << 20)\n";
    let cases: [(&str, &str, &[&str], &[&str]); 3] = [
        (
            "read",
            &read_outside,
            &[],
            &["scene.lua:2:", "outside the folders"],
        ),
        (
            "runaway",
            runaway,
            &[
                "--instruction-limit",
                "1000000000000",
                "--script-timeout",
                "2",
            ],
            &["scene.lua", "time limit"],
        ),
        (
            "memory",
            hungry,
            &["--memory-limit", "32"],
            &["scene.lua", "memory limit of 32 MiB"],
        ),
    ];
    for (tag, scene, args, needles) in cases {
        for backend in ["cpu", "both"] {
            let tag = format!("both-limits-{tag}-{backend}");
            let mut all = args.to_vec();
            all.extend(["--backend", backend]);
            let start = std::time::Instant::now();
            assert_fails(&tag, scene, &[], &all, 3, needles);
            assert!(
                start.elapsed() < std::time::Duration::from_secs(20),
                "{tag}: took {:?}",
                start.elapsed()
            );
        }
    }
    // Widened by --allow-read, both modes render the mesh.
    for backend in ["cpu", "both"] {
        let dir = temp_dir(&format!("both-limits-allowed-{backend}"));
        std::fs::write(dir.join("scene.lua"), &read_outside).unwrap();
        let allow = outside.display().to_string();
        let out = glint(
            &[
                "render",
                "scene.lua",
                "--backend",
                backend,
                "--allow-read",
                &allow,
            ],
            &dir,
        );
        assert!(out.status.success(), "{backend}: {}", stderr(&out));
    }
}

/// The default script timeout ends a runaway that the instruction hook cannot see (a
/// backtracking pattern inside Lua's C library) well within 30 s, start-up included.
#[test]
fn default_script_timeout_ends_a_stuck_pattern_within_30_s() {
    let scene = "string.find(string.rep('a', 5000), string.rep('a*', 30) .. 'b')\n";
    let start = std::time::Instant::now();
    assert_fails(
        "stuck-pattern",
        scene,
        &[],
        &["--backend", "cpu"],
        3,
        &["scene.lua", "script time limit of 15 s"],
    );
    let took = start.elapsed();
    assert!(took < std::time::Duration::from_secs(30), "took {took:?}");
}

/// `--prelude` reaches every mode that runs a script: `render` on the CPU, `--backend
/// both` (when a GPU adapter exists) and `bench --trace`; a flag naming no file is a
/// command-line error, and an error inside a prelude names the prelude's line.
#[test]
fn prelude_runs_in_every_mode_that_runs_a_script() {
    let dialects = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/dialects");
    let scene = dialects.join("examples/planes.lua");
    let prelude = dialects.join("planes.lua");
    let (scene, prelude) = (scene.to_str().unwrap(), prelude.to_str().unwrap());
    let dir = temp_dir("prelude-modes");
    let small = ["--width", "24", "--height", "16", "--aa", "none"];
    let mut cpu = vec![
        "render",
        scene,
        "-o",
        "p.png",
        "--backend",
        "cpu",
        "--prelude",
        prelude,
    ];
    cpu.extend(small);
    let out = glint(&cpu, &dir);
    assert!(out.status.success(), "cpu: {}", stderr(&out));
    // Without it the scene's calls are unknown: exit code 3, naming the line.
    let out = glint(&cpu[..6], &dir);
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    assert!(stderr(&out).contains("planes.lua:14:"), "{}", stderr(&out));
    let trace = [
        "bench",
        "--trace",
        scene,
        "--prelude",
        prelude,
        "--width",
        "16",
        "--height",
        "8",
        "--repeat",
        "1",
    ];
    let out = glint(&trace, &dir);
    assert!(out.status.success(), "bench --trace: {}", stderr(&out));
    // The GPU half only where GPU tests run (built with GLINT_SKIP_GPU=1, asking for a
    // context is the mistake the marks guard against).
    if !cfg!(glint_skip_gpu) && common::gpu_context().is_some() {
        let mut both = vec!["render", scene, "-o", "b.png", "--backend", "both"];
        both.extend(["--prelude", prelude]);
        both.extend(small);
        let out = glint(&both, &dir);
        assert!(out.status.success(), "both: {}", stderr(&out));
        assert!(dir.join("b-cpu.png").exists() && dir.join("b-gpu.png").exists());
    }
    let missing = ["render", scene, "--prelude", "no-such-prelude.lua"];
    let out = glint(&missing, &dir);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("--prelude no-such-prelude.lua"),
        "{}",
        stderr(&out)
    );
    assert_fails(
        "prelude-error",
        &format!("root = gr.node('root')\n{GOOD_RENDER}"),
        &[(
            "bad-prelude.lua",
            "x = 1\nerror('this dialect is broken')\n",
        )],
        &["--prelude", "bad-prelude.lua"],
        3,
        &["bad-prelude.lua:2: this dialect is broken"],
    );
}
