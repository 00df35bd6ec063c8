//! A compensated sum, for sums of many small terms or of nearly cancelling ones.

/// A Neumaier-compensated running sum, for sums of many small terms or of
/// nearly cancelling ones (the bound, exact path means, planners).
#[derive(Clone, Copy, Debug, Default)]
pub struct Sum {
    s: f64,
    c: f64,
}

impl Sum {
    /// Adds `x`.
    #[inline]
    pub fn add(&mut self, x: f64) {
        let t = self.s + x;
        self.c += if self.s.abs() >= x.abs() {
            (self.s - t) + x
        } else {
            (x - t) + self.s
        };
        self.s = t;
    }

    /// The sum.
    #[inline]
    pub fn value(&self) -> f64 {
        self.s + self.c
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compensated_sum_keeps_what_plain_addition_loses() {
        // Neumaier's example: 1 + 1e100 + 1 − 1e100 is 2; plain addition
        // (and Kahan's, which compensates only for the smaller addend)
        // gives 0.
        let mut s = Sum::default();
        for x in [1.0, 1e100, 1.0, -1e100] {
            s.add(x);
        }
        assert_eq!(s.value(), 2.0);
        // Ten million tenths: plain addition drifts by about 1e-4 here;
        // the compensated sum is the correctly rounded 1e6.
        let mut s = Sum::default();
        let mut plain = 0.0f64;
        for _ in 0..10_000_000 {
            s.add(0.1);
            plain += 0.1;
        }
        assert!(
            (plain - 1e6).abs() > 1e-6,
            "the case must defeat plain addition"
        );
        assert_eq!(s.value(), 1e6);
    }
}
