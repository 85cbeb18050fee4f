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

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(motion/2d,ComputeMotion2d);
// clang-format on
#else

#ifndef LMP_COMPUTE_MOTION_2D_H
#define LMP_COMPUTE_MOTION_2D_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeMotion2d : public Compute {
 public:
  ComputeMotion2d(class LAMMPS *, int, char **);
  ~ComputeMotion2d() override;
  void init() override;
  void compute_vector() override;

 private:
  double masstotal;
};

}    // namespace LAMMPS_NS

#endif
#endif
