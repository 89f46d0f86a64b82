//! Feature combinations for the kernel instrument: scenes that exist only as a
//! [`SceneFeatures`] set (`glint kernels --features`, `--feature-combinations`), so that
//! the register budgets are checked over the combinations a user's scene may have, not
//! only over the scenes in `scenes/`.
//!
//! Every one of the 17 features changes the compiled modules (each is named by some
//! `// #if` of `shaders/`), so all their combinations are 2^17 (84 672 that a scene can
//! have), at about 5 s of compiling each (every render entry in both wave sizes): days.
//! [`feature_combinations`] is a covering set instead, 42 combinations:
//! - the **largest modules**, where register demand peaks: every feature, and every
//!   feature but one (without the mesh, without smooth shading too: 18 sets), which
//!   hold each combination of features that a smaller set would hold together with
//!   everything else;
//! - a **user's scene** that broke the budgets while both other groups met them
//!   (glass, a mesh, a torus, a CSG cube minus a cylinder, a sphere; `wavefront_leg_closest`
//!   spilled 2 SGPRs in wave64): a combination known to matter stays tested;
//! - a **strength-3 covering array**: for any three features, each of their 8 on/off
//!   patterns is in some set (that a scene can have), so an interaction of up to three
//!   features, with or without the others, is compiled at least once; built greedily
//!   (each next set the one that covers the most patterns not yet covered, ties to the
//!   smallest bits), deterministic, starting from no feature and every feature.
//!
//! What a scene can have ([`possible`]): smooth shading only on a mesh, CSG only with a
//! leaf primitive of its own (a sphere, cube, cylinder, cone or torus), procedural
//! textures only with the texture or bump slot they fill.

use super::SceneFeatures;

/// How a combination is named in the instrument's rows: `features: ` and the names that
/// `--features` reads back (`none` for none).
pub fn name(features: SceneFeatures) -> String {
    if features == SceneFeatures::empty() {
        return "features: none".to_string();
    }
    format!("features: {features}")
}

/// A feature set from names (`SceneFeatures::ALL`'s: `sphere`, `area-light`, …) separated
/// by spaces, commas or `+`; `none` is the empty set.
pub fn parse(text: &str) -> Result<SceneFeatures, String> {
    let mut features = SceneFeatures::empty();
    let words = text
        .split([' ', ',', '+'])
        .map(str::trim)
        .filter(|w| !w.is_empty());
    for word in words {
        if word == "none" {
            continue;
        }
        let flag = SceneFeatures::ALL
            .iter()
            .find(|(_, n)| *n == word)
            .map(|(f, _)| *f)
            .ok_or_else(|| {
                let names: Vec<&str> = SceneFeatures::ALL.iter().map(|(_, n)| *n).collect();
                format!("unknown feature '{word}' (features: {})", names.join(", "))
            })?;
        features.insert(flag);
    }
    Ok(features)
}

/// Whether a scene can have exactly `features` (see the module's header).
pub fn possible(features: SceneFeatures) -> bool {
    let leaves = [
        SceneFeatures::SPHERE,
        SceneFeatures::CUBE,
        SceneFeatures::CYLINDER,
        SceneFeatures::CONE,
        SceneFeatures::TORUS,
    ];
    let smooth = features.contains(SceneFeatures::SMOOTH);
    let csg = features.contains(SceneFeatures::CSG);
    let procedural = features.contains(SceneFeatures::PROCEDURAL);
    (!smooth || features.contains(SceneFeatures::MESH))
        && (!csg || leaves.iter().any(|&l| features.contains(l)))
        && (!procedural || features.uses_textures())
}

/// Every feature.
fn every_feature() -> SceneFeatures {
    SceneFeatures::ALL
        .iter()
        .fold(SceneFeatures::empty(), |mut set, (f, _)| {
            set.insert(*f);
            set
        })
}

/// The budget test's combinations (the module's header says which and why): every
/// feature, every feature but one, a user's scene, then a strength-3 covering array,
/// without repeats.
pub fn feature_combinations() -> Vec<SceneFeatures> {
    let all = every_feature();
    let mut sets = vec![all];
    for (f, _) in SceneFeatures::ALL {
        let mut set = SceneFeatures(all.0 & !f.0);
        if *f == SceneFeatures::MESH {
            // Smooth shading goes with the mesh.
            set = SceneFeatures(set.0 & !SceneFeatures::SMOOTH.0);
        }
        sets.push(set);
    }
    // A new user's small scene that broke them (glass, a mesh, a torus, a cube minus a
    // cylinder, a sphere): in neither group above.
    sets.push(SceneFeatures(
        [
            SceneFeatures::SPHERE,
            SceneFeatures::CUBE,
            SceneFeatures::MESH,
            SceneFeatures::GRID,
            SceneFeatures::CYLINDER,
            SceneFeatures::TORUS,
            SceneFeatures::CSG,
            SceneFeatures::REFRACTION,
        ]
        .iter()
        .fold(0, |bits, f| bits | f.0),
    ));
    for set in covering_array(3) {
        if !sets.contains(&set) {
            sets.push(set);
        }
    }
    sets
}

/// A greedy covering array of `strength` over the features: sets (each [`possible`])
/// such that for any `strength` features, every on/off pattern of them that some
/// possible set has is in one of the sets. Starts from no feature and every feature.
pub fn covering_array(strength: usize) -> Vec<SceneFeatures> {
    let n = SceneFeatures::ALL.len();
    let flags: Vec<u32> = SceneFeatures::ALL.iter().map(|(f, _)| f.0).collect();
    let tuples = feature_tuples(n, strength);
    let patterns = 1usize << strength;
    // Pattern p of tuple t is covered[t * patterns + p].
    let pattern = |set: u32, tuple: &[usize]| {
        tuple.iter().enumerate().fold(0usize, |p, (bit, &i)| {
            p | (usize::from(set & flags[i] != 0) << bit)
        })
    };
    let candidates: Vec<u32> = (0u32..1 << n)
        .map(|bits| {
            (0..n)
                .filter(|&i| bits >> i & 1 == 1)
                .fold(0, |s, i| s | flags[i])
        })
        .filter(|&set| possible(SceneFeatures(set)))
        .collect();
    let new_patterns = |set: u32, covered: &[bool]| {
        tuples
            .iter()
            .enumerate()
            .filter(|(t, tuple)| !covered[t * patterns + pattern(set, tuple)])
            .count()
    };
    let mut covered = vec![false; tuples.len() * patterns];
    let mut chosen = Vec::new();
    let mut next = Some(0);
    while let Some(set) = next {
        for (t, tuple) in tuples.iter().enumerate() {
            covered[t * patterns + pattern(set, tuple)] = true;
        }
        chosen.push(SceneFeatures(set));
        next = if chosen.len() == 1 {
            Some(every_feature().0)
        } else {
            // The first of the sets that cover the most new patterns, if any does.
            let best = candidates
                .iter()
                .map(|&c| (new_patterns(c, &covered), c))
                .fold((0, 0), |a, b| if b.0 > a.0 { b } else { a });
            (best.0 > 0).then_some(best.1)
        };
    }
    chosen
}

/// Every `strength`-subset of 0..n, as sorted index lists.
fn feature_tuples(n: usize, strength: usize) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut tuple: Vec<usize> = (0..strength).collect();
    loop {
        out.push(tuple.clone());
        // The rightmost index that can still move right, moved, the rest after it.
        let Some(i) = (0..strength).rev().find(|&i| tuple[i] < n - strength + i) else {
            return out;
        };
        tuple[i] += 1;
        for j in i + 1..strength {
            tuple[j] = tuple[j - 1] + 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every possible feature set (2^n of the n features less the impossible ones; the
    /// flags' bits are not contiguous, so each subset is made flag by flag).
    fn possible_sets() -> Vec<SceneFeatures> {
        let flags: Vec<u32> = SceneFeatures::ALL.iter().map(|(f, _)| f.0).collect();
        (0u32..1 << flags.len())
            .map(|subset| {
                let bits = (0..flags.len())
                    .filter(|i| subset & (1 << i) != 0)
                    .fold(0, |bits, i| bits | flags[i]);
                SceneFeatures(bits)
            })
            .filter(|&s| possible(s))
            .collect()
    }

    #[test]
    fn the_covering_array_holds_every_pattern_of_every_three_features() {
        let sets = covering_array(3);
        let flags: Vec<u32> = SceneFeatures::ALL.iter().map(|(f, _)| f.0).collect();
        let all = possible_sets();
        for tuple in feature_tuples(flags.len(), 3) {
            let mask = tuple.iter().fold(0, |m, &i| m | flags[i]);
            for pattern in all.iter().map(|s| s.0 & mask) {
                assert!(
                    sets.iter().any(|s| s.0 & mask == pattern),
                    "no set has {} of {}",
                    SceneFeatures(pattern),
                    SceneFeatures(mask)
                );
            }
        }
        assert!(sets.iter().all(|&s| possible(s)));
        assert_eq!(feature_tuples(14, 3).len(), 364);
    }

    #[test]
    fn the_combinations_hold_the_largest_modules_once_each() {
        let sets = feature_combinations();
        let all = every_feature();
        assert_eq!(sets[0], all);
        for (f, name) in SceneFeatures::ALL {
            let but = SceneFeatures(all.0 & !f.0);
            let but_smooth = SceneFeatures(but.0 & !SceneFeatures::SMOOTH.0);
            let held = sets.contains(&but) || (!possible(but) && sets.contains(&but_smooth));
            assert!(held, "all but {name}");
        }
        let mut unique = sets.clone();
        unique.sort_by_key(|s| s.0);
        unique.dedup();
        assert_eq!(unique.len(), sets.len(), "no set twice");
        assert!(sets.iter().all(|&s| possible(s)));
        assert_eq!(feature_combinations(), sets, "the same sets every time");
    }

    #[test]
    fn names_read_back() {
        for set in feature_combinations() {
            let name = name(set);
            let names = name.strip_prefix("features: ").unwrap();
            assert_eq!(parse(names), Ok(set), "{name}");
        }
        assert_eq!(parse("none"), Ok(SceneFeatures::empty()));
        assert_eq!(
            parse("mesh+csg, area-light"),
            Ok(SceneFeatures(
                SceneFeatures::MESH.0 | SceneFeatures::CSG.0 | SceneFeatures::AREA_LIGHT.0
            ))
        );
        let err = parse("mesh glas").unwrap_err();
        assert!(
            err.contains("unknown feature 'glas'") && err.contains("refraction"),
            "{err}"
        );
    }

    #[test]
    fn possible_sets_follow_what_packing_allows() {
        assert!(!possible(SceneFeatures::SMOOTH));
        assert!(!possible(SceneFeatures::CSG));
        assert!(!possible(SceneFeatures::PROCEDURAL));
        assert!(possible(SceneFeatures(
            SceneFeatures::PROCEDURAL.0 | SceneFeatures::BUMP.0
        )));
        assert!(possible(SceneFeatures(
            SceneFeatures::CSG.0 | SceneFeatures::TORUS.0
        )));
        // Mesh: none, flat, smooth; CSG with 63 of the 64 leaf patterns; 6 free flags;
        // texture, bump and procedural in 7 of their 8 patterns.
        assert_eq!(possible_sets().len(), 3 * 63 * 64 * 7);
    }
}
