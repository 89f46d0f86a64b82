//! Image files: PNG/EXR written atomically, read back for diffs.
//!
//! PNG (and JPEG) hold what `Film::to_rgb8` gives (clamped, no gamma), or with
//! [`OutputTransfer::Srgb`] the sRGB transfer curve applied before quantisation; EXR
//! holds the linear f32 film unclamped, always. Reading maps 8-bit channels back by `/255` with no gamma, so a PNG
//! we wrote reads back to a film that re-quantises to the same bytes.

use std::ffi::OsString;
use std::fs::File;
use std::io::{BufWriter, Seek, Write};
use std::path::{Path, PathBuf};

use image::codecs::jpeg::JpegEncoder;
use image::codecs::png::PngEncoder;
use image::{DynamicImage, ExtendedColorType, ImageEncoder};
use thiserror::Error;

use crate::atomic_write::write_via_temp_with;
pub use crate::atomic_write::{remove_temp_files_on_signals, write_via_temp, TEMP_SUFFIX_MAX};
use crate::film::Film;

/// Everything that can go wrong reading or writing an image; every message names the path.
#[derive(Debug, Error)]
pub enum ImageIoError {
    #[error(
        "cannot write {}: unsupported extension (supported: {SUPPORTED_EXTENSIONS})",
        crate::display_path::shown(path)
    )]
    UnsupportedExtension { path: PathBuf },
    #[error("cannot write {}: the name is {len} bytes; with the temporary file's suffix ({TEMP_SUFFIX_MAX} bytes) it passes the file system's limit of {max} bytes per name", crate::display_path::shown(path))]
    NameTooLong {
        path: PathBuf,
        len: usize,
        max: usize,
    },
    #[error(
        "cannot write {}: directory {} does not exist",
        crate::display_path::shown(path),
        crate::display_path::shown(dir)
    )]
    MissingDirectory { path: PathBuf, dir: PathBuf },
    #[error(
        "cannot write {}: film is {width}x{height} but holds {len} pixels",
        crate::display_path::shown(path)
    )]
    MalformedFilm {
        path: PathBuf,
        width: u32,
        height: u32,
        len: usize,
    },
    #[error("cannot write {}: {source}", crate::display_path::shown(path))]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot read image {}: {source}", crate::display_path::shown(path))]
    Read {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot encode {}: {source}", crate::display_path::shown(path))]
    Encode {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    #[error("cannot encode {}: {source}", crate::display_path::shown(path))]
    EncodeExr {
        path: PathBuf,
        #[source]
        source: exr::error::Error,
    },
    /// `message` names the path.
    #[error("{message}")]
    Unreadable { path: PathBuf, message: String },
    #[error("cannot read image {}: {source}", crate::display_path::shown(path))]
    Decode {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
}

/// The output extensions glint writes, for messages.
pub const SUPPORTED_EXTENSIONS: &str = ".png, .exr, .jpg, .jpeg";

/// JPEG quality of `.jpg` outputs (1–100): high, since a render is the product.
const JPEG_QUALITY: u8 = 95;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Png,
    Exr,
    Jpeg,
}

fn format_for(path: &Path) -> Option<Format> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "png" => Some(Format::Png),
        "exr" => Some(Format::Exr),
        "jpg" | "jpeg" => Some(Format::Jpeg),
        _ => None,
    }
}

/// Whether `path`'s extension is one glint writes (checked before a script runs).
pub fn is_supported_output(path: &Path) -> bool {
    format_for(path).is_some()
}

/// Whether `path` is written as float EXR, which keeps the film linear whatever the
/// [`OutputTransfer`].
pub fn is_float_output(path: &Path) -> bool {
    format_for(path) == Some(Format::Exr)
}

/// How the linear film is encoded into 8-bit outputs (`--output-transfer`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum OutputTransfer {
    /// The film's values as they are, clamped and quantised (A4's convention; the goldens).
    #[default]
    Linear,
    /// The sRGB transfer curve (IEC 61966-2-1) applied before quantisation: a
    /// display-referred image, as pbrt or Cycles write one.
    Srgb,
}

impl OutputTransfer {
    /// The choices, for messages.
    pub const CHOICES: &'static str = "linear or srgb";

    /// `linear` or `srgb` (any case).
    pub fn parse(s: &str) -> Result<OutputTransfer, String> {
        match s.to_ascii_lowercase().as_str() {
            "linear" => Ok(OutputTransfer::Linear),
            "srgb" => Ok(OutputTransfer::Srgb),
            _ => Err(format!("expected {}, got '{s}'", OutputTransfer::CHOICES)),
        }
    }

    /// The film's 8-bit RGB bytes under this transfer.
    fn rgb8(self, film: &Film) -> Vec<u8> {
        match self {
            OutputTransfer::Linear => film.to_rgb8(),
            OutputTransfer::Srgb => film
                .pixels
                .iter()
                .flat_map(|p| p.map(|c| crate::film::quantize_channel(srgb_encode(c))))
                .collect(),
        }
    }
}

/// The sRGB transfer curve of a linear value (clamped to [0, 1] first; NaN stays NaN,
/// which quantises to 0 as in the linear encoding).
pub fn srgb_encode(c: f32) -> f32 {
    if c.is_nan() {
        return c;
    }
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Checks that `path` can be written (known extension, existing directory) without
/// writing it: a render can fail fast instead of after minutes of work.
pub fn check_output_path(path: &Path) -> Result<(), ImageIoError> {
    output_target(path).map(|_| ())
}

/// Format, directory and file name of an output path, or why it cannot be written.
fn output_target(path: &Path) -> Result<(Format, PathBuf, OsString), ImageIoError> {
    let unsupported = || ImageIoError::UnsupportedExtension {
        path: path.to_path_buf(),
    };
    let format = format_for(path).ok_or_else(unsupported)?;
    let file_name = path.file_name().ok_or_else(unsupported)?.to_os_string();
    // `Path::parent` of a bare file name is "", meaning the current directory.
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if !dir.is_dir() {
        return Err(ImageIoError::MissingDirectory {
            path: path.to_path_buf(),
            dir,
        });
    }
    if !writable_dir(&dir) {
        return Err(ImageIoError::Io {
            path: path.to_path_buf(),
            source: std::io::Error::from(std::io::ErrorKind::PermissionDenied),
        });
    }
    let max = name_max(&dir);
    if file_name.len() + TEMP_SUFFIX_MAX > max {
        return Err(ImageIoError::NameTooLong {
            path: path.to_path_buf(),
            len: file_name.len(),
            max,
        });
    }
    Ok((format, dir, file_name))
}

/// Whether this process may create files in `dir` (checked before a render, so that a
/// folder it cannot write fails at once, not after the render).
fn writable_dir(dir: &Path) -> bool {
    use std::os::unix::ffi::OsStrExt;
    let Ok(c) = std::ffi::CString::new(dir.as_os_str().as_bytes()) else {
        return false;
    };
    // SAFETY: a valid NUL-terminated path; access only reads it.
    unsafe { libc::access(c.as_ptr(), libc::W_OK | libc::X_OK) == 0 }
}

/// The longest file name the file system holding `dir` takes (255 where it cannot tell).
fn name_max(dir: &Path) -> usize {
    use std::os::unix::ffi::OsStrExt;
    let Ok(c) = std::ffi::CString::new(dir.as_os_str().as_bytes()) else {
        return 255;
    };
    // SAFETY: a valid NUL-terminated path; pathconf only reads it.
    let n = unsafe { libc::pathconf(c.as_ptr(), libc::_PC_NAME_MAX) };
    if n > 0 {
        n as usize
    } else {
        255
    }
}

/// Writes `film` to `path`, format chosen by extension (`.png` 8-bit RGB, `.exr` f32 RGB,
/// `.jpg` 8-bit RGB), linear ([`write_image_with`] for the sRGB transfer).
pub fn write_image(film: &Film, path: &Path) -> Result<(), ImageIoError> {
    write_image_with(film, path, OutputTransfer::Linear)
}

/// [`write_image`] with the 8-bit formats encoded by `transfer` (EXR stays linear).
///
/// Atomic ([`crate::atomic_write`]): the image goes to a hidden temp file in the
/// target's directory, created exclusively under an unpredictable name, and is renamed
/// over `path` only once complete; on any failure or ending signal the temp file is
/// removed. A reader therefore sees
/// either the old file or the whole new one, never a truncated image.
pub fn write_image_with(
    film: &Film,
    path: &Path,
    transfer: OutputTransfer,
) -> Result<(), ImageIoError> {
    let (format, _, _) = output_target(path)?;
    let expected = film.width as usize * film.height as usize;
    if film.pixels.len() != expected {
        // Checked up front: the encoders assert on buffer length and would panic.
        return Err(ImageIoError::MalformedFilm {
            path: path.to_path_buf(),
            width: film.width,
            height: film.height,
            len: film.pixels.len(),
        });
    }

    // Everything big is allocated before the temporary file exists, so running out of
    // memory cannot strand it.
    let pixels = match format {
        Format::Png => Pixels::Rgb8(transfer.rgb8(film)),
        Format::Jpeg => Pixels::Jpeg(transfer.rgb8(film)),
        Format::Exr => Pixels::Rgb32F,
    };
    let io_err = |source| ImageIoError::Io {
        path: path.to_path_buf(),
        source,
    };
    write_via_temp_with(path, io_err, |file| {
        write_encoded(film, &pixels, path, file)
    })
}

/// The encoded-ready pixels of a film.
enum Pixels {
    Rgb8(Vec<u8>),
    /// 8-bit RGB for the JPEG encoder.
    Jpeg(Vec<u8>),
    /// The film's own floats, written as they are.
    Rgb32F,
}

/// Encodes `film` into `file` (the temporary file [`write_via_temp_with`] made).
fn write_encoded(
    film: &Film,
    pixels: &Pixels,
    path: &Path,
    file: &mut File,
) -> Result<(), ImageIoError> {
    // Errors name the output, not the internal temporary file.
    let io_err = |source| ImageIoError::Io {
        path: path.to_path_buf(),
        source,
    };
    let encode_err = |source| ImageIoError::Encode {
        path: path.to_path_buf(),
        source,
    };
    let mut out = BufWriter::new(file);
    match pixels {
        Pixels::Rgb8(rgb) => PngEncoder::new(&mut out)
            .write_image(rgb, film.width, film.height, ExtendedColorType::Rgb8)
            .map_err(encode_err)?,
        Pixels::Jpeg(rgb) => JpegEncoder::new_with_quality(&mut out, JPEG_QUALITY)
            .write_image(rgb, film.width, film.height, ExtendedColorType::Rgb8)
            .map_err(encode_err)?,
        Pixels::Rgb32F => {
            write_exr_layer(film, Default::default(), &mut out).map_err(|source| {
                ImageIoError::EncodeExr {
                    path: path.to_path_buf(),
                    source,
                }
            })?
        }
    }
    // (write_via_temp_with syncs the file before the rename.)
    out.flush().map_err(io_err)?;
    Ok(())
}

/// The chunk order every EXR glint writes has: increasing, so that the file's bytes are
/// the same on every run. The exr crate compresses chunks in parallel and, with the
/// order unspecified (its default, and the image crate's), writes them as they finish:
/// the same pixels in files that differed from run to run.
const EXR_ENCODING: exr::prelude::Encoding = exr::prelude::Encoding {
    line_order: exr::prelude::LineOrder::Increasing,
    ..exr::prelude::Encoding::FAST_LOSSLESS
};

/// `film` as an f32 RGB EXR of one layer with `attributes` (a render's: none; a farm
/// tile's: its record), in [`EXR_ENCODING`].
pub fn write_exr_layer(
    film: &Film,
    attributes: exr::prelude::LayerAttributes,
    out: impl Write + Seek,
) -> exr::error::UnitResult {
    use exr::prelude::{Image, Layer, SpecificChannels, Vec2, WritableImage};
    let width = film.width as usize;
    let channels = SpecificChannels::rgb(|p: Vec2<usize>| {
        let [r, g, b] = film.pixels[p.y() * width + p.x()];
        (r, g, b)
    });
    let size = (width, film.height as usize);
    let layer = Layer::new(size, attributes, EXR_ENCODING, channels);
    Image::from_layer(layer).write().to_buffered(out)
}

/// Most pixels [`read_image`] decodes (glint's own largest image).
pub const MAX_READ_PIXELS: u64 = 1 << 27;

/// Bytes per pixel a decoder may allocate while reading (float RGBA, twice).
const DECODE_BYTES_PER_PIXEL: u64 = 32;

/// Reads a PNG, JPEG or EXR (format told by content; see [`crate::image_check`]) of at
/// most [`MAX_READ_PIXELS`] into a linear film. 8-bit channels map by `/255` with no
/// gamma, the inverse of `to_rgb8`; float images are taken as-is; alpha is dropped.
pub fn read_image(path: &Path) -> Result<Film, ImageIoError> {
    read_image_within(path, MAX_READ_PIXELS, |_, _| Ok(()))
}

/// [`read_image`] of an image of at most `max_pixels`, whose size `check` may refuse
/// (with a message) before it is decoded.
pub fn read_image_within(
    path: &Path,
    max_pixels: u64,
    check: impl FnOnce(u32, u32) -> Result<(), String>,
) -> Result<Film, ImageIoError> {
    let unreadable = |message: String| ImageIoError::Unreadable {
        path: path.to_path_buf(),
        message: format!(
            "cannot read image {}: {message}",
            crate::display_path::shown(path)
        ),
    };
    let bytes =
        crate::image_check::read_image_file(path).map_err(|message| ImageIoError::Unreadable {
            path: path.to_path_buf(),
            message,
        })?;
    let max_alloc = max_pixels.saturating_mul(DECODE_BYTES_PER_PIXEL) + (64 << 20);
    let (decoder, width, height) =
        crate::image_check::checked_decoder(&bytes, max_pixels, max_alloc).map_err(unreadable)?;
    check(width, height).map_err(unreadable)?;
    let image = DynamicImage::from_decoder(decoder).map_err(|source| ImageIoError::Decode {
        path: path.to_path_buf(),
        source,
    })?;
    let pixels = match image {
        DynamicImage::ImageRgb8(_)
        | DynamicImage::ImageRgba8(_)
        | DynamicImage::ImageLuma8(_)
        | DynamicImage::ImageLumaA8(_) => image
            .into_rgb8()
            .pixels()
            .map(|p| p.0.map(|c| f32::from(c) / 255.0))
            .collect(),
        // 16-bit and float sources: image's own conversion (16-bit scales by /65535).
        other => other.into_rgb32f().pixels().map(|p| p.0).collect(),
    };
    Ok(Film {
        width,
        height,
        pixels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::scratch::file_names;
    use std::fs;

    /// A fresh scratch directory per test, under the system temp dir.
    fn scratch(name: &str) -> crate::testing::scratch::TempDir {
        crate::testing::scratch::temp_dir(&format!("image-io-{name}"))
    }

    fn gradient(width: u32, height: u32) -> Film {
        let mut film = Film::new(width, height);
        for y in 0..height {
            for x in 0..width {
                let fx = x as f32 / width as f32;
                let fy = y as f32 / height as f32;
                // Out-of-range values on purpose: EXR must keep them, PNG must clamp.
                film.set(x, y, [fx * 1.7 - 0.3, fy, 0.123_456_79 + fx * fy * 10.0]);
            }
        }
        film
    }

    #[test]
    fn png_round_trip_is_byte_exact() {
        let dir = scratch("png");
        let film = gradient(17, 9);
        let path = dir.join("out.png");
        write_image(&film, &path).unwrap();
        let back = read_image(&path).unwrap();
        assert_eq!((back.width, back.height), (17, 9));
        assert_eq!(back.to_rgb8(), film.to_rgb8());
        // Reading is exactly /255, no gamma.
        assert_eq!(back.pixels[0][0], f32::from(film.to_rgb8()[0]) / 255.0);
        assert_eq!(file_names(&dir), vec!["out.png"]);
    }

    #[test]
    fn exr_round_trip_is_float_exact() {
        let dir = scratch("exr");
        let mut film = gradient(13, 7);
        film.set(3, 2, [1.0e6, -2.5, 1.0e-20]);
        let path = dir.join("out.EXR");
        write_image(&film, &path).unwrap();
        let back = read_image(&path).unwrap();
        assert_eq!(back, film);
        assert_eq!(file_names(&dir), vec!["out.EXR"]);
    }

    /// The same film gives the same EXR bytes every time (the determinism rule, for
    /// files): with the exr crate's default chunk order its parallel compression wrote the
    /// 64×64 tiles as they finished.
    #[test]
    fn an_exr_is_the_same_bytes_every_time() {
        let dir = scratch("exr-bytes");
        let mut film = gradient(640, 384);
        for (i, p) in film.pixels.iter_mut().enumerate() {
            // Tiles that compress differently, so that they finish at different times.
            let noise = (i as u32).wrapping_mul(2_654_435_761) >> 8;
            if (i / 640 / 64 + i % 640 / 64) % 2 == 0 {
                p[0] = noise as f32;
            }
        }
        let path = dir.join("out.exr");
        write_image(&film, &path).unwrap();
        let first = fs::read(&path).unwrap();
        for run in 1..12 {
            write_image(&film, &path).unwrap();
            assert!(
                fs::read(&path).unwrap() == first,
                "write {run} differs from write 0"
            );
        }
        assert_eq!(read_image(&path).unwrap(), film);
    }

    #[test]
    fn overwrite_replaces_existing_file() {
        let dir = scratch("overwrite");
        let path = dir.join("a.png");
        write_image(&Film::new(2, 2), &path).unwrap();
        let mut white = Film::new(3, 1);
        white.pixels.fill([1.0; 3]);
        write_image(&white, &path).unwrap();
        assert_eq!(read_image(&path).unwrap(), white);
        assert_eq!(file_names(&dir), vec!["a.png"]);
    }

    #[test]
    fn missing_directory_fails_and_leaves_nothing() {
        let dir = scratch("missing");
        let missing = dir.join("nope");
        let err = write_image(&Film::new(2, 2), &missing.join("x.png")).unwrap_err();
        assert!(matches!(err, ImageIoError::MissingDirectory { .. }));
        assert!(
            err.to_string().contains(&missing.display().to_string()),
            "{err}"
        );
        assert!(!missing.exists());
        assert!(file_names(&dir).is_empty());
    }

    #[test]
    fn unknown_extension_fails_and_leaves_nothing() {
        let dir = scratch("ext");
        for name in ["x.bmp", "x", "x.png.bak"] {
            let path = dir.join(name);
            let err = write_image(&Film::new(2, 2), &path).unwrap_err();
            let msg = err.to_string();
            assert!(msg.contains(".png") && msg.contains(".exr"), "{msg}");
            assert!(msg.contains(name), "{msg}");
        }
        assert!(file_names(&dir).is_empty());
    }

    #[test]
    fn failed_encode_removes_temp_file() {
        let dir = scratch("badfilm");
        let mut film = Film::new(4, 4);
        film.pixels.pop();
        let err = write_image(&film, &dir.join("x.exr")).unwrap_err();
        assert!(matches!(err, ImageIoError::MalformedFilm { .. }));
        // A zero-sized PNG is rejected by the encoder after the temp file exists.
        assert!(write_image(&Film::new(0, 0), &dir.join("y.png")).is_err());
        assert!(file_names(&dir).is_empty());
    }

    #[test]
    fn read_errors_name_the_path() {
        let dir = scratch("read");
        let missing = dir.join("absent.png");
        let err = read_image(&missing).unwrap_err();
        assert!(err.to_string().contains("absent.png"), "{err}");
        let junk = dir.join("junk.png");
        fs::write(&junk, b"not an image").unwrap();
        let err = read_image(&junk).unwrap_err();
        assert!(err.to_string().contains("junk.png"), "{err}");
    }
}
