//! The counters of the wavefront's queues in the GPU's `work_counts` buffer, from their
//! specification (`tracer::wavefront::queues::COUNTERS`): the WGSL functions that say
//! which word counts a generation's (or a glass round's) entries, and how many words a
//! layout's counters take (`gpu::plan` sizes `work_counts` by it). The CPU's queues are
//! `Vec`s that know their length: it has no counters.

use super::layout::Form;

/// A ring of `work_counts` words that successive generations (or glass rounds) take in
/// turn — generation g's word is `first + g mod ring` — so that one generation's entries
/// are read while the next one's are appended and the one after is cleared; a ring of
/// one word is a single word (its function takes no generation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Counter {
    /// The WGSL function's name.
    pub name: &'static str,
    pub first: u32,
    pub ring: u32,
    /// Only in a tree's layout (scenes with refraction).
    pub tree_only: bool,
}

impl Counter {
    /// Whether `form`'s modules have the counter.
    pub fn in_form(&self, form: Form) -> bool {
        !self.tree_only || form == Form::Tree
    }
}

/// Words of `work_counts` the counters of `form` take (from word 0, as the kernels bind
/// it).
pub fn counter_words(counters: &[Counter], form: Form) -> u32 {
    counters
        .iter()
        .filter(|c| c.in_form(form))
        .map(|c| c.first + c.ring)
        .max()
        .unwrap_or(0)
}

/// The WGSL functions of `form`'s counters: `NAME(g)`, the word of generation (or round)
/// g, or `NAME()` for a single word.
pub fn counters_wgsl(counters: &[Counter], form: Form) -> String {
    let mut out = String::new();
    for c in counters.iter().filter(|c| c.in_form(form)) {
        let (params, word) = match (c.ring, c.first) {
            (1, first) => (String::new(), format!("{first}u")),
            (ring, 0) => ("g: u32".to_string(), format!("g % {ring}u")),
            (ring, first) => ("g: u32".to_string(), format!("{first}u + g % {ring}u")),
        };
        out += &format!(
            "fn {}({params}) -> u32 {{\n    return {word};\n}}\n",
            c.name
        );
    }
    out
}
