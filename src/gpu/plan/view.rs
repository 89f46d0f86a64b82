//! `glint view`'s frames through the wavefront kernels: a band's pixels, one sample each
//! (the frame's stratum), the generations (a chain's or a tree's), then the store into
//! the progressive sums.

use super::chain::generation_dispatches;
use super::shape::WavefrontShape;
use super::{linear_workgroups, AdapterBounds, BindingOffsets, Chunk, Dispatch, Workgroups};
use crate::gpu::upload::buffers::GpuTile;

/// `glint view`'s frame `stratum` of `band` through the wavefront kernels
/// ([`Entry::WAVEFRONT_VIEW`]): the camera pass over the band's pixels, one sample each
/// (its stratum `stratum`, every pass told so by [`GpuTile::stratum`]), the
/// generations, then the store into the sums over the same samples.
pub fn view_wavefront_dispatches(
    band: Chunk,
    shape: WavefrontShape,
    stratum: u32,
    sentinel: u32,
    bounds: AdapterBounds,
) -> Vec<Dispatch> {
    let items = band.size[0] * band.size[1];
    let lanes = bounds.workgroup_side * bounds.workgroup_side;
    let (x, y) = linear_workgroups(items, lanes, bounds.max_workgroups);
    let camera = Dispatch {
        entry: 0,
        chunk: 0,
        params: GpuTile {
            origin: band.origin,
            size: band.size,
            side: band.side,
            level: 0,
            items,
            sentinel,
            stratum,
            slice: 0,
        },
        workgroups: Workgroups::Direct(x, y),
        clears_work: true,
        writes_args: false,
        offsets: BindingOffsets::default(),
    };
    // A tree: its rounds and fold before the store.
    let (mut out, store) = generation_dispatches(shape, camera, 1, camera.offsets);
    out.push(Dispatch {
        entry: store,
        clears_work: false,
        ..camera
    });
    out
}
