//! The `glint` binary end to end: renders write atomically where asked, and bad input of
//! every kind exits with a clear message, the documented exit code, no panic and no
//! output file left behind.

mod common;

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
        4,
        &["out.bmp", ".png"],
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
