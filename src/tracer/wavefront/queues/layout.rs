//! Where the wavefront's queues lie in the GPU's `samples` buffer (vec4 entries), from
//! the records and regions of `tracer::wavefront::queues`: each record's lanes and stride, and the regions one
//! after another, sized per sample of the chunk. A chain (no refraction) and a tree (with
//! it: generations wider than the chunk, the vertex tree, the glass shadow legs) lay
//! them out differently; `gpu::plan` sizes its buffers by [`vec4s_per_sample`] and the
//! WGSL accessors (the generator beside this file) index by [`Region::offset`].

use super::{QueueField, QueueRecord, TREE_CONDITION};
use crate::constants::{TREE_PATHS_PER_SAMPLE, TREE_VERTICES_PER_SAMPLE};

/// The wavefront's two layouts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// Scenes without refraction: every path a chain, a generation at most a path a sample.
    Chain,
    /// Scenes with refraction: paths branch (`src/tracer/wavefront/wavefront_tree.wgsl`).
    Tree,
}

/// How many entries a region holds, per sample of the chunk.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Entries {
    /// One a sample.
    Samples,
    /// One a path a generation may hold (a chain's: one a sample; a tree's:
    /// TREE_PATHS_PER_SAMPLE a sample).
    Paths,
    /// One a vertex of the vertex tree (TREE_VERTICES_PER_SAMPLE a sample).
    TreeVertices,
    /// One a light point of each path (L: the scene's light points).
    PathLightPoints,
}

/// A region of `samples`: a queue of one record, `copies` of it back to back (two: one
/// per parity of a generation or round, the one read and the one appended to).
#[derive(Clone, Copy, Debug)]
pub struct Region {
    /// The WGSL accessors' prefix (`path_depth`, `set_sample_flags`, `load_hit`, …).
    pub name: &'static str,
    pub record: QueueRecord,
    pub copies: u32,
    pub entries: Entries,
    /// Only in a tree's layout.
    pub tree_only: bool,
}

/// An offset or a size in vec4 entries, as multiples of the chunk's samples N, of the
/// vertex tree's vertices (TREE_VERTICES_PER_SAMPLE · N), of the paths a generation may
/// hold (C: N in a chain, TREE_PATHS_PER_SAMPLE · N in a tree) and of L · C.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Extent {
    pub samples: u64,
    pub paths: u64,
    pub tree_vertices: u64,
    pub light_points: u64,
}

impl Extent {
    /// `n` entries of the kind `entries` counts, none of the others.
    fn of(entries: Entries, n: u64) -> Extent {
        let mut extent = Extent::default();
        let count = match entries {
            Entries::Samples => &mut extent.samples,
            Entries::Paths => &mut extent.paths,
            Entries::TreeVertices => &mut extent.tree_vertices,
            Entries::PathLightPoints => &mut extent.light_points,
        };
        *count = n;
        extent
    }

    fn add(self, other: Extent) -> Extent {
        Extent {
            samples: self.samples + other.samples,
            paths: self.paths + other.paths,
            tree_vertices: self.tree_vertices + other.tree_vertices,
            light_points: self.light_points + other.light_points,
        }
    }

    /// Entries per sample of the chunk, with `light_points` L.
    pub fn per_sample(self, form: Form, light_points: u32) -> u64 {
        let paths = paths_per_sample(form);
        self.samples
            + self.paths * paths
            + self.tree_vertices * TREE_VERTICES_PER_SAMPLE as u64
            + self.light_points * light_points as u64 * paths
    }
}

/// Paths a generation may hold per sample of the chunk (tracing invocations, list slots).
pub fn paths_per_sample(form: Form) -> u64 {
    match form {
        Form::Chain => 1,
        Form::Tree => TREE_PATHS_PER_SAMPLE as u64,
    }
}

/// Whether `field` is in `form`'s layout (a tree-only field takes no lanes in a chain).
pub fn in_layout(field: &QueueField, form: Form) -> bool {
    form == Form::Tree || field.condition != Some(TREE_CONDITION)
}

/// A field's lanes: (vec4 of the record, component index 0–3), in the order of the
/// type's components. Panics on a malformed lane string (a bug in the specification,
/// which the unit tests read whole).
pub fn lanes(field: &QueueField) -> Vec<(u32, usize)> {
    let mut out = Vec::new();
    for group in field.lanes.split_whitespace() {
        let (word, components) = group
            .split_once('.')
            .unwrap_or_else(|| panic!("{}: lanes '{group}' need W.xyzw", field.name));
        let word: u32 = word
            .parse()
            .unwrap_or_else(|_| panic!("{}: '{word}' is no vec4 index", field.name));
        for c in components.chars() {
            let lane = "xyzw"
                .find(c)
                .unwrap_or_else(|| panic!("{}: '{c}' is no component", field.name));
            out.push((word, lane));
        }
    }
    out
}

/// vec4 entries a record takes in `form`'s layout.
pub fn stride(record: &QueueRecord, form: Form) -> u32 {
    record
        .fields
        .iter()
        .filter(|f| in_layout(f, form))
        .flat_map(|f| lanes(f).into_iter().map(|(word, _)| word + 1))
        .max()
        .unwrap_or(0)
}

impl Region {
    pub const fn new(
        name: &'static str,
        record: QueueRecord,
        copies: u32,
        entries: Entries,
        tree_only: bool,
    ) -> Region {
        Region {
            name,
            record,
            copies,
            entries,
            tree_only,
        }
    }

    /// Whether `form`'s layout has the region.
    pub fn in_form(&self, form: Form) -> bool {
        form == Form::Tree || !self.tree_only
    }

    /// One copy's size.
    pub fn copy_size(&self, form: Form) -> Extent {
        Extent::of(self.entries, stride(&self.record, form) as u64)
    }

    /// Where the region starts in `form`'s layout of `regions` (its first copy).
    pub fn offset(&self, regions: &[Region], form: Form) -> Extent {
        regions
            .iter()
            .take_while(|r| r.name != self.name)
            .filter(|r| r.in_form(form))
            .fold(Extent::default(), |at, r| at.add(r.size(form)))
    }

    /// Its copies' size.
    pub fn size(&self, form: Form) -> Extent {
        (0..self.copies).fold(Extent::default(), |at, _| at.add(self.copy_size(form)))
    }
}

/// vec4 entries of the queues of `regions` a sample of a chunk takes in `form`'s
/// layout, with `light_points` L.
pub fn vec4s_per_sample(regions: &[Region], form: Form, light_points: u32) -> u64 {
    regions
        .iter()
        .filter(|r| r.in_form(form))
        .map(|r| r.size(form).per_sample(form, light_points))
        .sum()
}
