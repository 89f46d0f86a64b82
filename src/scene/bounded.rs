//! Integer options checked once, where they enter (a CLI flag, a scene option, a light's
//! argument), and carried as typed values afterwards: a [`TraceDepth`] cannot hold 65, so
//! nothing downstream checks or clamps it again.

use crate::constants::{MAX_AA_DEPTH, MAX_AA_SAMPLES, MAX_SHADOW_SAMPLES, MAX_TRACE_DEPTH};
use std::fmt;

/// An integer known to lie in `MIN..=MAX`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Bounded<const MIN: u32, const MAX: u32>(u32);

/// `max_depth`: the deepest reflection/refraction chain.
pub type TraceDepth = Bounded<0, MAX_TRACE_DEPTH>;
/// `samples`: n of uniform n×n anti-aliasing.
pub type AaSamples = Bounded<1, MAX_AA_SAMPLES>;
/// `aa_depth`: adaptive anti-aliasing's deepest split.
pub type AaDepth = Bounded<0, MAX_AA_DEPTH>;
/// n of an area light's n×n shadow samples (`gr.area_light`'s n, `shadow_samples`).
pub type ShadowSamples = Bounded<1, MAX_SHADOW_SAMPLES>;

impl<const MIN: u32, const MAX: u32> Bounded<MIN, MAX> {
    /// `value` if it lies in range.
    pub fn new(value: i64) -> Option<Self> {
        (i64::from(MIN)..=i64::from(MAX))
            .contains(&value)
            .then_some(Self(value as u32))
    }

    /// A value known in the source; out of range is a compile-time error where it is
    /// used in a constant, a panic otherwise.
    pub const fn constant(value: u32) -> Self {
        assert!(value >= MIN && value <= MAX, "value out of range");
        Self(value)
    }

    pub const fn get(self) -> u32 {
        self.0
    }

    /// What a valid value is, for error messages: "an integer from 1 to 64".
    pub fn expected() -> String {
        format!("an integer from {MIN} to {MAX}")
    }

    /// Parses a command-line value (clap's `value_parser`).
    pub fn parse(text: &str) -> Result<Self, String> {
        text.trim()
            .parse::<i64>()
            .ok()
            .and_then(Self::new)
            .ok_or_else(|| format!("expected {}, got '{text}'", Self::expected()))
    }
}

impl<const MIN: u32, const MAX: u32> fmt::Display for Bounded<MIN, MAX> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accepts_exactly_its_range() {
        assert_eq!(TraceDepth::new(0).map(TraceDepth::get), Some(0));
        assert_eq!(
            TraceDepth::new(MAX_TRACE_DEPTH as i64).map(TraceDepth::get),
            Some(MAX_TRACE_DEPTH)
        );
        assert_eq!(TraceDepth::new(MAX_TRACE_DEPTH as i64 + 1), None);
        assert_eq!(ShadowSamples::new(0), None);
        assert_eq!(ShadowSamples::new(-1), None);
        assert_eq!(ShadowSamples::new(i64::MAX), None);
    }

    #[test]
    fn parse_names_the_range() {
        assert_eq!(ShadowSamples::parse("7"), Ok(ShadowSamples::constant(7)));
        let err = ShadowSamples::parse("65").unwrap_err();
        assert!(
            err.contains("from 1 to 64") && err.contains("'65'"),
            "{err}"
        );
        assert!(TraceDepth::parse("two").is_err());
    }
}
