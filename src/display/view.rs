//! The frame contract between an episode and a display.
//!
//! A display sends a [`FrameRequest`] (which heat layers, in which palette
//! and scale, what it already holds) and gets a [`Frame`]: a header of
//! numbers the core computed (status, counters, the decision and the moves
//! the final rule would choose among, the ratio) plus buffers (the new path
//! entries, RGBA layers, rollout traces). A layer's `key` names its pixels:
//! when the display already holds that key, the layer is not coloured or
//! sent again. Keys come from generation counters the episode keeps.

use crate::display::render::{Alpha, Colorizer, Extent, Palette, Scale, ScaleKind};
use crate::game::fnv::Fnv;
use crate::game::layer::Layer;
use crate::run::episode::{Episode, Status, TimePoint};
use crate::searchers::decision::{DecisionView, MoveScores, Planning};
use crate::searchers::mcts::search::final_rule;
use crate::searchers::mcts::uct::{leading, FinalRule};
use crate::searchers::phase::{BackupEntry, Expansion, PhaseKind, PhaseRecord, SelectLevel};
use std::sync::atomic::{AtomicU64, Ordering};

/// The palette and alpha ramp a display uses for `layer` unless told otherwise.
pub fn style(layer: Layer) -> (Palette, [u8; 2]) {
    match layer {
        Layer::Prior | Layer::Plan => (Palette::Viridis, [255, 255]),
        Layer::Posterior => (Palette::Cividis, [60, 255]),
        Layer::Searched => (Palette::Ember, [0, 70]),
        Layer::Visits | Layer::Walker => (Palette::Ember, [0, 235]),
    }
}

/// A layer as data, for a display's layer list and legend.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LayerInfo {
    /// The name a request uses.
    pub name: &'static str,
    /// A name for people.
    pub label: &'static str,
    /// Counts rather than masses.
    pub counts: bool,
    /// A yes/no layer.
    pub binary: bool,
    /// Its default palette.
    pub palette: Palette,
    /// Its default alpha ramp `[lo, hi]` (`[255, 255]` is opaque).
    pub alpha: [u8; 2],
}

/// Every layer, bottom to top as a display stacks them.
const ALL_LAYERS: [Layer; 6] = [
    Layer::Prior,
    Layer::Plan,
    Layer::Posterior,
    Layer::Searched,
    Layer::Visits,
    Layer::Walker,
];

/// Every layer, bottom to top as a display stacks them, as data.
pub fn layers() -> Vec<LayerInfo> {
    ALL_LAYERS
        .into_iter()
        .map(|l| {
            let (palette, alpha) = style(l);
            LayerInfo {
                name: l.name(),
                label: l.label(),
                counts: l.counts(),
                binary: l.binary(),
                palette,
                alpha,
            }
        })
        .collect()
}

/// The names of the layers `ep` can draw, bottom to top (a searcher
/// without per-cell counts has no count layers), for a display's layer switch.
pub fn layers_of(ep: &Episode) -> Vec<&'static str> {
    let mut scratch = Vec::new();
    layers()
        .into_iter()
        .zip(ALL_LAYERS)
        .filter(|(info, l)| !info.counts || ep.counts(*l, &mut scratch).is_some())
        .map(|(info, _)| info.name)
        .collect()
}

/// One heat layer to draw.
#[derive(Clone, Debug, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LayerRequest {
    /// Which layer.
    pub layer: Layer,
    /// In which palette.
    pub palette: Palette,
    /// On which scale (ignored for yes/no layers).
    pub scale: ScaleKind,
    /// Alpha ramp `[lo, hi]`; `[255, 255]` is opaque.
    pub alpha: [u8; 2],
    /// The key of the rendering the display holds, if any.
    #[serde(default)]
    pub have: Option<u64>,
}

/// What a display wants in the next frame.
#[derive(Clone, Debug, Default, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FrameRequest {
    /// The heat layers, bottom to top.
    pub layers: Vec<LayerRequest>,
    /// Path entries the display already holds (the frame sends the rest).
    pub path_from: u32,
    /// Send the kept rollout traces and the practice target.
    pub traces: bool,
    /// Send the cells the searcher means to enter next (a planner's path).
    pub intent: bool,
    /// The search is running on its own: big changing layers may lag by a
    /// fraction of a second rather than be recoloured after every loop.
    pub live: bool,
}

/// Bytes serialised as a byte buffer (a `Uint8Array` in JS).
#[derive(Clone, Copy, Debug)]
pub struct Bytes<'a>(pub &'a [u8]);

impl serde::Serialize for Bytes<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_bytes(self.0)
    }
}

/// The decision under way, with what the final rule would pick now.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct Decision {
    /// The statistics of the four moves.
    #[serde(flatten)]
    pub view: DecisionView,
    /// The final-move rule.
    pub rule: FinalRule,
    /// The moves the rule would choose among if the decision ended now:
    /// one, several when tied (one of them at random), none before the
    /// decision's first loop.
    pub leading: [bool; 4],
    /// The moves with the highest UCT value now (what selection would
    /// try next), none before the decision's first loop.
    pub highest_uct: [bool; 4],
    /// The four children's visits added up: under the per-cell tables,
    /// more than the loops from here, as rollouts passing through a
    /// neighbour count a visit too.
    pub children_visits: u64,
}

/// One heat layer of a frame.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LayerFrame<'a> {
    /// Which layer.
    pub layer: Layer,
    /// Names these pixels: equal keys, equal pixels.
    pub key: u64,
    /// True when the request already held this key (no pixels sent).
    pub same: bool,
    /// The pixels, `4·N²` RGBA bytes, unless `same`.
    pub rgba: Option<Bytes<'a>>,
    /// The values' extent, for the legend.
    pub min: f64,
    /// The smallest nonzero value.
    pub min_nonzero: f64,
    /// The largest value.
    pub max: f64,
    /// The sum of the values.
    pub sum: f64,
}

/// The loop stepped phase by phase, as far as it has gone: what each phase
/// did (see [`PhaseRecord`]), cells as little-endian u32 buffers.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PhaseFrame<'a> {
    /// The last phase done.
    pub phase: Option<PhaseKind>,
    /// The practice target the loop chases.
    pub practice: u32,
    /// Selection, root first: each level's four moves with their UCT terms.
    pub select: &'a [SelectLevel],
    /// What the expansion did, once done.
    pub expansion: Option<Expansion>,
    /// The loop's tree path (root first), as cells.
    pub path: Bytes<'a>,
    /// The rollout's cells after the leaf (once rolled out).
    pub rollout: Bytes<'a>,
    /// Where each chunk of the rollout ends (indices into `rollout`), to
    /// reveal it in a fixed number of frames.
    pub chunks: Vec<u32>,
    /// Steps of the rollout.
    pub rollout_steps: u32,
    /// The practice target was detected.
    pub detected: bool,
    /// The rollout stopped at its step cap.
    pub truncated: bool,
    /// The belief MCTS cut the rollout and charged its reference's rest.
    pub cut: bool,
    /// The reward (return) backed up.
    pub reward: f64,
    /// The nodes or table entries the back-up updated, old → new.
    pub backup: &'a [BackupEntry],
    /// Cells outside the root and its neighbours that gained a visit.
    pub others: u32,
    /// False for `code`'s expansion rollouts (not one of the loops).
    pub counts: bool,
}

/// Everything a display draws of one episode at one moment.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Frame<'a> {
    /// Where the episode stands.
    pub status: Status,
    /// Real moves so far.
    pub steps: u32,
    /// Moves onto a cell the searcher had already stood on.
    pub revisits: u32,
    /// The searcher's cell.
    pub position: u32,
    /// Loops in the decision under way (or the last one).
    pub loops_done: u32,
    /// Work so far: loops for a searcher that deliberates, else moves.
    pub work: u64,
    /// Rollouts over the episode.
    pub rollouts: u64,
    /// Rollout steps over the episode.
    pub rollout_steps: u64,
    /// Truncated rollouts over the episode.
    pub truncated: u64,
    /// Rollouts in the decision under way (or the last one).
    pub decision_rollouts: u64,
    /// Rollout steps in the decision under way (or the last one).
    pub decision_rollout_steps: u64,
    /// steps / optimal, once found with optimal > 0.
    pub ratio: Option<f64>,
    /// Planning mass searched so far.
    pub searched_mass: f64,
    /// The decision under way, for a searcher that deliberates.
    pub decision: Option<Decision>,
    /// The index of the first path entry sent.
    pub path_from: u32,
    /// Path entries from `path_from` on, as little-endian u32 cells.
    pub path: Bytes<'a>,
    /// The requested layers this searcher has, in request order.
    pub layers: Vec<LayerFrame<'a>>,
    /// Kept rollout traces, oldest first, as little-endian u32 cells (when asked).
    pub traces: Option<Vec<Bytes<'a>>>,
    /// The practice target of the newest trace.
    pub practice: Option<u32>,
    /// The cells a planner means to enter next, as little-endian u32 cells
    /// (when asked and the searcher plans a path; the first [`MAX_INTENT`]).
    pub intent: Option<Bytes<'a>>,
    /// How a planner scored the four moves at its last decision.
    pub scores: Option<MoveScores>,
    /// How far the plan being made has got, while a planner makes one.
    pub planning: Option<Planning>,
    /// Where the episode stands on its timeline.
    pub point: TimePoint,
    /// The loop stepped phase by phase, while one is shown.
    pub phase: Option<PhaseFrame<'a>>,
}

/// The most cells of a planner's intended path a frame carries: a plan can
/// run to the end of the search (a third of N² cells and more), which no
/// frame should copy and no board draw, at every frame.
pub const MAX_INTENT: usize = 4096;

/// Keys are masked to 53 bits so a JS number holds them exactly.
const KEY_MASK: u64 = (1 << 53) - 1;

static NEXT_ID: AtomicU64 = AtomicU64::new(1);

#[derive(Clone, Copy, Debug, Default)]
struct Memo {
    tick: u64,
    generation: u64,
}

/// Builds frames of one episode; owns the buffers they borrow.
pub struct FrameBuilder {
    /// Distinguishes this episode's keys from every other's (a display may
    /// keep a layer's pixels across runs).
    id: u64,
    colorizers: Vec<Colorizer>,
    rgba: Vec<Vec<u8>>,
    extent: Vec<Extent>,
    memo: Vec<Memo>,
    floats: Vec<f64>,
    counts: Vec<u32>,
    path: Vec<u8>,
    traces: Vec<Vec<u8>>,
    intent: Vec<u8>,
    phase_path: Vec<u8>,
    phase_rollout: Vec<u8>,
}

/// Recolouring period (ms) of changing layers while the search runs on its
/// own: at most ~30 times a second above 128×128 cells and ~8 above
/// 362×362, because colouring and copying them takes the worker's time
/// from the search; 0 (every change) otherwise.
pub fn recolour_period_ms(cells: usize, live: bool) -> f64 {
    match (live, cells) {
        (false, _) => 0.0,
        (true, c) if c > 1 << 17 => 120.0,
        (true, c) if c > 1 << 14 => 33.0,
        _ => 0.0,
    }
}

fn phase_frame<'a>(r: &'a PhaseRecord, path: &'a [u8], rollout: &'a [u8]) -> PhaseFrame<'a> {
    PhaseFrame {
        phase: r.phase,
        practice: r.practice,
        select: &r.select,
        expansion: r.expansion,
        path: Bytes(path),
        rollout: Bytes(rollout),
        chunks: r.chunks(),
        rollout_steps: r.rollout_steps,
        detected: r.detected,
        truncated: r.truncated,
        cut: r.cut,
        reward: r.reward,
        backup: &r.backup,
        others: r.others,
        counts: r.counts,
    }
}

fn le_bytes(cells: &[u32], out: &mut Vec<u8>) {
    out.clear();
    out.reserve(4 * cells.len());
    for c in cells {
        out.extend_from_slice(&c.to_le_bytes());
    }
}

impl FrameBuilder {
    /// A builder for an episode on a lattice of `cells` cells.
    pub fn new(cells: usize) -> FrameBuilder {
        let k = Layer::ALL.len();
        FrameBuilder {
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            colorizers: Palette::ALL.iter().map(|&p| Colorizer::new(p)).collect(),
            rgba: vec![Vec::new(); k],
            extent: vec![Extent::default(); k],
            memo: vec![Memo::default(); k],
            floats: Vec::with_capacity(cells),
            counts: Vec::new(),
            path: Vec::new(),
            traces: Vec::new(),
            intent: Vec::new(),
            phase_path: Vec::new(),
            phase_rollout: Vec::new(),
        }
    }

    /// The frame of `ep` that `req` asks for; `now_ms` is the clock the
    /// recolouring period of live layers reads.
    pub fn frame<'a>(&'a mut self, ep: &'a Episode, req: &FrameRequest, now_ms: f64) -> Frame<'a> {
        let plan = self.plan_layers(ep, req, now_ms);
        let path = ep.path();
        let from = if (req.path_from as usize) <= path.len() {
            req.path_from
        } else {
            0
        };
        le_bytes(&path[from as usize..], &mut self.path);

        let deliberates = ep.searcher_info().deliberates;
        let (traces, practice) = if req.traces && deliberates {
            let kept: Vec<(&[u32], u32)> = ep.traces().collect();
            self.traces.resize_with(kept.len(), Vec::new);
            // Oldest first, so a display draws the newest on top.
            for (buf, (cells, _)) in self.traces.iter_mut().zip(kept.iter().rev()) {
                le_bytes(cells, buf);
            }
            (
                Some(self.traces.iter().map(|b| Bytes(b)).collect()),
                kept.first().map(|&(_, t)| t),
            )
        } else {
            (None, None)
        };

        let intent = if req.intent && !ep.intent().is_empty() {
            let cells = ep.intent();
            le_bytes(&cells[..cells.len().min(MAX_INTENT)], &mut self.intent);
            Some(Bytes(&self.intent[..]))
        } else {
            None
        };

        let phase = ep.phase().map(|r| {
            let from = (r.rollout_from as usize).min(r.trace.len());
            le_bytes(&r.trace[..from], &mut self.phase_path);
            le_bytes(r.rollout(), &mut self.phase_rollout);
            phase_frame(r, &self.phase_path, &self.phase_rollout)
        });
        let rule = final_rule(&ep.config().settings);
        let decision = ep.decision().map(|view| {
            let started = view.children.iter().any(|c| c.selected > 0);
            Decision {
                view,
                rule,
                leading: if started {
                    leading(&view, rule)
                } else {
                    [false; 4]
                },
                highest_uct: if started {
                    leading(&view, FinalRule::Uct)
                } else {
                    [false; 4]
                },
                children_visits: view.children.iter().map(|c| u64::from(c.visits)).sum(),
            }
        });
        let result = ep.result();
        let counters = ep.counters();
        let spent = ep.decision_counters();
        Frame {
            status: ep.status(),
            steps: ep.steps(),
            revisits: ep.revisits(),
            position: ep.position(),
            loops_done: ep.loops_done(),
            work: ep.work(),
            rollouts: counters.rollouts,
            rollout_steps: counters.rollout_steps,
            truncated: counters.truncated,
            decision_rollouts: spent.rollouts,
            decision_rollout_steps: spent.rollout_steps,
            ratio: (ep.status() == Status::Found)
                .then(|| result.ratio())
                .flatten(),
            searched_mass: (1.0 - ep.belief().remaining()).clamp(0.0, 1.0),
            decision,
            path_from: from,
            path: Bytes(&self.path),
            layers: plan
                .into_iter()
                .map(|(layer, key, same)| {
                    let i = layer as usize;
                    let e = self.extent[i];
                    LayerFrame {
                        layer,
                        key,
                        same,
                        rgba: (!same).then(|| Bytes(&self.rgba[i])),
                        min: e.min,
                        min_nonzero: e.min_nonzero,
                        max: e.max,
                        sum: e.sum,
                    }
                })
                .collect(),
            traces,
            practice,
            intent,
            scores: ep.scores(),
            planning: ep.planning(),
            point: ep.point(),
            phase,
        }
    }

    /// Each requested layer with its key and whether the display already
    /// holds it, the ones it does not hold coloured (a layer this searcher
    /// lacks is left out).
    fn plan_layers(
        &mut self,
        ep: &Episode,
        req: &FrameRequest,
        now_ms: f64,
    ) -> Vec<(Layer, u64, bool)> {
        let period = recolour_period_ms(ep.torus().cells(), req.live);
        let mut plan: Vec<(Layer, u64, bool)> = Vec::with_capacity(req.layers.len());
        for lr in &req.layers {
            let i = lr.layer as usize;
            let generation = ep.generation(lr.layer);
            let m = &mut self.memo[i];
            let effective = if period > 0.0 && lr.layer.dynamic() {
                let tick = (now_ms / period).max(0.0) as u64;
                if tick != m.tick {
                    *m = Memo { tick, generation };
                }
                m.generation
            } else {
                *m = Memo {
                    tick: u64::MAX,
                    generation,
                };
                generation
            };
            let style = [
                lr.palette as u64,
                lr.scale as u64,
                lr.alpha[0] as u64,
                lr.alpha[1] as u64,
            ];
            let mut h = Fnv::default();
            for w in [
                self.id, i as u64, style[0], style[1], style[2], style[3], effective,
            ] {
                h.word(w);
            }
            let key = h.finish() & KEY_MASK;
            let same = lr.have == Some(key);
            if !same && !self.render(ep, lr) {
                continue; // this searcher has no such layer
            }
            plan.push((lr.layer, key, same));
        }
        plan
    }

    /// Colours `lr` into its buffer; false when the searcher lacks the layer.
    fn render(&mut self, ep: &Episode, lr: &LayerRequest) -> bool {
        let i = lr.layer as usize;
        let FrameBuilder {
            colorizers,
            rgba,
            extent,
            floats,
            counts,
            ..
        } = self;
        let col = &colorizers[lr.palette as usize];
        let buf = &mut rgba[i];
        buf.resize(4 * ep.torus().cells(), 0);
        let alpha = Alpha::of(lr.alpha);
        let belief = ep.belief();
        let mass = |v: &[f64], buf: &mut Vec<u8>| col.colorize_kind(v, buf, lr.scale, false, alpha);
        extent[i] = match lr.layer {
            Layer::Prior => mass(belief.prior_mass(), buf),
            Layer::Plan => mass(belief.plan_mass(), buf),
            Layer::Posterior => {
                belief.posterior_into(floats);
                mass(floats, buf)
            }
            Layer::Searched => col.colorize(belief.searched(), buf, Scale::Linear, alpha),
            Layer::Visits | Layer::Walker => match ep.counts(lr.layer, counts) {
                Some(v) => col.colorize_kind(v, buf, lr.scale, true, alpha),
                None => return false,
            },
        };
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;

    fn request(layers: &[(Layer, Option<u64>)], live: bool) -> FrameRequest {
        FrameRequest {
            layers: layers
                .iter()
                .map(|&(layer, have)| LayerRequest {
                    layer,
                    palette: Palette::Viridis,
                    scale: ScaleKind::Linear,
                    alpha: [0, 255],
                    have,
                })
                .collect(),
            path_from: 0,
            traces: true,
            intent: true,
            live,
        }
    }

    fn small() -> Config {
        Config {
            n: 12,
            ..Config::default()
        }
        .with(&[("loops", "10"), ("keep_traces", "2")])
    }

    #[test]
    fn layers_of_names_the_count_layers_only_for_searchers_that_keep_counts() {
        let of = |searcher: &str| {
            let cfg = small().with(&[("searcher", searcher)]);
            layers_of(&Episode::new(&cfg).unwrap())
        };
        let masses = ["prior", "plan", "posterior", "searched"];
        assert_eq!(of("mcts"), [&masses[..], &["visits"]].concat());
        assert_eq!(of("rw"), masses);
        assert_eq!(of("nsarw"), [&masses[..], &["visits", "walker"]].concat());
    }

    #[test]
    fn keys_change_with_the_data_and_held_layers_are_not_resent() {
        let mut ep = Episode::new(&small()).unwrap();
        let mut fb = FrameBuilder::new(144);
        let all = [
            (Layer::Prior, None),
            (Layer::Posterior, None),
            (Layer::Visits, None),
        ];
        let keys = |f: &Frame| f.layers.iter().map(|l| l.key).collect::<Vec<_>>();
        let first = keys(&fb.frame(&ep, &request(&all, false), 0.0));
        assert_eq!(first.len(), 3);
        // Held keys: nothing recoloured.
        let held: Vec<_> = all
            .iter()
            .zip(&first)
            .map(|(&(l, _), &k)| (l, Some(k)))
            .collect();
        let f = fb.frame(&ep, &request(&held, false), 0.0);
        assert!(f.layers.iter().all(|l| l.same && l.rgba.is_none()));
        // One loop changes the visits, not the prior or the posterior.
        ep.step_loops(1);
        let second = keys(&fb.frame(&ep, &request(&held, false), 0.0));
        assert_eq!(second[0], first[0]);
        assert_eq!(second[1], first[1]);
        assert_ne!(second[2], first[2]);
        // A move searches new cells: the posterior changes too.
        ep.step_move();
        let third = keys(&fb.frame(&ep, &request(&held, false), 0.0));
        assert_eq!(third[0], first[0]);
        assert_ne!(third[1], first[1]);
        // Another episode never shares a key.
        let other = Episode::new(&small()).unwrap();
        let mut fb2 = FrameBuilder::new(144);
        assert_ne!(
            keys(&fb2.frame(&other, &request(&all, false), 0.0))[0],
            first[0]
        );
    }

    #[test]
    fn live_big_layers_recolour_on_a_clock() {
        let cfg = Config {
            n: 200,
            ..Config::default()
        }
        .with(&[("loops", "5")]);
        let mut ep = Episode::new(&cfg).unwrap();
        let mut fb = FrameBuilder::new(40_000);
        let key = |fb: &mut FrameBuilder, ep: &Episode, t: f64, live: bool| {
            fb.frame(ep, &request(&[(Layer::Visits, None)], live), t)
                .layers[0]
                .key
        };
        let a = key(&mut fb, &ep, 0.0, true);
        ep.step_loops(1);
        assert_eq!(key(&mut fb, &ep, 10.0, true), a, "within one 33 ms tick");
        assert_ne!(key(&mut fb, &ep, 40.0, true), a, "the next tick shows it");
        let held = key(&mut fb, &ep, 50.0, true);
        ep.step_loops(1);
        assert_eq!(
            key(&mut fb, &ep, 60.0, true),
            held,
            "live: held until the tick"
        );
        assert_ne!(
            key(&mut fb, &ep, 60.0, false),
            held,
            "paused shows every change"
        );
    }

    #[test]
    fn a_frame_carries_at_most_max_intent_cells_of_a_plan() {
        // A beam plan over a uniform 120-torus runs to about 4 800 cells; a
        // cheap one (width and depth 1, horizon 2).
        let cfg = Config::default().with(&[
            ("n", "120"),
            ("prior", "uniform"),
            ("searcher", "beam"),
            ("beam_width", "1"),
            ("beam_depth", "1"),
            ("horizon", "2"),
        ]);
        let mut ep = Episode::new(&cfg).unwrap();
        ep.step_move();
        assert!(ep.intent().len() > MAX_INTENT, "{}", ep.intent().len());
        let mut fb = FrameBuilder::new((cfg.n * cfg.n) as usize);
        let f = fb.frame(
            &ep,
            &FrameRequest {
                intent: true,
                ..FrameRequest::default()
            },
            0.0,
        );
        let bytes = f.intent.unwrap().0;
        assert_eq!(bytes.len(), 4 * MAX_INTENT);
        let first = u32::from_le_bytes(bytes[0..4].try_into().unwrap());
        assert_eq!(first, ep.intent()[0]);
    }

    #[test]
    fn frames_carry_the_path_delta_decision_and_traces() {
        let mut ep = Episode::new(&small()).unwrap();
        ep.step_move();
        ep.step_move();
        ep.step_loops(3);
        let mut fb = FrameBuilder::new(144);
        let f = fb.frame(
            &ep,
            &FrameRequest {
                path_from: 1,
                traces: true,
                ..FrameRequest::default()
            },
            0.0,
        );
        assert_eq!(f.path_from, 1);
        assert_eq!(f.path.0.len(), 4 * 2);
        assert_eq!(
            u32::from_le_bytes(f.path.0[4..8].try_into().unwrap()),
            ep.position()
        );
        let d = f.decision.unwrap();
        assert_eq!(d.view.children.iter().map(|c| c.selected).sum::<u32>(), 3);
        assert!(d.leading.iter().any(|&l| l));
        let traces = f.traces.unwrap();
        assert_eq!(traces.len(), 2);
        let newest = traces[1].0;
        assert_eq!(
            u32::from_le_bytes(newest[0..4].try_into().unwrap()),
            ep.position()
        );
        assert!(f.practice.is_some());
        // A request beyond the path starts over.
        let f = fb.frame(
            &ep,
            &FrameRequest {
                path_from: 99,
                ..FrameRequest::default()
            },
            0.0,
        );
        assert_eq!(f.path_from, 0);
        // Walkers have no decision, no visits unless NSARW.
        let mut rw = small();
        rw.set("searcher", "rw").unwrap();
        let ep = Episode::new(&rw).unwrap();
        let f = fb.frame(
            &ep,
            &request(&[(Layer::Visits, None), (Layer::Prior, None)], false),
            0.0,
        );
        assert!(f.decision.is_none() && f.traces.is_none());
        assert_eq!(f.layers.len(), 1);
        assert_eq!(f.layers[0].layer, Layer::Prior);
    }

    #[test]
    fn leading_agrees_with_the_final_move() {
        use crate::game::rng;
        let mut ep = Episode::new(&small()).unwrap();
        for _ in 0..4 {
            ep.step_loops(7);
            let view = ep.decision().unwrap();
            for &rule in FinalRule::ALL {
                let lead = leading(&view, rule);
                for s in 0..16 {
                    let m = crate::searchers::mcts::uct::final_move(
                        &view,
                        rule,
                        &mut rng::stream(s, 0),
                    );
                    assert!(lead[m as usize], "{rule}: {m:?} not among {lead:?}");
                }
            }
        }
    }
}
