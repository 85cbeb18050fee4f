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
FixStyle(nve/2d,FixNVE2d);
// clang-format on
#else

#ifndef LMP_FIX_NVE_2D_H
#define LMP_FIX_NVE_2D_H

#include "fix_nve.h"

namespace LAMMPS_NS {

class FixNVE2d : public FixNVE {
 public:
  FixNVE2d(class LAMMPS *, int, char **);
  ~FixNVE2d() override;
  void init() override;
  void initial_integrate(int) override;
  void final_integrate() override;
  void post_run() override;

 private:
  double *dtfm_type;    // dtf / mass per atom type, once per half step
  int ntypes;
  int *every;           // nevery of each end-of-step fix, as of init()
  int nevery_fixes;
  bool pending;         // the last step's closing half kick is still to do
  bool fuse;            // may defer it (velocity Verlet, not rRESPA)

  void set_dtfm();
  static bool reads_atoms(Fix *fix);
  bool velocities_read(bigint step) const;
  void move_atoms(int kicks, bool drift);
};

}    // namespace LAMMPS_NS

#endif
#endif
