//! Image files read as a hostile one could be made: the decoder is chosen by content
//! (never by the name: a `t.png` that holds an OpenEXR is read as the EXR it is, within
//! EXR's checks), only regular files are read (a FIFO would block), and the size in the
//! header is checked before any decoder allocates for it. OpenEXR's header is read
//! here first, since the decoder sizes its tables from the data window before any limit
//! applies: a 359-byte file can claim a window that makes it allocate 275 GB.

use std::io::Cursor;
use std::path::Path;

use image::{ImageDecoder, ImageFormat, ImageReader};

use crate::scene::files::read_regular;

/// Largest image file read (the same cap as a scene's files).
pub const MAX_IMAGE_FILE_BYTES: u64 = 1 << 30;

/// The format of an image file's bytes, by their magic number.
pub fn sniff(bytes: &[u8]) -> Option<ImageFormat> {
    if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        Some(ImageFormat::Png)
    } else if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
        Some(ImageFormat::Jpeg)
    } else if bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        Some(ImageFormat::OpenExr)
    } else {
        None
    }
}

/// A decoder for the image `bytes` hold (PNG, JPEG or EXR by content) whose header
/// claims at most `max_pixels`, allocating at most `max_alloc` bytes; errors say why.
pub fn checked_decoder<'a>(
    bytes: &'a [u8],
    max_pixels: u64,
    max_alloc: u64,
) -> Result<(impl ImageDecoder + 'a, u32, u32), String> {
    let format = sniff(bytes).ok_or("not a PNG, JPEG or OpenEXR image (by its content)")?;
    if format == ImageFormat::OpenExr {
        let (w, h) = exr_window(bytes)?;
        if w * h > max_pixels {
            return Err(format!(
                "the image is {w}x{h}, over the limit of {max_pixels} pixels"
            ));
        }
    }
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(max_alloc);
    let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
    reader.limits(limits);
    let decoder = reader.into_decoder().map_err(|e| e.to_string())?;
    let (w, h) = decoder.dimensions();
    if u64::from(w) * u64::from(h) > max_pixels {
        return Err(format!(
            "the image is {w}x{h}, over the limit of {max_pixels} pixels"
        ));
    }
    Ok((decoder, w, h))
}

/// Reads a regular file of at most [`MAX_IMAGE_FILE_BYTES`] (FIFOs and devices refused
/// without blocking).
pub fn read_image_file(path: &Path) -> Result<Vec<u8>, String> {
    read_regular(path, "image", MAX_IMAGE_FILE_BYTES)
}

/// The data window (width, height) of an OpenEXR header, refusing what glint's decoder
/// could be made to over-allocate for: several parts, deep data, tiles under 16×16.
pub fn exr_window(bytes: &[u8]) -> Result<(u64, u64), String> {
    let bad = |why: &str| format!("not a usable OpenEXR file: {why}");
    let version = u32::from_le_bytes(
        bytes
            .get(4..8)
            .ok_or_else(|| bad("truncated"))?
            .try_into()
            .unwrap(),
    );
    if version & 0x1800 != 0 {
        return Err(bad("several parts or deep data are not supported"));
    }
    let mut at = 8;
    let mut window = None;
    loop {
        let name = c_string(bytes, &mut at).ok_or_else(|| bad("truncated header"))?;
        if name.is_empty() {
            break;
        }
        let kind = c_string(bytes, &mut at).ok_or_else(|| bad("truncated header"))?;
        let size = bytes
            .get(at..at + 4)
            .ok_or_else(|| bad("truncated header"))?;
        let size = i32::from_le_bytes(size.try_into().unwrap());
        at += 4;
        let value = usize::try_from(size)
            .ok()
            .and_then(|n| bytes.get(at..at.checked_add(n)?))
            .ok_or_else(|| bad("an attribute runs past the end of the file"))?;
        at += value.len();
        match (name, kind, value.len()) {
            (b"dataWindow", b"box2i", 16) => {
                let v: Vec<i64> = value
                    .chunks_exact(4)
                    .map(|c| i64::from(i32::from_le_bytes(c.try_into().unwrap())))
                    .collect();
                let (w, h) = (v[2] - v[0] + 1, v[3] - v[1] + 1);
                if w < 1 || h < 1 {
                    return Err(bad("an empty data window"));
                }
                window = Some((w as u64, h as u64));
            }
            (b"tiles", b"tiledesc", 9) => {
                let tx = u32::from_le_bytes(value[0..4].try_into().unwrap());
                let ty = u32::from_le_bytes(value[4..8].try_into().unwrap());
                if tx < 16 || ty < 16 || value[8] & 0x0F != 0 {
                    return Err(bad("tiles under 16×16 or with mip or rip levels"));
                }
            }
            _ => {}
        }
    }
    window.ok_or_else(|| bad("no data window"))
}

/// The NUL-terminated string at `*at` (at most 255 bytes), moving past it.
fn c_string<'a>(bytes: &'a [u8], at: &mut usize) -> Option<&'a [u8]> {
    let rest = bytes.get(*at..)?;
    let end = rest.iter().take(256).position(|&b| b == 0)?;
    *at += end + 1;
    Some(&rest[..end])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exr(window: [i32; 4]) -> Vec<u8> {
        let mut b = vec![0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0];
        b.extend(b"dataWindow\0box2i\0");
        b.extend(16i32.to_le_bytes());
        for v in window {
            b.extend(v.to_le_bytes());
        }
        b.push(0);
        b
    }

    #[test]
    fn forged_exr_windows_are_refused_before_decoding() {
        assert_eq!(exr_window(&exr([0, 0, 9, 4])).unwrap(), (10, 5));
        let huge = exr([-2_000_000_000, -2_000_000_000, 2_000_000_000, 2_000_000_000]);
        let e = checked_decoder(&huge, 1 << 24, 1 << 30).err().unwrap();
        assert!(e.contains("over the limit"), "{e}");
        assert!(exr_window(&exr([5, 0, 0, 0])).is_err());
        assert!(exr_window(&huge[..20]).is_err());
    }

    #[test]
    fn formats_are_told_by_content() {
        assert_eq!(sniff(b"\x89PNG\r\n\x1a\nrest"), Some(ImageFormat::Png));
        assert_eq!(sniff(&[0xFF, 0xD8, 0xFF, 0xE0]), Some(ImageFormat::Jpeg));
        assert_eq!(sniff(b"GIF89a"), None);
    }
}
