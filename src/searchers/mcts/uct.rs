//! UCT's choice among the four moves: ties at random, and the final rule
//! that picks the real move once a decision's loops are done.

use crate::game::lattice::Move;
use crate::game::named::named_enum;
use crate::game::rng::{self, Rng};
use crate::searchers::decision::DecisionView;

named_enum! {
    /// How the real move is chosen once a decision's loops are done.
    pub enum FinalRule {
        /// The child selected most often in this decision (robust child).
        Visits = "visits",
        /// The child with the best mean reward.
        Mean = "mean",
        /// The child with the best UCT value (the paper's Gaussian code).
        Uct = "uct",
        /// The variant's own rule (`search::final_rule` resolves it).
        Auto = "auto",
    }
}

/// The index of the largest valid value, ties broken uniformly at random.
/// Returns `None` when nothing is valid.
pub fn argmax_random(values: [f64; 4], valid: [bool; 4], rng: &mut Rng) -> Option<usize> {
    let mut best = f64::NEG_INFINITY;
    let mut ties = [0usize; 4];
    let mut k = 0;
    for i in 0..4 {
        if !valid[i] {
            continue;
        }
        let v = values[i];
        if k == 0 || v > best {
            best = v;
            k = 0;
        }
        if v == best {
            ties[k] = i;
            k += 1;
        }
    }
    if k == 0 {
        None
    } else {
        Some(ties[rng::below(rng, k as u32) as usize])
    }
}

/// What `rule` ranks the children by. An unvisited child has no evidence
/// of its mean: it ranks below every visited one.
fn final_values(view: &DecisionView, rule: FinalRule) -> [f64; 4] {
    let ch = &view.children;
    std::array::from_fn(|i| match rule {
        FinalRule::Visits => ch[i].selected as f64,
        FinalRule::Mean => {
            if ch[i].visits == 0 {
                -1.0
            } else {
                ch[i].mean
            }
        }
        // `auto` is resolved by `search::final_rule`; a bare view reads it
        // as the per-cell tables' rule.
        FinalRule::Uct | FinalRule::Auto => ch[i].uct,
    })
}

/// The final move under `rule` from the children's statistics (ties at random).
pub fn final_move(view: &DecisionView, rule: FinalRule, rng: &mut Rng) -> Move {
    let values = final_values(view, rule);
    Move::from_index(argmax_random(values, [true; 4], rng).unwrap_or(0) as u32)
}

/// The moves [`final_move`] would choose among if the decision ended now:
/// one, or several tied (it then picks one of them at random).
pub fn leading(view: &DecisionView, rule: FinalRule) -> [bool; 4] {
    let values = final_values(view, rule);
    let best = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    values.map(|v| v == best)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::game::rng;
    use crate::searchers::decision::{uct_terms, ChildStat};

    fn child(visits: u32, reward: f64, parent: u32, selected: u32) -> ChildStat {
        ChildStat::new(0, visits, reward, parent, 1.5, selected)
    }

    #[test]
    fn the_uct_terms_follow_the_formula() {
        // Q/N, c·sqrt(ln N_parent / N), and their sum: what the decision
        // panel shows and what tree and pomcp select by.
        let (mean, explore, uct) = uct_terms(3.0, 4, 20, 1.5);
        assert_eq!(mean, 0.75);
        let want = 1.5 * (20f64.ln() / 4.0).sqrt();
        assert!((explore - want).abs() < 1e-15, "{explore} against {want}");
        assert_eq!(uct, mean + explore);
        // Exploration shrinks as a child is visited and grows with its
        // parent; an unvisited child is tried first; a parent seen at
        // most once gives ln 1 = 0.
        assert!(uct_terms(3.0, 8, 20, 1.5).1 < explore);
        assert!(uct_terms(3.0, 4, 40, 1.5).1 > explore);
        assert_eq!(
            uct_terms(0.0, 0, 20, 1.5),
            (0.0, f64::INFINITY, f64::INFINITY)
        );
        assert_eq!(uct_terms(2.0, 4, 0, 1.5), (0.5, 0.0, 0.5));
        assert_eq!(uct_terms(2.0, 4, 1, 1.5), (0.5, 0.0, 0.5));
        let s = ChildStat::new(7, 4, 3.0, 20, 1.5, 2);
        assert_eq!(
            (s.cell, s.visits, s.reward, s.mean, s.explore, s.uct, s.selected),
            (7, 4, 3.0, mean, explore, uct, 2)
        );
    }

    #[test]
    fn argmax_breaks_ties_uniformly_among_the_valid_moves() {
        let mut rng = rng::stream(11, 0);
        let values = [0.5, 2.0, 2.0, 2.0];
        let valid = [true, true, false, true];
        let mut seen = [0u32; 4];
        let draws = 6000u32;
        for _ in 0..draws {
            seen[argmax_random(values, valid, &mut rng).unwrap()] += 1;
        }
        // Moves 1 and 3 tie among the valid ones: each half the draws,
        // within 4 standard errors of a binomial count (38.7 here).
        assert_eq!((seen[0], seen[2]), (0, 0));
        let se = (f64::from(draws) / 4.0).sqrt();
        for i in [1, 3] {
            let off = (f64::from(seen[i]) - f64::from(draws) / 2.0).abs();
            assert!(off < 4.0 * se, "{seen:?}");
        }
        // A unique maximum always wins, even at -∞ when it is all that is
        // valid, and nothing valid gives no move.
        let neg = f64::NEG_INFINITY;
        assert_eq!(
            argmax_random([1.0, 3.0, 2.0, 0.0], [true; 4], &mut rng),
            Some(1)
        );
        assert_eq!(
            argmax_random([9.0, neg, 9.0, 9.0], [false, true, false, false], &mut rng),
            Some(1)
        );
        assert_eq!(argmax_random([1.0; 4], [false; 4], &mut rng), None);
    }

    #[test]
    fn the_final_rules_rank_the_children_and_leading_names_the_tied_best() {
        // Move 0: selected most; move 1: best mean; move 2: unvisited
        // (best UCT); move 3: visited once with a mean of 0.
        let view = DecisionView {
            parent_visits: 30,
            c: 1.5,
            children: [
                child(20, 2.0, 30, 20),
                child(9, 4.5, 30, 5),
                child(0, 0.0, 30, 0),
                child(1, 0.0, 30, 1),
            ],
        };
        let mut rng = rng::stream(3, 0);
        for (rule, best) in [
            (FinalRule::Visits, Move::ALL[0]),
            (FinalRule::Mean, Move::ALL[1]),
            (FinalRule::Uct, Move::ALL[2]),
        ] {
            assert_eq!(final_move(&view, rule, &mut rng), best, "{rule}");
            let mut lead = [false; 4];
            lead[best as usize] = true;
            assert_eq!(leading(&view, rule), lead, "{rule}");
        }
        // Under `mean` an unvisited child ranks below a visited one whose
        // mean is 0, and equal selections tie.
        let mut cold = view;
        cold.children[1] = child(0, 0.0, 30, 0);
        cold.children[0].reward = 0.0;
        cold.children[0].mean = 0.0;
        assert_eq!(leading(&cold, FinalRule::Mean), [true, false, false, true]);
        cold.children[3].selected = 20;
        assert_eq!(
            leading(&cold, FinalRule::Visits),
            [true, false, false, true]
        );
    }
}
