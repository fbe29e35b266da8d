"""An independent bar-and-hinge code (numpy), written from the definitions of
docs/design.md "Mechanics" (MERLIN2's), not from phedra's sources: it reads
the positions phedra writes (FOLD files at full precision), builds its own
model, stiffness, eigenpairs (dense, numpy.linalg.eigh), velocity (differences
of the written configurations) and fold energy, so that the tests compare
phedra's answers with what other code says of the written files.
"""
import json
import subprocess

import numpy as np


def positions(phedra, preset, ts):
    """Vertex positions (one array per t) and the faces, from `phedra generate -o x.fold`."""
    import os
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "x.fold")
        args = [phedra, "generate", preset, "-o", path]
        for t in ts:
            args += ["--t", repr(float(t))]
        subprocess.run(args, check=True, capture_output=True)
        doc = json.load(open(path))
    frames = [np.asarray(f["vertices_coords"], dtype=float) for f in doc["file_frames"]]
    reference = np.asarray(doc["vertices_coords"], dtype=float)  # at t*
    return frames, [list(f) for f in doc["faces_vertices"]], reference


def bounding_diagonal(x):
    return float(np.linalg.norm(x.max(axis=0) - x.min(axis=0)))


def signed_angle(xj, xk, xi, xl):
    """MERLIN2's angle, sign(n . r_ij) times the angle between m and n, in [0, 2 pi) (atan2 of |m x n| and m . n)."""
    rkj, rij, rkl = xk - xj, xi - xj, xk - xl
    m, n = np.cross(rij, rkj), np.cross(rkj, rkl)
    a = np.arctan2(np.linalg.norm(np.cross(m, n)), m @ n)
    if n @ rij < 0:
        a = -a
    return a + 2 * np.pi if a < 0 else a


def angle_gradient(xj, xk, xi, xl):
    """Liu and Paulino (2017): d theta / d(x_j, x_k, x_i, x_l)."""
    rkj, rij, rkl = xk - xj, xi - xj, xk - xl
    m, n = np.cross(rij, rkj), np.cross(rkj, rkl)
    lkj = np.linalg.norm(rkj)
    di = lkj / (m @ m) * m
    dl = -lkj / (n @ n) * n
    a, b = (rij @ rkj) / (lkj * lkj), (rkl @ rkj) / (lkj * lkj)
    return [(a - 1) * di - b * dl, -a * di + (b - 1) * dl, di, dl]


class Model:
    """The model of faces at positions x: nodes welded at 1e-9 of `size`, one
    bar per distinct edge, fold hinges for every pair of panels at an edge,
    n4b5 or n5b8 panels."""

    def __init__(self, x, faces, size, panels="n5b8", ea=1e3, kf=0.01, kb=0.1):
        tol = 1e-9 * size
        n = len(x)
        rep = list(range(n))
        for a in range(n):  # O(n^2): small test models
            for b in range(a):
                if np.linalg.norm(x[a] - x[b]) <= tol:
                    rep[a] = rep[b]
                    break
        self.vertex_node = {}
        nodes = []
        polys = []
        seen = set()
        for f in faces:
            ids = []
            for v in f:
                r = rep[v]
                if r not in self.vertex_node:
                    self.vertex_node[r] = len(nodes)
                    nodes.append(x[r])
                ids.append(self.vertex_node[r])
            ring = [ids[k] for k in range(len(ids)) if ids[k] != ids[(k + 1) % len(ids)]]
            assert len(ring) >= 3 and len(set(ring)) == len(ring), "a collapse the model refuses"
            key = tuple(sorted(ring))
            if key in seen:
                continue
            seen.add(key)
            polys.append(ring)
        self.rep = rep
        self.x = np.array(nodes)
        self.polys = polys
        self.centres = []  # (panel, base corner, other corner, ratio)
        edges = {}         # sorted pair -> list of (panel, from, to, wing)
        bars = {}
        bends = []
        X = list(self.x)
        for p, v in enumerate(polys):
            wings = []
            if len(v) == 3:
                wings = [v[(k + 2) % 3] for k in range(3)]
            else:
                d02, d13 = np.linalg.norm(X[v[2]] - X[v[0]]), np.linalg.norm(X[v[3]] - X[v[1]])
                if panels == "n4b5":
                    a = 0 if d02 < d13 else 1
                    bars[tuple(sorted((v[a], v[a + 2])))] = True
                    bends.append(((v[0], v[2], v[1], v[3]) if a == 0 else (v[1], v[3], v[0], v[2]), min(d02, d13)))
                    for k in range(4):
                        ends = {v[k], v[(k + 1) % 4]}
                        wings.append(v[a + 2] if v[a] in ends else v[a])
                else:
                    # the diagonals' lines meet: solve P0 + s (P2 - P0) = P1 + u (P3 - P1)
                    A = np.column_stack([X[v[2]] - X[v[0]], -(X[v[3]] - X[v[1]])])
                    s, u = np.linalg.lstsq(A, X[v[1]] - X[v[0]], rcond=None)[0]
                    base, ratio = (0, s) if d02 < d13 else (1, u)
                    c = len(X)
                    X.append(X[v[base]] + ratio * (X[v[base + 2]] - X[v[base]]))
                    self.centres.append((p, v[base], v[base + 2], ratio))
                    for k in range(4):
                        bars[tuple(sorted((c, v[k])))] = True
                        bends.append(((c, v[k], v[(k - 1) % 4], v[(k + 1) % 4]), np.linalg.norm(X[c] - X[v[k]])))
                        wings.append(c)
            for k in range(len(v)):
                a, b = v[k], v[(k + 1) % len(v)]
                bars[tuple(sorted((a, b)))] = True
                edges.setdefault(tuple(sorted((a, b))), []).append((p, a, b, wings[k]))
        self.x = np.array(X)
        self.bars = [(a, b, ea) for a, b in bars]
        self.folds = []
        for uses in edges.values():
            for i in range(len(uses)):
                for j in range(i + 1, len(uses)):
                    _, a, b, wi = uses[i]
                    wl = uses[j][3]
                    self.folds.append(((a, b, wi, wl), np.linalg.norm(self.x[b] - self.x[a]), kf))
        self.bends = [(h, length, kb) for h, length in bends]

    def nodes_from_vertices(self, y):
        """Node values (positions or velocities) from per-vertex ones: corners, then the centres."""
        out = np.zeros_like(self.x)
        for r, node in self.vertex_node.items():
            out[node] = y[r]
        for k, (p, base, other, ratio) in enumerate(self.centres):
            c = len(self.vertex_node) + k
            out[c] = out[base] + ratio * (out[other] - out[base])
        return out

    def stiffness(self):
        n = 3 * len(self.x)
        K = np.zeros((n, n))

        def add(nodes, g, k):
            dofs = np.array([3 * i + c for i in nodes for c in range(3)])
            K[np.ix_(dofs, dofs)] += k * np.outer(g, g)

        for a, b, ea in self.bars:
            e = self.x[b] - self.x[a]
            L = np.linalg.norm(e)
            add((a, b), np.concatenate([-e / L, e / L]), ea / L)
        for h, L, k in self.folds + self.bends:
            add(h, np.concatenate(angle_gradient(*(self.x[i] for i in h))), k * L)
        return K

    def rigid_basis(self):
        c = self.x.mean(axis=0)
        cols = []
        for a in range(3):
            t = np.zeros_like(self.x)
            t[:, a] = 1
            cols.append(t.ravel())
            cols.append(np.cross(np.eye(3)[a], self.x - c).ravel())
        q, _ = np.linalg.qr(np.array(cols).T)
        return q


def modes(model, count):
    """(rigid-body mode count, the `count` smallest non-rigid eigenvalues, their vectors, the largest)."""
    w, v = np.linalg.eigh(model.stiffness())
    rigid = int(np.sum(w < 1e-9 * w[-1]))
    return rigid, w[rigid:rigid + count], v[:, rigid:rigid + count], w[-1]


def velocity(frames_at, h):
    """Fourth-order central difference from frames at t - 2h, t - h, t + h, t + 2h."""
    m2, m1, p1, p2 = frames_at
    return (m2 - 8 * m1 + 8 * p1 - p2) / (12 * h)


def continuous(theta, near):
    return theta + 2 * np.pi * np.round((near - theta) / (2 * np.pi))
