//! Axis-aligned boxes: the only thing the grids know about their items.

use glam::Vec3;

/// Item bounds grow by this fraction of their magnitude, so that a hit point computed
/// with rounding error still falls in a cell that lists the item.
pub const BOUNDS_PAD: f32 = 1.0e-5;

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::MAX),
        max: Vec3::splat(f32::MIN),
    };

    pub fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The common part (empty when they do not overlap).
    pub fn intersection(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.max(other.min),
            max: self.max.min(other.max),
        }
    }

    /// Whether the box holds no point (min > max on some axis).
    pub fn is_empty(self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// The box around a triangle's corners.
    pub fn of_triangle(corners: &[Vec3; 3]) -> Aabb {
        let [a, b, c] = *corners;
        Aabb {
            min: a.min(b).min(c),
            max: a.max(b).max(c),
        }
    }

    /// Grown by `BOUNDS_PAD` of its largest coordinate magnitude and extent (an empty box
    /// stays empty).
    pub fn padded(self) -> Aabb {
        if self.is_empty() {
            return Aabb::EMPTY;
        }
        let magnitude = self.min.abs().max(self.max.abs()).max_element();
        let pad = BOUNDS_PAD * (magnitude + (self.max - self.min).max_element());
        Aabb {
            min: self.min - Vec3::splat(pad),
            max: self.max + Vec3::splat(pad),
        }
    }
}
