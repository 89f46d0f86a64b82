//! The digest of a render: SHA-256 over everything that determines its pixels — glint's
//! version, the tracer (the CPU, or the GPU adapter by name: tracers agree closely, not
//! bit for bit), the scene script's bytes, and the packed scene the render traces, which
//! holds the render options (size, AA, depths, background) and every file the script read
//! as it was read (meshes, textures). Not in it: the thread count, the tile or crop, the
//! output name — nothing that changes a pixel. Tiles with one digest belong together.

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
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}
