//! `glint view`'s device side: progressive frames through the megakernel
//! (`view_sample`) or the wavefront kernels, one stratum a frame, into the sums.

pub mod progressive;
pub mod view_wavefront;
