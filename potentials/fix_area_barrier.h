/* -*- c++ -*- ----------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories

   This software is distributed under the GNU General Public License.
   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: the oblique-impact workflow (lattice disk on a
   lattice wall); see potentials/README.md.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(area/barrier,FixAreaBarrier);
// clang-format on
#else

#ifndef LMP_FIX_AREA_BARRIER_H
#define LMP_FIX_AREA_BARRIER_H

#include "fix.h"

namespace LAMMPS_NS {

class FixAreaBarrier : public Fix {
 public:
  FixAreaBarrier(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  double compute_vector(int) override;

 private:
  class AngleAreaBarrier *barrier;
  double now;         // triangles inside the barrier at the last step
  double most;        // the most at once since the fix was defined
  double jmin_now;    // the smallest J at the last step
  double jmin;        // the smallest since the fix was defined

  void tally();
};

}    // namespace LAMMPS_NS

#endif
#endif
