//! `glint view`'s command line: the scene, the tracer, the sampling the view converges
//! to, where S writes, and the sandbox flags every script-running command shares
//! ([`ScriptArgs`], one script driver).

use crate::script_args::ScriptArgs;
use glint::scene::lua::MAX_IMAGE_SIDE;
use glint::scene::{AaMode, AaSamples, OptionOverrides, TransformOrder};
use glint::script_driver::ScriptSettings;
use std::path::PathBuf;

/// Most frames `--frames` accepts (a test's bound, not a render's).
const MAX_FRAMES: u64 = 1 << 20;

/// `--backend` of the view: which tracer refines the image (presenting always uses the
/// GPU device the window's surface is on).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ViewBackend {
    /// A hardware GPU's tracer; the CPU tracer when the only adapter is a software one.
    Auto,
    /// The GPU tracer, also on a software adapter (lavapipe).
    Gpu,
    /// The CPU reference tracer; the window still presents on the GPU device.
    Cpu,
}

#[derive(Clone, Debug, clap::Args)]
pub struct ViewArgs {
    /// The scene script (Lua, CS488 `gr` language); its first gr.render call is shown.
    pub scene: PathBuf,
    /// Where S writes the image (.png or .exr; later saves get -2, -3… before the
    /// extension); default: the script's image name numbered -view-0001, -view-0002…
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Image width (overrides gr.render's); the window opens at the image's size.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_IMAGE_SIDE as i64))]
    pub width: Option<u32>,
    /// Image height (overrides gr.render's).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_IMAGE_SIDE as i64))]
    pub height: Option<u32>,
    /// Transform order: pre (M = Op·M) or post (M = M·Op).
    #[arg(long, value_parser = parse_order)]
    pub transform_order: Option<TransformOrder>,
    /// The sandbox's limits and readable folders (the same flags as `render`).
    #[command(flatten)]
    pub script: ScriptArgs,
    /// The folder S's default image names are taken from and confined to (default: the
    /// current folder). -o is not confined.
    #[arg(long, value_name = "DIR")]
    pub output_dir: Option<PathBuf>,
    /// A further folder a default image name may be written under (repeatable).
    #[arg(long, value_name = "DIR")]
    pub allow_write: Vec<PathBuf>,
    /// Tracer that refines the image: auto, gpu or cpu (G toggles while running).
    #[arg(long, value_enum, default_value = "auto")]
    pub backend: ViewBackend,
    /// GPU adapter to use: a substring of its name (see `glint info`).
    #[arg(long)]
    pub adapter: Option<String>,
    /// GPU kernel variant: hardware or software, instead of the one chosen by adapter
    /// (as `render`'s; the hardware one on lavapipe shows what a hardware GPU would run).
    #[arg(long, value_parser = glint::gpu::KernelVariant::parse)]
    pub kernel_variant: Option<glint::gpu::KernelVariant>,
    /// What the view converges to: uniform (n×n jittered samples a pixel, one a frame)
    /// or none (pixel centres, one frame). Default: the scene's own `aa` when it is none
    /// or uniform, else uniform.
    #[arg(long, value_parser = parse_view_aa)]
    pub aa: Option<AaMode>,
    /// n of the n×n samples the view accumulates (default: the scene's `samples`).
    #[arg(long, value_parser = AaSamples::parse)]
    pub samples: Option<AaSamples>,
    /// Quit after this many frames (each frame adds one sample a pixel; the view stops
    /// refining at n×n, so a larger N ends there).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=MAX_FRAMES))]
    pub frames: Option<u64>,
    /// With --frames: copy the window's surface after the last frame into this image
    /// (PNG), as presented.
    #[arg(long, requires = "frames")]
    pub screenshot: Option<PathBuf>,
}

fn parse_order(s: &str) -> Result<TransformOrder, String> {
    match s {
        "pre" => Ok(TransformOrder::Pre),
        "post" => Ok(TransformOrder::Post),
        _ => Err(format!("transform order must be pre or post, got '{s}'")),
    }
}

fn parse_view_aa(s: &str) -> Result<AaMode, String> {
    match AaMode::parse(s) {
        Some(AaMode::Adaptive) => Err(
            "glint view converges to uniform n×n sampling (one sample a pixel a frame); adaptive AA is glint render's (use --aa uniform or none)".into(),
        ),
        Some(mode) => Ok(mode),
        None => Err(format!("aa must be none or uniform, got '{s}'")),
    }
}

impl ViewArgs {
    /// The script's settings (the same driver and limits as `glint render`).
    pub fn script_settings(&self) -> Result<ScriptSettings, String> {
        self.script.settings(self.transform_order)
    }

    /// The render-option flags that beat the script (size; sampling is the view's own,
    /// applied by [`super::load::view_sampling`]).
    pub fn overrides(&self) -> OptionOverrides {
        OptionOverrides {
            width: self.width,
            height: self.height,
            ..OptionOverrides::default()
        }
    }
}
