// What the core says every client must agree on (GET /api/config): WebSocket close codes,
// stream limits and each world's arena, so the dashboard never spells them again. Loaded once,
// before any module that imports it runs (top-level await); retried while the core starts.

async function load() {
  for (let attempt = 0; ; attempt += 1) {
    try {
      const reply = await fetch("/api/config");
      if (reply.ok) return await reply.json();
    } catch {
      // the core is restarting: try again below
    }
    await new Promise((resolve) => setTimeout(resolve, Math.min(250 * 2 ** attempt, 4000)));
  }
}

export const config = await load();
/** Close codes by name: CLOSE.invalid_frame === 1007, ... */
export const CLOSE = config.close_codes;
