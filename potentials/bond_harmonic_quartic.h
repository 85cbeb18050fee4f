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

#ifdef BOND_CLASS
// clang-format off
BondStyle(harmonic/quartic,BondHarmonicQuartic);
// clang-format on
#else

#ifndef LMP_BOND_HARMONIC_QUARTIC_H
#define LMP_BOND_HARMONIC_QUARTIC_H

#include "bond.h"

// LAMMPS from 2022 on (platform.h appeared then) has Bond::born_matrix().
#if __has_include("platform.h")
#define BOND_HARMONIC_QUARTIC_BORN_MATRIX
#endif

namespace LAMMPS_NS {

class BondHarmonicQuartic : public Bond {
 public:
  BondHarmonicQuartic(class LAMMPS *);
  ~BondHarmonicQuartic() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double equilibrium_distance(int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_data(FILE *) override;
  double single(int, double, int, int, double &) override;
#ifdef BOND_HARMONIC_QUARTIC_BORN_MATRIX
  void born_matrix(int, double, int, int, double &, double &) override;
#endif
  void *extract(const char *, int &) override;
  double memory_usage() override;

  // one bond type's coefficients, packed so that the force loop reads one
  // stream instead of three (the workflow gives every bond its own type)
  struct Param {
    double r0, ka, kb;
  };
  // one entry of the bond list with its natural length, and the index of
  // its (ka, kb) in a table of the distinct pairs: the workflow's one type
  // per bond has a few distinct stiffnesses, so the loop reads 18 bytes
  // per bond instead of the list's 12 and a type's 24
  struct Packed {
    int i1, i2;
    double r0;
  };
  struct Stiffness {
    double ka, kb;
  };

 protected:
  double *r0;       // natural length
  double *ka;       // harmonic stiffness: E = ka x^2/2 + kb x^4/4, x = r - r0
  double *kb;       // quartic stiffness
  Param *param;     // copy of r0, ka, kb per type, filled by init_style()

  // the bond list in packed form (pack()), remade whenever the neighbour
  // lists are (Neighbor::ncalls) or the list changes address or length
  Packed *packed;
  unsigned short *packed_class;    // per bond: its row of stiffness
  int npacked, maxpacked;
  bigint packed_ncalls;
  int **packed_source;
  int *type_class;           // per type: its row of stiffness; -1: not packable
  Stiffness *stiffness;      // the distinct (ka, kb) of the types
  int nstiffness;
  int want_packed;           // bond_style harmonic/quartic packed no: never pack
  int use_packed;            // 0: the types' own path (too many distinct pairs,
                             // or a fix that changes bonds in a run)

  void allocate();
  void pack();
  template <int EVFLAG, int NEWTON_BOND, int THREE_D> void eval(int, int);
  template <int EVFLAG, int NEWTON_BOND, int THREE_D> void eval_packed(int, int);
};

}    // namespace LAMMPS_NS

#endif
#endif
