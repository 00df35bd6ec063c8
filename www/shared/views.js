// The page's two views (tabs): the live lattice and the Experiments
// workbench. The URL describes the view shown; the live run pauses while
// the experiments have the cores, and a page opened on the Experiments view
// with autoplay starts its live run when the live view is first shown.

import { $ } from './ui.js';

export class PageViews {
  /**
   * @param {object} o
   * @param {string} o.page                         the view shown first: live | experiments
   * @param {object} o.controller                   the live view's state machine
   * @param {{ live: () => string, experiments: () => string }} o.query   each view's URL query
   * @param {boolean} o.autoplay                    the live run plays when shown
   */
  constructor({ page, controller, query, autoplay }) {
    Object.assign(this, { page, controller, query });
    this.deferredPlay = autoplay && page !== 'live';
    $('tab-live').addEventListener('click', () => this.show('live'));
    $('tab-experiments').addEventListener('click', () => this.show('experiments'));
    $('message-close').addEventListener('click', () => ($('message').hidden = true));
  }

  /** Writes the shown view's query into the address bar. */
  updateUrl() {
    const q = this.query[this.page]();
    history.replaceState(null, '', `${location.pathname}${q ? `?${q}` : ''}`);
  }

  /** Shows a view; `play: false` cancels a deferred autoplay (the caller starts the run). */
  show(page, { play = true } = {}) {
    this.page = page;
    if (!play) this.deferredPlay = false;
    document.body.dataset.view = page;
    // The message goes with the view shown: beside the board in the live
    // view (never above it), at the top of the Experiments view.
    const box = $('message').parentElement;
    if (page === 'live') $('live').querySelector('.side').prepend(box);
    else $(page).prepend(box);
    $('live').hidden = page !== 'live';
    $('experiments').hidden = page !== 'experiments';
    $('tab-live').setAttribute('aria-pressed', String(page === 'live'));
    $('tab-experiments').setAttribute('aria-pressed', String(page === 'experiments'));
    const c = this.controller;
    if (page === 'experiments' && c.state === 'running') c.dispatch({ type: 'pause' });
    else c.dispatch({ type: 'redraw' });
    if (page === 'live' && this.deferredPlay) {
      this.deferredPlay = false;
      c.whenReady().then(() => c.dispatch({ type: 'play' }));
    }
    this.updateUrl();
  }
}
