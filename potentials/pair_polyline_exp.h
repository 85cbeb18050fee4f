/* -*- c++ -*- ----------------------------------------------------------
   Pair style polyline/exp: exponential repulsion of points from a polyline.
   Part of the oblique-impact workflow; see potentials/README.md.
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
  double a;          // decay rate of the repulsion, 1/length
  double v0;         // energy scale: E(l) = v0 exp(-a l)
  double cut;        // contact cutoff on the distance l to the polyline
  double reach;      // longest segment of the polyline
  tagint first;      // tags first..last are the polyline's vertices, in order
  tagint last;
  int rule;          // LEVER or GRADIENT
  int **active;      // active[itype][jtype]: points of itype feel vertices of jtype

  std::vector<tagint> seen;    // segments already examined for the current point

  void allocate();
  int vertex(tagint, int);
};

}    // namespace LAMMPS_NS

#endif
#endif
