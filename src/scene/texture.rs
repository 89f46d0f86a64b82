//! Images for texture and bump maps: decoded in Rust (PNG, JPEG through the `image`
//! crate) when a script names them, so Lua itself never opens a file. Texels are kept as
//! stored (8-bit RGBA, no gamma decoding): the scene language's colours are linear values
//! written as computed, so a texture on a fully lit matte surface reproduces itself.

use super::files::{read_regular, MAX_FILE_BYTES};
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

/// Reads and decodes `path`, a regular file of at most [`MAX_FILE_BYTES`]. The size in the
/// header is checked before decoding: each side at most [`MAX_TEXTURE_SIDE`], the decoded
/// texels at most `max_bytes`, and a JPEG must be long enough to hold that many pixels
/// (a 700-byte file claiming 8000×8000 is a truncated or forged one). Errors name the
/// path that was tried and what went wrong.
pub fn load_texture(path: &Path, max_bytes: u64) -> Result<Texture, String> {
    let bytes = read_regular(path, "texture", MAX_FILE_BYTES)?;
    let reader = || {
        image::ImageReader::new(Cursor::new(&bytes[..]))
            .with_guessed_format()
            .map_err(|e| format!("cannot read texture '{}': {e}", path.display()))
    };
    let format = reader()?.format();
    let (width, height) = reader()?
        .into_dimensions()
        .map_err(|e| format!("cannot decode texture '{}': {e}", path.display()))?;
    if width == 0 || height == 0 || width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
        return Err(format!(
            "texture '{}' is {width}×{height}; sides must be from 1 to {MAX_TEXTURE_SIDE}",
            path.display()
        ));
    }
    if format == Some(image::ImageFormat::Jpeg) {
        check_jpeg_length(path, bytes.len() as u64, width, height)?;
    }
    let needed = texture_bytes(width, height);
    if needed > max_bytes {
        return Err(format!(
            "texture '{}' is {width}×{height} ({} MiB decoded), over the {} MiB left of the memory limit (--memory-limit MIB)",
            path.display(),
            needed.div_ceil(1 << 20),
            max_bytes >> 20
        ));
    }
    let mut reader = reader()?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(width);
    limits.max_image_height = Some(height);
    // The decoder's own buffers: the image in its stored layout, then the RGBA copy.
    limits.max_alloc = Some(2 * needed + (1 << 20));
    reader.limits(limits);
    let image = reader
        .decode()
        .map_err(|e| format!("cannot decode texture '{}': {e}", path.display()))?
        .to_rgba8();
    Ok(Texture {
        path: path.to_path_buf(),
        width,
        height,
        rgba: image.pixels().map(|p| p.0).collect(),
    })
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
            path.display()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_and_undecodable_files_name_the_path() {
        let dir = crate::testing::scratch::temp_dir("texture");
        let missing = dir.join("missing.png");
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
