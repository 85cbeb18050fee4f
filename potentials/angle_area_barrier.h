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

#ifdef ANGLE_CLASS
// clang-format off
AngleStyle(area/barrier,AngleAreaBarrier);
// clang-format on
#else

#ifndef LMP_ANGLE_AREA_BARRIER_H
#define LMP_ANGLE_AREA_BARRIER_H

#include "angle.h"

namespace LAMMPS_NS {

class AngleAreaBarrier : public Angle {
 public:
  AngleAreaBarrier(class LAMMPS *);
  ~AngleAreaBarrier() override;
  void compute(int, int) override;
  void coeff(int, char **) override;
  double equilibrium_angle(int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_data(FILE *) override;
  double single(int, int, int, int) override;
  double memory_usage() override;

  // of the last force call, this rank's angles only (fix area/barrier sums
  // them over the ranks): how many are inside the barrier (J < Jc), and
  // the smallest J
  bigint nbarrier;
  double jmin;

 protected:
  double *a0;    // reference signed area (the triangle at rest, counter-clockwise)
  double *k;     // stiffness, energy per area
  double *jc;    // J below which the barrier acts

  void allocate();
};

}    // namespace LAMMPS_NS

#endif
#endif
