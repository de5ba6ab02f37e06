// Follows the server's background refinement after a solve answered with `refining`: long-polls
// GET /api/frame for the frames after that answer and hands each one of its generation to onFrame, until
// one says the refinement stopped or follow() / stop() is called again. Frames of other generations (a
// newer solve's, whose answer has not arrived yet) are skipped: that answer starts its own follow().
import { api } from './api.js';

export class RefinementFeed {
  constructor(onFrame) {
    this.onFrame = onFrame;
    this.token = 0; // a follow() or stop() ends the loops before it
  }

  follow(sequence, generation) {
    const token = ++this.token;
    this.#loop(token, sequence, generation);
  }

  stop() {
    this.token += 1;
  }

  async #loop(token, after, generation) {
    while (token === this.token) {
      let frame;
      try {
        frame = await api.frame(after, 5000);
      } catch {
        return; // the server went away; the next solve says so
      }
      if (token !== this.token) return;
      if (!frame) continue; // nothing new within the wait
      after = frame.header.sequence;
      if (frame.header.generation !== generation) return;
      this.onFrame(frame);
      if (!frame.header.refining) return;
    }
  }
}
