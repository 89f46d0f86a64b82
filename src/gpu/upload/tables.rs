//! The packed scene's arrays as textures ("tables"): instances, triangles, materials,
//! lights, cell starts and items, CSG programs, image texels, triangle UVs, mesh headers
//! and triangle normals, each a 2-D texture 2^`TABLE_ROW_BITS` texels wide that the kernel reads with
//! `textureLoad` (`src/pack/layout.wgsl`: `cell_start_at`, `load_instance`, …). Element i
//! of a one-word table is texel i; an element of a 16-byte-texel table is
//! `*_TABLE_TEXELS` consecutive texels.
//!
//! Why not storage buffers: Mesa's llvmpipe (lavapipe, glint's CI
//! GPU) loads a storage buffer with a per-lane scalar loop, one branch per lane and per
//! word, while a texel fetch is one vector gather for the 8 lanes. Measured on this
//! machine (`tools/examples/llvmpipe_loads.rs`, 2¹⁸ invocations × 256 dependent reads): a
//! 16-byte read 15.5 ns from a storage buffer against 1.8–3.1 ns as a texel, a 4-byte
//! read 5.4 ns against 3.3 ns. Hardware GPUs read both through caches; textures were the
//! usual place for traversal data in GPU ray tracers before storage buffers.

use crate::constants::TABLE_ROW_BITS;
use crate::gpu::device::context::GpuContext;
use crate::gpu::GpuError;
use bytemuck::Pod;
use std::mem::size_of;

/// Texels in a table row.
pub const TABLE_ROW: u64 = 1 << TABLE_ROW_BITS;

/// A table's texel format: one `u32` a texel, or four.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TableFormat {
    Words,
    Quads,
}

/// The texel format of each table of `SCENE_TABLE_BINDINGS` (bindings.rs), in the same
/// order: one word a texel for cell_start, cell_items, csg_program and texels, four for
/// the rest. The upload (`buffers`) and the bind group layout (`pipeline`) both read it.
pub const SCENE_TABLE_FORMATS: [TableFormat; 11] = {
    use TableFormat::{Quads, Words};
    [
        Quads, Quads, Quads, Quads, Words, Words, Words, Words, Quads, Quads, Quads,
    ]
};

impl TableFormat {
    fn texture_format(self) -> wgpu::TextureFormat {
        match self {
            TableFormat::Words => wgpu::TextureFormat::R32Uint,
            TableFormat::Quads => wgpu::TextureFormat::Rgba32Uint,
        }
    }

    fn texel_bytes(self) -> u64 {
        match self {
            TableFormat::Words => 4,
            TableFormat::Quads => 16,
        }
    }

    /// Texels that `words` u32 words take.
    pub fn texels(self, words: usize) -> u64 {
        (words as u64).div_ceil(self.texel_bytes() / 4)
    }
}

/// Rows a table of `texels` texels takes (at least one: a binding may not be empty).
pub fn table_rows(texels: u64) -> u64 {
    texels.div_ceil(TABLE_ROW).max(1)
}

/// Fails with [`GpuError::TableTooLarge`] when a table of `texels` texels needs more rows
/// than the adapter's 2-D textures may have (or its rows are wider than they may be).
pub fn check_table(
    limits: &wgpu::Limits,
    array: &'static str,
    texels: u64,
) -> Result<(), GpuError> {
    let rows = table_rows(texels);
    let limit = limits.max_texture_dimension_2d as u64;
    if rows > limit || TABLE_ROW > limit {
        return Err(GpuError::TableTooLarge {
            array,
            texels,
            rows,
            row: TABLE_ROW,
            limit,
        });
    }
    Ok(())
}

/// `elements` as table texels: each element's words followed by zero words up to
/// `texels` 16-byte texels (triangles: p0.xyz p1.x | p1.yz p2.xy | p2.z and three zeros;
/// triangle UVs: uv0 uv1 | uv2 and two zeros).
pub fn padded_texels<T: Pod>(elements: &[T], texels: u32) -> Vec<u32> {
    let words = texels as usize * 4;
    assert!(
        size_of::<T>() <= words * 4,
        "an element wider than its texels"
    );
    let mut out = Vec::with_capacity(elements.len() * words);
    for element in elements {
        let start = out.len();
        out.extend_from_slice(bytemuck::cast_slice::<T, u32>(std::slice::from_ref(
            element,
        )));
        out.resize(start + words, 0);
    }
    out
}

/// A table texture holding `words` (the element bytes as u32 words, in order), padded
/// with zeros to whole rows; the view the bind group binds.
pub fn upload_table(
    ctx: &GpuContext,
    name: &'static str,
    format: TableFormat,
    words: &[u32],
) -> wgpu::TextureView {
    let words_per_texel = (format.texel_bytes() / 4) as usize;
    let rows = table_rows(format.texels(words.len()));
    let mut data = vec![0u32; (rows * TABLE_ROW) as usize * words_per_texel];
    data[..words.len()].copy_from_slice(words);
    let texture = wgpu::util::DeviceExt::create_texture_with_data(
        &ctx.device,
        &ctx.queue,
        &wgpu::TextureDescriptor {
            label: Some(name),
            size: wgpu::Extent3d {
                width: TABLE_ROW as u32,
                height: rows as u32,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: format.texture_format(),
            // Either binding: sampled, or read-only storage (KernelConfig::storage_tables).
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::STORAGE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(&data),
    );
    texture.create_view(&wgpu::TextureViewDescriptor::default())
}

/// The bind group layout entry of a table of `format` at `binding`: a sampled texture,
/// or with `storage` a read-only storage texture (`KernelConfig::storage_tables`).
pub fn table_layout_entry(
    binding: u32,
    format: TableFormat,
    storage: bool,
) -> wgpu::BindGroupLayoutEntry {
    let ty = if storage {
        wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::ReadOnly,
            format: format.texture_format(),
            view_dimension: wgpu::TextureViewDimension::D2,
        }
    } else {
        wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Uint,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        }
    };
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty,
        count: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::{TRIANGLE_TABLE_TEXELS, TRIANGLE_UV_TABLE_TEXELS};
    use crate::pack::layout::{PackedTriangle, PackedTriangleUv};

    #[test]
    fn struct_tables_hold_each_element_in_whole_texels() {
        use crate::constants::*;
        use crate::pack::layout::*;
        use std::mem::size_of;
        // The WGSL loaders read exactly these texels per element (src/pack/layout.wgsl).
        assert_eq!(
            size_of::<PackedInstance>(),
            INSTANCE_TABLE_TEXELS as usize * 16
        );
        assert_eq!(size_of::<PackedMesh>(), MESH_TABLE_TEXELS as usize * 16);
        assert_eq!(
            size_of::<PackedMaterial>(),
            MATERIAL_TABLE_TEXELS as usize * 16
        );
        assert_eq!(size_of::<PackedLight>(), LIGHT_TABLE_TEXELS as usize * 16);
        // The padded ones: the padding is less than a texel.
        let triangle = TRIANGLE_TABLE_TEXELS as usize * 16;
        assert!(
            size_of::<PackedTriangle>() <= triangle && triangle - size_of::<PackedTriangle>() < 16
        );
        let uv = TRIANGLE_UV_TABLE_TEXELS as usize * 16;
        assert!(size_of::<PackedTriangleUv>() <= uv && uv - size_of::<PackedTriangleUv>() < 16);
        let normals = TRIANGLE_NORMAL_TABLE_TEXELS as usize * 16;
        let packed = size_of::<PackedTriangleNormals>();
        assert!(packed <= normals && normals - packed < 16);
        assert_eq!(TableFormat::Quads.texels(4 * 7 + 1), 8);
        assert_eq!(TableFormat::Words.texels(5), 5);
    }

    #[test]
    fn rows_round_up_and_never_vanish() {
        assert_eq!(table_rows(0), 1);
        assert_eq!(table_rows(1), 1);
        assert_eq!(table_rows(TABLE_ROW), 1);
        assert_eq!(table_rows(TABLE_ROW + 1), 2);
    }

    #[test]
    fn a_table_over_the_adapters_texture_height_is_an_error_naming_it() {
        let limits = wgpu::Limits {
            max_texture_dimension_2d: 8192,
            ..wgpu::Limits::default()
        };
        assert!(check_table(&limits, "cell items", 8192 * TABLE_ROW).is_ok());
        let error = check_table(&limits, "cell items", 8192 * TABLE_ROW + 1).unwrap_err();
        let message = error.to_string();
        assert!(message.contains("cell items table"), "{message}");
        assert!(message.contains("8193 rows of 4096"), "{message}");
        assert!(message.contains("--backend cpu"), "{message}");
    }

    #[test]
    fn triangles_take_three_texels_with_their_corners_in_order() {
        let t = PackedTriangle {
            p0: [1.0, 2.0, 3.0],
            p1: [4.0, 5.0, 6.0],
            p2: [7.0, 8.0, 9.0],
        };
        let words = padded_texels(&[t, t], TRIANGLE_TABLE_TEXELS);
        assert_eq!(words.len(), 2 * 12);
        let floats: Vec<f32> = words[..12].iter().map(|&w| f32::from_bits(w)).collect();
        assert_eq!(
            floats,
            [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 0.0, 0.0, 0.0]
        );
        assert_eq!(words[12..], words[..12]);
    }

    #[test]
    fn triangle_uvs_take_two_texels_with_their_corners_in_order() {
        let t = PackedTriangleUv {
            uv0: [1.0, 2.0],
            uv1: [3.0, 4.0],
            uv2: [5.0, 6.0],
        };
        let words = padded_texels(&[t, t], TRIANGLE_UV_TABLE_TEXELS);
        assert_eq!(words.len(), 2 * 8);
        let floats: Vec<f32> = words[8..].iter().map(|&w| f32::from_bits(w)).collect();
        assert_eq!(floats, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 0.0, 0.0]);
    }
}
