//! Periodic value noise from an integer hash: smooth, seeded, and tileable (the lattice
//! wraps at the period), so a texture made from it repeats without a seam. Only integer
//! arithmetic and correctly rounded float operations (+ − × ÷, floor), no transcendental
//! functions: the same bytes on every platform.

/// A hash of a lattice point and a seed to [0, 1).
fn hash(x: u32, y: u32, seed: u32) -> f32 {
    let mut h =
        x.wrapping_mul(0x8DA6_B343) ^ y.wrapping_mul(0xD816_3841) ^ seed.wrapping_mul(0xCB1A_B31F);
    h ^= h >> 15;
    h = h.wrapping_mul(0x2C1B_3C6D);
    h ^= h >> 12;
    h = h.wrapping_mul(0x297A_2D39);
    h ^= h >> 15;
    (h >> 8) as f32 / (1u32 << 24) as f32
}

/// Value noise in [0, 1) at (x, y) in lattice units, periodic with `period_x` ×
/// `period_y` lattice cells, smoothly interpolated (cubic fade).
pub fn value_noise(x: f32, y: f32, period_x: u32, period_y: u32, seed: u32) -> f32 {
    let (fx, fy) = (x.floor(), y.floor());
    let (tx, ty) = (fade(x - fx), fade(y - fy));
    let ix = (fx as i64).rem_euclid(period_x as i64) as u32;
    let iy = (fy as i64).rem_euclid(period_y as i64) as u32;
    let (jx, jy) = ((ix + 1) % period_x, (iy + 1) % period_y);
    let top = lerp(hash(ix, iy, seed), hash(jx, iy, seed), tx);
    let bottom = lerp(hash(ix, jy, seed), hash(jx, jy, seed), tx);
    lerp(top, bottom, ty)
}

/// Sum of `octaves` of value noise, each twice as fine and half as strong, normalised
/// to [0, 1); (u, v) ∈ [0, 1)² covers one period of `base_x` × `base_y` cells.
pub fn fractal(u: f32, v: f32, base_x: u32, base_y: u32, octaves: u32, seed: u32) -> f32 {
    let (mut sum, mut weight, mut total) = (0.0, 1.0, 0.0);
    for octave in 0..octaves {
        let (px, py) = (base_x << octave, base_y << octave);
        sum += weight * value_noise(u * px as f32, v * py as f32, px, py, seed + octave);
        total += weight;
        weight *= 0.5;
    }
    sum / total
}

fn fade(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
}

fn lerp(a: f32, b: f32, t: f32) -> f32 {
    a + (b - a) * t
}
