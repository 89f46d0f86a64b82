//! Frame buffers kept on a GPU context between frames ([`ScratchPool`]): a frame takes its
//! large buffers (output, guard flags, adaptive AA's lattice, split flags and lists, the
//! read-back staging) from the pool and gives them back when it ends. A buffer created
//! fresh costs its first frame wgpu's zero fill (every buffer is cleared before its first
//! use) and, on a software adapter, the page faults of new memory: 25–111 ms of an
//! adaptive 512² frame on lavapipe, whose lattice of 2049² samples is 67 MB (docs/gpu.md#the-dispatch-plan-of-a-frame).
//! Every word a frame reads it has written or cleared first in that frame, so what a kept
//! buffer held before changes nothing (the GPU parity tests render frame after frame on
//! one context).

use std::sync::Mutex;

/// Most buffers kept; beyond it the largest go.
const MAX_KEPT: usize = 12;

/// Buffers of ended frames, free for the next.
#[derive(Default)]
pub struct ScratchPool {
    kept: Mutex<Vec<wgpu::Buffer>>,
}

impl ScratchPool {
    /// A buffer of `size` bytes or a little more (at most twice), with exactly `usage`:
    /// the smallest kept one that fits, else a new one.
    pub fn take(
        &self,
        device: &wgpu::Device,
        size: u64,
        usage: wgpu::BufferUsages,
    ) -> wgpu::Buffer {
        let size = size.max(4);
        let mut kept = self.kept.lock().unwrap_or_else(|e| e.into_inner());
        let fits = |b: &wgpu::Buffer| b.usage() == usage && (size..=2 * size).contains(&b.size());
        let best = (0..kept.len())
            .filter(|&k| fits(&kept[k]))
            .min_by_key(|&k| kept[k].size());
        if let Some(k) = best {
            return kept.swap_remove(k);
        }
        drop(kept);
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("glint frame scratch"),
            size,
            usage,
            mapped_at_creation: false,
        })
    }

    /// Keeps `buffers` for later frames (the largest beyond `MAX_KEPT` are released).
    pub fn give_back(&self, buffers: impl IntoIterator<Item = wgpu::Buffer>) {
        let mut kept = self.kept.lock().unwrap_or_else(|e| e.into_inner());
        kept.extend(buffers);
        if kept.len() > MAX_KEPT {
            kept.sort_by_key(|b| b.size());
            kept.truncate(MAX_KEPT);
        }
    }

    /// Bytes kept (for tests).
    pub fn kept_bytes(&self) -> u64 {
        let kept = self.kept.lock().unwrap_or_else(|e| e.into_inner());
        kept.iter().map(|b| b.size()).sum()
    }
}
