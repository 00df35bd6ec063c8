// Temporary placeholder: proves the wasm package loads. The web page replaces it.
import init, { version } from './pkg/torus_search.js';

try {
  await init();
  document.getElementById('version').textContent = `v${version()}`;
  const canvas = document.getElementById('board');
  const ctx = canvas.getContext('2d');
  const n = 16;
  const cell = canvas.width / n;
  for (let y = 0; y < n; y++) {
    for (let x = 0; x < n; x++) {
      const v = Math.round((255 * ((x + y) % n)) / n);
      ctx.fillStyle = `rgb(${v}, ${255 - v}, 160)`;
      ctx.fillRect(x * cell, y * cell, cell, cell);
    }
  }
  document.body.dataset.state = 'running';
} catch (err) {
  document.body.dataset.state = 'error';
  console.error(err);
}
