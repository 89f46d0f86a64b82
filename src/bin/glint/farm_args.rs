//! The farm flags as `glint render` takes them (flattened into its arguments), and
//! `glint assemble`'s.

use glint::farm::run::FarmSettings;
use glint::farm::spec::{
    parse_crop, parse_frame, parse_frames, parse_tile, FrameRange, Index, TileSpec,
};
use glint::scene::lua::DEFAULT_MEMORY_LIMIT;
use glint::tiling::PixelRect;
use std::path::PathBuf;

/// Tiles, crop windows and frames (docs/farm.md).
#[derive(Clone, Debug, Default, clap::Args)]
pub struct FarmArgs {
    /// Render tile I of N (I from 0 to N-1, or auto: the farm's task index from
    /// SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX); writes NAME-tile-I-of-N.png with
    /// the tile's place and the render's digest. `glint assemble` joins the tiles.
    #[arg(long, value_name = "I/N", value_parser = parse_tile)]
    pub tile: Option<TileSpec>,
    /// Render only pixel columns x0..x1 and rows y0..y1 (half-open), written as a tile.
    #[arg(long, value_name = "x0,x1,y0,y1", value_parser = parse_crop)]
    pub crop: Option<PixelRect>,
    /// Run the script once per frame A, A+STEP, … B, with the globals `frame` and `clock`
    /// (0 at A to 1 at B); outputs NAME-0001.png, ….
    #[arg(long, value_name = "A-B[:STEP]", value_parser = parse_frames)]
    pub frames: Option<FrameRange>,
    /// Render frame N only (of --frames, whose range sets its clock; alone: clock 0), or
    /// auto: the task index-th frame of --frames.
    #[arg(long, value_name = "N", value_parser = parse_frame)]
    pub frame: Option<Index>,
    /// Leave an output alone that already holds this render's pixels (same digest and
    /// bounds), so a farm's retried task costs only the scene's load.
    #[arg(long)]
    pub skip_existing: bool,
}

impl FarmArgs {
    pub fn settings(&self) -> FarmSettings {
        FarmSettings {
            tile: self.tile,
            crop: self.crop,
            frames: self.frames,
            frame: self.frame,
            skip_existing: self.skip_existing,
        }
    }
}

/// `glint assemble`.
#[derive(Clone, Debug, clap::Args)]
pub struct AssembleArgs {
    /// The tiles (from `glint render --tile` or `--crop`).
    #[arg(required = true)]
    pub tiles: Vec<PathBuf>,
    /// The image to write (.png from PNG tiles, .exr from EXR tiles).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Memory budget in MiB for the tiles' files, the image and decoding a tile: tiles
    /// whose records ask for more are refused before anything is allocated.
    #[arg(long, value_name = "MIB", default_value_t = (DEFAULT_MEMORY_LIMIT >> 20) as u64,
          value_parser = clap::value_parser!(u64).range(16..=1 << 20))]
    pub memory_limit: u64,
}

impl AssembleArgs {
    /// `--memory-limit` in bytes.
    pub fn memory_budget(&self) -> u64 {
        self.memory_limit << 20
    }
}
