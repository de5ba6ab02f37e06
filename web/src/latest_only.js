// Runs an async job so that at most one is in flight and the newest request wins: requests made while a
// job runs collapse into one follow-up run. A drag therefore never queues stale solves, and the view
// lags the pointer by at most one solve.
export class LatestOnly {
  constructor(job) {
    this.job = job;
    this.running = false;
    this.pending = false;
    this.idleWaiters = [];
  }

  request() {
    this.pending = true;
    if (!this.running) this.#drain();
  }

  // Resolves once no job runs and none is pending.
  idle() {
    if (!this.running && !this.pending) return Promise.resolve();
    return new Promise((resolve) => this.idleWaiters.push(resolve));
  }

  async #drain() {
    this.running = true;
    while (this.pending) {
      this.pending = false;
      await this.job();
    }
    this.running = false;
    for (const resolve of this.idleWaiters.splice(0)) resolve();
  }
}
