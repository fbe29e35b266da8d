// Panel outlines and invalid-panel overlays for a phedra glTF, in either
// representation: line segments along every panel's edges (not the diagonal
// that splits a quad into triangles) that follow the animation, and the panels
// the file's buildability names as invalid drawn again in red on top.
import * as THREE from 'three';

/// The panels of a morph primitive as lists of local vertex indices, from its
/// triangle index: quads are written (a, b, c), (a, c, d); the primitive's
/// extras list which of its panels are single triangles (two corners welded).
export function primitivePanels(index, triangles) {
  const single = new Set(triangles ?? []);
  const panels = [];
  for (let at = 0, k = 0; at < index.length; ++k) {
    if (single.has(k)) {
      panels.push([index[at], index[at + 1], index[at + 2]]);
      at += 3;
    } else {
      panels.push([index[at], index[at + 1], index[at + 2], index[at + 5]]);
      at += 6;
    }
  }
  return panels;
}

/// Geometry sharing `source`'s positions and morph targets, with its own index.
function sharedGeometry(source, index) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', source.getAttribute('position'));
  if (source.morphAttributes.position) g.morphAttributes.position = source.morphAttributes.position;
  g.morphTargetsRelative = source.morphTargetsRelative;
  g.setIndex(index);
  return g;
}

/// Edges of the given panels (deduplicated) as a line-segment index.
function edgeIndex(panels) {
  const seen = new Set(), out = [];
  for (const p of panels) {
    for (let k = 0; k < p.length; ++k) {
      const a = p[k], b = p[(k + 1) % p.length];
      const key = a < b ? `${a},${b}` : `${b},${a}`;
      if (a === b || seen.has(key)) continue;
      seen.add(key);
      out.push(a, b);
    }
  }
  return out;
}

/// Adds the outlines and overlays to the loaded glTF scene. Returns
/// {edges: the number of edge segments, invalid: the number of panels drawn red}.
export function addPanelOutlines(gltf, invalidPanels = []) {
  const json = gltf.parser.json;
  const invalid = new Set(invalidPanels);
  // No depth writes: the fold lines drawn after them cover them instead of fighting them pixel by pixel.
  const lineMaterial = new THREE.LineBasicMaterial({ color: 0x1b2028, depthWrite: false });
  const redMaterial = new THREE.MeshBasicMaterial({ color: 0xe53935, side: THREE.DoubleSide,
    polygonOffset: true, polygonOffsetFactor: -1, polygonOffsetUnits: -1 });
  let edges = 0, red = 0;
  const backs = new Map();
  const meshes = [];
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  for (const mesh of meshes) {
    const geometry = mesh.geometry;
    let panels, numbers;
    if (mesh.userData.vertices) {
      // A node panel: its corners in order (a welded triangle repeats one).
      panels = [geometry.index.count === 6 ? [0, 1, 2, 3] : Array.from(geometry.index.array)];
      numbers = [mesh.userData.face];
    } else {
      // A morph primitive: GLTFLoader gives one mesh per primitive, in order.
      const association = gltf.parser.associations.get(mesh);
      const primitive = json.meshes[association?.meshes ?? 0]?.primitives[association?.primitives ?? 0];
      panels = primitivePanels(geometry.index.array, primitive?.extras?.phedra_triangles);
      const [first] = primitive?.extras?.phedra_panels ?? [0];
      numbers = panels.map((_, k) => first + k);
    }
    const lines = new THREE.LineSegments(sharedGeometry(geometry, edgeIndex(panels)), lineMaterial);
    edges += lines.geometry.index.count / 2;
    const bad = panels.filter((_, k) => invalid.has(numbers[k]));
    const attach = (object) => {
      if (mesh.morphTargetInfluences) {
        object.morphTargetInfluences = mesh.morphTargetInfluences;  // the same array: the mixer drives both
        object.morphTargetDictionary = mesh.morphTargetDictionary;
      }
      object.frustumCulled = false;  // the morphed shape leaves the rest pose's bounds
      mesh.add(object);
    };
    attach(lines);
    // Back faces darker than front faces (one material a member, double-sided in the file).
    if (!backs.has(mesh.material)) {
      // Faces pushed back a little in depth: the edges and fold lines on them do not flicker.
      Object.assign(mesh.material, { polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
      const back = mesh.material.clone();
      back.side = THREE.BackSide;
      back.color = mesh.material.color.clone().multiplyScalar(0.45);
      backs.set(mesh.material, back);
      mesh.material.side = THREE.FrontSide;
    }
    attach(new THREE.Mesh(geometry, backs.get(mesh.material)));
    if (bad.length) {
      const triangles = [];
      for (const p of bad) for (let k = 1; k + 1 < p.length; ++k) triangles.push(p[0], p[k], p[k + 1]);
      attach(new THREE.Mesh(sharedGeometry(geometry, triangles), redMaterial));
      red += bad.length;
    }
    mesh.frustumCulled = false;
  }
  return { edges, invalid: red };
}
