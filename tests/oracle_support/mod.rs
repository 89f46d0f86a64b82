//! Shared by the f64-oracle stress tests (`intersect_oracle`, `cylinder_cone_oracle`,
//! `torus_oracle`): a seeded generator, per-case seeds, f32/f64 conversions, the f32
//! rounding floor, the legality check every traced t must pass, and the oracle answer and
//! agreement tally the three share; and the rmse of two films, which the image oracles
//! (`area_lights`, `depth_of_field`) measure error by.
#![allow(dead_code)]

use glam::{DQuat, DVec3, Vec3};
use glint::constants::T_MISS;

pub struct Rng(pub u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.f64()
    }

    pub fn log_uniform(&mut self, a: f64, b: f64) -> f64 {
        (a.ln() + (b.ln() - a.ln()) * self.f64()).exp()
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    pub fn unit_vector(&mut self) -> DVec3 {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, std::f64::consts::TAU);
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    /// Uniform random rotation (Shoemake).
    pub fn rotation(&mut self) -> DQuat {
        let (u1, u2, u3) = (
            self.f64(),
            self.range(0.0, std::f64::consts::TAU),
            self.range(0.0, std::f64::consts::TAU),
        );
        let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
        DQuat::from_xyzw(a * u2.sin(), a * u2.cos(), b * u3.sin(), b * u3.cos()).normalize()
    }
}

pub const MARGIN: f64 = 1e-4;

/// Seed of case `i` of a test (distinct streams per test via `salt`).
pub fn case_seed(salt: u64, i: u64) -> u64 {
    let mut r = Rng::new(salt ^ i.wrapping_mul(0xD1B5_4A32_D192_ED03));
    r.next_u64()
}

/// Few-ulp rounding floor, in world units, of f32 arithmetic on coordinates up to
/// magnitude `m`.
pub fn f32_floor(m: f64) -> f64 {
    8.0 * f32::EPSILON as f64 * m
}

/// Largest |coordinate| of a point.
pub fn mag(p: DVec3) -> f64 {
    p.abs().max_element()
}

pub fn v32(v: DVec3) -> Vec3 {
    v.as_vec3()
}

pub fn v64(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

/// An f32 ray from `origin` aimed at `target` (both rounded to f32 first), unit direction.
pub fn aim(origin: DVec3, target: DVec3) -> (Vec3, Vec3) {
    let o = v32(origin);
    let d = (v64(v32(target)) - v64(o)).normalize();
    (o, v32(d).normalize())
}

/// The only legal results of an intersection routine: `T_MISS` or a t in (0, t_max).
pub fn assert_legal_t(t: f32, t_max: f32, what: &str, seed: u64) {
    assert!(
        t == T_MISS || (t > 0.0 && t < t_max),
        "{what}: t = {t} is neither T_MISS nor in (0, {t_max}) (seed {seed:#x})"
    );
}

/// The f64 oracle's answer for one ray.
pub struct Oracle {
    /// Nearest hit in (0, t_max), if any.
    pub t: Option<f64>,
    /// The ray passes within the test's band around a silhouette: not checked.
    pub grazing: bool,
    /// f32 rounding floor of t (world units) for this hit, added to the 1e-4·t tolerance.
    pub floor: f64,
}

/// Agreement of a tracer's t with the oracle over many rays.
#[derive(Default, Debug)]
pub struct Agreement {
    pub rays: usize,
    pub grazing: usize,
    pub hits: usize,
    pub misses: usize,
    /// Oracle hit, tracer missed.
    pub false_misses: usize,
    /// Oracle miss, tracer hit.
    pub false_hits: usize,
    /// Both hit, |Δt| > 1e-4·t + f32 floor.
    pub bad_t: usize,
    pub worst_rel_dt: f64,
    /// Largest |Δt| / (1e-4·t + f32 floor): the share of the tolerance used.
    pub worst_tolerance_used: f64,
    /// (seed, message) of the first few disagreements.
    pub examples: Vec<(u64, String)>,
}

/// Hits and misses each must be more than 1/`hits` and 1/`misses` of the checked rays
/// for the agreement to mean anything.
pub struct MinMix {
    pub hits: usize,
    pub misses: usize,
}

impl Agreement {
    pub fn record(&mut self, seed: u64, oracle: &Oracle, t: f32, detail: impl Fn() -> String) {
        self.rays += 1;
        if oracle.grazing {
            self.grazing += 1;
            return;
        }
        let bad = match oracle.t {
            Some(t_ref) => {
                self.hits += 1;
                if t == T_MISS {
                    self.false_misses += 1;
                    true
                } else {
                    let dt = (t as f64 - t_ref).abs();
                    self.worst_rel_dt = self.worst_rel_dt.max(dt / t_ref);
                    let tolerance = 1e-4 * t_ref + oracle.floor;
                    self.worst_tolerance_used = self.worst_tolerance_used.max(dt / tolerance);
                    let bad = dt > tolerance;
                    self.bad_t += bad as usize;
                    bad
                }
            }
            None => {
                self.misses += 1;
                self.false_hits += (t != T_MISS) as usize;
                t != T_MISS
            }
        };
        if bad && self.examples.len() < 8 {
            self.examples.push((
                seed,
                format!("oracle {:?}, got {t}: {}", oracle.t, detail()),
            ));
        }
    }

    /// Prints the figures and asserts that something was checked, the hit/miss mix (when
    /// `mix` is given) and at most 1e-4 of the checked rays disagreeing. `context` (a
    /// salt, say) goes into the failure messages.
    pub fn check(&self, what: &str, context: &str, mix: Option<MinMix>) {
        let checked = self.rays - self.grazing;
        let wrong = self.false_misses + self.false_hits + self.bad_t;
        let rate = 1.0 - wrong as f64 / checked.max(1) as f64;
        println!(
            "{what}: {} rays, {} grazing skipped, {checked} checked ({} hits, {} misses); \
             {wrong} disagree ({} false misses, {} false hits, {} bad t); \
             agreement {:.6}%; worst |Δt|/t {:.3e}, worst share of tolerance {:.3}",
            self.rays,
            self.grazing,
            self.hits,
            self.misses,
            self.false_misses,
            self.false_hits,
            self.bad_t,
            rate * 100.0,
            self.worst_rel_dt,
            self.worst_tolerance_used
        );
        for (seed, msg) in &self.examples {
            println!("  seed {seed:#x}: {msg}");
        }
        assert!(checked > 0, "{what}: nothing checked ({context})");
        if let Some(mix) = mix {
            assert!(
                self.hits > checked / mix.hits && self.misses > checked / mix.misses,
                "{what}: too few hits or misses to mean anything ({context}): {self:?}"
            );
        }
        assert!(
            wrong as f64 <= 1e-4 * checked as f64,
            "{what}: {wrong} of {checked} non-grazing rays disagree with the f64 oracle \
             ({context}; first: {:?})",
            self.examples
        );
    }
}

/// Root-mean-square difference of two films of one size, over every channel of every
/// pixel (linear values).
pub fn film_rmse(a: &glint::film::Film, b: &glint::film::Film) -> f64 {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let (sum, count) = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(p, q)| (0..3).map(move |c| (p[c] - q[c]) as f64))
        .fold((0.0, 0usize), |(s, n), d| (s + d * d, n + 1));
    (sum / count as f64).sqrt()
}
