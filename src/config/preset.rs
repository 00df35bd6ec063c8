//! Named readings of the paper: bundles of parameter values.
//!
//! The authors' code differs from their text in ways that change results
//! (`../shared/paper-code-differences.md`), so both readings are offered.
//! A preset is only a list of `(key, value)` edits over the schema: applying
//! one is the same as typing those flags, and anything given after it wins.
//! `EXPERIMENTS.md` documents each edit point by point.

use crate::game::named::named_enum;
use crate::param::ParamError;

named_enum! {
    /// A named reading of the paper.
    pub enum Preset {
        /// The algorithm as the paper's text describes it.
        PaperText = "paper-text",
        /// The selection and statistics of the authors' `MCTSgaussian.m`,
        /// on the paper's N-torus. Their numbers at side N come from their
        /// (N+1)-lattice: add `n = N + 1` and `prior = code`
        /// (`fidelity/README.md`).
        PaperCode = "paper-code",
    }
}

impl Preset {
    /// The parameter values this preset sets, as schema text.
    pub fn edits(self) -> &'static [(&'static str, &'static str)] {
        match self {
            // Section 2 of the text: c = √2, statistics per searcher
            // location, a practice target "placed according to the known
            // distribution" (the prior), "the best move" read as the most
            // selected child, no step or rollout cap given (the code's
            // 10 000 is used so runs end). The table is never decayed
            // (decay 1: the paper keeps it for the whole trial).
            Preset::PaperText => &[
                ("searcher", "mcts"),
                ("variant", "cells"),
                ("belief", "prior"),
                ("c", "1.4142135623730951"),
                ("final", "visits"),
                ("reset_each_move", "0"),
                ("decay", "1"),
                ("escape", "0"),
                ("rollout_cap", "10000"),
                ("step_cap", "10000"),
            ],
            Preset::PaperCode => &[
                ("searcher", "mcts"),
                ("variant", "code"),
                ("belief", "prior"),
                ("c", "2"),
                ("final", "uct"),
                ("reset_each_move", "0"),
                ("decay", "1"),
                ("escape", "0"),
                ("rollout_cap", "10000"),
                ("step_cap", "10000"),
            ],
        }
    }

    /// One line of help for the CLI and the page.
    pub fn help(self) -> &'static str {
        match self {
            Preset::PaperText => "the algorithm as the paper's text describes it (c = √2, practice targets from the prior, most-selected move)",
            Preset::PaperCode => "the authors' MCTSgaussian.m: c = 2, exploitation 1/K(s), max-UCT move, pass-through visits, statistics kept all trial, caps 10 000",
        }
    }

    /// The preset named `name`.
    ///
    /// # Errors
    /// A [`ParamError`] for field `preset` listing the names.
    pub fn from_name(name: &str) -> Result<Preset, ParamError> {
        Preset::parse(name).ok_or_else(|| {
            ParamError::new(
                "preset",
                name.to_string(),
                format!("one of {}", Preset::NAMES.join(", ")),
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;

    #[test]
    fn every_preset_applies_and_validates() {
        for &p in Preset::ALL {
            let mut cfg = Config::default();
            cfg.apply_preset(p);
            cfg.validate().unwrap();
            for (key, value) in p.edits() {
                assert_eq!(&cfg.get(key).unwrap(), value, "{p}: {key}");
            }
        }
    }

    #[test]
    fn a_preset_is_a_key_like_any_other() {
        // Wherever it appears, a preset applies first and the rest override it.
        let (cfg, errors) = crate::config::from_params([("c", "3"), ("preset", "paper-code")]);
        assert!(errors.is_empty(), "{errors:?}");
        assert_eq!(
            (
                cfg.settings.float(&crate::searchers::mcts::search::C),
                cfg.settings
                    .choice::<crate::searchers::mcts::variant::Variant>(
                        &crate::searchers::mcts::search::VARIANT
                    )
                    .name()
            ),
            (3.0, "code")
        );
        assert_eq!(cfg.preset(), None, "c = 3 is not the preset's");
        let mut cfg = Config::default();
        assert_eq!(cfg.preset(), None);
        cfg.set("preset", "paper-text").unwrap();
        assert_eq!(cfg.preset(), Some(Preset::PaperText));
        let e = cfg.set("preset", "none").unwrap_err();
        assert_eq!((e.field, e.value.as_str()), ("preset", "none"));
    }

    #[test]
    fn unknown_names_are_refused_with_the_list() {
        let e = Preset::from_name("paper").unwrap_err();
        assert_eq!(e.field, "preset");
        assert!(e.to_string().contains("paper-text, paper-code"), "{e}");
    }
}
