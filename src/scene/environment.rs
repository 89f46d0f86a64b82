//! HDR environment maps (`gr.render`'s `environment` option): an equirectangular image in
//! linear RGB floats, read from an OpenEXR (`.exr`) or Radiance RGBE (`.hdr`) file. Read as
//! textures are (the scene's read rule, the memory budget charged from the header before
//! anything is decoded), and the format is checked twice: the file's name must say `.exr`
//! or `.hdr`, and its content must be what the name says.

use super::files::{Opened, MAX_FILE_BYTES};
use super::texture::MAX_TEXTURE_SIDE;
use std::io::Cursor;
use std::path::{Path, PathBuf};

/// A decoded environment map: linear RGB, row-major from the image's top row (the
/// direction straight up, `v = 0`).
#[derive(Clone, PartialEq)]
pub struct Environment {
    /// The file it came from (for messages).
    pub path: PathBuf,
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<[f32; 3]>,
}

// Millions of texels are not worth printing: the path and size say which map it is.
impl std::fmt::Debug for Environment {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "Environment({}, {}×{})",
            crate::display_path::shown(&self.path),
            self.width,
            self.height
        )
    }
}

/// Bytes an environment of `width`×`height` holds once decoded (three f32 a texel).
pub fn environment_bytes(width: u32, height: u32) -> u64 {
    12 * u64::from(width) * u64::from(height)
}

/// The formats an environment may be in, by the file's extension (lower case).
fn format_by_name(path: &Path) -> Option<image::ImageFormat> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "exr" => Some(image::ImageFormat::OpenExr),
        "hdr" => Some(image::ImageFormat::Hdr),
        _ => None,
    }
}

/// The format the bytes hold, by their magic number.
fn format_by_content(bytes: &[u8]) -> Option<image::ImageFormat> {
    if bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        Some(image::ImageFormat::OpenExr)
    } else if bytes.starts_with(b"#?RADIANCE") || bytes.starts_with(b"#?RGBE") {
        Some(image::ImageFormat::Hdr)
    } else {
        None
    }
}

/// Reads and decodes `file`, which the scene's read rule opened: an OpenEXR or Radiance
/// HDR image (by name and by content) with sides from 1 to [`MAX_TEXTURE_SIDE`] and
/// finite texels. The decoder's reading of the header, the decoded image, its RGB float
/// copy and the texels kept are all counted against `max_bytes` before they are
/// allocated. Errors name the path and what went wrong; a refusal for memory contains
/// [`OVER_BUDGET`](super::texture::OVER_BUDGET).
pub fn load_opened_environment(file: Opened, max_bytes: u64) -> Result<Environment, String> {
    let path = file.path.clone();
    let shown = crate::display_path::shown(&path);
    let named = format_by_name(&path).ok_or_else(|| {
        format!("environment '{shown}' must be an OpenEXR (.exr) or Radiance HDR (.hdr) file")
    })?;
    let bytes = file.read("environment", MAX_FILE_BYTES)?;
    let format = format_by_content(&bytes);
    if format != Some(named) {
        return Err(format!(
            "cannot decode environment '{shown}': its content is not the {} image its name says",
            if named == image::ImageFormat::Hdr {
                "Radiance HDR"
            } else {
                "OpenEXR"
            }
        ));
    }
    decode(&path, &radiance_signature(bytes), named, max_bytes)
}

/// `bytes` with a `#?RGBE` signature (Mitsuba's and others') spelt `#?RADIANCE`, the one
/// the decoder accepts: the same format under its other name.
fn radiance_signature(bytes: Vec<u8>) -> Vec<u8> {
    match bytes.strip_prefix(b"#?RGBE") {
        Some(rest) => [b"#?RADIANCE".as_slice(), rest].concat(),
        None => bytes,
    }
}

/// Decodes `bytes`, an image in `format` from `path` (see [`load_opened_environment`]).
fn decode(
    path: &Path,
    bytes: &[u8],
    format: image::ImageFormat,
    max_bytes: u64,
) -> Result<Environment, String> {
    let shown = crate::display_path::shown(path);
    let cannot = |e: image::ImageError| format!("cannot decode environment '{shown}': {e}");
    let over = |what: &str| {
        format!(
            "environment '{shown}': {what} is over the {} MiB {} (--memory-limit MIB)",
            max_bytes >> 20,
            super::texture::OVER_BUDGET
        )
    };
    // The sides are checked below, by this function, so that a forged size gets the
    // message about sides rather than the decoder's.
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(max_bytes);
    let mut reader = image::ImageReader::with_format(Cursor::new(bytes), format);
    reader.limits(limits);
    let decoder = reader.into_decoder().map_err(|e| match e {
        image::ImageError::Limits(_) => over("its header"),
        e => cannot(e),
    })?;
    let (width, height) = image::ImageDecoder::dimensions(&decoder);
    if width == 0 || height == 0 || width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
        return Err(format!(
            "environment '{shown}' is {width}×{height}; sides must be from 1 to {MAX_TEXTURE_SIDE}"
        ));
    }
    let pixels = u64::from(width) * u64::from(height);
    let stored = pixels * u64::from(image::ImageDecoder::color_type(&decoder).bytes_per_pixel());
    // The decoded image, its RGB float copy, the texels kept.
    let needed = stored + 2 * environment_bytes(width, height);
    if needed > max_bytes {
        return Err(over(&format!(
            "{width}×{height} ({} MiB decoded)",
            needed.div_ceil(1 << 20)
        )));
    }
    let image = image::DynamicImage::from_decoder(decoder)
        .map_err(cannot)?
        .into_rgb32f();
    let rgb: Vec<[f32; 3]> = image.pixels().map(|p| p.0).collect();
    if let Some(i) = rgb.iter().position(|t| t.iter().any(|c| !c.is_finite())) {
        let (x, y) = (i as u32 % width, i as u32 / width);
        return Err(format!(
            "environment '{shown}' has a value that is not a finite number at pixel ({x}, {y})"
        ));
    }
    Ok(Environment {
        path: path.to_path_buf(),
        width,
        height,
        rgb,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_are_told_by_name_and_by_content() {
        assert_eq!(
            format_by_name(Path::new("a/sky.EXR")),
            Some(image::ImageFormat::OpenExr)
        );
        assert_eq!(
            format_by_name(Path::new("sky.hdr")),
            Some(image::ImageFormat::Hdr)
        );
        assert_eq!(format_by_name(Path::new("sky.png")), None);
        assert_eq!(format_by_name(Path::new("sky")), None);
        assert_eq!(
            format_by_content(b"#?RADIANCE\n"),
            Some(image::ImageFormat::Hdr)
        );
        assert_eq!(
            format_by_content(&[0x76, 0x2f, 0x31, 0x01, 2]),
            Some(image::ImageFormat::OpenExr)
        );
        assert_eq!(format_by_content(b"\x89PNG\r\n\x1a\n"), None);
        assert_eq!(radiance_signature(b"#?RGBE\nX".to_vec()), b"#?RADIANCE\nX");
        assert_eq!(
            radiance_signature(b"#?RADIANCE\n".to_vec()),
            b"#?RADIANCE\n"
        );
    }
}
