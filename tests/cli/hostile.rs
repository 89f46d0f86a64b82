//! Hostile scenes and command lines, run as a hostile user would: the `glint` binary as a
//! child process with a time bound, its peak memory (the child's own `ru_maxrss` from
//! `wait4`) under a bound, and after it: the documented exit code, a message naming the
//! file (and line), no panic, no abort, and no file left behind. Each case of
//! `docs/limits.md` has its class here, with variants of each.

use glint::testing::scratch::{temp_dir, TempDir};
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Memory budget given to most cases (MiB): small, so that going over it is quick.
const BUDGET_MIB: u64 = 256;
/// What a child may hold beyond its budget: the binary, wgpu's and Mesa's libraries,
/// thread stacks, allocator slack.
const OVERHEAD_MIB: u64 = 160;

struct Case<'a> {
    tag: &'a str,
    scene: &'a str,
    /// Extra input files (name, bytes).
    files: Vec<(&'a str, Vec<u8>)>,
    args: Vec<String>,
    code: i32,
    needles: Vec<&'a str>,
    /// Output files the case is expected to write.
    outputs: Vec<&'a str>,
    seconds: u64,
    peak_mib: u64,
}

impl<'a> Case<'a> {
    fn new(tag: &'a str, scene: &'a str, code: i32, needles: &[&'a str]) -> Case<'a> {
        Case {
            tag,
            scene,
            files: Vec::new(),
            args: Vec::new(),
            code,
            needles: needles.to_vec(),
            outputs: Vec::new(),
            seconds: 20,
            peak_mib: BUDGET_MIB + OVERHEAD_MIB,
        }
    }
    fn file(mut self, name: &'a str, bytes: impl Into<Vec<u8>>) -> Self {
        self.files.push((name, bytes.into()));
        self
    }
    fn args(mut self, args: &[&str]) -> Self {
        self.args.extend(args.iter().map(|s| s.to_string()));
        self
    }
    fn writes(mut self, name: &'a str) -> Self {
        self.outputs.push(name);
        self
    }
    fn within(mut self, seconds: u64, peak_mib: u64) -> Self {
        self.seconds = seconds;
        self.peak_mib = peak_mib;
        self
    }
}

/// A fresh folder for one case, beside a log folder (so the logs are no stray files),
/// both in a scratch folder that goes when the returned guard drops.
fn case_dir(tag: &str) -> (PathBuf, PathBuf, TempDir) {
    let root = temp_dir(&format!("hostile-{tag}"));
    let dir = root.join(tag);
    let logs = root.join(format!("{tag}.logs"));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::create_dir_all(&logs).unwrap();
    (dir, logs, root)
}

/// How a child ended.
struct Ended {
    code: Option<i32>,
    signal: Option<i32>,
    peak_mib: u64,
    elapsed: Duration,
    stderr: String,
}

/// Runs glint with `args` in `dir`, killing it after `limit`. `during` is called every
/// few milliseconds with the child's pid while it runs (for signal tests).
fn run_glint(
    args: &[String],
    dir: &Path,
    logs: &Path,
    limit: Duration,
    during: &mut dyn FnMut(i32) -> bool,
) -> Ended {
    let err_path = logs.join("stderr");
    let mut command = Command::new(env!("CARGO_BIN_EXE_glint"));
    command
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(&err_path).unwrap());
    // The child gets the default SIGINT and SIGTERM whatever this process inherited: a
    // test run started in the background by a non-interactive shell (`cmd &`) has SIGINT
    // ignored, a child inherits that, and glint rightly keeps an ignored signal ignored.
    // SAFETY: `signal` is async-signal-safe, as `pre_exec` requires.
    unsafe {
        command.pre_exec(|| {
            libc::signal(libc::SIGINT, libc::SIG_DFL);
            libc::signal(libc::SIGTERM, libc::SIG_DFL);
            Ok(())
        });
    }
    let child = command.spawn().expect("glint starts");
    let pid = child.id() as i32;
    let start = Instant::now();
    let mut status = 0;
    // SAFETY: plain libc calls on our own child; rusage is plain data.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let mut hooked = true;
    loop {
        let r = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
        if r == pid {
            break;
        }
        assert!(r == 0, "wait4 failed");
        if start.elapsed() > limit {
            unsafe { libc::kill(pid, libc::SIGKILL) };
            unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
            let stderr = std::fs::read_to_string(&err_path).unwrap_or_default();
            panic!("glint {args:?} ran past {limit:?}; stderr:\n{stderr}");
        }
        if hooked {
            hooked = during(pid);
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    let elapsed = start.elapsed();
    drop(child);
    let (code, signal) = if libc::WIFEXITED(status) {
        (Some(libc::WEXITSTATUS(status)), None)
    } else {
        (None, Some(libc::WTERMSIG(status)))
    };
    Ended {
        code,
        signal,
        // ru_maxrss is in KiB on Linux.
        peak_mib: usage.ru_maxrss as u64 / 1024,
        elapsed,
        stderr: std::fs::read_to_string(&err_path).unwrap_or_default(),
    }
}

fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Runs one case and checks everything the issue asks of it.
fn check(case: Case) {
    let (dir, logs, _root) = case_dir(case.tag);
    std::fs::write(dir.join("scene.lua"), case.scene).unwrap();
    let mut expected = vec!["scene.lua".to_string()];
    for (name, bytes) in &case.files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, bytes).unwrap();
        expected.push(name.split('/').next().unwrap().to_string());
    }
    let mut args = vec![
        "render".to_string(),
        "scene.lua".into(),
        "--backend".into(),
        "cpu".into(),
    ];
    if !case.args.iter().any(|a| a == "--memory-limit") {
        args.push("--memory-limit".into());
        args.push(BUDGET_MIB.to_string());
    }
    args.extend(case.args.iter().cloned());
    let ended = run_glint(
        &args,
        &dir,
        &logs,
        Duration::from_secs(case.seconds),
        &mut |_| false,
    );
    check_ended(&case, &ended);
    expected.extend(case.outputs.iter().map(|s| s.to_string()));
    expected.sort();
    expected.dedup();
    assert_eq!(
        listing(&dir),
        expected,
        "{}: files left behind or missing",
        case.tag
    );
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&logs);
}

fn check_ended(case: &Case, ended: &Ended) {
    let tag = case.tag;
    let err = &ended.stderr;
    assert_eq!(
        ended.signal, None,
        "{tag}: killed by a signal; stderr:\n{err}"
    );
    assert_eq!(
        ended.code,
        Some(case.code),
        "{tag}: exit code; stderr:\n{err}"
    );
    assert!(!err.contains("panicked"), "{tag}: panicked:\n{err}");
    for needle in &case.needles {
        assert!(
            err.contains(needle),
            "{tag}: stderr lacks {needle:?}:\n{err}"
        );
    }
    assert!(
        ended.peak_mib <= case.peak_mib,
        "{tag}: peak RSS {} MiB over {} MiB; stderr:\n{err}",
        ended.peak_mib,
        case.peak_mib
    );
    eprintln!(
        "{tag}: exit {:?} in {:.2} s, peak {} MiB",
        ended.code,
        ended.elapsed.as_secs_f64(),
        ended.peak_mib
    );
}

const RENDER: &str = "gr.render(root, 'out.png', 8, 8, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {gr.light({5,5,5}, {1,1,1}, {1,0,0})})\n";

fn with_render(body: &str) -> String {
    format!("root = gr.node('root')\n{body}{RENDER}")
}

#[test]
fn finalizers_are_refused_and_never_run() {
    check(Case::new(
        "gc-gr",
        "setmetatable({}, {__gc = function() gr.node('x') end})\n",
        3,
        &["scene.lua:1:", "__gc", "not available"],
    ));
    // Variants: a hang and an error in the finalizer, __gc set with rawset.
    check(Case::new(
        "gc-loop",
        "local mt = {}\nrawset(mt, '__gc', function() while true do end end)\nlocal ok = pcall(setmetatable, {}, mt)\nassert(not ok)\nsetmetatable({}, mt)\n",
        3,
        &["scene.lua:5:", "__gc"],
    ));
    // A __gc added after setmetatable is never called by Lua: the script ends normally.
    check(Case::new(
        "gc-late",
        "local mt = {}\nlocal t = setmetatable({}, mt)\nmt.__gc = function() while true do end end\nt = nil\ncollectgarbage()\n",
        0,
        &["never called gr.render"],
    ));
}

#[test]
fn scripts_stuck_where_no_hook_runs_end_at_the_time_limit() {
    let hangs = [
        ("pattern", "local s = string.rep('a', 40)\nstring.find(s, string.rep('a*', 30) .. 'b')\n"),
        ("match", "local s = string.rep('a', 5000)\nlocal p = string.rep('(.-)', 30)\nstring.match(s, p .. 'x')\n"),
        ("load-reader", "local first = true\nload(function() if first then first = false return '--' end return string.rep('x', 100000) end)\n"),
        ("gsub", "local s = string.rep('ab', 30)\nstring.gsub(s, string.rep('.-', 25) .. 'c', '')\n"),
    ];
    for (tag, scene) in hangs {
        check(
            Case::new(
                tag,
                scene,
                3,
                &["scene.lua", "script time limit of 1 s", "--script-timeout"],
            )
            .args(&["--script-timeout", "1"])
            .within(15, BUDGET_MIB + OVERHEAD_MIB),
        );
    }
    // Lua code the hook can stop: a pcall cannot hide the limit.
    check(
        Case::new(
            "pcall-loop",
            "for i = 1, 1e12 do pcall(function() local x = 0 for j = 1, 1e6 do x = x + j end end) end\n",
            3,
            &["scene.lua:1:", "script time limit"],
        )
        .args(&["--script-timeout", "1", "--instruction-limit", "100000000000000"])
        .within(15, BUDGET_MIB + OVERHEAD_MIB),
    );
}

#[test]
fn memory_spent_for_the_script_is_counted_before_it_is_spent() {
    // Instances doubling at each of 40 levels: 2^40 objects.
    let dag = with_render(
        "local n = gr.sphere('s')\nfor i = 1, 40 do local p = gr.node('n'..i) p:add_child(n) p:add_child(n) n = p end\nroot:add_child(n)\n",
    );
    check(Case::new(
        "dag",
        &dag,
        3,
        &["scene.lua:5: gr.render:", "paths"],
    ));
    // Fewer paths but each object costly: 2^20 spheres under a 256 MiB budget.
    let wide = with_render(
        "local n = gr.sphere('s')\nfor i = 1, 20 do local p = gr.node('n'..i) p:add_child(n) p:add_child(n) n = p end\nroot:add_child(n)\n",
    );
    check(Case::new(
        "dag-wide",
        &wide,
        3,
        &["scene.lua:5: gr.render:", "memory limit", "--memory-limit"],
    ));
    // Long names: copied into Rust and into every path name.
    let names = "local big = string.rep('x', 2^25)\nfor i = 1, 20 do gr.sphere(big) end\n";
    check(Case::new(
        "names",
        names,
        3,
        &["scene.lua:2: gr.sphere:", "memory limit"],
    ));
    // A big inline mesh table: Lua's heap and the Rust copy draw on the same budget.
    let inline = "local v, f = {}, {}\nfor i = 1, 3e6 do v[i] = {i, 0, 0} end\nfor i = 1, 1e6 do f[i] = {0, 1, 2} end\ngr.mesh('m', v, f)\n";
    check(Case::new(
        "inline-mesh",
        inline,
        3,
        &["scene.lua:", "memory limit"],
    ));
    // A big OBJ file: refused before parsing when parsing it could not fit.
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    obj.push_str(&"f 1 2 3\n".repeat(600_000));
    for scene in ["gr.mesh('m', 'big.obj')\n", "readobj('big.obj')\n"] {
        check(
            Case::new(
                "big-obj",
                scene,
                3,
                &["scene.lua:1:", "big.obj", "memory limit"],
            )
            .file("big.obj", obj.clone())
            .args(&["--memory-limit", "32"])
            .within(20, 32 + OVERHEAD_MIB),
        );
    }
    // A plain Lua table: the message has the line.
    let table = "local t = {}\nfor i = 1, 1e9 do t[i] = i end\n";
    check(Case::new(
        "lua-heap",
        table,
        3,
        &["scene.lua:2:", "memory limit of 256 MiB"],
    ));
}

/// A PNG of `w`×`h` grey texels, encoded in memory.
fn png(w: u32, h: u32) -> Vec<u8> {
    let mut bytes = Vec::new();
    image::RgbImage::from_pixel(w, h, image::Rgb([128, 128, 128]))
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    bytes
}

#[test]
fn textures_are_counted_once_per_file_and_before_decoding() {
    // 2048² texels = 16 MiB decoded; a budget of 64 MiB holds it once (with the packed
    // copy at render and the decoder's transient copy), not five times: the same file
    // under other spellings is shared.
    let big = png(2048, 2048);
    let scene = with_render(
        "for _, f in ipairs({'tex/big.png', 'tex/../tex/big.png', './tex/big.png', 'tex/./big.png', 'tex//big.png'}) do\n  gr.material('m'):set_diffuse(f)\nend\n",
    );
    check(
        Case::new("texture-cache", &scene, 0, &["wrote out.png"])
            .file("tex/big.png", big)
            .args(&["--memory-limit", "64"])
            .writes("out.png")
            .within(60, 64 + OVERHEAD_MIB),
    );
    // A texture larger than the budget is refused from its header, before decoding.
    let huge = png_header(16000, 16000);
    check(
        Case::new(
            "texture-huge",
            "gr.material('m'):set_diffuse('huge.png')\n",
            3,
            &["scene.lua:1:", "huge.png", "memory limit"],
        )
        .file("huge.png", huge)
        .within(60, BUDGET_MIB + OVERHEAD_MIB),
    );
}

#[test]
fn grids_of_large_overlapping_items_stay_bounded() {
    let spheres = "root = gr.node('root')\nfor i = 1, 20000 do root:add_child(gr.nh_sphere('s', {0,0,0}, i)) end\ngr.render(root, 'out.png', 16, 16, {0,0,50000}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {}, {aa='none'})\n";
    check(
        Case::new("spheres", spheres, 0, &["wrote out.png"])
            .writes("out.png")
            .args(&["--memory-limit", "1024"])
            .within(90, 1024 + OVERHEAD_MIB),
    );
    let disk = "local n = 10000\nlocal v, f = {}, {}\nfor i = 0, n - 1 do local a = 2 * math.pi * i / n v[#v + 1] = {math.cos(a), math.sin(a), 0} f[#f + 1] = i end\nroot = gr.node('root')\nroot:add_child(gr.mesh('disk', v, {f}))\ngr.render(root, 'out.png', 16, 16, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {}, {aa='none'})\n";
    check(
        Case::new("disk", disk, 0, &["wrote out.png"])
            .writes("out.png")
            .args(&["--memory-limit", "1024"])
            .within(90, 1024 + OVERHEAD_MIB),
    );
}

#[test]
fn add_child_is_cheap_for_wide_graphs() {
    let wide = "local P = gr.node('P')\nfor i = 1, 100000 do P:add_child(gr.sphere('c')) end\nlocal top = gr.node('top')\nfor i = 1, 100000 do local q = gr.node('q') q:add_child(P) top:add_child(q) end\n";
    check(
        Case::new("add-child", wide, 0, &["never called gr.render"])
            .within(60, BUDGET_MIB + OVERHEAD_MIB),
    );
    // Parents that already have a parent, children with big subtrees.
    let held = "local root = gr.node('root')\nlocal X = gr.node('X')\nfor i = 1, 100000 do X:add_child(gr.sphere('c')) end\nfor i = 1, 100000 do local q = gr.node('q') root:add_child(q) q:add_child(X) end\nlocal ok, e = pcall(function() X:add_child(root) end)\nassert(not ok and tostring(e):find('cycle'))\n";
    check(
        Case::new("add-child-held", held, 0, &["never called gr.render"])
            .within(60, BUDGET_MIB + OVERHEAD_MIB),
    );
}

#[test]
fn special_files_are_refused() {
    let (dir, logs, _root) = case_dir("fifo");
    for (i, scene) in [
        "gr.mesh('m', 'pipe')\n",
        "gr.material('m'):set_diffuse('pipe')\n",
        "require('pipe')\n",
        "readobj('pipe')\n",
    ]
    .iter()
    .enumerate()
    {
        let _ = std::fs::remove_file(dir.join("pipe"));
        let _ = std::fs::remove_file(dir.join("pipe.lua"));
        for name in ["pipe", "pipe.lua"] {
            let c = std::ffi::CString::new(dir.join(name).to_str().unwrap()).unwrap();
            // SAFETY: a valid NUL-terminated path.
            assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        }
        std::fs::write(dir.join("scene.lua"), scene).unwrap();
        let args: Vec<String> = ["render", "scene.lua", "--backend", "cpu"]
            .map(String::from)
            .to_vec();
        let ended = run_glint(&args, &dir, &logs, Duration::from_secs(20), &mut |_| false);
        let case = Case::new("fifo", scene, 3, &["scene.lua:1:", "not a regular file"]);
        check_ended(&case, &ended);
        assert_eq!(
            listing(&dir),
            vec!["pipe", "pipe.lua", "scene.lua"],
            "case {i}"
        );
    }
    // /dev/zero through a link in the scene's folder: outside it, and with the folder
    // allowed, not a regular file.
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.obj")).unwrap();
    std::fs::write(dir.join("scene.lua"), "gr.mesh('m', 'zero.obj')\n").unwrap();
    for (extra, needle) in [(None, "--allow-read"), (Some("/dev"), "not a regular file")] {
        let mut args: Vec<String> = ["render", "scene.lua", "--backend", "cpu"]
            .map(String::from)
            .to_vec();
        if let Some(d) = extra {
            args.extend(["--allow-read".to_string(), d.to_string()]);
        }
        let ended = run_glint(&args, &dir, &logs, Duration::from_secs(20), &mut |_| false);
        check_ended(
            &Case::new("zero", "", 3, &["scene.lua:1:", "zero.obj", needle]),
            &ended,
        );
    }
    assert_eq!(listing(&dir), vec!["scene.lua", "zero.obj"]);
}

#[test]
fn files_outside_the_scene_folder_are_refused_unless_allowed() {
    let outside =
        std::env::temp_dir().join(format!("glint-hostile-outside-{}", std::process::id()));
    std::fs::create_dir_all(&outside).unwrap();
    std::fs::write(
        outside.join("secret.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nSECRET\n",
    )
    .unwrap();
    let abs = outside.join("secret.obj").display().to_string();
    let scenes = [
        format!("gr.mesh('m', '{abs}')\n"),
        "gr.mesh('m', '../../../../../../etc/passwd')\n".to_string(),
        "readobj('/etc/passwd')\n".to_string(),
        "gr.material('m'):set_diffuse('/etc/passwd')\n".to_string(),
        "require('..etc.passwd')\n".to_string(),
        "gr.mesh('m', 'link.obj')\n".to_string(),
    ];
    for (i, scene) in scenes.iter().enumerate() {
        let tag = format!("outside-{i}");
        let case = Case::new(
            &tag,
            scene,
            3,
            &["scene.lua:1:", "outside the folders", "--allow-read"],
        );
        let (dir, _, _root) = case_dir(&tag);
        std::os::unix::fs::symlink(outside.join("secret.obj"), dir.join("link.obj")).unwrap();
        check_in(case, &dir, &["link.obj"]);
        assert!(
            !std::fs::read_to_string(dir.with_extension("logs").join("stderr"))
                .unwrap()
                .contains("SECRET")
        );
    }
    // Widened by the flag, the same mesh loads (no face error, no refusal).
    let tag = "outside-allowed";
    let (dir, _, _root) = case_dir(tag);
    let scene = with_render(&format!("root:add_child(gr.mesh('m', '{abs}'))\n"));
    let case = Case::new(tag, &scene, 0, &["wrote out.png"])
        .args(&["--allow-read", outside.to_str().unwrap()])
        .writes("out.png");
    check_in(case, &dir, &[]);
    // Error messages quote at most a short excerpt of a file's content.
    std::fs::write(
        outside.join("bad.obj"),
        format!("v 0 0 {}\n", "S".repeat(200)),
    )
    .unwrap();
    let tag = "outside-excerpt";
    let (dir, _, _root) = case_dir(tag);
    let case = Case::new(
        tag,
        "gr.mesh('m', 'bad.obj')\n",
        3,
        &["bad.obj:1: bad number 'SSSSSSSSSSSSSSSSSSSSSSSS…'"],
    )
    .args(&["--allow-read", outside.to_str().unwrap()]);
    std::fs::copy(outside.join("bad.obj"), dir.join("bad.obj")).unwrap();
    check_in(case, &dir, &["bad.obj"]);
    let _ = std::fs::remove_dir_all(&outside);
}

/// [`check`] in a folder already holding `present` (kept, not counted as left behind).
fn check_in(case: Case, dir: &Path, present: &[&str]) {
    let logs = dir.with_extension("logs");
    std::fs::create_dir_all(&logs).unwrap();
    std::fs::write(dir.join("scene.lua"), case.scene).unwrap();
    let mut args: Vec<String> = ["render", "scene.lua", "--backend", "cpu"]
        .map(String::from)
        .to_vec();
    args.extend(case.args.iter().cloned());
    let ended = run_glint(
        &args,
        dir,
        &logs,
        Duration::from_secs(case.seconds),
        &mut |_| false,
    );
    check_ended(&case, &ended);
    let mut expected: Vec<String> = ["scene.lua"]
        .iter()
        .chain(present)
        .chain(&case.outputs)
        .map(|s| s.to_string())
        .collect();
    expected.sort();
    assert_eq!(listing(dir), expected, "{}: files", case.tag);
}

#[test]
fn sizes_and_counts_are_bounded() {
    let huge = "root = gr.node('root')\ngr.render(root, 'out.png', 60000, 60000, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {})\n";
    check(Case::new(
        "pixels-script",
        huge,
        3,
        &["scene.lua:2: gr.render:", "pixels"],
    ));
    let scene = with_render("");
    for (tag, args, needle) in [
        (
            "width",
            vec!["--width", "4000000000", "--height", "1"],
            "--width",
        ),
        (
            "area",
            vec!["--width", "65536", "--height", "65536"],
            "pixels",
        ),
        ("threads-big", vec!["--threads", "100000"], "--threads"),
        ("threads-3000", vec!["--threads", "3000"], "--threads"),
        ("threads-0", vec!["--threads", "0"], "--threads"),
        (
            "timeout-0",
            vec!["--script-timeout", "0"],
            "--script-timeout",
        ),
        ("memory-tiny", vec!["--memory-limit", "1"], "--memory-limit"),
    ] {
        check(Case::new(tag, &scene, 2, &[needle]).args(&args));
    }
}

#[test]
fn an_interrupted_write_leaves_nothing_behind() {
    // A big empty render: the PNG takes long enough to encode that the signal usually
    // lands while the temporary file exists. It can still land after glint has renamed
    // the file, or after it has exited (the poll sees the temporary file just before the
    // rename): such a run proves nothing, so it is repeated, up to ATTEMPTS times.
    const ATTEMPTS: usize = 5;
    for sig in [libc::SIGINT, libc::SIGTERM] {
        let mut interrupted = false;
        for attempt in 0..ATTEMPTS {
            let (dir, logs, _root) = case_dir(&format!("signal-{sig}-{attempt}"));
            let scene = "root = gr.node('root')\ngr.render(root, 'out.png', 4000, 4000, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {}, {aa='none'})\n";
            std::fs::write(dir.join("scene.lua"), scene).unwrap();
            let args: Vec<String> = ["render", "scene.lua", "--backend", "cpu"]
                .map(String::from)
                .to_vec();
            let ended = run_glint(&args, &dir, &logs, Duration::from_secs(120), &mut |pid| {
                let temp = listing(&dir).iter().any(|n| n.contains(".tmp-"));
                if temp {
                    // SAFETY: signalling our own child.
                    unsafe { libc::kill(pid, sig) };
                }
                !temp
            });
            let names = listing(&dir);
            assert!(
                !names.iter().any(|n| n.contains(".tmp-")),
                "temporary file left behind: {names:?}; stderr:\n{}",
                ended.stderr
            );
            if ended.signal != Some(sig) {
                // Finished before the signal landed (or before a temp file was seen).
                assert_eq!(ended.code, Some(0), "stderr:\n{}", ended.stderr);
                continue;
            }
            if names.iter().any(|n| n == "out.png") {
                // Killed after the rename: the whole image, and nothing was interrupted.
                image::open(dir.join("out.png")).expect("a complete image");
                continue;
            }
            // Killed while writing: nothing left behind.
            assert_eq!(names, vec!["scene.lua"], "stderr:\n{}", ended.stderr);
            interrupted = true;
            break;
        }
        assert!(
            interrupted,
            "signal {sig} never landed while glint was writing, in {ATTEMPTS} attempts"
        );
    }
}

/// A PNG header (signature and IHDR) claiming `w`×`h` RGB pixels, with no pixels.
fn png_header(w: u32, h: u32) -> Vec<u8> {
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend(w.to_be_bytes());
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([8, 2, 0, 0, 0]);
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    out.extend(13u32.to_be_bytes());
    out.extend(&ihdr);
    out.extend(crc32(&ihdr).to_be_bytes());
    // An empty IDAT and IEND: the header is complete, the pixels are missing.
    for name in [b"IDAT", b"IEND"] {
        out.extend(0u32.to_be_bytes());
        out.extend(name);
        out.extend(crc32(name).to_be_bytes());
    }
    out
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[test]
fn diff_refuses_what_flip_cannot_hold_and_missing_files_once() {
    let (dir, logs, _root) = case_dir("diff");
    std::fs::write(dir.join("a.png"), png_header(8000, 8000)).unwrap();
    std::fs::write(dir.join("b.png"), png_header(8000, 8000)).unwrap();
    std::fs::write(dir.join("small.png"), png(4, 4)).unwrap();
    for (args, code, needles) in [
        (
            vec!["a.png", "b.png"],
            2,
            vec!["a.png", "8000x8000", "FLIP"],
        ),
        (
            vec!["a.png", "b.png", "--heatmap", "h.png"],
            2,
            vec!["8000x8000"],
        ),
        (vec!["missing.png", "small.png"], 2, vec!["missing.png"]),
        (vec!["small.png", "missing.png"], 2, vec!["missing.png"]),
    ] {
        let mut all = vec!["diff".to_string()];
        all.extend(args.iter().map(|s| s.to_string()));
        let ended = run_glint(&all, &dir, &logs, Duration::from_secs(20), &mut |_| false);
        check_ended(&Case::new("diff", "", code, &needles), &ended);
        assert_eq!(
            ended.stderr.lines().count(),
            1,
            "one message: {}",
            ended.stderr
        );
        assert!(
            ended.stderr.matches("No such file").count() <= 1,
            "{}",
            ended.stderr
        );
    }
    assert_eq!(listing(&dir), vec!["a.png", "b.png", "small.png"]);
}

/// A report printed into a pipe nobody reads any more (`glint diff a b | head -0`) ends
/// glint as SIGPIPE ends any command-line tool, quietly: no panic ("failed printing to
/// stdout") and no message.
#[test]
fn a_closed_stdout_ends_glint_quietly() {
    use std::os::unix::process::ExitStatusExt;
    let (dir, _logs, _root) = case_dir("closed-stdout");
    std::fs::write(dir.join("small.png"), png(4, 4)).unwrap();
    for args in [vec!["diff", "small.png", "small.png"], vec!["--help"]] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_glint"))
            .args(&args)
            .current_dir(&dir)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // The reading end closes before glint has read its images or parsed its flags.
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(
            out.status.success() || out.status.signal() == Some(libc::SIGPIPE),
            "{args:?}: {:?}, {stderr}",
            out.status
        );
        assert!(stderr.is_empty(), "{args:?}: {stderr}");
    }
}

/// A JPEG of `w`×`h` whose frame header is rewritten to claim `claim`×`claim`.
fn forged_jpeg(w: u32, h: u32, claim: u16) -> Vec<u8> {
    let mut bytes = Vec::new();
    image::RgbImage::from_pixel(w, h, image::Rgb([200, 10, 10]))
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Jpeg,
        )
        .unwrap();
    let sof = bytes
        .windows(2)
        .position(|w| w == [0xFF, 0xC0])
        .expect("baseline SOF0");
    bytes[sof + 5..sof + 7].copy_from_slice(&claim.to_be_bytes());
    bytes[sof + 7..sof + 9].copy_from_slice(&claim.to_be_bytes());
    bytes
}

#[test]
fn empty_and_wrong_files_are_errors_naming_the_file() {
    let utf16: Vec<u8> = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
        .encode_utf16()
        .flat_map(u16::to_le_bytes)
        .collect();
    let cases: Vec<(&str, &str, Vec<u8>, Vec<&str>)> = vec![
        (
            "empty-obj",
            "gr.mesh('m', 'm.obj')\n",
            vec![],
            vec!["scene.lua:1:", "m.obj", "no faces"],
        ),
        (
            "comments-obj",
            "gr.mesh('m', 'm.obj')\n",
            b"# nothing\nv 0 0 0\n".to_vec(),
            vec!["m.obj", "no faces"],
        ),
        (
            "utf16-obj",
            "gr.mesh('m', 'm.obj')\n",
            utf16,
            vec!["m.obj", "not an OBJ text file"],
        ),
        (
            "png-obj",
            "gr.mesh('m', 'm.obj')\n",
            png(2, 2),
            vec!["m.obj", "not an OBJ text file"],
        ),
        (
            "readobj-empty",
            "readobj('m.obj')\n",
            vec![],
            vec!["scene.lua:1: readobj:", "no faces"],
        ),
        (
            "jpeg-forged",
            "gr.material('m'):set_diffuse('m.obj')\n",
            forged_jpeg(16, 16, 8000),
            vec!["scene.lua:1:", "m.obj", "8000×8000", "truncated"],
        ),
    ];
    for (tag, scene, bytes, needles) in cases {
        check(Case::new(tag, scene, 3, &needles).file("m.obj", bytes));
    }
}

#[test]
fn messages_name_the_scene_file_and_line() {
    check(Case::new("out-jpg", "root = gr.node('root')\ngr.render(root, 'out.jpg', 8, 8, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {})\n", 4, &["scene.lua:2: gr.render:", "out.jpg"]));
    check(Case::new("out-nodir", "root = gr.node('root')\ngr.render(root, 'nodir/out.png', 8, 8, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {})\n", 4, &["scene.lua:2: gr.render:", "nodir"]));
    // An output folder that exists but cannot be written (even by root): the message
    // names the output, not the temporary file.
    let plain = with_render("");
    let unwritable = Case::new(
        "out-unwritable",
        &plain,
        4,
        &["scene.lua:2: gr.render:", "cannot write /proc/out.png"],
    )
    .args(&["-o", "/proc/out.png"]);
    check(unwritable);
    check(
        Case::new(
            "view-tiny",
            &with_render("").replace("{0,0,-1}", "{0,0,-1e-300}"),
            0,
            &["wrote out.png"],
        )
        .writes("out.png"),
    );
    check(Case::new(
        "view-zero",
        &with_render("").replace("{0,0,-1}", "{0,0,0}"),
        3,
        &["scene.lua:2:", "argument 6 (view)"],
    ));
    let huge = with_render("root:add_child(gr.sphere('s'))\n")
        .replace("{0,0,-1}, {0,1,0}", "{0,0,-1e200}, {0,1e200,0}");
    check(Case::new("view-huge", &huge, 0, &["wrote out.png"]).writes("out.png"));
    // Huge edges are not parallel: no overflow in the check.
    check(Case::new(
        "area-huge",
        "l = gr.area_light({0,5,0}, {1e200,0,0}, {0,0,1e200}, {1,1,1}, {1,0,0})\nl = gr.area_light({0,5,0}, {1e-200,0,0}, {0,0,1e-200}, {1,1,1}, {1,0,0})\n",
        0,
        &["never called gr.render"],
    ));
    check(Case::new(
        "area-parallel-huge",
        "l = gr.area_light({0,5,0}, {1e200,0,0}, {2e200,0,0}, {1,1,1}, {1,0,0})\n",
        3,
        &["scene.lua:1:", "argument 3 (v)", "parallel"],
    ));
    let coro = "local co = coroutine.wrap(function()\n  error('boom')\nend)\nco()\n";
    let case = Case::new("coroutine", coro, 3, &["scene.lua:2: boom"]);
    let (dir, logs, _root) = case_dir("coroutine");
    std::fs::write(dir.join("scene.lua"), coro).unwrap();
    let args: Vec<String> = ["render", "scene.lua", "--backend", "cpu"]
        .map(String::from)
        .to_vec();
    let ended = run_glint(&args, &dir, &logs, Duration::from_secs(20), &mut |_| false);
    check_ended(&case, &ended);
    assert_eq!(
        ended.stderr.matches("scene.lua:").count(),
        1,
        "{}",
        ended.stderr
    );
}
