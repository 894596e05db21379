#!/usr/bin/env python3
"""Run LAMMPS's peridynamic sphere-impact example and parse its output.

Reference half of the Peridot <-> LAMMPS comparison.  The decks in.pmb and
in.lps next to this file are LAMMPS's examples/peri/in.peri.pmb and
in.peri.lps (cylinder of radius 5 mm, y in [-5 mm, 0], simple cubic lattice
0.5 mm, density 2200 kg/m^3, point volume 1.25e-10 m^3, delta = 1.5001 mm,
struck by `fix indent` sphere of radius 1.5 mm at y = 1.55 mm - 100 m/s * t,
K = 1e17, 1000 steps of 1e-7 s) with extra output only; the trajectory is
bit-for-bit that of the unmodified example (checked: identical E_pair).

Units: LAMMPS PERI works in force *densities*.  fix indent's vector f_2[1..3]
is the force on the indenter summed over points, in N/m^3; multiplied by the
(uniform) point volume 1.25e-10 m^3 it is the force on the projectile in N.

Usage:
    import run_lammps
    r = run_lammps.run('pmb', '/tmp/lmp_pmb')     # or 'lps'
    r['time'], r['force'][:, 1], r['damage'], r['broken_fraction'], ...

    python3 run_lammps.py [workdir_root]   # runs both, prints a summary

numpy only; needs /usr/bin/lmp (LAMMPS 29 Sep 2021 with PERI).
"""

import os
import shutil
import subprocess
import sys
import time as _time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
POINT_VOLUME = 1.25e-10   # m^3, `set group all volume 1.25e-10`
LATTICE = 0.0005          # m
DELTA = 0.0015001         # m, horizon (pair_coeff cutoff)
DT = 1.0e-7               # s
DUMP_STEPS = (0, 250, 500, 750, 1000)


def _read_force_dat(path):
    """fix ave/time file: step time Fx Fy Fz nbroken_ends nbond_ends0."""
    rows = []
    with open(path) as fh:
        for line in fh:
            if line.startswith('#') or not line.strip():
                continue
            rows.append([float(v) for v in line.split()])
    a = np.array(rows, dtype=float)
    if a.ndim != 2 or a.shape[1] != 7:
        raise RuntimeError('unexpected format in %s' % path)
    return a


def _read_dump(path):
    """LAMMPS custom dump (one snapshot) -> (step, dict of columns)."""
    with open(path) as fh:
        lines = fh.read().splitlines()
    step = int(lines[lines.index('ITEM: TIMESTEP') + 1])
    natoms = int(lines[lines.index('ITEM: NUMBER OF ATOMS') + 1])
    hdr_i = next(i for i, l in enumerate(lines) if l.startswith('ITEM: ATOMS'))
    cols = lines[hdr_i].split()[2:]
    data = np.loadtxt(lines[hdr_i + 1:hdr_i + 1 + natoms], ndmin=2)
    order = np.argsort(data[:, cols.index('id')])
    data = data[order]
    d = {c: data[:, k] for k, c in enumerate(cols)}
    out = {
        'id': d['id'].astype(np.int64),
        'x0': np.column_stack([d['f_ref[1]'], d['f_ref[2]'], d['f_ref[3]']]),
        'x': np.column_stack([d['x'], d['y'], d['z']]),
        'damage': d['c_1'],
        'n0': d['f_n0'].astype(np.int64),
    }
    return step, out


def _log_value(log_text, key):
    for line in log_text.splitlines():
        if key in line:
            return line
    return None


def count_bonds(x0, delta=DELTA, lattice=LATTICE):
    """Initial bond count per point from reference positions (|xi| <= delta),
    the same test fix PERI_NEIGH uses.  Points are on a simple cubic lattice,
    so work with integer indices (exact)."""
    ijk = np.rint(x0 / lattice).astype(np.int64)
    lo = ijk.min(axis=0)
    ijk -= lo
    shape = ijk.max(axis=0) + 1
    occ = np.zeros(shape, dtype=bool)
    occ[ijk[:, 0], ijk[:, 1], ijk[:, 2]] = True
    m = int(np.floor(delta / lattice + 1e-9))
    r2max = (delta / lattice) ** 2
    n = np.zeros(len(x0), dtype=np.int64)
    for a in range(-m, m + 1):
        for b in range(-m, m + 1):
            for c in range(-m, m + 1):
                if (a, b, c) == (0, 0, 0) or a * a + b * b + c * c > r2max:
                    continue
                q = ijk + np.array([a, b, c])
                ok = np.all((q >= 0) & (q < shape), axis=1)
                hit = np.zeros(len(x0), dtype=bool)
                hit[ok] = occ[q[ok, 0], q[ok, 1], q[ok, 2]]
                n += hit
    return n


def run(model, workdir, lmp='/usr/bin/lmp', quiet=True, alpha=None):
    """Run the LAMMPS example for model 'pmb' or 'lps' in workdir; alpha, if given, replaces the example's
    alpha = 0.25 of the critical-stretch rule s0 = s00 - alpha * s_min (0: a constant s0 = s00, Peridot's).

    Returns a dict of numpy arrays / numbers:
      step, time [s]              output every 10 steps (0..1000)
      force [N], shape (n,3)      force on the projectile (fix indent vector
                                  x point volume); +y = pushing the sphere up
      force_density_sum, (n,3)    the raw fix indent vector [N/m^3]
      broken_fraction             broken bonds / initial bonds vs time (exact:
                                  sum_i n0_i*damage_i / sum_i n0_i)
      n_broken_bonds              number of broken bonds vs time
      n_bonds0                    number of initial bonds (each counted once)
      id, x0 (N,3), x (N,3)       final dump (step 1000): ids, reference and
      damage, n0                  current positions [m], damage/atom, initial
                                  bonds per point
      snapshots                   {step: dict(id,x0,x,damage,n0)} for
                                  steps 0,250,500,750,1000
      wall_s                      wall-clock seconds of the lmp process
      loop_s                      LAMMPS "Loop time" (the 1000 steps)
    """
    if model not in ('pmb', 'lps'):
        raise ValueError("model must be 'pmb' or 'lps'")
    workdir = os.path.abspath(workdir)
    os.makedirs(workdir, exist_ok=True)
    deck = 'in.' + model
    with open(os.path.join(HERE, deck)) as fh:
        text = fh.read()
    if alpha is not None:
        text = text.replace('0.0015001 0.0005 0.25', '0.0015001 0.0005 %r' % float(alpha))
    with open(os.path.join(workdir, deck), 'w') as fh:
        fh.write(text)
    for f in ['force.dat', 'log.lammps'] + ['dump.%d.txt' % s for s in DUMP_STEPS]:
        p = os.path.join(workdir, f)
        if os.path.exists(p):
            os.remove(p)

    env = dict(os.environ, OMP_NUM_THREADS='1')
    t0 = _time.perf_counter()
    with open(os.path.join(workdir, 'screen.txt'), 'w') as scr:
        proc = subprocess.run([lmp, '-in', deck, '-log', 'log.lammps'],
                              cwd=workdir, env=env, stdout=scr,
                              stderr=subprocess.STDOUT)
    wall = _time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError('lmp failed (rc=%d), see %s/screen.txt'
                           % (proc.returncode, workdir))

    with open(os.path.join(workdir, 'log.lammps')) as fh:
        log = fh.read()
    loop_line = _log_value(log, 'Loop time of')
    loop_s = float(loop_line.split()[3]) if loop_line else float('nan')
    bonds_line = _log_value(log, 'total # of bonds')
    # LAMMPS prints sum_i npartner_i, i.e. every bond counted from both ends
    bond_ends_log = int(bonds_line.split('=')[1]) if bonds_line else -1

    a = _read_force_dat(os.path.join(workdir, 'force.dat'))
    step = a[:, 0].astype(np.int64)
    fdens = a[:, 2:5]
    nbroken_ends = a[:, 5]
    nends0 = a[:, 6]
    if bond_ends_log >= 0 and not np.all(nends0 == bond_ends_log):
        raise RuntimeError('bond count mismatch: %s vs log %d'
                           % (nends0[0], bond_ends_log))

    snaps = {}
    for s in DUMP_STEPS:
        st, snap = _read_dump(os.path.join(workdir, 'dump.%d.txt' % s))
        snaps[st] = snap

    final = snaps[max(snaps)]
    # cross-checks: n0 from coord/atom == geometric count; thermo broken count
    # == sum n0*damage of the dumps
    n0_geo = count_bonds(final['x0'])
    if not np.array_equal(n0_geo, final['n0']):
        raise RuntimeError('initial bond counts disagree with geometry')
    for st, snap in snaps.items():
        k = np.nonzero(step == st)[0]
        if len(k):
            nb = float(np.sum(snap['n0'] * snap['damage']))
            if abs(nb - nbroken_ends[k[0]]) > 1e-6 * max(1.0, nb):
                raise RuntimeError('broken-bond count mismatch at step %d' % st)

    res = {
        'model': model,
        'step': step,
        'time': a[:, 1],
        'force_density_sum': fdens,
        'force': fdens * POINT_VOLUME,
        'n_broken_bonds': np.rint(nbroken_ends / 2).astype(np.int64),
        'n_bonds0': int(nends0[0] // 2),
        'broken_fraction': nbroken_ends / nends0,
        'id': final['id'],
        'x0': final['x0'],
        'x': final['x'],
        'damage': final['damage'],
        'n0': final['n0'],
        'snapshots': snaps,
        'wall_s': wall,
        'loop_s': loop_s,
    }
    return res


def summary(r):
    fy = r['force'][:, 1]
    k = int(np.argmax(fy))
    fmag = np.linalg.norm(r['force'], axis=1)
    d = r['damage']
    t = r['time']
    impulse = float(np.sum(0.5 * (fy[1:] + fy[:-1]) * np.diff(t)))
    lines = [
        'model %s: %d points, %d bonds' % (r['model'], len(d), r['n_bonds0']),
        '  peak projectile force Fy = %.4g N at t = %.3g s (step %d); '
        'max |F| = %.4g N' % (fy[k], r['time'][k], r['step'][k], fmag.max()),
        '  impulse int Fy dt (10-step samples, trapezoid) = %.4g N s' % impulse,
        '  final mean damage = %.4f, fraction of points with damage > 0.5 = '
        '%.4f' % (d.mean(), np.mean(d > 0.5)),
        '  broken-bond fraction at t = 2.5e-5/5e-5/7.5e-5/1e-4 s: %s'
        % ', '.join('%.4f' % r['broken_fraction'][r['step'] == s][0]
                    for s in (250, 500, 750, 1000)),
        '  wall time %.1f s (LAMMPS loop %.1f s)' % (r['wall_s'], r['loop_s']),
    ]
    return '\n'.join(lines)


if __name__ == '__main__':
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.environ.get('TMPDIR', '/tmp'), 'lammps_sphere_impact')
    for model in ('pmb', 'lps'):
        r = run(model, os.path.join(root, model))
        print(summary(r))
        sys.stdout.flush()
