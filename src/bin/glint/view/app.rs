//! The window and its event loop (winit 0.30): opening the window and the device that
//! presents it, then dispatching events to the [`Session`]. The loop sleeps
//! (`ControlFlow::Wait`) whenever the image is complete and nothing moves; it wakes for
//! input, for the file watcher, and (while the camera moves) when the move settles.

use super::args::ViewBackend;
use super::config::{no_display_message, ViewConfig, NO_DISPLAY_EXIT};
use super::input::{drag_kind, key_action, Action, DragKind, Mouse, KEYS_HELP};
use super::load::{load_scene, LoadedScene};
use super::present::Presenter;
use super::session::{Session, TracerKind};
use super::status::title;
use super::watch::WatchList;
use glint::display_path::for_terminal;
use glint::gpu::GpuContext;
use std::sync::Arc;
use winit::application::ApplicationHandler;
use winit::event::{ElementState, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{ModifiersState, PhysicalKey};
use winit::window::{Window, WindowId};

/// What wakes the loop besides the window: a watched file changed.
#[derive(Debug)]
pub enum ViewEvent {
    FilesChanged,
}

/// The loop's state: the session once the window is open, and how the run ends.
struct App {
    config: ViewConfig,
    /// The first script run's scene, until the window opens.
    first: Option<LoadedScene>,
    watch: WatchList,
    session: Option<Session>,
    mouse: Mouse,
    modifiers: ModifiersState,
    /// Set when the run must end with an error.
    failure: Option<(String, u8)>,
}

/// Runs the script once (a failing script exits 3 before a window opens, as `render`),
/// then the window until it is closed.
pub fn run_app(config: ViewConfig) -> Result<(), (String, u8)> {
    let outcome = load_scene(
        &config.scene,
        &config.script,
        &config.overrides,
        config.sampling,
    );
    let scene = outcome.scene.map_err(|e| (e, 3))?;
    let watch = WatchList::default();
    watch.set(&outcome.files);
    let event_loop = EventLoop::<ViewEvent>::with_user_event()
        .build()
        .map_err(|e| {
            (
                no_display_message(&format!("the window system cannot be reached ({e})")),
                NO_DISPLAY_EXIT,
            )
        })?;
    event_loop.set_control_flow(ControlFlow::Wait);
    let proxy = event_loop.create_proxy();
    watch.spawn(move || proxy.send_event(ViewEvent::FilesChanged).is_ok());
    let mut app = App {
        config,
        first: Some(scene),
        watch,
        session: None,
        mouse: Mouse::default(),
        modifiers: ModifiersState::default(),
        failure: None,
    };
    event_loop
        .run_app(&mut app)
        .map_err(|e| (format!("glint view: the event loop failed: {e}"), 1))?;
    match app.failure {
        Some(f) => Err(f),
        None => Ok(()),
    }
}

impl App {
    fn fail(&mut self, event_loop: &ActiveEventLoop, message: String, code: u8) {
        self.failure = Some((message, code));
        event_loop.exit();
    }

    /// Opens the window at the image's size and the device that presents it.
    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<Session, (String, u8)> {
        let scene = self.first.take().expect("opened once");
        let g = &scene.packed.globals;
        let attributes = Window::default_attributes()
            .with_title("glint view")
            .with_inner_size(winit::dpi::PhysicalSize::new(g.width, g.height));
        let window = Arc::new(event_loop.create_window(attributes).map_err(|e| {
            (
                no_display_message(&format!("the window cannot open ({e})")),
                NO_DISPLAY_EXIT,
            )
        })?);
        let (mut ctx, surface) =
            device_for_window(&window, self.config.adapter.as_deref()).map_err(|e| (e, 5))?;
        if let Some(variant) = self.config.kernel_variant {
            ctx.force_kernel_variant(variant);
        }
        let tracer = choose_tracer(self.config.backend, &ctx);
        let presenter = Presenter::new(&ctx, surface, &window).map_err(|e| (e, 5))?;
        Session::new(window, ctx, presenter, self.config.clone(), scene, tracer)
            .map_err(|e| (e.to_string(), 5))
    }

    fn update_title(&self) {
        if let Some(s) = &self.session {
            let t = title(
                &s.scene_name(),
                s.samples(),
                s.stride,
                s.status.rate,
                s.tracer.name(),
                &s.ctx.info.name,
                s.error.as_deref(),
            );
            s.window.set_title(&t);
        }
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let Some(s) = self.session.as_mut() else {
            return;
        };
        let last = match s.config.frames {
            Some(n) => {
                s.stride == 1 && (s.frames_done + 1 >= n || s.samples().0 + 1 >= s.samples().1)
            }
            None => false,
        };
        let finishing = last && s.samples().0 < s.samples().1;
        let shot = finishing && s.config.screenshot.is_some();
        match s.frame(shot) {
            Err(e) => return self.fail(event_loop, e.to_string(), 5),
            Ok(film) if finishing => {
                if let Some(path) = s.config.screenshot.clone() {
                    let Some(film) = film else {
                        let why = "the window's surface cannot be copied on this adapter";
                        return self.fail(event_loop, format!("--screenshot: {why}"), 1);
                    };
                    if let Err(e) = glint::image_io::write_image(&film, &path) {
                        return self.fail(event_loop, e.to_string(), 4);
                    }
                    eprintln!("glint view: wrote {}", glint::display_path::shown(&path));
                }
                event_loop.exit();
            }
            Ok(_) => {}
        }
        self.update_title();
    }

    fn key(&mut self, event_loop: &ActiveEventLoop, action: Action) {
        let Some(s) = self.session.as_mut() else {
            return;
        };
        match action {
            Action::Fly(f, r, u) => {
                let bounds = s.bounds;
                s.camera.fly(f, r, u, &bounds);
                s.moved();
            }
            Action::Reset => s.reset_camera(),
            Action::Frame => {
                let [w, h] = s.size();
                let bounds = s.bounds;
                s.camera.frame(&bounds, f64::from(w) / f64::from(h));
                s.moved();
            }
            Action::PrintCamera => println!("{}", s.camera.as_lua()),
            Action::Save => match s.save() {
                Ok(path) => {
                    let (spp, goal) = s.samples();
                    eprintln!(
                        "glint view: wrote {} ({spp}/{goal} samples a pixel)",
                        glint::display_path::shown(&path)
                    );
                }
                Err(e) => eprintln!("glint view: error: cannot save: {}", for_terminal(&e)),
            },
            Action::ToggleTracer => {
                let next = match s.tracer {
                    TracerKind::Gpu => TracerKind::Cpu,
                    TracerKind::Cpu => TracerKind::Gpu,
                };
                if let Err(e) = s.set_tracer(next) {
                    eprintln!(
                        "glint view: error: cannot switch to the {} tracer: {e}",
                        next.name()
                    );
                } else {
                    eprintln!("glint view: {} tracer", next.name());
                }
            }
            Action::Help => println!("{KEYS_HELP}"),
            Action::Quit => event_loop.exit(),
        }
        self.update_title();
    }

    fn mouse_moved(&mut self, to: (f64, f64)) {
        let Some(s) = self.session.as_mut() else {
            return;
        };
        if let Some((drag, dx, dy)) = self.mouse.moved(to) {
            match drag {
                DragKind::Orbit => s.camera.orbit(dx, dy),
                DragKind::Pan => {
                    let height = f64::from(s.window.inner_size().height);
                    s.camera.pan(dx, dy, height);
                }
            }
            s.moved();
        }
    }

    fn reload(&mut self) {
        let Some(s) = self.session.as_mut() else {
            return;
        };
        let (result, files) = s.reload();
        match result {
            Ok(()) => {
                s.error = None;
                self.watch.set(&files);
            }
            Err(e) => {
                eprintln!("glint view: error: {}", for_terminal(&e));
                s.error = Some(e);
                self.watch.add(&files);
            }
        }
        self.update_title();
    }
}

impl ApplicationHandler<ViewEvent> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.session.is_some() || self.first.is_none() {
            return;
        }
        match self.open(event_loop) {
            Ok(session) => {
                eprintln!(
                    "glint view: {} tracer on {} ({:?}; GPU kernel: {}); H prints the keys",
                    session.tracer.name(),
                    session.ctx.info.name,
                    session.ctx.info.backend,
                    session.ctx.kernel
                );
                self.session = Some(session);
                self.update_title();
            }
            Err((message, code)) => self.fail(event_loop, message, code),
        }
    }

    fn user_event(&mut self, _event_loop: &ActiveEventLoop, event: ViewEvent) {
        match event {
            ViewEvent::FilesChanged => self.reload(),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            WindowEvent::Resized(size) => {
                if let Some(s) = self.session.as_mut() {
                    s.presenter.resize(&s.ctx, size.width, size.height);
                    s.window.request_redraw();
                }
            }
            WindowEvent::ModifiersChanged(m) => self.modifiers = m.state(),
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                if let PhysicalKey::Code(code) = event.physical_key {
                    if let Some(action) = key_action(code, self.modifiers.control_key()) {
                        self.key(event_loop, action);
                    }
                }
            }
            WindowEvent::CursorMoved { position, .. } => self.mouse_moved((position.x, position.y)),
            WindowEvent::MouseInput { state, button, .. } => {
                self.mouse.drag = match state {
                    ElementState::Pressed => drag_kind(button),
                    ElementState::Released => None,
                };
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let notches = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                if let Some(s) = self.session.as_mut() {
                    s.camera.dolly(notches);
                    s.moved();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(s) = self.session.as_mut() else {
            return;
        };
        match s.moving_until {
            Some(t) if std::time::Instant::now() >= t => {
                s.settle();
                event_loop.set_control_flow(ControlFlow::Wait);
            }
            Some(t) => event_loop.set_control_flow(ControlFlow::WaitUntil(t)),
            None => event_loop.set_control_flow(ControlFlow::Wait),
        }
    }
}

/// The tracer `backend` asks for on `ctx`: auto takes the GPU tracer on a hardware
/// adapter and the CPU tracer on a software one (as `render`'s auto), with a note.
fn choose_tracer(backend: ViewBackend, ctx: &GpuContext) -> TracerKind {
    match backend {
        ViewBackend::Gpu => TracerKind::Gpu,
        ViewBackend::Cpu => TracerKind::Cpu,
        ViewBackend::Auto if ctx.info.device_type == wgpu::DeviceType::Cpu => {
            eprintln!(
                "glint view: note: tracing on the CPU; the adapter, {}, is a software one (it presents the window; --backend gpu or G traces on it)",
                ctx.info.name
            );
            TracerKind::Cpu
        }
        ViewBackend::Auto => TracerKind::Gpu,
    }
}

/// A device that can present to `window`: the instance on glint's backends (never GL),
/// the window's surface, and the adapter `name` picks (a substring) or the first that
/// can present to it, hardware before software.
fn device_for_window(
    window: &Arc<Window>,
    name: Option<&str>,
) -> Result<(GpuContext, wgpu::Surface<'static>), String> {
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    desc.backends = glint::gpu::device::context::backends();
    let instance = wgpu::Instance::new(desc);
    let surface = instance
        .create_surface(Arc::clone(window))
        .map_err(|e| format!("cannot make a surface for the window: {e}"))?;
    let adapters =
        pollster::block_on(instance.enumerate_adapters(glint::gpu::device::context::backends()));
    let names: Vec<String> = adapters.iter().map(|a| a.get_info().name).collect();
    let mut usable: Vec<wgpu::Adapter> = adapters
        .into_iter()
        .filter(|a| a.is_surface_supported(&surface))
        .filter(|a| {
            name.is_none_or(|n| a.get_info().name.to_lowercase().contains(&n.to_lowercase()))
        })
        .collect();
    usable.sort_by_key(|a| a.get_info().device_type == wgpu::DeviceType::Cpu);
    let adapter = usable.into_iter().next().ok_or_else(|| {
        format!(
            "no GPU adapter{} can present to the window (adapters: {}); glint view presents through Vulkan (Mesa's lavapipe is enough: apt-get install mesa-vulkan-drivers)",
            name.map(|n| format!(" named like '{n}'")).unwrap_or_default(),
            if names.is_empty() { "none".into() } else { names.join(", ") }
        )
    })?;
    let ctx = GpuContext::from_adapter(adapter).map_err(|e| e.to_string())?;
    Ok((ctx, surface))
}
