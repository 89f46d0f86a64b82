//! `glint render` with farm flags: the script runs once per frame (`--frames`, with the
//! globals `frame` and `clock`), and each `gr.render` renders the pixels of its tile or
//! crop window alone, written with their record ([`super::tile_file`]); `--skip-existing`
//! leaves a file alone that already holds this render's pixels (same digest and bounds).
//! Scripts run through [`crate::script_driver::run_script`]; requests are prepared as
//! [`crate::pipeline`] prepares them.

use super::digest::render_digest;
use super::spec::{task_index, FrameRange, Index, TileSpec};
use super::split::tile_rect;
use super::tile_file::{check_tile_path, write_tile, TileFileError, TileMeta};
use super::tile_read::{TileFile, MAX_TILE_FILE_BYTES};
use crate::file_name::with_suffix;
use crate::film::Film;
use crate::gpu::{render_gpu, GpuRenderOptions};
use crate::pipeline::{
    acquire_gpu, output_path, prepare_request, scene_error, write_policy, RenderSettings, RunError,
    Tracer,
};
use crate::scene::lua::FrameGlobals;
use crate::scene::{RenderRequest, SceneGraph};
use crate::script_driver::run_script_bytes;
use crate::tiling::PixelRect;
use crate::tracer::sampling::render::render_window;
use crate::write_policy::WritePolicy;
use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The farm flags of one `glint render`.
#[derive(Clone, Copy, Debug, Default)]
pub struct FarmSettings {
    /// `--tile I/N`.
    pub tile: Option<TileSpec>,
    /// `--crop x0,x1,y0,y1`.
    pub crop: Option<PixelRect>,
    /// `--frames A-B[:STEP]`.
    pub frames: Option<FrameRange>,
    /// `--frame N` (or `auto`).
    pub frame: Option<Index>,
    /// `--skip-existing`.
    pub skip_existing: bool,
}

impl FarmSettings {
    /// Whether any farm flag is given (else `glint render` runs as without them).
    pub fn any(&self) -> bool {
        self.tile.is_some()
            || self.crop.is_some()
            || self.frames.is_some()
            || self.frame.is_some()
            || self.skip_existing
    }
    /// Whether images are written as tiles with their record (PNG or EXR).
    fn writes_tiles(&self) -> bool {
        self.tile.is_some() || self.crop.is_some() || self.skip_existing
    }
}

/// Why a farm render failed.
#[derive(Debug, thiserror::Error)]
pub enum FarmError {
    /// The flags do not fit this scene or environment (exit code 2).
    #[error("{0}")]
    Usage(String),
    #[error("{0}")]
    Tile(#[from] TileFileError),
    #[error("{0}")]
    Run(#[from] RunError),
    /// The render itself failed (the scene's build, or the GPU): handed back to the
    /// script's `gr.render`, so the error carries its line (exit code 3, or 5 for the GPU).
    #[error("{0:#}")]
    Render(anyhow::Error),
}

impl FarmError {
    pub fn exit_code(&self) -> u8 {
        match self {
            FarmError::Usage(_) => 2,
            FarmError::Tile(_) => 4,
            FarmError::Run(e) => e.exit_code() as u8,
            FarmError::Render(_) => 3,
        }
    }
}

/// One image a farm render wrote or found written already.
#[derive(Clone, Debug)]
pub struct FarmImage {
    pub output: PathBuf,
    /// The full image's size and the pixels written.
    pub full_size: (u32, u32),
    pub bounds: PixelRect,
    /// The frame, under `--frames` or `--frame`.
    pub frame: Option<u32>,
    /// Found with the same digest and bounds under `--skip-existing`: not rendered.
    pub skipped: bool,
    pub render_time: Duration,
    /// "CPU" or "GPU".
    pub tracer: &'static str,
}

/// What one frame's script runs with.
#[derive(Clone, Copy)]
struct FrameJob {
    /// Frame number and output digits.
    frame: Option<(u32, usize)>,
    globals: Option<FrameGlobals>,
}

/// The frames to run: the whole range, one frame of it, one given frame, or none (the
/// script runs once without `frame` and `clock`).
pub fn frame_jobs(
    frames: Option<FrameRange>,
    frame: Option<Index>,
) -> Result<Vec<(u32, FrameGlobals, usize)>, String> {
    let job = |r: &FrameRange, n: u32| {
        (
            n,
            FrameGlobals {
                frame: i64::from(n),
                clock: r.clock(n),
            },
            r.digits(),
        )
    };
    match (frames, frame) {
        (None, None) => Ok(Vec::new()),
        (Some(r), None) => Ok(r.frames().map(|n| job(&r, n)).collect()),
        (Some(r), Some(Index::Given(n))) if r.contains(n) => Ok(vec![job(&r, n)]),
        (Some(r), Some(Index::Given(n))) => Err(format!(
            "--frame {n} is not a frame of --frames {}-{}:{}",
            r.first, r.last, r.step
        )),
        (Some(r), Some(Index::Auto)) => {
            let k = task_index()?;
            match r.frames().nth(k as usize) {
                Some(n) => Ok(vec![job(&r, n)]),
                None => Err(format!(
                    "--frame auto: task index {k} is past the {} frames of --frames {}-{}:{}",
                    r.frames().count(),
                    r.first,
                    r.last,
                    r.step
                )),
            }
        }
        (None, Some(Index::Given(n))) => Ok(vec![job(
            &FrameRange {
                first: n,
                last: n,
                step: 1,
            },
            n,
        )]),
        (None, Some(Index::Auto)) => {
            Err("--frame auto picks a frame of --frames A-B; give --frames too".into())
        }
    }
}

/// The suffix of tile `i` of `n`: `-tile-03-of-16`.
pub fn tile_suffix(i: u32, n: u32) -> String {
    let digits = (n - 1).to_string().len();
    format!("-tile-{i:0digits$}-of-{n}")
}

/// What a farm run did, for the command line's notes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FarmRun {
    /// The number of `gr.render` calls, over all frames.
    pub renders: usize,
    /// Some frame's script read the global `frame` or `clock`.
    pub reads_frame: bool,
}

/// Runs `scene` under the farm flags; `on_image` sees each image written or skipped.
pub fn run_farm(
    scene: &Path,
    settings: &RenderSettings,
    farm: &FarmSettings,
    on_image: &mut dyn FnMut(&FarmImage),
) -> Result<FarmRun, FarmError> {
    if farm.tile.is_some_and(|t| t.index == Index::Auto) && farm.frame == Some(Index::Auto) {
        return Err(FarmError::Usage("--tile auto and --frame auto would take the same task index; give one of them a number".into()));
    }
    if farm.tile.is_some() && farm.crop.is_some() {
        return Err(FarmError::Usage(
            "--tile and --crop both choose the pixels; give one".into(),
        ));
    }
    let tile = match farm.tile {
        Some(TileSpec {
            index: Index::Auto,
            count,
        }) => Some((task_index().map_err(FarmError::Usage)?, count)),
        Some(TileSpec {
            index: Index::Given(i),
            count,
        }) => Some((i, count)),
        None => None,
    };
    let jobs: Vec<FrameJob> = match frame_jobs(farm.frames, farm.frame).map_err(FarmError::Usage)? {
        jobs if jobs.is_empty() => vec![FrameJob {
            frame: None,
            globals: None,
        }],
        jobs => jobs
            .into_iter()
            .map(|(n, g, d)| FrameJob {
                frame: Some((n, d)),
                globals: Some(g),
            })
            .collect(),
    };
    // Read once, as every scene is read (a regular file, its size checked against the
    // budget first), and run from these bytes: the digest is of what ran.
    let memory_limit = settings.script.config().memory_limit;
    let script =
        crate::scene::lua::read_scene_bytes(scene, memory_limit).map_err(RunError::Scene)?;
    // Script-named outputs are confined as in every other mode (docs/limits.md, Writes).
    let policy = write_policy(settings).map_err(FarmError::Run)?;
    let gpu = acquire_gpu(
        settings.backend,
        settings.adapter.as_deref(),
        settings.stats,
    )
    .map_err(RunError::Gpu)?;
    let tracer = gpu.as_ref().map_or(Tracer::Cpu, Tracer::Gpu);
    let mut run = FarmRun::default();
    for job in jobs {
        let context = JobContext {
            settings,
            policy: &policy,
            farm,
            tile,
            tracer,
            script: &script,
            job,
        };
        let (renders, reads_frame) = run_frame(scene, &context, on_image)?;
        run.renders += renders;
        run.reads_frame |= reads_frame;
    }
    Ok(run)
}

/// What every `gr.render` of one frame shares.
struct JobContext<'a> {
    settings: &'a RenderSettings,
    /// Where the script's own output names may be written.
    policy: &'a WritePolicy,
    farm: &'a FarmSettings,
    tile: Option<(u32, u32)>,
    tracer: Tracer<'a>,
    script: &'a [u8],
    job: FrameJob,
}

/// Runs one frame's script: its `gr.render` calls, and whether it read `frame` or
/// `clock`.
fn run_frame(
    scene: &Path,
    c: &JobContext,
    on_image: &mut dyn FnMut(&FarmImage),
) -> Result<(usize, bool), FarmError> {
    let mut script_settings = c.settings.script.clone();
    script_settings.frame = c.job.globals;
    let failure: RefCell<Option<FarmError>> = RefCell::new(None);
    let mut index = 0;
    let mut on_render = |graph: &SceneGraph, request: &RenderRequest| -> anyhow::Result<()> {
        let result = render_one(graph, request, index, c);
        index += 1;
        match result {
            Ok(image) => {
                on_image(&image);
                Ok(())
            }
            // The pipeline's way: the script's gr.render fails with it (scene_error).
            Err(FarmError::Render(e)) => Err(e),
            // Kept whole for the caller; the script sees a message (and stops).
            Err(e) => {
                let message = e.to_string();
                *failure.borrow_mut() = Some(e);
                Err(anyhow::anyhow!(message))
            }
        }
    };
    let result = run_script_bytes(scene, c.script, &script_settings, &mut on_render);
    if let Some(e) = failure.into_inner() {
        return Err(e);
    }
    let report = result.map_err(|e| FarmError::Run(scene_error(e, None)))?;
    Ok((index, report.reads_frame))
}

/// The output path of render `index` of the frame: `-o`'s (the user's choice), or the
/// script's own name with its frame and tile suffixes, confined by the write policy (a
/// refused name is the script's error at its `gr.render`).
fn farm_output(c: &JobContext, request: &RenderRequest, index: usize) -> anyhow::Result<PathBuf> {
    let base = match &c.settings.output {
        Some(o) => output_path(Some(o), &request.output, index),
        None => request.output.clone(),
    };
    let mut out = base;
    if let Some((n, digits)) = c.job.frame {
        out = with_suffix(&out, &format!("-{n:0digits$}"));
    }
    if let Some((i, n)) = c.tile {
        out = with_suffix(&out, &tile_suffix(i, n));
    }
    match c.settings.output {
        Some(_) => Ok(out),
        None => c.policy.place(&out).map_err(anyhow::Error::msg),
    }
}

/// Prepares, checks, renders (unless found written) and writes one `gr.render`.
fn render_one(
    graph: &SceneGraph,
    request: &RenderRequest,
    index: usize,
    c: &JobContext,
) -> Result<FarmImage, FarmError> {
    let output = farm_output(c, request, index).map_err(FarmError::Render)?;
    let tiles = c.farm.writes_tiles();
    if tiles {
        check_tile_path(&output).map_err(FarmError::Usage)?;
    } else {
        crate::image_io::check_output_path(&output).map_err(RunError::Output)?;
    }
    let (request, packed) =
        prepare_request(graph, request, &c.settings.overrides).map_err(FarmError::Render)?;
    let (w, h) = (request.width, request.height);
    let bounds = match (c.tile, c.farm.crop) {
        (Some((i, n)), _) => tile_rect(w, h, i, n).map_err(|e| FarmError::Usage(e.to_string()))?,
        (None, Some(crop)) if crop.fits(w, h) => crop,
        (None, Some(crop)) => {
            return Err(FarmError::Usage(format!(
                "--crop {crop} reaches outside the {w}×{h} image"
            )))
        }
        (None, None) => PixelRect::full(w, h),
    };
    let tracer_id = match c.tracer {
        Tracer::Cpu => "cpu".to_string(),
        Tracer::Gpu(ctx) => format!(
            "gpu {} ({} {})",
            ctx.info.name, ctx.info.driver, ctx.info.driver_info
        ),
    };
    let meta = TileMeta {
        full_size: (w, h),
        bounds,
        digest: render_digest(c.script, &tracer_id, &packed),
        version: env!("CARGO_PKG_VERSION").to_string(),
        tile: c.tile,
    };
    let mut image = FarmImage {
        output: output.clone(),
        full_size: (w, h),
        bounds,
        frame: c.job.frame.map(|(n, _)| n),
        skipped: false,
        render_time: Duration::ZERO,
        tracer: if matches!(c.tracer, Tracer::Gpu(_)) {
            "GPU"
        } else {
            "CPU"
        },
    };
    if c.farm.skip_existing && holds_tile(&output, &meta, c.settings.script.config().memory_limit) {
        image.skipped = true;
        return Ok(image);
    }
    let start = Instant::now();
    let film = render_bounds(&packed, bounds, c.tracer, &output)?;
    image.render_time = start.elapsed();
    if tiles {
        write_tile(&film, &meta, &output)?;
    } else {
        crate::image_io::write_image(&film, &output).map_err(RunError::Output)?;
    }
    Ok(image)
}

/// Whether `path` already holds the tile `meta` describes, pixels checked against its
/// digest (read as any tile is: a FIFO, a device or a file of another kind there is
/// not waited on, not trusted, and rendered over).
fn holds_tile(path: &Path, meta: &TileMeta, budget: usize) -> bool {
    let budget = budget as u64;
    TileFile::open(path, MAX_TILE_FILE_BYTES.min(budget))
        .is_ok_and(|tile| tile.meta == *meta && tile.pixels(budget).is_ok())
}

/// The pixels of `bounds` on `tracer`.
fn render_bounds(
    packed: &crate::pack::PackedScene,
    bounds: PixelRect,
    tracer: Tracer,
    output: &Path,
) -> Result<Film, FarmError> {
    match tracer {
        Tracer::Cpu => Ok(render_window(packed, bounds, &|_, _| {})),
        Tracer::Gpu(ctx) => {
            let options = GpuRenderOptions {
                window: Some(bounds),
                ..GpuRenderOptions::default()
            };
            let r = render_gpu(ctx, packed, &options).map_err(|e| FarmError::Render(e.into()))?;
            if r.info.cpu_fallback_pixels > 0 {
                eprintln!(
                    "glint: note: {} pixels of {} re-rendered on the CPU: they passed the software adapter's loop limit",
                    r.info.cpu_fallback_pixels,
                    crate::display_path::shown(output)
                );
            }
            Ok(r.film)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_are_numbered_and_tiled() {
        assert_eq!(tile_suffix(3, 16), "-tile-03-of-16");
        assert_eq!(tile_suffix(0, 1), "-tile-0-of-1");
    }

    #[test]
    fn frame_jobs_pick_frames_and_clocks() {
        let r = FrameRange {
            first: 1,
            last: 5,
            step: 2,
        };
        let jobs = frame_jobs(Some(r), None).unwrap();
        let frames: Vec<(u32, f64)> = jobs.iter().map(|(n, g, _)| (*n, g.clock)).collect();
        assert_eq!(frames, vec![(1, 0.0), (3, 0.5), (5, 1.0)]);
        assert_eq!(
            frame_jobs(Some(r), Some(Index::Given(3))).unwrap()[0]
                .1
                .clock,
            0.5
        );
        assert!(frame_jobs(Some(r), Some(Index::Given(2))).is_err());
        assert_eq!(
            frame_jobs(None, Some(Index::Given(9))).unwrap()[0].1,
            FrameGlobals {
                frame: 9,
                clock: 0.0
            }
        );
        assert!(frame_jobs(None, Some(Index::Auto)).is_err());
        assert!(frame_jobs(None, None).unwrap().is_empty());
    }
}
