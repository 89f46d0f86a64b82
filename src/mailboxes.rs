//! Which per-ray mailboxes the traversal keeps: a switch both tracers read (the CPU's
//! `PackedScene::mailboxes`, the GPU kernel variant's `KernelConfig::mailboxes`), so it
//! lives beside them rather than in either.
//!
//! A mailbox remembers items (or a mesh's triangles) a ray has already tested, so that one
//! listed in several grid cells is not tested again. Skipping a second test changes no
//! answer (see `tracer::traversal::traverse::mailboxed`), only the work; which kind pays depends on the
//! device. On the CPU the full caches pay. On a software adapter (llvmpipe) a private
//! array indexed at run time becomes per-lane scatters and gathers, which cost more than
//! the tests they save; one slot is a plain scalar there, and on balance it pays
//! (docs/journal/2026-11-29-gpu-kernel-variant-measured.md measures both, scene by scene).
//! On a hardware GPU the full caches live in registers, up to 48 VGPRs of a kernel that
//! must fit 128 (RADV, NAVI21), and in storage they cost more memory operations than the tests
//! they save; every adapter keeps the one slot
//! (docs/journal/2026-12-02-mailboxes-out-of-registers.md).

use crate::constants::{ITEM_MAILBOX_SIZE, TRIANGLE_MAILBOX_SIZE};
use std::fmt;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mailboxes {
    /// `ITEM_MAILBOX_SIZE` item slots and `TRIANGLE_MAILBOX_SIZE` triangle slots per mesh
    /// walk, direct-mapped (the CPU tracer; the GPU kernel only under `bench --gpu
    /// --mailboxes on`).
    Full,
    /// One item slot (the last mailboxed item tested) and no triangle slots: a mesh
    /// instance met again in the next scene cell is not walked again (the GPU kernel on
    /// every adapter).
    LastItem,
    /// None: every item and triangle is tested in every cell that lists it (tests use it
    /// to show the answers do not depend on the mailboxes).
    Off,
}

impl Mailboxes {
    pub const ALL: [Mailboxes; 3] = [Mailboxes::Full, Mailboxes::LastItem, Mailboxes::Off];

    /// The mask that takes an item number to its slot, or None without an item mailbox.
    pub fn item_slot_mask(self) -> Option<u32> {
        match self {
            Mailboxes::Full => Some(ITEM_MAILBOX_SIZE - 1),
            Mailboxes::LastItem => Some(0),
            Mailboxes::Off => None,
        }
    }

    /// The mask that takes a triangle number to its slot, or None without a triangle
    /// mailbox.
    pub fn triangle_slot_mask(self) -> Option<u32> {
        match self {
            Mailboxes::Full => Some(TRIANGLE_MAILBOX_SIZE - 1),
            Mailboxes::LastItem | Mailboxes::Off => None,
        }
    }

    /// The name `glint bench --gpu --mailboxes` takes.
    pub fn option_name(self) -> &'static str {
        match self {
            Mailboxes::Full => "on",
            Mailboxes::LastItem => "last",
            Mailboxes::Off => "off",
        }
    }

    /// The variant named `name` (see [`Mailboxes::option_name`]).
    pub fn from_option_name(name: &str) -> Option<Mailboxes> {
        Mailboxes::ALL.into_iter().find(|m| m.option_name() == name)
    }
}

impl fmt::Display for Mailboxes {
    /// As the kernel variant's description prints it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Mailboxes::Full => "mailboxes",
            Mailboxes::LastItem => "last-item mailbox",
            Mailboxes::Off => "no mailboxes",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn option_names_round_trip() {
        for m in Mailboxes::ALL {
            assert_eq!(Mailboxes::from_option_name(m.option_name()), Some(m));
        }
        assert_eq!(Mailboxes::from_option_name("maybe"), None);
    }

    #[test]
    fn only_the_full_variant_keeps_triangles_and_the_last_item_keeps_one_slot() {
        assert_eq!(Mailboxes::LastItem.item_slot_mask(), Some(0));
        assert_eq!(Mailboxes::Off.item_slot_mask(), None);
        assert!(Mailboxes::Full.triangle_slot_mask().is_some());
        assert!(Mailboxes::LastItem.triangle_slot_mask().is_none());
    }
}
