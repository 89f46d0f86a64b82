//! GPU buffers for a packed scene: every packed array as a table (a texture, see
//! `crate::gpu::upload::tables`; never empty, since a binding may not be) and a uniform for
//! [`PackedGlobals`](crate::pack::PackedGlobals). Sizes are checked against the adapter's
//! limits first, so an oversized scene is an error that names the array; [`check_size`]
//! does the same for the frame's storage buffers.

use crate::constants::{
    TRIANGLE_NORMAL_TABLE_TEXELS, TRIANGLE_TABLE_TEXELS, TRIANGLE_UV_TABLE_TEXELS,
};
pub use crate::gpu::compile::bindings::SCENE_TABLE_BINDINGS;
use crate::gpu::device::context::GpuContext;
use crate::gpu::upload::tables::{check_table, padded_texels, upload_table, SCENE_TABLE_FORMATS};
use crate::gpu::GpuError;
use crate::pack::PackedScene;
use bytemuck::{Pod, Zeroable};
use std::borrow::Cow;
use wgpu::util::DeviceExt;

/// Per-dispatch uniform of the render entry point.
// Mirror of src/pack/layout.wgsl::GpuTile — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuTile {
    /// Top-left pixel of the tile.
    pub origin: [u32; 2],
    /// Pixels across and down (at most `side`).
    pub size: [u32; 2],
    /// The tile side the per-tile buffers are laid out for (row stride, in pixels).
    pub side: u32,
    /// Adaptive passes: the level of the squares this pass decides or splits.
    pub level: u32,
    /// One-dimensional kernels: the invocations that have work.
    pub items: u32,
    /// Iterations of the loop-limiter check ([`LIMITER_SENTINEL`]).
    pub sentinel: u32,
    /// The wavefront kernels' (the WGSL struct has the field only in modules with them):
    /// the camera pass's stratum of each chunk pixel (`glint view`'s frame), or
    /// [`ALL_STRATA`](crate::constants::ALL_STRATA): every stratum of each (a render).
    pub stratum: u32,
    /// The wavefront shadow pass's slice with CSG (WavefrontShape::shadow_slices): its
    /// requests are slice × items … slice × items + items − 1 (src/tracer/wavefront/wavefront_shadow.wgsl);
    /// the args kernel's: the slices of a shadow pass (WavefrontShape::shadow_slices).
    pub slice: u32,
}

/// `GpuTile::sentinel`: the loop-limiter check runs a loop of this many iterations; it
/// stops after one when Mesa's limiter has tripped (see `src/tracer/sampling/render.wgsl`).
pub const LIMITER_SENTINEL: u32 = 2;

/// The scene's buffers: the globals uniform (binding 0) and the tables.
pub struct SceneBuffers {
    pub globals: wgpu::Buffer,
    /// instances, triangles, materials, lights, cell_start, cell_items, csg_program,
    /// texels, triangle_uvs, meshes, triangle_normals, bound at [`SCENE_TABLE_BINDINGS`].
    pub tables: [wgpu::TextureView; 11],
}

/// `data` as u32 words, not copied (every packed struct is a whole number of words of
/// f32 and u32 fields).
fn words<T: Pod>(data: &[T]) -> Cow<'_, [u32]> {
    Cow::Borrowed(bytemuck::cast_slice(data))
}

/// Fails with [`GpuError::SceneTooLarge`] when `bytes` exceeds the binding limit.
pub fn check_size(ctx: &GpuContext, array: &'static str, bytes: u64) -> Result<(), GpuError> {
    let limit = ctx
        .limits
        .max_storage_buffer_binding_size
        .min(ctx.limits.max_buffer_size);
    if bytes > limit {
        return Err(GpuError::SceneTooLarge {
            array,
            bytes,
            limit,
            excess: bytes - limit,
        });
    }
    Ok(())
}

/// Uploads `scene` to `ctx`'s device.
pub fn upload_scene(ctx: &GpuContext, scene: &PackedScene) -> Result<SceneBuffers, GpuError> {
    use std::borrow::Cow::{Borrowed, Owned};
    // (Only the padded arrays are copied; the rest are uploaded from the scene.) In
    // `SCENE_TABLE_BINDINGS` order, which `SCENE_TABLE_FORMATS` follows too.
    let tables: [(&'static str, Cow<[u32]>); 11] = [
        ("instances", words(&scene.instances)),
        (
            "triangles",
            Owned(padded_texels(&scene.triangles, TRIANGLE_TABLE_TEXELS)),
        ),
        ("materials", words(&scene.materials)),
        ("lights", words(&scene.lights)),
        ("cell_start", Borrowed(&scene.cell_start)),
        ("cell_items", Borrowed(&scene.cell_items)),
        ("csg_program", Borrowed(&scene.csg_program)),
        ("texels", Borrowed(&scene.texels)),
        (
            "triangle_uvs",
            Owned(padded_texels(&scene.triangle_uvs, TRIANGLE_UV_TABLE_TEXELS)),
        ),
        ("meshes", words(&scene.meshes)),
        (
            "triangle_normals",
            Owned(padded_texels(
                &scene.triangle_normals,
                TRIANGLE_NORMAL_TABLE_TEXELS,
            )),
        ),
    ];
    for ((name, words), format) in tables.iter().zip(SCENE_TABLE_FORMATS) {
        check_table(&ctx.limits, name, format.texels(words.len()))?;
    }
    let device = &ctx.device;
    ctx.scoped("scene upload", || {
        let globals = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("globals"),
            contents: bytemuck::bytes_of(&scene.globals),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let tables = std::array::from_fn(|i| {
            let (name, words) = &tables[i];
            upload_table(ctx, name, SCENE_TABLE_FORMATS[i], words)
        });
        SceneBuffers { globals, tables }
    })
}

/// Bind group entries of the scene: 0 and [`SCENE_TABLE_BINDINGS`].
pub fn scene_entries(buffers: &SceneBuffers) -> Vec<wgpu::BindGroupEntry<'_>> {
    let mut entries = vec![wgpu::BindGroupEntry {
        binding: 0,
        resource: buffers.globals.as_entire_binding(),
    }];
    for (binding, view) in SCENE_TABLE_BINDINGS.iter().zip(&buffers.tables) {
        entries.push(wgpu::BindGroupEntry {
            binding: *binding,
            resource: wgpu::BindingResource::TextureView(view),
        });
    }
    entries
}

/// Copies `size` bytes of `source` back to the host (waits for the GPU).
pub fn read_back(ctx: &GpuContext, staging: &wgpu::Buffer, size: u64) -> Result<Vec<u8>, GpuError> {
    let (tx, rx) = std::sync::mpsc::channel();
    staging.map_async(wgpu::MapMode::Read, 0..size, move |r| {
        let _ = tx.send(r);
    });
    ctx.wait()?;
    take_mapped(staging, size, rx.recv().ok())
}

/// The first `size` bytes of `staging` once its `map_async` has reported `mapped` (None:
/// the callback never ran), copied out; the buffer is unmapped again.
pub fn take_mapped(
    staging: &wgpu::Buffer,
    size: u64,
    mapped: Option<Result<(), wgpu::BufferAsyncError>>,
) -> Result<Vec<u8>, GpuError> {
    let failed = |e: &dyn std::fmt::Display| GpuError::Wgpu {
        what: "read-back",
        message: e.to_string(),
    };
    match mapped {
        Some(Ok(())) => {}
        Some(Err(e)) => return Err(failed(&e)),
        None => return Err(GpuError::DeviceLost("the read-back never completed".into())),
    }
    let bytes = staging
        .get_mapped_range(0..size)
        .map_err(|e| failed(&e))?
        .to_vec();
    staging.unmap();
    Ok(bytes)
}
