//! The figures `glint bench --sweep` derives from its measurements: the cheapest setting
//! whose error is within a bound, the log-log slope of error against n, and the rule that
//! picks the default setting. Pure functions of (time, error) pairs, so they are tested
//! without rendering anything.

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

/// The default rule: of `candidates` (a setting's name and its measurement on each
/// scene), among those whose FLIP mean is at most `flip_bound` on every scene, the ones
/// whose total seconds are within a factor 1 + `time_tie` of the least count as equally
/// fast (one run cannot tell them apart), and of those the one with the least summed FLIP
/// mean wins. Returns its index.
pub fn choose_default(
    candidates: &[(String, Vec<Measured>)],
    flip_bound: f64,
    time_tie: f64,
) -> Option<usize> {
    let within: Vec<(usize, f64, f64)> = candidates
        .iter()
        .enumerate()
        .filter(|(_, (_, per_scene))| per_scene.iter().all(|m| m.flip <= flip_bound))
        .map(|(k, (_, per_scene))| {
            let seconds = per_scene.iter().map(|m| m.seconds).sum::<f64>();
            let flip = per_scene.iter().map(|m| m.flip).sum::<f64>();
            (k, seconds, flip)
        })
        .collect();
    let fastest = within.iter().map(|w| w.1).min_by(f64::total_cmp)?;
    within
        .iter()
        .filter(|w| w.1 <= fastest * (1.0 + time_tie))
        .min_by(|a, b| a.2.total_cmp(&b.2))
        .map(|w| w.0)
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
    fn default_is_the_cheapest_within_the_bound_everywhere() {
        let c = |name: &str, per_scene: &[(f64, f64)]| {
            (
                name.to_string(),
                per_scene
                    .iter()
                    .map(|&(seconds, flip)| m(name, seconds, 0.0, flip))
                    .collect::<Vec<_>>(),
            )
        };
        let all = [
            c("slow", &[(3.0, 0.01), (3.0, 0.01)]),
            c("cheap-but-misses-one", &[(0.5, 0.01), (0.5, 0.03)]),
            c("chosen", &[(1.0, 0.02), (1.5, 0.015)]),
            c("tied-but-worse", &[(1.1, 0.02), (1.5, 0.019)]),
        ];
        assert_eq!(choose_default(&all, 0.02, 0.0), Some(2));
        assert_eq!(choose_default(&all, 0.02, 0.1), Some(2));
        assert_eq!(choose_default(&all, 0.01, 0.1), Some(0));
        assert_eq!(choose_default(&all, 0.001, 0.1), None);
    }

    #[test]
    fn of_settings_tied_in_time_the_default_is_the_most_accurate() {
        let c = |name: &str, seconds: f64, flip: f64| {
            (name.to_string(), vec![m(name, seconds, 0.0, flip)])
        };
        let all = [
            c("fastest", 1.0, 0.019),
            c("within-the-tie", 1.09, 0.012),
            c("beyond-it", 1.2, 0.005),
        ];
        assert_eq!(choose_default(&all, 0.02, 0.1), Some(1));
        assert_eq!(choose_default(&all, 0.02, 0.0), Some(0));
        assert_eq!(choose_default(&all, 0.02, 0.25), Some(2));
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
