//! What the view reports: the window title (scene, samples per pixel, camera rays per
//! second, tracer and adapter, or the script's error) and one stderr line per event
//! worth timing — the first image, an image completed, a move's preview frame rate —
//! which are also how docs/view.md's figures were measured (`glint view: …` lines).

use std::time::{Duration, Instant};

/// Timings of the frames since the last restart and of the current move.
#[derive(Debug)]
pub struct Status {
    started: Instant,
    first_image: Option<Duration>,
    /// Full-resolution frames since the last restart: count and time.
    refine_frames: u32,
    refine_time: Duration,
    refine_rays: u64,
    /// The last full-resolution frame's time (chooses the preview's stride).
    last_full_frame: Option<Duration>,
    /// The move in progress: preview frames, their time, since when.
    move_frames: u32,
    move_since: Option<Instant>,
    /// When the move's last preview frame was done.
    move_last: Option<Instant>,
    move_stride: u32,
    /// Camera rays per second of the last frame.
    pub rate: f64,
}

impl Default for Status {
    fn default() -> Self {
        Status {
            started: Instant::now(),
            first_image: None,
            refine_frames: 0,
            refine_time: Duration::ZERO,
            refine_rays: 0,
            last_full_frame: None,
            move_frames: 0,
            move_since: None,
            move_last: None,
            move_stride: 1,
            rate: 0.0,
        }
    }
}

impl Status {
    pub fn full_frame_time(&self) -> Option<Duration> {
        self.last_full_frame
    }

    /// The image restarted at `stride`; `moving`: because the camera is moving (a move
    /// is reported when it ends even where its frames needed no preview stride: a small
    /// or fast image moves at full resolution).
    pub fn restarted(&mut self, stride: u32, moving: bool) {
        self.refine_frames = 0;
        self.refine_time = Duration::ZERO;
        self.refine_rays = 0;
        if moving && self.move_since.is_none() {
            self.move_since = Some(Instant::now());
            self.move_frames = 0;
        }
        self.move_stride = self.move_stride.max(stride);
    }

    /// A frame of `pixels` camera rays took `time` at `stride`.
    pub fn frame_done(&mut self, stride: u32, pixels: u64, time: Duration, complete: bool) {
        self.rate = pixels as f64 / time.as_secs_f64().max(1e-9);
        if self.first_image.is_none() {
            let t = self.started.elapsed();
            self.first_image = Some(t);
            eprintln!("glint view: first image after {} ms", t.as_millis());
        }
        if self.move_since.is_some() {
            self.move_frames += 1;
            self.move_last = Some(Instant::now());
        }
        if stride > 1 {
            return;
        }
        self.last_full_frame = Some(time);
        self.refine_frames += 1;
        self.refine_time += time;
        self.refine_rays += pixels;
        if complete {
            let secs = self.refine_time.as_secs_f64().max(1e-9);
            eprintln!(
                "glint view: image complete: {} samples a pixel in {:.3} s ({:.2} M samples/s)",
                self.refine_frames,
                secs,
                self.refine_rays as f64 / secs * 1e-6
            );
        }
    }

    /// The move ended: its preview frame rate (frames over the time from the move's
    /// start to its last frame).
    pub fn report_moving(&mut self) {
        // From the move's first restart to its last preview frame (the settling wait
        // after it is not the preview's).
        if let (Some(since), Some(last)) = (self.move_since.take(), self.move_last.take()) {
            let secs = last.duration_since(since).as_secs_f64();
            eprintln!(
                "glint view: moving: {} preview frames in {:.3} s ({:.1} frames/s, stride up to {})",
                self.move_frames,
                secs,
                f64::from(self.move_frames) / secs.max(1e-9),
                self.move_stride
            );
        }
        self.move_stride = 1;
    }
}

/// The window title: scene, samples a pixel, rays a second, tracer and adapter; or the
/// script's error (its first line), which stays until a run succeeds.
pub fn title(
    scene: &str,
    (spp, goal): (u32, u32),
    stride: u32,
    rate: f64,
    tracer: &str,
    adapter: &str,
    error: Option<&str>,
) -> String {
    if let Some(e) = error {
        let first = e.lines().next().unwrap_or(e);
        return format!("glint view — {scene} — ERROR: {first}");
    }
    let progress = if stride > 1 {
        format!("preview 1/{stride}")
    } else {
        format!("{spp}/{goal} spp")
    };
    format!(
        "glint view — {scene} — {progress} — {:.2} M rays/s — {tracer} tracer — {adapter}",
        rate * 1e-6
    )
}
