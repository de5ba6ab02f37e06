// Undo / redo over snapshots of the editing state: the stack's top is the current state, undo steps one
// back and keeps what it left for redo, a new action drops the redo list. At most `limit` snapshots are
// kept (the server keeps the same number of constraint revisions).
export class UndoHistory {
  constructor(limit = 200) {
    this.limit = limit;
    this.reset(null);
  }

  // Forgets everything; current (if any) becomes the only state.
  reset(current) {
    this.done = current ? [current] : [];
    this.undone = [];
  }

  push(state) {
    this.done.push(state);
    if (this.done.length > this.limit) this.done.shift();
    this.undone = [];
  }

  canUndo() {
    return this.done.length > 1;
  }

  canRedo() {
    return this.undone.length > 0;
  }

  // The state to go back to, or null.
  undo() {
    if (!this.canUndo()) return null;
    this.undone.push(this.done.pop());
    return this.done.at(-1);
  }

  redo() {
    if (!this.canRedo()) return null;
    this.done.push(this.undone.pop());
    return this.done.at(-1);
  }
}
