// Converts the npm `bunny` package (positions + cells, +Y up) into an ASCII PLY that stands on its
// feet with +Z up and rests on z = 0. Usage: node bunny_to_ply.js <package dir> <out.ply>
'use strict';
const fs = require('fs');
const [pkgDir, outPath] = process.argv.slice(2);
const bunny = require(require('path').resolve(pkgDir));
// Rotate +90 degrees about X: (x, y, z) -> (x, -z, y). A proper rotation, so orientation is kept.
const pts = bunny.positions.map(([x, y, z]) => [x, -z, y]);
const zmin = Math.min(...pts.map(p => p[2]));
for (const p of pts) p[2] -= zmin;
// Make the faces point outwards (positive signed volume) so normals mean "out of the solid".
let vol = 0;
for (const [a, b, c] of bunny.cells) {
  const [p, q, r] = [pts[a], pts[b], pts[c]];
  vol += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) + p[2] * (q[0] * r[1] - q[1] * r[0])) / 6;
}
const cells = vol < 0 ? bunny.cells.map(([a, b, c]) => [a, c, b]) : bunny.cells;
const lines = ['ply', 'format ascii 1.0', 'comment Stanford bunny from the npm package "bunny", +Z up',
  `element vertex ${pts.length}`, 'property float x', 'property float y', 'property float z',
  `element face ${cells.length}`, 'property list uchar int vertex_indices', 'end_header'];
for (const p of pts) lines.push(p.map(v => v.toFixed(6)).join(' '));
for (const c of cells) lines.push(`3 ${c.join(' ')}`);
fs.writeFileSync(outPath, lines.join('\n') + '\n');
console.error(`[bunny] ${pts.length} vertices, ${cells.length} faces, signed volume ${Math.abs(vol).toFixed(1)}${vol < 0 ? ' (faces flipped outward)' : ''}`);
