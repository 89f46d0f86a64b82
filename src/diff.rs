//! Image comparison for `glint diff` and golden-image tests: RMSE, PSNR, max difference
//! and NVIDIA's FLIP, plus a FLIP heat map; of films, or of two image files.
//!
//! Pixel metrics are taken on values clamped to [0,1] (NaN as 0), i.e. on what a PNG of
//! the film shows, so a diff of two renders agrees with a diff of their PNGs up to 8-bit
//! quantisation. FLIP runs on the 8-bit images themselves.

use std::fmt;
use std::path::{Path, PathBuf};

use thiserror::Error;

use crate::film::Film;
use crate::image_io::{read_image_within, write_image, MAX_READ_PIXELS};

/// FLIP's default viewing setup (0.7 m from a 0.7 m wide 4K monitor).
pub const PIXELS_PER_DEGREE: f32 = 67.0;

/// Slack for "within `tol`" tests: per-pixel differences of 8-bit-derived values are
/// k/255 computed in floating point, and may land a few ulps above `k as f32 / 255.0`.
/// Far below one 8-bit step (~0.0039), so it never admits a larger step.
const WITHIN_EPSILON: f32 = 1e-6;

#[derive(Debug, Error, PartialEq, Eq)]
pub enum DiffError {
    #[error("image sizes differ: {a_width}x{a_height} vs {b_width}x{b_height}")]
    SizeMismatch {
        a_width: u32,
        a_height: u32,
        b_width: u32,
        b_height: u32,
    },
    #[error("malformed film: {width}x{height} but {len} pixels")]
    MalformedFilm { width: u32, height: u32, len: usize },
    #[error("images of {width}x{height} are over the {limit} pixels FLIP can compare here (its error maps would not fit in memory)")]
    TooLarge { width: u32, height: u32, limit: u64 },
}

/// Most pixels a comparison may have: FLIP's C++ keeps about a dozen float images of
/// the input's size (colour and feature pipelines, filters), and does not survive an
/// allocation failure.
pub const MAX_DIFF_PIXELS: u64 = 1 << 24;

/// The figures of one comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct DiffReport {
    /// Root-mean-square difference over all channels, in [0,1] units.
    pub rmse: f64,
    /// Peak signal-to-noise ratio in dB for peak 1.0; `f64::INFINITY` when identical.
    pub psnr: f64,
    /// Largest per-channel |a-b| in [0,1] units.
    pub max_abs: f64,
    /// Mean of FLIP's per-pixel error map (0 = identical, 1 = maximal).
    pub flip_mean: f64,
    /// Per pixel, the largest channel |a-b|, row-major, top row first.
    pub max_abs_per_pixel: Vec<f32>,
}

impl DiffReport {
    /// Share (0..=1) of pixels whose largest channel difference is at most `tol`
    /// (in [0,1] units, e.g. `2.0 / 255.0`). An empty image counts as fully within.
    pub fn share_within(&self, tol: f32) -> f64 {
        if self.max_abs_per_pixel.is_empty() {
            return 1.0;
        }
        let within = self
            .max_abs_per_pixel
            .iter()
            .filter(|&&d| d <= tol + WITHIN_EPSILON)
            .count();
        within as f64 / self.max_abs_per_pixel.len() as f64
    }
}

impl fmt::Display for DiffReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "RMSE {:.5}", self.rmse)?;
        if self.psnr.is_infinite() {
            writeln!(f, "PSNR inf dB")?;
        } else {
            writeln!(f, "PSNR {:.1} dB", self.psnr)?;
        }
        writeln!(
            f,
            "max difference {:.0}/255 ({:.4})",
            self.max_abs * 255.0,
            self.max_abs
        )?;
        writeln!(f, "FLIP mean {:.4}", self.flip_mean)?;
        // Floored, so "100.00%" is only printed when every pixel is within.
        let percent = (self.share_within(2.0 / 255.0) * 10_000.0).floor() / 100.0;
        write!(f, "pixels within 2/255: {percent:.2}%")
    }
}

/// What a PNG shows of one channel: clamped to [0,1], NaN as 0 (as `quantize_channel`).
fn shown(c: f32) -> f32 {
    if c.is_nan() {
        0.0
    } else {
        c.clamp(0.0, 1.0)
    }
}

/// Refuses images over [`MAX_DIFF_PIXELS`].
pub fn check_diff_size(width: u32, height: u32) -> Result<(), DiffError> {
    if u64::from(width) * u64::from(height) > MAX_DIFF_PIXELS {
        return Err(DiffError::TooLarge {
            width,
            height,
            limit: MAX_DIFF_PIXELS,
        });
    }
    Ok(())
}

/// Why two image files cannot be compared ([`diff_files`]).
#[derive(Debug, Error)]
pub enum DiffFilesError {
    /// An input is missing, unreadable or too big (the message names the file).
    #[error("{0}")]
    Input(String),
    /// The images cannot be compared (sizes differ, or a film is malformed).
    #[error("cannot compare {a} with {b}: {error}")]
    Compare {
        a: String,
        b: String,
        error: DiffError,
    },
}

/// Reads one input: a regular file, decoded by its content, its size checked from the
/// header before it is decoded.
fn read_diff_input(path: &Path) -> Result<Film, DiffFilesError> {
    read_image_within(path, MAX_READ_PIXELS, |w, h| {
        check_diff_size(w, h).map_err(|e| e.to_string())
    })
    .map_err(|e| DiffFilesError::Input(e.to_string()))
}

/// Reads `a` (the reference) and `b` (PNG, JPEG or EXR, by content) and compares them as
/// [`diff_films`] does: the figures and FLIP's heat map.
pub fn diff_files(a: &Path, b: &Path) -> Result<(DiffReport, Film), DiffFilesError> {
    let film_a = read_diff_input(a)?;
    let film_b = read_diff_input(b)?;
    diff_films(&film_a, &film_b).map_err(|error| DiffFilesError::Compare {
        a: crate::display_path::shown(a),
        b: crate::display_path::shown(b),
        error,
    })
}

fn check_film(film: &Film) -> Result<(), DiffError> {
    if film.pixels.len() != film.width as usize * film.height as usize {
        return Err(DiffError::MalformedFilm {
            width: film.width,
            height: film.height,
            len: film.pixels.len(),
        });
    }
    Ok(())
}

/// Compares `a` (the reference) with `b` (the test image; FLIP is not quite symmetric).
///
/// Returns the figures and FLIP's error map through its magma colour map, as a film
/// whose `to_rgb8` gives the LUT's bytes exactly.
pub fn diff_films(a: &Film, b: &Film) -> Result<(DiffReport, Film), DiffError> {
    check_diff_size(a.width, a.height)?;
    if (a.width, a.height) != (b.width, b.height) {
        return Err(DiffError::SizeMismatch {
            a_width: a.width,
            a_height: a.height,
            b_width: b.width,
            b_height: b.height,
        });
    }
    check_film(a)?;
    check_film(b)?;
    let (width, height) = (a.width, a.height);

    let mut sum_sq = 0.0f64;
    let mut max_abs = 0.0f32;
    let max_abs_per_pixel: Vec<f32> = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(pa, pb)| {
            let mut pixel_max = 0.0f32;
            for (&ca, &cb) in pa.iter().zip(pb) {
                let d = (shown(ca) - shown(cb)).abs();
                sum_sq += f64::from(d) * f64::from(d);
                pixel_max = pixel_max.max(d);
            }
            max_abs = max_abs.max(pixel_max);
            pixel_max
        })
        .collect();
    let channels = max_abs_per_pixel.len() * 3;
    let mse = if channels == 0 {
        0.0
    } else {
        sum_sq / channels as f64
    };
    let rmse = mse.sqrt();
    let psnr = if mse == 0.0 {
        f64::INFINITY
    } else {
        -10.0 * mse.log10()
    };

    let (flip_mean, heat_map) = if width == 0 || height == 0 {
        // Nothing to compare; FLIP's C++ side is not asked about empty images.
        (0.0, Film::new(width, height))
    } else {
        let reference = nv_flip::FlipImageRgb8::with_data(width, height, &a.to_rgb8());
        let test = nv_flip::FlipImageRgb8::with_data(width, height, &b.to_rgb8());
        let error_map = nv_flip::flip(reference, test, PIXELS_PER_DEGREE);
        let errors = error_map.to_vec();
        let mean = errors.iter().map(|&e| f64::from(e)).sum::<f64>() / errors.len() as f64;
        let colours = error_map.apply_color_lut(&nv_flip::magma_lut()).to_vec();
        let pixels = colours
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]].map(|v| f32::from(v) / 255.0))
            .collect();
        (
            mean,
            Film {
                width,
                height,
                pixels,
            },
        )
    };

    let report = DiffReport {
        rmse,
        psnr,
        max_abs: f64::from(max_abs),
        flip_mean,
        max_abs_per_pixel,
    };
    Ok((report, heat_map))
}

/// Golden-image check: compares `actual` against `expected` and passes when the FLIP mean
/// is at most `max_flip_mean` and at least `min_share_within_2_255` (0..=1) of pixels are
/// within 2/255.
///
/// On failure writes `<out_dir>/<name>-actual.png`, `-expected.png` and `-heatmap.png`
/// (creating `out_dir`; no heat map when sizes differ) and returns a message with the
/// figures and those paths.
pub fn assert_images_match(
    name: &str,
    actual: &Film,
    expected: &Film,
    max_flip_mean: f64,
    min_share_within_2_255: f64,
    out_dir: &Path,
) -> Result<DiffReport, String> {
    let (problem, heat_map, report) = match diff_films(expected, actual) {
        Err(e) => (e.to_string(), None, None),
        Ok((report, heat_map)) => {
            let share = report.share_within(2.0 / 255.0);
            let mut reasons = Vec::new();
            if report.flip_mean > max_flip_mean {
                reasons.push(format!(
                    "FLIP mean {:.5} > allowed {max_flip_mean}",
                    report.flip_mean
                ));
            }
            if share < min_share_within_2_255 {
                reasons.push(format!(
                    "pixels within 2/255 {:.3}% < required {:.3}%",
                    share * 100.0,
                    min_share_within_2_255 * 100.0
                ));
            }
            if reasons.is_empty() {
                return Ok(report);
            }
            (reasons.join("; "), Some(heat_map), Some(report))
        }
    };

    let mut message = format!("image `{name}` does not match: {problem}\n");
    if let Some(report) = &report {
        message.push_str(&format!("{report}\n"));
    }
    let mut outputs: Vec<(PathBuf, &Film)> = vec![
        (out_dir.join(format!("{name}-actual.png")), actual),
        (out_dir.join(format!("{name}-expected.png")), expected),
    ];
    if let Some(heat_map) = &heat_map {
        outputs.push((out_dir.join(format!("{name}-heatmap.png")), heat_map));
    }
    if let Err(e) = std::fs::create_dir_all(out_dir) {
        message.push_str(&format!(
            "could not create {}: {e}\n",
            crate::display_path::shown(out_dir)
        ));
    }
    for (path, film) in &outputs {
        match write_image(film, path) {
            Ok(()) => message.push_str(&format!("wrote {}\n", crate::display_path::shown(path))),
            Err(e) => message.push_str(&format!("could not write: {e}\n")),
        }
    }
    Err(message.trim_end().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pattern(width: u32, height: u32) -> Film {
        let mut film = Film::new(width, height);
        for y in 0..height {
            for x in 0..width {
                let v = ((x * 7 + y * 13) % 256) as f32 / 255.0;
                film.set(x, y, [v, 1.0 - v, 0.5]);
            }
        }
        film
    }

    #[test]
    fn identical_films() {
        let film = pattern(32, 24);
        let (report, heat_map) = diff_films(&film, &film).unwrap();
        assert_eq!(report.rmse, 0.0);
        assert_eq!(report.psnr, f64::INFINITY);
        assert_eq!(report.max_abs, 0.0);
        assert_eq!(report.flip_mean, 0.0);
        assert_eq!(report.share_within(0.0), 1.0);
        assert_eq!((heat_map.width, heat_map.height), (32, 24));
        let text = report.to_string();
        assert!(text.contains("PSNR inf dB"), "{text}");
        assert!(text.contains("pixels within 2/255: 100.00%"), "{text}");
        assert_eq!(text.lines().count(), 5);
    }

    #[test]
    fn one_pixel_changed() {
        let a = pattern(10, 10);
        let mut b = a.clone();
        let [r, g, bl] = b.get(4, 5);
        b.set(4, 5, [r, g + 3.0 / 255.0, bl]);
        let (report, _) = diff_films(&a, &b).unwrap();
        assert!(
            (report.max_abs - 3.0 / 255.0).abs() < 1e-6,
            "{}",
            report.max_abs
        );
        assert_eq!(report.share_within(2.0 / 255.0), 0.99);
        assert_eq!(report.share_within(3.0 / 255.0), 1.0);
        let expected_rmse = (3.0f64 / 255.0) / (300.0f64).sqrt();
        assert!((report.rmse - expected_rmse).abs() < 1e-7);
        assert!(report.psnr.is_finite() && report.psnr > 40.0);
        let text = report.to_string();
        assert!(text.contains("max difference 3/255 (0.0118)"), "{text}");
        assert!(text.contains("pixels within 2/255: 99.00%"), "{text}");
    }

    #[test]
    fn differences_are_taken_on_clamped_values() {
        let mut a = Film::new(2, 1);
        a.pixels = vec![[5.0, -1.0, f32::NAN], [0.5; 3]];
        let b = Film {
            width: 2,
            height: 1,
            pixels: vec![[1.0, 0.0, 0.0], [0.5; 3]],
        };
        let (report, _) = diff_films(&a, &b).unwrap();
        assert_eq!(report.rmse, 0.0);
    }

    #[test]
    fn visibly_different_image_has_clear_flip() {
        let a = pattern(64, 64);
        let mut b = a.clone();
        for y in 16..48 {
            for x in 16..48 {
                b.set(x, y, [1.0, 0.0, 0.0]);
            }
        }
        let (report, heat_map) = diff_films(&a, &b).unwrap();
        assert!(report.flip_mean > 0.01, "{}", report.flip_mean);
        // The heat map is not black where the images differ.
        assert_ne!(heat_map.get(32, 32), heat_map.get(0, 0));
    }

    #[test]
    fn size_mismatch() {
        let err = diff_films(&Film::new(4, 3), &Film::new(3, 4)).unwrap_err();
        assert_eq!(err.to_string(), "image sizes differ: 4x3 vs 3x4");
    }

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("glint-diff-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn assert_images_match_passes_quietly() {
        let dir = scratch("pass");
        let film = pattern(16, 16);
        let report = assert_images_match("same", &film, &film, 0.001, 0.999, &dir).unwrap();
        assert_eq!(report.flip_mean, 0.0);
        assert!(!dir.exists());
    }

    #[test]
    fn assert_images_match_writes_files_on_failure() {
        let dir = scratch("fail").join("nested");
        let expected = pattern(16, 16);
        let mut actual = expected.clone();
        actual.pixels.iter_mut().for_each(|p| p[0] = 1.0);
        let msg = assert_images_match("case", &actual, &expected, 0.001, 0.999, &dir).unwrap_err();
        for suffix in ["actual", "expected", "heatmap"] {
            let path = dir.join(format!("case-{suffix}.png"));
            assert!(path.is_file(), "{} missing", path.display());
            assert!(msg.contains(&path.display().to_string()), "{msg}");
        }
        assert!(msg.contains("FLIP mean"), "{msg}");
        let back = crate::image_io::read_image(&dir.join("case-actual.png")).unwrap();
        assert_eq!(back.to_rgb8(), actual.to_rgb8());
        let _ = std::fs::remove_dir_all(dir.parent().unwrap());
    }
}
