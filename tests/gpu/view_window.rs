//! The harness of `glint view`'s window tests: a private Xvfb server per test (a free
//! display number chosen by Xvfb itself, `-displayfd`; never reset, `-noreset`), a `glint
//! view` process on it whose stdout and stderr lines are collected as they come, input
//! through xdotool, the window's pixels through xwd and ImageMagick, and the window
//! manager's close (WM_DELETE_WINDOW) sent as a client message with x11rb, since Xvfb
//! runs no window manager. Every wait is bounded, and dropping a handle kills its process (no orphans).
//! A wait for the view's window ends as soon as the view has ended, and its failure says
//! how the view ended (or that it still runs), what it printed, and which windows the
//! display has.

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// What the window tests need installed (Debian/Ubuntu), named in their failures.
pub const WINDOW_INSTALL_HINT: &str = "apt-get install -y xvfb xdotool x11-apps imagemagick";

/// Longest wait for anything a test waits for (a window, a line, an exit).
pub const WAIT: Duration = Duration::from_secs(60);

fn tool_missing(tool: &str, e: std::io::Error) -> ! {
    panic!("cannot run {tool} ({e}): the window tests need it: `{WINDOW_INSTALL_HINT}`")
}

/// A private X server, killed on drop.
pub struct Xvfb {
    child: Child,
    pub display: String,
}

impl Xvfb {
    pub fn start() -> Xvfb {
        let mut child = Command::new("Xvfb")
            .args([
                "-displayfd",
                "1",
                "-screen",
                "0",
                "800x600x24",
                "-nolisten",
                "tcp",
                // By default an X server resets when its last client leaves, and refuses a
                // client that connects during the reset. The harness's own short-lived
                // clients (each `xdotool search` while it waits for the window) were often
                // the last to leave just before `glint view` connected, which then failed
                // with "Failed to open connection to X server" (docs/testing.md).
                "-noreset",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap_or_else(|e| tool_missing("Xvfb", e));
        let stdout = child.stdout.take().expect("piped");
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = BufReader::new(stdout).read_line(&mut line);
            let _ = tx.send(line);
        });
        let line = match rx.recv_timeout(Duration::from_secs(20)) {
            Ok(line) if !line.trim().is_empty() => line,
            _ => {
                let _ = child.kill();
                let _ = child.wait();
                panic!("Xvfb did not report a display within 20 s")
            }
        };
        Xvfb {
            child,
            display: format!(":{}", line.trim()),
        }
    }

    /// Runs an X client tool on this display, returning its stdout (fails the test on an
    /// error, naming the tool).
    pub fn tool(&self, tool: &str, args: &[&str]) -> Vec<u8> {
        let mut child = Command::new(tool)
            .args(args)
            .env("DISPLAY", &self.display)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| tool_missing(tool, e));
        let mut out = Vec::new();
        let mut stdout = child.stdout.take().expect("piped");
        let reader = std::thread::spawn(move || {
            let _ = stdout.read_to_end(&mut out);
            out
        });
        let status = wait_bounded(&mut child, Duration::from_secs(30))
            .unwrap_or_else(|| panic!("{tool} {args:?} did not finish within 30 s"));
        let out = reader.join().unwrap_or_default();
        assert!(status.success(), "{tool} {args:?} failed: {status}");
        out
    }

    /// The ids of the windows whose name contains `name` (xdotool fails when there are
    /// none: that is an empty list here).
    pub fn windows(&self, name: &str) -> Vec<String> {
        let out = Command::new("xdotool")
            .args(["search", "--name", name])
            .env("DISPLAY", &self.display)
            .output()
            .unwrap_or_else(|e| tool_missing("xdotool", e));
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .map(|l| l.trim().to_string())
            .filter(|l| !l.is_empty())
            .collect()
    }

    /// The top-level windows on the display, each with its name and whether it is
    /// mapped, or why they cannot be listed: what a failure to find one shows. (x11rb,
    /// not a tool, so that it works wherever the tests' X connection does.)
    pub fn window_list(&self) -> String {
        use x11rb::connection::Connection;
        use x11rb::protocol::xproto::{AtomEnum, ConnectionExt};
        let Ok((conn, screen)) = x11rb::connect(Some(&self.display)) else {
            return format!("(cannot connect to {} to list them)", self.display);
        };
        let root = conn.setup().roots[screen].root;
        let Some(tree) = conn.query_tree(root).ok().and_then(|c| c.reply().ok()) else {
            return "(cannot query the window tree)".to_string();
        };
        let windows: Vec<String> = tree
            .children
            .iter()
            .map(|&w| {
                let name = conn
                    .get_property(false, w, AtomEnum::WM_NAME, AtomEnum::ANY, 0, 256)
                    .ok()
                    .and_then(|c| c.reply().ok())
                    .map(|r| String::from_utf8_lossy(&r.value).into_owned())
                    .unwrap_or_default();
                let state = conn
                    .get_window_attributes(w)
                    .ok()
                    .and_then(|c| c.reply().ok())
                    .map(|a| format!("{:?}", a.map_state))
                    .unwrap_or_default();
                format!("{w} '{name}' {state}")
            })
            .collect();
        if windows.is_empty() {
            "none".to_string()
        } else {
            windows.join(", ")
        }
    }

    pub fn has_window(&self, name: &str) -> bool {
        !self.windows(name).is_empty()
    }

    /// Presses `key` in `window`: focuses it, then types through XTEST (winit reads the
    /// keyboard through XInput2, which ignores the synthetic events `xdotool key
    /// --window` sends to a window without the focus).
    pub fn key(&self, window: &str, key: &str) {
        self.tool("xdotool", &["windowfocus", "--sync", window]);
        self.tool("xdotool", &["key", key]);
    }

    pub fn window_name(&self, window: &str) -> String {
        String::from_utf8_lossy(&self.tool("xdotool", &["getwindowname", window]))
            .trim()
            .to_string()
    }

    /// The window's pixels as shown (xwd, converted by ImageMagick), as RGB8.
    pub fn capture(&self, window: &str) -> image::RgbImage {
        let xwd = self.tool("xwd", &["-id", window, "-silent"]);
        let mut child = Command::new("convert")
            .args(["xwd:-", "png:-"])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| tool_missing("convert (ImageMagick)", e));
        let mut stdin = child.stdin.take().expect("piped");
        std::thread::spawn(move || {
            use std::io::Write;
            let _ = stdin.write_all(&xwd);
        });
        let out = child.wait_with_output().expect("convert runs");
        image::load_from_memory(&out.stdout)
            .expect("ImageMagick converts the xwd capture")
            .to_rgb8()
    }

    /// What a window manager sends when its close button is pressed: a WM_PROTOCOLS
    /// client message with WM_DELETE_WINDOW.
    pub fn close_as_window_manager(&self, window: &str) {
        use x11rb::protocol::xproto::{ClientMessageEvent, ConnectionExt, EventMask};
        let id: u32 = window.parse().expect("a window id");
        let (conn, _) = x11rb::connect(Some(&self.display)).expect("connect to Xvfb");
        let atom = |name: &[u8]| conn.intern_atom(false, name).unwrap().reply().unwrap().atom;
        let (protocols, delete) = (atom(b"WM_PROTOCOLS"), atom(b"WM_DELETE_WINDOW"));
        let event = ClientMessageEvent::new(32, id, protocols, [delete, 0, 0, 0, 0]);
        let sent = conn
            .send_event(false, id, EventMask::NO_EVENT, event)
            .unwrap();
        // Waits until the server has handled it (and says if it could not).
        sent.check().expect("the close message reaches the window");
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// `child`'s exit status, or None (after killing it) if it ran past `limit`.
pub fn wait_bounded(child: &mut Child, limit: Duration) -> Option<std::process::ExitStatus> {
    let deadline = Instant::now() + limit;
    loop {
        if let Ok(Some(status)) = child.try_wait() {
            return Some(status);
        }
        if Instant::now() >= deadline {
            let _ = child.kill();
            let _ = child.wait();
            return None;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A running `glint view`, its output lines collected; killed on drop.
pub struct View {
    child: Child,
    pub stdout: Arc<Mutex<Vec<String>>>,
    pub stderr: Arc<Mutex<Vec<String>>>,
    /// The threads collecting stdout and stderr.
    readers: [JoinHandle<()>; 2],
}

/// The lines `stream` gives, collected by a thread as they come, and that thread (done
/// once the stream has ended).
fn collect(stream: impl Read + Send + 'static) -> (Arc<Mutex<Vec<String>>>, JoinHandle<()>) {
    let lines = Arc::new(Mutex::new(Vec::new()));
    let sink = Arc::clone(&lines);
    let reader = std::thread::spawn(move || {
        for line in BufReader::new(stream).lines().map_while(Result::ok) {
            sink.lock().unwrap().push(line);
        }
    });
    (lines, reader)
}

impl View {
    /// `glint view ARGS` on `x`'s display, in folder `dir`.
    pub fn start(x: &Xvfb, dir: &Path, args: &[&str]) -> View {
        let mut child = Command::new(env!("CARGO_BIN_EXE_glint"))
            .arg("view")
            .args(args)
            .current_dir(dir)
            .env("DISPLAY", &x.display)
            .env_remove("WAYLAND_DISPLAY")
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("glint runs");
        let (stdout, out_reader) = collect(child.stdout.take().expect("piped"));
        let (stderr, err_reader) = collect(child.stderr.take().expect("piped"));
        View {
            child,
            stdout,
            stderr,
            readers: [out_reader, err_reader],
        }
    }

    /// Waits for a line of `stream` (from line `from` on) that contains `text`; returns
    /// its index and text.
    pub fn wait_line(
        &self,
        stream: &Arc<Mutex<Vec<String>>>,
        from: usize,
        text: &str,
        limit: Duration,
    ) -> (usize, String) {
        let deadline = Instant::now() + limit;
        loop {
            {
                let lines = stream.lock().unwrap();
                if let Some((i, l)) = lines
                    .iter()
                    .enumerate()
                    .skip(from)
                    .find(|(_, l)| l.contains(text))
                {
                    return (i, l.clone());
                }
            }
            assert!(
                Instant::now() < deadline,
                "no line with '{text}' within {limit:?}; stderr so far:\n{}",
                self.stderr.lock().unwrap().join("\n")
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    pub fn stdout_len(&self) -> usize {
        self.stdout.lock().unwrap().len()
    }

    /// Waits for this view's window, named like `name`, on `x` and returns its id. Fails
    /// as soon as the process has ended (a view that exits never opens its window) and
    /// when [`WAIT`] passes; either way the failure says whether the process still runs
    /// or how it ended, what it printed, and which windows the display has.
    pub fn window(&mut self, x: &Xvfb, name: &str) -> String {
        let started = Instant::now();
        loop {
            if let Some(id) = x.windows(name).into_iter().next() {
                // The view's start-up as the tests see it (shown with `--nocapture` or
                // beside a failure): the journal's measure of the window's delay.
                eprintln!(
                    "view_window: window '{name}' after {} ms",
                    started.elapsed().as_millis()
                );
                return id;
            }
            let ended = self.child.try_wait().ok().flatten();
            if ended.is_some() || started.elapsed() >= WAIT {
                let state = match ended {
                    Some(status) => format!("glint view ended ({status})"),
                    None => "glint view is still running".to_string(),
                };
                panic!(
                    "no window named like '{name}' after {:?}: {state}; the display's windows: {}\n{}",
                    started.elapsed(),
                    x.window_list(),
                    self.output()
                );
            }
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// What the process printed so far, for a failure's message.
    pub fn output(&mut self) -> String {
        // An ended process's last lines may still be in the pipes: waits (bounded: a
        // child it left running may hold them open) until the readers reach their end.
        if let Ok(Some(_)) = self.child.try_wait() {
            let deadline = Instant::now() + Duration::from_secs(5);
            while !self.readers.iter().all(JoinHandle::is_finished) && Instant::now() < deadline {
                std::thread::sleep(Duration::from_millis(20));
            }
        }
        format!(
            "--- glint view's stdout:\n{}\n--- its stderr:\n{}\n---",
            self.stdout.lock().unwrap().join("\n"),
            self.stderr.lock().unwrap().join("\n")
        )
    }

    /// Waits for the process to end (bounded), returning its status.
    pub fn wait_exit(&mut self, limit: Duration) -> Option<std::process::ExitStatus> {
        wait_bounded(&mut self.child, limit)
    }
}

impl Drop for View {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
