//! The wavefront's shadow pass (`wavefront_shadow.wgsl` on the GPU): each shadow request
//! the shade pass made, in request order — without refraction its ray traced to any hit
//! and its light slot zeroed where blocked; with refraction its first leg started for
//! the glass shadow rounds (`wavefront_tree`), which then finish each slot.

use super::batch::{light_points, Batch};
use super::wavefront_tree::{glass_shadow_rounds, start_shadow_leg};
use crate::pack::PackedScene;
use crate::tracer::shading::shade::{shadow_blocked, shadowed_term};
use crate::tracer::traversal::hit::TraversalCounters;

/// The shadow pass: each request through [`wavefront_shadow`], in request order (on the
/// GPU one request an invocation; with CSG L dispatches, slice s requests s·N … s·N + N
/// − 1).
pub fn shadow_pass(scene: &PackedScene, batch: &mut Batch, counters: &mut impl TraversalCounters) {
    if batch.keeps_tree {
        // Round 0's legs: request r's first is leg r (the args kernel's leg count).
        batch.legs.reset(batch.shadows.len());
    }
    for r in 0..batch.shadows.len() {
        wavefront_shadow(scene, batch, r, counters);
    }
}

/// The shadow pass's invocation for request `r`: through glass (scenes with refraction)
/// its first leg, for the rounds; else its shadow ray ([`shadow_request`]).
// Mirror of src/tracer/wavefront/wavefront_shadow.wgsl::wavefront_shadow — change both.
fn wavefront_shadow(
    scene: &PackedScene,
    batch: &mut Batch,
    r: usize,
    counters: &mut impl TraversalCounters,
) {
    if batch.keeps_tree {
        start_shadow_leg(batch, r);
    } else {
        shadow_request(scene, batch, r, counters);
    }
}

/// Request `r`'s shadow ray (any hit): its slot's term × the transmittance
/// (`shade::point_light`'s last product: 1 or, where the ray is blocked, zero).
// Mirror of src/tracer/wavefront/wavefront_shadow.wgsl::shadow_request — change both.
fn shadow_request(
    scene: &PackedScene,
    batch: &mut Batch,
    r: usize,
    counters: &mut impl TraversalCounters,
) {
    let points = light_points(scene) as usize;
    let slot = batch.shadows.slot[r] as usize;
    let i = slot / points;
    let origin = batch.vertices.shadow_origin[i];
    let magnitude = batch.vertices.magnitude[i];
    let position = batch.shadows.position[r];
    let transmittance = if shadow_blocked(scene, origin, position, magnitude, counters) {
        0.0
    } else {
        1.0
    };
    batch.slots.term[slot] = shadowed_term(batch.slots.term[slot], transmittance);
}

/// The glass shadow rounds (scenes with refraction, after the shadow pass started each
/// request's first leg: [`glass_shadow_rounds`]); the number of rounds.
pub fn glass_shadow_pass(
    scene: &PackedScene,
    batch: &mut Batch,
    counters: &mut impl TraversalCounters,
) -> u32 {
    glass_shadow_rounds(scene, batch, counters)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// `x × 1` keeps every bit of x (the shadow pass's unblocked product), −0.0, NaN and
    /// infinities included, and a blocked ray gives +0.0 whatever the term: what
    /// `point_light` returns in both cases.
    #[test]
    fn shadowed_term_keeps_the_bits() {
        for x in [
            0.0f32,
            -0.0,
            1.5,
            -2.25,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::MIN_POSITIVE / 2.0,
        ] {
            let term = Vec3::new(x, 1.0, -x);
            let kept = shadowed_term(term, 1.0);
            assert_eq!(
                kept.to_array().map(f32::to_bits),
                term.to_array().map(f32::to_bits)
            );
            let blocked = shadowed_term(term, 0.0);
            assert_eq!(blocked.to_array().map(f32::to_bits), [0; 3]);
        }
    }
}
