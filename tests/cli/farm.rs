//! The farm interface end to end: `glint render --tile/--crop/--frames/--frame
//! --skip-existing` and `glint assemble`, through the binary. Tiles assembled are the full
//! render's file byte for byte; bad tilings are refused naming the tiles; bad flags are
//! usage errors (exit code 2) that write nothing.

use crate::common;

use common::temp_dir;
use std::path::Path;
use std::process::{Command, Output};

/// A sphere that crosses the view as `clock` runs from 0 to 1, against a gradient, with an
/// area light's penumbra: edges of every kind for adaptive AA.
const SCENE: &str = r#"
local t = clock or 0.25
if frame ~= nil then
  assert(math.type(frame) == 'integer', 'frame is an integer')
end
root = gr.node('root')
s = gr.sphere('s')
root:add_child(s)
s:set_material(gr.material({0.8, 0.3, 0.2}, {0.5, 0.5, 0.5}, 25))
s:translate(-1.5 + 3 * t, 0, 0)
floor = gr.cube('floor')
root:add_child(floor)
floor:set_material(gr.material({0.4, 0.6, 0.4}, {0, 0, 0}, 10))
floor:scale(8, 0.2, 8)
floor:translate(-4, -1.4, -4)
l = gr.light({2, 5, 5}, {0.9, 0.9, 0.9}, {1, 0, 0})
gr.render(root, 'out.png', 23, 17, {0, 0, 6}, {0, 0, -1}, {0, 1, 0}, 50, {0.2, 0.2, 0.2}, {l})
"#;

fn glint_env(args: &[&str], cwd: &Path, env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_glint"));
    c.args(args).current_dir(cwd);
    for name in ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"] {
        c.env_remove(name);
    }
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("glint runs")
}

fn glint(args: &[&str], cwd: &Path) -> Output {
    glint_env(args, cwd, &[])
}

fn ok(o: &Output) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "glint failed: {err}");
    err
}

/// A folder holding the scene as scene.lua.
fn scene_dir(tag: &str) -> glint::testing::scratch::TempDir {
    let dir = temp_dir(tag);
    std::fs::write(dir.join("scene.lua"), SCENE).unwrap();
    dir
}

const CPU: [&str; 4] = ["--backend", "cpu", "--aa", "adaptive"];

fn render(dir: &Path, extra: &[&str]) -> String {
    let mut args = vec!["render", "scene.lua"];
    args.extend(CPU);
    args.extend(extra);
    ok(&glint(&args, dir))
}

fn read(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn tiles_assemble_to_the_full_render_byte_for_byte() {
    let dir = scene_dir("farm-assemble");
    render(&dir, &["-o", "full.png"]);
    // As a Slurm array and a Kubernetes Indexed Job would run it, at two thread counts.
    for i in 0..5 {
        let (var, threads) = match i % 2 {
            0 => ("SLURM_ARRAY_TASK_ID", "1"),
            _ => ("JOB_COMPLETION_INDEX", "2"),
        };
        let index = i.to_string();
        let mut args = vec!["render", "scene.lua", "--tile", "auto/5", "-o", "t.png"];
        args.extend(CPU);
        args.extend(["--threads", threads]);
        ok(&glint_env(&args, &dir, &[(var, &index)]));
    }
    let tiles: Vec<String> = (0..5).map(|i| format!("t-tile-{i}-of-5.png")).collect();
    let mut args = vec!["assemble", "-o", "joined.png"];
    args.extend(tiles.iter().map(String::as_str));
    ok(&glint(&args, &dir));
    assert!(
        read(&dir, "full.png") == read(&dir, "joined.png"),
        "the assembled image differs from the full render"
    );
    // A crop window is a tile too: with the rest, the same image.
    render(&dir, &["--crop", "0,23,0,5", "-o", "top.png"]);
    render(&dir, &["--crop", "0,23,5,17", "-o", "rest.png"]);
    ok(&glint(
        &["assemble", "rest.png", "top.png", "-o", "two.png"],
        &dir,
    ));
    assert!(read(&dir, "full.png") == read(&dir, "two.png"));
}

#[test]
fn exr_tiles_assemble_to_the_full_exr_byte_for_byte() {
    let dir = scene_dir("farm-exr");
    render(&dir, &["-o", "full.exr"]);
    for i in 0..3 {
        render(&dir, &["--tile", &format!("{i}/3"), "-o", "t.exr"]);
    }
    let tiles: Vec<String> = (0..3).map(|i| format!("t-tile-{i}-of-3.exr")).collect();
    let mut args = vec!["assemble", "-o", "joined.exr"];
    args.extend(tiles.iter().map(String::as_str));
    ok(&glint(&args, &dir));
    assert!(
        read(&dir, "full.exr") == read(&dir, "joined.exr"),
        "the assembled EXR differs from the full render"
    );
    // EXR tiles make an EXR; PNG and EXR tiles do not mix.
    render(&dir, &["--tile", "0/3", "-o", "p.png"]);
    assemble_fails(
        &dir,
        &[&tiles[0], &tiles[1], &tiles[2]],
        &["the tiles are EXR", ".exr"],
    );
    assemble_fails(
        &dir,
        &["p-tile-0-of-3.png", &tiles[1], &tiles[2]],
        &["t-tile-1-of-3.exr is EXR", "share a format"],
    );
}

fn assemble_fails(dir: &Path, tiles: &[&str], needles: &[&str]) {
    let mut args = vec!["assemble", "-o", "bad.png"];
    args.extend(tiles);
    let o = glint(&args, dir);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{tiles:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{tiles:?}: '{n}' not in: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    assert!(!dir.join("bad.png").exists(), "{tiles:?} left an output");
}

#[test]
fn assemble_refuses_gaps_overlaps_and_foreign_tiles() {
    let dir = scene_dir("farm-refuse");
    for i in 0..4 {
        render(&dir, &["--tile", &format!("{i}/4"), "-o", "t.png"]);
    }
    render(&dir, &["--tile", "0/2", "-o", "half.png"]);
    render(
        &dir,
        &["--tile", "1/4", "--background", "1,0,0", "-o", "red.png"],
    );
    render(&dir, &["-o", "plain.png"]);
    let t = |i: u32| format!("t-tile-{i}-of-4.png");
    let (t0, t1, t2, t3) = (t(0), t(1), t(2), t(3));
    assemble_fails(&dir, &[&t0, &t1, &t3], &["gap", "tile 2/4"]);
    assemble_fails(
        &dir,
        &[&t0, &t1, &t2, &t3, "half-tile-0-of-2.png"],
        &["overlap", "half-tile-0-of-2.png", &t0],
    );
    assemble_fails(
        &dir,
        &[&t0, "red-tile-1-of-4.png", &t2, &t3],
        &["red-tile-1-of-4.png", "another render"],
    );
    assemble_fails(
        &dir,
        &[&t0, "plain.png"],
        &["plain.png is not a glint tile"],
    );
    assemble_fails(&dir, &[&t0, "missing.png"], &["missing.png"]);
    ok(&glint(
        &["assemble", &t0, &t1, &t2, &t3, "-o", "good.png"],
        &dir,
    ));
}

#[test]
fn skip_existing_keeps_a_tile_of_the_same_render_only() {
    let dir = scene_dir("farm-skip");
    let args = ["--tile", "1/3", "-o", "t.png", "--skip-existing"];
    assert!(render(&dir, &args).contains("glint: wrote"));
    let path = dir.join("t-tile-1-of-3.png");
    let written = std::fs::metadata(&path).unwrap().modified().unwrap();
    let again = render(&dir, &args);
    assert!(again.contains("glint: kept"), "{again}");
    assert_eq!(
        std::fs::metadata(&path).unwrap().modified().unwrap(),
        written
    );
    // Another render's tile of the same name is rendered over.
    let mut other = args.to_vec();
    other.extend(["--background", "0,0,1"]);
    assert!(render(&dir, &other).contains("glint: wrote"));
    // So is a foreign file in its place.
    std::fs::write(&path, b"not a png").unwrap();
    assert!(render(&dir, &args).contains("glint: wrote"));
    assert!(render(&dir, &args).contains("glint: kept"));
}

#[test]
fn frames_run_the_script_with_frame_and_clock() {
    let dir = scene_dir("farm-frames");
    render(&dir, &["--frames", "1-3", "-o", "out.png"]);
    let frames: Vec<Vec<u8>> = (1..=3)
        .map(|n| read(&dir, &format!("out-{n:04}.png")))
        .collect();
    assert!(frames[0] != frames[2], "the clock moved nothing");
    // One frame of the range has that frame's clock; a frame and tiles combine.
    render(&dir, &["--frames", "1-3", "--frame", "3", "-o", "one.png"]);
    assert!(read(&dir, "one-0003.png") == frames[2]);
    for i in 0..2 {
        let frame = [("SLURM_ARRAY_TASK_ID", "1")];
        let mut args = vec!["render", "scene.lua", "--frames", "1-3", "--frame", "auto"];
        args.extend(CPU);
        let tile = format!("{i}/2");
        args.extend(["--tile", &tile, "-o", "f.png"]);
        ok(&glint_env(&args, &dir, &frame));
    }
    ok(&glint(
        &[
            "assemble",
            "f-0002-tile-0-of-2.png",
            "f-0002-tile-1-of-2.png",
            "-o",
            "f2.png",
        ],
        &dir,
    ));
    assert!(
        read(&dir, "f2.png") == frames[1],
        "frame 2 from tiles differs"
    );
    // A step: frames 0, 2, 4 of 0-4, clocks 0, 0.5, 1, so frame 2 of 0-4 is frame 2 of 1-3.
    render(&dir, &["--frames", "0-4:2", "-o", "step.png"]);
    assert!(!dir.join("step-0001.png").exists());
    assert!(read(&dir, "step-0004.png") == frames[2]);
}

#[test]
fn farm_flags_give_usage_errors_and_write_nothing() {
    let dir = scene_dir("farm-usage");
    let cases: &[(&[&str], &str)] = &[
        (&["--tile", "4/4"], "not below the tile count"),
        (&["--tile", "1/0"], "tile count must be"),
        (&["--tile", "x"], "expected I/N"),
        (&["--tile", "auto/4"], "neither is set"),
        (&["--crop", "0,99,0,1"], "reaches outside the 23×17 image"),
        (&["--crop", "3,3,0,1"], "half-open"),
        (&["--crop", "1,2,3"], "expected x0,x1,y0,y1"),
        (
            &["--tile", "0/2", "-o", "t.jpg"],
            "tiles are written as PNG or EXR",
        ),
        (&["--tile", "0/997"], "no grid of 997 tiles"),
        (&["--frames", "5-1"], "after the last"),
        (&["--frames", "1-5:0"], "step must be at least 1"),
        (
            &["--frames", "1-5", "--frame", "7"],
            "not a frame of --frames",
        ),
        (&["--frame", "auto"], "give --frames too"),
        (&["--tile", "0/2", "--crop", "0,1,0,1"], "give one"),
        (
            &["--tile", "auto/2", "--frames", "1-2", "--frame", "auto"],
            "same task index",
        ),
        (&["--tile", "0/2", "--stats"], "does not combine"),
    ];
    for (extra, needle) in cases {
        let mut args = vec!["render", "scene.lua", "--backend", "cpu"];
        args.extend(*extra);
        let o = glint_env(&args, &dir, &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(needle), "{extra:?}: '{needle}' not in: {err}");
        let names: Vec<_> = std::fs::read_dir(&*dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 1, "{extra:?} wrote {names:?}");
    }
}

#[test]
fn a_scene_error_under_farm_flags_is_the_scenes_with_its_line() {
    let dir = temp_dir("farm-scene-error");
    // A zero scale factor: the script fails at that call (exit code 3, as without them).
    let bad = SCENE.replace("s:translate(-1.5 + 3 * t, 0, 0)", "s:scale(0, 1, 1)");
    std::fs::write(dir.join("bad.lua"), bad).unwrap();
    for extra in [&["--tile", "0/2"][..], &["--frames", "1-2"][..]] {
        let mut args = vec!["render", "bad.lua", "--backend", "cpu"];
        args.extend(extra);
        let o = glint(&args, &dir);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(3), "{extra:?}: {err}");
        assert!(err.contains("bad.lua:"), "{extra:?}: no line in: {err}");
        let names: Vec<_> = std::fs::read_dir(&*dir).unwrap().collect();
        assert_eq!(names.len(), 1, "{extra:?} wrote a file");
    }
}

#[test]
fn the_shipped_animation_moves_its_camera() {
    let dir = temp_dir("farm-orbit");
    let scene = common::root().join("scenes/scrabble-orbit.lua");
    let scene = scene.to_str().unwrap();
    let args = [
        "render",
        scene,
        "--backend",
        "cpu",
        "--aa",
        "none",
        "--frames",
        "1-2",
    ];
    let mut args = args.to_vec();
    args.extend(["--width", "16", "--height", "9", "-o", "orbit.png"]);
    ok(&glint(&args, &dir));
    assert!(read(&dir, "orbit-0001.png") != read(&dir, "orbit-0002.png"));
}

/// The farm flags confine a script's own output names as every mode does: a name that
/// leaves the current folder (`..`, an absolute path) is refused at its `gr.render`
/// (exit code 3, naming the line), under `--tile`, `--crop` and `--frames` alike, and
/// nothing is written outside; `-o`, the user's choice, is not confined.
#[test]
fn farm_flags_confine_the_scripts_output_names() {
    let outer = temp_dir("farm-confined");
    let dir = outer.join("case");
    std::fs::create_dir(&dir).unwrap();
    let escape = outer.join("escape.png").display().to_string();
    for name in ["../escape.png", escape.as_str()] {
        std::fs::write(
            dir.join("scene.lua"),
            SCENE.replace("'out.png'", &format!("'{name}'")),
        )
        .unwrap();
        for flags in [
            &["--tile", "0/2"][..],
            &["--crop", "0,5,0,5"],
            &["--frames", "1-2"],
        ] {
            let mut args = vec!["render", "scene.lua", "--aa", "none"];
            args.extend_from_slice(flags);
            let out = glint(&args, &dir);
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(3), "{name} {flags:?}: {err}");
            assert!(err.contains("scene.lua:17:"), "{name} {flags:?}: {err}");
            let left: Vec<_> = std::fs::read_dir(&outer)
                .unwrap()
                .map(|e| e.unwrap().file_name())
                .filter(|n| n != "case")
                .collect();
            assert!(
                left.is_empty(),
                "{name} {flags:?}: written outside: {left:?}"
            );
        }
    }
    let out = glint(
        &["render", "scene.lua", "--tile", "0/2", "-o", "../ok.png"],
        &dir,
    );
    ok(&out);
    assert!(outer.join("ok-tile-0-of-2.png").exists());
}
