//! A wavefront batch in flight ([`Batch`]): its samples' records and the current
//! generation's queues (the structures of arrays `super::queues` specifies), with how
//! their entries are read and written, the scene's light points (a vertex's light slots)
//! and the hand-over to a new generation. Every pass (`wavefront`, `wavefront_shade`,
//! `wavefront_shadow`, `wavefront_gather`, `wavefront_tree`) reads and writes a batch
//! through these. The GPU's side (`batch.wgsl`) keeps the queues in its `samples` buffer
//! and counts their entries in `work_counts` (counters generated from the same
//! specification: `crate::tracer::wavefront::queues::counters`).

pub use super::queues::{
    CameraVertices, HitQueue, LegQueue, LightSlots, PathQueue, SampleRecords, ShadowQueue,
    VertexKind, VertexQueue, VertexTree,
};
use crate::constants::{LIGHT_AREA, RAY_STACK_SIZE, SAMPLE_FINE_DETAIL, SAMPLE_MIRRORS_CORNERS};
use crate::pack::layout::load_light;
use crate::pack::PackedScene;
use crate::tracer::base::ray::Ray;
use crate::tracer::base::rng::SampleSeed;
use crate::tracer::path::trace::{push_secondary_rays, ShadedHit, StackEntry};
use crate::tracer::sampling::pixel_sample::{sample_item_key, SampleHint};
use crate::tracer::traversal::hit::Hit;
use glam::Vec3;

impl SampleRecords {
    /// The [`SampleHint`] of sample `k`.
    pub fn hint(&self, k: usize) -> SampleHint {
        SampleHint {
            fine_detail: self.flags[k] & SAMPLE_FINE_DETAIL != 0,
            item: sample_item_key(self.camera_item[k], self.mirrored_item[k]),
        }
    }

    /// Sample `k`'s seed at a vertex of depth `depth`.
    pub(super) fn seed(&self, k: usize, depth: u32) -> SampleSeed {
        SampleSeed {
            pixel: self.seed_pixel[k],
            sample: self.seed_sample[k],
            depth,
            mirrors_corners: self.flags[k] & SAMPLE_MIRRORS_CORNERS != 0,
        }
    }

    /// Sets `flag` (a SAMPLE_* bit) of sample `k`.
    pub(super) fn set_flag(&mut self, k: usize, flag: u32) {
        self.flags[k] |= flag;
    }
}

impl PathQueue {
    /// Appends `entry` of sample `sample`; its index (the GPU's `atomicAdd` on the
    /// queue's counter).
    pub(super) fn append_path(&mut self, entry: &StackEntry, pending: u32, sample: u32) -> usize {
        let i = self.len();
        self.resize(i + 1);
        self.store_path(i, entry, pending, sample);
        i
    }

    /// Writes `entry` of sample `sample` as entry `i`.
    pub(super) fn store_path(&mut self, i: usize, entry: &StackEntry, pending: u32, sample: u32) {
        self.origin[i] = entry.ray.origin;
        self.dir[i] = entry.ray.dir;
        self.weight[i] = entry.weight;
        self.depth[i] = entry.depth;
        self.cone[i] = entry.cone;
        self.media[i] = entry.media;
        self.pending[i] = pending;
        self.sample[i] = sample;
    }

    /// Entry `i` as `trace_ray`'s stack holds it.
    pub(super) fn load_path(&self, i: usize) -> StackEntry {
        StackEntry {
            ray: Ray {
                origin: self.origin[i],
                dir: self.dir[i],
            },
            weight: self.weight[i],
            depth: self.depth[i],
            cone: self.cone[i],
            media: self.media[i],
        }
    }
}

impl ShadowQueue {
    /// Appends a request for light slot `slot` (vertex i's slot j is i·light_points +
    /// j); its index (the GPU's `atomicAdd`).
    pub(super) fn append_request(&mut self, slot: u32, position: Vec3) -> usize {
        let r = self.len();
        self.resize(r + 1);
        (self.slot[r], self.position[r]) = (slot, position);
        r
    }
}

/// The light points of a scene: one per point light, n² per n×n area light; slot j of a
/// vertex is light point j, lights in order, an area light's strata in stratum order.
// Mirror of src/tracer/wavefront/batch.wgsl::light_points — change both.
pub fn light_points(scene: &PackedScene) -> u32 {
    (0..scene.globals.num_lights)
        .map(|index| load_light(scene, index))
        .map(|light| {
            if light.kind == LIGHT_AREA {
                light.samples * light.samples
            } else {
                1
            }
        })
        .sum()
}

/// A batch in flight: its samples, the current generation's queues and the next
/// generation's path queue.
#[derive(Clone, Debug, Default)]
pub struct Batch {
    pub samples: SampleRecords,
    pub paths: PathQueue,
    pub hits: HitQueue,
    pub vertices: VertexQueue,
    /// `light_points` slots a vertex: vertex i's slot j at i·light_points + j.
    pub slots: LightSlots,
    pub light_points: u32,
    pub shadows: ShadowQueue,
    pub next: PathQueue,
    /// Generations started so far (the camera rays' is 1).
    pub generations: u32,
    /// Scenes with refraction: every vertex of every generation so far, kept for the
    /// fold (path i of the current generation is vertex `vertex_base` + i).
    pub tree: VertexTree,
    pub vertex_base: u32,
    /// Scenes with refraction: each sample's camera vertex, where the fold starts.
    pub camera_vertices: CameraVertices,
    /// Scenes with refraction: the live legs of the generation's glass shadow round
    /// (round 0's leg r is request r's first: `wavefront_tree::start_shadow_leg`).
    pub legs: LegQueue,
    /// Whether the batch keeps the tree (scenes with refraction) rather than adding
    /// each vertex's colour straight into its sample's (chains).
    pub keeps_tree: bool,
}

/// Sizes the per-path queues of the generation in `batch.paths` (the GPU sizes them for
/// the whole batch once; the args kernel's counters say how many are live).
pub(super) fn start_generation(batch: &mut Batch) {
    let len = batch.paths.len();
    batch.hits.reset(len);
    batch.vertices.reset(len);
    batch.slots.clear();
    batch.slots.resize(len * batch.light_points as usize);
    batch.shadows = ShadowQueue::default();
    batch.next.clear();
    batch.generations += 1;
    if batch.keeps_tree {
        batch.vertex_base = batch.tree.len() as u32;
        batch.tree.resize(batch.vertex_base as usize + len);
    }
}

/// The rays a hit spawns (`push_secondary_rays` at `shaded` and `hit` of `entry`'s ray),
/// pushed as `trace_ray` pushes them onto its stack, which holds `pending` entries
/// then: the stack and its size (the rays from `pending` on are the new ones; those
/// the full stack dropped are not there).
pub(super) fn spawned_rays(
    scene: &PackedScene,
    entry: &StackEntry,
    shaded: &ShadedHit,
    hit: &Hit,
    pending: usize,
) -> ([StackEntry; RAY_STACK_SIZE as usize], usize) {
    let mut stack = [*entry; RAY_STACK_SIZE as usize];
    let mut size = pending;
    push_secondary_rays(scene, &mut stack, &mut size, entry, shaded, hit);
    (stack, size)
}

/// A pass over the generation's paths: `invocation` for each path in queue order (on
/// the GPU one invocation a path; no invocation depends on another's order).
pub(super) fn each_path<C>(
    scene: &PackedScene,
    batch: &mut Batch,
    counters: &mut C,
    invocation: fn(&PackedScene, &mut Batch, usize, &mut C),
) {
    for i in 0..batch.paths.len() {
        invocation(scene, batch, i, counters);
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use glam::Vec2;

    /// A stack entry of depth `depth` with every field set.
    pub(in crate::tracer::wavefront) fn entry(depth: u32) -> StackEntry {
        StackEntry {
            ray: Ray {
                origin: Vec3::new(1.0, 2.0, 3.0),
                dir: Vec3::Z,
            },
            weight: Vec3::splat(0.5),
            depth,
            cone: Vec2::new(0.25, 0.125),
            media: crate::tracer::shading::dielectric::MediumStack {
                iors: [1.0; crate::constants::MEDIUM_STACK_SIZE as usize],
                count: 0,
            },
        }
    }

    /// Appends hand out consecutive indices and keep each field of an entry at its
    /// index (what the GPU's atomicAdd on a counter gives one invocation).
    #[test]
    fn appends_take_consecutive_slots() {
        let mut q = PathQueue::default();
        assert_eq!(q.append_path(&entry(0), 0, 7), 0);
        assert_eq!(q.append_path(&entry(3), 0, 2), 1);
        assert_eq!(q.len(), 2);
        assert_eq!((q.depth[1], q.sample[1]), (3, 2));
        assert_eq!((q.depth[0], q.sample[0]), (0, 7));
        assert_eq!(q.cone[1], Vec2::new(0.25, 0.125));
        let mut s = ShadowQueue::default();
        assert_eq!(s.append_request(4, Vec3::X), 0);
        assert_eq!(s.append_request(9, Vec3::Y), 1);
        assert_eq!((s.slot[1], s.position[1]), (9, Vec3::Y));
    }
}
