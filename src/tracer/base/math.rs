//! Small numeric helpers that several intersection routines share (a leaf module: it
//! depends on nothing else in the tracer).

use crate::constants::SAFE_RCP_LIMIT;
use glam::Vec3;

/// 1/x, or ±[`SAFE_RCP_LIMIT`] when |x| is too small to invert without overflow.
// Mirror of src/tracer/base/math.wgsl::safe_rcp — change both.
pub fn safe_rcp(x: f32) -> f32 {
    if x.abs() > 1.0 / SAFE_RCP_LIMIT {
        1.0 / x
    } else {
        SAFE_RCP_LIMIT.copysign(x)
    }
}

/// `safe_rcp` of each component.
// Mirror of src/tracer/base/math.wgsl::safe_rcp3 — change both.
pub fn safe_rcp3(v: Vec3) -> Vec3 {
    Vec3::new(safe_rcp(v.x), safe_rcp(v.y), safe_rcp(v.z))
}

/// A coordinate axis. As an enum it indexes a `[f32; 3]` with no bounds check (its values
/// are known to be 0..=2), where glam's `Vec3[usize]` is a match with a panic arm: the
/// hot loops (the DDA step, the watertight triangle test) index by a runtime axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(usize)]
pub enum Axis {
    X = 0,
    Y = 1,
    Z = 2,
}

impl Axis {
    /// The next axis, cyclically (x → y → z → x).
    pub fn next(self) -> Axis {
        match self {
            Axis::X => Axis::Y,
            Axis::Y => Axis::Z,
            Axis::Z => Axis::X,
        }
    }
}
