//! A new user's first hour (issue 56): the docs' first scene renders, the silent mistakes
//! get a note naming the call, messages point at the argument that is wrong, and the
//! rules that keep it so (GPU tests carry their mark) hold.

use crate::common::{root, temp_dir};
use glint::testing::scratch::TempDir;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn glint(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(args)
        .current_dir(cwd)
        .env("GLINT_PIPELINE_CACHE", "off")
        .output()
        .expect("glint runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Writes `scene` as `scene.lua` in a fresh folder and renders it with `args` on the CPU
/// tracer; returns the folder and the output.
fn render(tag: &str, scene: &str, args: &[&str]) -> (TempDir, Output) {
    let dir = temp_dir(tag);
    std::fs::write(dir.join("scene.lua"), scene).unwrap();
    let mut all = vec!["render", "scene.lua", "--backend", "cpu"];
    all.extend_from_slice(args);
    let out = glint(&all, &dir);
    (dir, out)
}

/// A small lit sphere scene with `fov` and one extra line before the render.
fn sphere_scene(fov: &str, extra: &str) -> String {
    format!(
        "root = gr.node('root')\ns = gr.sphere('ball')\nroot:add_child(s)\n{extra}\n\
         gr.render(root, 'out.png', 8, 8, {{0,0,5}}, {{0,0,-1}}, {{0,1,0}}, {fov}, {{0.1,0.1,0.1}}, {{gr.light({{5,5,5}}, {{1,1,1}}, {{1,0,0}})}})\n"
    )
}

/// The Lua block after `<!-- first-scene -->` in docs/scene-language.md.
fn first_scene() -> String {
    let doc = std::fs::read_to_string(root().join("docs/scene-language.md")).unwrap();
    let (_, after) = doc
        .split_once("<!-- first-scene -->\n```lua\n")
        .expect("docs/scene-language.md has the first scene");
    after.split_once("\n```").unwrap().0.to_string()
}

#[test]
fn the_docs_first_scene_renders_with_no_note() {
    let (dir, out) = render("first-scene", &first_scene(), &[]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(!err.contains("note") && !err.contains("hint"), "{err}");
    let film = glint::image_io::read_image(&dir.join("first.png")).unwrap();
    assert_eq!((film.width, film.height), (320, 240));
    // The picture beside it is this render.
    let picture = glint::image_io::read_image(&root().join("docs/first-scene.png")).unwrap();
    assert_eq!(picture.pixels, film.pixels);
    let doc = std::fs::read_to_string(root().join("docs/scene-language.md")).unwrap();
    for mistake in [
        "Degrees, not radians",
        "`view` is a direction",
        "`:` not `.`",
        "Paths",
        "linear",
    ] {
        assert!(doc.contains(mistake), "common mistakes: {mistake}");
    }
}

#[test]
fn output_transfer_srgb_encodes_png_and_leaves_exr_linear() {
    let scene = "root = gr.node('root')\ngr.render(root, 'out.png', 4, 4, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0,0,0}, {})\n";
    let background = ["--background", "0.2,0.2,0.2"];
    let (dir, out) = render("transfer-linear", scene, &background);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let linear = glint::image_io::read_image(&dir.join("out.png")).unwrap();
    assert_eq!((linear.pixels[0][0] * 255.0).round(), 51.0);
    let args = [&background[..], &["--output-transfer", "srgb"]].concat();
    let (dir, out) = render("transfer-srgb", scene, &args);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let srgb = glint::image_io::read_image(&dir.join("out.png")).unwrap();
    // sRGB(0.2) = 1.055 · 0.2^(1/2.4) − 0.055 = 0.4845 → 124.
    assert_eq!((srgb.pixels[0][0] * 255.0).round(), 124.0);
    let args = [&args[..], &["-o", "out.exr"]].concat();
    let (dir, out) = render("transfer-exr", scene, &args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(err.contains("out.exr is EXR, written linear"), "{err}");
    let exr = glint::image_io::read_image(&dir.join("out.exr")).unwrap();
    assert!((exr.pixels[0][0] - 0.2).abs() < 1e-6);
    let (dir, out) = render(
        "transfer-farm",
        scene,
        &["--output-transfer", "srgb", "--tile", "0/2"],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(!dir.join("out-tile-0-of-2.png").exists());
}

#[test]
fn radians_for_degrees_get_a_note_naming_the_call() {
    let (_, out) = render(
        "radians",
        &sphere_scene("math.rad(50)", "s:rotate('y', math.pi / 2)"),
        &[],
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        err.contains("scene.lua:5: gr.render: argument 8 (fov) is 0.87")
            && err.contains("degrees, not radians"),
        "{err}"
    );
    assert!(
        err.contains("scene.lua:4: node:rotate: argument 2 (angle) is 1.57") && err.contains("π/2"),
        "{err}"
    );
    // Degrees as meant: no note.
    let (_, out) = render("degrees", &sphere_scene("50", "s:rotate('y', 90)"), &[]);
    assert!(!stderr(&out).contains("note"), "{}", stderr(&out));
}

#[test]
fn the_eye_inside_an_opaque_solid_is_noted_by_name() {
    let scene = "root = gr.node('root')\nbox = gr.cube('walls')\nbox:translate(-0.5, -0.5, -0.5)\nbox:scale(20, 20, 20)\nroot:add_child(box)\n\
                 gr.render(root, 'out.png', 8, 8, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {gr.light({5,5,5}, {1,1,1}, {1,0,0})})\n";
    let (_, out) = render("eye-inside", scene, &[]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        err.contains("scene.lua:6: gr.render: the eye {0, 0, 5} is inside 'walls'"),
        "{err}"
    );
    let (_, out) = render("eye-outside", &sphere_scene("50", ""), &[]);
    assert!(!stderr(&out).contains("inside"), "{}", stderr(&out));
}

#[test]
fn an_empty_root_unused_frames_and_o_without_a_render() {
    let empty = "root = gr.node('root')\nkid = gr.node('kid')\nroot:add_child(kid)\ngr.render(root, 'out.png', 4, 4, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0,0,0}, {})\n";
    let (_, out) = render("empty-root", empty, &[]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        err.contains("scene.lua:4: gr.render: argument 1 (root) has nothing under it"),
        "{err}"
    );
    let (_, out) = render(
        "frames-unread",
        &sphere_scene("50", ""),
        &["--frames", "1-2"],
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(err.contains("never reads `frame` or `clock`"), "{err}");
    let (_, out) = render(
        "frames-read",
        &sphere_scene("50", "s:translate(clock, 0, 0)"),
        &["--frames", "1-2"],
    );
    assert!(!stderr(&out).contains("never reads"), "{}", stderr(&out));
    let (dir, out) = render("o-no-render", "root = gr.node('root')\n", &["-o", "x.png"]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(
        err.contains("never called gr.render, so -o x.png was not written"),
        "{err}"
    );
    assert!(!dir.join("x.png").exists());
}

#[test]
fn a_shifted_render_call_names_the_first_misplaced_argument() {
    let lights = "{gr.light({5,5,5}, {1,1,1}, {1,0,0})}";
    for call in [
        format!("gr.render(root, 160, 120, 'a.png', {{0,0,5}}, {{0,0,-1}}, {{0,1,0}}, 50, {{0.1,0.1,0.1}}, {lights})"),
        format!("gr.render(root, 160, 120, {{0,0,5}}, {{0,0,-1}}, {{0,1,0}}, 50, {{0.1,0.1,0.1}}, {lights})"),
    ] {
        let (_, out) = render("shifted", &format!("root = gr.node('root')\n{call}\n"), &[]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(3), "{err}");
        assert!(
            err.contains("scene.lua:2: gr.render: argument 2 (file) must be the image's file name, a string such as 'out.png', got 160")
                && err.contains("gr.render(root, file, width, height, eye, view, up, fov, ambient, lights[, options])"),
            "{err}"
        );
    }
}

#[test]
fn a_method_called_with_a_dot_says_to_write_a_colon() {
    let scene = "root = gr.node('root')\ns = gr.sphere('s')\nroot.add_child(s)\n";
    let (_, out) = render("dot-call", scene, &[]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(
        err.contains("scene.lua:3: node:add_child: argument 1 (child) must be a node, got nil; called with `.`? write `root:add_child(s)`"),
        "{err}"
    );
    let scene = "m = gr.material('m')\nm.set_refraction(1.5)\n";
    let (_, out) = render("dot-call-material", scene, &[]);
    assert!(
        stderr(&out).contains("write `m:set_refraction(1.5)`"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn the_pre2015_hint_needs_evidence_that_tells_the_eras_apart() {
    // docs/textures.md's way: an inline quad floor in a modern scene.
    let floor = "floor = gr.mesh('floor', {{-5,0,-5},{5,0,-5},{5,0,5},{-5,0,5}}, {{3,2,1,0}})\nroot:add_child(floor)\n";
    let (_, out) = render("inline-floor", &sphere_scene("50", floor), &[]);
    assert!(!stderr(&out).contains("pre-2015"), "{}", stderr(&out));
    let old = root().join("scenes/cs488/a4-pre2015/macho-cows.lua");
    let dir = temp_dir("pre2015-hint");
    let out = glint(
        &[
            "render",
            old.to_str().unwrap(),
            "--backend",
            "cpu",
            "-o",
            "m.png",
            "--width",
            "16",
            "--height",
            "16",
        ],
        &dir,
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        err.contains("looks like a pre-2015 CS488 scene (require('readobj')")
            && err.contains("macho-cows.lua:8)")
            && err.contains("gr.transform_order('pre') in the scene silences this hint"),
        "{err}"
    );
}

#[test]
fn a_bad_output_extension_is_refused_before_the_script_runs() {
    let (dir, out) = render("o-bmp", "error('the script ran')\n", &["-o", "out.bmp"]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("-o out.bmp: glint writes images by their extension: .png, .exr, .jpg"),
        "{err}"
    );
    assert!(
        !err.contains("the script ran") && !dir.join("out.bmp").exists(),
        "{err}"
    );
    let (dir, out) = render("o-jpg", &sphere_scene("50", ""), &["-o", "out.jpg"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let bytes = std::fs::read(dir.join("out.jpg")).unwrap();
    assert_eq!(&bytes[..3], &[0xFF, 0xD8, 0xFF], "a JPEG");
}

#[test]
fn dialect_advice_only_for_names_other_tracers_use_and_no_adapter_note() {
    let (_, out) = render("typo", "s = gr.sphre('s')\n", &[]);
    let err = stderr(&out);
    assert!(
        err.contains("nearest: gr.sphere") && !err.contains("--prelude"),
        "{err}"
    );
    let (_, out) = render("typo-method", "n = gr.node('n')\nn:roate('x', 90)\n", &[]);
    assert!(!stderr(&out).contains("--prelude"), "{}", stderr(&out));
    let (_, out) = render("foreign", "p = gr.plane('p')\n", &[]);
    assert!(stderr(&out).contains("--prelude"), "{}", stderr(&out));
    let (_, out) = render(
        "foreign-method",
        "m = gr.material('m')\nm:set_texture('w.png')\n",
        &[],
    );
    assert!(stderr(&out).contains("--prelude"), "{}", stderr(&out));
    // `--backend auto` without --stats: no note about the adapter on a run.
    let dir = temp_dir("adapter-note");
    std::fs::write(dir.join("scene.lua"), sphere_scene("50", "")).unwrap();
    let out = glint(&["render", "scene.lua"], &dir);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(!err.contains("rendering on the CPU"), "{err}");
}

#[test]
fn bench_sweep_on_a_users_scene_leads_with_flags_to_paste() {
    let dir = temp_dir("sweep-own");
    std::fs::write(dir.join("scene.lua"), sphere_scene("50", "")).unwrap();
    let out = glint(
        &[
            "bench",
            "--sweep",
            "--quick",
            "--cpu-only",
            "--scene",
            "scene.lua",
            "--plot",
            "p.svg",
        ],
        &dir,
    );
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert_eq!(out.status.code(), Some(0), "{text}{}", stderr(&out));
    let yours = text
        .find("## Your scene")
        .expect("a section for the user's scene");
    let table = text.find("| scene | setting |").unwrap();
    assert!(yours < table, "{text}");
    assert!(text[yours..table].contains("--aa "), "{text}");
    assert!(
        text.contains("is about glint's defaults, not about your scene"),
        "{text}"
    );
}

#[test]
fn the_budget_error_and_the_docs_name_sections_that_exist() {
    let kernels = std::fs::read_to_string(root().join("src/bin/glint/kernels_cmd.rs")).unwrap();
    assert!(kernels.contains("docs/gpu-kernels.md#register-budgets"));
    assert!(!kernels.contains("docs/gpu.md, \\\"Register budgets\\\""));
    let doc = std::fs::read_to_string(root().join("docs/gpu-kernels.md")).unwrap();
    assert!(doc.contains("\n### Register budgets\n"));
    let language = std::fs::read_to_string(root().join("docs/scene-language.md")).unwrap();
    assert!(language.contains("`m:set_reflection(r, g, b)`"));
    assert!(language.contains("## What a Whitted tracer does not do"));
}

#[test]
fn the_readme_puts_the_user_first() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let at = |s: &str| readme.find(s).unwrap_or_else(|| panic!("README lacks {s}"));
    let user = [
        "## Set-up",
        "## Render your own scene",
        "## Watch it live",
        "## Features",
        "## Gallery",
        "## Command line in brief",
    ];
    for w in user.windows(2) {
        assert!(at(w[0]) < at(w[1]), "{} before {}", w[0], w[1]);
    }
    assert!(at("## Command line in brief") < at("## Performance"));
    assert!(at("## Performance") < at("GPU kernels on a real GPU's compiler"));
    assert!(readme.contains("the folder glint was started in"));
    assert!(readme.contains("docs/scene-language.md#a-first-scene"));
    assert!(readme.lines().count() <= 150);
}

/// Every test that asks for a GPU (a context, or the binary's GPU backends) carries
/// `#[cfg_attr(glint_skip_gpu, ignore = …)]` or guards the request with
/// `cfg!(glint_skip_gpu)`, so that GLINT_SKIP_GPU=1 reports it as ignored.
#[test]
fn every_gpu_test_carries_the_skip_mark() {
    let asks = [
        "gpu_context(",
        "GpuContext::new(",
        "\"--backend\", \"gpu\"",
        "\"--backend\", \"both\"",
    ];
    let mut unmarked = Vec::new();
    let mut files = Vec::new();
    collect(&root().join("tests"), &mut files);
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for part in text.split("#[test]").skip(1) {
            let Some(fn_at) = part.find("fn ") else {
                continue;
            };
            let (attributes, body) = part.split_at(fn_at);
            let body = body.split("\n}\n").next().unwrap();
            let name = body[3..].split('(').next().unwrap();
            // (This test names the requests it looks for.)
            if name != "every_gpu_test_carries_the_skip_mark"
                && asks.iter().any(|a| body.contains(a))
                && !attributes.contains("glint_skip_gpu")
                && !body.contains("cfg!(glint_skip_gpu)")
            {
                unmarked.push(format!("{}: {name}", file.display()));
            }
        }
    }
    assert!(
        unmarked.is_empty(),
        "GPU tests without the skip mark: {unmarked:#?}"
    );
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            collect(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The progress bar (drawn only on a terminal: `script` from util-linux gives glint one)
/// names the file written, `-o`'s, not the name the script gave.
#[test]
fn the_progress_bar_names_the_file_written() {
    let dir = temp_dir("progress-label");
    std::fs::write(dir.join("scene.lua"), sphere_scene("50", "")).unwrap();
    let glint = env!("CARGO_BIN_EXE_glint");
    let out = Command::new("script")
        .args([
            "-qec",
            &format!("{glint} render scene.lua --backend cpu -o written.png"),
        ])
        .arg("/dev/null")
        .current_dir(&dir)
        .output()
        .expect("script (util-linux, in every Debian) runs glint on a terminal");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{text}");
    assert!(text.contains("rendering written.png ["), "{text}");
    assert!(!text.contains("rendering out.png"), "{text}");
}
