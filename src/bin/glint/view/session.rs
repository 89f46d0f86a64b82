//! One open view: the scene, the camera, the tracer refining it and the sums it adds
//! to, and what each frame, move, reload and save does. The window and its events are
//! `view/app.rs`'s; this holds the state they change.

use super::camera::{Bounds, ViewCamera};
use super::config::ViewConfig;
use super::load::{frames_to_converge, load_scene, LoadedScene};
use super::present::{Presented, Presenter};
use super::status::Status;
use glint::film::Film;
use glint::gpu::view::progressive::{Progressive, SumBuffer};
use glint::gpu::{GpuContext, GpuError};
use glint::pack::{PackedGlobals, SceneFeatures};
use glint::tracer::path::camera_media::fill_camera_media;
use glint::tracer::sampling::progressive::{accumulate_sample, film_of_sums};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use winit::window::Window;

/// How long after the last camera move the view keeps previewing before it refines.
pub const SETTLE: Duration = Duration::from_millis(150);
/// A preview frame aims at this many frames per second (its resolution follows).
const PREVIEW_FPS: f64 = 30.0;
/// Coarsest preview: one traced pixel per this many pixels across and down.
const MAX_PREVIEW_STRIDE: u32 = 8;

/// Which tracer refines the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TracerKind {
    Gpu,
    Cpu,
}

impl TracerKind {
    pub fn name(self) -> &'static str {
        match self {
            TracerKind::Gpu => "GPU",
            TracerKind::Cpu => "CPU",
        }
    }
}

/// The view's state between events.
pub struct Session {
    pub window: Arc<Window>,
    pub ctx: GpuContext,
    pub presenter: Presenter,
    pub config: ViewConfig,
    sums: SumBuffer,
    scene: LoadedScene,
    /// The script's globals with the view's sampling: what camera and preview size are
    /// applied to.
    base: PackedGlobals,
    pub camera: ViewCamera,
    pub bounds: Bounds,
    pub tracer: TracerKind,
    gpu: Option<Progressive>,
    cpu_sums: Vec<[f32; 4]>,
    /// The next sample index to add, and how many make the image.
    next_sample: u32,
    goal: u32,
    /// 1: full resolution; k: a preview tracing every k-th pixel across and down.
    pub stride: u32,
    /// While the camera moves: when the view starts refining if nothing else moves.
    pub moving_until: Option<Instant>,
    /// The last script error, shown until a run succeeds.
    pub error: Option<String>,
    pub status: Status,
    saves: usize,
    /// Full-resolution frames presented (for `--frames`).
    pub frames_done: u64,
    /// The first error wgpu reported outside an error scope (a frame then fails with
    /// it instead of wgpu's default handler panicking).
    device_error: Arc<Mutex<Option<String>>>,
}

impl Session {
    pub fn new(
        window: Arc<Window>,
        ctx: GpuContext,
        presenter: Presenter,
        config: ViewConfig,
        scene: LoadedScene,
        tracer: TracerKind,
    ) -> Result<Session, GpuError> {
        let g = scene.packed.globals;
        let sums = SumBuffer::new(&ctx, u64::from(g.width) * u64::from(g.height))?;
        let bounds = Bounds::of_globals(&g);
        let camera = ViewCamera::from_script(&scene.camera, &bounds);
        let device_error = Arc::new(Mutex::new(None));
        let slot = Arc::clone(&device_error);
        ctx.device
            .on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
                if let Ok(mut first) = slot.lock() {
                    first.get_or_insert_with(|| e.to_string());
                }
            }));
        let mut session = Session {
            device_error,
            window,
            ctx,
            presenter,
            config,
            sums,
            base: g,
            camera,
            bounds,
            tracer,
            gpu: None,
            cpu_sums: Vec::new(),
            next_sample: 0,
            goal: frames_to_converge(&scene.packed),
            stride: 1,
            moving_until: None,
            error: None,
            status: Status::default(),
            saves: 0,
            frames_done: 0,
            scene,
        };
        session.set_tracer(tracer)?;
        Ok(session)
    }

    /// The image's full size.
    pub fn size(&self) -> [u32; 2] {
        [self.base.width, self.base.height]
    }

    pub fn converged(&self) -> bool {
        self.stride == 1 && self.next_sample >= self.goal
    }

    /// Samples a pixel in the image shown, and how many make it.
    pub fn samples(&self) -> (u32, u32) {
        (self.next_sample.min(self.goal), self.goal)
    }

    pub fn scene_name(&self) -> String {
        let p = &self.config.scene;
        p.file_name().map_or_else(
            || glint::display_path::shown(p),
            |n| n.to_string_lossy().into_owned(),
        )
    }

    /// Switches to `tracer` (the GPU one needs the scene on the device) and restarts.
    pub fn set_tracer(&mut self, tracer: TracerKind) -> Result<(), GpuError> {
        self.tracer = tracer;
        match tracer {
            TracerKind::Gpu if self.gpu.is_none() => {
                self.gpu = Some(Progressive::new(&self.ctx, &self.scene.packed, &self.sums)?);
            }
            TracerKind::Cpu => self.cpu_sums = vec![[0.0; 4]; self.sums.capacity as usize],
            TracerKind::Gpu => {}
        }
        self.restart();
        Ok(())
    }

    /// Starts accumulating afresh with the current camera and stride.
    pub fn restart(&mut self) {
        let mut g = self.base;
        self.camera.apply(&mut g);
        g.width = self.base.width.div_ceil(self.stride);
        g.height = self.base.height.div_ceil(self.stride);
        let packed = &mut self.scene.packed;
        packed.globals = g;
        if packed.features.contains(SceneFeatures::REFRACTION) {
            // The media around the eye depend on where it is.
            fill_camera_media(packed);
        }
        if let (TracerKind::Gpu, Some(gpu)) = (self.tracer, self.gpu.as_mut()) {
            gpu.set_globals(&self.ctx, &self.scene.packed.globals);
        }
        self.next_sample = 0;
        self.goal = if self.stride > 1 {
            1
        } else {
            frames_to_converge(&self.scene.packed)
        };
        self.status
            .restarted(self.stride, self.moving_until.is_some());
        self.window.request_redraw();
    }

    /// The camera moved: preview at a resolution that keeps up, refine once it settles.
    pub fn moved(&mut self) {
        self.moving_until = Some(Instant::now() + SETTLE);
        self.stride = preview_stride(self.status.full_frame_time());
        self.restart();
    }

    /// Called when no move came for [`SETTLE`]: back to full resolution.
    pub fn settle(&mut self) {
        self.moving_until = None;
        self.status.report_moving();
        self.stride = 1;
        self.restart();
    }

    /// Adds the next sample (if the image is not complete) and presents; asks for the
    /// next frame while refining. With `screenshot`, returns the presented image.
    pub fn frame(&mut self, screenshot: bool) -> Result<Option<Film>, GpuError> {
        let refine = self.next_sample < self.goal;
        let s = self.next_sample;
        let g = self.scene.packed.globals;
        let started = Instant::now();
        if refine && self.tracer == TracerKind::Cpu {
            accumulate_sample(&self.scene.packed, s, &mut self.cpu_sums);
            let pixels = (g.width * g.height) as usize;
            self.sums.upload(&self.ctx, &self.cpu_sums[..pixels]);
        }
        let mut gpu = self
            .gpu
            .as_mut()
            .filter(|_| refine && self.tracer == TracerKind::Gpu);
        // A kernel that checks the software adapter's loop limiter traces apart from the
        // present and waits, so that the samples it cut short are re-traced on the CPU
        // before the sums are shown; elsewhere the tracing and the present are one submit.
        let apart = gpu.as_ref().is_some_and(|p| p.checks_limiter());
        if let Some(p) = gpu.as_mut().filter(|_| apart) {
            p.trace_sample(&self.ctx, &self.scene.packed, &self.sums, s)?;
        }
        // Whether sample s is in the sums before the present (then a present that must
        // be redone does not trace it again: it would be added twice).
        let added = refine && (apart || self.tracer == TracerKind::Cpu);
        let gpu = gpu.filter(|_| !apart).map(|p| &*p);
        let ctx = &self.ctx;
        let encode = |encoder: &mut wgpu::CommandEncoder| {
            if let Some(gpu) = gpu {
                gpu.encode_sample(ctx, encoder, s);
            }
        };
        let (presented, shot) = self.presenter.present(
            &self.ctx,
            &self.sums,
            [g.width, g.height],
            &encode,
            screenshot,
        );
        // Wait for the frame: the next one is traced only when this one is done (no
        // queue of stale frames while the camera moves), and the timings are real.
        self.ctx.wait()?;
        if let Some(message) = self.device_error.lock().ok().and_then(|e| e.clone()) {
            return Err(GpuError::Wgpu {
                what: "view frame",
                message,
            });
        }
        if let Presented::Reconfigured = presented {
            self.window.request_redraw();
            if !added {
                return Ok(None);
            }
        }
        if refine {
            self.next_sample += 1;
            let pixels = u64::from(g.width) * u64::from(g.height);
            self.status
                .frame_done(self.stride, pixels, started.elapsed(), self.converged());
            if self.stride == 1 {
                self.frames_done += 1;
            }
            if self.next_sample < self.goal {
                self.window.request_redraw();
            } else if self.stride == 1 {
                self.report_limited();
            }
        }
        Ok(shot)
    }

    /// After a GPU image completes: a note when the software adapter's loop limiter cut
    /// some samples short (they were re-traced on the CPU tracer, as `glint render`
    /// re-renders such pixels).
    fn report_limited(&self) {
        if let (TracerKind::Gpu, Some(gpu)) = (self.tracer, self.gpu.as_ref()) {
            let r = gpu.retraced();
            if r.samples > 0 {
                eprintln!(
                    "glint view: note: {} samples of {} pixels passed the software adapter's loop limit and were re-traced on the CPU tracer",
                    r.samples, r.pixels
                );
            }
        }
    }

    /// Re-runs the script; on success shows the new scene (keeping the user's camera
    /// unless the script's own camera changed), on failure keeps the image and returns
    /// the error. Returns the files the run read.
    pub fn reload(&mut self) -> (Result<(), String>, Vec<std::path::PathBuf>) {
        let started = Instant::now();
        let c = &self.config;
        let outcome = load_scene(&c.scene, &c.script, &c.overrides, c.sampling);
        let scene = match outcome.scene {
            Ok(scene) => scene,
            Err(e) => return (Err(e), outcome.files),
        };
        let result = self.show(scene);
        if result.is_ok() {
            eprintln!(
                "glint view: reloaded {} in {} ms",
                self.scene_name(),
                started.elapsed().as_millis()
            );
        }
        (result, outcome.files)
    }

    /// Replaces the scene with `scene` (a reload).
    fn show(&mut self, scene: LoadedScene) -> Result<(), String> {
        let g = scene.packed.globals;
        let bounds = Bounds::of_globals(&g);
        if scene.camera != self.scene.camera {
            self.camera = ViewCamera::from_script(&scene.camera, &bounds);
        }
        if [g.width, g.height] != self.size() {
            self.sums = SumBuffer::new(&self.ctx, u64::from(g.width) * u64::from(g.height))
                .map_err(|e| e.to_string())?;
            let _ = self
                .window
                .request_inner_size(winit::dpi::PhysicalSize::new(g.width, g.height));
        }
        self.bounds = bounds;
        self.base = g;
        self.scene = scene;
        self.gpu = None;
        self.set_tracer(self.tracer).map_err(|e| e.to_string())
    }

    /// The camera back to the script's.
    pub fn reset_camera(&mut self) {
        self.camera = ViewCamera::from_script(&self.scene.camera, &self.bounds);
        self.moved();
    }

    /// The image as shown now (each pixel's mean so far), at the current resolution.
    pub fn current_film(&self) -> Result<Film, GpuError> {
        let g = &self.scene.packed.globals;
        let pixels = u64::from(g.width) * u64::from(g.height);
        let sums = match self.tracer {
            TracerKind::Gpu => self.sums.read(&self.ctx, pixels)?,
            TracerKind::Cpu => self.cpu_sums[..pixels as usize].to_vec(),
        };
        Ok(film_of_sums(&sums, g.width, g.height))
    }

    /// Writes the current image (S) through the atomic writer, to `-o` (numbered after
    /// the first) or the script's image name numbered `-view-0001`… under the write
    /// policy; returns the path.
    pub fn save(&mut self) -> Result<std::path::PathBuf, String> {
        let film = self.current_film().map_err(|e| e.to_string())?;
        let path = super::save::save_path(&self.config, &self.scene.request.output, self.saves)?;
        glint::image_io::write_image(&film, &path).map_err(|e| e.to_string())?;
        self.saves += 1;
        Ok(path)
    }
}

/// The preview stride whose frame, one sample a pixel, takes about 1 / [`PREVIEW_FPS`]
/// given a full-resolution frame's time (a power of two up to [`MAX_PREVIEW_STRIDE`];
/// 4 before any frame was timed).
pub fn preview_stride(full_frame: Option<Duration>) -> u32 {
    let Some(full) = full_frame else {
        return 4;
    };
    let mut stride = 1;
    while stride < MAX_PREVIEW_STRIDE
        && full.as_secs_f64() / f64::from(stride * stride) > 1.0 / PREVIEW_FPS
    {
        stride *= 2;
    }
    stride
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_preview_is_as_fine_as_the_frame_rate_allows() {
        assert_eq!(preview_stride(Some(Duration::from_millis(10))), 1);
        assert_eq!(preview_stride(Some(Duration::from_millis(100))), 2);
        assert_eq!(preview_stride(Some(Duration::from_millis(500))), 4);
        assert_eq!(
            preview_stride(Some(Duration::from_secs(60))),
            MAX_PREVIEW_STRIDE
        );
        assert_eq!(preview_stride(None), 4);
    }
}
