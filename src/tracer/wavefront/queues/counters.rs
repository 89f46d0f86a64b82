//! The counters of the wavefront's queues in the GPU's `work_counts` buffer, from their
//! specification (`tracer::wavefront::queues::COUNTERS`): the WGSL functions that say
//! which word counts a generation's (or a glass round's) entries, and how many words a
//! layout's counters take (`gpu::plan` sizes `work_counts` by it). The CPU's queues are
//! `Vec`s that know their length: it has no counters. Also where a tree's args kernels
//! write their indirect arguments in `work_args` ([`leg_args`], [`tree_generation_args`]):
//! written once here, emitted into a tree's modules with the counters and read by the
//! host's plan (`gpu::plan::shape`).

use super::layout::Form;

/// Words of `work_args` a tree's glass round's indirect arguments take.
const LEG_ARGS_WORDS: u32 = 3;

/// Words of `work_args` before a tree's generations': its glass rounds' (round r < 10).
const TREE_ROUND_ARGS_WORDS: u32 = 10 * LEG_ARGS_WORDS;

/// Words of `work_args` a tree's generation's indirect arguments take: the next
/// generation's passes', then its shadow pass's.
const TREE_GENERATION_ARGS_WORDS: u32 = 6;

/// Where a tree's round r's legs' indirect arguments lie in `work_args` (words): the same
/// words every generation.
pub fn leg_args(r: u32) -> u32 {
    LEG_ARGS_WORDS * r
}

/// Where a tree's generation g's indirect arguments lie in `work_args` (words), after the
/// rounds'.
pub fn tree_generation_args(g: u32) -> u32 {
    TREE_ROUND_ARGS_WORDS + TREE_GENERATION_ARGS_WORDS * g
}

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
/// g, or `NAME()` for a single word; `counter_words()`, the words they take
/// ([`counter_words`]'s value: what adaptive AA's lattice store pass clears between
/// lattice passes); and in a tree's, [`leg_args`] and [`tree_generation_args`].
pub fn counters_wgsl(counters: &[Counter], form: Form) -> String {
    let mut out = format!(
        "fn counter_words() -> u32 {{\n    return {}u;\n}}\n",
        counter_words(counters, form)
    );
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
    if form == Form::Tree {
        out += &format!(
            "fn leg_args(r: u32) -> u32 {{\n    return {LEG_ARGS_WORDS}u * r;\n}}\n\
             fn tree_generation_args(g: u32) -> u32 {{\n    \
             return {TREE_ROUND_ARGS_WORDS}u + {TREE_GENERATION_ARGS_WORDS}u * g;\n}}\n"
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tree's argument words the WGSL is given are the host's: its functions return
    /// what the Rust ones do (read off the emitted text), and only a tree's modules have
    /// them.
    #[test]
    fn argument_words_are_the_hosts() {
        let tree = counters_wgsl(&[], Form::Tree);
        assert!(tree.contains(&format!("return {}u * r;", leg_args(1))));
        let step = tree_generation_args(1) - tree_generation_args(0);
        assert!(tree.contains(&format!(
            "return {}u + {step}u * g;",
            tree_generation_args(0)
        )));
        assert_eq!((leg_args(9), tree_generation_args(2)), (27, 42));
        assert!(!counters_wgsl(&[], Form::Chain).contains("leg_args"));
    }
}
