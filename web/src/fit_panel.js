// The "Fit to a scan" section: uploads a target (a point cloud or mesh, POST /api/target), draws its points,
// and fits the rest mesh to it on the server (POST /api/fit, `iarap register`'s registration), following the
// fit's frames (GET /api/frame): each round redraws the mesh and adds its mean distance to the plot, the last
// frame says how it ended. POST /api/cancel (Stop fit, Esc) stops it after the current round.
import { drawEnergyPlot } from './energy_plot.js';

const $ = (id) => document.getElementById(id);

// A whole number in [min, max] from the field, or an error naming it (never clamped behind the user's back).
function wholeField(id, name, min, max) {
  const text = $(id).value.trim();
  const value = Number(text);
  if (!/^\d+$/.test(text) || value < min || value > max) throw new Error(`${name} must be a whole number from ${min} to ${max}; got "${text}".`);
  return value;
}

export class FitPanel {
  // api: the serve API; viewer: the Viewer; guarded: runs an action showing its error; hooks: {method(): the
  // method to fit, beforeFit(): settles the page's solves, afterFit(): the fitted shape is the session's}.
  constructor(api, viewer, guarded, hooks) {
    this.api = api;
    this.viewer = viewer;
    this.hooks = hooks;
    this.target = null; // the session JSON's target
    this.residuals = [];
    this.frames = []; // the fit frames' headers, for tests/web
    this.token = 0; // a new fit or mesh ends the frame loop before it
    this.running = false;
    $('load-target').addEventListener('change', () => guarded(() => this.#upload()));
    $('show-target').addEventListener('change', () => viewer.setTargetVisible($('show-target').checked));
    $('fit').addEventListener('click', () => guarded(() => this.fit()));
    $('fit-cancel').addEventListener('click', () => guarded(() => api.cancel()));
  }

  // A mesh loaded (state: the session JSON): nothing of the previous fit stays; the session's target, if it
  // has one (a page reloaded after a target's upload), is drawn.
  async setMesh(state) {
    this.token += 1;
    this.running = false;
    this.residuals = [];
    drawEnergyPlot($('fit-plot'), {});
    $('fit-info').textContent = '';
    await this.#showTarget(state.target ?? null);
  }

  async #showTarget(target) {
    this.target = target;
    this.viewer.setTarget(target ? Float32Array.from((await this.api.target()).arrays.points) : null);
    if (target) $('fit-info').textContent = `target ${target.name}: ${target.points} points${target.faces ? `, ${target.faces} faces` : ''}`;
    this.#buttons();
  }

  async #upload() {
    const file = $('load-target').files[0];
    if (!file) return;
    $('load-target').value = '';
    $('fit-info').textContent = `reading ${file.name}...`;
    try {
      await this.#showTarget((await this.api.uploadTarget(file)).target);
    } catch (error) {
      $('fit-info').textContent = '';
      throw error;
    }
  }

  async fit() {
    const body = {
      method: this.hooks.method(),
      stages: wholeField('fit-stages', 'Stages', 1, 50),
      rounds_per_stage: wholeField('fit-rounds', 'Rounds', 1, 200),
    };
    await this.hooks.beforeFit();
    const started = await this.api.fit(body);
    this.residuals = [];
    this.running = true;
    this.#buttons();
    $('fit-info').textContent = `fitting with ${body.method}...`;
    const token = ++this.token;
    try {
      await this.#follow(token, started);
    } finally {
      if (token === this.token) {
        this.running = false;
        this.#buttons();
      }
    }
  }

  // The fit's frames until its last one, or until a frame of a newer generation says the session moved on.
  async #follow(token, { after, generation, max_rounds: maxRounds }) {
    for (;;) {
      const frame = await this.api.frame(after, 5000);
      if (token !== this.token) return;
      if (!frame) continue;
      after = frame.header.sequence;
      if (frame.header.generation !== generation) {
        $('fit-info').textContent += '\nstopped: the session moved on (a solve or a new selection)';
        return;
      }
      const { header, arrays } = frame;
      if (!header.fit) continue;
      this.frames.push({ ...header, receivedAt: performance.now() });
      if (this.frames.length > 500) this.frames.shift();
      this.viewer.setPositions(header.method, arrays.positions);
      const { fit } = header;
      if (fit.running) {
        this.residuals.push(fit.residual);
        drawEnergyPlot($('fit-plot'), { [header.method]: this.residuals }, 'round');
        $('fit-info').textContent = `round ${fit.round} (at most ${maxRounds}), stage ${fit.stage + 1}: mean distance ${fit.residual.toExponential(3)} of the target's diagonal`;
        continue;
      }
      const how = header.error ? `failed: ${header.error}` : fit.cancelled ? 'stopped' : 'done';
      $('fit-info').textContent = header.error
        ? `fit ${how}`
        : `fit ${how} after ${fit.round} rounds: mean distance ${fit.final_mean.toExponential(3)} (${fit.initial_mean.toExponential(3)} after the rigid start), 90th percentile ${fit.final_p90.toExponential(3)} of the target's diagonal${fit.committed ? '' : ' (not kept: the session moved on)'}`;
      if (fit.committed) this.hooks.afterFit();
      return;
    }
  }

  #buttons() {
    $('fit').disabled = !this.target || this.running;
    $('fit-cancel').disabled = !this.running;
  }
}
