//! The specification of the wavefront's queue records (pbrt-v4's `workitems.soa` is the
//! model): one line a field, the regions of the GPU's `samples` buffer they fill and the
//! counters of their entries. Lanes are a record's vec4s in the GPU's `samples` buffer
//! (`"2.w 3.x"`: vec4 2's w, then vec4 3's x); u32 fields are stored bit-cast into f32
//! lanes. From this one table, through the modules beside it, come
//! - the CPU wavefront's structures of arrays (one `Vec` a field: `PathQueue`, …), made
//!   by `queue_records!` ([`record`]);
//! - the WGSL accessors the wavefront kernels read and write their queues through
//!   ([`wgsl`]'s `queue_wgsl`, emitted into the render module as the constants' prelude
//!   is: no `.wgsl` file holds them);
//! - the regions of `samples` the queues take and the bytes a sample needs ([`layout`],
//!   which `gpu::plan` sizes its buffers by);
//! - the counters of their entries in `work_counts` ([`counters`]: the WGSL functions
//!   naming a generation's word, and the words `gpu::plan` sizes `work_counts` by).
//!
//! A new field is one line here. docs/architecture.md, "Queues", describes the layout.

pub mod counters;
pub mod layout;
pub mod record;
pub mod wgsl;

pub use record::{QueueField, QueueRecord, TREE_CONDITION};

use crate::constants::{
    MEDIUM_STACK_SIZE, NO_CHILD, NO_ITEM, VERTEX_LIT, VERTEX_MISS, VERTEX_UNLIT,
};
use crate::tracer::shading::dielectric::MediumStack;
use crate::tracer::traversal::hit::Hit;
use counters::Counter;
use glam::{Vec2, Vec3};
use layout::{Entries, Region};

/// What the gather pass does with a vertex (the GPU's VERTEX_* words).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[repr(u32)]
pub enum VertexKind {
    /// The ray hit nothing: its own term is the background.
    #[default]
    Miss = VERTEX_MISS,
    /// Phong shading: the ambient term, then the light slots.
    Lit = VERTEX_LIT,
    /// The UV debug view: its own term is the colour, no lights.
    Unlit = VERTEX_UNLIT,
}

/// The media of a chain's rays: a placeholder (without refraction no shading step reads
/// them; the GPU's path records have no lanes for them then).
pub const CHAIN_MEDIA: MediumStack = MediumStack {
    iors: [1.0; MEDIUM_STACK_SIZE as usize],
    count: 0,
};

crate::queue_records! {
    /// Per sample of the batch: its colour so far, what its `SampleHint` keeps (the
    /// camera ray's item, the item seen in a camera-hit mirror, the SAMPLE_* flags: fine
    /// detail, a camera-hit mirror, …) and its seed's pixel and sample.
    SampleRecords {
        colour: Vec3 = Vec3::ZERO => "vec3<f32>" at "0.xyz",
        camera_item: u32 = NO_ITEM => "u32" at "0.w",
        mirrored_item: u32 = NO_ITEM => "u32" at "1.x",
        flags: u32 = 0 => "u32" at "1.y",
        seed_pixel: u32 = 0 => "u32" at "1.z",
        seed_sample: u32 = 0 => "u32" at "1.w",
    }

    /// A generation's paths: each entry a ray with its weight, depth, cone and sample.
    PathQueue {
        origin: Vec3 = Vec3::ZERO => "vec3<f32>" at "0.xyz",
        sample: u32 = 0 => "u32" at "0.w",
        dir: Vec3 = Vec3::ZERO => "vec3<f32>" at "1.xyz",
        depth: u32 = 0 => "u32" at "1.w",
        weight: Vec3 = Vec3::ZERO => "vec3<f32>" at "2.xyz",
        cone: Vec2 = Vec2::ZERO => "vec2<f32>" at "2.w 3.x" if "TEXTURE|BUMP",
        /// The entries under this one on `trace_ray`'s stack when it would be popped
        /// (its index in that stack: see `tracer::wavefront::wavefront_tree`); always 0 in a chain.
        pending: u32 = 0 => "u32" at "3.y" if "REFRACTION",
        /// The media the ray travels in (scenes with refraction; a placeholder otherwise).
        media: MediumStack = CHAIN_MEDIA => "MediumStack" at "4.xyzw 3.z" if "REFRACTION",
    }

    /// Each path's closest hit, at its path's index (and each glass shadow leg's).
    HitQueue as "Hit" {
        t: f32 = 0.0 => "f32" at "0.x",
        item: u32 = NO_ITEM => "u32" at "0.y",
        b1: f32 = 0.0 => "f32" at "0.z",
        b2: f32 = 0.0 => "f32" at "0.w",
        part: u32 = NO_ITEM => "u32" at "1.x",
    }

    /// Each path's shaded vertex, at its path's index: what it adds by itself, and where
    /// its shadow rays start.
    VertexQueue {
        /// The ambient term, the background of a miss, or the UV debug view's colour.
        own: Vec3 = Vec3::ZERO => "vec3<f32>" at "0.xyz",
        kind: VertexKind = VertexKind::Miss => "u32" at "0.w",
        shadow_origin: Vec3 = Vec3::ZERO => "vec3<f32>" at "1.xyz",
        magnitude: f32 = 0.0 => "f32" at "1.w",
    }

    /// The light slots, `light_points` a vertex (vertex i's slot j at i·light_points + j):
    /// a light point's term, unshadowed until the shadow pass.
    LightSlots {
        term: Vec3 = Vec3::ZERO => "vec3<f32>" at "0.xyz",
    }

    /// The shadow rays the shade pass asks for: the light point each aims at and the
    /// light slot it is for (its vertex is slot div light_points).
    ShadowQueue {
        position: Vec3 = Vec3::ZERO => "vec3<f32>" at "0.xyz",
        slot: u32 = 0 => "u32" at "0.w",
    }

    /// Every vertex of a batch with refraction, generation after generation (generation
    /// g's path i is vertex `Batch::vertex_base` + i): its value and its children in
    /// push order.
    VertexTree {
        value: Vec3 = Vec3::ZERO => "vec3<f32>" at "0.xyz",
        children: [u32; 2] = [NO_CHILD; 2] => "vec2<u32>" at "0.w 1.x",
    }

    /// Per sample, with refraction: its camera vertex (the path the camera pass gave its
    /// camera ray in generation 0, whose vertex base is 0; NO_CHILD: none).
    CameraVertices {
        index: u32 = NO_CHILD => "u32" at "0.x",
    }

    /// The live legs of a glass shadow round: the state of each (`dielectric::ShadowLeg`:
    /// start, transmittance so far, media) and the request it continues.
    LegQueue {
        start: Vec3 = Vec3::ZERO => "vec3<f32>" at "0.xyz",
        transmittance: f32 = 0.0 => "f32" at "0.w",
        media: MediumStack = CHAIN_MEDIA => "MediumStack" at "1.xyzw 2.x",
        request: u32 = 0 => "u32" at "2.y",
    }
}

/// The regions of the GPU's `samples` buffer, in buffer order ([`layout`]).
pub const REGIONS: &[Region] = &[
    Region::new("sample", SampleRecords::RECORD, 1, Entries::Samples, false),
    Region::new("path", PathQueue::RECORD, 2, Entries::Paths, false),
    Region::new("hit", HitQueue::RECORD, 1, Entries::Paths, false),
    Region::new("vertex", VertexQueue::RECORD, 1, Entries::Paths, false),
    Region::new("node", VertexTree::RECORD, 1, Entries::TreeVertices, true),
    Region::new(
        "camera_vertex",
        CameraVertices::RECORD,
        1,
        Entries::Samples,
        true,
    ),
    Region::new(
        "slot",
        LightSlots::RECORD,
        1,
        Entries::PathLightPoints,
        false,
    ),
    Region::new(
        "request",
        ShadowQueue::RECORD,
        1,
        Entries::PathLightPoints,
        false,
    ),
    Region::new("leg", LegQueue::RECORD, 2, Entries::PathLightPoints, true),
    Region::new(
        "leg_hit",
        HitQueue::RECORD,
        1,
        Entries::PathLightPoints,
        true,
    ),
];

/// The counters of the queues' entries in the GPU's `work_counts` ([`counters`]):
/// a generation's paths (read, appended to, cleared: three words) and shadow requests;
/// in a tree's layout a glass round's legs, a generation's first vertex in the vertex
/// tree, and the scene's light points (written by the camera pass for the shadow pass
/// and the rounds, whose regions lie after L-sized ones).
pub const COUNTERS: &[Counter] = &[
    Counter {
        name: "path_counter",
        first: 0,
        ring: 3,
        tree_only: false,
    },
    Counter {
        name: "shadow_counter",
        first: 3,
        ring: 2,
        tree_only: false,
    },
    Counter {
        name: "leg_counter",
        first: 5,
        ring: 3,
        tree_only: true,
    },
    Counter {
        name: "vertex_base_counter",
        first: 8,
        ring: 2,
        tree_only: true,
    },
    Counter {
        name: "tree_points_word",
        first: 10,
        ring: 1,
        tree_only: true,
    },
];

impl HitQueue {
    pub fn store_hit(&mut self, i: usize, hit: &Hit) {
        (
            self.t[i],
            self.item[i],
            self.b1[i],
            self.b2[i],
            self.part[i],
        ) = (hit.t, hit.item, hit.b1, hit.b2, hit.part);
    }

    pub fn load_hit(&self, i: usize) -> Hit {
        Hit {
            t: self.t[i],
            item: self.item[i],
            b1: self.b1[i],
            b2: self.b2[i],
            part: self.part[i],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::layout::{in_layout, lanes, stride, vec4s_per_sample, Form};
    use super::wgsl::queue_wgsl;
    use super::*;
    use crate::constants::{TREE_PATHS_PER_SAMPLE, TREE_VERTICES_PER_SAMPLE};
    use std::collections::BTreeSet;

    /// Components of each WGSL type a field may have.
    fn components(wgsl: &str) -> usize {
        match wgsl {
            "f32" | "u32" => 1,
            "vec2<f32>" | "vec2<u32>" => 2,
            "vec3<f32>" => 3,
            "MediumStack" => MEDIUM_STACK_SIZE as usize + 1,
            other => panic!("no WGSL encoding for {other}"),
        }
    }

    /// Every field takes as many lanes as its type has components, no lane is taken
    /// twice in either layout, and a chain's record has no lanes of a tree's fields
    /// beyond its stride.
    #[test]
    fn records_take_distinct_lanes() {
        for region in REGIONS {
            for form in [Form::Chain, Form::Tree] {
                let mut taken = BTreeSet::new();
                for field in region.record.fields.iter().filter(|f| in_layout(f, form)) {
                    let lanes = lanes(field);
                    assert_eq!(lanes.len(), components(field.wgsl), "{}", field.name);
                    for lane in lanes {
                        assert!(
                            taken.insert(lane),
                            "{}: lane {lane:?} taken twice",
                            region.name
                        );
                        assert!(lane.0 < stride(&region.record, form));
                    }
                }
            }
        }
        assert_eq!(stride(&PathQueue::RECORD, Form::Chain), 4);
        assert_eq!(stride(&PathQueue::RECORD, Form::Tree), 5);
    }

    /// The regions add up to the layout the kernels were written for: a chain's 14 + 2L
    /// vec4s a sample, a tree's 3 + (14 + 10L)·TREE_PATHS_PER_SAMPLE +
    /// 2·TREE_VERTICES_PER_SAMPLE.
    #[test]
    fn regions_add_up_per_sample() {
        for l in [0, 1, 17] {
            assert_eq!(vec4s_per_sample(REGIONS, Form::Chain, l), 14 + 2 * l as u64);
            assert_eq!(
                vec4s_per_sample(REGIONS, Form::Tree, l),
                3 + (14 + 10 * l as u64) * TREE_PATHS_PER_SAMPLE as u64
                    + 2 * TREE_VERTICES_PER_SAMPLE as u64
            );
        }
    }

    /// Each field of each region gets its getter and setter, named region_field, and
    /// each region its whole-entry write; a field whose condition the module lacks gets
    /// none but stays an argument of the write.
    #[test]
    fn every_field_has_its_accessors() {
        let all = queue_wgsl(REGIONS, Form::Tree, &|_| true);
        for region in REGIONS {
            for field in region.record.fields {
                let name = format!("{}_{}", region.name, field.name);
                assert!(all.contains(&format!("fn {name}(")), "{name}");
                assert!(all.contains(&format!("fn set_{name}(")), "set_{name}");
            }
            assert!(all.contains(&format!("fn write_{}(", region.name)));
        }
        let chain = queue_wgsl(REGIONS, Form::Chain, &|c| c != "TEXTURE|BUMP");
        assert!(!chain.contains("fn path_cone(") && !chain.contains("fn leg_queue("));
        assert!(chain.contains("weight: vec3<f32>, cone_unused: vec2<f32>)"));
        // Without a cone the chain's fourth path vec4 holds nothing and is not written.
        assert!(!chain.contains("samples[at + 3u] = vec4<f32>(cone.y"));
    }

    /// The counters take distinct words, from word 0 without a gap: a chain's 5, a
    /// tree's 11 (the args kernels clear and the plan sizes exactly these).
    #[test]
    fn counters_take_distinct_words() {
        use super::counters::counter_words;
        for form in [Form::Chain, Form::Tree] {
            let mut words: Vec<u32> = COUNTERS
                .iter()
                .filter(|c| c.in_form(form))
                .flat_map(|c| c.first..c.first + c.ring)
                .collect();
            words.sort();
            let expected: Vec<u32> = (0..counter_words(COUNTERS, form)).collect();
            assert_eq!(words, expected, "{form:?}");
        }
        assert_eq!(counter_words(COUNTERS, Form::Chain), 5);
        assert_eq!(counter_words(COUNTERS, Form::Tree), 11);
    }

    /// The vertex kinds are the GPU's VERTEX_* words.
    #[test]
    fn vertex_kinds_are_the_gpu_words() {
        assert_eq!(VertexKind::Miss as u32, VERTEX_MISS);
        assert_eq!(VertexKind::Lit as u32, VERTEX_LIT);
        assert_eq!(VertexKind::Unlit as u32, VERTEX_UNLIT);
    }
}
