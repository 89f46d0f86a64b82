//! The script's wall-clock limit. The instruction hook cannot see time spent inside
//! Lua's C library (a pathological `string.find` pattern, `load` fed by an endless
//! reader) or in code Lua runs with hooks off: a watchdog thread measures the script's
//! own time (renders, which `gr.render` brackets with [`ScriptClock::pause`] and
//! [`ScriptClock::resume`], do not count). When the limit passes it raises a flag that
//! the instruction hook turns into an error; if the script is stuck where no hook runs
//! and `hard_exit` is set (the command line), it ends the process with exit code 3
//! after a short grace period, naming the script and the flag. No image is being
//! written then (renders pause the clock), so nothing is left behind.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Time the hook gets to stop the script after the limit, before the hard exit.
const GRACE: Duration = Duration::from_secs(2);

/// Exit code of a hard stop: a bad scene.
const EXIT_BAD_SCENE: i32 = 3;

struct Clock {
    /// Script time before the current run.
    spent: Duration,
    /// Start of the current run (None while a render runs).
    running_since: Option<Instant>,
    /// The script has finished: the watchdog stops.
    done: bool,
}

struct Shared {
    clock: Mutex<Clock>,
    wake: Condvar,
    expired: AtomicBool,
    /// The hook's message (with the script's file and line) once it has raised the
    /// limit, for the hard stop to repeat when a `pcall` keeps catching it.
    message: Mutex<Option<String>>,
}

/// The shared clock; cheap to clone into the script state.
#[derive(Clone)]
pub(crate) struct ScriptClock(Arc<Shared>);

impl ScriptClock {
    /// Whether the script has used up its time.
    pub fn expired(&self) -> bool {
        self.0.expired.load(Ordering::Relaxed)
    }

    /// Script time used so far (renders not counted).
    pub fn used(&self) -> Duration {
        let c = lock(&self.0.clock);
        c.spent + c.running_since.map_or(Duration::ZERO, |t| t.elapsed())
    }

    /// Records the hook's time-limit message (the first one is kept).
    pub fn note(&self, message: &str) {
        let mut m = self.0.message.lock().unwrap_or_else(|p| p.into_inner());
        m.get_or_insert_with(|| message.to_string());
    }

    /// Stops counting (a render starts).
    pub fn pause(&self) {
        let mut c = lock(&self.0.clock);
        if let Some(t) = c.running_since.take() {
            c.spent += t.elapsed();
        }
        self.0.wake.notify_all();
    }

    /// Counts again (a render ended).
    pub fn resume(&self) {
        let mut c = lock(&self.0.clock);
        if c.running_since.is_none() {
            c.running_since = Some(Instant::now());
        }
        self.0.wake.notify_all();
    }
}

fn lock(m: &Mutex<Clock>) -> std::sync::MutexGuard<'_, Clock> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// The running watchdog; dropping it stops the thread.
pub(crate) struct Watchdog {
    clock: ScriptClock,
    thread: Option<JoinHandle<()>>,
}

impl Watchdog {
    /// Starts timing the script `chunk_name` against `limit`.
    pub fn start(limit: Duration, hard_exit: bool, chunk_name: &str) -> Watchdog {
        let shared = Arc::new(Shared {
            clock: Mutex::new(Clock {
                spent: Duration::ZERO,
                running_since: Some(Instant::now()),
                done: false,
            }),
            wake: Condvar::new(),
            expired: AtomicBool::new(false),
            message: Mutex::new(None),
        });
        let clock = ScriptClock(shared.clone());
        let name = chunk_name.to_string();
        let thread = std::thread::Builder::new()
            .name("glint-script-watchdog".into())
            .spawn(move || watch(&shared, limit, hard_exit, &name))
            .ok();
        Watchdog { clock, thread }
    }

    pub fn clock(&self) -> ScriptClock {
        self.clock.clone()
    }
}

impl Drop for Watchdog {
    fn drop(&mut self) {
        lock(&self.clock.0.clock).done = true;
        self.clock.0.wake.notify_all();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// The watchdog thread: sleeps until the script's time could run out, flags it, and
/// (with `hard_exit`) ends the process when the script does not stop within [`GRACE`].
fn watch(shared: &Shared, limit: Duration, hard_exit: bool, name: &str) {
    let mut clock = lock(&shared.clock);
    let mut expired_at: Option<Instant> = None;
    loop {
        if clock.done {
            return;
        }
        let Some(since) = clock.running_since else {
            // A render is running: wait for it to end.
            clock = shared.wake.wait(clock).unwrap_or_else(|p| p.into_inner());
            continue;
        };
        let used = clock.spent + since.elapsed();
        if used < limit {
            let wait = limit - used;
            clock = shared
                .wake
                .wait_timeout(clock, wait)
                .unwrap_or_else(|p| p.into_inner())
                .0;
            continue;
        }
        shared.expired.store(true, Ordering::Relaxed);
        let first = *expired_at.get_or_insert_with(Instant::now);
        if hard_exit && first.elapsed() >= GRACE {
            let noted = shared
                .message
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .clone();
            match noted {
                // The hook raised it, but the script keeps catching it.
                Some(message) => eprintln!(
                    "glint: error: {}",
                    crate::display_path::for_terminal(&super::errors::cap_message(&message))
                ),
                None => eprintln!(
                    "glint: error: {name}: script time limit of {} s exceeded (the script is stuck where it cannot be interrupted, e.g. in a string pattern or a load reader); --script-timeout SECONDS raises the limit",
                    limit.as_secs_f64()
                ),
            }
            std::process::exit(EXIT_BAD_SCENE);
        }
        let wait = GRACE
            .saturating_sub(first.elapsed())
            .max(Duration::from_millis(10));
        clock = shared
            .wake
            .wait_timeout(clock, wait)
            .unwrap_or_else(|p| p.into_inner())
            .0;
    }
}
