// A minimal Chrome DevTools Protocol client over --remote-debugging-pipe:
// chromium reads JSON messages from fd 3 and writes them to fd 4, each
// ended by a NUL byte. No npm packages, no WebSocket, no port to pick.
import { spawn } from 'node:child_process';

export function launchChromium(binary, userDataDir, extraArgs = []) {
  const args = [
    '--headless', '--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader',
    '--remote-debugging-pipe', `--user-data-dir=${userDataDir}`,
    '--disable-background-networking', '--disable-component-update', '--no-first-run',
    '--no-default-browser-check', '--disable-dev-shm-usage', '--mute-audio', '--hide-scrollbars',
    ...extraArgs, 'about:blank',
  ];
  const proc = spawn(binary, args, { stdio: ['ignore', 'pipe', 'pipe', 'pipe', 'pipe'] });
  const log = [];
  const keep = (d) => { log.push(d.toString()); if (log.length > 200) log.shift(); };
  proc.stdout.on('data', keep);
  proc.stderr.on('data', keep);
  return { proc, cdp: new Cdp(proc), log };
}

export class Cdp {
  constructor(proc) {
    this.nextId = 1;
    this.pending = new Map();
    this.handlers = [];
    this.out = proc.stdio[3];
    this.closed = null;
    let parts = [];
    proc.stdio[4].on('data', (chunk) => {
      let start = 0, end;
      while ((end = chunk.indexOf(0, start)) >= 0) {
        parts.push(chunk.subarray(start, end));
        const text = Buffer.concat(parts).toString('utf8');
        parts = [];
        start = end + 1;
        this.dispatch(JSON.parse(text));
      }
      if (start < chunk.length) parts.push(chunk.subarray(start));
    });
    proc.on('exit', (code, signal) => {
      this.closed = `chromium exited (code ${code}, signal ${signal})`;
      for (const { reject } of this.pending.values()) reject(new Error(this.closed));
      this.pending.clear();
    });
  }

  send(method, params = {}, sessionId = undefined) {
    if (this.closed) return Promise.reject(new Error(this.closed));
    const id = this.nextId++;
    const msg = { id, method, params };
    if (sessionId) msg.sessionId = sessionId;
    return new Promise((resolve, reject) => {
      this.pending.set(id, { resolve, reject, method });
      this.out.write(JSON.stringify(msg) + '\0');
    });
  }

  // Calls fn(params) for every event `method` of one session.
  on(method, sessionId, fn) {
    this.handlers.push({ method, sessionId, fn });
  }

  dispatch(msg) {
    if (msg.id !== undefined) {
      const p = this.pending.get(msg.id);
      if (!p) return;
      this.pending.delete(msg.id);
      if (msg.error) p.reject(new Error(`${p.method}: ${msg.error.message}`));
      else p.resolve(msg.result);
      return;
    }
    for (const h of this.handlers) {
      if (h.method === msg.method && h.sessionId === msg.sessionId) h.fn(msg.params);
    }
  }
}
