/* ----------------------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories

   This software is distributed under the GNU General Public License.
   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: the oblique-impact workflow (lattice disk on a
   lattice wall); see potentials/README.md.

   Fix area/barrier: at every step, how many triangles of angle style
   area/barrier are inside their barrier (J < Jc, or turned over where
   Jc = 0) and the smallest J, summed over the ranks; a global vector of
   four: the most inside at once since the fix was defined, the smallest
   J since then, and both at the last step. The counts come from the
   angle style's own force loop, so the fix costs one reduction a step.
------------------------------------------------------------------------- */

#include "fix_area_barrier.h"

#include "angle_area_barrier.h"
#include "comm.h"
#include "error.h"
#include "force.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

/* ---------------------------------------------------------------------- */

FixAreaBarrier::FixAreaBarrier(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), barrier(nullptr), now(0.0), most(0.0), jmin_now(HUGE_VAL),
    jmin(HUGE_VAL)
{
  if (narg != 3) error->all(FLERR, "Illegal fix area/barrier command: expects no arguments");
  vector_flag = 1;
  size_vector = 4;
  global_freq = 1;
  extvector = 0;
  nevery = 1;
}

/* ---------------------------------------------------------------------- */

int FixAreaBarrier::setmask()
{
  return END_OF_STEP;
}

/* ---------------------------------------------------------------------- */

void FixAreaBarrier::init()
{
  barrier = dynamic_cast<AngleAreaBarrier *>(force->angle_match("area/barrier"));
  if (!barrier) error->all(FLERR, "Fix area/barrier requires angle style area/barrier");
}

/* ---------------------------------------------------------------------- */

void FixAreaBarrier::setup(int /*vflag*/)
{
  tally();
}

/* ---------------------------------------------------------------------- */

void FixAreaBarrier::end_of_step()
{
  tally();
}

/* ---------------------------------------------------------------------- */

void FixAreaBarrier::tally()
{
  const double local = (double) barrier->nbarrier;
  if (comm->nprocs == 1) {    // every step: no reduction where one rank holds all
    now = local;
    jmin_now = barrier->jmin;
  } else {
    MPI_Allreduce(&local, &now, 1, MPI_DOUBLE, MPI_SUM, world);
    MPI_Allreduce(&barrier->jmin, &jmin_now, 1, MPI_DOUBLE, MPI_MIN, world);
  }
  if (now > most) most = now;
  if (jmin_now < jmin) jmin = jmin_now;
}

/* ----------------------------------------------------------------------
   1: the most inside the barrier at once, 2: the smallest J, 3 and 4:
   both at the last step
------------------------------------------------------------------------- */

double FixAreaBarrier::compute_vector(int n)
{
  if (n == 0) return most;
  if (n == 1) return jmin;
  if (n == 2) return now;
  return jmin_now;
}
