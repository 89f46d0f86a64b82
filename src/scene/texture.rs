//! Images for texture and bump maps: decoded in Rust (PNG, JPEG through the `image`
//! crate) when a script names them, so Lua itself never opens a file. Texels are kept as
//! stored (8-bit RGBA, no gamma decoding): the scene language's colours are linear values
//! written as computed, so a texture on a fully lit matte surface reproduces itself.

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

/// Reads and decodes `path`. Errors name the path that was tried and what went wrong.
pub fn load_texture(path: &Path) -> Result<Texture, String> {
    let image = image::ImageReader::open(path)
        .map_err(|e| format!("cannot read texture '{}': {e}", path.display()))?
        .with_guessed_format()
        .map_err(|e| format!("cannot read texture '{}': {e}", path.display()))?
        .decode()
        .map_err(|e| format!("cannot decode texture '{}': {e}", path.display()))?
        .to_rgba8();
    let (width, height) = image.dimensions();
    if width == 0 || height == 0 || width > MAX_TEXTURE_SIDE || height > MAX_TEXTURE_SIDE {
        return Err(format!(
            "texture '{}' is {width}×{height}; sides must be from 1 to {MAX_TEXTURE_SIDE}",
            path.display()
        ));
    }
    Ok(Texture {
        path: path.to_path_buf(),
        width,
        height,
        rgba: image.pixels().map(|p| p.0).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_and_undecodable_files_name_the_path() {
        let dir = std::env::temp_dir().join(format!("glint-texture-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let missing = dir.join("missing.png");
        let e = load_texture(&missing).unwrap_err();
        assert!(
            e.starts_with("cannot read texture '") && e.contains("missing.png"),
            "{e}"
        );
        let junk = dir.join("junk.png");
        std::fs::write(&junk, b"not an image at all").unwrap();
        let e = load_texture(&junk).unwrap_err();
        assert!(e.contains("junk.png"), "{e}");
    }

    #[test]
    fn texels_are_kept_as_stored_top_row_first() {
        let dir = std::env::temp_dir().join(format!("glint-texture-ok-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("two.png");
        let img = image::RgbImage::from_raw(1, 2, vec![10, 20, 30, 200, 100, 0]).unwrap();
        img.save(&path).unwrap();
        let t = load_texture(&path).unwrap();
        assert_eq!((t.width, t.height), (1, 2));
        assert_eq!(t.rgba, vec![[10, 20, 30, 255], [200, 100, 0, 255]]);
    }
}
