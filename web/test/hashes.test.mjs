// Same bits as native: `node web/tools/hashes.mjs FILE` prints exactly what
// `dbss info FILE --hashes` prints (and fails exactly when it fails), on
// every golden file, the spec's test vector, the container fuzz corpus
// (damaged files included) and files freshly encoded from every shipped
// example.  DBSS_BIN names the native command (default build/bin/dbss).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readdirSync, rmSync, existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const repo = fileURLToPath(new URL('../..', import.meta.url));
const dbss = process.env.DBSS_BIN ?? join(repo, 'build/bin/dbss');
const hashes = join(repo, 'web/tools/hashes.mjs');
const filesIn = (dir, ext) => readdirSync(join(repo, dir)).filter((f) => f.endsWith(ext)).sort().map((f) => join(repo, dir, f));

function compare(file) {
  const native = spawnSync(dbss, ['info', file, '--hashes'], { encoding: 'utf8' });
  const wasm = spawnSync(process.execPath, [hashes, file], { encoding: 'utf8' });
  assert.equal(native.error, undefined, `${dbss}: ${native.error}`);
  assert.equal(wasm.stdout, native.stdout, `${file}: level lines differ`);
  assert.equal(wasm.status === 0, native.status === 0, `${file}: native exit ${native.status}, wasm exit ${wasm.status}\n${wasm.stderr}`);
  return native.stdout.split('\n').filter(Boolean).length;
}

test('native command is there', () => assert.ok(existsSync(dbss), `${dbss} missing: build it first (or set DBSS_BIN)`));

test('golden files and the spec test vector: same level lines as native', () => {
  const files = [...filesIn('tests/golden/v1', '.dbss'), ...filesIn('spec/test-vector', '.dbss')];
  assert.ok(files.length >= 5);
  for (const f of files) assert.ok(compare(f) >= 3, `${f}: fewer than 3 levels`);
});

test('the spec test vector hashes to the values spec/decoding.md lists', () => {
  const out = spawnSync(process.execPath, [hashes, join(repo, 'spec/test-vector/open-bipyramid-2-levels.dbss')], { encoding: 'utf8' });
  assert.equal(out.status, 0, out.stderr);
  const spec = (join(repo, 'spec/decoding.md'));
  const text = spawnSync('sed', ['-n', '/^```hashes$/,/^```$/p', spec], { encoding: 'utf8' }).stdout;
  const expected = text.split('\n').filter((l) => l.startsWith('level ')).join('\n') + '\n';
  assert.ok(expected.length > 20, 'no hashes block in spec/decoding.md');
  assert.equal(out.stdout, expected);
});

test('container fuzz corpus (cut, damaged, no-CRC files) and a garbage control mesh: same lines and verdict as native', () => {
  for (const f of [...filesIn('fuzz/corpus/container', '.dbss'), ...filesIn('tests/format/data', '.dbss')]) compare(f);
});

test('freshly encoded shipped examples: same lines as native', { timeout: 600000 }, () => {
  const dir = mkdtempSync(join(tmpdir(), 'dbss-web-'));
  try {
    const examples = filesIn('examples', '.xyz');
    assert.ok(examples.length >= 1);
    for (const ex of examples) {
      // 6 levels: the finest (1.26 M triangles) is past where a 32-bit
      // size_t once overflowed in the refinement step.
      for (const levels of [2, 6]) {
        const out = join(dir, `example-${levels}.dbss`);
        const enc = spawnSync(dbss, ['encode', ex, '-o', out, '--levels', String(levels)], { encoding: 'utf8' });
        assert.equal(enc.status, 0, enc.stderr);
        assert.equal(compare(out), levels + 1);
      }
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
