// Thin client of the server's JSON API: every failure becomes an ApiError carrying the
// server's message, so the page can show it.
export class ApiError extends Error {
  constructor(message, status) { super(message); this.status = status; }
}

async function parse(res) {
  const type = res.headers.get('content-type') || '';
  if (!res.ok) {
    let message = `${res.status} ${res.statusText}`;
    if (type.includes('json')) { try { message = (await res.json()).error || message; } catch (_) { /* keep */ } }
    throw new ApiError(message, res.status);
  }
  return type.includes('json') ? res.json() : res.blob();
}

export async function get(path) {
  let res;
  try { res = await fetch(path, { cache: 'no-store' }); } catch (e) { throw new ApiError('server unreachable', 0); }
  return parse(res);
}

export async function post(path, body = {}) {
  let res;
  try {
    res = await fetch(path, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
  } catch (e) { throw new ApiError('server unreachable', 0); }
  return parse(res);
}

// Resolves when job `id` has finished; rejects with its error when it failed.
export async function waitJob(id, { interval = 250, timeoutMs = 600000 } = {}) {
  const t0 = performance.now();
  for (;;) {
    const s = await get(`/api/jobs/${id}`);
    if (s.state === 'done') return s;
    if (s.state === 'failed') throw new ApiError(s.error || 'job failed', 500);
    if (performance.now() - t0 > timeoutMs) throw new ApiError('timed out waiting for the server', 0);
    await new Promise((r) => setTimeout(r, interval));
  }
}
