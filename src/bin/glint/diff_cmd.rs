//! `glint diff A B [--heatmap OUT]`: compare two images and print the figures.

use std::path::Path;

use crate::diff::{check_diff_size, diff_films, DiffError, DiffReport};
use crate::image_io::{read_image_within, write_image, ImageIoError, MAX_READ_PIXELS};

/// Why `glint diff` failed; each kind has its exit code.
#[derive(Debug, thiserror::Error)]
pub enum DiffCmdError {
    /// An input is missing, unreadable or too big (exit code 2: a bad argument).
    #[error("{0}")]
    Input(String),
    /// The images cannot be compared (exit code 3).
    #[error("cannot compare {a} with {b}: {error}")]
    Compare {
        a: String,
        b: String,
        error: DiffError,
    },
    /// The heat map cannot be written (exit code 4).
    #[error("{0}")]
    Output(ImageIoError),
}

impl DiffCmdError {
    pub fn exit_code(&self) -> u8 {
        match self {
            DiffCmdError::Input(_) => 2,
            DiffCmdError::Compare { .. } => 3,
            DiffCmdError::Output(_) => 4,
        }
    }
}

/// Reads one input: a regular file, decoded by its content, its size checked from the
/// header before it is decoded.
fn read_input(path: &Path) -> Result<crate::film::Film, DiffCmdError> {
    read_image_within(path, MAX_READ_PIXELS, |w, h| {
        check_diff_size(w, h).map_err(|e| e.to_string())
    })
    .map_err(|e| DiffCmdError::Input(e.to_string()))
}

/// Reads `a` (the reference) and `b`, prints the report to stdout and, if asked, writes
/// FLIP's magma heat map to `heatmap` (atomically, format by extension).
pub fn run_diff(a: &Path, b: &Path, heatmap: Option<&Path>) -> Result<DiffReport, DiffCmdError> {
    if let Some(path) = heatmap {
        crate::image_io::check_output_path(path).map_err(DiffCmdError::Output)?;
    }
    let film_a = read_input(a)?;
    let film_b = read_input(b)?;
    let (report, heat_map) =
        diff_films(&film_a, &film_b).map_err(|error| DiffCmdError::Compare {
            a: a.display().to_string(),
            b: b.display().to_string(),
            error,
        })?;
    println!("{report}");
    if let Some(path) = heatmap {
        write_image(&heat_map, path).map_err(DiffCmdError::Output)?;
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::Film;
    use crate::image_io::read_image;

    #[test]
    fn diffs_files_and_writes_heat_map() {
        let dir = std::env::temp_dir().join(format!("glint-diff-cmd-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let a = Film::new(8, 8);
        let mut b = a.clone();
        b.set(2, 3, [1.0, 1.0, 1.0]);
        write_image(&a, &dir.join("a.png")).unwrap();
        write_image(&b, &dir.join("b.exr")).unwrap();
        let heat = dir.join("heat.png");
        let report = run_diff(&dir.join("a.png"), &dir.join("b.exr"), Some(&heat)).unwrap();
        assert_eq!(report.max_abs, 1.0);
        assert_eq!(read_image(&heat).unwrap().width, 8);

        write_image(&Film::new(4, 4), &dir.join("small.png")).unwrap();
        let err = run_diff(&dir.join("a.png"), &dir.join("small.png"), None).unwrap_err();
        assert_eq!(err.exit_code(), 3);
        let msg = err.to_string();
        assert!(
            msg.contains("small.png") && msg.contains("8x8 vs 4x4"),
            "{msg}"
        );
        let err = run_diff(&dir.join("absent.png"), &dir.join("a.png"), None).unwrap_err();
        assert_eq!(err.exit_code(), 2);
        let msg = err.to_string();
        assert_eq!(msg.matches("absent.png").count(), 1, "{msg}");
        assert_eq!(msg.matches("No such file").count(), 1, "{msg}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
