/* ----------------------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories

   This software is distributed under the GNU General Public License.
   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: the oblique-impact workflow (lattice disk on a
   lattice wall); see potentials/README.md.

   Angle style area/barrier: a barrier against a triangle of a 2-D spring
   network turning inside out. Each angle (i1, i2, i3) is one triangle,
   counter-clockwise at rest; with its signed area A and J = A / A0,

     E = k A0 [Jc / J - 1 + ln(J / Jc)]   for 0 < J < Jc,
     E = 0                                for J >= Jc,

   with A0, k, Jc per angle type. E and dE/dJ vanish at Jc (C1), so the
   network's small-strain moduli are untouched; E diverges as J -> 0+,
   as an elastic continuum's energy does when an element's area vanishes.
   The force on atom m is -k (J - Jc) / J^2 dA/dx_m, along the gradient of
   the area. A triangle found with J <= 0 while Jc > 0 has crossed the
   barrier within one step: the run stops. Jc = 0 puts no energy on any
   triangle and only counts those turned over (J < 0).
------------------------------------------------------------------------- */

#include "angle_area_barrier.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

// LAMMPS from 2022 on (platform.h appeared then) names the caller in minimum_image()
#if __has_include("platform.h")
#define MINIMUM_IMAGE(dx, dy, dz) domain->minimum_image(FLERR, dx, dy, dz)
#else
#define MINIMUM_IMAGE(dx, dy, dz) domain->minimum_image(dx, dy, dz)
#endif

/* ---------------------------------------------------------------------- */

AngleAreaBarrier::AngleAreaBarrier(LAMMPS *lmp) :
    Angle(lmp), nbarrier(0), jmin(0.0), a0(nullptr), k(nullptr), jc(nullptr)
{
  writedata = 1;
}

/* ---------------------------------------------------------------------- */

AngleAreaBarrier::~AngleAreaBarrier()
{
  if (copymode) return;
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(a0);
    memory->destroy(k);
    memory->destroy(jc);
  }
}

/* ---------------------------------------------------------------------- */

void AngleAreaBarrier::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  double **x = atom->x;
  double **f = atom->f;
  int **anglelist = neighbor->anglelist;
  const int nanglelist = neighbor->nanglelist;
  const int nlocal = atom->nlocal;
  const int newton_bond = force->newton_bond;

  nbarrier = 0;
  jmin = HUGE_VAL;
  double f1[3], f3[3];
  f1[2] = f3[2] = 0.0;

  for (int n = 0; n < nanglelist; n++) {
    const int i1 = anglelist[n][0];
    const int i2 = anglelist[n][1];
    const int i3 = anglelist[n][2];
    const int type = anglelist[n][3];

    // both edges from atom 2, the virial's reference point
    const double delx1 = x[i1][0] - x[i2][0];
    const double dely1 = x[i1][1] - x[i2][1];
    const double delx2 = x[i3][0] - x[i2][0];
    const double dely2 = x[i3][1] - x[i2][1];

    // signed area of (1, 2, 3), positive counter-clockwise
    const double area = 0.5 * (delx2 * dely1 - dely2 * delx1);
    const double j = area / a0[type];

    // each angle counted once over the ranks: with newton_bond on it is in
    // one rank's list, with newton_bond off in the list of every rank that
    // owns one of its atoms, and the owner of atom 2 counts it
    if (newton_bond || i2 < nlocal) {
      if (j < jmin) jmin = j;
      if (j < jc[type]) nbarrier++;
    }
    if (j >= jc[type]) continue;
    if (j <= 0.0) {
      if (jc[type] == 0.0) continue;
      error->one(FLERR,
                 "Angle area/barrier: triangle {} {} {} turned over (J = {:.6g}) at step {}: "
                 "it crossed the barrier within one step, which is too long for it",
                 atom->tag[i1], atom->tag[i2], atom->tag[i3], j, update->ntimestep);
    }

    // dE/dA = k (J - Jc) / J^2; the force is -dE/dA times the area's gradient
    const double dedj = k[type] * (j - jc[type]) / (j * j);
    double eangle = 0.0;
    if (eflag) eangle = k[type] * a0[type] * (jc[type] / j - 1.0 + log(j / jc[type]));

    // dA/dx1 = (-dely2, delx2) / 2, dA/dx3 = (dely1, -delx1) / 2
    f1[0] = 0.5 * dedj * dely2;
    f1[1] = -0.5 * dedj * delx2;
    f3[0] = -0.5 * dedj * dely1;
    f3[1] = 0.5 * dedj * delx1;

    if (newton_bond || i1 < nlocal) {
      f[i1][0] += f1[0];
      f[i1][1] += f1[1];
    }
    if (newton_bond || i2 < nlocal) {
      f[i2][0] -= f1[0] + f3[0];
      f[i2][1] -= f1[1] + f3[1];
    }
    if (newton_bond || i3 < nlocal) {
      f[i3][0] += f3[0];
      f[i3][1] += f3[1];
    }

    if (evflag)
      ev_tally(i1, i2, i3, nlocal, newton_bond, eangle, f1, f3, delx1, dely1, 0.0, delx2, dely2,
               0.0);
  }
}

/* ---------------------------------------------------------------------- */

void AngleAreaBarrier::allocate()
{
  allocated = 1;
  const int n = atom->nangletypes + 1;

  memory->create(a0, n, "angle:a0");
  memory->create(k, n, "angle:k");
  memory->create(jc, n, "angle:jc");
  memory->create(setflag, n, "angle:setflag");
  for (int i = 0; i < n; i++) {
    setflag[i] = 0;
    a0[i] = k[i] = jc[i] = 0.0;
  }
}

/* ----------------------------------------------------------------------
   one angle_coeff line: N A0 k Jc (from the input or a data file)
------------------------------------------------------------------------- */

void AngleAreaBarrier::coeff(int narg, char **arg)
{
  if (domain->dimension != 2) error->all(FLERR, "Angle area/barrier requires dimension 2");
  if (narg != 4)
    error->all(FLERR,
               "Incorrect args for angle coefficients: angle area/barrier expects "
               "N A0 k Jc, got {} values",
               narg);
  if (!allocated) allocate();

  int ilo, ihi;
  utils::bounds(FLERR, arg[0], 1, atom->nangletypes, ilo, ihi, error);

  const double a0_one = utils::numeric(FLERR, arg[1], false, lmp);
  const double k_one = utils::numeric(FLERR, arg[2], false, lmp);
  const double jc_one = utils::numeric(FLERR, arg[3], false, lmp);
  if (!(a0_one > 0.0)) error->all(FLERR, "Angle area/barrier: A0 must be > 0, got {}", a0_one);
  if (!(k_one >= 0.0)) error->all(FLERR, "Angle area/barrier: k must be >= 0, got {}", k_one);
  if (!(jc_one >= 0.0 && jc_one < 1.0))
    error->all(FLERR, "Angle area/barrier: Jc must be in [0, 1), got {}", jc_one);

  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    a0[i] = a0_one;
    k[i] = k_one;
    jc[i] = jc_one;
    setflag[i] = 1;
    count++;
  }
  if (count == 0)
    error->all(FLERR, "Incorrect args for angle coefficients: no angle type in {}", arg[0]);
}

/* ----------------------------------------------------------------------
   no equilibrium angle: the energy is zero over a range of shapes; the
   equilateral triangle's, for the commands that ask (fix shake, ...)
------------------------------------------------------------------------- */

double AngleAreaBarrier::equilibrium_angle(int /*i*/)
{
  return acos(-1.0) / 3.0;
}

/* ---------------------------------------------------------------------- */

void AngleAreaBarrier::write_restart(FILE *fp)
{
  fwrite(&a0[1], sizeof(double), atom->nangletypes, fp);
  fwrite(&k[1], sizeof(double), atom->nangletypes, fp);
  fwrite(&jc[1], sizeof(double), atom->nangletypes, fp);
}

/* ---------------------------------------------------------------------- */

void AngleAreaBarrier::read_restart(FILE *fp)
{
  allocate();
  const int n = atom->nangletypes;
  if (comm->me == 0) {
    utils::sfread(FLERR, &a0[1], sizeof(double), n, fp, nullptr, error);
    utils::sfread(FLERR, &k[1], sizeof(double), n, fp, nullptr, error);
    utils::sfread(FLERR, &jc[1], sizeof(double), n, fp, nullptr, error);
  }
  MPI_Bcast(&a0[1], n, MPI_DOUBLE, 0, world);
  MPI_Bcast(&k[1], n, MPI_DOUBLE, 0, world);
  MPI_Bcast(&jc[1], n, MPI_DOUBLE, 0, world);
  for (int i = 1; i <= n; i++) setflag[i] = 1;
}

/* ----------------------------------------------------------------------
   17 significant digits: read_data gets back the very doubles
------------------------------------------------------------------------- */

void AngleAreaBarrier::write_data(FILE *fp)
{
  for (int i = 1; i <= atom->nangletypes; i++)
    fprintf(fp, "%d %.17g %.17g %.17g\n", i, a0[i], k[i], jc[i]);
}

/* ----------------------------------------------------------------------
   one triangle's energy (compute angle/local eng); infinite if turned over
   while its Jc > 0
------------------------------------------------------------------------- */

double AngleAreaBarrier::single(int type, int i1, int i2, int i3)
{
  double **x = atom->x;
  double delx1 = x[i1][0] - x[i2][0];
  double dely1 = x[i1][1] - x[i2][1];
  double delz1 = 0.0;
  MINIMUM_IMAGE(delx1, dely1, delz1);
  double delx2 = x[i3][0] - x[i2][0];
  double dely2 = x[i3][1] - x[i2][1];
  double delz2 = 0.0;
  MINIMUM_IMAGE(delx2, dely2, delz2);

  const double j = 0.5 * (delx2 * dely1 - dely2 * delx1) / a0[type];
  if (j >= jc[type]) return 0.0;
  if (j <= 0.0) return HUGE_VAL;
  return k[type] * a0[type] * (jc[type] / j - 1.0 + log(j / jc[type]));
}

/* ---------------------------------------------------------------------- */

double AngleAreaBarrier::memory_usage()
{
  return Angle::memory_usage() + (atom->nangletypes + 1) * (3.0 * sizeof(double) + sizeof(int));
}
