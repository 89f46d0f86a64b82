//! The digest of a render: SHA-256 over everything that determines its pixels — glint's
//! version, the tracer (the CPU, or the GPU adapter by name: tracers agree closely, not
//! bit for bit), the scene script's bytes, and the packed scene the render traces, which
//! holds the render options (size, AA, depths, background) and every file the script read
//! as it was read (meshes, textures, the environment map). Not in it: the thread count, the
//! tile or crop, the output name — nothing that changes a pixel. Tiles with one digest
//! belong together.
//!
//! A tile's record also holds [`tile_digest`]: SHA-256 over the rest of its record and its
//! pixels, which `glint assemble` recomputes, so a changed pixel, bound, label or render
//! digest is noticed (bit rot, mix-ups). It is a checksum, not a signature: whoever can
//! write a tile can compute it (docs/farm.md).

use crate::pack::PackedScene;
use sha2::{Digest, Sha256};

/// The digest as lower-case hex (64 digits).
pub fn render_digest(script: &[u8], tracer: &str, packed: &PackedScene) -> String {
    let mut h = Sha256::new();
    // Each part length-prefixed, so no two different inputs run together alike.
    let mut part = |bytes: &[u8]| {
        h.update((bytes.len() as u64).to_le_bytes());
        h.update(bytes);
    };
    part(b"glint render digest 1");
    part(env!("CARGO_PKG_VERSION").as_bytes());
    part(tracer.as_bytes());
    part(script);
    part(bytemuck::bytes_of(&packed.globals));
    part(bytemuck::cast_slice(&packed.instances));
    part(bytemuck::cast_slice(&packed.triangles));
    part(bytemuck::cast_slice(&packed.meshes));
    part(bytemuck::cast_slice(&packed.materials));
    part(bytemuck::cast_slice(&packed.lights));
    part(bytemuck::cast_slice(&packed.cell_start));
    part(bytemuck::cast_slice(&packed.cell_items));
    part(bytemuck::cast_slice(&packed.csg_program));
    part(bytemuck::cast_slice(&packed.texels));
    part(bytemuck::cast_slice(&packed.triangle_uvs));
    part(&packed.features.0.to_le_bytes());
    hex(h)
}

fn hex(h: Sha256) -> String {
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// A tile's pixels as its file holds them.
#[derive(Clone, Copy, Debug)]
pub enum TilePixels<'a> {
    /// A PNG tile's 8-bit RGB bytes, row by row.
    Rgb8(&'a [u8]),
    /// An EXR tile's floats, row by row.
    Float(&'a [[f32; 3]]),
}

/// The digest of a tile (64 hex digits): its `record` (every other text pair, in the
/// order written) and its pixels (a PNG's bytes, or an EXR's floats as little-endian
/// bits), each length-prefixed.
pub fn tile_digest(record: &[(&str, String)], pixels: TilePixels) -> String {
    let mut h = Sha256::new();
    let mut part = |bytes: &[u8]| {
        h.update((bytes.len() as u64).to_le_bytes());
        h.update(bytes);
    };
    part(b"glint tile digest 1");
    for (key, value) in record {
        part(key.as_bytes());
        part(value.as_bytes());
    }
    match pixels {
        TilePixels::Rgb8(bytes) => {
            part(b"rgb8");
            part(bytes);
        }
        TilePixels::Float(pixels) => {
            part(b"f32 rgb");
            h.update((pixels.len() as u64 * 12).to_le_bytes());
            // In rows of 4096 pixels: no copy of the whole tile.
            let mut row = Vec::with_capacity(4096 * 12);
            for chunk in pixels.chunks(4096) {
                row.clear();
                row.extend(chunk.iter().flatten().flat_map(|c| c.to_le_bytes()));
                h.update(&row);
            }
        }
    }
    hex(h)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tile_digest_covers_its_record_and_every_pixel_bit() {
        let record = vec![("glint:bounds", "0,1,0,2".to_string())];
        let floats = [[0.5, 1.0, -0.0], [2.0, 0.25, 0.0]];
        let base = tile_digest(&record, TilePixels::Float(&floats));
        assert_eq!(base.len(), 64);
        let mut flipped = floats;
        flipped[1][2] = 0.0_f32.copysign(-1.0);
        assert_ne!(tile_digest(&record, TilePixels::Float(&flipped)), base);
        let moved = vec![("glint:bounds", "1,2,0,2".to_string())];
        assert_ne!(tile_digest(&moved, TilePixels::Float(&floats)), base);
        let bytes = [1, 2, 3];
        assert_ne!(
            tile_digest(&record, TilePixels::Rgb8(&bytes)),
            tile_digest(&record, TilePixels::Rgb8(&[1, 2, 4]))
        );
    }
}
