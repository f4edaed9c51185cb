#!/usr/bin/env python3
"""Research prototype (not part of the build or the tests): the multiply scattered radiance of a
bench scene from a flux-limited diffusion solve on a regular grid, to hold against the path
tracer's `multiple` channel before a GPU version is written (docs/LIGHTING.md, "Tried
2026-12-03: flux-limited diffusion"). Needs python3-numpy and python3-scipy.

  build/prototype_io density build/density128.raw          (scripts/prototypes/prototype_io.cpp)
  build/prototype_io channels REF.exr build/ref.raw R G B A single multiple ambient
  python3 scripts/prototypes/flux_limited_diffusion.py data/bench_scenes/cluster.json \
      build/density128.raw build/ref.raw --spacing 0.1

What it computes (conservative medium, albedo 1; lengths in scene units):
  extinction   σ(x) = Σ_i σ0 · ρ_i · ρ̂((x − c_i)/r_i) / r_i     (σ0 = β·R, the unit optical radius)
  δ-Eddington  f = g², σ* = σ·(1 − f), g* = g/(1 + g)             (g the later phase's mean cosine)
  sunlight     E(x) = exp(−τ*(x)), τ* the optical depth σ* toward the sun   (per unit irradiance)
  source       q = (E(x + l·h/2) − E(x − l·h/2))/h, what the beam loses across a cell (≈ σ*·E;
               --point-source takes σ*·E at the cell centre)
  diffusion    −∇·(D ∇φ) = q, D = 1/(3σ*(1 − g*) + |∇φ|/φ)   (Wilson's flux limiter, iterated)
               Marshak (vacuum) faces on the grid's border
  radiance     L = ∫ σ(x) (φ + 3 g J·ω)/(4π) T(t) dt along each view ray, J = −D ∇φ,
               ω the direction toward the eye: orders ≥ 2 only, as the reference's `multiple`.
"""
import argparse
import json
import sys

import numpy as np
from scipy import sparse
from scipy.ndimage import map_coordinates
from scipy.sparse.linalg import cg

UNIT_OPTICAL_RADIUS = 12.866  # β·R of the default medium (extinction 0.07 /m, radius 183.8 m)
LATER_MEAN_COSINE = 0.757     # mean cosine of the default later phase (Cornette-Shanks, 0.7)


def radii(p):
    r = p['radii']
    return np.array(r if isinstance(r, list) else [r] * 3, float)


def quaternion_matrix(q):
    w, x, y, z = np.array(q, float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def axis_rotation(axis, degrees):
    c, s = np.cos(np.radians(degrees)), np.sin(np.radians(degrees))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = np.eye(3)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def to_particle(p):
    """World offset → unit-sphere coordinates: Qᵀ · D⁻¹ · Rᵀ (src/scene/Scene.cpp)."""
    R = np.eye(3)
    if 'quaternion' in p:
        R = quaternion_matrix(p['quaternion'])
    elif 'euler_deg' in p:
        e = p['euler_deg']
        R = axis_rotation(2, e[2]) @ axis_rotation(1, e[1]) @ axis_rotation(0, e[0])
    Q = quaternion_matrix(p['noise_quaternion']) if 'noise_quaternion' in p else np.eye(3)
    return Q.T @ np.diag(1 / radii(p)) @ R.T


def extinction_grid(particles, density, lo, h, n):
    xs = [lo[a] + h * (np.arange(n[a]) + 0.5) for a in range(3)]
    X, Y, Z = np.meshgrid(*xs, indexing='ij')
    sig = np.zeros(n)
    res = density.shape[0]
    for p in particles:
        # an ellipsoid's extinction depends on the direction (σ0·ρ·|M⁻¹ω|); the grid takes the
        # radii's geometric mean
        c, r, M = np.array(p['center'], float), radii(p), to_particle(p)
        lx, ly, lz = (M[k, 0] * (X - c[0]) + M[k, 1] * (Y - c[1]) + M[k, 2] * (Z - c[2]) for k in range(3))
        inside = lx * lx + ly * ly + lz * lz < 1
        coords = np.array([(l[inside] + 1) * res / 2 - 0.5 for l in (lz, ly, lx)])
        rho_hat = map_coordinates(density, coords, order=1, mode='nearest')
        sig[inside] += UNIT_OPTICAL_RADIUS * p['density'] * rho_hat / np.prod(r) ** (1 / 3)
    return sig, np.stack([X, Y, Z], -1)


def sample(field, points, lo, h):
    return map_coordinates(field, ((points - lo) / h - 0.5).T, order=1, mode='constant', cval=0.0)


def optical_depth_toward(field, points, direction, lo, h, length):
    tau, s, step = np.zeros(len(points)), 0.25 * h, 0.5 * h
    while s < length:
        tau += sample(field, points + s * direction, lo, h) * step
        s += step
    return tau


def solve_diffusion(D, source, h):
    """−∇·(D∇φ) = source, cell-centred finite volumes, harmonic face D, Marshak border faces."""
    n = D.shape
    count = D.size
    index = np.arange(count).reshape(n)
    rows, cols, vals, diag = [], [], [], np.zeros(count)
    for a in range(3):
        lo_sl, hi_sl = [slice(None)] * 3, [slice(None)] * 3
        lo_sl[a], hi_sl[a] = slice(0, -1), slice(1, None)
        ia, ib = index[tuple(lo_sl)].ravel(), index[tuple(hi_sl)].ravel()
        Da, Db = D[tuple(lo_sl)].ravel(), D[tuple(hi_sl)].ravel()
        coef = 2 * Da * Db / (Da + Db) / (h * h)
        np.add.at(diag, ia, coef)
        np.add.at(diag, ib, coef)
        rows += [ia, ib]
        cols += [ib, ia]
        vals += [-coef, -coef]
        for end in (0, -1):  # border: flux out = φ_face / 2
            sl = [slice(None)] * 3
            sl[a] = end
            ii, Dc = index[tuple(sl)].ravel(), D[tuple(sl)].ravel()
            k = 2 * Dc / h
            np.add.at(diag, ii, k / (2 * k + 1) / h)
    A = sparse.csr_matrix((np.concatenate(vals + [diag]),
                           (np.concatenate(rows + [np.arange(count)]), np.concatenate(cols + [np.arange(count)]))),
                          shape=(count, count))
    phi, info = cg(A, source.ravel(), tol=1e-8, maxiter=20000)
    if info != 0:
        print('warning: CG did not converge (%d)' % info, file=sys.stderr)
    return phi.reshape(n)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('scene')
    ap.add_argument('density', help='prototype_io density output (128³ float32)')
    ap.add_argument('reference', help='prototype_io channels output: R G B A single multiple ambient')
    ap.add_argument('--spacing', type=float, default=0.1, help='grid spacing (scene units)')
    ap.add_argument('--limiter-iterations', type=int, default=16)
    ap.add_argument('--point-source', action='store_true', help='source at cell centres (the first version)')
    ap.add_argument('--out', help='write the multiple-scattering image (float32, height × width)')
    args = ap.parse_args()

    scene = json.load(open(args.scene))
    particles = scene['particles']
    h, g = args.spacing, LATER_MEAN_COSINE
    density = np.fromfile(args.density, dtype=np.float32)
    res = round(len(density) ** (1 / 3))
    density = density.reshape(res, res, res)
    lo = np.min([np.array(p['center']) - radii(p).max() for p in particles], 0) - 3 * h
    hi = np.max([np.array(p['center']) + radii(p).max() for p in particles], 0) + 3 * h
    n = tuple(np.ceil((hi - lo) / h).astype(int))
    sig, X = extinction_grid(particles, density, lo, h, n)

    f, g_star = g * g, g / (1 + g)
    sig_star = sig * (1 - f)
    sun = np.array(scene['sun']['direction'], float)
    sun /= np.linalg.norm(sun)
    irradiance = scene['sun'].get('color', [1, 1, 1])[0]
    length = np.linalg.norm(hi - lo)
    if args.point_source:  # σ*·E at the cell centre: misses most of a steep sunlit layer
        tau_sun = optical_depth_toward(sig_star, X.reshape(-1, 3), sun, lo, h, length).reshape(n)
        source = sig_star * irradiance * np.exp(-tau_sun)
    else:  # what the beam loses across the cell: (E(x + l·h/2) − E(x − l·h/2)) / h
        points = X.reshape(-1, 3)
        near = optical_depth_toward(sig_star, points + 0.5 * h * sun, sun, lo, h, length).reshape(n)
        far = optical_depth_toward(sig_star, points - 0.5 * h * sun, sun, lo, h, length).reshape(n)
        source = irradiance * np.maximum(np.exp(-near) - np.exp(-far), 0) / h
    transport = sig_star * (1 - g_star)
    D = 1.0 / (3 * transport + 1.0 / h)
    for _ in range(args.limiter_iterations):
        phi = solve_diffusion(D, source, h)
        grad = np.gradient(phi, h)
        D = 1.0 / (3 * transport + np.sqrt(sum(x * x for x in grad)) / np.maximum(phi, 1e-12))
    flux = [-D * x for x in np.gradient(phi, h)]

    ref = np.fromfile(args.reference, dtype=np.float32)
    W, H = ref[:2].view(np.int32)
    ref = ref[2:].reshape(H, W, 7)
    cam = scene['camera']
    eye, target = np.array(cam['eye'], float), np.array(cam['target'], float)
    fwd = (target - eye) / np.linalg.norm(target - eye)
    right = np.cross(fwd, [0, 1, 0])
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    t = np.tan(np.radians(cam['fov_deg']) / 2)
    py, px = np.meshgrid(np.arange(H), np.arange(W), indexing='ij')
    dirs = fwd + ((2 * (px + 0.5) / W - 1) * t * W / H)[..., None] * right + ((1 - 2 * (py + 0.5) / H) * t)[..., None] * up
    dirs = (dirs / np.linalg.norm(dirs, axis=-1, keepdims=True)).reshape(-1, 3)
    centre, radius = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2
    d0, step = np.linalg.norm(eye - centre), 0.5 * h
    T, L = np.ones(len(dirs)), np.zeros(len(dirs))
    for s in np.arange(max(d0 - radius, 0), d0 + radius, step):
        q = eye + s * dirs
        sg = sample(sig, q, lo, h)
        if not sg.any():
            continue
        toward_eye = sum(sample(flux[a], q, lo, h) * -dirs[:, a] for a in range(3))
        L += T * (1 - np.exp(-sg * step)) * (sample(phi, q, lo, h) + 3 * g * toward_eye) / (4 * np.pi)
        T *= np.exp(-sg * step)
    L = L.reshape(H, W)

    reference = ref[..., 5] * irradiance
    cloud = ref[..., 3] > 0.01
    def box(x, r=2):
        p = np.pad(x, r, mode='edge')
        return sum(p[r + dy:r + dy + H, r + dx:r + dx + W] for dy in range(-r, r + 1) for dx in range(-r, r + 1)) / (2 * r + 1) ** 2
    interior = box(cloud.astype(float), 1) > 0.999
    rel = lambda a, b, m: 100 * np.sqrt(((a - b)[m] ** 2).mean()) / np.sqrt((b[m] ** 2).mean())
    print('%s: %d cells, spacing %g; multiple term: bias %+.1f%%, relative RMSE %.1f%%, after a 5x5 box %.1f%%; '
          'alpha error %.3f' % (args.scene, sig.size, h, 100 * (L[cloud].mean() / reference[cloud].mean() - 1),
                                rel(L, reference, interior), rel(box(L), box(reference), interior),
                                np.abs(1 - T.reshape(H, W) - ref[..., 3])[cloud].mean()))
    if args.out:
        L.astype(np.float32).tofile(args.out)


if __name__ == '__main__':
    main()
