// Mountain and valley: the hinges of a glTF export (either layout) coloured by the sign
// of their fold at the shown pose (FOLD's convention: valley positive), dimmed
// where both their panels turn their back to the camera, and the dihedral
// angle of one hinge over the whole motion.
import * as THREE from 'three';
import { primitivePanels } from './outline.js';

// Light orange and light sky blue: a pair the three kinds of colour blindness
// tell apart (blue against orange), of about the same lightness, so that valleys
// stand out as much as mountains on the (darkened) panels and stay apart from
// the dark panel edges (contrast of either about 2 : 1 or more on every member
// colour of the shipped arrays, checked on screenshots; the old blue #42a5f5
// was 1.04 : 1 on the blue panels).
export const foldColours = { mountain: 0xffb347, valley: 0x7fd1ff };
/// The hinges on panels seen from behind: as dark as the back faces are.
export const backFactor = 0.4;

const a = new THREE.Vector3(), b = new THREE.Vector3(), c = new THREE.Vector3();

/// Unit normal of a panel (Newell's, robust for planar quads and triangles).
export function normal(panel, x, out) {
  out.set(0, 0, 0);
  for (let k = 0; k < panel.length; ++k) {
    const i = 3 * panel[k], j = 3 * panel[(k + 1) % panel.length];
    out.x += (x[i + 1] - x[j + 1]) * (x[i + 2] + x[j + 2]);
    out.y += (x[i + 2] - x[j + 2]) * (x[i] + x[j]);
    out.z += (x[i] - x[j]) * (x[i + 1] + x[j + 1]);
  }
  return out.normalize();
}

/// Fold angle in degrees (valley > 0) of the hinge `from` -> `to` between panels
/// f (which runs along it that way) and g, at positions x (3 a vertex).
export function foldAngle(f, g, from, to, x) {
  const nf = normal(f, x, a), ng = normal(g, x, b);
  c.set(x[3 * to] - x[3 * from], x[3 * to + 1] - x[3 * from + 1], x[3 * to + 2] - x[3 * from + 2]).normalize();
  return THREE.MathUtils.radToDeg(Math.atan2(-new THREE.Vector3().crossVectors(nf, ng).dot(c), nf.dot(ng)));
}

/// The hinges of `panels` (lists of vertex indices, one orientation): edges two
/// panels share, [{from, to, f, g}] with f the panel that runs from -> to.
export function hingesOf(panels) {
  const seen = new Map(), out = [];
  panels.forEach((p, f) => {
    for (let k = 0; k < p.length; ++k) {
      const u = p[k], v = p[(k + 1) % p.length];
      if (u === v) continue;
      const key = u < v ? `${u},${v}` : `${v},${u}`;
      if (!seen.has(key)) seen.set(key, { from: u, to: v, f, g: -1 });
      else if (seen.get(key).g < 0) seen.get(key).g = f;
    }
  });
  for (const h of seen.values()) if (h.g >= 0) out.push(h);
  return out;
}

/// What the two layouts share: the hinges, their colours at the shown pose, a
/// picked hinge's angle and ends. Subclasses give shownPositions() (3 numbers a
/// vertex, in `frame`'s space), setLines(mountain, valley) and the frame.
class FoldsBase {
  init(panels, frame) {
    this.panels = panels;
    this.hinges = hingesOf(panels);
    this.frame = frame;  // positions are in this object's space
    this.signs = new Int8Array(this.hinges.length);
    this.back = new Uint8Array(this.hinges.length);  // 1: both panels turn their back to the camera
    this.normals = new Float32Array(3 * panels.length);
    this.eye = null;  // the camera, to dim the hinges of panels seen from behind
  }

  /// The camera whose view dims the hinges on back faces (null: none dimmed).
  watch(camera) { this.eye = camera; }

  /// Fold angle of hinge `h` in degrees at positions `x` (valley > 0).
  angle(h, x) {
    return foldAngle(this.panels[h.f], this.panels[h.g], h.from, h.to, x);
  }

  /// Which panels face the camera at positions x: 1 a panel that does (or when no camera is watched).
  facing(x) {
    const out = new Uint8Array(this.panels.length).fill(1);
    if (!this.eye) return out;
    this.frame.updateMatrixWorld(true);
    const eye = this.frame.worldToLocal(this.eye.getWorldPosition(new THREE.Vector3()));
    this.panels.forEach((p, f) => {
      const n = normal(p, x, c), i = 3 * p[0];
      out[f] = n.x * (eye.x - x[i]) + n.y * (eye.y - x[i + 1]) + n.z * (eye.z - x[i + 2]) >= 0 ? 1 : 0;
    });
    return out;
  }

  /// Colours the hinges by their fold at the shown pose, dimmed where both panels
  /// turn their back to the camera; {mountains, valleys}.
  update() {
    const x = this.shownPositions();
    const facing = this.facing(x);
    let changed = false, mountains = 0, valleys = 0;
    this.hinges.forEach((h, k) => {
      const angle = this.angle(h, x);
      const sign = Math.abs(angle) < 1e-6 ? 0 : angle > 0 ? 1 : -1;
      const back = facing[h.f] || facing[h.g] ? 0 : 1;
      if (sign !== this.signs[k] || back !== this.back[k]) { this.signs[k] = sign; this.back[k] = back; changed = true; }
      if (sign < 0) ++mountains; else if (sign > 0) ++valleys;
    });
    if (changed) {
      const lists = [[], [], [], []];  // mountain, valley, mountain behind, valley behind
      this.hinges.forEach((h, k) => {
        if (this.signs[k]) lists[(this.signs[k] < 0 ? 0 : 1) + 2 * this.back[k]].push(h.from, h.to);
      });
      [this.mountain, this.valley, this.mountainBack, this.valleyBack].forEach((line, j) => line.geometry.setIndex(lists[j]));
    }
    return { mountains, valleys };
  }

  /// The four line sets (mountain, valley, and both dimmed) made by `line(colour)`.
  makeLines(line) {
    const dim = (hex) => new THREE.Color(hex).multiplyScalar(backFactor);
    this.mountain = line(foldColours.mountain);
    this.valley = line(foldColours.valley);
    this.mountainBack = line(dim(foldColours.mountain));
    this.valleyBack = line(dim(foldColours.valley));
  }

  /// The hinge nearest a point of the surface (world space): its index, or -1.
  hingeNear(point) {
    const x = this.shownPositions(), p = this.frame.worldToLocal(point.clone());
    let best = -1, distance = Infinity;
    const s = new THREE.Line3();
    this.hinges.forEach((h, k) => {
      s.start.set(x[3 * h.from], x[3 * h.from + 1], x[3 * h.from + 2]);
      s.end.set(x[3 * h.to], x[3 * h.to + 1], x[3 * h.to + 2]);
      const d = s.closestPointToPoint(p, true, a).distanceTo(p);
      if (d < distance) { distance = d; best = k; }
    });
    return best;
  }

  /// The two ends of hinge k as shown (world space), for a marker.
  ends(k) {
    const x = this.shownPositions(), h = this.hinges[k];
    return [new THREE.Vector3(x[3 * h.from], x[3 * h.from + 1], x[3 * h.from + 2]).applyMatrix4(this.frame.matrixWorld),
            new THREE.Vector3(x[3 * h.to], x[3 * h.to + 1], x[3 * h.to + 2]).applyMatrix4(this.frame.matrixWorld)];
  }
}

/// The hinges of a morph-target export: the lines morph with the mesh on the GPU.
class MorphFolds extends FoldsBase {
  constructor(gltf, meshes) {
    super();
    this.mesh = meshes[0];  // every primitive shares the positions and the targets
    const json = gltf.parser.json;
    const panels = [];
    for (const mesh of meshes) {
      const association = gltf.parser.associations.get(mesh);
      const primitive = json.meshes[association?.meshes ?? 0]?.primitives[association?.primitives ?? 0];
      panels.push(...primitivePanels(mesh.geometry.index.array, primitive?.extras?.phedra_triangles));
    }
    this.init(panels, this.mesh);
    const geometry = this.mesh.geometry;
    const line = (colour) => {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', geometry.getAttribute('position'));
      g.morphAttributes.position = geometry.morphAttributes.position;
      g.morphTargetsRelative = geometry.morphTargetsRelative;
      g.setIndex([]);
      const l = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: colour, depthFunc: THREE.LessEqualDepth }));
      l.morphTargetInfluences = this.mesh.morphTargetInfluences;
      l.morphTargetDictionary = this.mesh.morphTargetDictionary;
      l.frustumCulled = false;
      l.renderOrder = 2;
      this.mesh.add(l);
      return l;
    };
    this.makeLines(line);
    this.positions = new Float32Array(geometry.getAttribute('position').array.length);
  }

  /// Every vertex as shown now (object space of the mesh: the morph targets applied).
  shownPositions() {
    const base = this.mesh.geometry.getAttribute('position').array, out = this.positions;
    out.set(base);
    const morphs = this.mesh.geometry.morphAttributes.position, w = this.mesh.morphTargetInfluences;
    w.forEach((weight, j) => {
      if (!weight) return;
      const d = morphs[j].array;
      for (let i = 0; i < out.length; ++i) out[i] += weight * d[i];
    });
    return out;
  }
}

/// The hinges of a node-per-panel export (`--nodes`): each panel's corners
/// (node extras.vertices: the file's vertex numbers) placed by its node, the
/// lines redrawn from them (space of the glTF scene).
class NodeFolds extends FoldsBase {
  constructor(gltf, nodes) {
    super();
    this.nodes = nodes;  // [{mesh, vertices}]
    let count = 0;
    for (const n of nodes) for (const v of n.vertices) count = Math.max(count, v + 1);
    this.init(nodes.map((n) => n.vertices), gltf.scene);
    this.positions = new Float32Array(3 * count);
    this.attribute = new THREE.BufferAttribute(this.positions.slice(), 3);
    const line = (colour) => {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', this.attribute);
      g.setIndex([]);
      const l = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: colour, depthFunc: THREE.LessEqualDepth }));
      l.frustumCulled = false;
      l.renderOrder = 2;
      gltf.scene.add(l);
      return l;
    };
    this.makeLines(line);
    this.inverse = new THREE.Matrix4();
  }

  shownPositions() {
    const out = this.positions, p = new THREE.Vector3();
    this.frame.updateMatrixWorld(true);
    this.inverse.copy(this.frame.matrixWorld).invert();
    for (const { mesh, vertices } of this.nodes) {
      const local = mesh.geometry.getAttribute('position');
      vertices.forEach((v, k) => {
        p.fromBufferAttribute(local, k).applyMatrix4(mesh.matrixWorld).applyMatrix4(this.inverse);
        out[3 * v] = p.x; out[3 * v + 1] = p.y; out[3 * v + 2] = p.z;
      });
    }
    return out;
  }

  update() {
    this.attribute.array.set(this.shownPositions());
    this.attribute.needsUpdate = true;
    return super.update();
  }
}

export class Folds {
  /// The folds of a loaded export, either layout (null when it has no panels).
  static of(gltf) {
    const meshes = [];
    gltf.scene.traverse((o) => { if (o.isMesh && !o.parent?.isMesh && o.geometry.morphAttributes.position) meshes.push(o); });
    if (meshes.length) return new MorphFolds(gltf, meshes);
    const json = gltf.parser.json, nodes = [];
    gltf.scene.traverse((o) => {
      const index = gltf.parser.associations.get(o)?.nodes;
      const vertices = index === undefined ? null : json.nodes[index]?.extras?.vertices;
      if (!vertices) return;
      const mesh = o.isMesh ? o : o.children.find((c) => c.isMesh);
      if (mesh) nodes.push({ mesh, vertices });
    });
    return nodes.length ? new NodeFolds(gltf, nodes) : null;
  }
}
