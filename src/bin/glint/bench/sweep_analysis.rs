//! The figures `glint bench --sweep` derives from its measurements: the cheapest setting
//! whose error is within a bound, the log-log slope of error against n, and the rule that
//! picks the default setting (issue 16's target as one number per setting). Pure
//! functions of (time, error) pairs, so they are tested without rendering anything.

/// One measured setting: its name, time in seconds, and errors against the reference.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    pub name: String,
    pub seconds: f64,
    pub rmse: f64,
    pub flip: f64,
}

/// Which error a comparison uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Metric {
    Rmse,
    Flip,
}

impl Metric {
    pub fn of(self, m: &Measured) -> f64 {
        match self {
            Metric::Rmse => m.rmse,
            Metric::Flip => m.flip,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Metric::Rmse => "RMSE",
            Metric::Flip => "FLIP mean",
        }
    }
}

/// The fastest of `candidates` whose `metric` is at most `bound`.
pub fn cheapest_within(candidates: &[Measured], metric: Metric, bound: f64) -> Option<&Measured> {
    candidates
        .iter()
        .filter(|m| metric.of(m) <= bound)
        .min_by(|a, b| a.seconds.total_cmp(&b.seconds))
}

/// Least-squares slope of ln y against ln x over the points with x, y > 0; None with
/// fewer than two such points or no spread in x.
pub fn loglog_slope(points: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if logs.len() < 2 {
        return None;
    }
    let n = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Issue 16's target as one number for one scene: the largest of a setting's FLIP mean
/// and RMSE over uniform 4×4's and of its core time over `time_share` of 4×4's. At most 1
/// where the setting reaches 4×4's error by both measures in at most that share of its
/// time; 1.1 where it misses by 10% on the worst of the three; NaN where one is not a
/// number.
pub fn target_ratio(m: &Measured, uniform4: &Measured, time_share: f64) -> f64 {
    worst_of([
        m.flip / uniform4.flip,
        m.rmse / uniform4.rmse,
        m.seconds / (time_share * uniform4.seconds),
    ])
}

/// The largest of `ratios`, NaN if one is NaN (f64::max would drop it).
fn worst_of(ratios: impl IntoIterator<Item = f64>) -> f64 {
    ratios.into_iter().fold(f64::NEG_INFINITY, |worst, r| {
        if worst.is_nan() || r.is_nan() {
            f64::NAN
        } else {
            worst.max(r)
        }
    })
}

/// The default rule: of `candidates` (a setting's name and its measurement on each
/// scene, in the order of `uniform4`, uniform 4×4's measurements), the one whose worst
/// scene is nearest the target — the least largest [`target_ratio`] over the scenes —
/// with that ratio. A setting that meets the target on every scene has a worst ratio of
/// at most 1, and of several such settings the one with the most margin wins.
pub fn choose_default(
    candidates: &[(String, Vec<Measured>)],
    uniform4: &[Measured],
    time_share: f64,
) -> Option<(usize, f64)> {
    candidates
        .iter()
        .enumerate()
        .map(|(k, (_, per_scene))| {
            let worst = worst_of(
                per_scene
                    .iter()
                    .zip(uniform4)
                    .map(|(m, u)| target_ratio(m, u, time_share)),
            );
            (k, worst)
        })
        .filter(|(_, worst)| !worst.is_nan())
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(name: &str, seconds: f64, rmse: f64, flip: f64) -> Measured {
        Measured {
            name: name.into(),
            seconds,
            rmse,
            flip,
        }
    }

    #[test]
    fn slope_of_a_power_law_is_its_exponent() {
        let points: Vec<(f64, f64)> = [1.0, 2.0, 3.0, 4.0, 6.0, 8.0]
            .iter()
            .map(|&n: &f64| (n, 0.3 * n.powf(-1.5)))
            .collect();
        assert!((loglog_slope(&points).unwrap() + 1.5).abs() < 1e-12);
        assert_eq!(loglog_slope(&points[..1]), None);
        assert_eq!(loglog_slope(&[(2.0, 1.0), (2.0, 0.5)]), None);
    }

    #[test]
    fn the_target_ratio_is_the_worst_of_both_errors_and_the_time() {
        let u4 = m("4x4", 10.0, 0.004, 0.02);
        assert_eq!(target_ratio(&m("a", 5.0, 0.004, 0.02), &u4, 0.5), 1.0);
        assert_eq!(target_ratio(&m("b", 6.0, 0.002, 0.01), &u4, 0.5), 1.2);
        assert_eq!(target_ratio(&m("c", 1.0, 0.006, 0.01), &u4, 0.5), 1.5);
        assert_eq!(target_ratio(&m("d", 1.0, 0.002, 0.03), &u4, 0.5), 1.5);
    }

    #[test]
    fn default_is_the_setting_whose_worst_scene_is_nearest_the_target() {
        let u4 = [m("4x4", 10.0, 0.004, 0.02), m("4x4", 20.0, 0.002, 0.01)];
        let c = |name: &str, per_scene: [(f64, f64, f64); 2]| {
            let ms = per_scene.map(|(seconds, rmse, flip)| m(name, seconds, rmse, flip));
            (name.to_string(), ms.to_vec())
        };
        let all = [
            // Meets the target on the first scene with room to spare, misses the second's
            // FLIP by 30%.
            c("lopsided", [(2.0, 0.001, 0.005), (5.0, 0.001, 0.013)]),
            // Misses only the second scene's time, by 10%.
            c("chosen", [(4.0, 0.003, 0.015), (11.0, 0.0015, 0.009)]),
            // Meets the first scene exactly, misses the second's RMSE by 20%.
            c("close", [(5.0, 0.004, 0.02), (9.0, 0.0024, 0.01)]),
            c("not-measured", [(f64::NAN, 0.0, 0.0), (1.0, 0.0, 0.0)]),
        ];
        let (k, worst) = choose_default(&all, &u4, 0.5).unwrap();
        assert_eq!(all[k].0, "chosen");
        assert!((worst - 1.1).abs() < 1e-12);
        // With a fifth of 4×4's time allowed, the cheap, lopsided setting comes nearest.
        let (k, worst) = choose_default(&all, &u4, 0.2).unwrap();
        assert_eq!(all[k].0, "lopsided");
        assert!((worst - 1.3).abs() < 1e-12);
        assert_eq!(choose_default(&[], &u4, 0.5), None);
    }

    #[test]
    fn cheapest_within_takes_the_fastest_under_the_bound() {
        let ms = [
            m("a", 3.0, 0.01, 0.02),
            m("b", 1.0, 0.05, 0.01),
            m("c", 2.0, 0.02, 0.03),
        ];
        assert_eq!(cheapest_within(&ms, Metric::Flip, 0.02).unwrap().name, "b");
        assert_eq!(cheapest_within(&ms, Metric::Rmse, 0.02).unwrap().name, "c");
        assert!(cheapest_within(&ms, Metric::Rmse, 0.001).is_none());
    }
}
