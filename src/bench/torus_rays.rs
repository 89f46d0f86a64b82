//! The rays of `glint bench --torus`, shared by its CPU rows (`bench_torus`) and its GPU
//! rows (`bench_torus_gpu`): `TorusRay` and the seeded ray generator.

use super::splitmix::SplitMix;
use glam::{DVec3, Vec3};

/// One benchmark ray in object space: origin, unit direction.
#[derive(Clone, Copy, Debug)]
pub struct TorusRay {
    pub o: Vec3,
    pub d: Vec3,
}

/// Rays from `near`..`far` bounding radii away (log-uniform) towards random points in
/// the torus's bounding box.
pub fn rays(count: usize, rin: f64, rout: f64, near: f64, far: f64, seed: u64) -> Vec<TorusRay> {
    let mut rng = SplitMix(seed);
    let size = rin + rout;
    (0..count)
        .map(|_| {
            let target = DVec3::new(
                rng.range(-size, size),
                rng.range(-size, size),
                rng.range(-rout, rout),
            );
            let dist = size * (near.ln() + (far.ln() - near.ln()) * rng.unit_f64()).exp();
            let o = (target + rng.unit() * dist).as_vec3();
            let d = (target - o.as_dvec3()).normalize().as_vec3().normalize();
            TorusRay { o, d }
        })
        .collect()
}
