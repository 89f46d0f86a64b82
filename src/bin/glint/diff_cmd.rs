//! `glint diff A B [--heatmap OUT]`: compare two images and print the figures.

use std::path::Path;

use glint::diff::{diff_files, DiffFilesError, DiffReport};
use glint::image_io::{write_image, ImageIoError};

/// Why `glint diff` failed; each kind has its exit code.
#[derive(Debug, thiserror::Error)]
pub enum DiffCmdError {
    /// An input is missing, unreadable or too big, or the images cannot be compared.
    #[error(transparent)]
    Files(DiffFilesError),
    /// The heat map cannot be written (exit code 4).
    #[error("{0}")]
    Output(ImageIoError),
}

impl DiffCmdError {
    pub fn exit_code(&self) -> u8 {
        match self {
            // A bad argument.
            DiffCmdError::Files(DiffFilesError::Input(_)) => 2,
            DiffCmdError::Files(DiffFilesError::Compare { .. }) => 3,
            DiffCmdError::Output(_) => 4,
        }
    }
}

/// Compares `a` (the reference) with `b`, prints the report to stdout and, if asked,
/// writes FLIP's magma heat map to `heatmap` (atomically, format by extension).
pub fn run_diff(a: &Path, b: &Path, heatmap: Option<&Path>) -> Result<DiffReport, DiffCmdError> {
    if let Some(path) = heatmap {
        glint::image_io::check_output_path(path).map_err(DiffCmdError::Output)?;
    }
    let (report, heat_map) = diff_files(a, b).map_err(DiffCmdError::Files)?;
    println!("{report}");
    if let Some(path) = heatmap {
        write_image(&heat_map, path).map_err(DiffCmdError::Output)?;
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint::film::Film;
    use glint::image_io::read_image;

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
