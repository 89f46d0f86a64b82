//! `glint diff A B [--heatmap OUT]`: compare two images and print the figures.

use std::path::Path;

use anyhow::Context;

use crate::diff::{diff_films, DiffReport};
use crate::image_io::{read_image, write_image};

/// Reads `a` (the reference) and `b`, prints the report to stdout and, if asked, writes
/// FLIP's magma heat map to `heatmap` (atomically, format by extension).
pub fn run_diff(a: &Path, b: &Path, heatmap: Option<&Path>) -> anyhow::Result<DiffReport> {
    let film_a = read_image(a)?;
    let film_b = read_image(b)?;
    let (report, heat_map) = diff_films(&film_a, &film_b)
        .with_context(|| format!("cannot compare {} with {}", a.display(), b.display()))?;
    println!("{report}");
    if let Some(path) = heatmap {
        write_image(&heat_map, path)?;
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::film::Film;

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
        let msg = format!("{err:#}");
        assert!(
            msg.contains("small.png") && msg.contains("8x8 vs 4x4"),
            "{msg}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
