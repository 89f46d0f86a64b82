//! Images for texture and bump maps: decoded in Rust (PNG, JPEG through the `image`
//! crate) when a script names them, so Lua itself never opens a file. Texels are kept as
//! stored (8-bit RGBA, no gamma decoding): the scene language's colours are linear values
//! written as computed, so a texture on a fully lit matte surface reproduces itself.

use super::files::{read_regular, Opened, MAX_FILE_BYTES};
use std::io::Cursor;
use std::path::{Path, PathBuf};

/// Index of a texture in [`SceneGraph::textures`](super::SceneGraph::textures).
pub type TextureId = usize;

/// Largest texture side accepted (a guard against absurd images, not a GPU limit).
pub const MAX_TEXTURE_SIDE: u32 = 1 << 14;

/// A decoded image: RGBA8 texels, row-major from the image's top row.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// The file it came from (for messages).
    pub path: PathBuf,
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<[u8; 4]>,
}

/// Bytes a texture of `width`×`height` holds once decoded (RGBA8).
pub fn texture_bytes(width: u32, height: u32) -> u64 {
    4 * u64::from(width) * u64::from(height)
}

/// The texture formats glint reads, told by content (never by the file's name: a file
/// named `t.png` that holds an OpenEXR is refused, not handed to another decoder).
pub fn texture_format(bytes: &[u8]) -> Option<image::ImageFormat> {
    if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        Some(image::ImageFormat::Png)
    } else if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
        Some(image::ImageFormat::Jpeg)
    } else {
        None
    }
}

/// Reads and decodes `path`, a regular file of at most [`MAX_FILE_BYTES`] holding a PNG
/// or a JPEG (by content). Everything is counted before it is decoded against
/// `max_bytes`: the decoder's reading of the header (a PNG's ICC profile and text
/// chunks), then, from the header's size and colour type, the decoded image, its RGBA
/// copy and the texels kept. Each side is at most [`MAX_TEXTURE_SIDE`], and a JPEG must
/// be long enough to hold the pixels its header claims (a 700-byte file claiming
/// 8000×8000 is a truncated or forged one). Errors name the path and what went wrong.
pub fn load_texture(path: &Path, max_bytes: u64) -> Result<Texture, String> {
    decode_texture(
        path,
        &read_regular(path, "texture", MAX_FILE_BYTES)?,
        max_bytes,
    )
}

/// [`load_texture`] for a file the scene's read rule opened
/// ([`ReadPolicy::open`](super::files::ReadPolicy::open)).
pub fn load_opened_texture(file: Opened, max_bytes: u64) -> Result<Texture, String> {
    let path = file.path.clone();
    decode_texture(&path, &file.read("texture", MAX_FILE_BYTES)?, max_bytes)
}

/// Decodes the bytes of the texture file `path` (see [`load_texture`]).
fn decode_texture(path: &Path, bytes: &[u8], max_bytes: u64) -> Result<Texture, String> {
    let format = texture_format(bytes).ok_or_else(|| {
        format!(
            "cannot decode texture '{}': not a PNG or JPEG image (by its content); textures are PNG or JPEG",
            crate::display_path::shown(path)
        )
    })?;
    let cannot = |e: image::ImageError| {
        format!(
            "cannot decode texture '{}': {e}",
            crate::display_path::shown(path)
        )
    };
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_TEXTURE_SIDE);
    limits.max_image_height = Some(MAX_TEXTURE_SIDE);
    limits.max_alloc = Some(max_bytes);
    let mut reader = image::ImageReader::with_format(Cursor::new(bytes), format);
    reader.limits(limits.clone());
    let decoder = reader.into_decoder().map_err(|e| match e {
        image::ImageError::Limits(_) => over_budget(path, "its header", max_bytes),
        e => cannot(e),
    })?;
    let (width, height) = image::ImageDecoder::dimensions(&decoder);
    if width == 0 || height == 0 || width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
        return Err(format!(
            "texture '{}' is {width}×{height}; sides must be from 1 to {MAX_TEXTURE_SIDE}",
            crate::display_path::shown(path)
        ));
    }
    if format == image::ImageFormat::Jpeg {
        check_jpeg_length(path, bytes.len() as u64, width, height)?;
    }
    let pixels = u64::from(width) * u64::from(height);
    let stored = pixels * u64::from(image::ImageDecoder::color_type(&decoder).bytes_per_pixel());
    // The decoded image, its RGBA copy, the texels kept.
    let needed = stored + 2 * texture_bytes(width, height);
    if needed > max_bytes {
        return Err(over_budget(
            path,
            &format!(
                "{width}×{height} ({} MiB decoded)",
                needed.div_ceil(1 << 20)
            ),
            max_bytes,
        ));
    }
    let image = image::DynamicImage::from_decoder(decoder)
        .map_err(cannot)?
        .into_rgba8();
    Ok(Texture {
        path: path.to_path_buf(),
        width,
        height,
        rgba: image.pixels().map(|p| p.0).collect(),
    })
}

/// What every refusal of [`load_texture`] for the memory budget says (the caller makes
/// such a refusal a reached limit).
pub const OVER_BUDGET: &str = "left of the memory limit";

fn over_budget(path: &Path, what: &str, max_bytes: u64) -> String {
    format!(
        "texture '{}': {what} is over the {} MiB {OVER_BUDGET} (--memory-limit MIB)",
        crate::display_path::shown(path),
        max_bytes >> 20
    )
}

/// Fewest bytes a baseline JPEG of `width`×`height` can take: each 8×8 block of the
/// luma channel codes at least its DC difference and an end-of-block (2 bits each in the
/// shortest Huffman codes), i.e. 1/128 byte per pixel; a file shorter than half that
/// cannot hold the image its header claims.
fn check_jpeg_length(path: &Path, len: u64, width: u32, height: u32) -> Result<(), String> {
    let minimum = u64::from(width) * u64::from(height) / 256;
    if len < minimum {
        return Err(format!(
            "texture '{}' claims {width}×{height} pixels in a {len}-byte JPEG (at least {minimum} bytes are needed): the file is truncated or not what its header says",
            crate::display_path::shown(path)
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_and_undecodable_files_name_the_path() {
        let (dir, missing) = crate::testing::scratch::temp_file("texture", "missing.png");
        let e = load_texture(&missing, u64::MAX).unwrap_err();
        assert!(
            e.starts_with("cannot read texture '") && e.contains("missing.png"),
            "{e}"
        );
        let junk = dir.join("junk.png");
        std::fs::write(&junk, b"not an image at all").unwrap();
        let e = load_texture(&junk, u64::MAX).unwrap_err();
        assert!(e.contains("junk.png"), "{e}");
    }

    #[test]
    fn texels_are_kept_as_stored_top_row_first() {
        let dir = crate::testing::scratch::temp_dir("texture-ok");
        let path = dir.join("two.png");
        let img = image::RgbImage::from_raw(1, 2, vec![10, 20, 30, 200, 100, 0]).unwrap();
        img.save(&path).unwrap();
        let t = load_texture(&path, u64::MAX).unwrap();
        assert_eq!((t.width, t.height), (1, 2));
        assert_eq!(t.rgba, vec![[10, 20, 30, 255], [200, 100, 0, 255]]);
    }
}
