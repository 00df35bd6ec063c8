//! The budget of one decision: a number of loops, or a time in milliseconds
//! on a clock the host provides.

use crate::game::counters::Counters;

/// The default clock: monotonic milliseconds natively. In wasm the facade
/// sets one that reads `performance.now()`.
#[cfg(not(target_arch = "wasm32"))]
pub fn default_clock() -> f64 {
    use std::sync::OnceLock;
    use std::time::Instant;
    static T0: OnceLock<Instant> = OnceLock::new();
    T0.get_or_init(Instant::now).elapsed().as_secs_f64() * 1e3
}

/// Without a host clock a time budget can never expire, so a decision also
/// ends after [`NO_CLOCK_LOOPS`] loops.
#[cfg(target_arch = "wasm32")]
pub fn default_clock() -> f64 {
    0.0
}

/// The loop count at which a time budget ends even if the clock never advances.
pub const NO_CLOCK_LOOPS: u32 = 10_000_000;

/// Loops or milliseconds per decision, and what the decision under way has used.
#[derive(Clone, Debug)]
pub struct Budget {
    loops: u32,
    ms: Option<f64>,
    clock: fn() -> f64,
    /// When the decision under way started; `None` between decisions.
    t0: Option<f64>,
    loops_done: u32,
    spent: Counters,
}

impl Budget {
    /// `loops` per decision, or `ms` milliseconds when given.
    pub fn new(loops: u32, ms: Option<f64>) -> Budget {
        Budget {
            loops,
            ms,
            clock: default_clock,
            t0: None,
            loops_done: 0,
            spent: Counters::default(),
        }
    }

    /// Sets the millisecond clock that time budgets read.
    pub fn set_clock(&mut self, clock: fn() -> f64) {
        self.clock = clock;
    }

    /// The clock time budgets read.
    pub fn clock(&self) -> fn() -> f64 {
        self.clock
    }

    /// The time budget in milliseconds, if decisions are timed.
    pub fn ms(&self) -> Option<f64> {
        self.ms
    }

    /// The clock's time now, in milliseconds.
    pub fn now(&self) -> f64 {
        (self.clock)()
    }

    /// True while a decision is under way.
    pub fn is_open(&self) -> bool {
        self.t0.is_some()
    }

    /// Starts a decision: the clock and the counters start from zero.
    pub fn open(&mut self) {
        self.t0 = Some((self.clock)());
        self.loops_done = 0;
        self.spent = Counters::default();
    }

    /// Ends the decision (its counters stay readable until the next one).
    pub fn close(&mut self) {
        self.t0 = None;
    }

    /// True once the decision under way has used its budget. A decision
    /// always runs at least one loop.
    pub fn spent(&self) -> bool {
        match self.ms {
            None => self.loops_done >= self.loops,
            Some(ms) => {
                self.loops_done >= NO_CLOCK_LOOPS
                    || (self.loops_done > 0 && (self.clock)() - self.t0.unwrap_or(0.0) >= ms)
            }
        }
    }

    /// Records one loop and its rollout.
    pub fn record(&mut self, steps: u32, detected: bool) {
        self.loops_done += 1;
        self.spent.add(steps, detected);
    }

    /// Loops done in the decision under way (or the last one).
    pub fn loops_done(&self) -> u32 {
        self.loops_done
    }

    /// Rollout counters of the decision under way (or the last one).
    pub fn counters(&self) -> Counters {
        self.spent
    }
}

#[cfg(all(test, not(target_arch = "wasm32")))]
mod tests {
    use super::*;

    #[test]
    fn the_native_clock_counts_milliseconds() {
        // A budget of `ms` milliseconds must last that long: after a 25 ms
        // sleep the clock has advanced by at least 25 (a clock in seconds,
        // or a constant, would show 0.025 or 0) and by less than 10 000
        // (one in microseconds would show 25 000).
        let t0 = default_clock();
        std::thread::sleep(std::time::Duration::from_millis(25));
        let dt = default_clock() - t0;
        assert!((25.0..10_000.0).contains(&dt), "{dt} ms for a 25 ms sleep");
    }
}
