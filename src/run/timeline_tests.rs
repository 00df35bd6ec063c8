//! Thinning the snapshots.

use super::*;
use crate::config::Config;

#[test]
fn thinning_keeps_every_other_snapshot_and_doubles_the_spacing() {
    let cfg = Config {
        n: 10,
        sigma: 2.0,
        ..Config::default()
    }
    .with(&[("loops", "8")]);
    let mut ep = Episode::new(&cfg).unwrap();
    // No spacing and no cap: a snapshot at every move.
    let mut tl = Timeline::with_spacing(&ep, usize::MAX, 0);
    for _ in 0..6 {
        ep.step_move();
        tl.note(&ep);
    }
    let moves = |tl: &Timeline| tl.snaps.iter().map(|(s, _)| s.steps()).collect::<Vec<_>>();
    assert_eq!(moves(&tl), [1, 2, 3, 4, 5, 6]);
    // A second note at the same move takes none.
    tl.note(&ep);
    assert_eq!(tl.snaps.len(), 6);
    tl.ratio = 1;
    tl.thin();
    assert_eq!(moves(&tl), [2, 4, 6]);
    assert_eq!(tl.ratio, 2);
    assert_eq!(tl.bytes, tl.snaps.iter().map(|&(_, b)| b).sum::<usize>());
    tl.thin();
    assert_eq!(moves(&tl), [4]);
    tl.thin();
    assert!(tl.snaps.is_empty() && tl.bytes == 0);
    assert_eq!(tl.memory().bytes, 0);
}

#[test]
fn a_point_reads_from_json_strictly_and_names_what_is_wrong() {
    let read = |text: &str| point_from_json(&serde_json::from_str(text).unwrap());
    assert_eq!(
        read(r#"{"move": 3, "loop": 7, "phase": "rollout"}"#),
        Ok(TimePoint {
            mv: 3,
            loop_: 7,
            phase: Some(PhaseKind::Rollout)
        })
    );
    assert_eq!(read(r#"{"move": 0}"#), Ok(TimePoint::at(0, 0)));
    assert_eq!(
        read(r#"{"move": 2, "phase": null}"#),
        Ok(TimePoint::at(2, 0))
    );
    for (text, names) in [
        (r#"{"move": -1}"#, ["move", "-1"]),
        (r#"{"move": 1.5}"#, ["move", "1.5"]),
        (r#"{"move": 4294967296}"#, ["move", "4294967296"]),
        (r#"{"move": "3"}"#, ["move", "\"3\""]),
        (r#"{"loop": 3}"#, ["move", "nothing"]),
        (r#"{"move": 1, "loop": -2}"#, ["loop", "-2"]),
        (r#"{"move": 1, "phase": "roll"}"#, ["phase", "roll"]),
        (r#"{"move": 1, "step": 2}"#, ["seek", "step"]),
        (r#"[1, 2]"#, ["seek", "[1,2]"]),
    ] {
        let e = read(text).unwrap_err().to_string();
        for n in names {
            assert!(e.contains(n), "{text}: {e}");
        }
    }
}
