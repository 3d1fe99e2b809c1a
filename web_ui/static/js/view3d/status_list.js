// A display's status, as rviz's status tree: named entries ("Topic", "Transform", one per skipped
// marker...), each ok, warn or error with a sentence; the worst level is the display's.

const LEVELS = { ok: 0, warn: 1, error: 2 };
const MAX_ENTRIES = 50; // kept per display: the rest is counted, not listed

export class StatusList {
  constructor() {
    this._entries = new Map(); // key -> {level, text}
    this._hidden = 0;
    /** Bumped on every change, so the panel redraws only what changed. */
    this.version = 0;
  }

  get(key) {
    return this._entries.get(key) || null;
  }

  set(key, level, text) {
    const old = this._entries.get(key);
    if (old && old.level === level && old.text === text) return;
    if (!old && this._entries.size >= MAX_ENTRIES) {
      this._hidden += 1;
      this.version += 1;
      return;
    }
    this._entries.set(key, { level, text });
    this.version += 1;
  }

  clear(key) {
    if (this._entries.delete(key)) this.version += 1;
  }

  /** Drop every entry whose key starts with `prefix` (the notes of deleted markers). */
  clearPrefix(prefix) {
    for (const key of [...this._entries.keys()]) if (key.startsWith(prefix)) this._entries.delete(key);
    this._hidden = 0;
    this.version += 1;
  }

  /** {level, entries: [{key, level, text}], hidden}: the worst first. */
  summary() {
    const entries = [...this._entries].map(([key, s]) => ({ key, level: s.level, text: s.text }));
    entries.sort((a, b) => LEVELS[b.level] - LEVELS[a.level]);
    return { level: entries.length ? entries[0].level : "ok", entries, hidden: this._hidden };
  }
}
