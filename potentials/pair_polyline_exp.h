/* -*- c++ -*- ----------------------------------------------------------
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
   Pair style polyline/exp: exponential repulsion of points from a polyline.
   Contributing author: the oblique-impact workflow project.
   See potentials/README.md.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(polyline/exp,PairPolylineExp);
// clang-format on
#else

#ifndef LMP_PAIR_POLYLINE_EXP_H
#define LMP_PAIR_POLYLINE_EXP_H

#include "pair.h"

#include <vector>

namespace LAMMPS_NS {

class PairPolylineExp : public Pair {
 public:
  PairPolylineExp(class LAMMPS *);
  ~PairPolylineExp() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;

 protected:
  double a;        // decay rate of the repulsion, 1/length
  double v0;       // energy scale: E(l) = v0 exp(-a l)
  double cut;      // contact cutoff on the distance l to the polyline
  double reach;       // longest segment of the polyline
  tagint lo[2];       // tags lo[k]..hi[k] are polyline k's vertices, in order
  tagint hi[2];
  int npolylines;     // 1: the polyline acts on points; 2 (partner): each ring
                      //    acts on the other's vertices as points
  int closed;         // the polylines are closed rings around their bodies
  int rule;           // LEVER or GRADIENT
  int **active;       // active[itype][jtype]: points of itype feel vertices of jtype

  std::vector<tagint> seen;    // segments already examined for the current point

  void allocate();
  int target(int);
  int vertex(tagint, int, int);
  bool inside_ring(int, int, int);
};

}    // namespace LAMMPS_NS

#endif
#endif
