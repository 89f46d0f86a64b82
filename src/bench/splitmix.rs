//! splitmix64: the tiny seeded generator of the benchmarks' geometry and rays (one
//! generator, so every benchmark's inputs are reproducible the same way).

use glam::DVec3;

/// splitmix64 state; each draw advances it.
pub struct SplitMix(pub u64);

impl SplitMix {
    /// Uniform in [0, 1).
    pub fn unit_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E3779B97F4A7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [0, 1)³.
    pub fn vec(&mut self) -> DVec3 {
        DVec3::new(self.unit_f64(), self.unit_f64(), self.unit_f64())
    }

    /// Uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit_f64()
    }

    /// Uniform on the unit sphere.
    pub fn unit(&mut self) -> DVec3 {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, std::f64::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}
