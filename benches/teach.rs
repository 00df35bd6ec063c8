//! Teaching benchmarks (timed here, never in tests): exporting a tree of
//! 10⁵ nodes, seeking anywhere in a 200-move episode at N = 40, L = 100,
//! the snapshots' memory, and what the timeline costs a race at full speed.
//!
//! `cargo bench --bench teach` prints one JSON object. With
//! `-- --instructions race|episode LOOPS` it only runs LOOPS loops of the
//! teaching configuration through a race (timeline kept) or a bare
//! episode, for `valgrind --tool=callgrind` to count.

use std::hint::black_box;
use std::time::Instant;
use torus_search::bench::{big_tree, played, race_loops, seek_points, teach_config};
use torus_search::run::episode::{Episode, Status, TimePoint};
use torus_search::searchers::tree_export::TreeQuery;

/// Loops a call, as the page's worker asks for them at full speed.
const CALL: u64 = 400;

fn episode_loops(loops: u64) -> u64 {
    let mut ep = Episode::new(&teach_config()).expect("valid");
    let mut done = 0;
    while done < loops && ep.status() == Status::Running {
        let before = ep.counters().rollouts;
        ep.advance(CALL.min(loops - done));
        done += ep.counters().rollouts - before;
    }
    ep.steps() as u64
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// The export of a tree of about 10⁵ nodes, all of them and cut.
fn tree_export() -> serde_json::Value {
    let ep = big_tree(&teach_config(), 100_000).expect("valid");
    let all = TreeQuery {
        max_nodes: 1 << 20,
        ..TreeQuery::default()
    };
    let cut = TreeQuery {
        max_nodes: 2_000,
        ..TreeQuery::default()
    };
    let time = |q: &TreeQuery| {
        let reps = 10;
        let t = Instant::now();
        let mut nodes = 0;
        for _ in 0..reps {
            nodes = black_box(ep.tree(q).unwrap().unwrap()).nodes.len();
        }
        (nodes, ms(t) / reps as f64)
    };
    let (n_all, t_all) = time(&all);
    let (n_cut, t_cut) = time(&cut);
    serde_json::json!({
        "nodes": n_all, "all_ms": t_all, "cut_nodes": n_cut, "cut_ms": t_cut,
    })
}

/// Seeks to 200 spread points of a 200-move episode (or its end).
fn seeking() -> serde_json::Value {
    let cfg = teach_config();
    let t = Instant::now();
    let (mut ep, tl) = played(&cfg, 200).expect("valid");
    let play_ms = ms(t);
    let moves = ep.steps();
    let mut times = Vec::new();
    let mut refused = 0;
    for to in seek_points(&tl, 100, 200) {
        let t = Instant::now();
        if tl.seek(&mut ep, to).is_err() {
            // An escape's decision runs no loops: its start instead.
            refused += 1;
            tl.seek(&mut ep, TimePoint::at(to.mv, 0))
                .expect("a move reached");
        }
        times.push(ms(t));
    }
    times.sort_by(f64::total_cmp);
    let mean = times.iter().sum::<f64>() / times.len() as f64;
    let m = tl.memory();
    serde_json::json!({
        "moves": moves, "play_ms": play_ms, "seeks": times.len(), "refused": refused,
        "mean_ms": mean, "median_ms": times[times.len() / 2], "max_ms": times[times.len() - 1],
        "snapshot_bytes": m.bytes, "snapshots": m.snapshots, "cap_bytes": m.cap,
        "work_per_byte": m.work_per_byte, "episode_bytes": ep.heap_bytes(),
    })
}

/// Loops at full speed through a race (timeline kept) against a bare
/// episode, interleaved, best of five each.
fn timeline_cost() -> serde_json::Value {
    let loops = 20_000;
    let (mut race, mut bare) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..5 {
        let t = Instant::now();
        black_box(race_loops(&teach_config(), loops, CALL).expect("valid"));
        race = race.min(ms(t));
        let t = Instant::now();
        black_box(episode_loops(loops));
        bare = bare.min(ms(t));
    }
    serde_json::json!({ "loops": loops, "race_ms": race, "episode_ms": bare, "race_over_episode": race / bare })
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(at) = args.iter().position(|a| a == "--instructions") {
        let loops: u64 = args[at + 2].parse().expect("LOOPS");
        let moves = match args[at + 1].as_str() {
            "race" => race_loops(&teach_config(), loops, CALL).expect("valid"),
            _ => episode_loops(loops),
        };
        println!("{moves} moves");
        return;
    }
    let out = serde_json::json!({
        "tree_export": tree_export(),
        "seek": seeking(),
        "timeline_cost": timeline_cost(),
    });
    println!("{}", serde_json::to_string_pretty(&out).unwrap());
}
