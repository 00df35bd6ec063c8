//! `experiment --dry-run`: what a run would do (the normalised spec, its
//! points and units, every series' configuration) and about how long it
//! would take, from a short calibration run.

use super::args::int_flag;
use super::usage::UsageError;
use crate::config::{self, Config};
use crate::experiment::{self, Plan};
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// Calibration seconds without `--calibration`.
const DEFAULT_CALIBRATION: u64 = 3;

/// Every parameter a run of `cfg` reads, but the seed, as `key=value`.
pub(super) fn config_line(cfg: &Config) -> String {
    config::params()
        .iter()
        .filter(|e| e.param().key != "seed" && e.applies_to(cfg))
        .map(|e| format!("{}={}", e.param().key, e.value(cfg).text()))
        .collect::<Vec<_>>()
        .join(" ")
}

/// `83.0` → "1 min 23 s".
pub(super) fn duration_text(s: f64) -> String {
    if s < 60.0 {
        return format!("{s:.1} s");
    }
    let m = (s / 60.0).floor();
    if m < 60.0 {
        return format!("{m} min {:.0} s", s - 60.0 * m);
    }
    format!("{} h {} min", (m / 60.0).floor(), m % 60.0)
}

/// A calibration: seconds per unit of the points measured.
pub(super) struct Calibration {
    /// `(point, seconds)` of each unit run.
    pub measured: Vec<(usize, f64)>,
    /// Wall-clock seconds the calibration took.
    pub seconds: f64,
}

/// Runs trial 0 of the points (the first units of `from..to`), series by
/// series at each x value so that every series is sampled early, starting
/// no unit after `budget`. A unit started runs to its end.
pub(super) fn calibrate(
    plan: &Plan,
    from: u64,
    to: u64,
    budget: Duration,
    pool: &rayon::ThreadPool,
) -> Calibration {
    let points = plan.points.len() as u64;
    let mut units: Vec<u64> = (from..to.min(from + points)).collect();
    units.sort_by_key(|&u| {
        let p = &plan.points[(u % points) as usize];
        (p.x, p.series)
    });
    let t0 = Instant::now();
    let measured = pool.install(|| {
        units
            .par_iter()
            .with_max_len(1)
            .filter_map(|&u| {
                if t0.elapsed() >= budget {
                    return None;
                }
                let t = Instant::now();
                experiment::run_unit(plan, u, None);
                Some(((u % points) as usize, t.elapsed().as_secs_f64()))
            })
            .collect()
    });
    Calibration {
        measured,
        seconds: t0.elapsed().as_secs_f64(),
    }
}

/// Estimated seconds of work (on one thread) for units `from..to`: each
/// point's measured unit cost, else its series' mean, else the mean of all.
pub(super) fn estimate(plan: &Plan, from: u64, to: u64, cal: &Calibration) -> Option<f64> {
    if cal.measured.is_empty() {
        return None;
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let all: Vec<f64> = cal.measured.iter().map(|m| m.1).collect();
    let cost = |p: usize| {
        if let Some(&(_, s)) = cal.measured.iter().find(|m| m.0 == p) {
            return s;
        }
        let series = plan.points[p].series;
        let same: Vec<f64> = cal
            .measured
            .iter()
            .filter(|m| plan.points[m.0].series == series)
            .map(|m| m.1)
            .collect();
        if same.is_empty() {
            mean(&all)
        } else {
            mean(&same)
        }
    };
    let points = plan.points.len() as u64;
    // Units of point p in from..to: those u ≡ p (mod points).
    let count = |p: u64| {
        let first = from + (p + points - from % points) % points;
        if first >= to {
            0
        } else {
            (to - 1 - first) / points + 1
        }
    };
    Some(
        (0..points)
            .map(|p| cost(p as usize) * count(p) as f64)
            .sum(),
    )
}

pub(super) fn dry_run(
    m: &clap::ArgMatches,
    plan: &Plan,
    from: u64,
    to: u64,
    threads: usize,
    pool: &rayon::ThreadPool,
) -> Result<(), UsageError> {
    let budget = int_flag(m, "calibration", 0, 600)?.unwrap_or(DEFAULT_CALIBRATION);
    let h = &plan.header;
    out!("spec: {}", plan.spec.to_text());
    out!(
        "{}: {} points ({} series × {} x values) × {} {} = {} units",
        h.name,
        plan.points.len(),
        h.series.len(),
        h.x.values.len(),
        plan.trials(),
        if h.kind == experiment::Kind::Targets {
            "samples"
        } else {
            "trials"
        },
        plan.total_units()
    );
    if (from, to) != (0, plan.total_units()) {
        out!("this shard: units {from}..{to} ({} units)", to - from);
    }
    if let Some(key) = &h.x.key {
        out!("x: {key} = {}", h.x.values.join(", "));
    }
    for (si, label) in h.series.iter().enumerate() {
        let p = plan
            .points
            .iter()
            .find(|p| p.series == si)
            .expect("every series has points");
        out!("series {label:?}: {}", config_line(&p.config));
    }
    if budget == 0 {
        out!("no calibration (--calibration 0), so no estimate");
        return Ok(());
    }
    let cal = calibrate(plan, from, to, Duration::from_secs(budget), pool);
    let measured = cal.measured.len();
    out!(
        "calibration: trial 0 of {measured} of {} points in {:.1} s on {threads} threads",
        plan.points.len(),
        cal.seconds
    );
    match estimate(plan, from, to, &cal) {
        Some(work) => out!(
            "estimated time: about {} on {threads} threads ({} of work; units took {:.3}–{:.3} s; one trial per point \
             is a rough guide, as an MCTS episode trapped to the step cap costs far more than most)",
            duration_text(work / threads as f64),
            duration_text(work),
            cal.measured.iter().map(|m| m.1).fold(f64::INFINITY, f64::min),
            cal.measured.iter().map(|m| m.1).fold(0.0, f64::max)
        ),
        None => out!("no unit finished within the calibration, so no estimate"),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn estimates_count_each_points_units_in_the_range() {
        let plan = Plan::from_spec_text(
            r#"{"name":"custom","trials":5,"sweep":{"key":"n","values":["5","6","7"]}}"#,
        )
        .unwrap();
        // Point p costs p + 1 seconds; 3 points × 5 trials = units 0..15.
        let all = Calibration {
            measured: vec![(0, 1.0), (1, 2.0), (2, 3.0)],
            seconds: 0.0,
        };
        assert_eq!(estimate(&plan, 0, 15, &all), Some(5.0 * 6.0));
        // Units 4..11: points 1,2,0,1,2,0,1.
        assert_eq!(
            estimate(&plan, 4, 11, &all),
            Some(3.0 * 2.0 + 2.0 * 3.0 + 2.0)
        );
        // An unmeasured point costs the series' mean (one series here).
        let some = Calibration {
            measured: vec![(0, 1.0), (2, 3.0)],
            seconds: 0.0,
        };
        assert_eq!(estimate(&plan, 0, 3, &some), Some(1.0 + 2.0 + 3.0));
        let none = Calibration {
            measured: vec![],
            seconds: 0.0,
        };
        assert_eq!(estimate(&plan, 0, 15, &none), None);
        assert_eq!(duration_text(83.0), "1 min 23 s");
        assert_eq!(duration_text(7.25), "7.2 s");
        assert_eq!(duration_text(7500.0), "2 h 5 min");
    }
}
