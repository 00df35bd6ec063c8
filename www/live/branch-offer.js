// The choice an edit offers while the run is paused after move 0 (the
// controller's `choosing` state, set by LiveState.propose): branch from the
// move shown, keeping the path so far, or restart from move 0; Cancel or
// Escape keeps the run as it was. Nothing happens until one is chosen.
// Under it, once a run has branched, a line says where and from what (the
// engine's lineage and configDifferences).

import { $, setText } from '../shared/ui.js';

/** What changed from `a` to `b`, as "c 1.414 → 0.3, loops 16 → 60" (the engine's differences). */
function changes(engine, a, b) {
  const short = (v) => (/^-?\d+\.\d{5,}$/.test(v) ? String(Number(Number(v).toPrecision(4))) : v);
  return engine
    .configDifferences(a, b)
    .filter((d) => d.key !== 'keep_traces')
    .map((d) => `${d.label} ${short(d.a)} → ${short(d.b)}`)
    .join(', ');
}

export class BranchOffer {
  /**
   * @param {object} o
   * @param {object} o.engine       the wasm module (configDifferences)
   * @param {object} o.controller   the playback state machine (its `choosing` state and `offer`)
   * @param {object} o.live         the LiveState (chooseBranch, chooseRestart, cancelOffer)
   */
  constructor({ engine, controller, live }) {
    Object.assign(this, { engine, controller });
    $('branch-go').addEventListener('click', () => live.chooseBranch());
    $('branch-restart').addEventListener('click', () => live.chooseRestart());
    $('branch-cancel').addEventListener('click', () => live.cancelOffer());
    // Escape from anywhere (the edited field keeps the focus on a phone).
    document.addEventListener('keydown', (e) => {
      if (e.key !== 'Escape' || controller.state !== 'choosing') return;
      e.preventDefault();
      live.cancelOffer();
    });
    controller.on('state', (s) => this.show(s === 'choosing' ? controller.offer : null));
    controller.on('runs', (runs) => this.note(runs[0]));
  }

  /** Shows the offer (null hides it), the Branch button focused. */
  show(offer) {
    const box = $('branch-offer');
    const was = !box.hidden;
    box.hidden = !offer;
    if (!offer) return;
    const what = changes(this.engine, offer.from, offer.config) || 'a setting';
    setText('branch-offer-text', `Changed ${what}. Keep the path up to move ${offer.move} and go on with the new setting, or start over?`);
    setText('branch-go', `Branch from move ${offer.move}`);
    if (!was) $('branch-go').focus({ preventScroll: true });
    box.scrollIntoView({ block: 'nearest' });
  }

  /** Under the playback bar: where run `run` branched, and what its parent had otherwise. */
  note(run) {
    const last = run?.lineage?.at(-1);
    const el = $('branch-note');
    el.hidden = !last;
    if (!last) return;
    const what = changes(this.engine, last.config, run.config);
    setText('branch-note', `Branched at move ${last.move}${what ? ` (${what})` : ''}. Dashed: the path kept from before; ▲ the branch point.`);
  }
}
