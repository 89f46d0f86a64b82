//! The farm flags of `glint render` as values: `--tile I/N` (I may be `auto`: the task
//! index a scheduler gives, [`TASK_INDEX_VARIABLES`]), `--crop x0,x1,y0,y1`,
//! `--frames A-B[:STEP]` and `--frame N`. Parsers return messages for clap (exit code 2).

use crate::tiling::PixelRect;

/// Environment variables that hold a farm task's 0-based index, in the order they are
/// looked up: Slurm job arrays, then Kubernetes Indexed Jobs.
pub const TASK_INDEX_VARIABLES: [&str; 2] = ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"];

/// An index given on the command line, or `auto`: the scheduler's task index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Index {
    Given(u32),
    Auto,
}

/// `--tile I/N`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileSpec {
    pub index: Index,
    pub count: u32,
}

/// Most tiles `--tile` accepts.
pub const MAX_TILES: u32 = 1 << 20;

/// Parses `--tile I/N`: I from 0 to N − 1, or `auto`.
pub fn parse_tile(s: &str) -> Result<TileSpec, String> {
    let bad = || format!("expected I/N (tile I of N, I from 0 to N-1, or auto/N), got '{s}'");
    let (i, n) = s.split_once('/').ok_or_else(bad)?;
    let count: u32 = n.trim().parse().map_err(|_| bad())?;
    if count == 0 || count > MAX_TILES {
        return Err(format!(
            "the tile count must be 1 to {MAX_TILES}, got '{n}'"
        ));
    }
    let index = parse_index(i).ok_or_else(bad)?;
    if let Index::Given(i) = index {
        if i >= count {
            return Err(format!(
                "tile index {i} is not below the tile count {count} (tiles are numbered 0 to {})",
                count - 1
            ));
        }
    }
    Ok(TileSpec { index, count })
}

fn parse_index(s: &str) -> Option<Index> {
    match s.trim() {
        "auto" => Some(Index::Auto),
        n => n.parse().ok().map(Index::Given),
    }
}

/// Parses `--crop x0,x1,y0,y1`: columns x0..x1 and rows y0..y1, half-open, not empty
/// (checked against the image size when it is known).
pub fn parse_crop(s: &str) -> Result<PixelRect, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let numbers: Option<Vec<u32>> = parts.iter().map(|p| p.parse().ok()).collect();
    match numbers.as_deref() {
        Some(&[x0, x1, y0, y1]) if x0 < x1 && y0 < y1 => Ok(PixelRect { x0, x1, y0, y1 }),
        Some(&[_, _, _, _]) => Err(format!(
            "the crop window x0,x1,y0,y1 is half-open and must hold a pixel (x0 < x1, y0 < y1), got '{s}'"
        )),
        _ => Err(format!(
            "expected x0,x1,y0,y1 (pixel columns x0..x1, rows y0..y1, half-open), got '{s}'"
        )),
    }
}

/// `--frames A-B[:STEP]`: frames A, A + STEP, … up to B.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameRange {
    pub first: u32,
    pub last: u32,
    pub step: u32,
}

/// Most frames one range may hold.
pub const MAX_FRAMES: u32 = 1_000_000;

impl FrameRange {
    /// The frames, in order.
    pub fn frames(&self) -> impl Iterator<Item = u32> {
        (self.first..=self.last).step_by(self.step as usize)
    }
    /// The clock of `frame`: 0 at A, 1 at B (0 when A = B).
    pub fn clock(&self, frame: u32) -> f64 {
        if self.last == self.first {
            return 0.0;
        }
        f64::from(frame - self.first) / f64::from(self.last - self.first)
    }
    pub fn contains(&self, frame: u32) -> bool {
        (self.first..=self.last).contains(&frame) && (frame - self.first).is_multiple_of(self.step)
    }
    /// Digits of the numbered outputs: at least 4, as many as B has.
    pub fn digits(&self) -> usize {
        self.last.to_string().len().max(4)
    }
}

/// Parses `--frames A-B[:STEP]`.
pub fn parse_frames(s: &str) -> Result<FrameRange, String> {
    let bad = || format!("expected A-B or A-B:STEP (frames A to B, every STEP-th), got '{s}'");
    let (range, step) = match s.split_once(':') {
        Some((r, st)) => (r, st.trim().parse::<u32>().map_err(|_| bad())?),
        None => (s, 1),
    };
    let (a, b) = range.split_once('-').ok_or_else(bad)?;
    let first: u32 = a.trim().parse().map_err(|_| bad())?;
    let last: u32 = b.trim().parse().map_err(|_| bad())?;
    if step == 0 {
        return Err(format!("the frame step must be at least 1, got '{s}'"));
    }
    if first > last {
        return Err(format!(
            "the first frame {first} is after the last {last} in '{s}'"
        ));
    }
    if (last - first) / step >= MAX_FRAMES {
        return Err(format!("'{s}' is over {MAX_FRAMES} frames"));
    }
    Ok(FrameRange { first, last, step })
}

/// Parses `--frame N` (or `auto`: the task index-th frame of `--frames`).
pub fn parse_frame(s: &str) -> Result<Index, String> {
    parse_index(s).ok_or_else(|| format!("expected a frame number or auto, got '{s}'"))
}

/// The farm task index from the environment ([`TASK_INDEX_VARIABLES`]), or why not.
pub fn task_index_from(env: impl Fn(&str) -> Option<String>) -> Result<u32, String> {
    for name in TASK_INDEX_VARIABLES {
        if let Some(value) = env(name) {
            return value.trim().parse().map_err(|_| {
                format!("{name}={value:?} is not a task index (a whole number from 0)")
            });
        }
    }
    Err(format!(
        "auto needs the farm's task index in {} or {}; neither is set",
        TASK_INDEX_VARIABLES[0], TASK_INDEX_VARIABLES[1]
    ))
}

/// [`task_index_from`] the process environment.
pub fn task_index() -> Result<u32, String> {
    task_index_from(|name| std::env::var(name).ok())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tile_specs_parse_and_bad_ones_say_why() {
        assert_eq!(
            parse_tile("3/16"),
            Ok(TileSpec {
                index: Index::Given(3),
                count: 16
            })
        );
        assert_eq!(
            parse_tile("auto/4"),
            Ok(TileSpec {
                index: Index::Auto,
                count: 4
            })
        );
        assert!(parse_tile("4/4").unwrap_err().contains("not below"));
        assert!(parse_tile("0/0").unwrap_err().contains("1 to"));
        for bad in ["", "3", "a/4", "-1/4", "1/x", "1/2/3"] {
            assert!(parse_tile(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn crops_parse_half_open() {
        let r = parse_crop("0,10,5,6").unwrap();
        assert_eq!((r.width(), r.height()), (10, 1));
        assert!(parse_crop("3,3,0,1").unwrap_err().contains("half-open"));
        for bad in ["1,2,3", "a,b,c,d", "1,2,3,4,5", "-1,2,0,1"] {
            assert!(parse_crop(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn frame_ranges_give_frames_and_clocks() {
        let r = parse_frames("1-9:4").unwrap();
        assert_eq!(r.frames().collect::<Vec<_>>(), vec![1, 5, 9]);
        assert_eq!((r.clock(1), r.clock(5), r.clock(9)), (0.0, 0.5, 1.0));
        assert!(r.contains(5) && !r.contains(4) && !r.contains(13));
        assert_eq!(parse_frames("7-7").unwrap().clock(7), 0.0);
        assert_eq!(parse_frames("0-123456").unwrap().digits(), 6);
        for bad in ["9-1", "1-9:0", "1", "a-b", "1-2:x"] {
            assert!(parse_frames(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_task_index_comes_from_slurm_or_kubernetes() {
        let env = |pairs: &'static [(&'static str, &'static str)]| {
            move |n: &str| {
                pairs
                    .iter()
                    .find(|(k, _)| *k == n)
                    .map(|(_, v)| v.to_string())
            }
        };
        assert_eq!(task_index_from(env(&[("SLURM_ARRAY_TASK_ID", "7")])), Ok(7));
        assert_eq!(
            task_index_from(env(&[("JOB_COMPLETION_INDEX", "2")])),
            Ok(2)
        );
        assert!(task_index_from(env(&[]))
            .unwrap_err()
            .contains("neither is set"));
        assert!(task_index_from(env(&[("SLURM_ARRAY_TASK_ID", "x")])).is_err());
    }
}
