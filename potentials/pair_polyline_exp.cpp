/* ----------------------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/

   Copyright (2026) the contributors to the oblique-impact workflow.
   This file is not part of the LAMMPS distribution. It is written to be
   compiled against LAMMPS and is, like LAMMPS, free software: you may
   redistribute and modify it under the GNU General Public License as
   published by the Free Software Foundation, version 2 or (at your
   option) any later version. It comes WITHOUT ANY WARRANTY; see the
   LICENSE file in the top-level directory of the oblique-impact workflow.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: the oblique-impact workflow project
     (pair style polyline/exp; see potentials/README.md)
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Pair style polyline/exp: exponential repulsion of points from a polyline.

   A point p of a "point" type is repelled by the closest feature (segment
   interior or vertex) of a polyline whose vertices are the atoms with tags
   first..last, in tag order; the polyline is the top of a body that lies
   below it (towards -y):

     E = v0 exp(-a l),  l = |p - q|,  q the closest point of the polyline

   The reaction -F is shared by the segment's two ends with the lever rule,
   weights (1-t) and t for q = w1 + t (w2 - w1); at a vertex it all goes to
   the vertex. By the envelope theorem this is also the exact gradient of E,
   which the "gradient" rule computes independently (for checks).

   "closed yes" makes the polyline a ring around its body (the last vertex
   joins the first, counter-clockwise, the body on its left); "partner f l"
   adds a second ring, and each ring's vertices are then the points that the
   other ring repels: two rough disks in contact (docs/model.md).
------------------------------------------------------------------------- */

#include "pair_polyline_exp.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

// LAMMPS versions from 2022 on request neighbor lists with add_request();
// platform.h appeared with them.
#if __has_include("platform.h")
#define POLYLINE_EXP_ADD_REQUEST
#else
#include "neigh_request.h"
#endif

#include <algorithm>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

enum { LEVER, GRADIENT };

// a ring's outward direction at a vertex: the chord from CHORD vertices
// before it to CHORD after it (inside_ring)
static constexpr int CHORD = 4;

/* ---------------------------------------------------------------------- */

PairPolylineExp::PairPolylineExp(LAMMPS *lmp) : Pair(lmp), active(nullptr)
{
  single_enable = 0;
  restartinfo = 0;
  manybody_flag = 1;
  // compute() tallies the virial contact by contact (ev_tally, ev_tally3) and
  // never calls virial_fdotr_compute(): without this flag, Pair::ev_setup()
  // would leave the global virial to that f dot r sum, and so at zero
  no_virial_fdotr_compute = 1;

  a = v0 = cut = reach = 0.0;
  lo[0] = hi[0] = lo[1] = hi[1] = 0;
  npolylines = 1;
  closed = 0;
  rule = LEVER;
}

/* ---------------------------------------------------------------------- */

PairPolylineExp::~PairPolylineExp()
{
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(active);
  }
}

/* ---------------------------------------------------------------------- */

void PairPolylineExp::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  double **x = atom->x;
  double **f = atom->f;
  int *type = atom->type;
  tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;
  const double cut_contact_sq = cut * cut;
  const double reach_sq = reach * reach;

  const int inum = list->inum;
  int *ilist = list->ilist;
  int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int itype = type[i];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    const int k = target(i);
    const tagint first = lo[k], last = hi[k];

    // closest feature of the polyline within the cutoff, as the segment
    // (w1,w2) and the parameter t of the foot of the perpendicular on it;
    // and the parity of the crossings of the upward vertical ray from the
    // point with the polyline, odd if the point is inside the body (which is
    // below the polyline). A rough surface can fold under a grazing impact,
    // so the side of the closest segment does not tell inside from outside.

    double best = cut_contact_sq;
    int w1 = -1, w2 = -1;
    double t = 0.0;
    int crossings = 0;
    seen.clear();

    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (!active[itype][type[j]]) continue;
      if (tag[j] < first || tag[j] > last)
        error->one(FLERR,
                   "Pair polyline/exp: atom {} has a vertex type but is not on the polyline "
                   "(tags {}..{})",
                   tag[j], first, last);

      const int ends[2][2] = {{vertex(tag[j] - 1, i, k), j}, {j, vertex(tag[j] + 1, i, k)}};
      for (int s = 0; s < 2; s++) {
        const int ja = ends[s][0], jb = ends[s][1];
        if (ja < 0 || jb < 0) continue;
        if (std::find(seen.begin(), seen.end(), tag[ja]) != seen.end()) continue;
        seen.push_back(tag[ja]);

        const double sx = x[jb][0] - x[ja][0];
        const double sy = x[jb][1] - x[ja][1];
        const double ss = sx * sx + sy * sy;
        if (ss > reach_sq)
          error->one(FLERR,
                     "Pair polyline/exp: segment {}-{} is {} long, more than reach {}, "
                     "at step {}: the run went unstable, or reach is too small",
                     tag[ja], tag[jb], sqrt(ss), reach, update->ntimestep);
        const double ux = x[i][0] - x[ja][0];
        const double uy = x[i][1] - x[ja][1];
        double tt = (ux * sx + uy * sy) / ss;
        if (tt < 0.0) tt = 0.0;
        if (tt > 1.0) tt = 1.0;
        const double dx = ux - tt * sx;
        const double dy = uy - tt * sy;
        const double dsq = dx * dx + dy * dy;
        if (dsq < best) {
          best = dsq;
          w1 = ja;
          w2 = jb;
          t = tt;
        }
        // half-open in x, so that a ray through a vertex counts once; the
        // crossing is above the point if (u x s) / s_x > 0 (the open wall's
        // test: a ring casts its own ray once the closest feature is known)
        if (!closed) {
          const bool straddles = (x[ja][0] <= x[i][0]) != (x[jb][0] <= x[i][0]);
          if (straddles && (ux * sy - uy * sx) * sx > 0.0) crossings++;
        }
      }
    }
    if (w1 < 0) continue;

    const double l = sqrt(best);
    if (closed) {
      if (l == 0.0 || inside_ring(i, (t < 0.5) ? w1 : w2, k))
        error->one(FLERR,
                   "Pair polyline/exp: atom {} is inside the ring {}..{} at step {} "
                   "({} from its surface, near vertex {})",
                   tag[i], first, last, update->ntimestep, l, tag[w1]);
    } else if (l == 0.0 || crossings % 2)
      error->one(FLERR,
                 "Pair polyline/exp: atom {} is inside the wall at step {} "
                 "({} from the surface, near vertex {})",
                 tag[i], update->ntimestep, l, tag[w1]);

    const double evdwl = v0 * exp(-a * l);
    const double fmag = a * evdwl;
    const bool at_vertex = (t <= 0.0 || t >= 1.0);
    const int v = (t <= 0.0) ? w1 : w2;

    // p - q: the force on the point acts along it, away from the surface
    double del[2];
    if (at_vertex) {
      del[0] = x[i][0] - x[v][0];
      del[1] = x[i][1] - x[v][1];
    } else {
      del[0] = x[i][0] - (x[w1][0] + t * (x[w2][0] - x[w1][0]));
      del[1] = x[i][1] - (x[w1][1] + t * (x[w2][1] - x[w1][1]));
    }

    if (at_vertex) {
      const double fpair = fmag / l;
      f[i][0] += del[0] * fpair;
      f[i][1] += del[1] * fpair;
      f[v][0] -= del[0] * fpair;
      f[v][1] -= del[1] * fpair;
      if (evflag) ev_tally(i, v, nlocal, 1, evdwl, 0.0, fpair, del[0], del[1], 0.0);
      continue;
    }

    double fi[3], fw1[3], fw2[3];
    fi[2] = fw1[2] = fw2[2] = 0.0;
    if (rule == LEVER) {
      fi[0] = fmag * del[0] / l;
      fi[1] = fmag * del[1] / l;
      fw1[0] = -(1.0 - t) * fi[0];
      fw1[1] = -(1.0 - t) * fi[1];
      fw2[0] = -t * fi[0];
      fw2[1] = -t * fi[1];
    } else {
      // l = |d| with d = (s x u) / |s| the signed distance to the segment's
      // line; derivatives of d with respect to u = p - w1 and s = w2 - w1
      const double sx = x[w2][0] - x[w1][0];
      const double sy = x[w2][1] - x[w1][1];
      const double ux = x[i][0] - x[w1][0];
      const double uy = x[i][1] - x[w1][1];
      const double len = sqrt(sx * sx + sy * sy);
      const double d = (sx * uy - sy * ux) / len;
      const double sign = (d < 0.0) ? -1.0 : 1.0;
      const double ddu[2] = {-sy / len, sx / len};
      const double dds[2] = {uy / len - d * sx / (len * len), -ux / len - d * sy / (len * len)};
      for (int k = 0; k < 2; k++) {
        fi[k] = sign * fmag * ddu[k];
        fw1[k] = sign * fmag * (-ddu[k] - dds[k]);
        fw2[k] = sign * fmag * dds[k];
      }
    }
    for (int k = 0; k < 2; k++) {
      f[i][k] += fi[k];
      f[w1][k] += fw1[k];
      f[w2][k] += fw2[k];
    }
    if (evflag) {
      double drji[3] = {x[w1][0] - x[i][0], x[w1][1] - x[i][1], 0.0};
      double drki[3] = {x[w2][0] - x[i][0], x[w2][1] - x[i][1], 0.0};
      ev_tally3(i, w1, w2, evdwl, 0.0, fw1, fw2, drji, drki);
    }
  }
}

/* ----------------------------------------------------------------------
   the polyline that acts on point i: the only one, or the other ring
------------------------------------------------------------------------- */

int PairPolylineExp::target(int i)
{
  if (npolylines == 1) return 0;
  const tagint t = atom->tag[i];
  if (t >= lo[0] && t <= hi[0]) return 1;
  if (t >= lo[1] && t <= hi[1]) return 0;
  error->one(FLERR, "Pair polyline/exp: atom {} has a point type but is on neither ring", t);
  return -1;
}

/* ----------------------------------------------------------------------
   local index of polyline k's vertex with tag t, the image closest to atom
   i; -1 past either end of an open polyline, the other end for a ring
------------------------------------------------------------------------- */

int PairPolylineExp::vertex(tagint t, int i, int k)
{
  if (closed) {
    const tagint n = hi[k] - lo[k] + 1;
    t = lo[k] + ((t - lo[k]) % n + n) % n;
  } else if (t < lo[k] || t > hi[k])
    return -1;
  const int m = atom->map(t);
  if (m < 0)
    error->one(FLERR,
               "Pair polyline/exp: vertex {} is not on this rank; "
               "raise comm_modify cutoff to at least cutoff + {} reach = {}",
               t, closed ? CHORD : 2, cut + (closed ? CHORD : 2) * reach);
  return domain->closest_image(i, m);
}

/* ----------------------------------------------------------------------
   whether point i lies inside ring k, whose closest vertex to it is w:
   the parity of the crossings of the ray from the point along the ring's
   outward direction there with the segments examined for the point (seen).
   A rough surface folds under a sliding contact (a vertex pushed past its
   neighbour), so the side of the closest feature does not tell inside from
   outside; a fixed direction, as the wall's upward ray, would meet the
   ring's far side, which the neighbour list does not hold. The outward
   direction is the right normal of the chord from CHORD vertices before w
   to as many after it (the ring runs counter-clockwise), which a fold of a
   few vertices does not turn.
------------------------------------------------------------------------- */

bool PairPolylineExp::inside_ring(int i, int w, int k)
{
  double **x = atom->x;
  tagint *tag = atom->tag;
  const int before = vertex(tag[w] - CHORD, i, k);
  const int after = vertex(tag[w] + CHORD, i, k);
  const double ux = x[after][1] - x[before][1];
  const double uy = x[before][0] - x[after][0];

  // positions relative to the point, as (across, along) the ray
  int crossings = 0;
  for (const tagint start : seen) {
    const int ja = vertex(start, i, k), jb = vertex(start + 1, i, k);
    const double ax = x[ja][0] - x[i][0], ay = x[ja][1] - x[i][1];
    const double bx = x[jb][0] - x[i][0], by = x[jb][1] - x[i][1];
    const double sa = ax * uy - ay * ux, sb = bx * uy - by * ux;
    if ((sa <= 0.0) == (sb <= 0.0)) continue;    // half-open: a vertex on the ray counts once
    const double ha = ax * ux + ay * uy, hb = bx * ux + by * uy;
    if (ha + (0.0 - sa) * (hb - ha) / (sb - sa) > 0.0) crossings++;
  }
  return crossings % 2;
}

/* ---------------------------------------------------------------------- */

void PairPolylineExp::allocate()
{
  allocated = 1;
  const int n = atom->ntypes + 1;
  memory->create(setflag, n, n, "pair:setflag");
  memory->create(cutsq, n, n, "pair:cutsq");
  memory->create(active, n, n, "pair:active");
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) setflag[i][j] = active[i][j] = 0;
}

/* ----------------------------------------------------------------------
   pair_style polyline/exp a V0 cutoff first last [reach L] [rule lever|gradient]
                           [closed yes|no] [partner first2 last2]
------------------------------------------------------------------------- */

void PairPolylineExp::settings(int narg, char **arg)
{
  if (narg < 5)
    error->all(FLERR,
               "Illegal pair_style polyline/exp command: expected "
               "a V0 cutoff first last [reach L] [rule lever|gradient] [closed yes|no] "
               "[partner first2 last2]");

  a = utils::numeric(FLERR, arg[0], false, lmp);
  v0 = utils::numeric(FLERR, arg[1], false, lmp);
  cut = utils::numeric(FLERR, arg[2], false, lmp);
  lo[0] = utils::tnumeric(FLERR, arg[3], false, lmp);
  hi[0] = utils::tnumeric(FLERR, arg[4], false, lmp);
  reach = 3.0 * cut;
  rule = LEVER;
  npolylines = 1;
  closed = 0;

  int iarg = 5;
  while (iarg < narg) {
    // a keyword without its value gets the message of utils::missing_cmd_args(),
    // which the 29 Sep 2021 headers (Debian's LAMMPS) do not have yet
    if (strcmp(arg[iarg], "reach") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "Illegal pair_style polyline/exp reach command: missing argument(s)");
      reach = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    } else if (strcmp(arg[iarg], "rule") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "Illegal pair_style polyline/exp rule command: missing argument(s)");
      if (strcmp(arg[iarg + 1], "lever") == 0)
        rule = LEVER;
      else if (strcmp(arg[iarg + 1], "gradient") == 0)
        rule = GRADIENT;
      else
        error->all(FLERR, "Pair polyline/exp: rule must be lever or gradient, got {}",
                   arg[iarg + 1]);
    } else if (strcmp(arg[iarg], "closed") == 0) {
      if (iarg + 2 > narg)
        error->all(FLERR, "Illegal pair_style polyline/exp closed command: missing argument(s)");
      // utils::logical() came after the 29 Sep 2021 release (Debian's LAMMPS)
      if (strcmp(arg[iarg + 1], "yes") == 0)
        closed = 1;
      else if (strcmp(arg[iarg + 1], "no") == 0)
        closed = 0;
      else
        error->all(FLERR, "Pair polyline/exp: closed must be yes or no, got {}", arg[iarg + 1]);
    } else if (strcmp(arg[iarg], "partner") == 0) {
      if (iarg + 3 > narg)
        error->all(FLERR, "Illegal pair_style polyline/exp partner command: missing argument(s)");
      lo[1] = utils::tnumeric(FLERR, arg[iarg + 1], false, lmp);
      hi[1] = utils::tnumeric(FLERR, arg[iarg + 2], false, lmp);
      npolylines = 2;
      iarg++;
    } else {
      error->all(FLERR,
                 "Pair polyline/exp: unknown keyword {} (allowed: reach L, rule lever|gradient, "
                 "closed yes|no, partner first2 last2)",
                 arg[iarg]);
    }
    iarg += 2;
  }
  if (npolylines == 2 && !closed)
    error->all(FLERR, "Pair polyline/exp: partner needs closed rings (closed yes)");

  if (a <= 0.0) error->all(FLERR, "Pair polyline/exp: a must be > 0, got {}", a);
  if (v0 <= 0.0) error->all(FLERR, "Pair polyline/exp: V0 must be > 0, got {}", v0);
  if (cut <= 0.0) error->all(FLERR, "Pair polyline/exp: cutoff must be > 0, got {}", cut);
  if (reach <= 0.0) error->all(FLERR, "Pair polyline/exp: reach must be > 0, got {}", reach);
  for (int k = 0; k < npolylines; k++)
    if (lo[k] < 1 || hi[k] < lo[k] + (closed ? 2 * CHORD : 1))
      error->all(FLERR, "Pair polyline/exp: need 1 <= first < last{}, got first {} last {}",
                 closed ? fmt::format(" and {} vertices to a ring", 2 * CHORD + 1) : "", lo[k],
                 hi[k]);
  if (npolylines == 2 && lo[1] <= hi[0] && lo[0] <= hi[1])
    error->all(FLERR, "Pair polyline/exp: the rings {}..{} and {}..{} overlap", lo[0], hi[0],
               lo[1], hi[1]);
}

/* ----------------------------------------------------------------------
   pair_coeff I J: points of types I are repelled by the polyline, whose
   vertices have types J (with partner, and the other way round); every
   other type pair interacts with nothing
------------------------------------------------------------------------- */

void PairPolylineExp::coeff(int narg, char **arg)
{
  if (narg != 2)
    error->all(FLERR,
               "Incorrect args for pair coefficients: pair_coeff I J "
               "(I: types of the points, J: types of the polyline's vertices)");
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  // two rings act on each other: the types of either are points and vertices
  for (int i = ilo; i <= ihi; i++)
    for (int j = jlo; j <= jhi; j++) {
      active[i][j] = 1;
      if (npolylines == 2) active[j][i] = 1;
    }

  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) setflag[i][j] = 1;
}

/* ---------------------------------------------------------------------- */

void PairPolylineExp::init_style()
{
  if (domain->dimension != 2) error->all(FLERR, "Pair polyline/exp requires dimension 2");
  if (!atom->tag_enable || atom->map_style == Atom::MAP_NONE)
    error->all(FLERR, "Pair polyline/exp requires atom IDs and an atom map");
  if (force->newton_pair == 0) error->all(FLERR, "Pair polyline/exp requires newton pair on");

#ifdef POLYLINE_EXP_ADD_REQUEST
  // each point needs all its neighbours, owned or ghost
  neighbor->add_request(this, NeighConst::REQ_FULL);
#else
  // the same full list, requested the way LAMMPS did before add_request()
  const int irequest = neighbor->request(this, instance_me);
  neighbor->requests[irequest]->half = 0;
  neighbor->requests[irequest]->full = 1;
#endif
}

/* ----------------------------------------------------------------------
   a point within the cutoff of a segment is within cutoff + reach/2 of one
   of its ends, which is therefore in the point's neighbour list; the other
   end is found through the atom map
------------------------------------------------------------------------- */

double PairPolylineExp::init_one(int i, int j)
{
  if (active[i][j] || active[j][i]) return cut + 0.5 * reach;
  return 0.0;
}
