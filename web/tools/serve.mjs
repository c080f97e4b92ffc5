#!/usr/bin/env node
// A small static server for the viewer, tests and benchmark: honours HTTP
// Range requests (Python's http.server does not) and can send .dbss files
// slowly, in pieces, like a throttled connection.
//
//   node web/tools/serve.mjs [--port N] [--rate BYTES_PER_S] [--piece BYTES] [FILE.dbss]
//
// Serves the repository's web/ and build-web/dist/ folders, and FILE as
// /file.dbss; prints the viewer's URL.  Only GET and HEAD; nothing outside
// those folders is reachable.
import { createServer } from 'node:http';
import { createReadStream, readFileSync, statSync } from 'node:fs';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const TYPES = {
  '.html': 'text/html; charset=utf-8', '.mjs': 'text/javascript', '.js': 'text/javascript',
  '.css': 'text/css', '.json': 'application/json', '.wasm': 'application/wasm',
  '.dbss': 'application/octet-stream', '.drc': 'application/octet-stream', '.png': 'image/png',
};

// rate: bytes per second for .dbss files (0: full speed), in pieces of
// `piece` bytes.  files: {'/name.dbss': path}.  mounts: {'/prefix/': dir}.
// hold (tests): an object the caller may fill in later, {path, at, until}:
// a throttled send of `path` stops at file byte `at` until the promise
// `until` settles, so a test can see what a client does with a prefix of
// the file however slow the machine is.
export function startServer({ port = 0, host = '127.0.0.1', rate = 0, piece = 1024, files = {}, mounts = {}, hold = null } = {}) {
  const server = createServer((req, res) => {
    const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    const fail = (code, text) => { res.writeHead(code, { 'Content-Type': 'text/plain' }); res.end(text + '\n'); };
    if (req.method !== 'GET' && req.method !== 'HEAD') return fail(405, 'only GET and HEAD');
    if (path === '/') {
      res.writeHead(302, { Location: '/web/viewer/' + (files['/file.dbss'] ? '?file=/file.dbss' : '') });
      return res.end();
    }
    let file = files[path];
    if (!file) {
      for (const [prefix, dir] of Object.entries(mounts)) {
        if (!path.startsWith(prefix)) continue;
        const p = resolve(dir, normalize('./' + path.slice(prefix.length)));
        if (p === resolve(dir) || p.startsWith(resolve(dir) + sep)) file = p;
        break;
      }
    }
    let st;
    try {
      st = file && statSync(file);
      if (st && st.isDirectory()) { file = join(file, 'index.html'); st = statSync(file); }
    } catch { st = null; }
    if (!st) return fail(404, `${path}: not found`);

    const size = st.size;
    let start = 0, end = size;  // [start, end)
    const range = req.headers.range;
    let status = 200;
    if (range) {
      const m = /^bytes=(\d*)-(\d*)$/.exec(range);
      if (m && (m[1] !== '' || m[2] !== '')) {
        if (m[1] === '') { start = Math.max(0, size - Number(m[2])); }  // suffix: the last N bytes
        else { start = Number(m[1]); end = m[2] === '' ? size : Math.min(size, Number(m[2]) + 1); }
        if (start >= size || start >= end) {
          res.writeHead(416, { 'Content-Range': `bytes */${size}` });
          return res.end();
        }
        status = 206;
      }
    }
    const headers = { 'Content-Type': TYPES[extname(file)] ?? 'application/octet-stream', 'Content-Length': end - start,
      'Accept-Ranges': 'bytes', 'Cache-Control': 'no-store' };
    if (status === 206) headers['Content-Range'] = `bytes ${start}-${end - 1}/${size}`;
    res.writeHead(status, headers);
    if (req.method === 'HEAD' || end === start) return res.end();
    if (!rate || extname(file) !== '.dbss') return createReadStream(file, { start, end: end - 1 }).pipe(res);
    // Throttled: one piece every piece/rate seconds.
    const bytes = readFileSync(file).subarray(start, end);
    // The hold as an offset into this response (a Range response starts later).
    const held = hold && hold.path === path && hold.until && hold.at > start && hold.at < end ? hold : null;
    let at = 0;
    const tick = () => {
      if (res.destroyed) return;
      let n = Math.min(piece, bytes.length - at);
      if (held && at < held.at - start) n = Math.min(n, held.at - start - at);
      res.write(bytes.subarray(at, at + n));
      at += n;
      if (at >= bytes.length) return res.end();
      const next = () => setTimeout(tick, (1000 * n) / rate);
      if (held && at === held.at - start) held.until.then(next, next);
      else next();
    };
    tick();
  });
  return new Promise((ok, fail) => {
    server.once('error', fail);
    server.listen(port, host, () => ok({ server, url: `http://${host}:${server.address().port}` }));
  });
}

// The repository's usual mounts: web/ and the web build.
export function repoMounts(repo, buildDir = join(repo, 'build-web')) {
  return { '/web/': join(repo, 'web'), '/build-web/dist/': join(buildDir, 'dist') };
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const args = process.argv.slice(2);
  const opts = { port: 8000, rate: 0, piece: 1024 };
  let file = null;
  for (let i = 0; i < args.length; ++i) {
    const a = args[i];
    if (a === '--port' || a === '--rate' || a === '--piece') {
      const v = Number(args[++i]);
      if (!Number.isInteger(v) || v < 0) { console.error(`serve: ${a} needs a whole number`); process.exit(2); }
      opts[a.slice(2)] = v;
    } else if (a.startsWith('-')) { console.error(`serve: unknown option ${a}`); process.exit(2); }
    else file = a;
  }
  if (file) {
    try { statSync(file); } catch (e) { console.error(`serve: ${file}: ${e.message}`); process.exit(1); }
  }
  const repo = fileURLToPath(new URL('../..', import.meta.url));
  const { url } = await startServer({ ...opts, files: file ? { '/file.dbss': resolve(file) } : {}, mounts: repoMounts(repo, process.env.DBSS_WEB_BUILD) });
  console.log(`dbss viewer: ${url}/${file ? '' : 'web/viewer/'}` + (opts.rate ? `  (.dbss files at ${opts.rate} bytes/s)` : ''));
}
