//! Quantiles: of sorted data (R's type 7), and Student's t at 97.5%.

/// The two-sided 95% quantile of Student's t with `df` degrees of freedom
/// (NaN for 0): within 5 × 10⁻⁴ up to 30 (a three-decimal table) and
/// 3 × 10⁻⁸ above.
pub fn t975(df: u64) -> f64 {
    // As printed t tables give them. Six decimals would move the intervals
    // of samples of 2–31 (the bootstrap's expanded tails use this), and a
    // result file's statistics must match the ones recomputed from its
    // rows, so every file written with this table would then be refused.
    const TABLE: [f64; 30] = [
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
        2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
        2.052, 2.048, 2.045, 2.042,
    ];
    match df {
        0 => f64::NAN,
        1..=30 => TABLE[df as usize - 1],
        _ => {
            // Cornish–Fisher expansion around z (Abramowitz & Stegun 26.7.5);
            // error below 3e-8 for df > 30 (largest at 31).
            let z: f64 = 1.959_963_984_540_054;
            let v = df as f64;
            let z3 = z.powi(3);
            let z5 = z.powi(5);
            let z7 = z.powi(7);
            let z9 = z.powi(9);
            z + (z3 + z) / (4.0 * v)
                + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * v * v)
                + (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / (384.0 * v.powi(3))
                + (79.0 * z9 + 776.0 * z7 + 1482.0 * z5 - 1920.0 * z3 - 945.0 * z)
                    / (92160.0 * v.powi(4))
        }
    }
}

/// The quantile `q` of sorted data (linear interpolation, R type 7).
pub fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let h = (sorted.len() - 1) as f64 * q;
    let lo = h.floor() as usize;
    let hi = h.ceil() as usize;
    sorted[lo] + (h - lo as f64) * (sorted[hi] - sorted[lo])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn t_quantiles_match_reference_values() {
        // scipy.stats.t.ppf(0.975, df) to nine decimals: the table up to
        // df = 30 (three decimals, so within 5e-4) and the expansion above
        // it, which a slip moving t975(31) by 5e-8 or more fails.
        let reference = [
            (1, 12.706204736),
            (2, 4.302652730),
            (4, 2.776445105),
            (10, 2.228138852),
            (26, 2.055529439),
            (30, 2.042272456),
            (31, 2.039513446),
            (32, 2.036933343),
            (40, 2.021075390),
            (50, 2.008559112),
            (64, 1.997729654),
            (100, 1.983971519),
            (128, 1.978670850),
            (200, 1.971896224),
            (1000, 1.962339081),
            (1_000_000, 1.959966357),
        ];
        for (df, t) in reference {
            let tol = if df <= 30 { 5e-4 } else { 5e-8 };
            assert!(
                (t975(df) - t).abs() < tol,
                "t975({df}) = {} against {t}",
                t975(df)
            );
        }
        assert!(t975(0).is_nan(), "no degrees of freedom: no quantile");
        // Decreasing in df, through the seam between table and expansion.
        for df in 1..200 {
            assert!(t975(df + 1) < t975(df), "t975 rises at df = {df}");
        }
    }
}
