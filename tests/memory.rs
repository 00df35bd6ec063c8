//! Peak heap of an N = 1024 episode, measured with a counting allocator.
//! The budget is 64 MiB; run with `--nocapture` to see the figures.
#![cfg(not(target_arch = "wasm32"))]

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use torus_search::config::Config;
use torus_search::game::layer::Layer;
use torus_search::game::prior::PriorKind;
use torus_search::run::episode::Episode;
use torus_search::searchers::registry::SearcherId;

struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
/// The allocator is global to this test binary: measure one case at a time.
static SERIAL: Mutex<()> = Mutex::new(());

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(l) };
        if !p.is_null() {
            let now = LIVE.fetch_add(l.size(), Ordering::Relaxed) + l.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        unsafe { System.dealloc(p, l) };
        LIVE.fetch_sub(l.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static A: Counting = Counting;

const MIB: f64 = 1024.0 * 1024.0;

/// Peak bytes above the live heap at entry while building `cfg` and making `moves` moves.
fn peak_during(cfg: &Config, moves: u32) -> usize {
    let _g = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let base = LIVE.load(Ordering::Relaxed);
    PEAK.store(base, Ordering::Relaxed);
    {
        let mut e = Episode::new(cfg).expect("valid config");
        for _ in 0..moves {
            e.step_move();
        }
        // What a frame reads of it: the posterior and the searcher's counts.
        let mut posterior = Vec::new();
        e.belief().posterior_into(&mut posterior);
        let mut scratch = Vec::new();
        let _ = e.counts(Layer::Visits, &mut scratch).map(<[u32]>::len);
    }
    PEAK.load(Ordering::Relaxed) - base
}

#[test]
fn an_episode_at_n_1024_stays_under_64_mib() {
    let big = Config {
        n: 1024,
        ..Config::default()
    }
    .with(&[("loops", "20"), ("rollout_cap", "2000")]);
    let cases = [
        ("mcts cells gaussian", big.clone()),
        (
            "mcts cells uniform posterior",
            Config {
                prior: PriorKind::Uniform,
                ..big.clone()
            }
            .with(&[("belief", "posterior")]),
        ),
        (
            "mcts tree gaussian",
            big.clone().with(&[("variant", "tree")]),
        ),
        (
            "mcts cells nsarw rollouts",
            big.clone().with(&[("rollout", "nsarw")]),
        ),
        (
            "nsarw walker uniform",
            Config {
                searcher: SearcherId::parse("nsarw").unwrap(),
                prior: PriorKind::Uniform,
                ..big.clone()
            },
        ),
    ];
    for (name, cfg) in cases {
        let peak = peak_during(&cfg, 10);
        println!("{name:<32} peak heap {:>6.1} MiB", peak as f64 / MIB);
        assert!(
            (peak as f64) < 64.0 * MIB,
            "{name}: {:.1} MiB",
            peak as f64 / MIB
        );
        // The lattice alone needs 16 MiB of neighbour table: a figure far
        // below that means the measurement is broken.
        assert!(
            (peak as f64) > 16.0 * MIB,
            "{name}: {:.1} MiB",
            peak as f64 / MIB
        );
    }
}
