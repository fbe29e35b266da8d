// Loads FOLD files with the npm `fold` package and checks them: every frame has
// the vertex count of the base frame, edges and faces are consistent, the
// mountain/valley filters agree with the assignments; and geometrically: no
// zero-length edge in any frame, one connected mesh, every fold angle's sign
// matching its assignment (F and B exactly 0), no face with repeated vertices.
// usage: node tests/js/check_fold.mjs FILE.fold ...
import { createRequire } from 'node:module';
import { readFile } from 'node:fs/promises';

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const FOLD = require('fold');

let failed = false;
const fail = (file, message) => { console.log(`${file}: ${message}`); failed = true; };
for (const file of process.argv.slice(2)) {
  const fold = JSON.parse(await readFile(file, 'utf8'));
  const vertices = FOLD.filter.numVertices(fold);
  const edges = FOLD.filter.numEdges(fold);
  const faces = FOLD.filter.numFaces(fold);
  if (fold.file_spec !== 1.2) fail(file, `file_spec ${fold.file_spec}`);
  if (!(vertices > 0 && edges > 0 && faces > 0)) fail(file, 'empty mesh');
  for (const f of fold.faces_vertices) if (f.some((v) => v < 0 || v >= vertices)) fail(file, 'face index out of range');
  const assigned = FOLD.filter.mountainEdges(fold).length + FOLD.filter.valleyEdges(fold).length +
                   FOLD.filter.flatEdges(fold).length + FOLD.filter.boundaryEdges(fold).length;
  if (assigned !== edges) fail(file, `${assigned} assigned edges of ${edges}`);
  const frames = fold.file_frames ?? [];
  for (const [k, frame] of frames.entries()) {
    if (!frame.frame_inherit || frame.frame_parent !== 0) fail(file, `frame ${k + 1} does not inherit frame 0`);
    const merged = { ...fold, ...frame };
    if (FOLD.filter.numVertices(merged) !== vertices) fail(file, `frame ${k + 1} has ${FOLD.filter.numVertices(merged)} vertices, not ${vertices}`);
    if (frame.edges_foldAngle.length !== edges || frame.edges_assignment.length !== edges) fail(file, `frame ${k + 1}: edge fields of the wrong length`);
    if (frame.vertices_coords.some((p) => p.length !== 3 || p.some((x) => !Number.isFinite(x)))) fail(file, `frame ${k + 1}: bad coordinates`);
  }
  // Geometry, every frame.
  const root = [...Array(vertices).keys()];
  const find = (v) => (root[v] === v ? v : (root[v] = find(root[v])));
  for (const [a, b] of fold.edges_vertices) root[find(a)] = find(b);
  const components = root.filter((v, i) => find(i) === i).length;
  if (components !== 1) fail(file, `${components} connected components`);
  for (const f of fold.faces_vertices) if (new Set(f).size !== f.length) fail(file, `a face repeats a vertex: ${f}`);
  const size = Math.hypot(...[0, 1, 2].map((c) => Math.max(...fold.vertices_coords.map((p) => p[c])) - Math.min(...fold.vertices_coords.map((p) => p[c]))));
  for (const [k, state] of [fold, ...frames].entries()) {
    const coords = state.vertices_coords;
    const shortest = Math.min(...fold.edges_vertices.map(([a, b]) => Math.hypot(...[0, 1, 2].map((c) => coords[a][c] - coords[b][c]))));
    if (!(shortest > 1e-9 * size)) fail(file, `frame ${k}: an edge of length ${shortest}`);
    const angles = state.edges_foldAngle, assignment = state.edges_assignment;
    for (let e = 0; e < edges; ++e) {
      const ok = assignment[e] === 'V' ? angles[e] > 0 : assignment[e] === 'M' ? angles[e] < 0 : angles[e] === 0;
      if (!ok) { fail(file, `frame ${k}: edge ${e} is ${assignment[e]} with fold angle ${angles[e]}`); break; }
    }
  }
  console.log(`${file}: ${vertices} vertices, ${edges} edges, ${faces} faces, ${frames.length + 1} frames`);
}
process.exit(failed ? 1 : 0);
