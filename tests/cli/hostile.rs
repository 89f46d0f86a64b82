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
/// The address space each child gets (`RLIMIT_AS`): an allocation the budget did not
/// see fails there and aborts the child, which every case counts as a failure.
const ADDRESS_SPACE_BYTES: u64 = 6 << 30;

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

/// Gives the child glint the default SIGINT and SIGTERM whatever this process inherited
/// (a test run started in the background by a non-interactive shell, `cmd &`, has SIGINT
/// ignored, a child inherits that, and glint rightly keeps an ignored signal ignored) and
/// caps its address space at [`ADDRESS_SPACE_BYTES`].
fn confine(command: &mut Command) {
    // SAFETY: signal and setrlimit are async-signal-safe, as `pre_exec` requires.
    unsafe {
        command.pre_exec(|| {
            libc::signal(libc::SIGINT, libc::SIG_DFL);
            libc::signal(libc::SIGTERM, libc::SIG_DFL);
            let cap = libc::rlimit {
                rlim_cur: ADDRESS_SPACE_BYTES,
                rlim_max: ADDRESS_SPACE_BYTES,
            };
            libc::setrlimit(libc::RLIMIT_AS, &cap);
            Ok(())
        });
    }
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
    confine(&mut command);
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

/// A runner's hook that sends `sig` to the child as soon as a temporary file (`.tmp-`)
/// appears in `dir`, and stops hooking then.
fn signal_once_a_temp_file_exists(dir: &Path, sig: i32) -> impl FnMut(i32) -> bool + '_ {
    move |pid| {
        let temp = listing(dir).iter().any(|n| n.contains(".tmp-"));
        if temp {
            // SAFETY: signalling our own child.
            unsafe { libc::kill(pid, sig) };
        }
        !temp
    }
}

/// Renders a `side`×`side` empty image in a fresh case folder `tag` and sends `sig` as
/// soon as the temporary image file exists; returns how glint ended, the folder, what it
/// holds afterwards and the folder's guard, having checked that no temporary file is left.
fn signal_during_write(tag: &str, side: u32, sig: i32) -> (Ended, PathBuf, Vec<String>, TempDir) {
    let (dir, logs, root) = case_dir(tag);
    let scene = format!("root = gr.node('root')\ngr.render(root, 'out.png', {side}, {side}, {{0,0,5}}, {{0,0,-1}}, {{0,1,0}}, 50, {{0.1,0.1,0.1}}, {{}}, {{aa='none'}})\n");
    std::fs::write(dir.join("scene.lua"), scene).unwrap();
    let args: Vec<String> = ["render", "scene.lua", "--backend", "cpu"]
        .map(String::from)
        .to_vec();
    let ended = run_glint(
        &args,
        &dir,
        &logs,
        Duration::from_secs(120),
        &mut signal_once_a_temp_file_exists(&dir, sig),
    );
    let names = listing(&dir);
    assert!(
        !names.iter().any(|n| n.contains(".tmp-")),
        "signal {sig}: temporary file left behind: {names:?}; stderr:\n{}",
        ended.stderr
    );
    (ended, dir, names, root)
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
            let (ended, dir, names, _root) =
                signal_during_write(&format!("signal-{sig}-{attempt}"), 4000, sig);
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
    check(Case::new("out-bmp", "root = gr.node('root')\ngr.render(root, 'out.bmp', 8, 8, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {})\n", 4, &["scene.lua:2: gr.render:", "out.bmp"]));
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

/// `gr.render` with the output name `name` (Lua source text, quoted by the caller).
fn render_named(name: &str) -> String {
    with_render("").replace("'out.png'", name)
}

/// The scratch root of a case (its folder, its log folder, and whatever else the case
/// put beside them) holds only `expected`.
fn root_holds(dir: &Path, expected: &[&str]) {
    let root = dir.parent().unwrap();
    let mut expected: Vec<String> = expected.iter().map(|s| s.to_string()).collect();
    expected.sort();
    assert_eq!(
        listing(root),
        expected,
        "files written outside the case's folder"
    );
}

#[test]
fn script_named_outputs_are_confined_like_reads() {
    let refused = ["scene.lua:2: gr.render:", "cannot write"];
    // Relative names that leave the folder, absolute names, and names through links.
    for (i, name) in [
        "'../up.png'",
        "'sub/../../up.png'",
        "'link/up.png'",
        "'ABS/up.png'",
        "'/dev/shm/glint-hostile-up.png'",
    ]
    .iter()
    .enumerate()
    {
        let tag = format!("write-out-{i}");
        let (dir, _, _root) = case_dir(&tag);
        let outside = dir.parent().unwrap().join("outside");
        std::fs::create_dir_all(&outside).unwrap();
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        std::os::unix::fs::symlink(&outside, dir.join("link")).unwrap();
        let scene = render_named(&name.replace("ABS", outside.to_str().unwrap()));
        check_in(Case::new(&tag, &scene, 3, &refused), &dir, &["link", "sub"]);
        assert!(listing(&outside).is_empty(), "{name}: written outside");
        assert!(!Path::new("/dev/shm/glint-hostile-up.png").exists());
        root_holds(&dir, &[&tag, &format!("{tag}.logs"), "outside"]);
    }
    // Files that are not writable images are never replaced (nor followed).
    let secret = b"not an image".to_vec();
    for (i, (name, needle)) in [
        ("'notes.png'", "not a PNG or EXR"),
        ("'ro.png'", "read-only"),
        ("'l.png'", "symbolic link"),
        ("'d.png'", "not a regular file"),
    ]
    .iter()
    .enumerate()
    {
        use std::os::unix::fs::PermissionsExt;
        let tag = format!("write-replace-{i}");
        let (dir, _, _root) = case_dir(&tag);
        std::fs::write(dir.join("notes.png"), &secret).unwrap();
        std::fs::write(dir.join("ro.png"), png(2, 2)).unwrap();
        std::fs::set_permissions(dir.join("ro.png"), std::fs::Permissions::from_mode(0o444))
            .unwrap();
        std::os::unix::fs::symlink("notes.png", dir.join("l.png")).unwrap();
        std::fs::create_dir(dir.join("d.png")).unwrap();
        let scene = render_named(name);
        let case = Case::new(&tag, &scene, 3, &[refused[0], needle]);
        check_in(case, &dir, &["notes.png", "ro.png", "l.png", "d.png"]);
        assert_eq!(std::fs::read(dir.join("notes.png")).unwrap(), secret);
        assert_eq!(std::fs::read(dir.join("ro.png")).unwrap(), png(2, 2));
    }
    // A name that is not UTF-8 is refused, not mangled into another.
    check(Case::new(
        "write-utf8",
        &render_named("'o\\255.png'"),
        3,
        &["scene.lua:2: gr.render:", "argument 2 (file)", "UTF-8"],
    ));
    // A name the temporary suffix makes too long fails before the render, not after.
    let long = format!("'{}.png'", "n".repeat(230));
    let slow = render_named(&long).replace("8, 8,", "3000, 3000,");
    check(
        Case::new(
            "write-long",
            &slow,
            4,
            &["scene.lua:2: gr.render:", "bytes per name"],
        )
        .within(5, BUDGET_MIB + OVERHEAD_MIB),
    );
}

#[test]
fn output_folders_widen_the_write_rule_and_o_stays_the_users() {
    let tag = "write-flags";
    let (dir, _, _root) = case_dir(tag);
    let root = dir.parent().unwrap().to_path_buf();
    let (out, extra) = (root.join("out"), root.join("extra"));
    std::fs::create_dir_all(&out).unwrap();
    std::fs::create_dir_all(&extra).unwrap();
    let (a_png, b_png, shm) = (
        render_named("'a.png'"),
        render_named("'../extra/b.png'"),
        render_named("'/dev/shm/x.png'"),
    );
    // --output-dir: the script's names are taken from it and confined to it.
    let case = Case::new(tag, &a_png, 0, &["wrote"]).args(&["--output-dir", out.to_str().unwrap()]);
    check_in(case, &dir, &[]);
    assert_eq!(listing(&out), vec!["a.png"]);
    let case =
        Case::new(tag, &b_png, 3, &["cannot write"]).args(&["--output-dir", out.to_str().unwrap()]);
    check_in(case, &dir, &[]);
    // --allow-write: a further folder.
    let case = Case::new(tag, &b_png, 0, &["wrote"]).args(&[
        "--output-dir",
        out.to_str().unwrap(),
        "--allow-write",
        extra.to_str().unwrap(),
    ]);
    check_in(case, &dir, &[]);
    assert_eq!(listing(&extra), vec!["b.png"]);
    // -o is the user's own choice, wherever it points.
    let chosen = extra.join("c.png");
    let case = Case::new(tag, &shm, 0, &["wrote"]).args(&["-o", chosen.to_str().unwrap()]);
    check_in(case, &dir, &[]);
    assert_eq!(listing(&extra), vec!["b.png", "c.png"]);
    for (flag, code) in [("--output-dir", 2), ("--allow-write", 2)] {
        let case = Case::new(tag, &a_png, code, &[flag]).args(&[flag, "/nonexistent-glint-folder"]);
        check_in(case, &dir, &[]);
    }
}

#[test]
fn a_reached_limit_is_final_even_when_caught() {
    let caught_then_render = |body: &str| {
        with_render(&format!(
            "local ok = pcall(function() {body} end)\nassert(not ok)\n"
        ))
    };
    // Instruction, time and memory limits, each caught by pcall: the render after it
    // fails, nothing is written.
    for (tag, body, args, needle) in [
        (
            "final-instructions",
            "while true do end",
            vec!["--instruction-limit", "1000000"],
            "instruction limit",
        ),
        (
            "final-time",
            "while true do end",
            vec![
                "--script-timeout",
                "1",
                "--instruction-limit",
                "100000000000",
            ],
            "script time limit",
        ),
        (
            "final-memory",
            "local t = {} for i = 1, 1e9 do t[i] = i end",
            vec![],
            "memory limit",
        ),
        (
            "final-budget",
            "local s = string.rep('x', 2^20) for i = 1, 1e6 do gr.node(s) end",
            vec![],
            "memory limit",
        ),
    ] {
        check(
            Case::new(tag, &caught_then_render(body), 3, &["scene.lua:", needle])
                .args(&args)
                .within(15, BUDGET_MIB + OVERHEAD_MIB),
        );
    }
    // The budget's refusals before reading or decoding are reached limits too.
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    // 4.8 MB: over 32 MiB at the reader's 8 bytes per byte of OBJ text.
    obj.push_str(&"f 1 2 3\n".repeat(600_000));
    for (tag, body, file, bytes) in [
        (
            "final-texture",
            "gr.material('m'):set_diffuse('huge.png')",
            "huge.png",
            png_header(16000, 16000),
        ),
        (
            "final-obj",
            "gr.mesh('m', 'big.obj')",
            "big.obj",
            obj.into_bytes(),
        ),
    ] {
        check(
            Case::new(
                tag,
                &caught_then_render(body),
                3,
                &["scene.lua:2:", file, "memory limit"],
            )
            .file(file, bytes)
            .args(&["--memory-limit", "32"])
            .within(15, 32 + OVERHEAD_MIB),
        );
    }
    // A loop that keeps catching: every instruction fails once the limit is reached,
    // so the loop cannot go on (the hook's step aligned with the loop once let it).
    for (tag, scene) in [
        ("final-loop", "while true do pcall(function() end) end\n"),
        (
            "final-coroutine",
            "while true do coroutine.resume(coroutine.create(function() while true do end end)) end\n",
        ),
        (
            "final-render-loop",
            "root = gr.node('root')\nwhile true do pcall(gr.render, root, 'out.png', 1, 1, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0,0,0}, {}) pcall(function() while true do end end) end\n",
        ),
    ] {
        let ended_case = Case::new(tag, scene, 3, &["scene.lua:", "instruction limit"])
            .args(&["--instruction-limit", "100000", "--script-timeout", "60"])
            .within(10, BUDGET_MIB + OVERHEAD_MIB);
        let ended_case = if tag == "final-render-loop" {
            ended_case.writes("out.png")
        } else {
            ended_case
        };
        check(ended_case);
    }
}

#[test]
fn renders_per_script_are_bounded() {
    let many = "root = gr.node('root')\nfor i = 1, 1e9 do\n  gr.render(root, 'out.png', 1, 1, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0,0,0}, {})\nend\n";
    check(
        Case::new(
            "renders-default",
            many,
            3,
            &["scene.lua:3: gr.render:", "1024 renders", "--max-renders"],
        )
        .writes("out.png")
        .within(60, BUDGET_MIB + OVERHEAD_MIB),
    );
    check(
        Case::new(
            "renders-flag",
            many,
            3,
            &["scene.lua:3:", "limit of 3 renders"],
        )
        .args(&["--max-renders", "3"])
        .writes("out.png"),
    );
    let pcall_many = "root = gr.node('root')\nfor i = 1, 1e9 do\n  pcall(gr.render, root, 'out.png', 1, 1, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0,0,0}, {})\nend\n";
    check(
        Case::new(
            "renders-pcall",
            pcall_many,
            3,
            &["scene.lua:3:", "limit of 3 renders"],
        )
        .args(&["--max-renders", "3"])
        .writes("out.png"),
    );
    check(
        Case::new(
            "renders-pixels",
            &many.replace("1, 1, {0,0,5}", "100, 100, {0,0,5}"),
            3,
            &["scene.lua:3:", "30000 pixels", "--max-render-pixels"],
        )
        .args(&["--max-render-pixels", "25000"])
        .writes("out.png"),
    );
    for args in [["--max-renders", "0"], ["--max-render-pixels", "0"]] {
        check(Case::new("renders-zero", &with_render(""), 2, &[args[0]]).args(&args));
    }
}

#[test]
fn every_allocation_for_the_script_is_counted_first() {
    let bound = 64 + OVERHEAD_MIB;
    let cases: Vec<(&str, String, &str)> = vec![
        // Material names and materials themselves.
        (
            "mem-material-names",
            "local big = string.rep('x', 2^23)\nfor i = 1, 40 do gr.material(big) end\n".into(),
            "scene.lua:2: gr.material:",
        ),
        (
            "mem-materials",
            "while true do gr.material('m') end\n".into(),
            "scene.lua:1: gr.material:",
        ),
        // One face of 10⁵ corners listed 4 096 times: 4 × 10⁸ triangles from 1.6 MB.
        (
            "mem-faces",
            "local f = {}\nfor i = 1, 100000 do f[i] = i % 3 end\nlocal F = {}\nfor i = 1, 4096 do F[i] = f end\ngr.mesh('m', {{0,0,0}, {1,0,0}, {0,1,0}}, F)\n".into(),
            "scene.lua:5: gr.mesh:",
        ),
    ];
    for (tag, scene, needle) in cases {
        check(
            Case::new(tag, &scene, 3, &[needle, "memory limit of 64 MiB"])
                .args(&["--memory-limit", "64"])
                .within(30, bound),
        );
    }
    // Other budgets: one light listed 2^21 times (the copies are counted before they
    // are made); add_child links to one child (16 MiB: each call costs microseconds).
    for (tag, scene, needle, mib) in [
        (
            "mem-lights",
            "local l = gr.light({0,0,0}, {1,1,1}, {1,0,0})\nlocal t = {}\nfor i = 1, 2^21 do t[i] = l end\nroot = gr.node('r')\ngr.render(root, 'o.png', 4, 4, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0,0,0}, t)\n",
            "scene.lua:5: gr.render:",
            256,
        ),
        // add_child links to one child.
        (
            "mem-links",
            "local p, c = gr.node('p'), gr.sphere('c')\nfor i = 1, 1e9 do p:add_child(c) end\n",
            "scene.lua:2: node:add_child:",
            16,
        ),
    ] {
        let limit = format!("memory limit of {mib} MiB");
        check(
            Case::new(tag, scene, 3, &[needle, &limit])
                .args(&["--memory-limit", &mib.to_string()])
                .within(30, mib + OVERHEAD_MIB),
        );
    }
    // Small Lua objects: the C allocator's headers and rounding are counted with the
    // heap (Lua counts 40 bytes for `{i}` where malloc takes 64 and more). The margin
    // is tighter here (64 MiB: the CPU backend's binary and stacks take about 12).
    check(
        Case::new(
            "mem-small-objects",
            "local t = {}\nfor i = 1, 1e9 do t[i] = {i} end\n",
            3,
            &["scene.lua:2:", "memory limit of 512 MiB"],
        )
        .args(&[
            "--memory-limit",
            "512",
            "--instruction-limit",
            "100000000000",
        ])
        .within(30, 512 + 64),
    );
    // A module and the scene text itself are counted before they are read.
    let big_text = format!("-- {}\n", "x".repeat(40 << 20));
    check(
        Case::new(
            "mem-module",
            "require('big')\n",
            3,
            &["scene.lua:1: require:", "big.lua", "memory limit"],
        )
        .file("big.lua", big_text.clone())
        .args(&["--memory-limit", "64"])
        .within(20, bound),
    );
    let (dir, logs, _root) = case_dir("mem-scene");
    std::fs::write(dir.join("scene.lua"), &big_text).unwrap();
    let args: Vec<String> = [
        "render",
        "scene.lua",
        "--backend",
        "cpu",
        "--memory-limit",
        "64",
    ]
    .map(String::from)
    .to_vec();
    let ended = run_glint(&args, &dir, &logs, Duration::from_secs(20), &mut |_| false);
    check_ended(
        &Case::new("mem-scene", "", 3, &["scene.lua", "memory limit of 64 MiB"]).within(20, bound),
        &ended,
    );
    // A PNG whose ICC profile inflates to 400 MiB: the decoder's reading of the header
    // is held to the budget too (the profile, which glint does not use, is dropped).
    check(
        Case::new(
            "mem-iccp",
            "gr.material('m'):set_diffuse('icc.png')\n",
            0,
            &["never called gr.render"],
        )
        .file("icc.png", png_with_icc(400 << 20))
        .args(&["--memory-limit", "64"])
        .within(30, bound),
    );
}

/// A 2×2 PNG carrying an ICC profile of `len` zero bytes (compressed to a few hundred
/// KB in its iCCP chunk).
fn png_with_icc(len: usize) -> Vec<u8> {
    use image::ImageEncoder;
    let mut bytes = Vec::new();
    let mut encoder = image::codecs::png::PngEncoder::new(&mut bytes);
    encoder.set_icc_profile(vec![0; len]).unwrap();
    encoder
        .write_image(&[9; 12], 2, 2, image::ExtendedColorType::Rgb8)
        .unwrap();
    bytes
}

/// A small OpenEXR whose data window is rewritten to claim `side`×`side` pixels.
fn forged_exr(side: i32) -> Vec<u8> {
    let mut bytes = Vec::new();
    image::Rgb32FImage::from_pixel(4, 4, image::Rgb([0.5, 0.5, 0.5]))
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::OpenExr,
        )
        .unwrap();
    let key = b"dataWindow\0box2i\0";
    let at = bytes
        .windows(key.len())
        .position(|w| w == key)
        .expect("a data window")
        + key.len()
        + 4;
    bytes[at + 8..at + 12].copy_from_slice(&(side - 1).to_le_bytes());
    bytes[at + 12..at + 16].copy_from_slice(&(side - 1).to_le_bytes());
    bytes
}

#[test]
fn images_are_decoded_by_content_within_the_budget() {
    let forged = forged_exr(1 << 30);
    // An EXR (forged or not) named like a PNG is no texture: textures are PNG or JPEG.
    for (tag, bytes) in [
        ("tex-exr-forged", forged.clone()),
        ("tex-exr", forged_exr(4)),
    ] {
        check(
            Case::new(
                tag,
                "gr.material('m'):set_diffuse('t.png')\n",
                3,
                &["scene.lua:1:", "t.png", "not a PNG or JPEG"],
            )
            .file("t.png", bytes)
            .args(&["--memory-limit", "64"])
            .within(20, 64 + OVERHEAD_MIB),
        );
    }
    // glint diff: the forged EXR, whatever its name, is refused from its header.
    let (dir, logs, _root) = case_dir("diff-forged");
    std::fs::write(dir.join("t.png"), &forged).unwrap();
    std::fs::write(dir.join("t.exr"), &forged).unwrap();
    std::fs::write(dir.join("small.png"), png(4, 4)).unwrap();
    let fifo = dir.join("fifo.png");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    for (a, b, needle) in [
        ("t.png", "small.png", "t.png"),
        ("small.png", "t.exr", "t.exr"),
        ("fifo.png", "small.png", "not a regular file"),
        ("small.png", "fifo.png", "not a regular file"),
        ("scene.lua", "small.png", "not a PNG, JPEG or OpenEXR"),
    ] {
        std::fs::write(dir.join("scene.lua"), "x = 1\n").unwrap();
        let args = ["diff", a, b].map(String::from).to_vec();
        let ended = run_glint(&args, &dir, &logs, Duration::from_secs(10), &mut |_| false);
        check_ended(&Case::new("diff-forged", "", 2, &[needle]), &ended);
    }
}

#[test]
fn work_the_hook_cannot_see_is_bounded() {
    // Default limits: each must end within the case's 30 s with the line.
    let cases = [
        // A shared CSG tree under 100 000 distinct roots: counted from the DAG.
        (
            "work-csg",
            "local c = gr.sphere('s')\nfor k = 1, 16 do c = gr.csg('c', 'u', c, c) end\nroot = gr.node('root')\nfor i = 1, 100000 do root:add_child(gr.csg('r', 'u', c, c)) end\ngr.render(root, 'out.png', 8, 8, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0,0,0}, {})\n",
            "scene.lua:5: gr.render:",
        ),
        ("work-move", "local t = {}\ntable.move(t, 1, 1e12, 2)\n", "scene.lua:2:"),
        (
            "work-format",
            "local s = string.rep('\"', 2^25)\nfor i = 1, 1e9 do local q = string.format('%q', s) end\n",
            "scene.lua:2:",
        ),
        (
            "work-gc",
            "local t = {}\nfor i = 1, 2e6 do t[i] = {} end\nfor i = 1, 1e9 do collectgarbage() end\n",
            "scene.lua:3:",
        ),
        (
            "work-pcall",
            "for i = 1, 1e12 do pcall(string.rep) end\n",
            "scene.lua:1:",
        ),
        (
            "work-xpcall",
            "local function h(e) error(e) end\nfor i = 1, 1e12 do xpcall(error, h, 'x') end\n",
            "scene.lua:",
        ),
    ];
    for (tag, scene, needle) in cases {
        check(
            Case::new(tag, scene, 3, &[needle])
                .args(&["--memory-limit", "1024"])
                .within(30, 1024 + OVERHEAD_MIB),
        );
    }
    // A 64 MiB chunk name given to load is cut to a line and not copied at each step.
    let (dir, logs, _root) = case_dir("work-chunk-name");
    std::fs::write(
        dir.join("scene.lua"),
        "local n = string.rep('n', 2^26)\nlocal f = load('for i = 1, 1e12 do end', n)\nf()\n",
    )
    .unwrap();
    let args = [
        "render",
        "scene.lua",
        "--backend",
        "cpu",
        "--instruction-limit",
        "50000000",
    ]
    .map(String::from)
    .to_vec();
    let ended = run_glint(&args, &dir, &logs, Duration::from_secs(20), &mut |_| false);
    check_ended(
        &Case::new(
            "work-chunk-name",
            "",
            3,
            &["[string \"nnn", "instruction limit"],
        )
        .within(20, 1024),
        &ended,
    );
    assert!(ended.stderr.len() < 1000, "{} bytes", ended.stderr.len());
    assert!(
        ended.elapsed < Duration::from_secs(10),
        "{:?}",
        ended.elapsed
    );
}

#[test]
fn every_signal_that_ends_glint_during_a_write_removes_the_temporary_file() {
    // The signals glint did not clean up after before (SIGINT and SIGTERM are tested
    // above), sent while the temporary file exists.
    for sig in [
        libc::SIGQUIT,
        libc::SIGUSR1,
        libc::SIGALRM,
        libc::SIGXCPU,
        libc::SIGXFSZ,
        libc::SIGPWR,
        libc::SIGRTMIN() + 1,
    ] {
        signal_during_write(&format!("signal-more-{sig}"), 3000, sig);
    }
    // A real file-size limit: the write passes it, SIGXFSZ ends glint, nothing is left.
    let (dir, _logs, _root) = case_dir("fsize");
    let scene = "root = gr.sphere('s')\ngr.render(root, 'out.exr', 200, 200, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {gr.light({5,5,5}, {1,1,1}, {1,0,0})})\n";
    std::fs::write(dir.join("scene.lua"), scene).unwrap();
    let mut command = Command::new(env!("CARGO_BIN_EXE_glint"));
    command
        .args(["render", "scene.lua", "--backend", "cpu"])
        .current_dir(&dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    // SAFETY: setrlimit and signal are async-signal-safe, as `pre_exec` requires.
    unsafe {
        command.pre_exec(|| {
            libc::signal(libc::SIGXFSZ, libc::SIG_DFL);
            let cap = libc::rlimit {
                rlim_cur: 64 << 10,
                rlim_max: 64 << 10,
            };
            libc::setrlimit(libc::RLIMIT_FSIZE, &cap);
            Ok(())
        });
    }
    let status = command.status().unwrap();
    assert!(
        !status.success(),
        "a 480 KB EXR under a 64 KB file-size limit"
    );
    assert_eq!(listing(&dir), vec!["scene.lua"], "{status:?}");
}

#[test]
fn exit_codes_and_messages_say_what_and_where() {
    let scene = with_render("");
    for (tag, args, needle) in [
        (
            "instructions-0",
            vec!["--instruction-limit", "0"],
            "--instruction-limit",
        ),
        ("min-weight-2", vec!["--min-weight", "2"], "--min-weight"),
        (
            "min-weight-huge",
            vec!["--min-weight", "1e30"],
            "--min-weight",
        ),
        (
            "aperture-negative",
            vec!["--aperture", "-1"],
            "aperture must be a non-negative lens radius",
        ),
        ("aperture-nan", vec!["--aperture", "NaN"], "--aperture"),
        ("focus-zero", vec!["--focus", "0"], "--focus"),
        (
            "focus-negative",
            vec!["--focus", "-2"],
            "focus must be a positive distance",
        ),
        ("focus-inf", vec!["--focus", "inf"], "--focus"),
    ] {
        check(Case::new(tag, &scene, 2, &[needle]).args(&args));
    }
    // Memory errors inside `..`, string.rep and table.concat name their line.
    for (tag, body, line) in [
        (
            "mem-concat",
            "local s = string.rep('x', 2^25)\nlocal u = s .. s .. s .. s .. s .. s .. s .. s\n",
            "scene.lua:2:",
        ),
        ("mem-rep", "local x = 1\nlocal s = string.rep('x', 2^30)\n", "scene.lua:2:"),
        (
            "mem-table-concat",
            "local t = {}\nfor i = 1, 100 do t[i] = string.rep('y', 2^20) end\nlocal s = table.concat(t)\n",
            "scene.lua:3:",
        ),
    ] {
        check(
            Case::new(tag, body, 3, &[line, "memory limit of 256 MiB"])
                .args(&["--memory-limit", "256"])
                .within(20, 256 + OVERHEAD_MIB),
        );
    }
    // The script runs as a coroutine (so a memory error keeps its line): a yield from
    // its main chunk is still the error it is in plain Lua.
    check(Case::new(
        "top-yield",
        "x = 1\ncoroutine.yield(1)\n",
        3,
        &["scene.lua:2:", "yield from outside a coroutine"],
    ));
    // A binary chunk as the scene names the file.
    check(Case::new(
        "binary-scene",
        "\x1bLuaT\0\x19\u{93}\r\n\x1a\n",
        3,
        &["scene.lua:1:", "binary"],
    ));
    // Error messages are capped.
    let (dir, logs, _root) = case_dir("long-message");
    std::fs::write(dir.join("scene.lua"), "error(string.rep('x', 2^24))\n").unwrap();
    let args: Vec<String> = ["render", "scene.lua", "--backend", "cpu"]
        .map(String::from)
        .to_vec();
    let ended = run_glint(&args, &dir, &logs, Duration::from_secs(20), &mut |_| false);
    check_ended(&Case::new("long-message", "", 3, &["scene.lua:1:"]), &ended);
    assert!(ended.stderr.len() < 8192, "{} bytes", ended.stderr.len());
    // A chunk name cannot make an error blame another file.
    for name in ["'@/etc/passwd'", "'=/etc/passwd'"] {
        let scene = format!("load('error(\"x\")', {name})()\n");
        let (dir, logs, _root) = case_dir("chunk-name");
        std::fs::write(dir.join("scene.lua"), &scene).unwrap();
        let ended = run_glint(&args, &dir, &logs, Duration::from_secs(20), &mut |_| false);
        check_ended(&Case::new("chunk-name", "", 3, &["[string"]), &ended);
        assert!(!ended.stderr.contains("/etc/passwd:1"), "{}", ended.stderr);
    }
    // A UTF-8 byte-order mark, in a scene and in an OBJ file, is no statement.
    let bom = format!(
        "\u{feff}{}",
        with_render("root:add_child(gr.mesh('m', 'm.obj'))\n")
    );
    check(
        Case::new("bom", &bom, 0, &["wrote out.png"])
            .file("m.obj", "\u{feff}v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
            .writes("out.png"),
    );
    // Normal indices are checked as the others are.
    check(
        Case::new(
            "vn-range",
            "gr.mesh('m', 'm.obj')\n",
            3,
            &["m.obj:5:", "normal index 5 out of range"],
        )
        .file(
            "m.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//5 2//1 3//1\n",
        ),
    );
}

#[test]
fn huge_names_are_counted_and_never_copied_whole_into_messages() {
    // Two 128 MiB names in a cycle error and a too-deep path: the message quotes each
    // name short, so nothing the budget did not see is allocated for it.
    for (tag, scene, needle) in [
        (
            "name-cycle",
            "local big = string.rep('n', 2^27)\nlocal a = gr.node(big)\nlocal b = gr.node(big)\na:add_child(b)\nb:add_child(a)\n",
            "scene.lua:5: node:add_child:",
        ),
        (
            "name-csg",
            "local big = string.rep('n', 2^27)\ngr.csg('c', 'u', gr.node(big), gr.sphere('s'))\n",
            "scene.lua:2: gr.csg:",
        ),
        (
            "name-material",
            "local big = string.rep('n', 2^27)\nlocal m = gr.material(big)\ngr.sphere('s'):set_material(m)\nlocal n = gr.node(big)\nn:set_material(m)\n",
            "scene.lua:5: node:set_material:",
        ),
    ] {
        let (dir, logs, _root) = case_dir(tag);
        std::fs::write(dir.join("scene.lua"), scene).unwrap();
        let args = ["render", "scene.lua", "--backend", "cpu", "--memory-limit", "1024"]
            .map(String::from)
            .to_vec();
        let ended = run_glint(&args, &dir, &logs, Duration::from_secs(20), &mut |_| false);
        let case = Case::new(tag, scene, 3, &[needle]).within(20, 1024 + OVERHEAD_MIB);
        check_ended(&case, &ended);
        assert!(ended.stderr.len() < 2000, "{tag}: {} bytes", ended.stderr.len());
        assert_eq!(listing(&dir), vec!["scene.lua"]);
    }
}

// ---- Round three: farm tiles as untrusted input ----
// Tiles come back from other machines: `glint assemble` (and `--skip-existing`) must
// treat them as a hostile file, bounded before anything is allocated, opened once, their
// labels checked against the split and their pixels against the digest in their record.

/// A 16×8 render of one sphere of colour `rgb` (two colours: two different renders).
/// Split in two, its tiles are 8×8 each, so their bounds can be swapped.
fn farm_scene(rgb: &str) -> String {
    format!(
        "root = gr.node('root')\ns = gr.sphere('s')\nroot:add_child(s)\n\
         s:set_material(gr.material({{{rgb}}}, {{0.3, 0.3, 0.3}}, 10))\n\
         gr.render(root, 'out.png', 16, 8, {{0, 0, 4}}, {{0, 0, -1}}, {{0, 1, 0}}, 50, \
         {{0.1, 0.1, 0.3}}, {{gr.light({{5, 5, 5}}, {{1, 1, 1}}, {{1, 0, 0}})}})\n"
    )
}

/// Runs glint with `args` in `dir` (at most `seconds`, the usual peak memory) and checks
/// its exit code and message ([`check_ended`]).
fn farm_glint(tag: &str, dir: &Path, logs: &Path, args: &[&str], code: i32, needles: &[&str]) {
    farm_glint_within(tag, dir, logs, args, (code, needles), 20);
}

fn farm_glint_within(
    tag: &str,
    dir: &Path,
    logs: &Path,
    args: &[&str],
    (code, needles): (i32, &[&str]),
    seconds: u64,
) -> Ended {
    let args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
    let ended = run_glint(&args, dir, logs, Duration::from_secs(seconds), &mut |_| {
        false
    });
    check_ended(&Case::new(tag, "", code, needles), &ended);
    ended
}

/// Renders `scene` (a file in `dir`) as tiles 0..n of n, `OUT-tile-I-of-N.EXT`.
fn render_farm_tiles(dir: &Path, logs: &Path, scene: &str, n: u32, out: &str) {
    for i in 0..n {
        let tile = format!("{i}/{n}");
        let args = [
            "render",
            scene,
            "--backend",
            "cpu",
            "--tile",
            &tile,
            "-o",
            out,
        ];
        farm_glint("render-tile", dir, logs, &args, 0, &[]);
    }
}

/// `glint assemble TILES -o out.EXT` refused (exit code 2) naming `needles`, within
/// `seconds`, writing nothing.
fn assemble_refused(tag: &str, dir: &Path, logs: &Path, tiles: &[&str], needles: &[&str]) {
    assemble_refused_within(tag, dir, logs, tiles, needles, 20);
}

fn assemble_refused_within(
    tag: &str,
    dir: &Path,
    logs: &Path,
    tiles: &[&str],
    needles: &[&str],
    seconds: u64,
) {
    let before = listing(dir);
    let out = if tiles[0].ends_with(".exr") {
        "out.exr"
    } else {
        "out.png"
    };
    let mut args = vec!["assemble", "-o", out];
    args.extend(tiles);
    farm_glint_within(tag, dir, logs, &args, (2, needles), seconds);
    assert_eq!(listing(dir), before, "{tag}: a file was written");
}

/// A PNG tile taken apart: its size, its text chunks (the record) and its RGB bytes.
struct PngTile {
    width: u32,
    height: u32,
    texts: Vec<(String, String)>,
    rgb: Vec<u8>,
}

impl PngTile {
    fn read(path: &Path) -> PngTile {
        let file = std::io::BufReader::new(std::fs::File::open(path).unwrap());
        let mut reader = png::Decoder::new(file).read_info().unwrap();
        let info = reader.info();
        let (width, height) = (info.width, info.height);
        let texts = info
            .uncompressed_latin1_text
            .iter()
            .map(|c| (c.keyword.clone(), c.text.clone()))
            .collect();
        let mut rgb = vec![0; reader.output_buffer_size().unwrap()];
        reader.next_frame(&mut rgb).unwrap();
        PngTile {
            width,
            height,
            texts,
            rgb,
        }
    }
    /// A `width`×`height` grey tile with the record `texts`.
    fn forged(width: u32, height: u32, texts: &[(&str, &str)]) -> PngTile {
        PngTile {
            width,
            height,
            texts: texts
                .iter()
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .collect(),
            rgb: vec![128; (width * height * 3) as usize],
        }
    }
    fn text(&self, key: &str) -> String {
        let found = self.texts.iter().find(|(k, _)| k == key);
        found.map(|(_, v)| v.clone()).unwrap_or_default()
    }
    fn set(&mut self, key: &str, value: &str) {
        self.texts.retain(|(k, _)| k != key);
        self.texts.push((key.to_string(), value.to_string()));
    }
    fn remove(&mut self, key: &str) {
        self.texts.retain(|(k, _)| k != key);
    }
    fn write(&self, path: &Path) {
        let mut bytes = Vec::new();
        let mut encoder = png::Encoder::new(&mut bytes, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        for (k, v) in &self.texts {
            encoder.add_text_chunk(k.clone(), v.clone()).unwrap();
        }
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(&self.rgb).unwrap();
        writer.finish().unwrap();
        std::fs::write(path, bytes).unwrap();
    }
}

/// A record claiming a `full` image of which the tile holds `bounds`, with digests that
/// look right (64 hex digits) so that only the claim itself can be refused.
fn forged_record<'a>(full: &'a str, bounds: &'a str) -> Vec<(&'a str, &'a str)> {
    const HEX: &str = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";
    vec![
        ("glint:full-size", full),
        ("glint:bounds", bounds),
        ("glint:digest", HEX),
        ("glint:version", env!("CARGO_PKG_VERSION")),
        ("glint:pixels", HEX),
    ]
}

fn mkfifo(path: &Path) {
    let c = std::ffi::CString::new(path.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
}

/// A PNG chunk: length, name, data, CRC.
fn png_chunk(out: &mut Vec<u8>, name: &[u8; 4], data: &[u8]) {
    out.extend((data.len() as u32).to_be_bytes());
    let mut named = name.to_vec();
    named.extend(data);
    out.extend(&named);
    out.extend(crc32(&named).to_be_bytes());
}

/// A zlib stream of `n` zero bytes in fixed-Huffman deflate: a literal 0, then copies of
/// 258 bytes at distance 1 (13 bits each), so a few MB stand for hundreds of MB.
fn zlib_zeros(n: u64) -> Vec<u8> {
    struct Bits {
        out: Vec<u8>,
        acc: u64,
        count: u32,
    }
    impl Bits {
        fn put(&mut self, value: u64, bits: u32) {
            self.acc |= value << self.count;
            self.count += bits;
            while self.count >= 8 {
                self.out.push(self.acc as u8);
                self.acc >>= 8;
                self.count -= 8;
            }
        }
        /// A Huffman code: most significant bit first.
        fn code(&mut self, code: u32, bits: u32) {
            self.put(u64::from(code.reverse_bits() >> (32 - bits)), bits);
        }
    }
    let mut b = Bits {
        out: vec![0x78, 0x01],
        acc: 0,
        count: 0,
    };
    b.put(1, 1); // the final block
    b.put(1, 2); // fixed Huffman codes
    b.code(0x30, 8); // literal 0
    let mut left = n - 1;
    while left >= 258 {
        b.code(0b1100_0101, 8); // length 258
        b.code(0, 5); // distance 1
        left -= 258;
    }
    for _ in 0..left {
        b.code(0x30, 8);
    }
    b.code(0, 7); // end of block
    if b.count > 0 {
        b.out.push(b.acc as u8);
    }
    // Adler-32 of zeros: a stays 1, b counts the bytes.
    let adler = ((n % 65521) << 16) as u32 | 1;
    b.out.extend(adler.to_be_bytes());
    b.out
}

/// A real `side`×`side` RGB PNG of black pixels (its deflated rows, a few MB) whose
/// record claims it is a whole image of that size.
fn huge_png_tile(side: u32) -> Vec<u8> {
    let full = format!("{side}x{side}");
    let bounds = format!("0,{side},0,{side}");
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = side.to_be_bytes().to_vec();
    ihdr.extend(side.to_be_bytes());
    ihdr.extend([8, 2, 0, 0, 0]);
    png_chunk(&mut out, b"IHDR", &ihdr);
    for (k, v) in forged_record(&full, &bounds) {
        png_chunk(&mut out, b"tEXt", format!("{k}\0{v}").as_bytes());
    }
    let raw = u64::from(side) * (1 + 3 * u64::from(side));
    png_chunk(&mut out, b"IDAT", &zlib_zeros(raw));
    png_chunk(&mut out, b"IEND", &[]);
    out
}

/// Layer attributes holding `texts` (a tile's record).
fn exr_texts(name: &str, texts: &[(&str, &str)]) -> exr::prelude::LayerAttributes {
    use exr::meta::attribute::{AttributeValue, Text};
    let mut attributes = exr::prelude::LayerAttributes::named(name);
    for (k, v) in texts {
        let value = AttributeValue::Text(Text::from(*v));
        attributes.other.insert(Text::from(*k), value);
    }
    attributes
}

/// A 4×4 grey EXR tile whose layer carries `texts`, stored as one 16×16 block, its data
/// window and block size then rewritten to claim `side`×`side` pixels in one block: the
/// file stays a few hundred bytes and its table of blocks stays consistent.
fn forged_exr_tile(texts: &[(&str, &str)], side: i32) -> Vec<u8> {
    use exr::prelude::*;
    let encoding = Encoding {
        compression: Compression::Uncompressed,
        blocks: Blocks::Tiles(Vec2(16, 16)),
        line_order: LineOrder::Increasing,
    };
    let layer = Layer::new(
        (4, 4),
        exr_texts("glint tile", texts),
        encoding,
        SpecificChannels::rgb(|_| (0.5_f32, 0.5_f32, 0.5_f32)),
    );
    let mut bytes = Vec::new();
    let image = Image::from_layer(layer);
    image
        .write()
        .to_buffered(std::io::Cursor::new(&mut bytes))
        .unwrap();
    let find =
        |key: &[u8]| bytes.windows(key.len()).position(|w| w == key).unwrap() + key.len() + 4;
    let window = find(b"dataWindow\0box2i\0");
    let tiles = find(b"tiles\0tiledesc\0");
    bytes[window + 8..window + 12].copy_from_slice(&(side - 1).to_le_bytes());
    bytes[window + 12..window + 16].copy_from_slice(&(side - 1).to_le_bytes());
    bytes[tiles..tiles + 4].copy_from_slice(&side.to_le_bytes());
    bytes[tiles + 4..tiles + 8].copy_from_slice(&side.to_le_bytes());
    bytes
}

/// A two-part EXR: the first part carries a 4×4 tile's record over a luminance channel
/// only, the second is a 2×2 RGB image without one (what a reader of "the first RGB
/// layer" would take).
fn two_part_exr_tile() -> Vec<u8> {
    use exr::prelude::*;
    let record = forged_record("4x4", "0,4,0,4");
    let first = Layer::new(
        (4, 4),
        exr_texts("glint tile", &record),
        Encoding::UNCOMPRESSED,
        SpecificChannels::build()
            .with_channel("Y")
            .with_pixel_fn(|_| (0.5_f32,)),
    );
    let second = Layer::new(
        (2, 2),
        LayerAttributes::named("other"),
        Encoding::UNCOMPRESSED,
        SpecificChannels::rgb(|_| (1.0_f32, 0.0_f32, 0.0_f32)),
    );
    let image = Image::empty(ImageAttributes::new(IntegerBounds::from_dimensions((4, 4))))
        .with_layer(first)
        .with_layer(second);
    let mut bytes = Vec::new();
    image
        .write()
        .to_buffered(std::io::Cursor::new(&mut bytes))
        .unwrap();
    bytes
}

/// The members of one class, each checked in turn; the test fails once at the end,
/// naming every member that failed (one run against an old binary shows them all).
struct Members<'a> {
    dir: &'a Path,
    failed: Vec<String>,
}

impl<'a> Members<'a> {
    fn new(dir: &'a Path) -> Members<'a> {
        Members {
            dir,
            failed: Vec::new(),
        }
    }
    fn check(&mut self, name: &str, case: impl FnOnce()) {
        if std::panic::catch_unwind(std::panic::AssertUnwindSafe(case)).is_err() {
            self.failed.push(name.to_string());
            // What a failed member wrote must not decide the next one.
            for out in ["out.png", "out.exr"] {
                let _ = std::fs::remove_file(self.dir.join(out));
            }
        }
    }
    fn done(self) {
        assert!(self.failed.is_empty(), "members failed: {:?}", self.failed);
    }
}

/// Tiles that claim more than any image glint makes, or more than the memory budget, are
/// refused from their record, before anything is sized from it: a few hundred bytes
/// claiming 100000² or 4294967295² pixels, a real 16000² PNG, an EXR whose data window
/// asks 206 GB, a full size within the pixel limit but over the budget.
#[test]
fn assemble_bounds_a_tiles_claims_before_allocating() {
    let (dir, logs, _root) = case_dir("farm-claims");
    let mut members = Members::new(&dir);
    let cases: [(&str, &str, &[&str]); 3] = [
        (
            "t-100k.png",
            "100000x100000",
            &["t-100k.png", "100000×100000"],
        ),
        (
            "t-u32.png",
            "4294967295x4294967295",
            &["t-u32.png", "4294967295×4294967295"],
        ),
        (
            "t-budget.png",
            "10000x10000",
            &["t-budget.png", "--memory-limit"],
        ),
    ];
    for (name, full, needles) in cases {
        PngTile::forged(1, 1, &forged_record(full, "0,1,0,1")).write(&dir.join(name));
        members.check(name, || {
            assemble_refused(name, &dir, &logs, &[name], needles)
        });
        std::fs::remove_file(dir.join(name)).unwrap();
    }
    std::fs::write(dir.join("t-16k.png"), huge_png_tile(16000)).unwrap();
    members.check("png-16k", || {
        assemble_refused(
            "png-16k",
            &dir,
            &logs,
            &["t-16k.png"],
            &["t-16k.png", "16000×16000"],
        )
    });
    std::fs::remove_file(dir.join("t-16k.png")).unwrap();
    let side = 131_072;
    let (full, bounds) = (format!("{side}x{side}"), format!("0,{side},0,{side}"));
    let exr = forged_exr_tile(&forged_record(&full, &bounds), side);
    assert!(exr.len() < 1000, "{} bytes", exr.len());
    std::fs::write(dir.join("t-206g.exr"), exr).unwrap();
    members.check("exr-206g", || {
        assemble_refused(
            "exr-206g",
            &dir,
            &logs,
            &["t-206g.exr"],
            &["t-206g.exr", "131072"],
        )
    });
    members.done();
}

/// Only a regular file is a tile: a FIFO is refused at once (never waited on), a device
/// too; a multi-part EXR is refused (the part checked would not be the part read).
#[test]
fn assemble_reads_each_tile_once_as_the_regular_file_it_is() {
    let (dir, logs, _root) = case_dir("farm-special");
    let mut members = Members::new(&dir);
    mkfifo(&dir.join("t-fifo.png"));
    std::os::unix::fs::symlink("/dev/zero", dir.join("t-zero.exr")).unwrap();
    std::fs::write(dir.join("t-parts.exr"), two_part_exr_tile()).unwrap();
    for (tile, needle) in [
        ("t-fifo.png", "not a regular file"),
        ("t-zero.exr", "not a regular file"),
        ("t-parts.exr", "several parts"),
    ] {
        members.check(tile, || {
            assemble_refused_within(tile, &dir, &logs, &[tile], &[tile, needle], 10)
        });
    }
    members.done();
}

/// A farm of two tiles of scene A (`a-tile-I-of-2.EXT`) and two of scene B, in `dir`.
fn two_farms(dir: &Path, logs: &Path, ext: &str) {
    std::fs::write(dir.join("a.lua"), farm_scene("0.8, 0.3, 0.2")).unwrap();
    std::fs::write(dir.join("b.lua"), farm_scene("0.2, 0.3, 0.8")).unwrap();
    render_farm_tiles(dir, logs, "a.lua", 2, &format!("a.{ext}"));
    render_farm_tiles(dir, logs, "b.lua", 2, &format!("b.{ext}"));
}

/// A tile whose record or pixels were changed after it was written is refused, naming
/// it: bounds swapped between two tiles (the label no longer matches the split; with the
/// labels swapped too, or on crop tiles without labels, the pixels no longer match their
/// digest), a digest copied from another render's tile, an edited pixel, a forged tile
/// count (at once, not after a minute), and a tile without the pixel digest (written
/// before it existed: to be rendered again).
#[test]
fn assemble_checks_labels_and_pixels_against_the_record() {
    let (dir, logs, _root) = case_dir("farm-forged");
    two_farms(&dir, &logs, "png");
    let mut members = Members::new(&dir);
    let (a0, a1) = ("a-tile-0-of-2.png", "a-tile-1-of-2.png");
    let read = |name: &str| PngTile::read(&dir.join(name));
    let write = |tile: &PngTile, name: &str| tile.write(&dir.join(name));
    let refused = |tag: &str, tiles: &[&str], needles: &[&str]| {
        assemble_refused_within(tag, &dir, &logs, tiles, needles, 10)
    };
    // The genuine tiles assemble.
    farm_glint(
        "genuine",
        &dir,
        &logs,
        &["assemble", a0, a1, "-o", "ok.png"],
        0,
        &[],
    );
    std::fs::remove_file(dir.join("ok.png")).unwrap();
    let (mut s0, mut s1) = (read(a0), read(a1));
    let (b0, b1) = (s0.text("glint:bounds"), s1.text("glint:bounds"));
    s0.set("glint:bounds", &b1);
    s1.set("glint:bounds", &b0);
    write(&s0, "s0.png");
    write(&s1, "s1.png");
    let swapped = ["s0.png", "s1.png"];
    members.check("swapped", || {
        refused("swapped", &swapped, &["s0.png", "0/2", &b0])
    });
    s0.set("glint:tile", "1/2");
    s1.set("glint:tile", "0/2");
    write(&s0, "s0.png");
    write(&s1, "s1.png");
    members.check("swapped-labels", || {
        refused("swapped-labels", &swapped, &["s0.png", "pixels"])
    });
    s0.remove("glint:tile");
    s1.remove("glint:tile");
    write(&s0, "s0.png");
    write(&s1, "s1.png");
    members.check("swapped-crops", || {
        refused("swapped-crops", &swapped, &["s0.png", "pixels"])
    });
    // Another render's tile under this render's digest, with or without its pixel digest.
    let mut copied = read("b-tile-1-of-2.png");
    copied.set("glint:digest", &read(a1).text("glint:digest"));
    write(&copied, "c1.png");
    members.check("copied-digest", || {
        refused("copied-digest", &[a0, "c1.png"], &["c1.png", "pixels"])
    });
    copied.set("glint:pixels", &read(a1).text("glint:pixels"));
    write(&copied, "c2.png");
    members.check("copied-both", || {
        refused("copied-both", &[a0, "c2.png"], &["c2.png", "pixels"])
    });
    let mut edited = read(a1);
    edited.rgb[7] ^= 0x10;
    write(&edited, "e1.png");
    members.check("edited", || {
        refused("edited", &[a0, "e1.png"], &["e1.png", "pixels"])
    });
    let mut old = read(a1);
    old.remove("glint:pixels");
    write(&old, "o1.png");
    members.check("no-pixel-digest", || {
        refused(
            "no-pixel-digest",
            &[a0, "o1.png"],
            &["o1.png", "render it again"],
        )
    });
    for (k, (label, needle)) in [
        ("0/4294967295", "4294967295"),
        ("0/65537", "65537"),
        ("3/2", "3/2"),
    ]
    .into_iter()
    .enumerate()
    {
        let mut forged = read(a0);
        forged.set("glint:tile", label);
        let name = format!("f{k}.png");
        write(&forged, &name);
        members.check(label, || refused(label, &[&name], &[&name, needle]));
    }
    members.done();
}

/// Any bit flipped in an EXR tile (60 places spread over the file, header and pixels) is
/// refused, or changes nothing: never an image other than the full render's.
#[test]
fn a_bit_flipped_in_an_exr_tile_never_makes_a_wrong_image() {
    let (dir, logs, _root) = case_dir("farm-flips");
    std::fs::write(dir.join("a.lua"), farm_scene("0.8, 0.3, 0.2")).unwrap();
    render_farm_tiles(&dir, &logs, "a.lua", 2, "a.exr");
    let (a0, a1) = ("a-tile-0-of-2.exr", "a-tile-1-of-2.exr");
    farm_glint(
        "genuine",
        &dir,
        &logs,
        &["assemble", a0, a1, "-o", "ref.exr"],
        0,
        &[],
    );
    let reference = std::fs::read(dir.join("ref.exr")).unwrap();
    let genuine = std::fs::read(dir.join(a1)).unwrap();
    let (mut refused, mut wrong) = (0, Vec::new());
    for k in 0..60 {
        let mut bytes = genuine.clone();
        let at = k * bytes.len() / 60 + k % 7;
        bytes[at] ^= 1 << (k % 8);
        std::fs::write(dir.join("f1.exr"), &bytes).unwrap();
        let args: Vec<String> = ["assemble", a0, "f1.exr", "-o", "out.exr"]
            .map(String::from)
            .to_vec();
        let ended = run_glint(&args, &dir, &logs, Duration::from_secs(20), &mut |_| false);
        let err = &ended.stderr;
        assert_eq!(
            ended.signal, None,
            "flip at {at}: killed by a signal:\n{err}"
        );
        assert!(!err.contains("panicked"), "flip at {at}: panicked:\n{err}");
        match ended.code {
            Some(0) => {
                let out = std::fs::read(dir.join("out.exr")).unwrap();
                if out != reference {
                    wrong.push(at);
                }
                std::fs::remove_file(dir.join("out.exr")).unwrap();
            }
            Some(2) => {
                assert!(err.contains("f1.exr"), "flip at {at}: {err}");
                assert!(
                    !dir.join("out.exr").exists(),
                    "flip at {at}: an image was written"
                );
                refused += 1;
            }
            other => panic!("flip at {at}: exit {other:?}:\n{err}"),
        }
    }
    assert!(
        wrong.is_empty(),
        "exit 0 with a wrong image for flips at bytes {wrong:?}"
    );
    assert!(refused >= 40, "only {refused} of 60 flips refused");
}

/// `--skip-existing` looks at what is at the tile's name without blocking and trusts
/// only a regular file holding this render's tile: a FIFO or a link to a device there is
/// rendered over.
#[test]
fn skip_existing_never_blocks_on_what_is_at_the_tiles_name() {
    let (dir, logs, _root) = case_dir("farm-skip");
    std::fs::write(dir.join("scene.lua"), farm_scene("0.8, 0.3, 0.2")).unwrap();
    let mut members = Members::new(&dir);
    let tile = dir.join("out-tile-0-of-2.png");
    let args = [
        "render",
        "scene.lua",
        "--backend",
        "cpu",
        "--tile",
        "0/2",
        "--skip-existing",
        "-o",
        "out.png",
    ];
    for plant in ["fifo", "zero"] {
        match plant {
            "fifo" => mkfifo(&tile),
            _ => std::os::unix::fs::symlink("/dev/zero", &tile).unwrap(),
        }
        members.check(plant, || {
            farm_glint_within(
                plant,
                &dir,
                &logs,
                &args,
                (0, &["wrote", "out-tile-0-of-2.png"]),
                10,
            );
            let kind = std::fs::symlink_metadata(&tile).unwrap().file_type();
            assert!(kind.is_file(), "{plant}: {kind:?}");
            // Now a genuine tile: kept.
            farm_glint_within(plant, &dir, &logs, &args, (0, &["kept"]), 10);
        });
        let _ = std::fs::remove_file(&tile);
    }
    members.done();
}

/// With a farm flag, the scene is read as every scene is: a FIFO or a device is refused
/// without blocking or reading it, a file over the limit before it is read.
#[test]
fn farm_renders_read_the_scene_as_a_bounded_regular_file() {
    let (dir, logs, _root) = case_dir("farm-scene");
    let mut members = Members::new(&dir);
    mkfifo(&dir.join("fifo.lua"));
    let big = std::fs::File::create(dir.join("big.lua")).unwrap();
    big.set_len(2 << 30).unwrap();
    for (scene, needle) in [
        ("fifo.lua", "not a regular file"),
        ("/dev/zero", "not a regular file"),
        ("big.lua", "big.lua"),
    ] {
        for flag in [
            &["--tile", "0/2"][..],
            &["--frames", "1-2"],
            &["--skip-existing"],
        ] {
            let mut args = vec!["render", scene, "--backend", "cpu", "-o", "out.png"];
            args.extend(flag);
            members.check(&format!("{scene} {}", flag[0]), || {
                farm_glint_within(scene, &dir, &logs, &args, (3, &[scene, needle]), 10);
            });
        }
    }
    assert_eq!(listing(&dir), vec!["big.lua", "fifo.lua"]);
    members.done();
}

// ---- Round three: files as they are, temp names, signals ----

/// Runs glint as [`run_glint`] does (address-space cap, time bound, default SIGINT and
/// SIGTERM), with `env` set, `HOME` a scratch folder unless `env` names it, and the
/// cache variables of the caller's environment removed; `shell` (if any) runs first in
/// the same process, which then becomes glint (`exec`, same pid: a planted name can
/// hold glint's pid).
fn run_glint_env<A: AsRef<std::ffi::OsStr> + std::fmt::Debug>(
    args: &[A],
    dir: &Path,
    env: &[(&str, &std::ffi::OsStr)],
    shell: Option<&str>,
    limit: Duration,
    during: &mut dyn FnMut(i32) -> bool,
) -> Ended {
    let scratch_home = dir.with_extension("home");
    std::fs::create_dir_all(&scratch_home).unwrap();
    let err_path = dir.with_extension("stderr");
    let mut command = match shell {
        Some(script) => {
            let mut c = Command::new("sh");
            c.arg("-c")
                .arg(format!("{script}\nexec \"$0\" \"$@\""))
                .arg(env!("CARGO_BIN_EXE_glint"));
            c
        }
        None => Command::new(env!("CARGO_BIN_EXE_glint")),
    };
    command
        .args(args)
        .current_dir(dir)
        .env("HOME", &scratch_home)
        .env_remove("GLINT_CACHE_DIR")
        .env_remove("GLINT_PIPELINE_CACHE")
        .env_remove("XDG_CACHE_HOME")
        .envs(env.iter().copied())
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(&err_path).unwrap());
    confine(&mut command);
    let pid = command.spawn().expect("glint starts").id() as i32;
    let start = Instant::now();
    let (mut status, mut hooked) = (0, true);
    // SAFETY: plain libc calls on our own child; rusage is plain data.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    while unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) } == 0 {
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
    let exited = libc::WIFEXITED(status);
    Ended {
        code: exited.then(|| libc::WEXITSTATUS(status)),
        signal: (!exited).then(|| libc::WTERMSIG(status)),
        peak_mib: usage.ru_maxrss as u64 / 1024,
        elapsed: start.elapsed(),
        stderr: std::fs::read_to_string(&err_path).unwrap_or_default(),
    }
}

/// Checks how a [`run_glint_env`] run ended: `code`, each needle, no panic, the peak.
fn ended_as(tag: &str, ended: &Ended, code: i32, needles: &[&str], peak_mib: u64) {
    let case = Case::new(tag, "", code, needles).within(30, peak_mib);
    check_ended(&case, ended);
}

const SMALL_RENDER: &str = "root = gr.node('root')\ngr.render(root, 'out.png', 16, 16, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {}, {aa='none'})\n";

/// A link planted at the temporary name glint would have used (`.NAME.tmp-PID-0`, the
/// first write of the process) pointing at a victim file: glint must neither write
/// through it nor rename it over the output, for a render, a tile, a crop and `-o`.
#[test]
fn temporary_files_cannot_be_hijacked_by_a_planted_link() {
    for (tag, extra, output) in [
        ("plant-render", vec![], "out.png"),
        ("plant-tile", vec!["--tile", "0/2"], "out-tile-0-of-2.png"),
        ("plant-crop", vec!["--crop", "0,8,0,8"], "out.png"),
        ("plant-o", vec!["-o", "mine.exr"], "mine.exr"),
    ] {
        let (dir, _logs, _root) = case_dir(tag);
        std::fs::write(dir.join("scene.lua"), SMALL_RENDER).unwrap();
        std::fs::write(dir.join("victim.txt"), "precious").unwrap();
        let planted = format!(".{output}.tmp-");
        let shell = format!("ln -s victim.txt \"{planted}$$-0\"");
        let mut args = vec!["render", "scene.lua", "--backend", "cpu"];
        args.extend(extra);
        let ended = run_glint_env(
            &args,
            &dir,
            &[],
            Some(&shell),
            Duration::from_secs(30),
            &mut |_| false,
        );
        ended_as(tag, &ended, 0, &[], BUDGET_MIB + OVERHEAD_MIB);
        assert_eq!(
            std::fs::read_to_string(dir.join("victim.txt")).unwrap(),
            "precious",
            "{tag}: written through the planted link"
        );
        let meta = std::fs::symlink_metadata(dir.join(output)).unwrap();
        assert!(meta.is_file(), "{tag}: the output is not a regular file");
        let names = listing(&dir);
        let stray: Vec<_> = names.iter().filter(|n| n.contains(".tmp-")).collect();
        assert_eq!(stray.len(), 1, "{tag}: only the planted link: {names:?}");
        assert!(stray[0].starts_with(&planted), "{tag}: {names:?}");
    }
}

/// SIGTERM (what Slurm sends at a time limit), SIGINT and SIGXFSZ while a `--tile` or
/// `--crop` file is written remove its temporary file, as for a plain render.
#[test]
fn a_signal_during_a_tile_write_leaves_nothing_behind() {
    const ATTEMPTS: usize = 5;
    let cases = [
        (libc::SIGTERM, "--tile", "0/2"),
        (libc::SIGINT, "--crop", "0,4000,0,2000"),
        (libc::SIGXFSZ, "--tile", "1/2"),
    ];
    for (sig, flag, value) in cases {
        let mut interrupted = false;
        for attempt in 0..ATTEMPTS {
            let (dir, _logs, _root) = case_dir(&format!("tile-signal-{sig}-{attempt}"));
            let scene = "root = gr.node('root')\ngr.render(root, 'big.png', 4000, 4000, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {}, {aa='none'})\n";
            std::fs::write(dir.join("scene.lua"), scene).unwrap();
            let args = ["render", "scene.lua", "--backend", "cpu", flag, value];
            let ended = run_glint_env(
                &args,
                &dir,
                &[],
                None,
                Duration::from_secs(120),
                &mut signal_once_a_temp_file_exists(&dir, sig),
            );
            let names = listing(&dir);
            assert!(
                !names.iter().any(|n| n.contains(".tmp-")),
                "signal {sig} during {flag} {value}: temporary file left: {names:?}; stderr:\n{}",
                ended.stderr
            );
            if ended.signal == Some(sig) && names == ["scene.lua"] {
                interrupted = true;
                break;
            }
        }
        assert!(
            interrupted,
            "signal {sig} never landed during a {flag} write"
        );
    }
}

/// Pipeline-cache files that are not what they seem (a FIFO, links to `/dev/zero` and
/// to a FIFO, a 2 GiB sparse file, a 60 MiB one whose header cannot be whole) are
/// refused without blocking or reading them, and the render goes on; a cache folder
/// behind a dangling link is said as such; a bad `GLINT_PIPELINE_CACHE` is usage.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn pipeline_cache_files_are_opened_as_they_really_are() {
    let (dir, _logs, _root) = case_dir("cache-files");
    std::fs::write(dir.join("scene.lua"), SMALL_RENDER).unwrap();
    let cache = dir.with_extension("cache");
    let env = [("GLINT_CACHE_DIR", cache.as_os_str())];
    let args = ["render", "scene.lua", "--backend", "gpu"];
    let limit = Duration::from_secs(30);
    let ended = run_glint_env(&args, &dir, &env, None, limit, &mut |_| false);
    ended_as("cache-fill", &ended, 0, &[], BUDGET_MIB + OVERHEAD_MIB);
    let files: Vec<PathBuf> = std::fs::read_dir(&cache)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert!(!files.is_empty(), "no cache file written");
    let fifo = dir.with_extension("fifo");
    mkfifo(&fifo);
    let plant = |how: &str, file: &Path| {
        std::fs::remove_file(file).unwrap();
        match how {
            "fifo" => mkfifo(file),
            "zero" => std::os::unix::fs::symlink("/dev/zero", file).unwrap(),
            "fifo-link" => std::os::unix::fs::symlink(&fifo, file).unwrap(),
            sparse => {
                let f = std::fs::File::create(file).unwrap();
                let len = if sparse == "2GiB" { 2 << 30 } else { 60 << 20 };
                use std::io::Write;
                (&f).write_all(b"GLINTPC\n\x01\0\0\0\x10\0\0\0\x10\0\0\0\0\0\0\0")
                    .unwrap();
                f.set_len(len).unwrap();
            }
        }
    };
    for (how, needle) in [
        ("fifo", "not a regular file"),
        ("zero", "not a regular file"),
        ("fifo-link", "not a regular file"),
        ("2GiB", "larger than any pipeline cache file"),
        ("60MiB", "corrupt"),
    ] {
        for file in &files {
            plant(how, file);
        }
        let ended = run_glint_env(&args, &dir, &env, None, limit, &mut |_| false);
        ended_as(
            how,
            &ended,
            0,
            &[needle, "it is rewritten"],
            BUDGET_MIB + OVERHEAD_MIB,
        );
        assert!(
            ended.elapsed < Duration::from_secs(20),
            "{how}: {:?}",
            ended.elapsed
        );
    }
    // The cache folder behind a dangling link.
    let dangling = dir.with_extension("dangling");
    std::os::unix::fs::symlink(dir.with_extension("nowhere"), &dangling).unwrap();
    let below = dangling.join("sub");
    let env = [("GLINT_CACHE_DIR", below.as_os_str())];
    let ended = run_glint_env(&args, &dir, &env, None, limit, &mut |_| false);
    ended_as(
        "cache-dangling",
        &ended,
        0,
        &["is a symbolic link to nothing"],
        512,
    );
    assert!(!ended.stderr.contains("os error 17"), "{}", ended.stderr);
    // A value of the switch glint does not take: a usage error, before anything runs.
    let env = [("GLINT_PIPELINE_CACHE", std::ffi::OsStr::new("maybe"))];
    for command in [&args[..], &["bench", "--torus"][..]] {
        let ended = run_glint_env(command, &dir, &env, None, limit, &mut |_| false);
        ended_as(
            "cache-switch",
            &ended,
            2,
            &["GLINT_PIPELINE_CACHE=\"maybe\""],
            512,
        );
    }
    assert_eq!(listing(&dir), vec!["out.png", "scene.lua"]);
}

/// `glint kernels DIR` walks the folder without following a symbolic-link loop and
/// without reading FIFOs or devices named `.lua`; `--wgsl` of a module naga would
/// overflow its stack on is refused, naming its file and line.
#[test]
fn kernels_walks_folders_as_they_are_and_bounds_what_reaches_naga() {
    let (dir, _logs, _root) = case_dir("kernels-dir");
    let scenes = dir.join("scenes");
    std::fs::create_dir_all(scenes.join("sub")).unwrap();
    std::os::unix::fs::symlink("..", scenes.join("sub/loop")).unwrap();
    std::os::unix::fs::symlink(&scenes, scenes.join("self")).unwrap();
    mkfifo(&scenes.join("fifo.lua"));
    std::os::unix::fs::symlink("/dev/zero", scenes.join("zero.lua")).unwrap();
    let args = ["kernels", "scenes", "--family", "NAVI21", "--wave", "64"];
    let limit = Duration::from_secs(30);
    let ended = run_glint_env(&args, &dir, &[], None, limit, &mut |_| false);
    // Nothing but links and special files: no scene scripts under it.
    ended_as(
        "kernels-dir",
        &ended,
        2,
        &["no scene scripts under it"],
        512,
    );
    let terms = vec!["x"; 20_000].join(" + ");
    let module = format!(
        "@compute @workgroup_size(1)\nfn main() {{\n  var x: f32 = 1.0;\n  let y = {terms};\n}}\n"
    );
    std::fs::write(dir.join("sum.wgsl"), module).unwrap();
    let nested = format!(
        "fn f() -> f32 {{ return {}1.0{}; }}\n",
        "(".repeat(5000),
        ")".repeat(5000)
    );
    std::fs::write(dir.join("nested.wgsl"), nested).unwrap();
    for (file, needle) in [
        ("sum.wgsl", "sum.wgsl:4: a statement with more than"),
        ("nested.wgsl", "nested.wgsl:1: brackets nest deeper"),
    ] {
        let args = [
            "kernels", "--wgsl", file, "--family", "NAVI21", "--wave", "64",
        ];
        let ended = run_glint_env(&args, &dir, &[], None, limit, &mut |_| false);
        ended_as(file, &ended, 2, &[needle], 512);
    }
    mkfifo(&dir.join("fifo.wgsl"));
    let args = ["kernels", "--wgsl", "fifo.wgsl", "--family", "NAVI21"];
    let ended = run_glint_env(&args, &dir, &[], None, limit, &mut |_| false);
    ended_as(
        "fifo.wgsl",
        &ended,
        2,
        &["fifo.wgsl", "not a regular file"],
        512,
    );
}

/// `--prelude ~/dialect.lua` runs the prelude (which may read its own folder's
/// modules) but gives a downloaded scene nothing of the home folder.
#[test]
fn a_prelude_in_the_home_folder_does_not_open_it_to_the_scene() {
    let (dir, _logs, _root) = case_dir("prelude-home");
    let home = dir.join("home");
    let downloads = home.join("downloads");
    std::fs::create_dir_all(&downloads).unwrap();
    std::fs::write(home.join("dialect.lua"), "require('helper')\n").unwrap();
    std::fs::write(home.join("helper.lua"), "helper_ran = true\n").unwrap();
    std::fs::write(
        home.join("secret.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    let scene = "assert(helper_ran)\ngr.mesh('m', '../secret.obj')\n";
    std::fs::write(downloads.join("scene.lua"), scene).unwrap();
    let prelude = home.join("dialect.lua");
    let args = [
        "render",
        "scene.lua",
        "--backend",
        "cpu",
        "--prelude",
        prelude.to_str().unwrap(),
    ];
    let env = [("HOME", home.as_os_str())];
    let ended = run_glint_env(
        &args,
        &downloads,
        &env,
        None,
        Duration::from_secs(20),
        &mut |_| false,
    );
    ended_as(
        "prelude-home",
        &ended,
        3,
        &["scene.lua:2:", "secret.obj", "outside the folders"],
        BUDGET_MIB + OVERHEAD_MIB,
    );
    // A prelude beside the scene still opens its folder (the dialects' layout).
    std::fs::copy(home.join("secret.obj"), downloads.join("mine.obj")).unwrap();
    std::fs::write(downloads.join("scene.lua"), "gr.mesh('m', 'mine.obj')\n").unwrap();
    let ended = run_glint_env(
        &args,
        &downloads,
        &env,
        None,
        Duration::from_secs(20),
        &mut |_| false,
    );
    ended_as(
        "prelude-home-own",
        &ended,
        0,
        &["never called gr.render"],
        BUDGET_MIB + OVERHEAD_MIB,
    );
}

/// `glint bench` flags that would panic or allocate without bound are usage errors.
#[test]
fn bench_flags_out_of_range_are_usage_errors() {
    let (dir, _logs, _root) = case_dir("bench-flags");
    for (flag, value) in [
        ("--gpu-budget", "nan"),
        ("--gpu-budget", "inf"),
        ("--gpu-budget", "-5"),
        ("--gpu-budget", "0"),
        ("--max-triangles", "18446744073709551615"),
        ("--max-triangles", "0"),
        ("--rays", "0"),
    ] {
        let value = format!("{flag}={value}");
        let args = ["bench", "--sweep", "--quick", "--cpu-only", &value];
        let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(20), &mut |_| {
            false
        });
        ended_as(&value, &ended, 2, &[flag], 512);
    }
    assert!(listing(&dir).is_empty());
}

/// A file name that holds a newline or a terminal escape is printed escaped: it cannot
/// forge a status line or recolour the terminal.
#[test]
fn printed_names_escape_control_characters() {
    let (dir, _logs, _root) = case_dir("control-names");
    std::fs::write(dir.join("scene.lua"), SMALL_RENDER).unwrap();
    let name = "a\nglint: error: forged\x1b[31m.png";
    let args = ["render", "scene.lua", "--backend", "cpu", "-o", name];
    let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(20), &mut |_| {
        false
    });
    ended_as(
        "control-names",
        &ended,
        0,
        &["a\\nglint: error: forged\\u{1b}[31m.png"],
        512,
    );
    assert!(!ended.stderr.contains('\x1b'), "{:?}", ended.stderr);
    assert!(
        !ended.stderr.lines().any(|l| l.starts_with("glint: error")),
        "{:?}",
        ended.stderr
    );
}

/// A script nesting deeper than Lua's parser follows names its file and line (Lua says
/// a bare "C stack overflow"), and a path too long to show whole keeps the reason.
#[test]
fn parse_overflows_and_long_paths_say_where_and_why() {
    for (tag, line2) in [
        (
            "nest-parens",
            format!("x = {}1{}", "(".repeat(300), ")".repeat(300)),
        ),
        (
            "nest-tables",
            format!("x = {}{}", "{".repeat(300), "}".repeat(300)),
        ),
        ("nest-concat", format!("x = 1{}", " .. 1".repeat(400))),
    ] {
        let scene = format!("x = 0\n{line2}\n");
        check(Case::new(
            tag,
            &scene,
            3,
            &["scene.lua:2: the script nests too deeply"],
        ));
    }
    let (dir, _logs, _root) = case_dir("long-path");
    let long = format!("{}/scene.lua", vec!["d".repeat(200); 21].join("/"));
    let args = ["render", long.as_str(), "--backend", "cpu"];
    let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(20), &mut |_| {
        false
    });
    assert_ne!(ended.code, Some(0), "{}", ended.stderr);
    assert!(!ended.stderr.contains("panicked"), "{}", ended.stderr);
    assert!(ended.stderr.contains("d/scene.lua': "), "{}", ended.stderr);
    assert!(
        ended.stderr.contains("File name too long"),
        "{}",
        ended.stderr
    );
}

/// File names from Lua with bytes that are not UTF-8 are refused naming the argument,
/// never mangled into another name.
#[test]
fn file_names_from_lua_that_are_not_utf8_are_refused_not_mangled() {
    for (tag, scene) in [
        ("mesh-bytes", "gr.mesh('m', 'a\\255.obj')\n"),
        (
            "texture-bytes",
            "gr.material('m'):set_diffuse('t\\255.png')\n",
        ),
        ("require-bytes", "require('m\\255')\n"),
        ("readobj-bytes", "readobj('a\\255.obj')\n"),
    ] {
        check(Case::new(
            tag,
            scene,
            3,
            &["scene.lua:1:", "a file name in UTF-8"],
        ));
    }
}

// ---- Round three: what was left ----
// The last review's open points: budgets that name their flag, a user's WGSL naga refuses
// as a usage error, names that are not UTF-8 on the farm's derived names, and every path
// and user string escaped before it reaches the terminal.

/// `glint assemble` whose tiles' files alone pass `--memory-limit` names the flag (the
/// message used to say only "over the limit of N bytes", as if the tile were too big).
#[test]
fn assemble_past_its_budget_by_the_tiles_files_names_the_memory_limit() {
    let (dir, _logs, _root) = case_dir("assemble-files-budget");
    // Sparse: its size is what is checked, before a byte of it is read.
    let tile = std::fs::File::create(dir.join("big-tile-0-of-1.png")).unwrap();
    tile.set_len(20 << 20).unwrap();
    let args = [
        "assemble",
        "-o",
        "out.png",
        "big-tile-0-of-1.png",
        "--memory-limit",
        "16",
    ];
    let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(20), &mut |_| {
        false
    });
    ended_as(
        "assemble-files-budget",
        &ended,
        2,
        &[
            "big-tile-0-of-1.png",
            "memory limit of 16 MiB",
            "--memory-limit MIB",
        ],
        512,
    );
    assert_eq!(listing(&dir), vec!["big-tile-0-of-1.png"]);
}

/// `glint kernels --wgsl FILE` of a module naga refuses (an unknown name, a syntax
/// error) is a bad argument (exit code 2, naming the file and naga's line), found before
/// any device opens; it used to be exit code 5, "no Vulkan or a scene that fails".
#[test]
fn kernels_wgsl_that_naga_refuses_is_a_usage_error() {
    let (dir, _logs, _root) = case_dir("kernels-wgsl-invalid");
    std::fs::write(
        dir.join("unknown.wgsl"),
        "@compute @workgroup_size(1)\nfn main() { let x: f32 = undefined_thing; }\n",
    )
    .unwrap();
    std::fs::write(dir.join("broken.wgsl"), "fn f() -> f32 { return 1.0;\n").unwrap();
    for (file, needle) in [
        ("unknown.wgsl", "undefined_thing"),
        ("broken.wgsl", "expected"),
    ] {
        let args = [
            "kernels", "--wgsl", file, "--family", "NAVI21", "--wave", "64",
        ];
        let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(30), &mut |_| {
            false
        });
        ended_as(file, &ended, 2, &[file, needle, ":2:"], 512);
    }
}

/// Names glint derives from a name it was given (`--tile`'s `-tile-I-of-N`, a script's
/// later images `-2`, `--backend both`'s `-cpu`) keep the given name's bytes when they
/// are not UTF-8: `f\xff.png` gives `f\xff-tile-0-of-2.png`, never a `f\u{FFFD}…` file
/// nobody asked for; `assemble` reads them back and names them escaped.
#[test]
fn derived_names_keep_bytes_that_are_not_utf8() {
    use std::ffi::{OsStr, OsString};
    use std::os::unix::ffi::{OsStrExt, OsStringExt};
    let (dir, _logs, _root) = case_dir("non-utf8-farm");
    std::fs::write(dir.join("scene.lua"), SMALL_RENDER).unwrap();
    let name = |rest: &str| OsString::from_vec([b"f\xff".as_slice(), rest.as_bytes()].concat());
    for tile in ["0/2", "1/2"] {
        let args: Vec<&OsStr> = vec![
            OsStr::new("render"),
            OsStr::new("scene.lua"),
            OsStr::new("--backend"),
            OsStr::new("cpu"),
            OsStr::new("--tile"),
            OsStr::new(tile),
            OsStr::new("-o"),
        ];
        let out = name(".png");
        let args: Vec<&OsStr> = args.into_iter().chain([out.as_os_str()]).collect();
        let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(20), &mut |_| {
            false
        });
        ended_as("non-utf8-tile", &ended, 0, &["wrote f\\xff-tile-"], 512);
    }
    let (t0, t1, all) = (
        name("-tile-0-of-2.png"),
        name("-tile-1-of-2.png"),
        name("-all.png"),
    );
    let args = [OsStr::new("assemble"), OsStr::new("-o"), &all, &t0, &t1];
    let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(20), &mut |_| {
        false
    });
    ended_as(
        "non-utf8-assemble",
        &ended,
        0,
        &["wrote f\\xff-all.png"],
        512,
    );
    let mut names: Vec<Vec<u8>> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().as_bytes().to_vec())
        .collect();
    names.sort();
    let expected: Vec<Vec<u8>> = [&all, &t0, &t1]
        .iter()
        .map(|n| n.as_bytes().to_vec())
        .chain([b"scene.lua".to_vec()])
        .collect();
    assert_eq!(names, expected, "derived names mangled");
}

/// A newline or a terminal escape in any name or string a message quotes — the scene's
/// own file name, a node's name, an axis, a module's name, a script's `error` text, a
/// tile's name — is printed escaped: one line per message, no escape byte on stderr.
#[test]
fn names_and_strings_in_messages_never_reach_the_terminal_raw() {
    const HOSTILE: &str = "\\nglint: error: forged\\27[31m";
    let scenes = [
        ("scene-name", "error('x')".to_string()),
        ("error-text", format!("error('a{HOSTILE}')")),
        (
            "node-name",
            format!("n = gr.node('n{HOSTILE}') n:add_child(n)"),
        ),
        ("axis", format!("gr.node('r'):rotate('q{HOSTILE}', 3)")),
        ("module-name", format!("require('m{HOSTILE}')")),
        ("mesh-name", format!("gr.mesh('m', 'x{HOSTILE}.obj')")),
        ("syntax", format!("x = 'a{HOSTILE}")),
    ];
    let scene_file = "s\nglint: error: forged\x1b[31m.lua";
    for (tag, body) in scenes {
        let (dir, _logs, _root) = case_dir(&format!("raw-{tag}"));
        std::fs::write(dir.join(scene_file), format!("{body}\n")).unwrap();
        let args = ["render", scene_file, "--backend", "cpu"];
        let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(20), &mut |_| {
            false
        });
        ended_as(
            tag,
            &ended,
            3,
            &["s\\nglint: error: forged\\u{1b}[31m.lua:1:"],
            512,
        );
        assert!(!ended.stderr.contains('\x1b'), "{tag}: {:?}", ended.stderr);
        assert_eq!(ended.stderr.lines().count(), 1, "{tag}: {:?}", ended.stderr);
    }
    // A tile's name in `assemble`'s refusals.
    let (dir, _logs, _root) = case_dir("raw-tile-name");
    let tile = "t\nglint: wrote forged\x1b[31m-tile-0-of-1.png";
    std::fs::write(dir.join(tile), b"not a tile").unwrap();
    let args = ["assemble", "-o", "out.png", tile];
    let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(20), &mut |_| {
        false
    });
    ended_as(
        "raw-tile-name",
        &ended,
        2,
        &["t\\nglint: wrote forged\\u{1b}[31m"],
        512,
    );
    assert!(!ended.stderr.contains('\x1b'), "{:?}", ended.stderr);
    assert_eq!(ended.stderr.lines().count(), 1, "{:?}", ended.stderr);
}

/// The source rule that keeps the test above true for messages it does not drive: no
/// library or binary code prints a path with `Path::display` (which passes newlines and
/// escapes through) or names a `PathBuf` field in a `thiserror` message; every path a
/// message shows goes through `glint::display_path::shown`.
#[test]
fn every_printed_path_goes_through_display_path() {
    let mut offences = Vec::new();
    let mut stack = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("src")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let text = std::fs::read_to_string(&path).unwrap();
                // Unit tests (each file's last module) may print as they like.
                let code = text.split("#[cfg(test)]").next().unwrap();
                offences.extend(
                    raw_path_prints(code)
                        .into_iter()
                        .map(|(line, what)| format!("{}:{line}: {what}", path.display())),
                );
            }
        }
    }
    assert!(
        offences.is_empty(),
        "paths printed raw:\n{}",
        offences.join("\n")
    );
}

/// The lines of `code` that print a path raw: `.display()`, and `{field}` in an
/// `#[error(…)]` message of a variant whose `field` is a `PathBuf` or `&Path`.
fn raw_path_prints(code: &str) -> Vec<(usize, String)> {
    let lines: Vec<&str> = code.lines().collect();
    let mut found = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        if line.contains(".display()") && !line.trim_start().starts_with("//") {
            found.push((i + 1, "Path::display".to_string()));
        }
        if !line.trim_start().starts_with("#[error(") {
            continue;
        }
        // The attribute (it may span lines), then the variant's fields up to its end.
        let mut attribute = String::new();
        let mut j = i;
        while j < lines.len() {
            attribute.push_str(lines[j]);
            j += 1;
            if lines[j - 1].trim_end().ends_with(")]") {
                break;
            }
        }
        while j < lines.len() && !lines[j].trim_start().starts_with("#[error(") {
            let field = lines[j].trim();
            for ty in [": PathBuf", ": &Path", ": &'a Path"] {
                if let Some(name) = field.split(ty).next().filter(|_| field.contains(ty)) {
                    let name = name.rsplit(['{', ' ']).next().unwrap_or(name);
                    if attribute.contains(&format!("{{{name}}}"))
                        || attribute.contains(&format!("{{{name}:"))
                    {
                        found.push((i + 1, format!("thiserror field `{name}`")));
                    }
                }
            }
            if field.starts_with('}') || field.ends_with("},") || field.ends_with("),") {
                break;
            }
            j += 1;
        }
    }
    found
}

/// A module or a prelude nesting deeper than Lua's parser follows names its own file and
/// line, as the scene does (a module said only the `require` line, a prelude nothing but
/// "C stack overflow").
#[test]
fn parse_overflows_in_modules_and_preludes_name_their_file_and_line() {
    let deep = format!("x = 0\n\nx = {}1{}\n", "(".repeat(300), ")".repeat(300));
    for (tag, extra) in [
        ("module", &[][..]),
        ("prelude", &["--prelude", "deep.lua"][..]),
    ] {
        let scene = if tag == "module" {
            "x = 1\nrequire('deep')\n"
        } else {
            "x = 1\n"
        };
        check(
            Case::new(tag, scene, 3, &["deep.lua:3: the script nests too deeply"])
                .file("deep.lua", deep.as_bytes())
                .args(extra),
        );
    }
}

/// A dangling symbolic link at an output's name (`-o`, a `--tile`'s name, `assemble -o`,
/// `diff --heatmap`) is replaced by the image, never "File exists (os error 17)", and
/// the link's target is not created.
#[test]
fn a_dangling_link_at_an_output_name_is_replaced() {
    let (dir, _logs, _root) = case_dir("dangling-outputs");
    std::fs::write(dir.join("scene.lua"), SMALL_RENDER).unwrap();
    let names = ["o.png", "t-tile-0-of-1.png", "all.png", "heat.png"];
    for name in names {
        std::os::unix::fs::symlink(format!("nowhere/{name}"), dir.join(name)).unwrap();
    }
    let runs: [&[&str]; 4] = [
        &["render", "scene.lua", "--backend", "cpu", "-o", "o.png"],
        &[
            "render",
            "scene.lua",
            "--backend",
            "cpu",
            "--tile",
            "0/1",
            "-o",
            "t.png",
        ],
        &["assemble", "-o", "all.png", "t-tile-0-of-1.png"],
        &["diff", "o.png", "all.png", "--heatmap", "heat.png"],
    ];
    for args in runs {
        let ended = run_glint_env(args, &dir, &[], None, Duration::from_secs(20), &mut |_| {
            false
        });
        ended_as(args[0], &ended, 0, &[], 512);
        assert!(!ended.stderr.contains("os error 17"), "{}", ended.stderr);
    }
    for name in names {
        let meta = std::fs::symlink_metadata(dir.join(name)).unwrap();
        assert!(meta.is_file(), "{name} is still a link");
    }
    assert!(!dir.join("nowhere").exists());
}

/// How many folders of [`DEEP_NAME`] a deep case nests: 22 of 201 bytes, 4 422 bytes
/// below the case's folder, past PATH_MAX (4 096) whatever the scratch folder's path.
const DEEP_LEVELS: usize = 22;

fn deep_name() -> String {
    "d".repeat(200)
}

/// A shell line that creates (`mkdir -p`) and enters the deep folder one level at a time
/// (each `cd` short, the whole path past PATH_MAX), failing with 99 if it cannot.
fn descend_deep() -> String {
    format!(
        "for i in $(seq {DEEP_LEVELS}); do mkdir -p {0} && cd -P {0} || exit 99; done",
        deep_name()
    )
}

/// Runs `script` in the deep folder below `dir` (entered as [`descend_deep`] does) and
/// returns its standard output: how the test writes and reads files there, independently
/// of glint's own folder walk.
fn in_deep(dir: &Path, script: &str) -> Vec<u8> {
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!("{}\n{script}", descend_deep()))
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(out.status.success(), "{script}: {:?}", out);
    out.stdout
}

/// A textured square: a mesh file with texture coordinates and a PNG, both read by name.
const DEEP_OBJ: &str =
    "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";

/// A scene reading `mesh` and `texture` and writing `out.png`.
fn deep_scene(mesh: &str, texture: &str) -> String {
    format!(
        "root = gr.node('root')\nlocal m = gr.mesh('m', '{mesh}')\nlocal mat = gr.material({{1, 1, 1}}, {{0, 0, 0}}, 1)\nmat:set_diffuse('{texture}')\nm:set_material(mat)\nroot:add_child(m)\ngr.render(root, 'out.png', 16, 16, {{0,0,3}}, {{0,0,-1}}, {{0,1,0}}, 50, {{0.2,0.2,0.2}}, {{gr.light({{0,0,5}}, {{1,1,1}}, {{1,0,0}})}}, {{aa='none'}})\n"
    )
}

/// A PNG whose texels differ (so that a wrong texture shows in the image).
fn gradient_png() -> Vec<u8> {
    let mut bytes = Vec::new();
    image::RgbImage::from_fn(4, 4, |x, y| image::Rgb([60 * x as u8, 60 * y as u8, 90]))
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    bytes
}

/// The image the deep scenes must make: the same scene rendered in a shallow folder.
fn shallow_reference(root: &Path) -> Vec<u8> {
    let dir = root.join("shallow");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("scene.lua"), deep_scene("m.obj", "t.png")).unwrap();
    std::fs::write(dir.join("m.obj"), DEEP_OBJ).unwrap();
    std::fs::write(dir.join("t.png"), gradient_png()).unwrap();
    let args = ["render", "scene.lua", "--backend", "cpu"];
    let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(30), &mut |_| {
        false
    });
    ended_as("shallow", &ended, 0, &[], BUDGET_MIB + OVERHEAD_MIB);
    std::fs::read(dir.join("out.png")).unwrap()
}

/// Runs `script` in `dir` (after `prefix`, a shell line) with the scene, the mesh and
/// the texture given to it as `$1`, `$2` and its standard input.
fn write_scene_files(dir: &Path, prefix: &str, script: &str, scene: &str) {
    use std::io::Write;
    let mut writer = Command::new("sh")
        .arg("-c")
        .arg(format!("{prefix}\n{script}"))
        .arg("sh")
        .arg(scene)
        .arg(DEEP_OBJ)
        .current_dir(dir)
        .stdin(Stdio::piped())
        .spawn()
        .unwrap();
    writer
        .stdin
        .take()
        .unwrap()
        .write_all(&gradient_png())
        .unwrap();
    assert!(writer.wait().unwrap().success(), "{script}");
}

/// Started in a folder whose absolute path is over PATH_MAX (22 folders of 200 bytes),
/// a scene reads its mesh and its texture beside it and writes its image, its tiles and
/// `assemble`'s output there, each the image the same scene makes in a shallow folder,
/// with nothing else left behind: the read and write rules walk folder handles, never
/// absolute paths.
#[test]
fn a_scene_past_path_max_reads_its_mesh_and_texture_and_writes_beside_it() {
    let (dir, _logs, root) = case_dir("deep-start");
    let reference = shallow_reference(&root);
    write_scene_files(
        &dir,
        &descend_deep(),
        "printf '%s' \"$1\" > scene.lua && printf '%s' \"$2\" > m.obj && cat > t.png",
        &deep_scene("m.obj", "t.png"),
    );
    let runs: [&[&str]; 4] = [
        &["render", "scene.lua", "--backend", "cpu"],
        &["render", "scene.lua", "--backend", "cpu", "--tile", "0/2"],
        &["render", "scene.lua", "--backend", "cpu", "--tile", "1/2"],
        &[
            "assemble",
            "-o",
            "all.png",
            "out-tile-0-of-2.png",
            "out-tile-1-of-2.png",
        ],
    ];
    for args in runs {
        let ended = run_glint_env(
            args,
            &dir,
            &[],
            Some(&descend_deep()),
            Duration::from_secs(30),
            &mut |_| false,
        );
        ended_as(&args.join(" "), &ended, 0, &[], BUDGET_MIB + OVERHEAD_MIB);
    }
    let listing = String::from_utf8(in_deep(&dir, "ls -A")).unwrap();
    assert_eq!(
        listing.lines().collect::<Vec<_>>(),
        [
            "all.png",
            "m.obj",
            "out-tile-0-of-2.png",
            "out-tile-1-of-2.png",
            "out.png",
            "scene.lua",
            "t.png"
        ],
        "files left behind or missing"
    );
    assert_eq!(in_deep(&dir, "cat out.png"), reference, "the render");
    let assembled = image::load_from_memory(&in_deep(&dir, "cat all.png")).unwrap();
    let whole = image::load_from_memory(&reference).unwrap();
    assert_eq!(assembled.to_rgb8(), whole.to_rgb8(), "the assembled tiles");
}

/// Started in a shallow folder, a scene named by a relative path (4 090 bytes: the system
/// opens it) whose absolute path is past PATH_MAX reads its mesh and its texture, the
/// texture by a name whose path from the start folder is itself past PATH_MAX
/// (`tex/../tex/../tex/t.png`, which only a walk from folder handles opens).
#[test]
fn a_scene_whose_absolute_path_is_past_path_max_reads_beside_it() {
    let (dir, _logs, root) = case_dir("deep-relative");
    let reference = shallow_reference(&root);
    let mut relative = vec![deep_name(); 20];
    relative.push("e".repeat(60));
    let relative = relative.join("/");
    let texture = "tex/../tex/../tex/t.png";
    let scene = format!("{relative}/scene.lua");
    assert!(scene.len() < libc::PATH_MAX as usize);
    assert!(dir.join(&scene).as_os_str().len() > libc::PATH_MAX as usize);
    assert!(relative.len() + 1 + texture.len() > libc::PATH_MAX as usize);
    // (Each name the shell opens is under PATH_MAX; `cd` there would not be.)
    write_scene_files(
        &dir,
        &format!("mkdir -p {relative}/tex || exit 99"),
        &format!(
            "printf '%s' \"$1\" > {relative}/scene.lua && printf '%s' \"$2\" > {relative}/m.obj && cat > {relative}/tex/t.png"
        ),
        &deep_scene("m.obj", texture),
    );
    let args = ["render", scene.as_str(), "--backend", "cpu"];
    let ended = run_glint_env(&args, &dir, &[], None, Duration::from_secs(30), &mut |_| {
        false
    });
    ended_as("deep-relative", &ended, 0, &[], BUDGET_MIB + OVERHEAD_MIB);
    assert_eq!(std::fs::read(dir.join("out.png")).unwrap(), reference);
}

/// In a folder past PATH_MAX the sandbox holds as anywhere: a symbolic link to a file
/// outside, `..` out of it, and an output through a link to a folder outside are
/// refused, naming the flag; nothing is written outside.
#[test]
fn a_folder_past_path_max_still_refuses_links_and_dots_out_of_it() {
    let (dir, _logs, _root) = case_dir("deep-escape");
    std::fs::write(dir.join("secret.obj"), DEEP_OBJ).unwrap();
    std::fs::create_dir(dir.join("elsewhere")).unwrap();
    let up = vec![".."; DEEP_LEVELS].join("/");
    let outside = dir.display().to_string();
    for (tag, scene, needle) in [
        (
            "deep-link-out",
            deep_scene("link.obj", "t.png"),
            "link.obj': it is outside the folders this scene may read",
        ),
        (
            "deep-dots-out",
            deep_scene(&format!("{up}/secret.obj"), "t.png"),
            "secret.obj': it is outside the folders this scene may read",
        ),
        (
            "deep-write-out",
            deep_scene("m.obj", "t.png").replace("'out.png'", "'away/out.png'"),
            "cannot write 'away/out.png': it is outside the folders this scene may write",
        ),
    ] {
        write_scene_files(
            &dir,
            &descend_deep(),
            &format!(
                "printf '%s' \"$1\" > scene.lua && printf '%s' \"$2\" > m.obj && cat > t.png && ln -sfn '{outside}/secret.obj' link.obj && ln -sfn '{outside}/elsewhere' away"
            ),
            &scene,
        );
        let args = ["render", "scene.lua", "--backend", "cpu"];
        let ended = run_glint_env(
            &args,
            &dir,
            &[],
            Some(&descend_deep()),
            Duration::from_secs(30),
            &mut |_| false,
        );
        ended_as(
            tag,
            &ended,
            3,
            &[needle, "--allow-"],
            BUDGET_MIB + OVERHEAD_MIB,
        );
        assert!(listing(&dir.join("elsewhere")).is_empty(), "{tag}");
        let left = String::from_utf8(in_deep(&dir, "ls -A")).unwrap();
        assert_eq!(
            left.lines().collect::<Vec<_>>(),
            ["away", "link.obj", "m.obj", "scene.lua", "t.png"],
            "{tag}"
        );
    }
}
