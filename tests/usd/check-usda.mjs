// An independent reader for Wisp's .usda: TinyUSDZ (npm "tinyusdz", a USD parser compiled to
// WebAssembly) parses the file; the checks read TinyUSDZ's own re-serialisation of what it parsed
// (layerToString), so nothing here trusts Wisp's writer. Optionally compares every frame's points
// with a cyHair .hair sequence of the same bake, read here from its bytes.
//
//   node check-usda.mjs FILE.usda --frames A:B [--hair PATTERN.####.hair] [--head]
//
// Exit status 0 when every check holds; 1 with a message otherwise.
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

function fail(message) {
  console.error(`check-usda: ${message}`);
  process.exit(1);
}

const args = process.argv.slice(2);
const file = args[0];
const option = (name) => {
  const i = args.indexOf(name);
  return i >= 0 ? args[i + 1] : undefined;
};
if (!file || !option('--frames')) fail('usage: check-usda.mjs FILE.usda --frames A:B [--hair PATTERN] [--head]');
const [first, last] = option('--frames').split(':').map(Number);

// tinyusdz's npm build targets browsers; it runs in node when it takes itself for a browser
// renderer and is handed the wasm bytes (no fetch of a file: URL).
process.type = 'renderer';
globalThis.window = globalThis.window || {};
const require = createRequire(import.meta.url);
const entry = require.resolve('tinyusdz/tinyusdz.js', { paths: [process.env.WISP_TINYUSDZ_DIR || process.cwd()] });
const { default: createModule } = await import(entry);
const M = await createModule({ wasmBinary: fs.readFileSync(path.join(path.dirname(entry), 'tinyusdz.wasm')) });

const loader = new M.TinyUSDZLoaderNative();
const bytes = new Uint8Array(fs.readFileSync(file));
if (!loader.loadAsLayerFromBinary(bytes, file)) fail(`${file}: TinyUSDZ could not parse it`);
const text = loader.layerToString();

const stage = text.slice(0, text.indexOf(')'));
if (!/metersPerUnit = 1\b/.test(stage)) fail('metersPerUnit is not 1');
if (!/upAxis = "Y"/.test(stage)) fail('upAxis is not "Y"');

const curves = text.match(/def BasisCurves "hair"\s*\{([\s\S]*?)\n    \}/);
if (!curves) fail('no BasisCurves "hair"');
const body = curves[1];
const counts = body.match(/int\[\] curveVertexCounts = \[([^\]]*)\]/);
if (!counts) fail('no curveVertexCounts');
const vertexCounts = counts[1].split(',').map(Number);
const total = vertexCounts.reduce((a, b) => a + b, 0);
if (vertexCounts.some((n) => !(n >= 2))) fail('a curve has fewer than 2 points');

const numbers = (s) => s.match(/-?\d+(?:\.\d*)?(?:e[-+]?\d+)?/gi).map(Number);
const samples = new Map();
const animated = first !== last;
if (animated) {
  const block = body.match(/point3f\[\] points\.timeSamples = \{([\s\S]*?)\n\s*\}/);
  if (!block) fail('no points.timeSamples');
  for (const line of block[1].split('\n')) {
    const m = line.match(/^\s*([-\d.e+]+):\s*\[(.*)\],?\s*$/);
    if (m) samples.set(Number(m[1]), numbers(m[2]));
  }
} else {
  const m = body.match(/point3f\[\] points = \[(.*)\]/);
  if (!m) fail('no points');
  samples.set(first, numbers(m[1]));
}
if (samples.size !== last - first + 1) fail(`${samples.size} point samples for frames ${first}:${last}`);
for (let f = first; f <= last; ++f) {
  const p = samples.get(f);
  if (!p) fail(`no sample at time code ${f}`);
  if (p.length !== 3 * total) fail(`frame ${f}: ${p.length / 3} points; curveVertexCounts add up to ${total}`);
}
const widths = body.match(/float\[\] widths = \[([^\]]*)\]/);
if (!widths || numbers(widths[1]).length !== total) fail('widths are not one per point');
if (!/interpolation = "vertex"/.test(body)) fail('widths are not per vertex');

// The tips move between frames.
let moved = 0;
if (animated) {
  for (let f = first + 1; f <= last; ++f) {
    const a = samples.get(f - 1), b = samples.get(f);
    let tip = -1;
    for (const n of vertexCounts) {
      tip += n;
      const d = Math.hypot(a[3 * tip] - b[3 * tip], a[3 * tip + 1] - b[3 * tip + 1], a[3 * tip + 2] - b[3 * tip + 2]);
      if (d > 1e-4) ++moved;
    }
  }
  if (moved === 0) fail('no tip moves between frames');
}

if (args.includes('--head')) {
  const head = text.match(/def Mesh "mesh"[\s\S]*?int\[\] faceVertexCounts = \[([^\]]*)\]/);
  if (!head) fail('no head Mesh');
  const xform = text.match(/matrix4d xformOp:transform(\.timeSamples)? =/);
  if (!xform) fail('the head has no xformOp:transform');
}

// The same bake as a cyHair sequence: every point within 1e-6 m.
const pattern = option('--hair');
let worst = 0;
if (pattern) {
  const hashes = pattern.match(/#+(?!.*#)/)[0];
  for (let f = first; f <= last; ++f) {
    const name = pattern.replace(/#+(?!.*#)/, String(f).padStart(hashes.length, '0'));
    const buf = fs.readFileSync(name);
    if (buf.toString('latin1', 0, 4) !== 'HAIR') fail(`${name}: not a cyHair file`);
    const strands = buf.readUInt32LE(4), points = buf.readUInt32LE(8), flags = buf.readUInt32LE(12);
    let at = 128;
    const segments = [];
    if (flags & 1) {
      for (let s = 0; s < strands; ++s) segments.push(buf.readUInt16LE(at + 2 * s));
      at += 2 * strands;
    }
    if (!(flags & 2)) fail(`${name}: no points array`);
    if (points !== total) fail(`${name}: ${points} points; the .usda has ${total}`);
    const usd = samples.get(f);
    for (let i = 0; i < 3 * points; ++i) worst = Math.max(worst, Math.abs(buf.readFloatLE(at + 4 * i) - usd[i]));
  }
  if (!(worst <= 1e-6)) fail(`a point differs from the .hair sequence by ${worst} m`);
}
console.log(`check-usda: ${file}: TinyUSDZ read ${vertexCounts.length} curves, ${total} points, ${samples.size} samples` +
            (animated ? `, ${moved} tip moves` : '') + (pattern ? `, largest difference from the .hair sequence ${worst} m` : ''));
